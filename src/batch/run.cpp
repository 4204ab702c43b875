#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "mixmesh/batch/batch.hpp"
#include "mixmesh/core/atomic_file.hpp"

extern char** environ;

namespace mixmesh::batch {

namespace fs = std::filesystem;

namespace {

struct RunningCase {
  std::size_t index;
  std::chrono::steady_clock::time_point start;
};

pid_t start_case(const BatchCase& batch_case, const fs::path& folder, const BatchOptions& options) {
  std::vector<std::string> arguments = options.command;
  arguments.push_back(batch_case.config.string());
  for (const std::string& setting : batch_case.settings) {
    arguments.push_back("--set");
    arguments.push_back(setting);
  }
  arguments.insert(arguments.end(),
                   {"--output-dir", folder.string(), "--report", (folder / "report.toml").string()});
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);

  const std::string log_path = (folder / "log.txt").string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  pid_t process = 0;
  const int status = posix_spawn(&process, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (status != 0) throw Error(std::string(argv[0]) + ": cannot start: " + std::strerror(status));
  return process;
}

// RFC 4180: a field with a comma, quote or line break goes in quotes, its quotes doubled.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string result = "\"";
  for (char character : text) result += character == '"' ? std::string("\"\"") : std::string(1, character);
  return result + "\"";
}

}  // namespace

std::vector<CaseResult> run_batch(const std::vector<BatchCase>& cases, const BatchOptions& options,
                                  const Log& log) {
  if (options.command.empty()) throw Error("batch: no command to run");
  std::vector<CaseResult> results(cases.size());
  std::map<pid_t, RunningCase> running;
  std::size_t next = 0;
  std::size_t finished = 0;
  const std::size_t jobs = static_cast<std::size_t>(std::max(1, options.jobs));

  while (finished < cases.size()) {
    while (next < cases.size() && running.size() < jobs) {
      CaseResult& result = results[next];
      result.name = cases[next].name;
      result.folder = options.output_folder / cases[next].name;
      fs::create_directories(result.folder);
      fs::remove(result.folder / "report.toml");
      const pid_t process = start_case(cases[next], result.folder, options);
      running[process] = {next, std::chrono::steady_clock::now()};
      log.detail("batch: started " + result.name);
      ++next;
    }
    int status = 0;
    rusage usage{};
    const pid_t process = wait4(-1, &status, 0, &usage);
    if (process < 0) {
      if (errno == EINTR) continue;
      throw Error(std::string("batch: wait failed: ") + std::strerror(errno));
    }
    const auto found = running.find(process);
    if (found == running.end()) continue;
    CaseResult& result = results[found->second.index];
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - found->second.start).count();
    result.peak_memory_kib = usage.ru_maxrss;
    if (WIFEXITED(status)) {
      result.exit_code = WEXITSTATUS(status);
      result.status = result.exit_code == 0 ? "ok" : "failed (exit " + std::to_string(result.exit_code) + ")";
    } else {
      result.exit_code = 128 + WTERMSIG(status);
      result.status = "failed (signal " + std::to_string(WTERMSIG(status)) + ")";
    }
    result.report = read_report(result.folder / "report.toml");
    if (result.exit_code != 0) result.error = last_error_line(result.folder / "log.txt");
    running.erase(found);
    ++finished;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.1f s", result.seconds);
    log.info("batch: [" + std::to_string(finished) + "/" + std::to_string(cases.size()) + "] " + result.name +
             ": " + result.status + ", " + seconds);
  }
  return results;
}

// Only the top-level entries (points, cells, quality ...): the tables after them, stage
// times and deformed meshes, repeat those names.
std::map<std::string, std::string> read_report(const fs::path& path) {
  std::map<std::string, std::string> report;
  if (!fs::exists(path)) return report;
  std::ifstream stream(path);
  std::string line;
  while (std::getline(stream, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (line[0] == '[') break;
    const auto equals = line.find('=');
    if (equals == std::string::npos) continue;
    auto trim = [](std::string text) {
      const auto first = text.find_first_not_of(" \t\"");
      const auto last = text.find_last_not_of(" \t\"\r");
      return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
    };
    report[trim(line.substr(0, equals))] = trim(line.substr(equals + 1));
  }
  return report;
}

std::string last_error_line(const fs::path& path) {
  std::ifstream stream(path);
  std::string line;
  std::string found;
  while (std::getline(stream, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::string lower = line;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char character) { return static_cast<char>(std::tolower(character)); });
    if (lower.find("error") != std::string::npos) found = line;
  }
  return found;
}

void write_summary(const fs::path& path, const std::vector<CaseResult>& results) {
  const std::vector<std::string> report_columns = {
      "points",     "hexahedra",           "prisms",          "pyramids",
      "tetrahedra", "min_scaled_jacobian", "deformed_meshes", "deformed_min_scaled_jacobian"};
  write_atomically(path, [&](const fs::path& temporary) {
    std::ofstream csv(temporary);
    csv << "case,status";
    for (const std::string& column : report_columns) csv << ',' << column;
    csv << ",seconds,peak_memory_mib,error\n";
    for (const CaseResult& result : results) {
      csv << result.name << ',' << result.status;
      for (const std::string& column : report_columns) {
        const auto value = result.report.find(column);
        csv << ',' << (value == result.report.end() ? "" : value->second);
      }
      char numbers[64];
      std::snprintf(numbers, sizeof numbers, ",%.2f,%.1f,", result.seconds, result.peak_memory_kib / 1024.0);
      csv << numbers << csv_field(result.error) << '\n';
    }
    if (!csv.flush()) throw Error(path.string() + ": cannot write summary");
  });
}

}  // namespace mixmesh::batch
