#include <gtest/gtest.h>

#include <fstream>

#include "mixmesh/batch/batch.hpp"

#include "scratch_files.hpp"

using namespace mixmesh;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  return scratch_files::folder("batch-test", name);
}

using scratch_files::write;

}  // namespace

TEST(Batch, SweepsExpandToTheProductWithReadableNames) {
  const std::vector<config::Sweep> sweeps = {{"planform.leading_edge_sweep", {"0", "15", "30"}},
                                             {"planform.taper", {"0.3", "1.0"}}};
  const auto cases = batch::expand_sweeps("cases/wing.toml", sweeps);
  ASSERT_EQ(cases.size(), 6u);
  EXPECT_EQ(cases[0].name, "wing__leading_edge_sweep-0__taper-0.3");
  EXPECT_EQ(cases[5].name, "wing__leading_edge_sweep-30__taper-1.0");
  EXPECT_EQ(cases[5].settings,
            (std::vector<std::string>{"planform.leading_edge_sweep=30", "planform.taper=1.0"}));
  EXPECT_EQ(batch::expand_sweeps("a/b.toml", {}).front().name, "b");
}

TEST(Batch, ConfigsComeFromPathsPatternsAndListFiles) {
  const fs::path folder = scratch("collect");
  for (const char* name : {"a.toml", "b.toml", "c.toml"}) write(folder / name, "");
  write(folder / "cases.list", "# two cases\na.toml\n  c.toml  # trailing comment\n\n");
  const auto from_pattern = batch::collect_configs({(folder / "*.toml").string()});
  EXPECT_EQ(from_pattern.size(), 3u);
  const auto from_list = batch::collect_configs({(folder / "cases.list").string()});
  ASSERT_EQ(from_list.size(), 2u);
  EXPECT_EQ(from_list[1].filename(), "c.toml");
  EXPECT_THROW(batch::collect_configs({(folder / "missing.toml").string()}), Error);
  EXPECT_THROW(batch::collect_configs({(folder / "*.cfg").string()}), Error);
  write(folder / "bad.list", "a.toml\nnope.toml\n");
  try {
    batch::collect_configs({(folder / "bad.list").string()});
    FAIL() << "a list naming a missing file must fail";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("bad.list:2:"), std::string::npos) << error.what();
  }
}

TEST(Batch, FailingAndCrashingCasesDoNotStopTheOthers) {
  const fs::path folder = scratch("run");
  // Stands in for `mixmesh generate`: fails or dies by the config's content,
  // otherwise writes a report.
  write(folder / "case.sh",
        "config=$1; shift\n"
        "while [ $# -gt 0 ]; do case $1 in --report) report=$2; shift;; esac; shift; done\n"
        "if grep -q fail \"$config\"; then echo 'mixmesh: error: config is bad' >&2; exit 3; fi\n"
        "if grep -q crash \"$config\"; then kill -9 $$; fi\n"
        "printf 'points = 42\\ndeformed_meshes = 2\\n\\n[stages]\\npoints = 7\\n\\n[[deform]]\\n"
        "min_scaled_jacobian = 0.5\\n' > \"$report\"\n");
  std::vector<batch::BatchCase> cases;
  for (const char* content : {"good", "fail", "crash", "good"}) {
    const fs::path config = folder / (std::string(content) + std::to_string(cases.size()) + ".toml");
    write(config, content);
    cases.push_back({config.stem().string(), config, {}});
  }
  batch::BatchOptions options;
  options.jobs = 2;
  options.output_folder = folder / "out";
  options.command = {"/bin/sh", (folder / "case.sh").string()};
  const auto results = batch::run_batch(cases, options, Log());
  ASSERT_EQ(results.size(), 4u);
  EXPECT_EQ(results[0].status, "ok");
  EXPECT_EQ(results[0].report.at("points"), "42");  // not the same name in a table below
  EXPECT_EQ(results[0].report.at("deformed_meshes"), "2");
  EXPECT_EQ(results[0].report.count("min_scaled_jacobian"), 0u);
  EXPECT_EQ(results[1].status, "failed (exit 3)");
  EXPECT_EQ(results[2].status, "failed (signal 9)");
  EXPECT_EQ(results[3].status, "ok");
  std::ifstream log(folder / "out" / "fail1" / "log.txt");
  std::string line;
  std::getline(log, line);
  EXPECT_EQ(line, "mixmesh: error: config is bad");
  EXPECT_GT(results[0].peak_memory_kib, 0);

  batch::write_summary(folder / "summary.csv", results);
  std::ifstream summary(folder / "summary.csv");
  std::getline(summary, line);
  EXPECT_EQ(line,
            "case,status,points,hexahedra,prisms,pyramids,tetrahedra,min_scaled_jacobian,deformed_meshes,"
            "deformed_min_scaled_jacobian,seconds,peak_memory_mib,error");
  std::getline(summary, line);
  EXPECT_EQ(line.rfind("good0,ok,42,,,,,,2,,", 0), 0u) << line;
  EXPECT_EQ(line.back(), ',');  // no error line for a case that succeeded
  std::getline(summary, line);
  EXPECT_NE(line.find(",mixmesh: error: config is bad"), std::string::npos)
      << line;  // the failed case's last error line
}
