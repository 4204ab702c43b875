#include "mixmesh/optimize/sliver_removal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "tetrahedron_complex.hpp"

namespace mixmesh {

namespace {

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
    for (std::size_t t = 0; t < complex_.size(); ++t)
      if (complex_.alive(static_cast<int>(t))) {
        const double q = quality(complex_, static_cast<int>(t));
        if (q < target) work.push_back({q, static_cast<int>(t)});
      }
    std::sort(work.begin(), work.end());
    std::size_t done = 0;
    for (const auto& [q, t] : work) {
      if (!complex_.alive(t) || quality(complex_, t) >= target) continue;
      if (remove_an_edge(t)) {
        ++report.edge_removals;
      } else if (flip_a_face(t)) {
        ++report.face_flips;
      } else if (split_an_edge(t)) {
        ++report.edge_splits;
      } else if (options_.smooth_points && smooth_a_point(t)) {
        ++report.smoothed_points;
      } else {
        continue;
      }
      ++done;
    }
    return done;
  }

 private:
  // Edge removal (Shewchuk's formulation): the best triangulation of the ring polygon,
  // by the dynamic programme over its sub-polygons, each triangle giving one
  // tetrahedron with either end of the edge.
  bool remove_an_edge(int t) {
    static constexpr std::array<std::array<int, 2>, 6> edges{{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};
    const Tetrahedron nodes = complex_.nodes(t);
    for (const auto& edge : edges) {
      Index a = nodes[static_cast<std::size_t>(edge[0])], b = nodes[static_cast<std::size_t>(edge[1])];
      if (!complex_.ring(t, a, b, apexes_, ring_) || static_cast<int>(apexes_.size()) > options_.maximum_ring)
        continue;
      // Old tetrahedra (a, b, v_i, v_i+1) all have the mesh's orientation; with the ring
      // in that order the new ones are (a, v_i, v_k, v_j) and (b, v_i, v_j, v_k).
      const Tetrahedron first{a, b, apexes_[0], apexes_[1]};
      if (complex_.orientation() * tetrahedron_volume6(point(first[0]), point(first[1]), point(first[2]),
                                                       point(first[3])) <
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
      Tally replaced;
      for (const Tetrahedron& piece : pieces) replaced.add(quality(complex_, piece), target());
      if (!replaced.better_than(old)) continue;
      const int region = complex_.region(t);
      for (int cell : ring_) complex_.remove(cell);
      for (const Tetrahedron& piece : pieces) complex_.add(piece, region);
      return true;
    }
    return false;
  }

  // 2 -> 3: tetrahedra (f, d) and (f, e) sharing face f become three round edge (d, e).
  bool flip_a_face(int t) {
    const Tetrahedron nodes = complex_.nodes(t);
    for (int skip = 0; skip < 4; ++skip) {
      std::array<Index, 3> face{};
      for (int k = 0, n = 0; k < 4; ++k)
        if (k != skip) face[static_cast<std::size_t>(n++)] = nodes[static_cast<std::size_t>(k)];
      const int other = complex_.neighbour(t, face[0], face[1], face[2]);
      if (other < 0) continue;
      const Index d = nodes[static_cast<std::size_t>(skip)];
      Index e = -1;
      for (Index node : complex_.nodes(other))
        if (node != face[0] && node != face[1] && node != face[2]) e = node;
      // The face's ring round (d, e) in the order that gives the mesh's orientation.
      std::array<Index, 3> ring = face;
      if (complex_.orientation() *
              tetrahedron_volume6(point(d), point(e), point(ring[0]), point(ring[1])) <
          0.0)
        std::swap(ring[1], ring[2]);
      Tally old, replaced;
      old.add(quality(complex_, t), target());
      old.add(quality(complex_, other), target());
      for (int k = 0; k < 3; ++k)
        replaced.add(quality(complex_, Tetrahedron{d, e, ring[static_cast<std::size_t>(k)],
                                                   ring[static_cast<std::size_t>((k + 1) % 3)]}),
                     target());
      if (!replaced.better_than(old)) continue;
      const int region = complex_.region(t);
      complex_.remove(t);
      complex_.remove(other);
      for (int k = 0; k < 3; ++k)
        complex_.add({d, e, ring[static_cast<std::size_t>(k)], ring[static_cast<std::size_t>((k + 1) % 3)]}, region);
      return true;
    }
    return false;
  }

  // Edge split: a sliver's four points lie almost in a plane, two of its edges crossing
  // (seen across the plane); a new point where one of them passes the other cuts every
  // tetrahedron round that edge in two. Where the other edge belongs to a pyramid (the
  // interface's split of a flat outer cell: the cell's centre just under the hull,
  // right below the middle of the outer quad's diagonal) this is the only way out.
  bool split_an_edge(int t) {
    static constexpr std::array<std::array<int, 4>, 6> edges{
        {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}}};
    const Tetrahedron nodes = complex_.nodes(t);
    for (const auto& edge : edges) {
      const Index a = nodes[static_cast<std::size_t>(edge[0])], c = nodes[static_cast<std::size_t>(edge[1])];
      if (!complex_.ring(t, a, c, apexes_, ring_)) continue;
      // The point of segment a-c closest to the line of the opposite edge.
      const Vector3 u = point(c) - point(a);
      const Vector3 v = point(nodes[static_cast<std::size_t>(edge[3])]) - point(nodes[static_cast<std::size_t>(edge[2])]);
      const Vector3 w = point(a) - point(nodes[static_cast<std::size_t>(edge[2])]);
      const double uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), uw = u.dot(w), vw = v.dot(w);
      const double denominator = uu * vv - uv * uv;
      if (!(denominator > 1e-12 * uu * vv)) continue;
      const double s = std::clamp((uv * vw - vv * uw) / denominator, 0.2, 0.8);
      const Vector3 middle = point(a) + s * u;
      Tally old;
      for (int cell : ring_) old.add(quality(complex_, cell), target());
      // Each tetrahedron round the edge gives two: the new point in place of c, and in
      // place of a (the same orientation).
      std::vector<Tetrahedron> pieces;
      for (int cell : ring_)
        for (Index replaced : {c, a}) {
          Tetrahedron piece = complex_.nodes(cell);
          for (Index& node : piece)
            if (node == replaced) node = -1;
          pieces.push_back(piece);
        }
      complex_.points().push_back(middle);
      const auto scratch = static_cast<Index>(complex_.points().size() - 1);
      Tally replaced;
      for (Tetrahedron piece : pieces) {
        for (Index& node : piece)
          if (node < 0) node = scratch;
        replaced.add(quality(complex_, piece), target());
      }
      complex_.points().pop_back();
      if (!replaced.better_than(old)) continue;
      const Index added = complex_.add_point(middle);
      std::vector<int> regions;
      for (int cell : ring_) regions.push_back(complex_.region(cell));
      for (int cell : ring_) complex_.remove(cell);
      for (std::size_t k = 0; k < pieces.size(); ++k) {
        Tetrahedron piece = pieces[k];
        for (Index& node : piece)
          if (node < 0) node = added;
        complex_.add(piece, regions[k / 2]);
      }
      return true;
    }
    return false;
  }

  // Moves a free point of t to the best of a few trial positions: towards the mean of
  // its neighbours, and along the normal of the opposite face (a sliver's fourth point
  // lies almost in the plane of the other three).
  bool smooth_a_point(int t) {
    const Tetrahedron nodes = complex_.nodes(t);
    for (int k = 0; k < 4; ++k) {
      const Index p = nodes[static_cast<std::size_t>(k)];
      if (!complex_.free_point(p)) continue;
      const std::vector<int> cells = complex_.around(p);
      auto worst = [&]() {
        double value = std::numeric_limits<double>::infinity();
        for (int cell : cells) value = std::min(value, quality(complex_, cell));
        return value;
      };
      Vector3& x = complex_.points()[static_cast<std::size_t>(p)];
      const Vector3 start = x;
      const double old_worst = worst();
      Vector3 mean = Vector3::Zero();
      double length = 0.0;
      int count = 0;
      for (int cell : cells)
        for (Index node : complex_.nodes(cell))
          if (node != p) {
            mean += point(node);
            length += (point(node) - start).norm();
            ++count;
          }
      mean /= count;
      length /= count;
      const Vector3& u = point(nodes[static_cast<std::size_t>((k + 1) % 4)]);
      const Vector3& v = point(nodes[static_cast<std::size_t>((k + 2) % 4)]);
      const Vector3& w = point(nodes[static_cast<std::size_t>((k + 3) % 4)]);
      Vector3 normal = (v - u).cross(w - u);
      normal = normal.norm() > 0.0 ? Vector3(normal.normalized()) : Vector3::Zero();
      if (normal.dot(start - u) < 0.0) normal = -normal;
      std::vector<Vector3> trials;
      for (double f : {1.0, 0.5, 0.25}) trials.push_back(start + f * (mean - start));
      for (double f : {0.05, 0.1, 0.2, 0.4}) trials.push_back(start + f * length * normal);
      Vector3 best = start;
      double best_worst = old_worst;
      for (const Vector3& trial : trials) {
        x = trial;
        const double value = worst();
        if (value > best_worst + 1e-6) {
          best_worst = value;
          best = trial;
        }
      }
      x = best;
      if (best != start) return true;
    }
    return false;
  }

  const Vector3& point(Index p) { return complex_.points()[static_cast<std::size_t>(p)]; }
  double target() const { return 180.0 - options_.target_dihedral_degrees; }

  TetrahedronComplex complex_;
  SliverOptions options_;
  std::vector<Index> apexes_;
  std::vector<int> ring_;
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
  return report;
}

}  // namespace mixmesh
