#include <unistd.h>

#include <fstream>
#include <iostream>
#include <set>

#include "commands.hpp"
#include "mixmesh/batch/batch.hpp"
#include "mixmesh/batch/slurm.hpp"
#include "mixmesh/core/atomic_file.hpp"
#include "mixmesh/pipeline/generate.hpp"

namespace mixmesh::cli {

namespace {

namespace fs = std::filesystem;

struct Arguments {
  std::vector<std::string> inputs;
  int jobs = 1;
  std::string output_folder = "batch";
  std::string slurm_folder;
  bool dry_run = false;
  batch::SlurmOptions slurm;  // as given on the command line
  std::string script_template;
  std::string collect_folder;
  std::string task_manifest;
  std::size_t task_index = 0;
};

// The Slurm options given on the command line, which override a [slurm] table.
struct SlurmFlags {
  CLI::Option* partition = nullptr;
  CLI::Option* time = nullptr;
  CLI::Option* memory = nullptr;
  CLI::Option* account = nullptr;
  CLI::Option* concurrency = nullptr;
  CLI::Option* directives = nullptr;
  CLI::Option* script_template = nullptr;
};

// The running mixmesh program, so the cases run with the same build.
std::string own_program() {
  std::error_code error;
  const auto path = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) throw Error("batch: cannot find the mixmesh program: " + error.message());
  return path.string();
}

std::vector<std::string> generate_command() {
  return {own_program(), "generate", "--quiet"};
}

// The cases of the command line's configs, sweeps expanded; a config that cannot be
// read becomes a failed result carrying its error instead.
std::vector<batch::BatchCase> read_cases(const std::vector<fs::path>& configs,
                                         std::vector<batch::CaseResult>& rejected) {
  std::vector<batch::BatchCase> cases;
  for (const auto& config : configs) {
    try {
      config::Document document = config::Document::load(config);
      document.discover_sweeps();
      read_generate_options(document);  // checks the config and finds its sweeps
      for (auto& expanded : batch::expand_sweeps(config, document.sweeps()))
        cases.push_back(std::move(expanded));
    } catch (const Error& error) {
      batch::CaseResult failed;
      failed.name = config.stem().string();
      failed.status = "failed (config)";
      failed.exit_code = 1;
      failed.error = error.what();
      rejected.push_back(failed);
    }
  }
  return cases;
}

// Writes the summary and ends with the number of cases that are not ok as the exit status.
void finish(const std::vector<batch::CaseResult>& results, const fs::path& summary, const Log& log) {
  batch::write_summary(summary, results);
  int failed = 0;
  int unfinished = 0;
  for (const auto& result : results) {
    failed += result.status != "ok" && result.status != "not finished";
    unfinished += result.status == "not finished";
  }
  const std::size_t ok = results.size() - static_cast<std::size_t>(failed + unfinished);
  log.info("batch: " + std::to_string(ok) + " ok, " + std::to_string(failed) + " failed" +
           (unfinished > 0 ? ", " + std::to_string(unfinished) + " not finished" : std::string()) +
           "; summary in " + summary.string());
  if (failed + unfinished > 0) throw CLI::RuntimeError(std::min(failed + unfinished, 125));
}

void run_locally(const Arguments& arguments, const Log& log) {
  std::vector<batch::CaseResult> rejected;
  const auto cases = read_cases(batch::collect_configs(arguments.inputs), rejected);
  for (const auto& failed : rejected) log.warning(failed.error);
  log.info("batch: " + std::to_string(cases.size()) + " cases, " + std::to_string(arguments.jobs) +
           " at a time");
  batch::BatchOptions options;
  options.jobs = arguments.jobs;
  options.output_folder = arguments.output_folder;
  options.command = generate_command();
  std::vector<batch::CaseResult> results = batch::run_batch(cases, options, log);
  results.insert(results.end(), rejected.begin(), rejected.end());
  finish(results, fs::path(arguments.output_folder) / "summary.csv", log);
}

// The [slurm] tables of the configs (which must agree), then the command line on top.
batch::SlurmOptions slurm_options(const std::vector<fs::path>& configs, const Arguments& arguments,
                                  const SlurmFlags& flags) {
  std::optional<std::pair<batch::SlurmOptions, std::string>> from_file;
  for (const fs::path& config : configs) {
    const config::Document document = config::Document::load(config);
    std::optional<config::Section> table = document.root().optional_section("slurm");
    if (!table) continue;
    batch::SlurmOptions options = batch::read_slurm_options(*table);
    if (!from_file) {
      from_file.emplace(options, table->where());
    } else if (!(options == from_file->first)) {
      table->fail({}, "[slurm] differs from the one at " + from_file->second +
                          "; one submission has one set of cluster settings");
    }
  }
  batch::SlurmOptions options = from_file ? from_file->first : batch::SlurmOptions{};
  const batch::SlurmOptions& given = arguments.slurm;
  if (flags.partition->count() > 0) options.partition = given.partition;
  if (flags.time->count() > 0) options.time = given.time;
  if (flags.memory->count() > 0) options.memory = given.memory;
  if (flags.account->count() > 0) options.account = given.account;
  if (flags.concurrency->count() > 0) options.concurrency = given.concurrency;
  if (flags.directives->count() > 0) options.directives = given.directives;
  if (flags.script_template->count() > 0) options.script_template = arguments.script_template;
  return options;
}

void submit_to_slurm(const Arguments& arguments, const SlurmFlags& flags, const Log& log) {
  const std::vector<fs::path> configs = batch::collect_configs(arguments.inputs);
  // A bad config stops the submission: queueing a cluster job for a typo helps nobody.
  std::vector<batch::CaseResult> rejected;
  const std::vector<batch::BatchCase> cases = read_cases(configs, rejected);
  if (!rejected.empty()) throw Error(rejected.front().error);
  std::set<std::string> names;
  for (const auto& batch_case : cases)
    if (!names.insert(batch_case.name).second)
      throw Error("batch: two cases are named '" + batch_case.name + "'; their folders would collide");
  const batch::SlurmOptions options = slurm_options(configs, arguments, flags);

  const fs::path folder = fs::absolute(arguments.slurm_folder).lexically_normal();
  fs::create_directories(folder / "slurm");
  for (const auto& batch_case : cases) fs::create_directories(folder / batch_case.name);
  batch::write_manifest(folder / "manifest.tsv", cases);
  const std::vector<std::size_t> indexes = batch::cases_to_run(cases, folder);
  const std::size_t complete = cases.size() - indexes.size();
  if (indexes.empty()) {
    log.info("batch: all " + std::to_string(cases.size()) +
             " cases have a complete result; nothing to submit");
    return;
  }
  const std::string script = batch::array_script({own_program(), folder, indexes}, options);
  const fs::path script_path = folder / "array.sh";
  write_atomically(script_path, [&](const fs::path& temporary) {
    std::ofstream file(temporary);
    file << script;
    if (!file.flush()) throw Error(script_path.string() + ": cannot write the array script");
  });
  log.info("batch: " + std::to_string(cases.size()) + " cases in " + (folder / "manifest.tsv").string() +
           ", " + std::to_string(indexes.size()) + " to run" +
           (complete > 0 ? " (" + std::to_string(complete) + " complete already)" : std::string()));
  if (arguments.dry_run) {
    log.info("batch: dry run: submit with  sbatch " + script_path.string());
    return;
  }
  const std::string job = batch::submit_array(script_path);
  log.info("batch: submitted job " + job + "; watch with  squeue --job " + job +
           "; when it is done:  mixmesh batch --collect " + folder.string());
}

void add_slurm_options(CLI::App& command, Arguments& arguments, SlurmFlags& flags) {
  auto value_check = [](const std::string& key) {
    return CLI::Validator(
        [key](std::string& value) {
          const std::string problem = batch::slurm_value_problem(key, value);
          return problem.empty() ? problem : "'" + value + "' " + problem;
        },
        "", key);
  };
  CLI::Option* slurm =
      command
          .add_option("--slurm", arguments.slurm_folder,
                      "Run on a Slurm cluster instead: write OUTPUT/manifest.tsv (one line per case), "
                      "OUTPUT/array.sh (a job array, one task per case) and a folder per case, then submit "
                      "with sbatch. Cases that already have a complete result are left out, so submitting "
                      "again re-runs only what failed or never ran. Settings come from a [slurm] table in "
                      "the configs and from the options below, which override it")
          ->option_text("OUTPUT");
  command.add_flag("--dry-run", arguments.dry_run, "With --slurm: write the files but do not submit")
      ->needs(slurm);
  // A --slurm setting whose text is checked as its [slurm] key would be.
  auto slurm_setting = [&](const std::string& name, auto& target, const std::string& help,
                           const std::string& key) {
    return command.add_option(name, target, help)->check(value_check(key))->needs(slurm);
  };
  flags.partition = slurm_setting("--partition", arguments.slurm.partition, "Slurm partition", "partition");
  flags.time = slurm_setting("--time", arguments.slurm.time,
                             "Time limit of one task: minutes, HH:MM:SS or D-HH:MM:SS", "time");
  flags.memory =
      slurm_setting("--memory", arguments.slurm.memory, "Memory of one task, e.g. 4G (--mem)", "memory");
  flags.account = slurm_setting("--account", arguments.slurm.account, "Slurm account to charge", "account");
  flags.concurrency =
      command
          .add_option("--concurrency", arguments.slurm.concurrency,
                      "Tasks running at once (--array=...%K); default: as many as Slurm allows")
          ->check(CLI::Range(1, 1000000))
          ->needs(slurm);
  flags.directives =
      slurm_setting("--sbatch", arguments.slurm.directives,
                    "One more #SBATCH option, repeatable; write --sbatch=--qos=short", "directive");
  flags.script_template =
      command
          .add_option("--template", arguments.script_template,
                      "A site's array script: {{sbatch}} becomes the #SBATCH lines, {{task}} the command "
                      "that runs one task, {{output}} the output folder")
          ->check(CLI::ExistingFile)
          ->needs(slurm);
}

}  // namespace

void add_batch_command(CLI::App& application) {
  auto arguments = std::make_shared<Arguments>();
  auto flags = std::make_shared<SlurmFlags>();
  CLI::App* command = application.add_subcommand(
      "batch",
      "Generate many configs, N at a time, each in its own process and folder (OUTPUT/CASE with log.txt and "
      "report.toml). A scalar config key given as a list (e.g. leading_edge_sweep = [0, 15, 30, 45]) runs "
      "once per value, over the product of all such lists. Writes OUTPUT/summary.csv; the exit status is "
      "the number of failed cases (0: all succeeded). With --slurm the cases run as a Slurm job array "
      "instead, and --collect writes the same summary once the array is done.");
  CLI::Option* cases = command->add_option("cases", arguments->inputs,
                                           "Config files, glob patterns or list files (.txt/.list)");
  CLI::Option* jobs = command->add_option("-j,--jobs", arguments->jobs, "Cases run at the same time")
                          ->check(CLI::Range(1, 256));
  CLI::Option* output = command->add_option("-o,--output", arguments->output_folder,
                                            "Folder for the case folders and summary.csv");
  add_slurm_options(*command, *arguments, *flags);
  command->get_option("--slurm")->excludes(jobs)->excludes(output);
  CLI::Option* collect =
      command
          ->add_option("--collect", arguments->collect_folder,
                       "Write OUTPUT/summary.csv of a Slurm batch from its task results, as a local run "
                       "would; a case without one is 'not finished', with Slurm's last error line")
          ->option_text("OUTPUT")
          ->excludes(cases)
          ->excludes(jobs)
          ->excludes(output)
          ->excludes(command->get_option("--slurm"));
  // What each task of the array script runs; not for users.
  CLI::Option* task = command->add_option("--task", arguments->task_manifest)->group("")->excludes(cases);
  command->add_option("--index", arguments->task_index)->group("")->needs(task);
  task->needs(command->get_option("--index"))->excludes(collect);

  command->callback([arguments, flags, cases, task, collect] {
    const Log log(&std::cout);
    if (task->count() > 0) {
      const auto result =
          batch::run_task(arguments->task_manifest, arguments->task_index, generate_command(), log);
      if (result.exit_code != 0) throw CLI::RuntimeError(result.exit_code);
    } else if (collect->count() > 0) {
      const fs::path folder = arguments->collect_folder;
      finish(batch::collect_results(folder), folder / "summary.csv", log);
    } else if (cases->count() == 0) {
      throw CLI::RequiredError("cases");
    } else if (!arguments->slurm_folder.empty()) {
      submit_to_slurm(*arguments, *flags, log);
    } else {
      run_locally(*arguments, log);
    }
  });
}

}  // namespace mixmesh::cli
