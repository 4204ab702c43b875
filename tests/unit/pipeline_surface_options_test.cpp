// Config tables [wing] and [surface]: the ready case reads as the ONERA M6, and every
// kind of bad input gives one error naming file:line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "mixmesh/config/config.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/pipeline/surface_options.hpp"
#include "mixmesh/pipeline/wing_options.hpp"

using namespace mixmesh;

namespace {

std::filesystem::path folder() {
  const auto path = std::filesystem::path(::testing::TempDir()) / "pipeline_surface_options_test";
  std::filesystem::create_directories(path);
  return path;
}

std::filesystem::path write_file(const std::string& name, const std::string& text) {
  const auto path = folder() / name;
  std::ofstream(path) << text;
  return path;
}

// Loads `text` as a config file and reads both tables; returns the error message ("" if none).
std::string error_of(const std::string& text) {
  const auto path = write_file("case.toml", text);
  try {
    config::Document document = config::Document::load(path);
    config::Section root = document.root();
    config::Section wing = root.section("wing");
    read_wing_definition(wing);
    if (auto surface = root.optional_section("surface")) read_surface_options(*surface);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

const std::string naca_wing = "[wing]\nnaca = \"0012\"\nroot_chord = 1.0\nsemi_span = 2.0\ntaper = 0.5\n";

}  // namespace

TEST(SurfaceConfig, OneraM6CaseReadsAsTheOneraM6) {
  config::Document document =
      config::Document::load(std::string(MIXMESH_SOURCE_DIR) + "/cases/onera_m6.toml");
  config::Section root = document.root();
  config::Section wing_table = root.section("wing");
  const WingDefinition wing = read_wing_definition(wing_table);
  ASSERT_EQ(wing.stations.size(), 2u);
  EXPECT_DOUBLE_EQ(wing.stations[0].chord, 0.8059);
  EXPECT_DOUBLE_EQ(wing.semi_span(), 1.1963);
  EXPECT_NEAR(wing.stations[1].chord, 0.4537, 5e-4);
  EXPECT_NEAR(wing.stations[1].leading_edge_x, 1.1963 * std::tan(M_PI / 6.0), 1e-12);
  EXPECT_EQ(wing.stations[1].twist_degrees, 0.0);
  EXPECT_EQ(wing.stations[1].leading_edge_z, 0.0);
  config::Section surface_table = root.section("surface");
  const SurfaceOptions options = read_surface_options(surface_table);
  EXPECT_EQ(options.chordwise_cells, 200);
  EXPECT_EQ(options.spanwise_cells, 40);
}

TEST(SurfaceConfig, StationsAreReadInOrderWithTheirOwnAirfoils) {
  const std::string text =
      "[wing]\nnaca = \"2412\"\ntwist_axis = 0.3\n"
      "[[wing.station]]\ny = 0.0\nchord = 2.0\n"
      "[[wing.station]]\ny = 1.0\nchord = 1.5\nleading_edge_x = 0.4\nleading_edge_z = 0.1\ntwist = -2.0\n"
      "[[wing.station]]\ny = 3.0\nchord = 0.5\nleading_edge_x = 1.8\ntwist = -4.0\nnaca = \"0010\"\n";
  config::Document document = config::Document::load(write_file("stations.toml", text));
  config::Section wing_table = document.root().section("wing");
  const WingDefinition wing = read_wing_definition(wing_table);
  ASSERT_EQ(wing.stations.size(), 3u);
  ASSERT_EQ(wing.airfoils.size(), 2u);
  EXPECT_EQ(wing.stations[1].airfoil, 0u);
  EXPECT_EQ(wing.stations[2].airfoil, 1u);
  EXPECT_EQ(wing.airfoils[1].source, "NACA 0010");
  EXPECT_DOUBLE_EQ(wing.stations[1].twist_degrees, -2.0);
  EXPECT_DOUBLE_EQ(wing.twist_axis, 0.3);
}

TEST(SurfaceConfig, EachBadInputIsOneErrorWithFileAndLine) {
  const auto expect_error = [](const std::string& text, const std::string& location,
                               const std::string& words) {
    const std::string message = error_of(text);
    EXPECT_NE(message.find(location), std::string::npos) << "expected '" << location << "' in: " << message;
    EXPECT_NE(message.find(words), std::string::npos) << "expected '" << words << "' in: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  expect_error(naca_wing, "", "");  // sanity: the base text is fine
  EXPECT_EQ(error_of(naca_wing), "");
  // Negative chord.
  expect_error("[wing]\nnaca = \"0012\"\nroot_chord = -1.0\nsemi_span = 2.0\ntaper = 0.5\n",
               "case.toml:3:", "root_chord");
  expect_error(
      "[wing]\nnaca = \"0012\"\n[[wing.station]]\ny = 0.0\nchord = 1.0\n[[wing.station]]\ny = 1.0\nchord = "
      "-0.5\n",
      "case.toml:8:", "chord");
  // Sweeps that leave no tip chord.
  expect_error(
      "[wing]\nnaca = \"0012\"\nroot_chord = 1.0\nsemi_span = 2.0\nleading_edge_sweep = "
      "40\ntrailing_edge_sweep = 0\n",
      "case.toml:6:", "tip chord");
  // Missing and unreadable airfoil files.
  expect_error("[wing]\nairfoil_file = \"missing.dat\"\nroot_chord = 1.0\nsemi_span = 2.0\ntaper = 0.5\n",
               "case.toml:2:", "missing.dat");
  write_file("unreadable.dat", "SECTION\n1.0 0.0\n0.5 0.05 0.3\n");
  expect_error("[wing]\nairfoil_file = \"unreadable.dat\"\nroot_chord = 1.0\nsemi_span = 2.0\ntaper = 0.5\n",
               "unreadable.dat:3:", "two numbers");
  // Crossing surfaces and too few points: the airfoil file's line.
  write_file("crossing.dat",
             "X\n1 0.01\n0.75 0.04\n0.5 0.05\n0.25 0.04\n0 0\n0.25 -0.04\n0.5 0.06\n0.75 -0.04\n1 -0.01\n");
  expect_error("[wing]\nairfoil_file = \"crossing.dat\"\nroot_chord = 1.0\nsemi_span = 2.0\ntaper = 0.5\n",
               "crossing.dat:", "cross");
  write_file("few.dat", "F\n1 0\n0.5 0.05\n0 0\n0.5 -0.05\n1 0\n");
  expect_error("[wing]\nairfoil_file = \"few.dat\"\nroot_chord = 1.0\nsemi_span = 2.0\ntaper = 0.5\n",
               "few.dat", "too few points");
  // Unknown keys, in each table.
  expect_error(naca_wing + "span = 3.0\n", "case.toml:6:", "unknown key 'wing.span'");
  expect_error(naca_wing + "[surface]\nchordwise = 100\n", "case.toml:7:", "unknown key 'surface.chordwise'");
  expect_error(naca_wing + "[surface.wake]\nlenght = 5\n",
               "case.toml:7:", "unknown key 'surface.wake.lenght'");
  // Other bad values.
  expect_error(naca_wing + "[surface]\nchordwise_cells = 4\n", "case.toml:7:", "chordwise_cells");
  expect_error(naca_wing + "[surface]\nbase_cells = 3\n", "case.toml:7:", "even");
  expect_error(naca_wing + "[surface]\nbase_face_aspect = -1\n", "case.toml:7:", "base_face_aspect");
  expect_error("[wing]\nnaca = \"0012\"\nroot_chord = 1.0\nsemi_span = 2.0\n", "case.toml:1:", "taper");
  expect_error("[wing]\nnaca = \"9x12\"\nroot_chord = 1.0\nsemi_span = 2.0\ntaper = 0.5\n",
               "case.toml:2:", "NACA");
  expect_error("[wing]\nnaca = \"0012\"\nroot_chord = 1.0\n[[wing.station]]\ny = 0.0\nchord = 1.0\n",
               "case.toml:3:", "classic planform");
  expect_error(
      "[wing]\nnaca = \"0012\"\n[[wing.station]]\ny = 0.5\nchord = 1.0\n[[wing.station]]\ny = 1.0\nchord = "
      "1.0\n",
      "case.toml:4:", "symmetry plane");
}
