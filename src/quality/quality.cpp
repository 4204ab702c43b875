// measure_quality and check_mesh: per-cell metrics in parallel, then their statistics.
#include "mixmesh/quality/quality.hpp"

#include "mixmesh/mesh/cell_geometry.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "mixmesh/core/error.hpp"
#include "mixmesh/core/log.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/quality/cell_quality.hpp"
#include "hull_metric_quality.hpp"
#include "validity_parts.hpp"

namespace mixmesh {

namespace {

constexpr double degrees_per_radian = 57.29577951308232;

// Values waiting for their statistics, computed together in parallel at the end.
struct PendingEntry {
  std::string metric;
  std::string entity;
  std::vector<double> values;
};

template <typename Function>
void for_each_index(std::size_t count, const Function& function) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 2048), [&](const auto& range) {
    for (std::size_t item = range.begin(); item != range.end(); ++item) function(item);
  });
}

// OpenFOAM's non-orthogonality: the angle between the vector joining the centres and
// the face area vector, in degrees.
double angle_degrees(const Vector3& centres, const Vector3& area) {
  const double lengths = centres.norm() * area.norm();
  if (!(lengths > 0.0)) return lengths == 0.0 ? 90.0 : std::nan("");
  // atan2 rather than acos: exact near 0°, where acos loses half the digits.
  return std::atan2(centres.cross(area).norm(), centres.dot(area)) * degrees_per_radian;
}

using Centroids = std::array<std::vector<Vector3>, 4>;

Centroids cell_centroids(const MixedMesh& mesh) {
  Centroids centroids;
  for (CellType type : all_cell_types) {
    auto& centres = centroids[static_cast<std::size_t>(index(type))];
    centres.resize(mesh.cell_count(type));
    for_each_index(centres.size(), [&](std::size_t cell) {
      centres[cell] = cell_centroid(type, mesh.points, mesh.cell(type, cell));
    });
  }
  return centroids;
}

FaceGeometry cell_face_geometry(const MixedMesh& mesh, const CellFace& face) {
  Index nodes[4];
  const int count = face_nodes(mesh, face, nodes);
  return face_geometry(mesh.points, nodes, count);
}

std::vector<double> interior_non_orthogonality(const MixedMesh& mesh, const FaceConnectivity& faces,
                                               const Centroids& centroids) {
  auto centre = [&](const CellFace& face) -> const Vector3& {
    return centroids[static_cast<std::size_t>(index(face.type))][static_cast<std::size_t>(face.cell)];
  };
  std::vector<double> angles(faces.interior.size());
  for_each_index(angles.size(), [&](std::size_t face) {
    const auto& pair = faces.interior[face];
    // The first cell owns the face: its outward normal points to the second.
    angles[face] = angle_degrees(centre(pair[1]) - centre(pair[0]), cell_face_geometry(mesh, pair[0]).area);
  });
  return angles;
}

void measure_cells(const MixedMesh& mesh, std::vector<PendingEntry>& pending) {
  for (CellType type : all_cell_types) {
    const std::size_t count = mesh.cell_count(type);
    if (count == 0) continue;
    const bool tetrahedra = type == CellType::tetrahedron;
    std::vector<double> jacobian(count), skew(count), ratio(count), slivers(tetrahedra ? count : 0),
        dihedral(tetrahedra ? count : 0);
    for_each_index(count, [&](std::size_t cell) {
      const Index* nodes = mesh.cell(type, cell);
      jacobian[cell] = scaled_jacobian(type, mesh.points, nodes);
      skew[cell] = skewness(type, mesh.points, nodes);
      ratio[cell] = aspect_ratio(type, mesh.points, nodes);
      if (tetrahedra) {
        slivers[cell] = sliver(mesh.points, nodes);
        auto at = [&](int corner) -> const Vector3& { return mesh.points[static_cast<std::size_t>(nodes[corner])]; };
        dihedral[cell] = largest_dihedral_degrees(at(0), at(1), at(2), at(3));
      }
    });
    const std::string entity(name(type));
    pending.push_back({"scaled_jacobian", entity, std::move(jacobian)});
    pending.push_back({"skewness", entity, std::move(skew)});
    pending.push_back({"aspect_ratio", entity, std::move(ratio)});
    if (tetrahedra) {
      pending.push_back({"sliver", entity, std::move(slivers)});
      // Near 180 for a flat tetrahedron; right or acute for a stretched, well-aligned
      // one, which the scaled Jacobian calls bad all the same.
      pending.push_back({"largest_dihedral", entity, std::move(dihedral)});
    }
  }
}

// Layer cells stacked in columns: the top face (local face 1) of the lower cell is the
// bottom face (local face 0) of the upper one.
void measure_growth(const MixedMesh& mesh, const FaceConnectivity& faces,
                    std::vector<PendingEntry>& pending) {
  auto layered = [](CellType type) { return type == CellType::prism || type == CellType::hexahedron; };
  std::array<std::vector<double>, 4> ratios;
  for (const auto& pair : faces.interior) {
    if (!layered(pair[0].type) || !layered(pair[1].type)) continue;
    const int first = pair[0].local_face;
    const int second = pair[1].local_face;
    if (!((first == 1 && second == 0) || (first == 0 && second == 1))) continue;
    const CellFace& lower = first == 1 ? pair[0] : pair[1];
    const CellFace& upper = first == 1 ? pair[1] : pair[0];
    const double below =
        layer_height(lower.type, mesh.points, mesh.cell(lower.type, static_cast<std::size_t>(lower.cell)));
    const double above =
        layer_height(upper.type, mesh.points, mesh.cell(upper.type, static_cast<std::size_t>(upper.cell)));
    ratios[static_cast<std::size_t>(index(upper.type))].push_back(above / below);
  }
  for (CellType type : {CellType::prism, CellType::hexahedron})
    if (!ratios[static_cast<std::size_t>(index(type))].empty())
      pending.push_back({"growth_ratio", std::string(name(type)),
                         std::move(ratios[static_cast<std::size_t>(index(type))])});
}

void measure_planar(const MixedMesh& mesh, std::vector<PendingEntry>& pending) {
  struct EdgeSide {
    std::array<Index, 2> key;
    FaceType type;
    std::size_t cell;
    Vector3 normal;  // outward, length = edge length
    bool operator<(const EdgeSide& other) const { return key < other.key; }
  };
  std::vector<EdgeSide> sides;
  std::array<std::vector<Vector3>, 2> centres;
  for (FaceType type : all_face_types) {
    const FaceBlock& block = mesh.planar_cells[static_cast<std::size_t>(index(type))];
    const int stride = node_count(type);
    const std::size_t count = block.nodes.size() / static_cast<std::size_t>(stride);
    auto& centre = centres[static_cast<std::size_t>(index(type))];
    centre.resize(count);
    if (count == 0) continue;
    std::vector<double> jacobian(count), skew(count), ratio(count);
    for_each_index(count, [&](std::size_t cell) {
      const Index* nodes = block.nodes.data() + cell * static_cast<std::size_t>(stride);
      jacobian[cell] = scaled_jacobian(type, mesh.points, nodes);
      skew[cell] = skewness(type, mesh.points, nodes);
      ratio[cell] = aspect_ratio(type, mesh.points, nodes);
      centre[cell] = face_geometry(mesh.points, nodes, stride).centre;
    });
    for (std::size_t cell = 0; cell < count; ++cell) {
      const Index* nodes = block.nodes.data() + cell * static_cast<std::size_t>(stride);
      for (int corner = 0; corner < stride; ++corner) {
        const Index from = nodes[corner];
        const Index to = nodes[(corner + 1) % stride];
        const Vector3 along =
            mesh.points[static_cast<std::size_t>(to)] - mesh.points[static_cast<std::size_t>(from)];
        sides.push_back(
            {{std::min(from, to), std::max(from, to)}, type, cell, Vector3(along.y(), -along.x(), 0.0)});
      }
    }
    const std::string entity(name(type));
    pending.push_back({"scaled_jacobian", entity, std::move(jacobian)});
    pending.push_back({"skewness", entity, std::move(skew)});
    pending.push_back({"aspect_ratio", entity, std::move(ratio)});
  }
  std::sort(sides.begin(), sides.end());
  std::vector<double> interior;
  std::vector<double> boundary;
  auto centre_of = [&](const EdgeSide& side) -> const Vector3& {
    return centres[static_cast<std::size_t>(index(side.type))][side.cell];
  };
  for (std::size_t first = 0; first < sides.size();) {
    std::size_t last = first + 1;
    while (last < sides.size() && sides[last].key == sides[first].key) ++last;
    const EdgeSide& owner = sides[first];
    if (last - first == 2) {
      interior.push_back(angle_degrees(centre_of(sides[first + 1]) - centre_of(owner), owner.normal));
    } else if (last - first == 1) {
      const Vector3 middle = 0.5 * (mesh.points[static_cast<std::size_t>(owner.key[0])] +
                                    mesh.points[static_cast<std::size_t>(owner.key[1])]);
      boundary.push_back(angle_degrees(middle - centre_of(owner), owner.normal));
    }
    first = last;
  }
  if (!interior.empty()) pending.push_back({"non_orthogonality", "interior edges", std::move(interior)});
  if (!boundary.empty()) pending.push_back({"non_orthogonality", "boundary edges", std::move(boundary)});
}

QualityReport finish(std::vector<PendingEntry>& pending, const QualityOptions& options) {
  QualityReport report;
  report.entries.resize(pending.size());
  tbb::parallel_for(std::size_t{0}, pending.size(), [&](std::size_t entry) {
    report.entries[entry] = {pending[entry].metric, pending[entry].entity,
                             compute_statistics(std::move(pending[entry].values), options.histogram_bins)};
  });
  return report;
}

QualityReport measure_volume_quality(const MixedMesh& mesh, const FaceConnectivity& faces,
                                     const QualityOptions& options) {
  std::vector<PendingEntry> pending;
  measure_cells(mesh, pending);
  const Centroids centroids = cell_centroids(mesh);
  std::vector<double> interior = interior_non_orthogonality(mesh, faces, centroids);
  if (!interior.empty()) pending.push_back({"non_orthogonality", "interior faces", std::move(interior)});
  std::vector<double> boundary(faces.boundary.size());
  for_each_index(boundary.size(), [&](std::size_t face) {
    const CellFace& side = faces.boundary[face];
    const FaceGeometry geometry = cell_face_geometry(mesh, side);
    const Vector3& centre =
        centroids[static_cast<std::size_t>(index(side.type))][static_cast<std::size_t>(side.cell)];
    boundary[face] = angle_degrees(geometry.centre - centre, geometry.area);
  });
  if (!boundary.empty()) pending.push_back({"non_orthogonality", "boundary faces", std::move(boundary)});
  measure_growth(mesh, faces, pending);
  quality_detail::HullMetricValues hull = quality_detail::hull_metric_values(mesh, faces);
  if (!hull.shapes.empty()) {
    pending.push_back({"metric_edge_length", "hull tetrahedra", std::move(hull.edge_lengths)});
    pending.push_back({"metric_shape", "hull tetrahedra", std::move(hull.shapes)});
  }
  return finish(pending, options);
}

}  // namespace

const QualityEntry* QualityReport::find(const std::string& metric, const std::string& entity) const {
  for (const QualityEntry& entry : entries)
    if (entry.metric == metric && entry.entity == entity) return &entry;
  return nullptr;
}

std::vector<double> non_orthogonality(const MixedMesh& mesh, const FaceConnectivity& faces) {
  return interior_non_orthogonality(mesh, faces, cell_centroids(mesh));
}

QualityReport measure_quality(const MixedMesh& mesh, const QualityOptions& options) {
  compute_statistics({}, options.histogram_bins);  // throws for a bad bin count
  const Finding indices = quality_detail::check_node_indices(mesh, ValidityOptions{});
  if (indices.count > 0)
    throw Error("cannot measure quality: " + std::to_string(indices.count) +
                " cells or faces have node indices outside the " + std::to_string(mesh.points.size()) +
                " points");
  if (mesh.planar()) {
    std::vector<PendingEntry> pending;
    measure_planar(mesh, pending);
    return finish(pending, options);
  }
  return measure_volume_quality(mesh, match_faces(mesh), options);
}

CheckReport check_mesh(const MixedMesh& mesh, const CheckOptions& options) {
  quality_detail::check_options(options.validity);
  compute_statistics({}, options.quality.histogram_bins);  // throws for a bad bin count
  CheckReport report;
  Stopwatch validity_clock;
  Finding indices = quality_detail::check_node_indices(mesh, options.validity);
  if (indices.count > 0) {
    report.validity = validate(mesh, options.validity);
    report.validity_seconds = validity_clock.seconds();
    return report;
  }
  if (mesh.planar()) {
    report.validity = validate(mesh, options.validity);
    report.validity_seconds = validity_clock.seconds();
    Stopwatch quality_clock;
    std::vector<PendingEntry> pending;
    measure_planar(mesh, pending);
    report.quality = finish(pending, options.quality);
    report.quality_seconds = quality_clock.seconds();
    return report;
  }
  const FaceConnectivity faces = match_faces(mesh);
  report.validity = quality_detail::validate_volume(mesh, faces, options.validity);
  report.validity.findings.insert(report.validity.findings.begin(), std::move(indices));
  report.validity_seconds = validity_clock.seconds();
  Stopwatch quality_clock;
  report.quality = measure_volume_quality(mesh, faces, options.quality);
  report.quality_seconds = quality_clock.seconds();
  return report;
}

}  // namespace mixmesh
