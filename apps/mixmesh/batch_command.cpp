#include <unistd.h>

#include <iostream>

#include "commands.hpp"
#include "mixmesh/batch/batch.hpp"
#include "mixmesh/pipeline/generate.hpp"

namespace mixmesh::cli {

namespace {

// The running mixmesh program, so the cases run with the same build.
std::string own_program() {
  std::error_code error;
  const auto path = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) throw Error("batch: cannot find the mixmesh program: " + error.message());
  return path.string();
}

}  // namespace

void add_batch_command(CLI::App& application) {
  struct Arguments {
    std::vector<std::string> inputs;
    int jobs = 1;
    std::string output_folder = "batch";
  };
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = application.add_subcommand(
      "batch",
      "Generate many configs, N at a time, each in its own process and folder (OUTPUT/CASE with log.txt and "
      "report.toml). A scalar config key given as a list (e.g. leading_edge_sweep = [0, 15, 30, 45]) runs "
      "once "
      "per value, over the product of all such lists. Writes OUTPUT/summary.csv; the exit status is the "
      "number "
      "of failed cases (0: all succeeded).");
  command->add_option("cases", arguments->inputs, "Config files, glob patterns or list files (.txt/.list)")
      ->required();
  command->add_option("-j,--jobs", arguments->jobs, "Cases run at the same time")->check(CLI::Range(1, 256));
  command->add_option("-o,--output", arguments->output_folder, "Folder for the case folders and summary.csv");
  command->callback([arguments] {
    const Log log(&std::cout);
    std::vector<batch::BatchCase> cases;
    std::vector<batch::CaseResult> rejected;
    for (const auto& config : batch::collect_configs(arguments->inputs)) {
      try {
        config::Document document = config::Document::load(config);
        document.discover_sweeps();
        read_generate_options(document);  // checks the config and finds its sweeps
        for (auto& expanded : batch::expand_sweeps(config, document.sweeps()))
          cases.push_back(std::move(expanded));
      } catch (const Error& error) {
        log.warning(error.what());
        batch::CaseResult failed;
        failed.name = config.stem().string();
        failed.status = "failed (config)";
        failed.exit_code = 1;
        rejected.push_back(failed);
      }
    }
    log.info("batch: " + std::to_string(cases.size()) + " cases, " + std::to_string(arguments->jobs) +
             " at a time");
    batch::BatchOptions options;
    options.jobs = arguments->jobs;
    options.output_folder = arguments->output_folder;
    options.command = {own_program(), "generate", "--quiet"};
    std::vector<batch::CaseResult> results = batch::run_batch(cases, options, log);
    results.insert(results.end(), rejected.begin(), rejected.end());
    const auto summary = std::filesystem::path(arguments->output_folder) / "summary.csv";
    batch::write_summary(summary, results);
    int failed = 0;
    for (const auto& result : results) failed += result.status != "ok";
    log.info("batch: " + std::to_string(results.size() - static_cast<std::size_t>(failed)) + " ok, " +
             std::to_string(failed) + " failed; summary in " + summary.string());
    if (failed > 0) throw CLI::RuntimeError(std::min(failed, 125));
  });
}

}  // namespace mixmesh::cli
