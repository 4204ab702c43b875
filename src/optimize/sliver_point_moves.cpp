// Point moves of the sliver pass: a point that only tetrahedra use (or a point of a flat
// boundary, or a split point or cap apex) goes where its tetrahedra are better.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "mixmesh/mesh/cell_geometry.hpp"
#include "sliver_removal_pass.hpp"

namespace mixmesh::optimize_detail {

namespace {

// Steps from `here` along the six axes, halving from a twentieth of `length` to a
// five-hundredth; `improves(trial)` judges each and returns the position it keeps, if
// it keeps one, and the steps go on from there.
template <typename Improves>
void axis_steps(Vector3 here, double length, const Improves& improves) {
  const Vector3 axes[6] = {Vector3::UnitX(),  -Vector3::UnitX(), Vector3::UnitY(),
                           -Vector3::UnitY(), Vector3::UnitZ(),  -Vector3::UnitZ()};
  for (double step = 0.05 * length; step > 2e-3 * length; step *= 0.5)
    for (const Vector3& axis : axes)
      if (const std::optional<Vector3> kept = improves(here + step * axis)) here = *kept;
}

}  // namespace

// The scaled corner Jacobian of a pyramid of the mesh, or -1 where it is invalid or
// fails checkMesh's face-pyramid test.
double SliverRemoval::pyramid_quality(std::size_t pyramid) const {
  const Index* corners = complex_.mesh().cell(CellType::pyramid, pyramid);
  const CellShape shape = cell_shape(CellType::pyramid, complex_.points(), corners);
  if (!shape.valid() || inverted_face_pyramids(CellType::pyramid, complex_.points(), corners) > 0)
    return -1.0;
  return shape.min_corner_jacobian;
}

// The points next to p (through its tetrahedra and, for an apex, the base corners of
// its pyramids): their mean and their mean distance from p, the scale of its moves.
SliverRemoval::Neighbourhood SliverRemoval::neighbourhood(Index p, const std::vector<std::size_t>* pyramids) {
  const Vector3 start = point(p);
  Neighbourhood result{Vector3::Zero(), 0.0};
  int count = 0;
  auto add_neighbour = [&](Index node) {
    result.mean += point(node);
    result.length += (point(node) - start).norm();
    ++count;
  };
  for (int cell : complex_.around(p))
    for (Index node : complex_.nodes(cell))
      if (node != p) add_neighbour(node);
  if (pyramids)
    for (std::size_t pyramid : *pyramids) {
      const Index* corners = complex_.mesh().cell(CellType::pyramid, pyramid);
      std::for_each(corners, corners + 4, add_neighbour);
    }
  result.mean /= count;
  result.length /= count;
  return result;
}

// Point move: a free point of t to the best of a few trial positions, towards the
// mean of its neighbours and along the normal of the opposite face (a sliver's fourth
// point lies almost in the plane of the other three). A point on a flat boundary (the
// symmetry plane) moves within its plane, so its boundary triangles stay in it. A
// `searched` move (search_point) is the fallback for a sliver nothing else mends; with
// `apexes` it also moves the points of t that are apexes of pyramids, which are kept
// valid and no flatter than options_.apex_pyramid_quality.
void SliverRemoval::move_a_point(int t, bool searched, bool apexes) {
  const Tetrahedron nodes = complex_.nodes(t);
  for (int k = 0; k < 4; ++k) {
    const Index p = nodes[static_cast<std::size_t>(k)];
    const Vector3& plane = complex_.plane_normal(p);
    const std::vector<std::size_t>* pyramids = searched && apexes ? complex_.apex_pyramids(p) : nullptr;
    if (!complex_.free_point(p) && plane.isZero() && !pyramids) continue;
    const std::vector<int>& cells = complex_.around(p);
    Vector3& x = complex_.points()[static_cast<std::size_t>(p)];
    const Vector3 start = x;
    // An apex's pyramids bound where it may go: each no flatter than the bound, or
    // than itself where it starts flatter. An apex with a pyramid that already fails
    // (checkMesh's face pyramids can, in a cell that passes the corner test) stays:
    // no floor would hold that pyramid.
    std::vector<double> pyramid_floors;
    if (pyramids)
      for (std::size_t pyramid : *pyramids)
        pyramid_floors.push_back(std::min(options_.apex_pyramid_quality, pyramid_quality(pyramid)));
    if (std::any_of(pyramid_floors.begin(), pyramid_floors.end(), [](double floor) { return floor < 0.0; }))
      continue;
    auto tally = [&]() {
      Tally result;
      for (int cell : cells) result.add(quality(complex_, cell), target());
      if (pyramids)
        for (std::size_t number = 0; number < pyramids->size(); ++number)
          if (!(pyramid_quality((*pyramids)[number]) >= pyramid_floors[number]))
            result.add(invalid_quality, target());
      return result;
    };
    const auto [mean, length] = neighbourhood(p, pyramids);
    Change change;
    change.operation = Operation::point_move;
    change.before = change.after = tally();
    change.moved_point = p;
    if (searched) {
      search_point(t, p, plane, x, start, change, tally, length);
      // A point has tens of tetrahedra round it (a cap's apex a hundred): one that
      // the move mends must not cost the others more than it gains, or slivers spread.
      if (change.after.shortfall > change.before.shortfall) change.after = change.before;
    } else {
      try_ordinary_moves(nodes, k, plane, x, start, mean, length, change, tally);
    }
    x = start;
    consider(std::move(change));  // taken only where a trial beat the start
  }
}

// The ordinary trials of point k of `nodes`: towards the mean of its neighbours, off
// the opposite face by parts of its edges' mean `length`, and at its own scale.
template <typename Tallies>
void SliverRemoval::try_ordinary_moves(const Tetrahedron& nodes, int k, const Vector3& plane, Vector3& x,
                                       const Vector3& start, const Vector3& mean, double length,
                                       Change& change, const Tallies& tally) {
  const Vector3& u = point(nodes[static_cast<std::size_t>((k + 1) % 4)]);
  const Vector3& v = point(nodes[static_cast<std::size_t>((k + 2) % 4)]);
  const Vector3& w = point(nodes[static_cast<std::size_t>((k + 3) % 4)]);
  Vector3 normal = (v - u).cross(w - u);
  normal -= plane.dot(normal) * plane;
  normal = normal.norm() > 1e-12 * (v - u).squaredNorm() ? Vector3(normal.normalized()) : Vector3::Zero();
  if (normal.dot(start - u) < 0.0) normal = -normal;
  const Vector3 towards_mean = mean - start - plane.dot(mean - start) * plane;
  std::vector<Vector3> trials;
  for (double f : {1.0, 0.5, 0.25}) trials.push_back(start + f * towards_mean);
  if (!normal.isZero())
    for (double f : {0.05, 0.1, 0.2, 0.4}) trials.push_back(start + f * length * normal);
  auto try_each = [&]() {
    for (const Vector3& trial : trials) {
      x = trial;
      const Tally here = tally();
      if (here.better_than(change.after)) {
        change.after = here;
        change.moved_to = trial;
      }
    }
  };
  try_each();
  // Where no such step helps, steps of a few times the point's height over the
  // opposite face: a sliver far smaller than the edges round its point (one inserted
  // in the concave corner between a wake's first cap and the wing's hull lies a
  // millimetre off the cap's face, under edges tens of millimetres long, with the
  // hull half a millimetre away) needs a step at its own scale. Only as a fallback:
  // taken first, such short steps trim slivers that a later insertion would mend.
  if (!normal.isZero() && !change.after.better_than(change.before)) {
    const double height = normal.dot(start - u);
    trials.clear();
    for (double multiple : {1.0, 2.0, 4.0, 8.0})
      if (multiple * height < 0.05 * length) trials.push_back(start + multiple * height * normal);
    try_each();
  }
}

// Where the ordinary trials fail, the valid positions round a point are often a thin
// slab: round an apex, a pyramid on a twisted base leaves one a few tenths of a
// millimetre thick (the split point of a cell at a tip's trailing edge, 4 mm wide at
// one end and 35 mm at the other), and round a far-field point in a cluster of slivers
// over needle hull faces its neighbours do. Fixed steps along a few directions seldom
// lie in it. So the point goes part of the way towards each other point of the sliver
// `t` and its centroid (the first part that helps on each line), then from the best
// position so far by steps along the axes, halving from a twentieth of its edges' mean
// `length`. Where neither helps, the slab lies along none of those lines: the point
// tries 64 directions spread evenly over the sphere at radii halving from 0.4 of
// `length`, and the axis steps go on from the best of those. A point on a flat boundary
// stays in its plane. `x` is the point's coordinates, which `tally` reads.
template <typename Tallies>
void SliverRemoval::search_point(int t, Index p, const Vector3& plane, Vector3& x, const Vector3& start,
                                 Change& change, const Tallies& tally, double length) {
  auto improves = [&](Vector3 trial) -> std::optional<Vector3> {
    trial -= plane.dot(trial - start) * plane;
    x = trial;
    const Tally result = tally();
    if (!result.better_than(change.after)) return std::nullopt;
    change.after = result;
    change.moved_to = trial;
    return trial;
  };
  auto moved = [&]() { return change.after.better_than(change.before); };
  std::vector<Vector3> targets;
  Vector3 centroid = Vector3::Zero();
  for (Index node : complex_.nodes(t)) {
    centroid += 0.25 * point(node);
    if (node != p) targets.push_back(point(node));
  }
  targets.push_back(centroid);
  for (const Vector3& target : targets)
    for (double part : {0.75, 0.5, 0.25, 0.125, 0.0625})
      if (improves(start + part * (target - start))) break;
  axis_steps(moved() ? change.moved_to : start, length, improves);
  if (moved()) return;
  for (const Vector3& direction : sphere_directions())
    for (double part = 0.4; part > 0.01; part *= 0.5) improves(start + part * length * direction);
  if (moved()) axis_steps(change.moved_to, length, improves);
}

// Unit vectors spread evenly over the sphere (a Fibonacci lattice: equal bands in z,
// the golden angle between consecutive longitudes).
const std::vector<Vector3>& SliverRemoval::sphere_directions() {
  static const std::vector<Vector3> directions = [] {
    constexpr int count = 64;
    const double golden_angle = M_PI * (3.0 - std::sqrt(5.0));
    std::vector<Vector3> result;
    for (int i = 0; i < count; ++i) {
      const double z = 1.0 - (2.0 * i + 1.0) / count, radius = std::sqrt(1.0 - z * z);
      result.push_back(Vector3(radius * std::cos(golden_angle * i), radius * std::sin(golden_angle * i), z));
    }
    return result;
  }();
  return directions;
}

std::size_t SliverRemoval::lift_pyramids() {
  std::size_t lifted = 0;
  for (std::size_t p = 0; p < complex_.points().size(); ++p) {
    const std::vector<std::size_t>* pyramids = complex_.apex_pyramids(static_cast<Index>(p));
    if (pyramids && lift_pyramid(static_cast<Index>(p), *pyramids)) ++lifted;
  }
  return lifted;
}

// A cap lowered to clear the hull, or the split point of a cell whose base is warped
// (where a flat tip meets the trailing edge), can leave a pyramid under the bound that
// no sliver calls for, since the tetrahedra round the apex are fine. The apex goes to
// the nearest position found where its flattest pyramid reaches the bound, or else
// comes closest: 64 directions spread over the sphere at radii doubling from 0.0125 to
// 0.4 of its edges' mean length, then axis steps from the best of those. Above the
// bound the pyramid counts as at it, so the apex moves no further than it must. Every
// tetrahedron round it must stay at or above the target, or at or above itself where
// it starts below, so the pass's work is kept and no new sliver appears.
bool SliverRemoval::lift_pyramid(Index p, const std::vector<std::size_t>& pyramids) {
  auto flattest = [&]() {
    double worst = std::numeric_limits<double>::infinity();
    for (std::size_t pyramid : pyramids) worst = std::min(worst, pyramid_quality(pyramid));
    return worst;
  };
  if (!(flattest() < options_.apex_pyramid_quality)) return false;
  const std::vector<int>& cells = complex_.around(p);
  std::vector<double> floors;
  for (int cell : cells) floors.push_back(std::min(quality(complex_, cell), target()));
  // Tally: the worst is the flattest pyramid, the shortfall the tetrahedra's.
  auto tally = [&]() {
    Tally result;
    result.worst = std::min(flattest(), options_.apex_pyramid_quality);
    for (std::size_t k = 0; k < cells.size(); ++k) {
      const double q = quality(complex_, cells[k]);
      if (!(q >= floors[k])) {
        result.worst = invalid_quality;
        return result;
      }
      result.shortfall += std::max(0.0, target() - q);
    }
    return result;
  };
  Vector3& x = complex_.points()[static_cast<std::size_t>(p)];
  const Vector3 start = x;
  const double length = neighbourhood(p, &pyramids).length;
  const Tally before = tally();
  Tally best = before;
  Vector3 best_position = start;
  auto improves = [&](const Vector3& trial) -> std::optional<Vector3> {
    x = trial;
    const Tally result = tally();
    if (!result.better_than(best)) return std::nullopt;
    best = result;
    best_position = trial;
    return trial;
  };
  for (double part = 0.0125; part < 0.5; part *= 2.0)
    for (const Vector3& direction : sphere_directions()) improves(start + part * length * direction);
  axis_steps(best_position, length, improves);
  x = best_position;  // the start unless a trial beat it
  return x != start;
}

}  // namespace mixmesh::optimize_detail
