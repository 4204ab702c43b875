// The files of a Slurm batch (manifest, array script, task results) and resuming.
// The array itself runs against a real Slurm in tests/regression/slurm.cmake.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "mixmesh/batch/slurm.hpp"

#include "error_message.hpp"
#include "scratch_files.hpp"

using namespace mixmesh;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  return scratch_files::folder("batch-slurm-test", name);
}

using scratch_files::write;

std::string read(const fs::path& path) {
  std::ifstream stream(path);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

const std::vector<batch::BatchCase> three_cases = {
    {"wing__taper-0.3", "cases/wing.toml", {"wing.taper=0.3", "output.formats=[\"vtu\", \"su2\"]"}},
    {"wing__taper-1.0", "cases/wing.toml", {"wing.taper=1.0", "output.formats=[\"vtu\", \"su2\"]"}},
    {"other", "/abs/other.toml", {}}};

}  // namespace

TEST(BatchSlurm, ManifestKeepsEveryCaseOnOneLineWithAnAbsoluteConfig) {
  const fs::path folder = scratch("manifest");
  batch::write_manifest(folder / "manifest.tsv", three_cases);
  const auto cases = batch::read_manifest(folder / "manifest.tsv");
  ASSERT_EQ(cases.size(), 3u);
  EXPECT_EQ(cases[1].name, "wing__taper-1.0");
  EXPECT_EQ(cases[1].config, fs::current_path() / "cases/wing.toml");
  EXPECT_EQ(cases[1].settings, three_cases[1].settings);
  EXPECT_EQ(cases[2].config, "/abs/other.toml");
  EXPECT_TRUE(cases[2].settings.empty());

  EXPECT_NE(error_message([&] {
              batch::write_manifest(folder / "tab.tsv", {{"a", "a.toml", {"wing.name=\"x\ty\""}}});
            }).find("tab"),
            std::string::npos);
  write(folder / "bad.tsv", "# comment\nfine\t/a.toml\nno-config-here\n");
  EXPECT_NE(error_message([&] {
              batch::read_manifest(folder / "bad.tsv");
            }).find("bad.tsv:3: expected CASE<TAB>CONFIG"),
            std::string::npos);
}

TEST(BatchSlurm, ArrayIndexesAreRanges) {
  EXPECT_EQ(batch::array_indexes({0, 1, 2, 3, 7, 9, 10}), "0-3,7,9-10");
  EXPECT_EQ(batch::array_indexes({5}), "5");
  EXPECT_EQ(batch::array_indexes({2, 4}), "2,4");
}

TEST(BatchSlurm, ValuesThatWouldBreakAnSbatchLineAreRefused) {
  for (const char* time : {"30", "10:00", "01:00:00", "2-12", "2-12:30", "2-12:30:00", "UNLIMITED"})
    EXPECT_EQ(batch::slurm_value_problem("time", time), "") << time;
  for (const char* time : {"1h", "", "1:00:00:00", "-5"})
    EXPECT_NE(batch::slurm_value_problem("time", time), "") << time;
  EXPECT_EQ(batch::slurm_value_problem("memory", "4G"), "");
  EXPECT_NE(batch::slurm_value_problem("memory", "4 GB"), "");
  EXPECT_EQ(batch::slurm_value_problem("partition", "short,long"), "");
  EXPECT_NE(batch::slurm_value_problem("partition", "short\n#SBATCH --x"), "");
  EXPECT_EQ(batch::slurm_value_problem("directive", "--qos=short"), "");
  EXPECT_EQ(batch::slurm_value_problem("directive", "#SBATCH --qos=short"), "");
  EXPECT_NE(batch::slurm_value_problem("directive", "qos=short"), "");
  EXPECT_NE(batch::slurm_value_problem("directive", "--qos short"), "");
  EXPECT_NE(batch::slurm_value_problem("directive", "--array=0-3"), "");
}

TEST(BatchSlurm, SlurmTableIsReadWithPositions) {
  auto read = [](const std::string& text) {
    config::Document document = config::Document::parse(text, "/cases/batch.toml");
    config::Section table = document.root().section("slurm");
    return batch::read_slurm_options(table);
  };
  const auto options = read(
      "[slurm]\npartition = \"short\"\ntime = \"00:20:00\"\nmemory = \"2G\"\naccount = \"aero\"\n"
      "concurrency = 8\ndirectives = [\"--qos=low\"]\ntemplate = \"site.sh\"\n");
  EXPECT_EQ(options.partition, "short");
  EXPECT_EQ(options.time, "00:20:00");
  EXPECT_EQ(options.memory, "2G");
  EXPECT_EQ(options.account, "aero");
  EXPECT_EQ(options.concurrency, 8);
  EXPECT_EQ(options.directives, std::vector<std::string>{"--qos=low"});
  EXPECT_EQ(options.script_template, "/cases/site.sh");
  EXPECT_EQ(error_message([&] { read("[slurm]\n\ntime = \"1h\"\n"); }),
            "/cases/batch.toml:3:8: 'slurm.time' = \"1h\" must be minutes, MM:SS, HH:MM:SS, D-HH, D-HH:MM or "
            "D-HH:MM:SS");
  EXPECT_NE(error_message([&] {
              read("[slurm]\npartiton = \"x\"\n");
            }).find("batch.toml:2:1: unknown key 'slurm.partiton'"),
            std::string::npos);
  EXPECT_NE(error_message([&] { read("[slurm]\nconcurrency = 0\n"); }).find("batch.toml:2:15:"),
            std::string::npos);
  EXPECT_NE(error_message([&] {
              read("[slurm]\ndirectives = [\"--array=1\"]\n");
            }).find("--array is set by the batch"),
            std::string::npos);
}

TEST(BatchSlurm, ArrayScriptHasTheSbatchLinesBeforeTheTask) {
  batch::SlurmOptions options;
  options.partition = "short";
  options.time = "00:10:00";
  options.memory = "2G";
  options.account = "aero";
  options.concurrency = 2;
  options.directives = {"--qos=low", "#SBATCH --cpus-per-task=4"};
  const batch::ArrayJob job{"/opt/mixmesh it's/bin/mixmesh", "/scratch/wings", {0, 1, 3}};
  const std::string script = batch::array_script(job, options);
  EXPECT_EQ(script.rfind("#!/bin/bash\n", 0), 0u);
  for (const char* line : {"#SBATCH --array=0-1,3%2\n", "#SBATCH --output=/scratch/wings/slurm/%a.out\n",
                           "#SBATCH --partition=short\n", "#SBATCH --time=00:10:00\n", "#SBATCH --mem=2G\n",
                           "#SBATCH --account=aero\n", "#SBATCH --qos=low\n", "#SBATCH --cpus-per-task=4\n",
                           "#SBATCH --job-name=mixmesh-wings\n"})
    EXPECT_NE(script.find(line), std::string::npos) << line << " missing from\n" << script;
  const std::string task =
      "'/opt/mixmesh it'\\''s/bin/mixmesh' batch --task '/scratch/wings/manifest.tsv' --index "
      "\"$SLURM_ARRAY_TASK_ID\"\n";
  ASSERT_NE(script.find(task), std::string::npos) << script;
  // sbatch stops reading #SBATCH lines at the first command.
  EXPECT_GT(script.find(task), script.rfind("#SBATCH"));

  EXPECT_NE(error_message([&] {
              batch::array_script({"/bin/mixmesh", "/my wings", {0}}, {});
            }).find("spaces"),
            std::string::npos);
}

TEST(BatchSlurm, SiteTemplateReplacesTheBuiltInScript) {
  const fs::path folder = scratch("template");
  batch::SlurmOptions options;
  options.script_template = folder / "site.sh";
  write(options.script_template, "#!/bin/bash\n{{sbatch}}\nmodule load gcc\ncd {{output}}\n{{task}}\n");
  const std::string script = batch::array_script({"/bin/mixmesh", "/out", {4}}, options);
  EXPECT_NE(script.find("#SBATCH --ntasks=1\nmodule load gcc\ncd '/out'\n'/bin/mixmesh' batch --task"),
            std::string::npos)
      << script;

  // The misspelling is named, not only the placeholder it leaves missing.
  write(options.script_template, "#!/bin/bash\n{{sbatch}}\n{{tsk}}\n");
  EXPECT_NE(error_message([&] {
              batch::array_script({"/bin/mixmesh", "/out", {4}}, options);
            }).find("site.sh:3: unknown placeholder {{tsk}}"),
            std::string::npos);
  write(options.script_template, "#!/bin/bash\n{{sbatch}}\n");
  EXPECT_NE(error_message([&] {
              batch::array_script({"/bin/mixmesh", "/out", {4}}, options);
            }).find("has no {{task}}"),
            std::string::npos);
}

TEST(BatchSlurm, ResubmittingSkipsOnlyCasesWithACompleteResultOfTheSameCase) {
  const fs::path folder = scratch("resume");
  std::vector<batch::BatchCase> cases;
  for (const char* name : {"complete", "failed", "never_ran", "other_sweep", "no_report", "corrupt"})
    cases.push_back({name, folder / "wing.toml", {"wing.taper=0.5"}});
  batch::CaseResult ok;
  ok.status = "ok";
  batch::CaseResult failed;
  failed.status = "failed (exit 1)";
  failed.exit_code = 1;
  for (const auto& batch_case : cases) fs::create_directories(folder / batch_case.name);
  for (const std::size_t index : {0, 3, 4}) {
    batch::write_task_result(folder / cases[index].name / "task.toml", cases[index], ok);
    if (index != 4) write(folder / cases[index].name / "report.toml", "points = 10\n");
  }
  batch::write_task_result(folder / "failed" / "task.toml", cases[1], failed);
  write(folder / "corrupt" / "task.toml", "status = \"ok\n");
  write(folder / "corrupt" / "report.toml", "points = 10\n");
  cases[3].settings = {"wing.taper=0.7"};  // the same name now means another case
  EXPECT_EQ(batch::cases_to_run(cases, folder), (std::vector<std::size_t>{1, 2, 3, 4, 5}));
}

TEST(BatchSlurm, TasksRunAsTheLocalBatchAndCollectGivesItsSummary) {
  const fs::path folder = scratch("tasks");
  // Stands in for `mixmesh generate`, as in batch_test.cpp.
  write(folder / "case.sh",
        "config=$1; shift\n"
        "while [ $# -gt 0 ]; do case $1 in --report) report=$2; shift;; esac; shift; done\n"
        "if grep -q fail \"$config\"; then echo 'mixmesh: error: wing.toml:3: bad, really' >&2; exit 3; fi\n"
        "printf 'points = 42\\nmin_scaled_jacobian = 0.25\\n' > \"$report\"\n");
  write(folder / "good.toml", "good");
  write(folder / "fail.toml", "fail");
  const fs::path output = folder / "out";
  fs::create_directories(output);
  batch::write_manifest(output / "manifest.tsv", {{"good", folder / "good.toml", {}},
                                                  {"fail", folder / "fail.toml", {}},
                                                  {"late", folder / "good.toml", {"wing.taper=0.5"}}});
  const std::vector<std::string> command = {"/bin/sh", (folder / "case.sh").string()};
  EXPECT_EQ(batch::run_task(output / "manifest.tsv", 0, command, Log()).status, "ok");
  EXPECT_EQ(batch::run_task(output / "manifest.tsv", 1, command, Log()).exit_code, 3);
  EXPECT_NE(
      error_message([&] { batch::run_task(output / "manifest.tsv", 3, command, Log()); }).find("no case 3"),
      std::string::npos);
  write(output / "slurm" / "2.out",
        "slurmstepd: error: *** JOB 7 ON vm CANCELLED AT 2026-01-01T00:00:00 DUE TO "
        "TIME LIMIT ***\n");

  const auto results = batch::collect_results(output);
  ASSERT_EQ(results.size(), 3u);
  EXPECT_EQ(results[0].status, "ok");
  EXPECT_EQ(results[0].report.at("points"), "42");
  EXPECT_GT(results[0].peak_memory_kib, 0);
  EXPECT_EQ(results[1].status, "failed (exit 3)");
  EXPECT_EQ(results[1].error, "mixmesh: error: wing.toml:3: bad, really");
  EXPECT_EQ(results[2].status, "not finished");
  EXPECT_NE(results[2].error.find("DUE TO TIME LIMIT"), std::string::npos);
  EXPECT_EQ(batch::cases_to_run(batch::read_manifest(output / "manifest.tsv"), output),
            (std::vector<std::size_t>{1, 2}));

  batch::write_summary(output / "summary.csv", results);
  const std::string summary = read(output / "summary.csv");
  EXPECT_NE(summary.find("\ngood,ok,42,,,,,0.25,,,"), std::string::npos) << summary;
  EXPECT_NE(summary.find(",\"mixmesh: error: wing.toml:3: bad, really\"\n"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\nlate,not finished,"), std::string::npos) << summary;
}
