// `mixmesh compare`: Wild's Table 1 for a wing config. Three meshes of the same wing,
// wall spacing, growth and layer count:
//
//   mixed, anisotropic tets   the config as it is, with [farfield] sizing = anisotropic
//   mixed, isotropic tets     the same with sizing = isotropic
//   hybrid (prisms + tets)    an isotropic all-triangle surface (isotropic_surface.hpp),
//                             O-type prism layers (no wake), isotropic tets
//
//   std::vector<CompareRow> rows = run_compare(options, compare_options, log);
//   std::cout << compare_table(rows);
//   write_compare_csv("compare.csv", rows);
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mixmesh/pipeline/generate.hpp"

namespace mixmesh {

enum class CompareVariant { mixed_anisotropic, mixed_isotropic, hybrid };
inline constexpr CompareVariant all_compare_variants[] = {
    CompareVariant::mixed_anisotropic, CompareVariant::mixed_isotropic, CompareVariant::hybrid};

// "mixed_anisotropic", "mixed_isotropic", "hybrid": file stems and CSV keys.
std::string variant_key(CompareVariant variant);
// "mixed, anisotropic tets", ...: Table 1's row labels.
std::string variant_label(CompareVariant variant);

struct CompareOptions {
  // Target edge length of the hybrid's surface triangles in metres; 0: the mean
  // chordwise edge of the mixed surface at mid-span (default_isotropic_edge_length).
  double hybrid_edge_length = 0.0;
  // Write each valid mesh as output.folder / "<output.name>_<variant key>.vtu".
  bool write_meshes = true;
  // The variants to build, in this order (default all three).
  std::vector<CompareVariant> variants{std::begin(all_compare_variants), std::end(all_compare_variants)};
};

// One row of the table.
struct CompareRow {
  std::string key;     // variant key
  std::string label;   // row label
  std::string source;  // "mixmesh" or "Wild Table 1"
  std::size_t points = 0;
  std::size_t surface_elements = 0;
  std::size_t hexahedra = 0;
  std::size_t tetrahedra = 0;
  std::size_t prisms = 0;
  std::size_t pyramids = 0;
  double min_scaled_jacobian = 0.0;  // mixmesh rows only
  double layer_thickness = 0.0;      // mixmesh rows only: thickness of the full layers
  double seconds = 0.0;              // mixmesh rows only
  // Fraction of the hull-adjacent tetrahedron edges with a metric length in [0.6, 1.6]
  // (FarFieldResult::hull_lengths); mixmesh rows with a metric stage only, else unset.
  std::optional<double> hull_metric_within_range;
  std::filesystem::path mesh_file;   // empty when not written
};

// The ONERA M6 rows of Wild's Table 1 (method.md §6).
std::vector<CompareRow> wild_table1();

// The generate options of one variant, derived from the config's options: the far-field
// sizing of the variant; the hybrid keeps march (first spacing, growth, layer count,
// smoothing), interface and far-field options and marches an isotropic surface.
GenerateOptions variant_options(const GenerateOptions& base, CompareVariant variant);

// The config's wing. Throws mixmesh::Error if the config has no [wing] or imports
// patches ([[surface.import]]), which the hybrid's isotropic surface cannot reproduce.
const WingDefinition& compare_wing(const GenerateOptions& base);

// The hybrid's surface: generate_isotropic_wing_surface of the config's wing with
// options.hybrid_edge_length (0: the default rule).
SurfaceMesh hybrid_surface(const GenerateOptions& base, const CompareOptions& options);

// Edge lengths of the triangles of a surface (each edge once), for the hybrid
// surface's summary line.
struct EdgeStatistics {
  std::size_t edges = 0;
  double mean = 0.0, minimum = 0.0, maximum = 0.0;
};
EdgeStatistics triangle_edge_statistics(const SurfaceMesh& surface);

CompareRow compare_row(CompareVariant variant, const GenerateReport& report);

// Generates, validates (generate throws if a mesh is invalid) and optionally writes the
// three meshes one after the other, keeping one mesh in memory at a time. Errors name
// the variant: "compare: hybrid: march: ...".
std::vector<CompareRow> run_compare(const GenerateOptions& base, const CompareOptions& options,
                                    const Log& log);

// Share of the hybrid's points; the row with key "hybrid" among `rows` is the
// reference (throws mixmesh::Error if there is none or it has no points).
double point_ratio_to_hybrid(const CompareRow& row, const std::vector<CompareRow>& rows);

// The variant of a key ("hybrid", ...); throws mixmesh::Error naming the key otherwise.
CompareVariant variant_from_key(const std::string& key);

// What the anisotropic far field costs and gives, for the summary below the table:
// "anisotropic over isotropic tets: +2.1 % points, +22.0 % tetrahedra" when both
// mixed rows were built, and each row's "metric edge lengths at the hull in [0.6, 1.6]"
// where it has them; one line each.
std::string compare_summary(const std::vector<CompareRow>& measured);

// The measured rows, their ratios to the measured hybrid ("-" and an empty CSV field
// when no hybrid was built), then Wild's rows with their ratios, as an aligned table.
std::string compare_table(const std::vector<CompareRow>& measured);

// CSV: header mesh,label,source,points,surface_elements,hexahedra,tetrahedra,prisms,
// pyramids,points_to_hybrid; the measured rows then Wild's. JSON: {"measured": [...],
// "reference": [...]} with the same fields plus min_scaled_jacobian, seconds, mesh_file.
void write_compare_csv(const std::filesystem::path& path, const std::vector<CompareRow>& measured);
void write_compare_json(const std::filesystem::path& path, const std::vector<CompareRow>& measured);

// The picture window of a cut through the wing at y = span_fraction * semi-span: the
// section's extent in x and z, widened by `margin` local chords on each side.
struct CutWindow {
  double y = 0.0;
  double x_minimum = 0.0, x_maximum = 0.0, z_minimum = 0.0, z_maximum = 0.0;
  double leading_edge_x = 0.0, leading_edge_z = 0.0, chord = 0.0;  // of the cut section
};
CutWindow cut_window(const WingDefinition& wing, double span_fraction, double margin = 0.15);

// A close-up of the leading edge of the cut section showing the marched layers: from
// 1.5 T ahead of the leading edge to 3.5 T behind it and 1.5 T above and below, with
// T the layer thickness but at least 0.05 % of the local chord.
CutWindow leading_edge_close_up(const CutWindow& window, double layer_thickness);

}  // namespace mixmesh
