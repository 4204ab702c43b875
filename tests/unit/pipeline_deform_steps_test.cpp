// [[deform]] steps of a generation config: how they are read and what is refused.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace mixmesh
