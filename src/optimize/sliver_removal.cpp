#include "mixmesh/optimize/sliver_removal.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "sliver_removal_pass.hpp"

namespace mixmesh {

namespace optimize_detail {

double quality(const TetrahedronComplex& complex, const Tetrahedron& t) {
  const auto& p = complex.points();
  const Vector3& a = p[static_cast<std::size_t>(t[0])];
  const Vector3& b = p[static_cast<std::size_t>(t[1])];
  const Vector3& c = p[static_cast<std::size_t>(t[2])];
  const Vector3& d = p[static_cast<std::size_t>(t[3])];
  const double volume = complex.orientation() * tetrahedron_volume6(a, b, c, d);
  const double longest = std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (d - a).squaredNorm(),
                                   (c - b).squaredNorm(), (d - b).squaredNorm(), (d - c).squaredNorm()});
  if (!(volume > 1e-12 * longest * std::sqrt(longest))) return invalid_quality;
  return 180.0 - largest_dihedral_degrees(a, b, c, d);
}

// One pass over the tetrahedra above the target; returns the operations done.
std::size_t SliverRemoval::pass(SliverReport& report) {
  const double target = 180.0 - options_.target_dihedral_degrees;
  std::vector<std::pair<double, int>> work;
  for (int t : candidates()) {
    const double q = quality(complex_, t);
    if (q < target) work.push_back({q, t});
  }
  std::sort(work.begin(), work.end());
  previous_work_.clear();
  for (const auto& entry : work) previous_work_.push_back(entry.second);
  scanned_size_ = complex_.size();
  moved_points_.clear();
  std::size_t done = 0;
  for (const auto& entry : work) {
    const int t = entry.second;
    if (!complex_.alive(t)) continue;
    const double now = quality(complex_, t);
    if (now >= target) continue;
    // Every removal, flip and split of t is weighed and the best taken: the first
    // that helps is often a poor one (an edge removal that joins a flat outer cell's
    // centre to a far-field point where the split of the cell's diagonal gives right
    // angles).
    best_.reset();
    remove_an_edge(t);
    flip_a_face(t);
    split_an_edge(t);
    collapse_a_point(t);
    if (options_.smooth_points) move_a_point(t, false);
    // A failed insertion is not tried again on a tetrahedron nearer the target: its
    // neighbours seldom change enough to let it in. One flatter than halfway from the
    // target to 180 degrees is tried in every pass: round it the neighbours' slivers
    // are being mended, and a cavity refused in one pass is often clean in the next.
    if (!best_ && options_.insert_points && (!insertion_failed(t) || now < 0.5 * target)) {
      insert_a_point(t);
      if (!best_) insertion_failed_[static_cast<std::size_t>(t)] = 1;
    }
    // The searched move, up to fifty trials a point, comes last: taken before the insertion it
    // trims slivers a new point would mend (176.9 degrees instead of 173.8 on the
    // patch of *A point in a corner under long edges*, docs/generate.md). Moving an
    // apex costs its pyramids shape, so apexes join it only for a tetrahedron above
    // options_.apex_dihedral_degrees (below that, on the ONERA M6, the pyramids fell
    // from 0.0139 to 0.0035 while the largest dihedral angle stayed).
    if (!best_ && options_.search_points) move_a_point(t, true, now < 180.0 - options_.apex_dihedral_degrees);
    if (!best_) continue;
    apply(*best_, report);
    ++done;
  }
  return done;
}

void SliverRemoval::consider(Change&& change) {
  if (!change.after.better_than(change.before)) return;
  if (!best_ || change.preferred_to(*best_)) best_ = std::move(change);
}

// The living tetrahedra that may lie above the target: all of them in the first pass;
// after it only those whose shape may have changed (added since the last scan, or
// round a moved point) and those left above the target by the last pass, since a
// tetrahedron's quality depends on its own points alone. The same set as a full scan.
std::vector<int> SliverRemoval::candidates() const {
  std::vector<int> result;
  if (!scanned_size_) {
    for (std::size_t t = 0; t < complex_.size(); ++t)
      if (complex_.alive(static_cast<int>(t))) result.push_back(static_cast<int>(t));
    return result;
  }
  result = previous_work_;
  for (std::size_t t = *scanned_size_; t < complex_.size(); ++t) result.push_back(static_cast<int>(t));
  for (Index point : moved_points_) {
    const std::vector<int>& around = complex_.around(point);
    result.insert(result.end(), around.begin(), around.end());
  }
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  result.erase(std::remove_if(result.begin(), result.end(), [&](int t) { return !complex_.alive(t); }),
               result.end());
  return result;
}

void SliverRemoval::apply(const Change& change, SliverReport& report) {
  if (change.moved_point >= 0) {
    complex_.points()[static_cast<std::size_t>(change.moved_point)] = change.moved_to;
    moved_points_.push_back(change.moved_point);
  }
  const Index added = change.new_point ? complex_.add_point(*change.new_point) : -1;
  for (int cell : change.removed) complex_.remove(cell);
  for (std::size_t k = 0; k < change.added.size(); ++k) {
    Tetrahedron piece = change.added[k];
    for (Index& node : piece)
      if (node < 0) node = added;
    complex_.add(piece, change.regions[k]);
  }
  switch (change.operation) {
    case Operation::edge_removal:
      ++report.edge_removals;
      break;
    case Operation::face_flip:
      ++report.face_flips;
      break;
    case Operation::edge_split:
      ++report.edge_splits;
      break;
    case Operation::point_collapse:
      ++report.point_collapses;
      break;
    case Operation::point_move:
      ++report.smoothed_points;
      break;
    case Operation::point_insertion:
      ++report.point_insertions;
      break;
  }
}

}  // namespace optimize_detail

namespace {

using optimize_detail::Tetrahedron;
using optimize_detail::TetrahedronComplex;

void measure(const TetrahedronComplex& complex, double target, double& largest, std::size_t& above,
             std::size_t& count) {
  largest = 0.0;
  above = 0;
  count = 0;
  for (std::size_t t = 0; t < complex.size(); ++t) {
    if (!complex.alive(static_cast<int>(t))) continue;
    const Tetrahedron& n = complex.nodes(static_cast<int>(t));
    const auto& p = complex.points();
    const double angle =
        largest_dihedral_degrees(p[static_cast<std::size_t>(n[0])], p[static_cast<std::size_t>(n[1])],
                                 p[static_cast<std::size_t>(n[2])], p[static_cast<std::size_t>(n[3])]);
    largest = std::max(largest, angle);
    above += angle > target ? 1 : 0;
    ++count;
  }
}

}  // namespace

SliverReport remove_slivers(MixedMesh& mesh, const SliverOptions& options) {
  if (!(options.target_dihedral_degrees > 90.0 && options.target_dihedral_degrees < 180.0))
    throw Error("slivers: the target dihedral angle must lie in (90, 180) degrees, got " +
                std::to_string(options.target_dihedral_degrees));
  if (options.maximum_ring < 3) throw Error("slivers: the largest edge ring must be at least 3");
  if (!(options.apex_dihedral_degrees > 90.0 && options.apex_dihedral_degrees < 180.0))
    throw Error("slivers: the apexes' dihedral angle must lie in (90, 180) degrees, got " +
                std::to_string(options.apex_dihedral_degrees));
  if (!(options.apex_pyramid_quality > 0.0 && options.apex_pyramid_quality <= 1.0))
    throw Error("slivers: the apexes' pyramid quality is a scaled Jacobian in (0, 1], got " +
                std::to_string(options.apex_pyramid_quality));
  SliverReport report;
  optimize_detail::SliverRemoval removal(mesh, options);
  measure(removal.complex(), options.target_dihedral_degrees, report.largest_dihedral_before,
          report.above_target_before, report.tetrahedra_before);
  for (int pass = 0; pass < options.passes; ++pass) {
    ++report.passes;
    if (removal.pass(report) == 0) break;
  }
  if (options.lift_pyramids) report.lifted_apexes = removal.lift_pyramids();
  measure(removal.complex(), options.target_dihedral_degrees, report.largest_dihedral_after,
          report.above_target_after, report.tetrahedra_after);
  removal.complex().write_back();
  // Collapsed points are left without cells.
  if (report.point_collapses > 0) compact_points(mesh);
  return report;
}

}  // namespace mixmesh
