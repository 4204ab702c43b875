#include "plot_scripts.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <cstdlib>

#include "mixmesh/core/error.hpp"

extern char** environ;

namespace mixmesh::cli {

std::filesystem::path find_plot_scripts(const std::string& script, const std::string& given) {
  std::vector<std::filesystem::path> candidates;
  if (!given.empty()) candidates.emplace_back(given);
  if (const char* variable = std::getenv("MIXMESH_SCRIPTS")) candidates.emplace_back(variable);
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    candidates.push_back(program.parent_path().parent_path() / "share" / "mixmesh" / "scripts");
    for (std::filesystem::path folder = program.parent_path(); folder.has_relative_path();
         folder = folder.parent_path())
      candidates.push_back(folder / "scripts");
  }
  for (const std::filesystem::path& candidate : candidates)
    if (std::filesystem::is_regular_file(candidate / script)) return candidate;
  return {};
}

void run_plot_script(const std::vector<std::string>& command) {
  std::vector<char*> arguments;
  for (const std::string& argument : command) arguments.push_back(const_cast<char*>(argument.c_str()));
  arguments.push_back(nullptr);
  pid_t process = 0;
  if (posix_spawnp(&process, arguments[0], nullptr, nullptr, arguments.data(), environ) != 0)
    throw Error("cannot run " + command[0]);
  int status = 0;
  if (waitpid(process, &status, 0) < 0) throw Error("lost the process of " + command[0]);
  const std::string script = command.size() > 1 ? " " + command[1] : std::string();
  if (!WIFEXITED(status)) throw Error(command[0] + script + " was killed (signal " +
                                      std::to_string(WTERMSIG(status)) + ")");
  if (WEXITSTATUS(status) != 0)
    throw Error(command[0] + script + " failed (exit status " + std::to_string(WEXITSTATUS(status)) + ")");
}

}  // namespace mixmesh::cli
