// The task side of a Slurm batch: the manifest, one task's run and result, resuming
// and collecting.
#include <fstream>

#include "mixmesh/batch/slurm.hpp"
#include "mixmesh/core/atomic_file.hpp"
#include "mixmesh/core/quoted.hpp"

namespace mixmesh::batch {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> split_tabs(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (std::size_t tab; (tab = line.find('\t', start)) != std::string::npos; start = tab + 1)
    fields.push_back(line.substr(start, tab - start));
  fields.push_back(line.substr(start));
  return fields;
}

// A manifest field holds no tab or line break, so each case stays one line.
void check_field(const std::string& field, const std::string& what) {
  if (field.find_first_of("\t\r\n") != std::string::npos)
    throw Error("batch: " + what + " '" + field +
                "' holds a tab or line break and cannot go into a manifest");
}

// Configs are named by absolute path in the manifest and the task results, so tasks
// and re-submissions agree whatever their working folder.
std::string absolute_config(const fs::path& config) {
  return fs::absolute(config).lexically_normal().string();
}

std::string strip_carriage_return(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

}  // namespace

void write_manifest(const fs::path& path, const std::vector<BatchCase>& cases) {
  write_atomically(path, [&](const fs::path& temporary) {
    std::ofstream file(temporary);
    file << "# mixmesh batch manifest: task N of the Slurm array runs case line N (from 0); "
            "case, config, settings, tab-separated\n";
    for (const BatchCase& batch_case : cases) {
      const std::string config = absolute_config(batch_case.config);
      check_field(batch_case.name, "case name");
      check_field(config, "config path");
      file << batch_case.name << '\t' << config;
      for (const std::string& setting : batch_case.settings) {
        check_field(setting, "setting");
        file << '\t' << setting;
      }
      file << '\n';
    }
    if (!file.flush()) throw Error(path.string() + ": cannot write the manifest");
  });
}

std::vector<BatchCase> read_manifest(const fs::path& path) {
  std::ifstream file(path);
  if (!file) throw Error(path.string() + ": cannot open the manifest");
  std::vector<BatchCase> cases;
  std::string line;
  for (long number = 1; std::getline(file, line); ++number) {
    line = strip_carriage_return(line);
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields = split_tabs(line);
    if (fields.size() < 2 || fields[0].empty() || fields[1].empty())
      throw file_error(path.string(), number,
                       "expected CASE<TAB>CONFIG[<TAB>KEY=VALUE...], not '" + line + "'");
    cases.push_back({fields[0], fields[1], {fields.begin() + 2, fields.end()}});
  }
  return cases;
}

void write_task_result(const fs::path& path, const BatchCase& batch_case, const CaseResult& result) {
  write_atomically(path, [&](const fs::path& temporary) {
    std::ofstream file(temporary);
    file << "# mixmesh batch task: the result of one case of a Slurm array\n"
         << "case = " << quoted(batch_case.name)
         << "\nconfig = " << quoted(absolute_config(batch_case.config)) << "\nsettings = [";
    for (std::size_t index = 0; index < batch_case.settings.size(); ++index)
      file << (index == 0 ? "" : ", ") << quoted(batch_case.settings[index]);
    file << "]\nstatus = " << quoted(result.status) << "\nexit_code = " << result.exit_code
         << "\nseconds = " << result.seconds << "\npeak_memory_kib = " << result.peak_memory_kib
         << "\nerror = " << quoted(result.error) << '\n';
    if (!file.flush()) throw Error(path.string() + ": cannot write the task result");
  });
}

std::optional<CaseResult> read_task_result(const fs::path& path, const BatchCase& batch_case) {
  if (!fs::exists(path)) return std::nullopt;
  config::Document document = config::Document::load(path);
  config::Section root = document.root();
  std::string name;
  std::string config;
  std::vector<std::string> settings;
  CaseResult result;
  root.require("case", name);
  root.require("config", config);
  root.read("settings", settings);
  root.require("status", result.status);
  root.read("exit_code", result.exit_code);
  root.read("seconds", result.seconds);
  double peak_memory_kib = 0.0;
  root.read("peak_memory_kib", peak_memory_kib);
  root.read("error", result.error);
  root.finish();
  // The result of an earlier case of the same name but another config or sweep value.
  if (name != batch_case.name || config != absolute_config(batch_case.config) ||
      settings != batch_case.settings)
    return std::nullopt;
  result.name = name;
  result.peak_memory_kib = static_cast<long>(peak_memory_kib);
  result.folder = path.parent_path();
  result.report = read_report(result.folder / "report.toml");
  return result;
}

std::vector<std::size_t> cases_to_run(const std::vector<BatchCase>& cases, const fs::path& output_folder) {
  std::vector<std::size_t> indexes;
  for (std::size_t index = 0; index < cases.size(); ++index) {
    const fs::path folder = output_folder / cases[index].name;
    std::optional<CaseResult> result;
    try {
      result = read_task_result(folder / "task.toml", cases[index]);
    } catch (const Error&) {
      // An unreadable result is no result: the case runs again.
    }
    const bool complete = result && result->status == "ok" && !result->report.empty();
    if (!complete) indexes.push_back(index);
  }
  return indexes;
}

CaseResult run_task(const fs::path& manifest, std::size_t index, const std::vector<std::string>& command,
                    const Log& log) {
  const std::vector<BatchCase> cases = read_manifest(manifest);
  if (index >= cases.size())
    throw Error(manifest.string() + ": no case " + std::to_string(index) + " (the manifest has " +
                std::to_string(cases.size()) + ")");
  BatchOptions options;
  options.output_folder = manifest.parent_path();
  options.command = command;
  const fs::path result_path = options.output_folder / cases[index].name / "task.toml";
  // A result of an earlier submission must not stand while the case runs again.
  fs::remove(result_path);
  CaseResult result = run_batch({cases[index]}, options, log).front();
  write_task_result(result_path, cases[index], result);
  return result;
}

std::vector<CaseResult> collect_results(const fs::path& output_folder) {
  const std::vector<BatchCase> cases = read_manifest(output_folder / "manifest.tsv");
  std::vector<CaseResult> results;
  for (std::size_t index = 0; index < cases.size(); ++index) {
    const fs::path folder = output_folder / cases[index].name;
    if (auto result = read_task_result(folder / "task.toml", cases[index])) {
      results.push_back(std::move(*result));
      continue;
    }
    CaseResult result;
    result.name = cases[index].name;
    result.status = "not finished";
    result.exit_code = -1;
    result.folder = folder;
    // Slurm's own last word on the task (time limit, out of memory), else the case's.
    result.error = last_error_line(output_folder / "slurm" / (std::to_string(index) + ".out"));
    if (result.error.empty()) result.error = last_error_line(folder / "log.txt");
    results.push_back(std::move(result));
  }
  return results;
}

}  // namespace mixmesh::batch
