#include "mixmesh/quality/report_format.hpp"

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "mixmesh/core/quoted.hpp"

namespace mixmesh {

namespace {

// A JSON number, or null where JSON has none.
std::string number(double value) {
  if (!std::isfinite(value)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::size_t planar_count(const MixedMesh& mesh, FaceType type) {
  return mesh.planar_cells[static_cast<std::size_t>(index(type))].nodes.size() /
         static_cast<std::size_t>(node_count(type));
}

std::string fixed(double value, int digits = 4) {
  if (!std::isfinite(value)) return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
  std::ostringstream out;
  const double magnitude = std::abs(value);
  if (magnitude != 0.0 && (magnitude >= 1e5 || magnitude < 1e-3))
    out << std::scientific << std::setprecision(digits - 1) << value;
  else
    out << std::fixed << std::setprecision(digits) << value;
  return out.str();
}

}  // namespace

std::string format_table(const MixedMesh& mesh, const CheckReport& report, const ReportContext& context) {
  std::ostringstream out;
  const ValidityReport& validity = report.validity;
  out << "mesh " << context.file << "\n";
  out << "  points " << mesh.points.size();
  if (validity.planar) {
    out << "  planar triangles " << planar_count(mesh, FaceType::triangle) << "  planar quads "
        << planar_count(mesh, FaceType::quad) << "  boundary edges " << mesh.boundary_edges.markers.size()
        << "\n";
    out << "  interior edges " << validity.interior_faces << "  boundary edges " << validity.boundary_faces
        << "  total area " << fixed(validity.total_volume, 6) << "\n";
  } else {
    for (CellType type : all_cell_types) out << "  " << name(type) << ' ' << mesh.cell_count(type);
    out << "\n  tagged triangles " << mesh.face_count(FaceType::triangle) << "  tagged quads "
        << mesh.face_count(FaceType::quad) << "  markers " << mesh.marker_names.size() << "\n";
    out << "  interior faces " << validity.interior_faces << "  boundary faces " << validity.boundary_faces
        << "  total volume " << fixed(validity.total_volume, 6) << "\n";
  }

  out << "\nvalidity\n";
  for (const Finding& finding : validity.findings) {
    out << "  " << std::left << std::setw(26) << finding.check << std::right << std::setw(10) << finding.count
        << "  "
        << (finding.count == 0                             ? "ok"
            : finding.severity == Finding::Severity::error ? "ERROR"
                                                           : "warning")
        << "  " << finding.description << "\n";
    for (const Offender& offender : finding.examples)
      out << "      " << offender.entity << ' ' << offender.index
          << (offender.detail.empty() ? "" : " " + offender.detail) << " at (" << fixed(offender.location.x())
          << ", " << fixed(offender.location.y()) << ", " << fixed(offender.location.z()) << ")\n";
  }

  if (!report.quality.entries.empty()) {
    out << "\nquality" << std::string(30, ' ') << std::setw(9) << "count";
    for (const char* heading : {"min", "p1", "p5", "median", "p95", "p99", "max", "mean"})
      out << std::setw(11) << heading;
    out << "\n";
    for (const QualityEntry& entry : report.quality.entries) {
      const Statistics& statistics = entry.statistics;
      out << "  " << std::left << std::setw(19) << entry.metric << std::setw(16) << entry.entity << std::right
          << std::setw(9) << statistics.count;
      for (double value :
           {statistics.min, statistics.percentiles[0], statistics.percentiles[1], statistics.percentiles[2],
            statistics.percentiles[3], statistics.percentiles[4], statistics.max, statistics.mean})
        out << std::setw(11) << fixed(value);
      if (statistics.non_finite > 0) out << "  (" << statistics.non_finite << " not finite)";
      out << "\n";
    }
  }
  out << "\ntimings: read " << fixed(context.read_seconds, 3) << " s  validity "
      << fixed(report.validity_seconds, 3) << " s  quality " << fixed(report.quality_seconds, 3) << " s\n";
  out << validity.summary() << "\n";
  return out.str();
}

std::string format_json(const MixedMesh& mesh, const CheckReport& report, const ReportContext& context) {
  const ValidityReport& validity = report.validity;
  std::ostringstream out;
  out << "{\n  \"file\": " << quoted(context.file)
      << ",\n  \"valid\": " << (validity.valid() ? "true" : "false")
      << ",\n  \"summary\": " << quoted(validity.summary()) << ",\n";
  out << "  \"timings\": {\"read_seconds\": " << number(context.read_seconds)
      << ", \"validity_seconds\": " << number(report.validity_seconds)
      << ", \"quality_seconds\": " << number(report.quality_seconds) << "},\n";
  out << "  \"counts\": {\"points\": " << mesh.points.size();
  for (CellType type : all_cell_types) out << ", \"" << name(type) << "\": " << mesh.cell_count(type);
  out << ", \"triangle_faces\": " << mesh.face_count(FaceType::triangle)
      << ", \"quad_faces\": " << mesh.face_count(FaceType::quad)
      << ", \"planar_triangles\": " << planar_count(mesh, FaceType::triangle)
      << ", \"planar_quads\": " << planar_count(mesh, FaceType::quad)
      << ", \"boundary_edges\": " << mesh.boundary_edges.nodes.size() / 2
      << ", \"interior_faces\": " << validity.interior_faces
      << ", \"boundary_faces\": " << validity.boundary_faces << "},\n";
  out << "  \"total_volume\": " << number(validity.total_volume)
      << ",\n  \"planar\": " << (validity.planar ? "true" : "false") << ",\n  \"findings\": [";
  for (std::size_t item = 0; item < validity.findings.size(); ++item) {
    const Finding& finding = validity.findings[item];
    out << (item ? ",\n" : "\n") << "    {\"check\": " << quoted(finding.check)
        << ", \"description\": " << quoted(finding.description) << ", \"severity\": \""
        << (finding.severity == Finding::Severity::error ? "error" : "warning")
        << "\", \"count\": " << finding.count << ", \"examples\": [";
    for (std::size_t example = 0; example < finding.examples.size(); ++example) {
      const Offender& offender = finding.examples[example];
      out << (example ? ", " : "") << "{\"entity\": " << quoted(offender.entity)
          << ", \"index\": " << offender.index << ", \"location\": [" << number(offender.location.x()) << ", "
          << number(offender.location.y()) << ", " << number(offender.location.z())
          << "], \"detail\": " << quoted(offender.detail) << "}";
    }
    out << "]}";
  }
  out << "\n  ],\n  \"quality\": [";
  for (std::size_t item = 0; item < report.quality.entries.size(); ++item) {
    const QualityEntry& entry = report.quality.entries[item];
    const Statistics& statistics = entry.statistics;
    out << (item ? ",\n" : "\n") << "    {\"metric\": " << quoted(entry.metric)
        << ", \"entity\": " << quoted(entry.entity) << ", \"count\": " << statistics.count
        << ", \"non_finite\": " << statistics.non_finite << ", \"min\": " << number(statistics.min)
        << ", \"max\": " << number(statistics.max) << ", \"mean\": " << number(statistics.mean)
        << ", \"percentiles\": {";
    for (std::size_t slot = 0; slot < statistics_percentiles.size(); ++slot)
      out << (slot ? ", " : "") << "\"" << statistics_percentiles[slot]
          << "\": " << number(statistics.percentiles[slot]);
    out << "}, \"histogram\": {\"min\": " << number(statistics.min) << ", \"max\": " << number(statistics.max)
        << ", \"counts\": [";
    for (std::size_t bin = 0; bin < statistics.histogram.size(); ++bin)
      out << (bin ? ", " : "") << statistics.histogram[bin];
    out << "]}}";
  }
  out << "\n  ]\n}\n";
  return out.str();
}

}  // namespace mixmesh
