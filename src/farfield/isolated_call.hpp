// run_isolated: a computation in a forked child process, its result sent back
// through a pipe. For library code that can crash or run too long on bad input
// (TetGen): a crash becomes a mixmesh::Error, a time-out a TimeLimitError.
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh::farfield_detail {

namespace isolated_detail {

// The child writes a tag byte (0 result, 1 error message) and then the payload.
class Channel {
 public:
  explicit Channel(int descriptor) : descriptor_(descriptor) {}

  void write_bytes(const void* data, std::size_t size) {
    const char* bytes = static_cast<const char*>(data);
    while (size > 0) {
      const ssize_t written = ::write(descriptor_, bytes, size);
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) _exit(3);
      bytes += written;
      size -= static_cast<std::size_t>(written);
    }
  }
  bool read_bytes(void* data, std::size_t size) {
    char* bytes = static_cast<char*>(data);
    while (size > 0) {
      const ssize_t got = ::read(descriptor_, bytes, size);
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) return false;
      bytes += got;
      size -= static_cast<std::size_t>(got);
    }
    return true;
  }
  template <typename Element>
  void write_vector(const std::vector<Element>& values) {
    static_assert(std::is_trivially_copyable_v<Element>);
    const std::size_t count = values.size();
    write_bytes(&count, sizeof count);
    write_bytes(values.data(), count * sizeof(Element));
  }
  template <typename Element>
  bool read_vector(std::vector<Element>& values) {
    std::size_t count = 0;
    if (!read_bytes(&count, sizeof count)) return false;
    values.resize(count);
    return read_bytes(values.data(), count * sizeof(Element));
  }

 private:
  int descriptor_;
};

inline void send(Channel& channel, const std::string& text) {
  channel.write_vector(std::vector<char>(text.begin(), text.end()));
}
inline bool receive(Channel& channel, std::string& text) {
  std::vector<char> characters;
  if (!channel.read_vector(characters)) return false;
  text.assign(characters.begin(), characters.end());
  return true;
}

}  // namespace isolated_detail

// A call stopped at its time limit (the caller may fall back to something cheaper).
class TimeLimitError : public Error {
 public:
  using Error::Error;
};

// Result types need send(Channel&, const Result&) and receive(Channel&, Result&)
// overloads that argument-dependent lookup finds (see tetgen_call.cpp).
// `time_limit_seconds` > 0: the child is stopped (SIGALRM) after that many seconds and
// the call throws TimeLimitError saying so.
template <typename Result, typename Body>
Result run_isolated(const std::string& what, Body body, unsigned time_limit_seconds = 0) {
  using isolated_detail::Channel;
  int ends[2];
  if (pipe(ends) != 0)
    throw Error("farfield: cannot create a pipe for " + what + ": " + std::strerror(errno));
  const pid_t child = fork();
  if (child < 0) {
    close(ends[0]);
    close(ends[1]);
    throw Error("farfield: cannot start " + what + ": " + std::strerror(errno));
  }
  if (child == 0) {
    close(ends[0]);
    if (time_limit_seconds > 0) alarm(time_limit_seconds);
    Channel channel(ends[1]);
    char tag = 0;
    try {
      Result result = body();
      channel.write_bytes(&tag, 1);
      send(channel, result);
    } catch (const std::exception& error) {
      tag = 1;
      channel.write_bytes(&tag, 1);
      send(channel, std::string(error.what()));
    }
    _exit(0);  // no destructors, no atexit handlers of the parent's state
  }
  close(ends[1]);
  Channel channel(ends[0]);
  char tag = 2;
  Result result{};
  std::string message;
  const bool complete =
      channel.read_bytes(&tag, 1) && (tag == 0 ? receive(channel, result) : receive(channel, message));
  close(ends[0]);
  int status = 0;
  while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  if (complete && tag == 0) return result;
  if (complete && tag == 1) throw Error(message);
  if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM && time_limit_seconds > 0)
    throw TimeLimitError("farfield: " + what + " did not finish within " +
                         std::to_string(time_limit_seconds) + " s");
  if (WIFSIGNALED(status))
    throw Error("farfield: " + what + " crashed (signal " + std::to_string(WTERMSIG(status)) + ")");
  throw Error("farfield: " + what + " stopped without a result (exit " + std::to_string(WEXITSTATUS(status)) +
              ")");
}

}  // namespace mixmesh::farfield_detail
