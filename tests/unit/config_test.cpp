#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "mixmesh/config/config.hpp"

using namespace mixmesh;
using config::Bounds;
using config::Document;

namespace {

// Runs `body` and returns the message of the mixmesh::Error it throws ("" if none).
template <typename Body>
std::string error_of(Body body) {
  try {
    body();
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

struct WingOptions {  // a typical option struct: defaults in one place
  double root_chord = 1.0;
  int sections = 5;
  bool closed_trailing_edge = true;
  std::string distribution = "vinokur";
  std::filesystem::path airfoil;
  std::vector<double> twist;
};

WingOptions read_wing(const Document& document) {
  WingOptions options;
  config::Section root = document.root();
  config::Section wing = root.section("wing");
  wing.read("root_chord", options.root_chord, Bounds::positive());
  wing.read("sections", options.sections, Bounds::at_least(2));
  wing.read("closed_trailing_edge", options.closed_trailing_edge);
  wing.read_choice("distribution", options.distribution, {"uniform", "vinokur", "tanh"});
  wing.read_path("airfoil", options.airfoil);
  wing.read("twist", options.twist, Bounds::between(-90, 90));
  wing.finish();
  root.finish();
  return options;
}

}  // namespace

TEST(Config, ReadsTypedValuesAndKeepsDefaults) {
  const Document document = Document::parse(
      "[wing]\nroot_chord = 0.8059\nsections = 3\nairfoil = 'airfoils/onera_d.dat'\ntwist = [0, -1.5]\n",
      "/cases/m6.toml");
  const WingOptions options = read_wing(document);
  EXPECT_DOUBLE_EQ(options.root_chord, 0.8059);
  EXPECT_EQ(options.sections, 3);
  EXPECT_TRUE(options.closed_trailing_edge);
  EXPECT_EQ(options.distribution, "vinokur");
  EXPECT_EQ(options.airfoil, std::filesystem::path("/cases/airfoils/onera_d.dat"));
  EXPECT_EQ(options.twist, (std::vector<double>{0.0, -1.5}));
}

TEST(Config, NamedValuesKeepTheirDefaultAndRejectOtherNames) {
  enum class Shape { sphere, box };
  auto read_shape = [](const std::string& text) {
    const Document document = Document::parse(text, "f.toml");
    config::Section table = document.root().section("farfield");
    Shape shape = Shape::box;
    table.read_choice("shape", shape, {{"sphere", Shape::sphere}, {"box", Shape::box}});
    return shape;
  };
  EXPECT_EQ(read_shape("[farfield]\n"), Shape::box);
  EXPECT_EQ(read_shape("[farfield]\nshape = \"sphere\"\n"), Shape::sphere);
  EXPECT_EQ(error_of([&] { read_shape("[farfield]\nshape = \"cube\"\n"); }),
            "f.toml:2:9: 'farfield.shape' = \"cube\" must be one of: sphere, box");
}

TEST(Config, IntegerIsAcceptedWhereANumberIsExpected) {
  EXPECT_DOUBLE_EQ(read_wing(Document::parse("[wing]\nroot_chord = 2\n", "a.toml")).root_chord, 2.0);
}

TEST(Config, UnknownKeyIsReportedWithItsPosition) {
  EXPECT_EQ(error_of([] { read_wing(Document::parse("[wing]\nroot_chord = 1\nroot_cord = 2\n", "w.toml")); }),
            "w.toml:3:1: unknown key 'wing.root_cord'");
  EXPECT_EQ(error_of([] { read_wing(Document::parse("[wing]\n[extra]\n", "w.toml")); }),
            "w.toml:2:2: unknown key 'extra'");
}

TEST(Config, WrongTypeIsReportedWithItsPosition) {
  EXPECT_EQ(error_of([] { read_wing(Document::parse("[wing]\nroot_chord = 'long'\n", "w.toml")); }),
            "w.toml:2:14: 'wing.root_chord' must be a number, not a string");
  EXPECT_EQ(error_of([] { read_wing(Document::parse("[wing]\nsections = 2.5\n", "w.toml")); }),
            "w.toml:2:12: 'wing.sections' must be an integer, not a number");
  EXPECT_EQ(error_of([] { read_wing(Document::parse("[wing]\ntwist = [1, 'a']\n", "w.toml")); }),
            "w.toml:2:13: 'wing.twist' must hold numbers only, not a string");
}

TEST(Config, OutOfRangeValueIsReported) {
  EXPECT_EQ(error_of([] { read_wing(Document::parse("[wing]\nroot_chord = -0.5\n", "w.toml")); }),
            "w.toml:2:14: 'wing.root_chord' = -0.5 must be > 0");
  EXPECT_EQ(error_of([] { read_wing(Document::parse("[wing]\nroot_chord = nan\n", "w.toml")); }),
            "w.toml:2:14: 'wing.root_chord' = nan must be > 0");
  EXPECT_EQ(error_of([] { read_wing(Document::parse("[wing]\ntwist = [0, 91]\n", "w.toml")); }),
            "w.toml:2:13: 'wing.twist' holds 91, which must be in [-90, 90]");
  EXPECT_EQ(error_of([] { read_wing(Document::parse("[wing]\ndistribution = 'cosine'\n", "w.toml")); }),
            "w.toml:2:16: 'wing.distribution' = \"cosine\" must be one of: uniform, vinokur, tanh");
}

TEST(Config, MissingSectionAndSyntaxErrorsAreReported) {
  EXPECT_EQ(error_of([] { read_wing(Document::parse("title = 'x'\n", "w.toml")); }),
            "w.toml:1:1: missing table [wing]");
  const std::string syntax = error_of([] { Document::parse("[wing\nroot_chord = 1\n", "w.toml"); });
  EXPECT_EQ(syntax.rfind("w.toml:1:", 0), 0u) << syntax;
}

TEST(Config, ArraysOfTablesAreReadInOrder) {
  const Document document =
      Document::parse("[[station]]\ny = 0\n[[station]]\ny = 1.5\nchord = 2\n", "s.toml");
  config::Section root = document.root();
  std::vector<double> positions;
  for (config::Section station : root.sections("station")) {
    double y = 0.0;
    station.require("y", y);
    positions.push_back(y);
    double chord = 1.0;
    station.read("chord", chord, Bounds::positive());
    station.finish();
  }
  root.finish();
  EXPECT_EQ(positions, (std::vector<double>{0.0, 1.5}));
}

TEST(Config, RequiredKeyMissingIsReported) {
  const Document document = Document::parse("[[station]]\nchord = 2\n", "s.toml");
  config::Section station = document.root().sections("station").front();
  double y = 0.0;
  EXPECT_EQ(error_of([&] { station.require("y", y); }), "s.toml:1:1: [station] needs 'y'");
}

TEST(Config, MissingFileIsReported) {
  EXPECT_EQ(error_of([] { Document::load("/nonexistent/case.toml"); }),
            "/nonexistent/case.toml: cannot open config file");
}

TEST(Config, SetReplacesAndCreatesValues) {
  Document document = Document::parse("[wing]\nroot_chord = 1\n", "/cases/w.toml");
  document.set("wing.root_chord=0.5");
  document.set("wing.twist=[1, 2]");
  document.set("wing.distribution='tanh'");
  const WingOptions options = read_wing(document);
  EXPECT_DOUBLE_EQ(options.root_chord, 0.5);
  EXPECT_EQ(options.twist, (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(options.distribution, "tanh");
  document.set("output.formats=['vtu']");
  EXPECT_EQ(error_of([&] { read_wing(document); }),
            "/cases/w.toml (value set on the command line): unknown key 'output'");
  EXPECT_EQ(error_of([&] { document.set("wing.root_chord"); }),
            "--set wing.root_chord: expected KEY=VALUE, e.g. planform.taper=0.3");
  EXPECT_EQ(error_of([&] { document.set("wing.root_chord.x=1"); }),
            "--set wing.root_chord.x=1: 'wing.root_chord' is not a table");
}

TEST(Config, SweepDiscoveryListsScalarOptionsGivenAsArrays) {
  Document document = Document::parse(
      "[wing]\nroot_chord = [1, 2.5, 0.3]\nsections = [3, 4]\ntwist = [0, 1]\ndistribution = ['uniform', "
      "'tanh']\n",
      "w.toml");
  EXPECT_NE(error_of([&] { read_wing(document); }), "");  // an array where a number belongs
  document.discover_sweeps();
  const WingOptions first = read_wing(document);
  EXPECT_DOUBLE_EQ(first.root_chord, 1.0);
  EXPECT_EQ(first.distribution, "uniform");
  EXPECT_EQ(first.twist, (std::vector<double>{0.0, 1.0}));  // a list option stays a list
  ASSERT_EQ(document.sweeps().size(), 3u);
  EXPECT_EQ(document.sweeps()[0].key, "wing.root_chord");
  EXPECT_EQ(document.sweeps()[0].values, (std::vector<std::string>{"1", "2.5", "0.3"}));
  EXPECT_EQ(document.sweeps()[2].values, (std::vector<std::string>{"'uniform'", "'tanh'"}));
  for (const config::Sweep& sweep : document.sweeps()) document.set(sweep.key + "=" + sweep.values.back());
  const WingOptions last = read_wing(document);
  EXPECT_DOUBLE_EQ(last.root_chord, 0.3);
  EXPECT_EQ(last.sections, 4);
  EXPECT_EQ(last.distribution, "tanh");
}
