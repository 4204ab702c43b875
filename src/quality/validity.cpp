// validate() for volume meshes, and the report's verdict and summary.
#include "mixmesh/quality/validity.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"
#include "validity_parts.hpp"

namespace mixmesh {

bool ValidityReport::valid() const {
  return std::none_of(findings.begin(), findings.end(), [](const Finding& finding) {
    return finding.severity == Finding::Severity::error && finding.count > 0;
  });
}

const Finding* ValidityReport::find(const std::string& check) const {
  for (const Finding& finding : findings)
    if (finding.check == check) return &finding;
  return nullptr;
}

std::string ValidityReport::summary() const {
  std::size_t errors = 0;
  std::size_t warnings = 0;
  std::ostringstream problems;
  for (const Finding& finding : findings) {
    if (finding.count == 0) continue;
    (finding.severity == Finding::Severity::error ? errors : warnings) += 1;
    problems << (problems.tellp() > 0 ? "; " : "") << finding.count << ' ' << finding.description
             << (finding.severity == Finding::Severity::warning ? " (warning)" : "");
  }
  std::ostringstream line;
  line << (valid() ? "valid" : "INVALID") << ": " << errors << (errors == 1 ? " error, " : " errors, ")
       << warnings << (warnings == 1 ? " warning" : " warnings");
  if (problems.tellp() > 0) line << " (" << problems.str() << ')';
  return line.str();
}

namespace quality_detail {

namespace {

// A cell face offender: the cell, with the local face as detail.
void add_face_offender(Finding& finding, const MixedMesh& mesh, const CellFace& face, std::size_t examples) {
  add_offender(finding, examples, std::string(name(face.type)), static_cast<std::size_t>(face.cell),
               face_centre(mesh, face), "face " + std::to_string(face.local_face));
}

// Boundary edges (of boundary cell faces) not on exactly two boundary faces: cracks,
// hanging nodes, or two bodies touching along an edge.
Finding check_boundary_edges(const MixedMesh& mesh, const FaceConnectivity& faces,
                             const ValidityOptions& options) {
  Finding finding = make_finding("open_boundary_edges", "boundary edges not on exactly two boundary faces");
  std::vector<std::array<Index, 2>> edges;
  edges.reserve(faces.boundary.size() * 4);
  for (const CellFace& face : faces.boundary) {
    Index nodes[4];
    const int count = face_nodes(mesh, face, nodes);
    for (int corner = 0; corner < count; ++corner) {
      const Index from = nodes[corner];
      const Index to = nodes[(corner + 1) % count];
      edges.push_back({std::min(from, to), std::max(from, to)});
    }
  }
  tbb::parallel_sort(edges.begin(), edges.end());
  for (std::size_t first = 0; first < edges.size();) {
    std::size_t last = first + 1;
    while (last < edges.size() && edges[last] == edges[first]) ++last;
    if (last - first != 2) {
      const Vector3 middle = 0.5 * (mesh.points[static_cast<std::size_t>(edges[first][0])] +
                                    mesh.points[static_cast<std::size_t>(edges[first][1])]);
      add_offender(finding, options.examples, "edge", static_cast<std::size_t>(edges[first][0]), middle,
                   "nodes " + std::to_string(edges[first][0]) + "-" + std::to_string(edges[first][1]) +
                       " on " + std::to_string(last - first) + " boundary faces");
    }
    first = last;
  }
  return finding;
}

// The boundary triangles lying in a boundary quad, for the examples (match_faces
// only counts them).
Finding check_triangles_in_quads(const MixedMesh& mesh, const FaceConnectivity& faces,
                                 const ValidityOptions& options) {
  Finding finding = make_finding("triangle_against_quad", "boundary triangles inside a boundary quad");
  if (faces.triangles_in_quads == 0) return finding;
  std::vector<std::pair<std::array<Index, 4>, std::size_t>> quads;
  for (std::size_t face = 0; face < faces.boundary.size(); ++face) {
    Index nodes[4];
    if (face_nodes(mesh, faces.boundary[face], nodes) != 4) continue;
    std::array<Index, 4> sorted{nodes[0], nodes[1], nodes[2], nodes[3]};
    std::sort(sorted.begin(), sorted.end());
    quads.emplace_back(sorted, face);
  }
  for (const CellFace& face : faces.boundary) {
    Index nodes[4];
    if (face_nodes(mesh, face, nodes) != 3) continue;
    for (const auto& quad : quads) {
      const auto& corners = quad.first;
      auto holds = [&](Index node) { return std::binary_search(corners.begin(), corners.end(), node); };
      if (holds(nodes[0]) && holds(nodes[1]) && holds(nodes[2])) {
        add_face_offender(finding, mesh, face, options.examples);
        break;
      }
    }
  }
  // Trust match_faces' count; the scan above only finds the examples.
  finding.count = faces.triangles_in_quads;
  return finding;
}

}  // namespace

ValidityReport validate_volume(const MixedMesh& mesh, const FaceConnectivity& faces,
                               const ValidityOptions& options) {
  ValidityReport report;
  report.points = mesh.points.size();
  Finding non_positive = make_finding("non_positive_volume", "cells with non-positive volume");
  Finding tangled =
      make_finding("tangled_cells",
                   "cells with positive volume but a negative corner, sub-tetrahedron or face pyramid");
  std::vector<char> used(mesh.points.size(), 0);
  for (CellType type : all_cell_types) {
    const std::size_t count = mesh.cell_count(type);
    // 0 good, 1 non-positive, 2 tangled, 3 not computable (non-finite coordinates,
    // reported with the points).
    std::vector<char> verdict(count, 0);
    std::vector<double> volume(count, 0.0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 4096), [&](const auto& range) {
      for (std::size_t cell = range.begin(); cell != range.end(); ++cell) {
        const CellShape shape = cell_shape(type, mesh.points, mesh.cell(type, cell));
        volume[cell] = shape.volume;
        if (!std::isfinite(shape.volume))
          verdict[cell] = 3;
        else if (shape.volume <= 0.0)
          verdict[cell] = 1;
        else if (!shape.valid() || inverted_face_pyramids(type, mesh.points, mesh.cell(type, cell)) > 0)
          verdict[cell] = 2;
      }
    });
    for (std::size_t cell = 0; cell < count; ++cell) {
      if (verdict[cell] != 3) report.total_volume += volume[cell];
      if (verdict[cell] == 1 || verdict[cell] == 2)
        add_offender(verdict[cell] == 1 ? non_positive : tangled, options.examples, std::string(name(type)),
                     cell, cell_centre(type, mesh.points, mesh.cell(type, cell)));
    }
    for (Index node : mesh.block(type).nodes) used[static_cast<std::size_t>(node)] = 1;
  }
  Finding empty = make_finding("no_cells", "meshes without cells");
  if (mesh.cell_count() == 0) add_offender(empty, options.examples, "mesh", 0, Vector3::Zero());
  report.findings.push_back(std::move(empty));
  report.findings.push_back(std::move(non_positive));
  report.findings.push_back(std::move(tangled));

  Finding many = make_finding("faces_on_many_cells", "cell faces shared by more than two cells");
  for (const CellFace& face : faces.shared_by_many) add_face_offender(many, mesh, face, options.examples);
  report.findings.push_back(std::move(many));

  Finding same = make_finding("same_orientation", "interior faces wound the same way by both cells");
  for (const auto& pair : faces.same_orientation) add_face_offender(same, mesh, pair[0], options.examples);
  report.findings.push_back(std::move(same));

  report.findings.push_back(check_triangles_in_quads(mesh, faces, options));
  report.findings.push_back(check_boundary_edges(mesh, faces, options));

  Finding untagged =
      make_finding("untagged_boundary_faces", "boundary faces without a marker",
                   options.require_markers ? Finding::Severity::error : Finding::Severity::warning);
  for (const CellFace& face : faces.untagged_boundary)
    add_face_offender(untagged, mesh, face, options.examples);
  report.findings.push_back(std::move(untagged));

  Finding stray =
      make_finding("markers_off_boundary", "tagged faces that are not boundary faces of the cells");
  for (const auto& [type, face] : faces.stray_boundary_faces) {
    const Index* nodes = mesh.face(type, face);
    Vector3 centre = Vector3::Zero();
    for (int corner = 0; corner < node_count(type); ++corner)
      centre += mesh.points[static_cast<std::size_t>(nodes[corner])];
    add_offender(stray, options.examples, std::string(name(type)) + " face", face, centre / node_count(type));
  }
  report.findings.push_back(std::move(stray));

  check_points(mesh, used, options, report.findings);
  report.interior_faces = faces.interior.size() + faces.same_orientation.size();
  report.boundary_faces = faces.boundary.size();
  return report;
}

}  // namespace quality_detail

ValidityReport validate(const MixedMesh& mesh, const ValidityOptions& options) {
  quality_detail::check_options(options);
  Finding indices = quality_detail::check_node_indices(mesh, options);
  if (indices.count > 0) {
    ValidityReport report;
    report.points = mesh.points.size();
    report.planar = mesh.planar();
    report.findings.push_back(std::move(indices));
    return report;
  }
  if (mesh.planar()) {
    ValidityReport report = quality_detail::validate_planar(mesh, options);
    report.findings.insert(report.findings.begin(), std::move(indices));
    return report;
  }
  ValidityReport report = quality_detail::validate_volume(mesh, match_faces(mesh), options);
  report.findings.insert(report.findings.begin(), std::move(indices));
  return report;
}

}  // namespace mixmesh
