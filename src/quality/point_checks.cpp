// Findings common to volume and planar meshes: node indices, coordinates, unused and
// duplicate points.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "validity_parts.hpp"

namespace mixmesh::quality_detail {

Finding make_finding(const std::string& check, const std::string& description, Finding::Severity severity) {
  Finding finding;
  finding.check = check;
  finding.description = description;
  finding.severity = severity;
  return finding;
}

void add_offender(Finding& finding, std::size_t examples, std::string entity, std::size_t index,
                  const Vector3& location, std::string detail) {
  ++finding.count;
  if (finding.examples.size() < examples)
    finding.examples.push_back({std::move(entity), index, location, std::move(detail)});
}

namespace {

bool in_range(const Index* nodes, int count, std::size_t point_count) {
  for (int corner = 0; corner < count; ++corner)
    if (nodes[corner] < 0 || static_cast<std::size_t>(nodes[corner]) >= point_count) return false;
  return true;
}

void check_block(const std::vector<Index>& nodes, int stride, std::size_t point_count,
                 std::string_view entity, const ValidityOptions& options, Finding& finding) {
  const std::size_t count = nodes.size() / static_cast<std::size_t>(stride);
  for (std::size_t item = 0; item < count; ++item)
    if (!in_range(&nodes[item * static_cast<std::size_t>(stride)], stride, point_count))
      add_offender(finding, options.examples, std::string(entity), item, Vector3::Constant(std::nan("")));
}

// Integer cell of a uniform grid; the hash table below maps it to the points inside.
struct GridKey {
  std::int64_t x, y, z;
  bool operator<(const GridKey& other) const {
    if (x != other.x) return x < other.x;
    if (y != other.y) return y < other.y;
    return z < other.z;
  }
  bool operator==(const GridKey& other) const { return x == other.x && y == other.y && z == other.z; }
};

std::uint64_t hash(const GridKey& key) {
  std::uint64_t value = static_cast<std::uint64_t>(key.x) * 0x9E3779B97F4A7C15ull;
  value ^= static_cast<std::uint64_t>(key.y) * 0xC2B2AE3D27D4EB4Full + (value << 6) + (value >> 2);
  value ^= static_cast<std::uint64_t>(key.z) * 0x165667B19E3779F9ull + (value << 6) + (value >> 2);
  return value ^ (value >> 29);
}

// Points with another point within `tolerance` (absolute): a uniform grid of cells
// larger than the tolerance, so that a point needs to look into a neighbouring cell
// only when it lies within the tolerance of that cell's side. Points sorted by cell,
// an open-addressing table from cell to run of points: O(n log n), parallel.
std::vector<char> find_duplicates(const std::vector<Vector3>& points, const std::vector<char>& finite,
                                  const Vector3& lower, double tolerance, double cell_size) {
  const std::size_t count = points.size();
  auto grid = [&](const Vector3& point) {
    const Vector3 scaled = (point - lower) / cell_size;
    return GridKey{static_cast<std::int64_t>(std::floor(scaled.x())),
                   static_cast<std::int64_t>(std::floor(scaled.y())),
                   static_cast<std::int64_t>(std::floor(scaled.z()))};
  };
  // (cell, point) pairs sorted together: the sort reads contiguous memory.
  std::vector<std::pair<GridKey, std::size_t>> sorted;
  sorted.reserve(count);
  for (std::size_t point = 0; point < count; ++point)
    if (finite[point]) sorted.emplace_back(GridKey{0, 0, 0}, point);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, sorted.size()), [&](const auto& range) {
    for (std::size_t slot = range.begin(); slot != range.end(); ++slot)
      sorted[slot].first = grid(points[sorted[slot].second]);
  });
  tbb::parallel_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
    return a.first < b.first || (a.first == b.first && a.second < b.second);
  });
  std::vector<GridKey> keys(count);
  std::vector<std::size_t> order(sorted.size());
  for (std::size_t slot = 0; slot < sorted.size(); ++slot) {
    order[slot] = sorted[slot].second;
    keys[sorted[slot].second] = sorted[slot].first;
  }
  sorted = {};

  // Runs of equal cells and the table cell → run.
  std::vector<std::size_t> run_start;
  for (std::size_t slot = 0; slot < order.size(); ++slot)
    if (slot == 0 || !(keys[order[slot]] == keys[order[slot - 1]])) run_start.push_back(slot);
  run_start.push_back(order.size());
  const std::size_t runs = run_start.size() - 1;
  std::size_t capacity = 16;
  while (capacity < 2 * runs) capacity *= 2;
  std::vector<std::int64_t> table(capacity, -1);
  for (std::size_t run = 0; run < runs; ++run) {
    std::size_t slot = hash(keys[order[run_start[run]]]) & (capacity - 1);
    while (table[slot] >= 0) slot = (slot + 1) & (capacity - 1);
    table[slot] = static_cast<std::int64_t>(run);
  }
  auto find_run = [&](const GridKey& key) -> std::int64_t {
    std::size_t slot = hash(key) & (capacity - 1);
    while (table[slot] >= 0) {
      const std::int64_t run = table[slot];
      if (keys[order[run_start[static_cast<std::size_t>(run)]]] == key) return run;
      slot = (slot + 1) & (capacity - 1);
    }
    return -1;
  };

  std::vector<char> duplicate(count, 0);
  const double squared = tolerance * tolerance;
  auto near = [&](std::size_t point, std::size_t first, std::size_t last) {
    for (std::size_t other = first; other < last; ++other) {
      const std::size_t candidate = order[other];
      if (candidate != point && (points[candidate] - points[point]).squaredNorm() <= squared) return true;
    }
    return false;
  };
  // By runs: the own cell is the run itself; the table is only asked about
  // neighbouring cells, for the few points within the tolerance of a cell side.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs), [&](const auto& range) {
    for (std::size_t run = range.begin(); run != range.end(); ++run) {
      for (std::size_t slot = run_start[run]; slot < run_start[run + 1]; ++slot) {
        const std::size_t point = order[slot];
        bool found = near(point, run_start[run], run_start[run + 1]);
        const GridKey& key = keys[point];
        const Vector3 scaled = (points[point] - lower) / cell_size;
        std::array<std::array<int, 2>, 3> reach{};
        for (int axis = 0; axis < 3; ++axis) {
          const double fraction = scaled[axis] - std::floor(scaled[axis]);
          reach[static_cast<std::size_t>(axis)] = {fraction * cell_size <= tolerance ? -1 : 0,
                                                   (1.0 - fraction) * cell_size <= tolerance ? 1 : 0};
        }
        for (int dx = reach[0][0]; dx <= reach[0][1] && !found; ++dx)
          for (int dy = reach[1][0]; dy <= reach[1][1] && !found; ++dy)
            for (int dz = reach[2][0]; dz <= reach[2][1] && !found; ++dz) {
              if (dx == 0 && dy == 0 && dz == 0) continue;
              const std::int64_t other = find_run({key.x + dx, key.y + dy, key.z + dz});
              if (other >= 0)
                found = near(point, run_start[static_cast<std::size_t>(other)],
                             run_start[static_cast<std::size_t>(other) + 1]);
            }
        duplicate[point] = found;
      }
    }
  });
  return duplicate;
}

}  // namespace

Finding check_node_indices(const MixedMesh& mesh, const ValidityOptions& options) {
  Finding finding =
      make_finding("node_index_out_of_range", "cells or faces with a node index outside the points");
  const std::size_t point_count = mesh.points.size();
  for (CellType type : all_cell_types)
    check_block(mesh.block(type).nodes, node_count(type), point_count, name(type), options, finding);
  for (FaceType type : all_face_types) {
    const std::string entity = std::string(name(type)) + " face";
    check_block(mesh.faces(type).nodes, node_count(type), point_count, entity, options, finding);
    check_block(mesh.planar_cells[static_cast<std::size_t>(index(type))].nodes, node_count(type), point_count,
                "planar " + std::string(name(type)), options, finding);
  }
  check_block(mesh.boundary_edges.nodes, 2, point_count, "boundary edge", options, finding);
  return finding;
}

void check_options(const ValidityOptions& options) {
  auto out_of_range = [](const char* what, double value, const char* range) {
    std::ostringstream message;
    message << what << ' ' << value << " is outside " << range
            << " (a fraction of the bounding-box diagonal)";
    return Error(message.str());
  };
  if (!(options.duplicate_tolerance >= 0.0 && options.duplicate_tolerance <= 1e-2))
    throw out_of_range("duplicate point tolerance", options.duplicate_tolerance, "[0, 0.01]");
  if (!(options.planar_tolerance >= 0.0 && options.planar_tolerance <= 1.0))
    throw out_of_range("planar tolerance", options.planar_tolerance, "[0, 1]");
}

void check_points(const MixedMesh& mesh, const std::vector<char>& used, const ValidityOptions& options,
                  std::vector<Finding>& findings) {
  const std::vector<Vector3>& points = mesh.points;
  Finding not_finite = make_finding("non_finite_coordinates", "points with NaN or infinite coordinates");
  Finding unused = make_finding("unused_points", "points used by no cell", Finding::Severity::warning);
  Finding duplicates = make_finding("duplicate_points", "points with another point within the tolerance");

  std::vector<char> finite(points.size(), 0);
  Vector3 lower = Vector3::Constant(std::numeric_limits<double>::infinity());
  Vector3 upper = -lower;
  for (std::size_t point = 0; point < points.size(); ++point) {
    finite[point] = points[point].allFinite();
    if (!finite[point]) {
      add_offender(not_finite, options.examples, "point", point, points[point]);
      continue;
    }
    lower = lower.cwiseMin(points[point]);
    upper = upper.cwiseMax(points[point]);
    if (!used[point]) add_offender(unused, options.examples, "point", point, points[point]);
  }

  const std::size_t finite_count = points.size() - not_finite.count;
  if (finite_count > 1) {
    const double diagonal = (upper - lower).norm();
    // Cells at least the tolerance wide, at most a millionth of the diagonal so that
    // a typical cell holds one point; 1e-15 keeps the integer cell numbers in range.
    const double tolerance = options.duplicate_tolerance * diagonal;
    const double cell_size =
        diagonal > 0.0
            ? std::max({tolerance, std::min(1000.0 * tolerance, 1e-6 * diagonal), 1e-15 * diagonal})
            : 1.0;
    const std::vector<char> duplicate = find_duplicates(points, finite, lower, tolerance, cell_size);
    for (std::size_t point = 0; point < points.size(); ++point)
      if (duplicate[point]) add_offender(duplicates, options.examples, "point", point, points[point]);
  }
  findings.push_back(std::move(not_finite));
  findings.push_back(std::move(unused));
  findings.push_back(std::move(duplicates));
}

Vector3 face_centre(const MixedMesh& mesh, const CellFace& face) {
  Index nodes[4];
  const int count = face_nodes(mesh, face, nodes);
  Vector3 sum = Vector3::Zero();
  for (int corner = 0; corner < count; ++corner) sum += mesh.points[static_cast<std::size_t>(nodes[corner])];
  return sum / count;
}

}  // namespace mixmesh::quality_detail
