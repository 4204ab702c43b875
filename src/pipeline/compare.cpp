// Wild Table 1 for a wing config: the two mixed meshes and the hybrid baseline
// (compare.hpp), and the table, CSV and JSON of their counts.
#include "mixmesh/pipeline/compare.hpp"

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <set>
#include <sstream>

#include "mixmesh/core/atomic_file.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/core/quoted.hpp"
#include "mixmesh/surface/isotropic_surface.hpp"

namespace mixmesh {

namespace {

CompareRow reference_row(CompareVariant variant, std::size_t points, std::size_t surface,
                         std::size_t hexahedra, std::size_t tetrahedra, std::size_t prisms,
                         std::size_t pyramids) {
  CompareRow row;
  row.key = variant_key(variant);
  row.label = variant_label(variant);
  row.source = "Wild Table 1";
  row.points = points;
  row.surface_elements = surface;
  row.hexahedra = hexahedra;
  row.tetrahedra = tetrahedra;
  row.prisms = prisms;
  row.pyramids = pyramids;
  return row;
}

bool has_hybrid(const std::vector<CompareRow>& rows) {
  return std::any_of(rows.begin(), rows.end(), [](const CompareRow& row) { return row.key == "hybrid"; });
}

std::string ratio_text(const CompareRow& row, const std::vector<CompareRow>& rows) {
  if (!has_hybrid(rows)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.1f %%", 100.0 * point_ratio_to_hybrid(row, rows));
  return text;
}

}  // namespace

std::string variant_key(CompareVariant variant) {
  switch (variant) {
    case CompareVariant::mixed_anisotropic:
      return "mixed_anisotropic";
    case CompareVariant::mixed_isotropic:
      return "mixed_isotropic";
    case CompareVariant::hybrid:
      return "hybrid";
  }
  return "unknown";
}

std::string variant_label(CompareVariant variant) {
  switch (variant) {
    case CompareVariant::mixed_anisotropic:
      return "mixed, anisotropic tets";
    case CompareVariant::mixed_isotropic:
      return "mixed, isotropic tets";
    case CompareVariant::hybrid:
      return "hybrid (prisms + tets)";
  }
  return "unknown";
}

std::vector<CompareRow> wild_table1() {
  return {reference_row(CompareVariant::mixed_anisotropic, 456212, 32826, 191828, 467445, 316352, 41752),
          reference_row(CompareVariant::mixed_isotropic, 445310, 32826, 191828, 416421, 316352, 41752),
          reference_row(CompareVariant::hybrid, 1916138, 113702, 0, 974515, 3443584, 0)};
}

GenerateOptions variant_options(const GenerateOptions& base, CompareVariant variant) {
  GenerateOptions options = base;
  options.farfield.sizing =
      variant == CompareVariant::mixed_anisotropic ? FarFieldSizing::anisotropic : FarFieldSizing::isotropic;
  options.output.name = base.output.name + "_" + variant_key(variant);
  return options;
}

const WingDefinition& compare_wing(const GenerateOptions& base) {
  if (!base.surface.wing)
    throw Error("compare: the config has no [wing]; the comparison needs a generated wing");
  if (!base.surface.imports.empty())
    throw Error(
        "compare: the config imports surface patches ([[surface.import]]); the hybrid baseline "
        "can only triangulate the generated wing");
  return *base.surface.wing;
}

SurfaceMesh hybrid_surface(const GenerateOptions& base, const CompareOptions& options) {
  return generate_isotropic_wing_surface(compare_wing(base), base.surface.options,
                                         options.hybrid_edge_length);
}

EdgeStatistics triangle_edge_statistics(const SurfaceMesh& surface) {
  std::set<std::pair<Index, Index>> edges;
  for (const TrianglePatch& patch : surface.unstructured)
    for (std::size_t k = 0; k + 2 < patch.triangles.size(); k += 3)
      for (std::size_t e = 0; e < 3; ++e) {
        const Index a = patch.triangles[k + e], b = patch.triangles[k + (e + 1) % 3];
        edges.insert({std::min(a, b), std::max(a, b)});
      }
  EdgeStatistics statistics;
  statistics.edges = edges.size();
  if (edges.empty()) return statistics;
  statistics.minimum = 1e300;
  double sum = 0.0;
  for (const auto& [a, b] : edges) {
    const double length =
        (surface.points[static_cast<std::size_t>(a)] - surface.points[static_cast<std::size_t>(b)]).norm();
    sum += length;
    statistics.minimum = std::min(statistics.minimum, length);
    statistics.maximum = std::max(statistics.maximum, length);
  }
  statistics.mean = sum / static_cast<double>(edges.size());
  return statistics;
}

CompareRow compare_row(CompareVariant variant, const GenerateReport& report) {
  CompareRow row;
  row.key = variant_key(variant);
  row.label = variant_label(variant);
  row.source = "mixmesh";
  row.points = report.points;
  row.surface_elements = report.surface_elements;
  row.hexahedra = report.hexahedra;
  row.tetrahedra = report.tetrahedra;
  row.prisms = report.prisms;
  row.pyramids = report.pyramids;
  row.min_scaled_jacobian = report.min_scaled_jacobian;
  row.layer_thickness = report.march.total_thickness;
  row.seconds = report.seconds;
  if (report.farfield_summary.hull_lengths.edges > 0)
    row.hull_metric_within_range = report.farfield_summary.hull_lengths.within_range;
  return row;
}

std::vector<CompareRow> run_compare(const GenerateOptions& base, const CompareOptions& options,
                                    const Log& log) {
  compare_wing(base);  // before spending time on the first mesh
  std::vector<CompareRow> rows;
  for (CompareVariant variant : options.variants) {
    const GenerateOptions variant_generate = variant_options(base, variant);
    log.info("compare: " + variant_label(variant));
    try {
      GenerateResult result;
      if (variant == CompareVariant::hybrid) {
        Stopwatch watch;
        const SurfaceMesh surface = hybrid_surface(base, options);
        const double seconds = watch.seconds();
        const EdgeStatistics edges = triangle_edge_statistics(surface);
        std::ostringstream summary;
        summary << std::setprecision(4) << "surface: " << seconds << " s, isotropic triangles, "
                << surface.points.size() << " points, edges mean " << edges.mean << " m (" << edges.minimum
                << " to " << edges.maximum << ")";
        log.info(summary.str());
        result = generate_from_surface(surface, variant_generate, log);
        result.report.stages.insert(result.report.stages.begin(), StageTiming{"surface", seconds});
        result.report.seconds += seconds;
      } else {
        result = generate(variant_generate, log);
      }
      rows.push_back(compare_row(variant, result.report));
      if (options.write_meshes) {
        OutputOptions output = variant_generate.output;
        output.formats = {"vtu"};
        rows.back().mesh_file = write_outputs(result, output).front();
        log.info("wrote " + rows.back().mesh_file.string());
      }
    } catch (const Error& error) {
      throw Error("compare: " + variant_key(variant) + ": " + error.what());
    }
  }
  return rows;
}

CompareVariant variant_from_key(const std::string& key) {
  for (CompareVariant variant : all_compare_variants)
    if (variant_key(variant) == key) return variant;
  throw Error("compare: unknown mesh '" + key + "' (mixed_anisotropic, mixed_isotropic, hybrid)");
}

double point_ratio_to_hybrid(const CompareRow& row, const std::vector<CompareRow>& rows) {
  const auto hybrid = std::find_if(rows.begin(), rows.end(),
                                   [&](const CompareRow& candidate) { return candidate.key == "hybrid"; });
  if (hybrid == rows.end() || hybrid->points == 0)
    throw Error("compare: no hybrid row with points to compare '" + row.key + "' with");
  return static_cast<double>(row.points) / static_cast<double>(hybrid->points);
}

std::string compare_table(const std::vector<CompareRow>& measured) {
  const std::vector<CompareRow> reference = wild_table1();
  std::ostringstream table;
  const auto line = [&](const std::string& label, const std::vector<std::string>& cells) {
    table << std::left << std::setw(26) << label << std::right;
    for (const std::string& cell : cells) table << std::setw(11) << cell;
    table << '\n';
  };
  const auto count = [](std::size_t value) { return value == 0 ? std::string("-") : std::to_string(value); };
  line("mesh", {"points", "surface", "hexahedra", "tetrahedra", "prisms", "pyramids", "points/hyb"});
  for (const auto* rows : {&measured, &reference}) {
    table << (rows == &measured ? "mixmesh\n" : "Wild Table 1 (ONERA M6)\n");
    for (const CompareRow& row : *rows)
      line("  " + row.label,
           {std::to_string(row.points), count(row.surface_elements), count(row.hexahedra),
            count(row.tetrahedra), count(row.prisms), count(row.pyramids), ratio_text(row, *rows)});
  }
  return table.str();
}

std::string compare_summary(const std::vector<CompareRow>& measured) {
  auto find = [&](CompareVariant variant) {
    const auto row = std::find_if(measured.begin(), measured.end(),
                                  [&](const CompareRow& candidate) { return candidate.key == variant_key(variant); });
    return row == measured.end() ? nullptr : &*row;
  };
  std::ostringstream text;
  text << std::fixed << std::setprecision(1);
  const CompareRow* anisotropic = find(CompareVariant::mixed_anisotropic);
  const CompareRow* isotropic = find(CompareVariant::mixed_isotropic);
  auto growth = [](std::size_t value, std::size_t base) {
    return 100.0 * (static_cast<double>(value) / static_cast<double>(base) - 1.0);
  };
  if (anisotropic && isotropic && isotropic->points > 0 && isotropic->tetrahedra > 0)
    text << "anisotropic over isotropic tets: " << std::showpos << growth(anisotropic->points, isotropic->points)
         << " % points, " << growth(anisotropic->tetrahedra, isotropic->tetrahedra) << std::noshowpos
         << " % tetrahedra\n";
  for (const CompareRow& row : measured)
    if (row.hull_metric_within_range)
      text << row.label << ": metric edge lengths at the hull in [0.6, 1.6]: "
           << 100.0 * *row.hull_metric_within_range << " %\n";
  return text.str();
}

void write_compare_csv(const std::filesystem::path& path, const std::vector<CompareRow>& measured) {
  std::ostringstream csv;
  csv << "mesh,label,source,points,surface_elements,hexahedra,tetrahedra,prisms,pyramids,points_to_hybrid\n";
  const std::vector<CompareRow> reference = wild_table1();
  for (const auto* rows : {&measured, &reference})
    for (const CompareRow& row : *rows) {
      csv << row.key << ",\"" << row.label << "\"," << row.source << ',' << row.points << ','
          << row.surface_elements << ',' << row.hexahedra << ',' << row.tetrahedra << ',' << row.prisms << ','
          << row.pyramids << ',';
      if (has_hybrid(*rows)) csv << std::setprecision(6) << point_ratio_to_hybrid(row, *rows);
      csv << '\n';
    }
  write_text_atomically(path, csv.str());
}

void write_compare_json(const std::filesystem::path& path, const std::vector<CompareRow>& measured) {
  std::ostringstream json;
  json << std::setprecision(8) << "{\n";
  const std::vector<CompareRow> reference = wild_table1();
  for (const auto* rows : {&measured, &reference}) {
    json << "  " << (rows == &measured ? "\"measured\"" : "\"reference\"") << ": [\n";
    for (std::size_t k = 0; k < rows->size(); ++k) {
      const CompareRow& row = (*rows)[k];
      json << "    {\"mesh\": " << quoted(row.key) << ", \"label\": " << quoted(row.label)
           << ", \"source\": " << quoted(row.source) << ", \"points\": " << row.points
           << ", \"surface_elements\": " << row.surface_elements << ", \"hexahedra\": " << row.hexahedra
           << ", \"tetrahedra\": " << row.tetrahedra << ", \"prisms\": " << row.prisms
           << ", \"pyramids\": " << row.pyramids << ", \"points_to_hybrid\": ";
      if (has_hybrid(*rows)) {
        json << point_ratio_to_hybrid(row, *rows);
      } else {
        json << "null";
      }
      if (rows == &measured) {
        json << ", \"min_scaled_jacobian\": " << row.min_scaled_jacobian << ", \"seconds\": " << row.seconds
             << ", \"hull_metric_within_range\": ";
        if (row.hull_metric_within_range) {
          json << *row.hull_metric_within_range;
        } else {
          json << "null";
        }
        json << ", \"mesh_file\": " << quoted(row.mesh_file.string());
      }
      json << (k + 1 < rows->size() ? "},\n" : "}\n");
    }
    json << (rows == &measured ? "  ],\n" : "  ]\n");
  }
  json << "}\n";
  write_text_atomically(path, json.str());
}

CutWindow cut_window(const WingDefinition& wing, double span_fraction, double margin) {
  validate_wing(wing);
  if (!(span_fraction >= 0.0 && span_fraction <= 1.0))
    throw Error("compare: cut position " + std::to_string(span_fraction) +
                " must lie in [0, 1] of the semi-span");
  CutWindow window;
  window.y = wing.stations.front().y + span_fraction * wing.semi_span();
  const StationBlend blend = station_at(wing, window.y);
  double x_minimum = 1e300, x_maximum = -1e300, z_minimum = 1e300, z_maximum = -1e300;
  for (std::size_t airfoil : {blend.first_airfoil, blend.second_airfoil})
    for (const Vector2& point : wing.airfoils[airfoil].points) {
      const Vector3 placed = place_section_point(blend.parameters, wing.twist_axis, point);
      if (placed.x() < x_minimum) {
        window.leading_edge_x = placed.x();
        window.leading_edge_z = placed.z();
      }
      x_minimum = std::min(x_minimum, placed.x());
      x_maximum = std::max(x_maximum, placed.x());
      z_minimum = std::min(z_minimum, placed.z());
      z_maximum = std::max(z_maximum, placed.z());
    }
  const double chord = blend.parameters.chord;
  window.chord = chord;
  window.x_minimum = x_minimum - margin * chord;
  window.x_maximum = x_maximum + margin * chord;
  // A 5:3 picture centred on the section.
  const double middle = 0.5 * (z_minimum + z_maximum),
               half_height = 0.3 * (window.x_maximum - window.x_minimum);
  window.z_minimum = middle - half_height;
  window.z_maximum = middle + half_height;
  return window;
}

CutWindow leading_edge_close_up(const CutWindow& window, double layer_thickness) {
  const double size = std::max(layer_thickness, 0.0005 * window.chord);
  CutWindow close_up = window;
  close_up.x_minimum = window.leading_edge_x - 1.5 * size;
  close_up.x_maximum = window.leading_edge_x + 3.5 * size;
  close_up.z_minimum = window.leading_edge_z - 1.5 * size;
  close_up.z_maximum = window.leading_edge_z + 1.5 * size;
  return close_up;
}

}  // namespace mixmesh
