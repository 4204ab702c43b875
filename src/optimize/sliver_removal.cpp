#include "mixmesh/optimize/sliver_removal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "tetrahedron_complex.hpp"

namespace mixmesh {

namespace {

using optimize_detail::face_opposite;
using optimize_detail::Tetrahedron;
using optimize_detail::TetrahedronComplex;

constexpr double invalid = -std::numeric_limits<double>::infinity();

// 180 degrees less the largest dihedral angle (higher is better), or -infinity for a
// tetrahedron that is inverted or flatter than rounding can tell from inverted.
double quality(const TetrahedronComplex& complex, const Tetrahedron& t) {
  const auto& p = complex.points();
  const Vector3& a = p[static_cast<std::size_t>(t[0])];
  const Vector3& b = p[static_cast<std::size_t>(t[1])];
  const Vector3& c = p[static_cast<std::size_t>(t[2])];
  const Vector3& d = p[static_cast<std::size_t>(t[3])];
  const double volume = complex.orientation() * tetrahedron_volume6(a, b, c, d);
  const double longest = std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (d - a).squaredNorm(),
                                   (c - b).squaredNorm(), (d - b).squaredNorm(), (d - c).squaredNorm()});
  if (!(volume > 1e-12 * longest * std::sqrt(longest))) return invalid;
  return 180.0 - largest_dihedral_degrees(a, b, c, d);
}

double quality(const TetrahedronComplex& complex, int t) {
  return quality(complex, complex.nodes(t));
}

// The worst quality of a set of tetrahedra and their shortfall: how far they fall below
// the target in total. A change is taken when it raises the worst, or keeps it and
// lowers the shortfall (a sliver next to a worse one that the change cannot mend).
struct Tally {
  double worst = std::numeric_limits<double>::infinity();
  double shortfall = 0.0;

  void add(double q, double target) {
    worst = std::min(worst, q);
    shortfall += q == invalid ? std::numeric_limits<double>::infinity() : std::max(0.0, target - q);
  }
  bool better_than(const Tally& old) const {
    if (worst == invalid) return false;
    return worst > old.worst + 1e-6 || (worst >= old.worst - 1e-9 && shortfall < old.shortfall - 1e-6);
  }
};

class SliverRemoval {
 public:
  SliverRemoval(MixedMesh& mesh, const SliverOptions& options) : complex_(mesh), options_(options) {}

  TetrahedronComplex& complex() { return complex_; }

  // One pass over the tetrahedra above the target; returns the operations done.
  std::size_t pass(SliverReport& report) {
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

 private:
  enum class Operation { edge_removal, face_flip, edge_split, point_collapse, point_move, point_insertion };

  // A local change: tetrahedra that go, tetrahedra that replace them (node -1: the
  // new point of a split), or a point that moves, and the quality of both sets.
  struct Change {
    Operation operation = Operation::edge_removal;
    std::vector<int> removed;
    std::vector<Tetrahedron> added;
    std::vector<int> regions;
    std::optional<Vector3> new_point;
    Index moved_point = -1;
    Vector3 moved_to = Vector3::Zero();
    Tally before, after;

    // Ranked by the worst tetrahedron it leaves, then by how much it lowers the shortfall.
    bool preferred_to(const Change& other) const {
      if (after.worst > other.after.worst + 1e-6) return true;
      if (after.worst < other.after.worst - 1e-6) return false;
      return before.shortfall - after.shortfall > other.before.shortfall - other.after.shortfall + 1e-6;
    }
  };

  void consider(Change&& change) {
    if (!change.after.better_than(change.before)) return;
    if (!best_ || change.preferred_to(*best_)) best_ = std::move(change);
  }

  // The living tetrahedra that may lie above the target: all of them in the first pass;
  // after it only those whose shape may have changed (added since the last scan, or
  // round a moved point) and those left above the target by the last pass, since a
  // tetrahedron's quality depends on its own points alone. The same set as a full scan.
  std::vector<int> candidates() const {
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

  void apply(const Change& change, SliverReport& report) {
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

  // Edge removal (Shewchuk's formulation): the best triangulation of the ring polygon,
  // by the dynamic programme over its sub-polygons, each triangle giving one
  // tetrahedron with either end of the edge.
  void remove_an_edge(int t) {
    static constexpr std::array<std::array<int, 2>, 6> edges{
        {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};
    const Tetrahedron nodes = complex_.nodes(t);
    for (const auto& edge : edges) {
      Index a = nodes[static_cast<std::size_t>(edge[0])], b = nodes[static_cast<std::size_t>(edge[1])];
      if (!complex_.ring(t, a, b, apexes_, ring_) || static_cast<int>(apexes_.size()) > options_.maximum_ring)
        continue;
      // Old tetrahedra (a, b, v_i, v_i+1) all have the mesh's orientation; with the ring
      // in that order the new ones are (a, v_i, v_k, v_j) and (b, v_i, v_j, v_k).
      const Tetrahedron first{a, b, apexes_[0], apexes_[1]};
      if (complex_.orientation() *
              tetrahedron_volume6(point(first[0]), point(first[1]), point(first[2]), point(first[3])) <
          0.0)
        std::swap(a, b);
      Tally old;
      for (int cell : ring_) old.add(quality(complex_, cell), target());
      const int m = static_cast<int>(apexes_.size());
      std::vector<double> best(static_cast<std::size_t>(m * m), std::numeric_limits<double>::infinity());
      std::vector<int> split(static_cast<std::size_t>(m * m), -1);
      auto at = [&](int i, int j) -> double& { return best[static_cast<std::size_t>(i * m + j)]; };
      for (int length = 2; length < m; ++length)
        for (int i = 0; i + length < m; ++i) {
          const int j = i + length;
          at(i, j) = invalid;
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
      if (at(0, m - 1) == invalid) continue;
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

  // 2 -> 3: tetrahedra (f, d) and (f, e) sharing face f become three round edge (d, e).
  void flip_a_face(int t) {
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
  void split_an_edge(int t) {
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
  void collapse_a_point(int t) {
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
          if (change.after.worst == invalid) break;
          change.added.push_back(piece);
          change.regions.push_back(complex_.region(cell));
        }
        if (!change.after.better_than(change.before) || !link_condition(v, w, neighbours)) continue;
        consider(std::move(change));
      }
    }
  }

  // The points next to both v and w are exactly the apexes round edge (v, w).
  bool link_condition(Index v, Index w, const std::vector<Index>& around_v) {
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

  // The scaled corner Jacobian of a pyramid of the mesh, or -1 where it is invalid or
  // fails checkMesh's face-pyramid test.
  double pyramid_quality(std::size_t pyramid) const {
    const Index* corners = complex_.mesh().cell(CellType::pyramid, pyramid);
    const CellShape shape = cell_shape(CellType::pyramid, complex_.points(), corners);
    if (!shape.valid() || inverted_face_pyramids(CellType::pyramid, complex_.points(), corners) > 0) return -1.0;
    return shape.min_corner_jacobian;
  }

  // Point move: a free point of t to the best of a few trial positions, towards the
  // mean of its neighbours and along the normal of the opposite face (a sliver's fourth
  // point lies almost in the plane of the other three). A point on a flat boundary (the
  // symmetry plane) moves within its plane, so its boundary triangles stay in it. A
  // `searched` move (search_point) is the fallback for a sliver nothing else mends; with
  // `apexes` it also moves the points of t that are apexes of pyramids, which are kept
  // valid and no flatter than options_.apex_pyramid_quality.
  void move_a_point(int t, bool searched, bool apexes = false) {
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
            if (!(pyramid_quality((*pyramids)[number]) >= pyramid_floors[number])) result.add(invalid, target());
        return result;
      };
      Vector3 mean = Vector3::Zero();
      double length = 0.0;
      int count = 0;
      auto add_neighbour = [&](Index node) {
        mean += point(node);
        length += (point(node) - start).norm();
        ++count;
      };
      for (int cell : cells)
        for (Index node : complex_.nodes(cell))
          if (node != p) add_neighbour(node);
      if (pyramids)
        for (std::size_t pyramid : *pyramids) {
          const Index* corners = complex_.mesh().cell(CellType::pyramid, pyramid);
          std::for_each(corners, corners + 4, add_neighbour);
        }
      mean /= count;
      length /= count;
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
  void try_ordinary_moves(const Tetrahedron& nodes, int k, const Vector3& plane, Vector3& x, const Vector3& start,
                          const Vector3& mean, double length, Change& change, const Tallies& tally) {
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
  void search_point(int t, Index p, const Vector3& plane, Vector3& x, const Vector3& start, Change& change,
                    const Tallies& tally, double length) {
    auto improves = [&](Vector3 trial) {
      trial -= plane.dot(trial - start) * plane;
      x = trial;
      const Tally result = tally();
      if (!result.better_than(change.after)) return false;
      change.after = result;
      change.moved_to = trial;
      return true;
    };
    auto moved = [&]() { return change.after.better_than(change.before); };
    auto axis_steps = [&](Vector3 here) {
      const Vector3 directions[6] = {Vector3::UnitX(),  -Vector3::UnitX(), Vector3::UnitY(),
                                     -Vector3::UnitY(), Vector3::UnitZ(),  -Vector3::UnitZ()};
      for (double step = 0.05 * length; step > 2e-3 * length; step *= 0.5)
        for (const Vector3& direction : directions)
          if (improves(here + step * direction)) here = change.moved_to;
    };
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
    axis_steps(moved() ? change.moved_to : start);
    if (moved()) return;
    for (const Vector3& direction : sphere_directions())
      for (double part = 0.4; part > 0.01; part *= 0.5) improves(start + part * length * direction);
    if (moved()) axis_steps(change.moved_to);
  }

  // Unit vectors spread evenly over the sphere (a Fibonacci lattice: equal bands in z,
  // the golden angle between consecutive longitudes).
  static const std::vector<Vector3>& sphere_directions() {
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
  void insert_a_point(int t) {
    const Tetrahedron nodes = complex_.nodes(t);
    const Vector3 &a = point(nodes[0]), &b = point(nodes[1]), &c = point(nodes[2]), &d = point(nodes[3]);
    const std::array<double, 6> lengths = {(b - a).squaredNorm(), (c - a).squaredNorm(),
                                           (d - a).squaredNorm(), (c - b).squaredNorm(),
                                           (d - b).squaredNorm(), (d - c).squaredNorm()};
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
  enum class Cavity { circumsphere, smallest };
  void try_insertion(int t, const Vector3& x, int start, Cavity kind) {
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
  void cone_cavity(const Vector3& x) {
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

  const Vector3& point(Index p) { return complex_.points()[static_cast<std::size_t>(p)]; }
  double target() const { return 180.0 - options_.target_dihedral_degrees; }

  TetrahedronComplex complex_;
  SliverOptions options_;
  // What the next pass needs to find the tetrahedra above the target (candidates()).
  std::optional<std::size_t> scanned_size_;
  std::vector<int> previous_work_;
  std::vector<Index> moved_points_;
  std::vector<Index> apexes_;
  std::vector<int> ring_;
  std::optional<Change> best_;
  std::vector<Vector3> trials_;
  std::vector<int> starts_;  // the tetrahedron holding each trial point (-1: none)
  std::vector<int> cavity_;
  std::vector<char> insertion_failed_;

  bool insertion_failed(int t) {
    if (insertion_failed_.size() < complex_.size()) insertion_failed_.resize(complex_.size(), 0);
    return insertion_failed_[static_cast<std::size_t>(t)] != 0;
  }
};

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
  SliverRemoval removal(mesh, options);
  measure(removal.complex(), options.target_dihedral_degrees, report.largest_dihedral_before,
          report.above_target_before, report.tetrahedra_before);
  for (int pass = 0; pass < options.passes; ++pass) {
    ++report.passes;
    if (removal.pass(report) == 0) break;
  }
  measure(removal.complex(), options.target_dihedral_degrees, report.largest_dihedral_after,
          report.above_target_after, report.tetrahedra_after);
  removal.complex().write_back();
  // Collapsed points are left without cells.
  if (report.point_collapses > 0) compact_points(mesh);
  return report;
}

}  // namespace mixmesh
