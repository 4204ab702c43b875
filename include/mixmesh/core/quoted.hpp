// Text written into JSON and TOML files: one function for both, as TOML's basic
// strings take JSON's escapes.
#pragma once

#include <string>

namespace mixmesh {

// `text` in double quotes, with quotes, backslashes and control characters escaped
// (\", \\, \n, \t, \u00XX), valid as a JSON string and as a TOML basic string.
std::string quoted(const std::string& text);

}  // namespace mixmesh
