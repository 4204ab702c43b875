// The cluster side of a Slurm batch: its settings, the array script and sbatch.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "mixmesh/batch/slurm.hpp"

extern char** environ;

namespace mixmesh::batch {

namespace fs = std::filesystem;

namespace {

// The script a site without its own template gets. The #SBATCH lines must come
// before the first command, or sbatch ignores them.
constexpr const char* built_in_template =
    "#!/bin/bash\n"
    "# mixmesh batch on a Slurm job array: task N runs line N of manifest.tsv.\n"
    "{{sbatch}}\n"
    "{{task}}\n";

std::string shell_quoted(const std::string& text) {
  std::string result = "'";
  for (char character : text) result += character == '\'' ? std::string("'\\''") : std::string(1, character);
  return result + "'";
}

bool has_control_or_space(const std::string& text) {
  for (char character : text)
    if (std::iscntrl(static_cast<unsigned char>(character)) || character == ' ') return true;
  return false;
}

// Checked by hand rather than with <regex>, which GCC 12 warns about inside its own
// headers under the sanitizers.
bool is_digits(const std::string& text, std::size_t most = std::string::npos) {
  return !text.empty() && text.size() <= most &&
         std::all_of(text.begin(), text.end(),
                     [](unsigned char character) { return std::isdigit(character); });
}

bool is_slurm_name(const std::string& text) {
  return !text.empty() && std::all_of(text.begin(), text.end(), [](unsigned char character) {
    return std::isalnum(character) ||
           std::string("_.,+-").find(static_cast<char>(character)) != std::string::npos;
  });
}

// Slurm's time formats: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S, or no limit.
bool is_slurm_time(const std::string& text) {
  if (text == "UNLIMITED" || text == "INFINITE") return true;
  std::string rest = text;
  const auto dash = rest.find('-');
  if (dash != std::string::npos) {
    if (!is_digits(rest.substr(0, dash))) return false;
    rest = rest.substr(dash + 1);
  }
  std::vector<std::string> parts;
  for (std::size_t start = 0;; start = rest.find(':', start) + 1) {
    parts.push_back(rest.substr(start, rest.find(':', start) - start));
    if (rest.find(':', start) == std::string::npos) break;
  }
  if (parts.size() > 3 || !is_digits(parts[0])) return false;
  return std::all_of(parts.begin() + 1, parts.end(),
                     [](const std::string& part) { return is_digits(part, 2); });
}

std::string sbatch_lines(const ArrayJob& job, const SlurmOptions& options) {
  std::string array = "--array=" + array_indexes(job.indexes);
  if (options.concurrency > 0) array += "%" + std::to_string(options.concurrency);
  std::vector<std::string> lines = {"--job-name=mixmesh-" + job.output_folder.filename().string(), array,
                                    "--output=" + (job.output_folder / "slurm" / "%a.out").string(),
                                    "--ntasks=1"};
  if (!options.partition.empty()) lines.push_back("--partition=" + options.partition);
  if (!options.time.empty()) lines.push_back("--time=" + options.time);
  if (!options.memory.empty()) lines.push_back("--mem=" + options.memory);
  if (!options.account.empty()) lines.push_back("--account=" + options.account);
  for (const std::string& directive : options.directives)
    lines.push_back(directive.rfind("#SBATCH", 0) == 0 ? directive.substr(directive.find('-')) : directive);
  std::string text;
  for (const std::string& line : lines) text += (text.empty() ? "" : "\n") + ("#SBATCH " + line);
  return text;
}

std::string read_template(const fs::path& path) {
  if (path.empty()) return built_in_template;
  std::ifstream stream(path);
  if (!stream) throw Error(path.string() + ": cannot open the script template");
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

// Replaces every {{name}}; an unknown one is an error at its line, since a site
// template with a misspelt placeholder would otherwise submit a broken script. A
// template without the #SBATCH lines or the task would run nothing useful.
std::string fill_template(const std::string& text, const fs::path& path,
                          const std::vector<std::pair<std::string, std::string>>& values) {
  const std::string name = path.empty() ? "the built-in template" : path.string();
  std::string result;
  for (std::size_t start = 0;;) {
    const std::size_t open = text.find("{{", start);
    result += text.substr(start, open - start);
    if (open == std::string::npos) break;
    const std::size_t close = text.find("}}", open);
    const std::string placeholder = text.substr(open, close == std::string::npos ? 2 : close + 2 - open);
    const auto known = std::find_if(values.begin(), values.end(),
                                    [&](const auto& entry) { return entry.first == placeholder; });
    if (known == values.end()) {
      const long line = 1 + static_cast<long>(std::count(text.begin(), text.begin() + open, '\n'));
      throw file_error(name, line,
                       "unknown placeholder " + placeholder + " (known: {{sbatch}}, {{task}}, {{output}})");
    }
    result += known->second;
    start = close + 2;
  }
  for (const char* required : {"{{sbatch}}", "{{task}}"})
    if (text.find(required) == std::string::npos)
      throw Error(name + ": the script template has no " + required);
  return result;
}

}  // namespace

bool SlurmOptions::operator==(const SlurmOptions& other) const {
  return partition == other.partition && time == other.time && memory == other.memory &&
         account == other.account && concurrency == other.concurrency && directives == other.directives &&
         script_template == other.script_template;
}

std::string slurm_value_problem(const std::string& key, const std::string& value) {
  if (key == "partition" || key == "account")
    return is_slurm_name(value) ? "" : "must be a Slurm name (letters, digits, _ . , + -)";
  if (key == "time")
    return is_slurm_time(value) ? "" : "must be minutes, MM:SS, HH:MM:SS, D-HH, D-HH:MM or D-HH:MM:SS";
  if (key == "memory") {
    const bool unit = !value.empty() && std::string("KMGT").find(value.back()) != std::string::npos;
    return is_digits(unit ? value.substr(0, value.size() - 1) : value)
               ? ""
               : "must be a size such as 800M or 4G (sbatch --mem)";
  }
  if (key == "directive") {
    const std::string option = value.rfind("#SBATCH", 0) == 0 ? value.substr(7) : value;
    const auto first = option.find_first_not_of(' ');
    if (first == std::string::npos || option.compare(first, 1, "-") != 0)
      return "must be an sbatch option such as --qos=short";
    if (has_control_or_space(option.substr(first)))
      return "must be one sbatch option, without spaces or line breaks";
    if (option.compare(first, 7, "--array") == 0 || option.compare(first, 2, "-a") == 0)
      return "--array is set by the batch: one task per case of the manifest";
    return "";
  }
  return "is not a Slurm setting";
}

SlurmOptions read_slurm_options(config::Section& table) {
  SlurmOptions options;
  for (const auto& [key, value] : {std::pair{"partition", &options.partition},
                                   {"time", &options.time},
                                   {"memory", &options.memory},
                                   {"account", &options.account}}) {
    table.read(key, *value);
    if (!table.has(key)) continue;
    const std::string problem = slurm_value_problem(key, *value);
    if (!problem.empty()) table.fail(key, "'slurm." + std::string(key) + "' = \"" + *value + "\" " + problem);
  }
  table.read("concurrency", options.concurrency, config::Bounds::at_least(1));
  table.read("directives", options.directives);
  for (const std::string& directive : options.directives) {
    const std::string problem = slurm_value_problem("directive", directive);
    if (!problem.empty())
      table.fail("directives", "'slurm.directives' holds \"" + directive + "\", which " + problem);
  }
  table.read_path("template", options.script_template);
  table.finish();
  return options;
}

std::string array_indexes(const std::vector<std::size_t>& indexes) {
  std::string text;
  for (std::size_t first = 0; first < indexes.size();) {
    std::size_t last = first;
    while (last + 1 < indexes.size() && indexes[last + 1] == indexes[last] + 1) ++last;
    text += (text.empty() ? "" : ",") + std::to_string(indexes[first]);
    if (last > first) text += "-" + std::to_string(indexes[last]);
    first = last + 1;
  }
  return text;
}

std::string array_script(const ArrayJob& job, const SlurmOptions& options) {
  if (job.indexes.empty()) throw Error("batch: an array script needs at least one case");
  // #SBATCH lines are split at spaces, so a folder with one cannot be named there.
  if (has_control_or_space(job.output_folder.string()))
    throw Error(job.output_folder.string() + ": a Slurm output folder must not contain spaces");
  const std::string task = shell_quoted(job.program.string()) + " batch --task " +
                           shell_quoted((job.output_folder / "manifest.tsv").string()) +
                           " --index \"$SLURM_ARRAY_TASK_ID\"";
  return fill_template(read_template(options.script_template), options.script_template,
                       {{"{{sbatch}}", sbatch_lines(job, options)},
                        {"{{task}}", task},
                        {"{{output}}", shell_quoted(job.output_folder.string())}});
}

std::string submit_array(const fs::path& script) {
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) throw Error(std::string("batch: cannot run sbatch: ") + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_ends[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipe_ends[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_ends[0]);
  std::vector<std::string> arguments = {"sbatch", "--parsable", script.string()};
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  argv.push_back(nullptr);
  pid_t process = 0;
  const int status = posix_spawnp(&process, "sbatch", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_ends[1]);
  std::string output;
  char buffer[4096];
  for (ssize_t count; status == 0 && (count = read(pipe_ends[0], buffer, sizeof buffer)) != 0;) {
    if (count > 0) output.append(buffer, static_cast<std::size_t>(count));
    if (count < 0 && errno != EINTR) break;
  }
  close(pipe_ends[0]);
  if (status != 0) throw Error(std::string("batch: cannot run sbatch: ") + std::strerror(status));
  int exit_status = 0;
  while (waitpid(process, &exit_status, 0) < 0 && errno == EINTR) {
  }
  // sbatch prints "JOBID" or "JOBID;CLUSTER" on success and "sbatch: error: ..." otherwise.
  while (!output.empty() && (output.back() == '\n' || output.back() == '\r')) output.pop_back();
  const std::string last_line =
      output.substr(output.rfind('\n') == std::string::npos ? 0 : output.rfind('\n') + 1);
  if (!WIFEXITED(exit_status) || WEXITSTATUS(exit_status) != 0 || last_line.empty())
    throw Error(last_line.empty() ? "sbatch failed without a message" : last_line);
  return last_line.substr(0, last_line.find(';'));
}

}  // namespace mixmesh::batch
