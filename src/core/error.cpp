#include "mixmesh/core/error.hpp"

namespace mixmesh {

Error file_error(const std::string& path, long line, const std::string& message) {
  std::string where = path;
  if (line > 0) where += ":" + std::to_string(line);
  return Error(where + ": " + message);
}

}  // namespace mixmesh
