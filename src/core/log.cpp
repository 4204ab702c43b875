#include "mixmesh/core/log.hpp"

#include <cstdio>

namespace mixmesh {

double Log::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Log::write(Level level, const std::string& message) const {
  if (stream_ == nullptr || level > level_) return;
  char stamp[32];
  std::snprintf(stamp, sizeof stamp, "[%7.2fs] ", elapsed());
  *stream_ << stamp << message << '\n' << std::flush;
}

}  // namespace mixmesh
