// Point insertion of the sliver pass: a new point where no flip, split, collapse or move
// mends a sliver, its cavity refilled by the cone from it.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "mixmesh/mesh/cell_geometry.hpp"
#include "sliver_removal_pass.hpp"

namespace mixmesh::optimize_detail {

// Point insertion: a sliver whose four points lie on faces the pass cannot cross (two
// hull triangles of a shallow concave fold, a cap's side and its neighbour's) has no
// flip out; a new point above it does. Trial points: the sliver's circumcentre and
// points over each of its crossable faces, each with its star-shaped Bowyer-Watson
// cavity (grown until star-shaped from the point) coned from it. A sliver much longer
// than it is short (three nearly collinear hull nodes of one station, 4 cm apart, and
// a point of the next, 2 m away) also gets points at its own short scale over the
// middles of each face and of its edges, on both sides: a point a tenth of its longest
// edge up lands five cells away and leaves the flat tetrahedra on either side of the
// three nodes' triangle.
void SliverRemoval::insert_a_point(int t) {
  const Tetrahedron nodes = complex_.nodes(t);
  const Vector3 &a = point(nodes[0]), &b = point(nodes[1]), &c = point(nodes[2]), &d = point(nodes[3]);
  const std::array<double, 6> lengths = {(b - a).squaredNorm(), (c - a).squaredNorm(), (d - a).squaredNorm(),
                                         (c - b).squaredNorm(), (d - b).squaredNorm(), (d - c).squaredNorm()};
  const double longest = std::sqrt(*std::max_element(lengths.begin(), lengths.end()));
  const double shortest = std::sqrt(*std::min_element(lengths.begin(), lengths.end()));
  const Vector3 centroid = 0.25 * a + 0.25 * b + 0.25 * c + 0.25 * d;
  trials_.clear();
  if (const auto centre = tetrahedron_circumcentre(a, b, c, d);
      centre && (*centre - centroid).norm() < longest)
    trials_.push_back(*centre);
  for (int vertex = 0; vertex < 4; ++vertex) {
    if (complex_.neighbour_opposite(t, vertex) < 0) continue;
    const std::array<Index, 3> face = face_opposite(nodes, vertex);
    const Vector3 middle = (point(face[0]) + point(face[1]) + point(face[2])) / 3.0;
    Vector3 normal = (point(face[1]) - point(face[0])).cross(point(face[2]) - point(face[0]));
    if (!(normal.norm() > 0.0)) continue;
    normal.normalize();
    if (normal.dot(point(nodes[static_cast<std::size_t>(vertex)]) - middle) > 0.0) normal = -normal;
    for (double height : {0.1, 0.25, 0.5}) trials_.push_back(middle + height * longest * normal);
    // The short scale's heights, on both sides of the face (which side is the sliver's
    // is not clear when it is flat): half the shortest edge, doubled up to the lowest
    // of the long scale's.
    if (2.0 * shortest < 0.1 * longest)
      for (const Vector3& base : std::array<Vector3, 4>{middle, 0.5 * (point(face[0]) + point(face[1])),
                                                        0.5 * (point(face[1]) + point(face[2])),
                                                        0.5 * (point(face[2]) + point(face[0]))})
        for (double height = 0.5 * shortest; height < 0.1 * longest; height *= 2.0) {
          trials_.push_back(base + height * normal);
          trials_.push_back(base - height * normal);
        }
  }
  // Each trial point is located once: the smallest cavities start where it lies too.
  starts_.clear();
  for (const Vector3& trial : trials_) starts_.push_back(complex_.locate(t, trial));
  for (const Cavity cavity : {Cavity::circumsphere, Cavity::smallest}) {
    if (best_) break;
    for (std::size_t trial = 0; trial < trials_.size(); ++trial)
      if (starts_[trial] >= 0) try_insertion(t, trials_[trial], starts_[trial], cavity);
  }
}

// The cavity of x (in tetrahedron `start`): the tetrahedra whose circumsphere holds it
// (Bowyer-Watson), or, where no trial point's gave a change, the smallest one: the
// sliver and the tetrahedron holding x. Either is grown until it is star-shaped from x. Over a nearly
// flat hull the circumspheres of the flat tetrahedra round a sliver are huge and hold
// x, so the first runs to its limit over them and is seldom star-shaped (seed 58 wing
// 18: every trial's cavity round the sliver left at 178.8 degrees was at the limit);
// the smallest cones x over the sliver and a few neighbours. It comes second because
// a larger cavity, where one works, leaves room for the slivers next to it.
void SliverRemoval::try_insertion(int t, const Vector3& x, int start, Cavity kind) {
  if (kind == Cavity::smallest)
    cavity_.assign(1, start);
  else
    complex_.circumsphere_cavity(x, start, 64, cavity_);
  // A flat sliver's circumsphere is nearly a plane and may leave x out: a sliver whose
  // four points lie in one plane (the sides of a row of caps over a sheet's cells,
  // where TetGen joins two triangulations of that plane by flat tetrahedra) got no
  // cavity at all. It is taken in anyway; the star-shape growth and the volume check
  // below still judge the cavity.
  if (std::find(cavity_.begin(), cavity_.end(), t) == cavity_.end()) cavity_.push_back(t);
  if (complex_.make_star_shaped(x, 96, cavity_)) cone_cavity(x);
}

// The change that replaces the tetrahedra of cavity_ (star-shaped from x) by the cone
// from x over its boundary.
void SliverRemoval::cone_cavity(const Vector3& x) {
  Change change;
  change.operation = Operation::point_insertion;
  change.removed = cavity_;
  double volume_before = 0.0, volume_after = 0.0;
  auto volume = [&](const Tetrahedron& n) {
    return std::abs(tetrahedron_volume6(point(n[0]), point(n[1]), point(n[2]), point(n[3])));
  };
  for (int cell : cavity_) {
    change.before.add(quality(complex_, cell), target());
    volume_before += volume(complex_.nodes(cell));
  }
  // Each boundary face of the cavity gives the tetrahedron of its cell with x in place
  // of the vertex opposite it (the same orientation).
  complex_.points().push_back(x);
  const auto scratch = static_cast<Index>(complex_.points().size() - 1);
  for (int cell : cavity_)
    for (int vertex = 0; vertex < 4; ++vertex) {
      const int other = complex_.neighbour_opposite(cell, vertex);
      if (other >= 0 && std::find(cavity_.begin(), cavity_.end(), other) != cavity_.end()) continue;
      Tetrahedron piece = complex_.nodes(cell);
      piece[static_cast<std::size_t>(vertex)] = scratch;
      change.after.add(quality(complex_, piece), target());
      volume_after += volume(piece);
      piece[static_cast<std::size_t>(vertex)] = -1;
      change.added.push_back(piece);
      change.regions.push_back(complex_.region(cell));
    }
  complex_.points().pop_back();
  // A cavity round a tetrahedron it does not hold would be covered twice.
  if (std::abs(volume_after - volume_before) > 1e-9 * volume_before) return;
  change.new_point = x;
  consider(std::move(change));
}

}  // namespace mixmesh::optimize_detail
