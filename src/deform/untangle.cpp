// Untangling after the layer transport (untangle.hpp says why).
#include "deform/untangle.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <numeric>

#include "deform/ara_smoothing.hpp"
#include "deform/rotation.hpp"
#include "mixmesh/mesh/topology.hpp"

namespace mixmesh::deform::detail {

void edge_neighbours(const DualMesh& dual, std::size_t node, std::vector<Index>& out) {
  out.clear();
  for (std::size_t slot = dual.point_cell_offsets[node]; slot < dual.point_cell_offsets[node + 1]; ++slot) {
    for_each_cell_edge(dual, static_cast<std::size_t>(dual.point_cells[slot]), [&](Index from, Index to) {
      if (from == static_cast<Index>(node)) out.push_back(to);
      if (to == static_cast<Index>(node)) out.push_back(from);
    });
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

std::vector<Index> inverted_region(const DualMesh& dual, const std::vector<char>& invalid, int rings) {
  std::vector<char> taken(dual.point_count, 0);
  std::vector<Index> region, neighbours;
  for (std::size_t cell = 0; cell < invalid.size(); ++cell) {
    if (!invalid[cell]) continue;
    for (int local = 0; local < dual.cell_size(cell); ++local) {
      const Index node = dual.nodes(cell)[local];
      if (taken[static_cast<std::size_t>(node)]) continue;
      taken[static_cast<std::size_t>(node)] = 1;
      region.push_back(node);
    }
  }
  for (int step = 0; step < rings; ++step) {
    const std::size_t size = region.size();
    for (std::size_t slot = 0; slot < size; ++slot) {
      edge_neighbours(dual, static_cast<std::size_t>(region[slot]), neighbours);
      for (Index other : neighbours) {
        if (taken[static_cast<std::size_t>(other)]) continue;
        taken[static_cast<std::size_t>(other)] = 1;
        region.push_back(other);
      }
    }
  }
  return region;
}

namespace {

// Rings of nodes round the inverted cells tried before giving up, and the sweeps of the
// affine update per try: a kink of the method's field is a node or two wide.
constexpr int largest_ring = 4;
constexpr int sweeps = 10;
constexpr int tries_per_ring = 3;

// Where the least-squares affine map of the neighbours' motion (weights 1/r², so each
// neighbour counts by its direction, not its distance) takes `node`; the mean
// translation when the neighbours do not span the space.
Vector3 affine_position(const DualMesh& dual, std::size_t node, const std::vector<Index>& neighbours,
                        const std::vector<Vector3>& original, const std::vector<Vector3>& moved) {
  double total = 0.0;
  Vector3 centre = Vector3::Zero();
  Vector3 image = Vector3::Zero();
  for (Index other : neighbours) {
    const std::size_t at = static_cast<std::size_t>(other);
    const double weight = 1.0 / std::max((original[at] - original[node]).squaredNorm(), 1e-300);
    total += weight;
    centre += weight * original[at];
    image += weight * moved[at];
  }
  if (total <= 0.0) return moved[node];
  centre /= total;
  image /= total;
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d cross = Eigen::Matrix3d::Zero();
  for (Index other : neighbours) {
    const std::size_t at = static_cast<std::size_t>(other);
    const double weight = 1.0 / std::max((original[at] - original[node]).squaredNorm(), 1e-300);
    const Vector3 from = original[at] - centre;
    second += weight * from * from.transpose();
    cross += weight * (moved[at] - image) * from.transpose();
  }
  if (dual.planar) {  // no z extent: the map of the plane, z kept
    second.row(2).setZero();
    second.col(2).setZero();
    second(2, 2) = 1.0;
    cross.col(2).setZero();
    cross(2, 2) = 1.0;
  }
  const Eigen::LDLT<Eigen::Matrix3d> solver(second);
  const double largest = second.diagonal().maxCoeff();
  const Vector3 pivots = solver.vectorD();
  if (solver.info() != Eigen::Success || largest <= 0.0 || pivots.minCoeff() <= 1e-10 * largest)
    return original[node] + (image - centre);
  const Eigen::Matrix3d map = solver.solve(cross.transpose()).transpose();
  return image + map * (original[node] - centre);
}

}  // namespace

UntangleReport untangle(const DualMesh& dual, const BoundaryMotion& boundary,
                        const std::vector<Vector3>& original, std::vector<Vector3>& moved) {
  UntangleReport report;
  const std::size_t cells = dual.cell_count();
  std::vector<char> invalid(cells, 0);
  parallel_items(cells, [&](std::size_t cell) { invalid[cell] = !cell_valid(dual, cell, moved); });
  report.inverted_before = static_cast<std::size_t>(std::count(invalid.begin(), invalid.end(), 1));
  report.inverted_after = report.inverted_before;
  if (report.inverted_before == 0) {
    report.invalid = std::move(invalid);
    return report;
  }

  const std::size_t point_count = original.size();
  std::vector<char> ever_moved(point_count, 0);
  for (int ring = 0; ring <= largest_ring && report.inverted_after > 0; ++ring) {
    for (int repeat = 0; repeat < tries_per_ring && report.inverted_after > 0; ++repeat) {
      ++report.rounds;
      // The region: the nodes of the inverted cells and `ring` rings round them.
      std::vector<Index> region = inverted_region(dual, invalid, ring);
      region.erase(std::remove_if(region.begin(), region.end(),
                                  [&](Index node) {
                                    return boundary.roles[static_cast<std::size_t>(node)] ==
                                           NodeRole::prescribed;
                                  }),
                   region.end());
      // The cells the region touches, and how many of them are inverted now.
      const std::vector<Index> touched = cells_of_nodes(dual, region);

      std::vector<std::vector<Index>> stars(region.size());
      for (std::size_t slot = 0; slot < region.size(); ++slot)
        edge_neighbours(dual, static_cast<std::size_t>(region[slot]), stars[slot]);
      std::vector<Vector3> kept(region.size());
      for (std::size_t slot = 0; slot < region.size(); ++slot)
        kept[slot] = moved[static_cast<std::size_t>(region[slot])];
      std::vector<Vector3> next(region.size());
      for (int sweep = 0; sweep < sweeps; ++sweep) {
        parallel_items(region.size(), [&](std::size_t slot) {
          const std::size_t node = static_cast<std::size_t>(region[slot]);
          next[slot] = affine_position(dual, node, stars[slot], original, moved);
          project_sliding(boundary, original, node, next[slot]);
        });
        for (std::size_t slot = 0; slot < region.size(); ++slot)
          moved[static_cast<std::size_t>(region[slot])] = next[slot];
      }
      // Each cluster of the region (nodes joined by a touched cell) is kept when fewer of
      // its cells are inverted than before, and put back otherwise.
      std::vector<std::size_t> cluster(region.size());
      std::iota(cluster.begin(), cluster.end(), std::size_t{0});
      auto root = [&](std::size_t slot) {
        while (cluster[slot] != slot) slot = cluster[slot] = cluster[cluster[slot]];
        return slot;
      };
      std::vector<std::size_t> slot_of(point_count, region.size());
      for (std::size_t slot = 0; slot < region.size(); ++slot)
        slot_of[static_cast<std::size_t>(region[slot])] = slot;
      std::vector<std::size_t> cell_cluster(touched.size());
      for (std::size_t entry = 0; entry < touched.size(); ++entry) {
        const std::size_t cell = static_cast<std::size_t>(touched[entry]);
        std::size_t first = region.size();
        for (int local = 0; local < dual.cell_size(cell); ++local) {
          const std::size_t slot = slot_of[static_cast<std::size_t>(dual.nodes(cell)[local])];
          if (slot == region.size()) continue;
          if (first == region.size())
            first = root(slot);
          else
            cluster[root(slot)] = first;
        }
        cell_cluster[entry] = first;
      }
      std::vector<char> now(touched.size());
      parallel_items(touched.size(), [&](std::size_t entry) {
        now[entry] = !cell_valid(dual, static_cast<std::size_t>(touched[entry]), moved);
      });
      std::vector<long> change(region.size(), 0);  // inverted after less before, per cluster root
      for (std::size_t entry = 0; entry < touched.size(); ++entry)
        change[root(cell_cluster[entry])] +=
            static_cast<long>(now[entry]) -
            static_cast<long>(invalid[static_cast<std::size_t>(touched[entry])]);
      bool better = false;
      for (std::size_t slot = 0; slot < region.size(); ++slot) {
        if (change[root(slot)] < 0) {
          better = true;
          ever_moved[static_cast<std::size_t>(region[slot])] = 1;
        } else {
          moved[static_cast<std::size_t>(region[slot])] = kept[slot];
        }
      }
      for (std::size_t entry = 0; entry < touched.size(); ++entry) {
        if (change[root(cell_cluster[entry])] >= 0) continue;
        const std::size_t cell = static_cast<std::size_t>(touched[entry]);
        report.inverted_after -= static_cast<std::size_t>(invalid[cell]);
        report.inverted_after += static_cast<std::size_t>(now[entry]);
        invalid[cell] = now[entry];
      }
      if (!better) break;  // no cluster got better: try a wider region
    }
  }
  // What the affine maps leave (flat cells up to 0.9 m long whose neighbours' motion is
  // not affine over that length to the fraction of a millimetre they are thick): a
  // local optimisation that puts each node where its cells' volumes are largest.
  if (report.inverted_after > 0) {
    report.optimise_before = report.inverted_after;
    report.inverted_after = optimise_inverted(dual, boundary, original, moved, invalid, ever_moved);
  }
  report.moved_nodes = static_cast<std::size_t>(std::count(ever_moved.begin(), ever_moved.end(), 1));
  report.invalid = std::move(invalid);
  return report;
}

}  // namespace mixmesh::deform::detail
