// The compare feature without running the generator: the variants' options, the
// hybrid surface of a config, Wild's reference rows, the table, CSV and JSON files and
// the cut window.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "mixmesh/core/error.hpp"
#include "mixmesh/pipeline/compare.hpp"
#include "mixmesh/surface/surface_conversion.hpp"

using namespace mixmesh;

namespace {

GenerateOptions onera_options() {
  config::Document document =
      config::Document::load(std::string(MIXMESH_SOURCE_DIR) + "/cases/onera_m6.toml");
  return read_generate_options(document);
}

std::vector<CompareRow> measured_rows() {
  std::vector<CompareRow> rows;
  for (CompareVariant variant : all_compare_variants) {
    GenerateReport report;
    report.points = variant == CompareVariant::hybrid ? 1000 : 240;
    report.surface_elements = 100;
    report.tetrahedra = 50;
    rows.push_back(compare_row(variant, report));
  }
  return rows;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

}  // namespace

TEST(Compare, WildTableOneMixedMeshesUseAQuarterOfTheHybridPoints) {
  const std::vector<CompareRow> rows = wild_table1();
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_NEAR(point_ratio_to_hybrid(rows[0], rows), 0.238, 0.0005);
  EXPECT_NEAR(point_ratio_to_hybrid(rows[1], rows), 0.232, 0.0005);
  EXPECT_EQ(point_ratio_to_hybrid(rows[2], rows), 1.0);
  EXPECT_EQ(rows[2].hexahedra, 0u);
  EXPECT_EQ(rows[2].pyramids, 0u);
}

TEST(Compare, VariantsDifferOnlyInFarFieldSizingAndName) {
  const GenerateOptions base = onera_options();
  const GenerateOptions anisotropic = variant_options(base, CompareVariant::mixed_anisotropic);
  const GenerateOptions isotropic = variant_options(base, CompareVariant::mixed_isotropic);
  const GenerateOptions hybrid = variant_options(base, CompareVariant::hybrid);
  EXPECT_EQ(anisotropic.farfield.sizing, FarFieldSizing::anisotropic);
  EXPECT_EQ(isotropic.farfield.sizing, FarFieldSizing::isotropic);
  EXPECT_EQ(hybrid.farfield.sizing, FarFieldSizing::isotropic);
  EXPECT_EQ(hybrid.output.name, "onera_m6_hybrid");
  // Same wall spacing, growth and layer count in every variant.
  for (const GenerateOptions* options : {&anisotropic, &isotropic, &hybrid}) {
    EXPECT_EQ(options->march.spacing.layer_count, base.march.spacing.layer_count);
    EXPECT_EQ(options->march.spacing.growth_rate, base.march.spacing.growth_rate);
    EXPECT_EQ(options->march.spacing.first_spacing, base.march.spacing.first_spacing);
  }
}

TEST(Compare, HybridSurfaceIsAllTrianglesWithoutWake) {
  GenerateOptions base = onera_options();
  CompareOptions options;
  options.hybrid_edge_length = 0.03;
  const SurfaceMesh surface = hybrid_surface(base, options);
  EXPECT_TRUE(surface.structured.empty());
  for (const TrianglePatch& patch : surface.unstructured) EXPECT_EQ(patch.role, PatchRole::wall);
  const MixedMesh mesh = to_mixed_mesh(surface);
  EXPECT_EQ(mesh.face_count(FaceType::quad), 0u);
  EXPECT_GT(mesh.face_count(FaceType::triangle), 1000u);
}

TEST(Compare, TableCsvAndJsonHoldEveryRow) {
  const std::vector<CompareRow> rows = measured_rows();
  const std::string table = compare_table(rows);
  EXPECT_NE(table.find("hybrid (prisms + tets)"), std::string::npos);
  EXPECT_NE(table.find("24.0 %"), std::string::npos);
  EXPECT_NE(table.find("23.8 %"), std::string::npos);  // Wild's anisotropic mixed mesh

  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "mixmesh_compare_test";
  std::filesystem::create_directories(folder);
  write_compare_csv(folder / "compare.csv", rows);
  write_compare_json(folder / "compare.json", rows);
  std::istringstream csv(read_text(folder / "compare.csv"));
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(csv, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 7u);  // header, three measured, three reference
  EXPECT_EQ(lines[0].rfind("mesh,label,source,points,", 0), 0u);
  EXPECT_EQ(lines[1], "mixed_anisotropic,\"mixed, anisotropic tets\",mixmesh,240,100,0,50,0,0,0.24");
  EXPECT_EQ(lines[4].rfind("mixed_anisotropic,\"mixed, anisotropic tets\",Wild Table 1,456212,", 0), 0u);
  const std::string json = read_text(folder / "compare.json");
  EXPECT_NE(json.find("\"measured\": ["), std::string::npos);
  EXPECT_NE(json.find("\"points\": 1916138"), std::string::npos);
  EXPECT_NE(json.find("\"points_to_hybrid\": 0.24,"), std::string::npos);
  EXPECT_NE(json.find("\"hull_metric_within_range\": null"), std::string::npos);  // no metric stage
  std::filesystem::remove_all(folder);
}

TEST(Compare, SummaryGivesTheAnisotropicOverheadAndTheHullMetricConformity) {
  std::vector<CompareRow> rows = measured_rows();
  rows[0].points = 264;  // anisotropic: 264 points and 65 tetrahedra against 240 and 50
  rows[0].tetrahedra = 65;
  rows[0].hull_metric_within_range = 0.8014;
  const std::string summary = compare_summary(rows);
  EXPECT_NE(summary.find("anisotropic over isotropic tets: +10.0 % points, +30.0 % tetrahedra"), std::string::npos)
      << summary;
  EXPECT_NE(summary.find("mixed, anisotropic tets: metric edge lengths at the hull in [0.6, 1.6]: 80.1 %"),
            std::string::npos)
      << summary;
  EXPECT_EQ(summary.find("mixed, isotropic tets: metric"), std::string::npos) << summary;
  // Without the isotropic row there is nothing to compare with.
  rows.erase(rows.begin() + 1);
  EXPECT_EQ(compare_summary(rows).find("over isotropic"), std::string::npos);
}

TEST(Compare, RatioNeedsAHybridRow) {
  std::vector<CompareRow> rows = measured_rows();
  rows.pop_back();
  EXPECT_THROW(point_ratio_to_hybrid(rows.front(), rows), Error);
  // Without a hybrid the table has no ratios, and the CSV leaves the field empty.
  const std::string table = compare_table(rows);
  EXPECT_NE(table.find("mixed, isotropic tets"), std::string::npos);
  EXPECT_EQ(table.find("24.0 %"), std::string::npos);
  EXPECT_NE(table.find("23.8 %"), std::string::npos);
  rows = measured_rows();
  rows.back().points = 0;
  EXPECT_THROW(compare_table(rows), Error);
}

TEST(Compare, NeedsAGeneratedWingWithoutImports) {
  GenerateOptions base = onera_options();
  base.surface.imports.emplace_back();
  EXPECT_THROW(compare_wing(base), Error);
  EXPECT_THROW(run_compare(base, CompareOptions{}, Log()), Error);
  base = onera_options();
  base.surface.wing.reset();
  EXPECT_THROW(hybrid_surface(base, CompareOptions{}), Error);
}

TEST(Compare, VariantKeys) {
  for (CompareVariant variant : all_compare_variants)
    EXPECT_EQ(variant_from_key(variant_key(variant)), variant);
  EXPECT_THROW(variant_from_key("structured"), Error);
}

TEST(Compare, CutWindowFramesTheSection) {
  const GenerateOptions base = onera_options();
  const CutWindow window = cut_window(compare_wing(base), 0.44);
  EXPECT_NEAR(window.y, 0.44 * 1.1963, 1e-12);
  const double leading_edge = window.y * std::tan(30.0 * M_PI / 180.0);
  const double trailing_edge = 0.8059 + window.y * std::tan(15.8 * M_PI / 180.0);
  EXPECT_LT(window.x_minimum, leading_edge);
  EXPECT_GT(window.x_maximum, trailing_edge);
  EXPECT_LT(window.x_maximum - window.x_minimum, 1.5 * (trailing_edge - leading_edge));
  EXPECT_LT(window.z_minimum, -0.02);
  EXPECT_GT(window.z_maximum, 0.02);
  EXPECT_NEAR(window.leading_edge_x, leading_edge, 1e-9);
  EXPECT_NEAR(window.leading_edge_z, 0.0, 1e-9);
  const CutWindow close_up = leading_edge_close_up(window, 0.01);
  EXPECT_NEAR(close_up.x_minimum, leading_edge - 0.015, 1e-9);
  EXPECT_NEAR(close_up.x_maximum, leading_edge + 0.035, 1e-9);
  EXPECT_NEAR(close_up.z_maximum - close_up.z_minimum, 0.03, 1e-9);
  // A very thin layer still gets a close-up of 0.05 % of the chord.
  EXPECT_NEAR(leading_edge_close_up(window, 1e-8).z_maximum, 0.00075 * window.chord, 1e-12);
  EXPECT_THROW(cut_window(compare_wing(base), 1.5), Error);
  EXPECT_THROW(cut_window(compare_wing(base), -0.1), Error);
}
