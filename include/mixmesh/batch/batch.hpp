// Batch runs: many configs, N at a time, each in its own process and folder.
//
// A case runs as `PROGRAM generate CONFIG --set KEY=VALUE... --output-dir FOLDER
// --report FOLDER/report.toml` with its output in FOLDER/log.txt. A separate process
// per case means one crashing or failing case never stops the others, and its peak
// memory is measured by the kernel (wait4), not estimated.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "mixmesh/config/config.hpp"
#include "mixmesh/core/log.hpp"

namespace mixmesh::batch {

struct BatchCase {
  std::string name;  // readable, unique: stem plus swept values
  std::filesystem::path config;
  std::vector<std::string> settings;  // KEY=VALUE for Document::set
};

// Config paths from the command line: files, glob patterns ("cases/*.toml") and list
// files (*.txt or *.list: one path or pattern per line, '#' starts a comment,
// relative to the list file). Throws on a pattern or file that names nothing.
std::vector<std::filesystem::path> collect_configs(const std::vector<std::string>& inputs);

// One case per combination of the sweeps' values (their Cartesian product), named
// "STEM__KEY-VALUE__KEY-VALUE" with the last component of each key.
std::vector<BatchCase> expand_sweeps(const std::filesystem::path& config,
                                     const std::vector<config::Sweep>& sweeps);

struct BatchOptions {
  int jobs = 1;
  std::filesystem::path output_folder = "batch";
  std::vector<std::string> command;  // program and subcommand, e.g. {"/usr/bin/mixmesh", "generate"}
};

struct CaseResult {
  std::string name;
  std::string status;  // "ok", or "failed (exit N)" / "failed (signal N)"; "not finished" (Slurm)
  int exit_code = 0;
  double seconds = 0.0;
  long peak_memory_kib = 0;
  std::filesystem::path folder;
  std::map<std::string, std::string> report;  // scalar entries of report.toml
  std::string error;                          // a failed case's last error line, from its log
};

std::vector<CaseResult> run_batch(const std::vector<BatchCase>& cases, const BatchOptions& options,
                                  const Log& log);

// Top-level scalar entries of a case's report.toml; empty when there is none (a
// failed case).
std::map<std::string, std::string> read_report(const std::filesystem::path& path);

// The last line of a log that contains "error" ("mixmesh: error: ...", "slurmstepd:
// error: ... TIME LIMIT"), or "" when none does or there is no log.
std::string last_error_line(const std::filesystem::path& path);

// Summary CSV: case, status, points, cells by type, min scaled Jacobian, deformed
// meshes, seconds, peak memory and the error line of a failed case; written atomically.
void write_summary(const std::filesystem::path& path, const std::vector<CaseResult>& results);

}  // namespace mixmesh::batch
