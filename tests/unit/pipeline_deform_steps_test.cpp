// [[deform]] steps of a generation config: how they are read and what is refused.
#include <gtest/gtest.h>

#include <toml++/toml.h>
#include <filesystem>
#include <string>

#include "mixmesh/core/error.hpp"
#include "mixmesh/pipeline/generate.hpp"

namespace mixmesh {
namespace {

const std::string wing = "[wing]\nnaca = \"0012\"\nroot_chord = 1.0\nsemi_span = 2.0\ntaper = 0.6\n";

std::string step(const std::string& name, const std::string& extra = "") {
  return "[[deform]]\nname = \"" + name + "\"\n" + extra +
         "[[deform.body]]\nmarkers = [\"wall\"]\nangle = 3.0\n";
}

std::string error_of(const std::string& text, bool sweeps = false) {
  config::Document document = config::Document::parse(text, "case.toml");
  if (sweeps) document.discover_sweeps();
  try {
    read_generate_options(document);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(PipelineDeformSteps, ReadsStepsInOrder) {
  config::Document document =
      config::Document::parse(wing + step("a") + step("b", "steps = 3\n"), "case.toml");
  const GenerateOptions options = read_generate_options(document);
  ASSERT_EQ(options.deform.size(), 2u);
  EXPECT_EQ(options.deform[0].name, "a");
  EXPECT_EQ(options.deform[1].motion.steps, 3);
  EXPECT_NE(options.deform[1].where.find("case.toml:"), std::string::npos);
}

TEST(PipelineDeformSteps, RefusesTwoStepsOfOneName) {
  const std::string message = error_of(wing + step("a") + step("a"));
  EXPECT_NE(message.find("case.toml:"), std::string::npos) << message;
  EXPECT_NE(message.find("two [[deform]] steps named 'a'"), std::string::npos) << message;
}

TEST(PipelineDeformSteps, RefusesStepsThatWouldWriteOneFileTwice) {
  // "a" with three steps writes a_0001 … a_0003, which a step named "a_0002" would overwrite.
  const std::string message = error_of(wing + step("a", "steps = 3\n") + step("a_0002"));
  EXPECT_NE(message.find("case.toml:13"), std::string::npos) << message;
  EXPECT_NE(message.find("would write the files of 'a'"), std::string::npos) << message;
}

TEST(PipelineDeformSteps, RefusesANearestFaceCache) {
  const std::string message = error_of(wing + step("a") + "[deform.ara]\ncache = \"faces.bin\"\n");
  EXPECT_NE(message.find("case.toml:12"), std::string::npos) << message;
  EXPECT_NE(message.find("no nearest-face cache"), std::string::npos) << message;
}

TEST(PipelineDeformSteps, RefusesABatchSweepInsideAStep) {
  // A list of values is a sweep for `mixmesh batch`, which sets keys by their dotted
  // path; deform.body.angle does not say which step it means.
  const std::string text =
      wing + "[[deform]]\nname = \"a\"\n[[deform.body]]\nmarkers = [\"wall\"]\nangle = [3.0, 5.0]\n";
  const std::string message = error_of(text, true);
  EXPECT_NE(message.find("case.toml:10"), std::string::npos) << message;
  EXPECT_NE(message.find("cannot vary it"), std::string::npos) << message;
  // A sweep outside the steps stays a sweep.
  EXPECT_EQ(error_of("[wing]\nnaca = [\"0012\", \"0015\"]\nroot_chord = 1.0\nsemi_span = 2.0\ntaper = 0.6\n" +
                         step("a"),
                     true),
            "");
}

// (Not a [[deform]] key, but read by the same reader: the wake's spread angle.)
TEST(PipelineDeformSteps, MarchWakeSpreadIsReadAndBounded) {
  config::Document good = config::Document::parse(wing + "[march]\nwake_spread = 2.5\n", "case.toml");
  EXPECT_EQ(read_generate_options(good).march.wake_spread_degrees, 2.5);
  EXPECT_NE(error_of(wing + "[march]\nwake_spread = 45.0\n").find("case.toml:7:15: 'march.wake_spread'"),
            std::string::npos)
      << error_of(wing + "[march]\nwake_spread = 45.0\n");
}

// The report is TOML that reads back: a step name with quotes and a backslash is escaped.
TEST(PipelineDeformSteps, ReportReadsBackWithTheStepNames) {
  std::vector<DeformedMesh> meshes(2);
  meshes[0].step_name = "pitch \"up\" \\ 3";
  meshes[0].stem = "wing_" + meshes[0].step_name;
  meshes[0].min_scaled_jacobian = 0.25;
  meshes[1].step_name = "ramp";
  meshes[1].stem = "wing_ramp_0002";
  meshes[1].index = 2;
  meshes[1].steps = 3;
  meshes[1].min_scaled_jacobian = 0.125;
  const auto path = std::filesystem::temp_directory_path() / "mixmesh_deform_report.toml";
  write_report(path, GenerateReport{}, meshes);
  const toml::table report = toml::parse_file(path.string());
  std::filesystem::remove(path);
  EXPECT_EQ(report["deformed_meshes"].value<int>(), 2);
  EXPECT_EQ(report["deformed_min_scaled_jacobian"].value<double>(), 0.125);
  EXPECT_EQ(report["deform"][0]["step"].value<std::string>(), meshes[0].step_name);
  EXPECT_EQ(report["deform"][0]["file_stem"].value<std::string>(), meshes[0].stem);
  EXPECT_EQ(report["deform"][1]["index"].value<int>(), 2);
  EXPECT_EQ(report["deform"][1]["steps"].value<int>(), 3);
}

}  // namespace
}  // namespace mixmesh
