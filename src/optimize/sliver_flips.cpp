// Flips, splits and collapses of the sliver pass: operations that change which tetrahedra
// fill a region round a sliver, its points staying where they are (a split adds one).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "mixmesh/mesh/cell_geometry.hpp"
#include "sliver_removal_pass.hpp"

namespace mixmesh::optimize_detail {

// Edge removal (Shewchuk's formulation): the best triangulation of the ring polygon,
// by the dynamic programme over its sub-polygons, each triangle giving one
// tetrahedron with either end of the edge. Rings longer than maximum_ring try the
// fans from each of their points only.
void SliverRemoval::remove_an_edge(int t) {
  static constexpr std::array<std::array<int, 2>, 6> edges{{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};
  const Tetrahedron nodes = complex_.nodes(t);
  for (const auto& edge : edges) {
    Index a = nodes[static_cast<std::size_t>(edge[0])], b = nodes[static_cast<std::size_t>(edge[1])];
    if (!complex_.ring(t, a, b, apexes_, ring_)) continue;
    // Old tetrahedra (a, b, v_i, v_i+1) all have the mesh's orientation; with the ring
    // in that order the new ones are (a, v_i, v_k, v_j) and (b, v_i, v_j, v_k).
    const Tetrahedron first{a, b, apexes_[0], apexes_[1]};
    if (complex_.orientation() *
            tetrahedron_volume6(point(first[0]), point(first[1]), point(first[2]), point(first[3])) <
        0.0)
      std::swap(a, b);
    Tally old;
    for (int cell : ring_) old.add(quality(complex_, cell), target());
    if (static_cast<int>(apexes_.size()) > options_.maximum_ring) {
      remove_an_edge_by_fans(t, a, b, old);
      continue;
    }
    const int m = static_cast<int>(apexes_.size());
    std::vector<double> best(static_cast<std::size_t>(m * m), std::numeric_limits<double>::infinity());
    std::vector<int> split(static_cast<std::size_t>(m * m), -1);
    auto at = [&](int i, int j) -> double& { return best[static_cast<std::size_t>(i * m + j)]; };
    for (int length = 2; length < m; ++length)
      for (int i = 0; i + length < m; ++i) {
        const int j = i + length;
        at(i, j) = invalid_quality;
        for (int k = i + 1; k < j; ++k) {
          const Index vi = apexes_[static_cast<std::size_t>(i)], vk = apexes_[static_cast<std::size_t>(k)],
                      vj = apexes_[static_cast<std::size_t>(j)];
          const double here = std::min({at(i, k), at(k, j), quality(complex_, Tetrahedron{a, vi, vk, vj}),
                                        quality(complex_, Tetrahedron{b, vi, vj, vk})});
          if (here > at(i, j)) {
            at(i, j) = here;
            split[static_cast<std::size_t>(i * m + j)] = k;
          }
        }
      }
    if (at(0, m - 1) == invalid_quality) continue;
    std::vector<Tetrahedron> pieces;
    std::vector<std::pair<int, int>> pending{{0, m - 1}};
    while (!pending.empty()) {
      const auto [i, j] = pending.back();
      pending.pop_back();
      if (j - i < 2) continue;
      const int k = split[static_cast<std::size_t>(i * m + j)];
      const Index vi = apexes_[static_cast<std::size_t>(i)], vk = apexes_[static_cast<std::size_t>(k)],
                  vj = apexes_[static_cast<std::size_t>(j)];
      pieces.push_back({a, vi, vk, vj});
      pieces.push_back({b, vi, vj, vk});
      pending.push_back({i, k});
      pending.push_back({k, j});
    }
    Change change;
    change.operation = Operation::edge_removal;
    change.before = old;
    for (const Tetrahedron& piece : pieces) change.after.add(quality(complex_, piece), target());
    change.removed = ring_;
    change.regions.assign(pieces.size(), complex_.region(t));
    change.added = std::move(pieces);
    consider(std::move(change));
  }
}

// The removal of edge (a, b) (oriented as in remove_an_edge) by the fan of its ring
// polygon from one of its points r: each tetrahedron round the edge without r is cut
// in two at r, those with r go. Where r lies on the edge (three hull points in a line
// at a trailing edge, 2.6 mm apart, random wing 39 of seed 95) the tetrahedra with r
// are flat, no hull point can move, and the ring is often longer than the dynamic
// programme is given.
void SliverRemoval::remove_an_edge_by_fans(int t, Index a, Index b, const Tally& old) {
  const std::size_t m = apexes_.size();
  for (std::size_t r = 0; r < m; ++r) {
    Change change;
    change.operation = Operation::edge_removal;
    change.before = old;
    change.removed = ring_;
    bool valid = true;  // a fan with an inverted piece is not weighed further
    for (std::size_t s = 1; valid && s + 1 < m; ++s) {
      const Index vi = apexes_[r], vk = apexes_[(r + s) % m], vj = apexes_[(r + s + 1) % m];
      for (const Tetrahedron& piece : {Tetrahedron{a, vi, vk, vj}, Tetrahedron{b, vi, vj, vk}}) {
        const double q = quality(complex_, piece);
        valid = valid && q != invalid_quality;
        change.added.push_back(piece);
        change.after.add(q, target());
      }
    }
    if (!valid) continue;
    change.regions.assign(change.added.size(), complex_.region(t));
    consider(std::move(change));
  }
}

// 2 -> 3: tetrahedra (f, d) and (f, e) sharing face f become three round edge (d, e).
void SliverRemoval::flip_a_face(int t) {
  const Tetrahedron nodes = complex_.nodes(t);
  for (int skip = 0; skip < 4; ++skip) {
    const std::array<Index, 3> face = face_opposite(nodes, skip);
    const int other = complex_.neighbour(t, face[0], face[1], face[2]);
    if (other < 0) continue;
    const Index d = nodes[static_cast<std::size_t>(skip)];
    Index e = -1;
    for (Index node : complex_.nodes(other))
      if (node != face[0] && node != face[1] && node != face[2]) e = node;
    // The face's ring round (d, e) in the order that gives the mesh's orientation.
    std::array<Index, 3> ring = face;
    if (complex_.orientation() * tetrahedron_volume6(point(d), point(e), point(ring[0]), point(ring[1])) <
        0.0)
      std::swap(ring[1], ring[2]);
    Change change;
    change.operation = Operation::face_flip;
    change.before.add(quality(complex_, t), target());
    change.before.add(quality(complex_, other), target());
    change.removed = {t, other};
    for (int k = 0; k < 3; ++k) {
      change.added.push_back(
          {d, e, ring[static_cast<std::size_t>(k)], ring[static_cast<std::size_t>((k + 1) % 3)]});
      change.after.add(quality(complex_, change.added.back()), target());
    }
    change.regions.assign(3, complex_.region(t));
    consider(std::move(change));
  }
}

// Edge split: a sliver's four points lie almost in a plane, two of its edges crossing
// (seen across the plane); a new point where one of them passes the other cuts every
// tetrahedron round that edge in two. Where the other edge belongs to a pyramid (the
// interface's split of a flat outer cell: the cell's centre just under the hull,
// right below the middle of the outer quad's diagonal) this is the only way out.
void SliverRemoval::split_an_edge(int t) {
  static constexpr std::array<std::array<int, 4>, 6> edges{
      {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}}};
  const Tetrahedron nodes = complex_.nodes(t);
  for (const auto& edge : edges) {
    const Index a = nodes[static_cast<std::size_t>(edge[0])], c = nodes[static_cast<std::size_t>(edge[1])];
    if (!complex_.ring(t, a, c, apexes_, ring_)) continue;
    // The point of segment a-c closest to the line of the opposite edge.
    const Vector3 u = point(c) - point(a);
    const Vector3 v =
        point(nodes[static_cast<std::size_t>(edge[3])]) - point(nodes[static_cast<std::size_t>(edge[2])]);
    const Vector3 w = point(a) - point(nodes[static_cast<std::size_t>(edge[2])]);
    const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), uw = u.dot(w), vw = v.dot(w);
    const double denominator = uu * vv - uv * uv;
    if (!(denominator > 1e-12 * uu * vv)) continue;
    const double s = std::clamp((uv * vw - vv * uw) / denominator, 0.2, 0.8);
    const Vector3 crossing = point(a) + s * u;
    // The new point only tetrahedra use, so it may leave the edge: where the sliver
    // lies on a shallow fold of faces it cannot cross (a hull valley between two
    // layer cells), a point on the edge stays in the fold; towards the middle of the
    // ring's apexes it lifts out of it.
    Vector3 apex_middle = Vector3::Zero();
    for (Index apex : apexes_) apex_middle += point(apex) / static_cast<double>(apexes_.size());
    Change base;
    base.operation = Operation::edge_split;
    for (int cell : ring_) base.before.add(quality(complex_, cell), target());
    // Each tetrahedron round the edge gives two: the new point in place of c, and in
    // place of a (the same orientation).
    for (int cell : ring_)
      for (Index replaced : {c, a}) {
        Tetrahedron piece = complex_.nodes(cell);
        for (Index& node : piece)
          if (node == replaced) node = -1;
        base.added.push_back(piece);
        base.regions.push_back(complex_.region(cell));
      }
    base.removed = ring_;
    for (const double lift : {0.0, 0.25, 0.5}) {
      const Vector3 position = crossing + lift * (apex_middle - crossing);
      Change change = base;
      complex_.points().push_back(position);
      const auto scratch = static_cast<Index>(complex_.points().size() - 1);
      for (Tetrahedron piece : change.added) {
        for (Index& node : piece)
          if (node < 0) node = scratch;
        change.after.add(quality(complex_, piece), target());
      }
      complex_.points().pop_back();
      change.new_point = position;
      consider(std::move(change));
    }
  }
}

// Point collapse: a free point of t (a far-field point, say a metric point TetGen
// kept just above a hull face) merges into one of its neighbours w. Every tetrahedron
// round the point that has w goes; in the others w takes the point's place. The star
// of the point is a closed ball, so with every new tetrahedron positive the cone from
// w fills it exactly; the points next to both must be those round the edge (the link
// condition), or the cone would pinch the mesh.
void SliverRemoval::collapse_a_point(int t) {
  const Tetrahedron nodes = complex_.nodes(t);
  for (Index v : nodes) {
    if (!complex_.free_point(v)) continue;
    const std::vector<int> star = complex_.around(v);
    std::vector<Index> neighbours;
    for (int cell : star)
      for (Index node : complex_.nodes(cell))
        if (node != v) neighbours.push_back(node);
    std::sort(neighbours.begin(), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
    Tally old;
    for (int cell : star) old.add(quality(complex_, cell), target());
    for (Index w : neighbours) {
      Change change;
      change.operation = Operation::point_collapse;
      change.before = old;
      change.removed = star;
      for (int cell : star) {
        Tetrahedron piece = complex_.nodes(cell);
        if (std::find(piece.begin(), piece.end(), w) != piece.end()) continue;
        std::replace(piece.begin(), piece.end(), v, w);
        change.after.add(quality(complex_, piece), target());
        if (change.after.worst == invalid_quality) break;
        change.added.push_back(piece);
        change.regions.push_back(complex_.region(cell));
      }
      if (!change.after.better_than(change.before) || !link_condition(v, w, neighbours)) continue;
      consider(std::move(change));
    }
  }
}

// The points next to both v and w are exactly the apexes round edge (v, w).
bool SliverRemoval::link_condition(Index v, Index w, const std::vector<Index>& around_v) {
  int edge_cell = -1;
  for (int cell : complex_.around(v)) {
    const Tetrahedron& n = complex_.nodes(cell);
    if (std::find(n.begin(), n.end(), w) != n.end()) edge_cell = cell;
  }
  if (edge_cell < 0 || !complex_.ring(edge_cell, v, w, apexes_, ring_)) return false;
  std::vector<Index> around_w;
  for (int cell : complex_.around(w))
    for (Index node : complex_.nodes(cell))
      if (node != w && node != v) around_w.push_back(node);
  std::sort(around_w.begin(), around_w.end());
  around_w.erase(std::unique(around_w.begin(), around_w.end()), around_w.end());
  std::size_t common = 0;
  for (Index node : around_v)
    if (node != w && std::binary_search(around_w.begin(), around_w.end(), node)) ++common;
  return common == apexes_.size();
}

}  // namespace mixmesh::optimize_detail
