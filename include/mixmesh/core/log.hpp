// One logger for progress lines and timings. Stages take a Log& (or none) rather
// than printing, so libraries stay quiet and tests can capture what was said.
#pragma once

#include <chrono>
#include <ostream>
#include <string>

namespace mixmesh {

class Log {
 public:
  enum class Level { quiet = 0, normal = 1, verbose = 2 };

  explicit Log(std::ostream* stream = nullptr, Level level = Level::normal)
      : stream_(stream), level_(level), start_(std::chrono::steady_clock::now()) {}

  void info(const std::string& message) const { write(Level::normal, message); }
  void detail(const std::string& message) const { write(Level::verbose, message); }
  void warning(const std::string& message) const { write(Level::normal, "warning: " + message); }
  // Seconds since the log was created.
  double elapsed() const;

 private:
  void write(Level level, const std::string& message) const;
  std::ostream* stream_;
  Level level_;
  std::chrono::steady_clock::time_point start_;
};

// Wall-clock stopwatch for stage timings.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace mixmesh
