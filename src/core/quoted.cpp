#include "mixmesh/core/quoted.hpp"

#include <cstdio>

namespace mixmesh {

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char character : text) {
    switch (character) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(character) < 0x20 || character == '\x7f') {
          char escape[8];
          std::snprintf(escape, sizeof escape, "\\u%04x", static_cast<unsigned>(character));
          out += escape;
        } else {
          out += character;
        }
    }
  }
  return out + '"';
}

}  // namespace mixmesh
