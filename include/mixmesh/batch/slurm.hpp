// Batches on a Slurm cluster: one job-array task per case.
//
//   OUTPUT/manifest.tsv   one line per case (sweeps expanded): name, config, settings;
//                         task N of the array runs line N
//   OUTPUT/array.sh       #SBATCH lines, then `mixmesh batch --task MANIFEST --index N`
//   OUTPUT/CASE/          what a local batch writes (log.txt, report.toml, meshes),
//                         plus task.toml: the case's status, seconds and peak memory
//   OUTPUT/slurm/N.out    what Slurm itself says about task N (time limit, node failure)
//
// A task runs its case through run_batch, so it is the same `mixmesh generate`
// process with the same atomic outputs as a local batch. A submission lists in
// --array only the cases without a complete result, so re-submitting resumes.
// collect_results turns the folder into the CaseResults of a local run.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mixmesh/batch/batch.hpp"
#include "mixmesh/config/config.hpp"

namespace mixmesh::batch {

// What the user may set; empty means the cluster's default. From the command line
// or from a [slurm] table of a batch config.
struct SlurmOptions {
  std::string partition;
  std::string time;    // per task: minutes, MM:SS, HH:MM:SS, D-HH, D-HH:MM or D-HH:MM:SS
  std::string memory;  // per task, sbatch --mem: 800M, 4G ...
  std::string account;
  int concurrency = 0;                    // tasks running at once (--array=...%K); 0: as many as Slurm allows
  std::vector<std::string> directives;    // more sbatch options, e.g. "--qos=short"
  std::filesystem::path script_template;  // a site's own script; empty: the built-in one

  bool operator==(const SlurmOptions& other) const;
};

// Why `value` cannot be given as `key` (partition, time, memory, account, directive),
// or "" when it can. Values become #SBATCH lines, so they are checked before anything
// is written rather than left for sbatch to reject.
std::string slurm_value_problem(const std::string& key, const std::string& value);

// The [slurm] table of a batch config: partition, time, memory, account,
// concurrency, directives (a list) and template (a path relative to the config).
// Errors name the key's file:line:column.
SlurmOptions read_slurm_options(config::Section& table);

// The manifest: a comment line, then NAME<TAB>CONFIG[<TAB>KEY=VALUE...] per case,
// the config's path absolute so tasks do not depend on their working folder.
void write_manifest(const std::filesystem::path& path, const std::vector<BatchCase>& cases);
std::vector<BatchCase> read_manifest(const std::filesystem::path& path);

// The result of one task, written atomically to CASE/task.toml when its case has
// run, and read back by collect_results. The case's config and settings are kept so
// a re-submission does not take the result of another case of the same name.
void write_task_result(const std::filesystem::path& path, const BatchCase& batch_case,
                       const CaseResult& result);
std::optional<CaseResult> read_task_result(const std::filesystem::path& path, const BatchCase& batch_case);

// Indexes of the cases to submit: those without a complete result in
// OUTPUT/CASE (task.toml of the same case with status ok, and its report.toml).
std::vector<std::size_t> cases_to_run(const std::vector<BatchCase>& cases,
                                      const std::filesystem::path& output_folder);

// Indexes in sbatch's --array form, runs of consecutive ones as ranges: "0-3,7,9-10".
std::string array_indexes(const std::vector<std::size_t>& indexes);

struct ArrayJob {
  std::filesystem::path program;        // the mixmesh each task runs
  std::filesystem::path output_folder;  // absolute
  std::vector<std::size_t> indexes;     // manifest lines to run; not empty
};

// The array script: the built-in template, or options.script_template, with its
// placeholders {{sbatch}} (the #SBATCH lines), {{task}} (the command that runs one
// task) and {{output}} (the output folder, shell-quoted) filled in.
std::string array_script(const ArrayJob& job, const SlurmOptions& options);

// Submits a script with `sbatch --parsable` and returns the job id; throws with
// sbatch's own error line when it refuses.
std::string submit_array(const std::filesystem::path& script);

// Case `index` of the manifest, run as a local batch would run it (`command` is
// BatchOptions::command), its result written to OUTPUT/CASE/task.toml.
CaseResult run_task(const std::filesystem::path& manifest, std::size_t index,
                    const std::vector<std::string>& command, const Log& log);

// One CaseResult per manifest line, in its order: from task.toml and report.toml,
// or status "not finished" for a case without a result (not started, running, or
// ended by Slurm, whose last error line from slurm/N.out becomes the error).
std::vector<CaseResult> collect_results(const std::filesystem::path& output_folder);

}  // namespace mixmesh::batch
