// The error type of mixmesh: bad input, geometry that cannot be meshed, a failed
// stage. It carries its context (file:line:column, stage, entity) in one line so the
// command line can print it as is and exit non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace mixmesh {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "path:line: message" (line omitted when 0), the form every reader reports in.
Error file_error(const std::string& path, long line, const std::string& message);

}  // namespace mixmesh
