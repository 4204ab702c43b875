// The sliver pass's working state (remove_slivers, include/mixmesh/optimize/
// sliver_removal.hpp): the quality measure, the local changes it weighs and the pass
// itself. Its operations live in sliver_flips.cpp (edge removal, face flip, edge split,
// point collapse), sliver_point_moves.cpp (ordinary and searched point moves) and
// sliver_insertion.cpp (point insertion).
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "mixmesh/optimize/sliver_removal.hpp"
#include "tetrahedron_complex.hpp"

namespace mixmesh::optimize_detail {

constexpr double invalid_quality = -std::numeric_limits<double>::infinity();

// 180 degrees less the largest dihedral angle (higher is better), or -infinity for a
// tetrahedron that is inverted or flatter than rounding can tell from inverted.
double quality(const TetrahedronComplex& complex, const Tetrahedron& t);
inline double quality(const TetrahedronComplex& complex, int t) {
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
    shortfall += q == invalid_quality ? std::numeric_limits<double>::infinity() : std::max(0.0, target - q);
  }
  bool better_than(const Tally& old) const {
    if (worst == invalid_quality) return false;
    return worst > old.worst + 1e-6 || (worst >= old.worst - 1e-9 && shortfall < old.shortfall - 1e-6);
  }
};

class SliverRemoval {
 public:
  SliverRemoval(MixedMesh& mesh, const SliverOptions& options) : complex_(mesh), options_(options) {}

  TetrahedronComplex& complex() { return complex_; }

  // One pass over the tetrahedra above the target; returns the operations done.
  std::size_t pass(SliverReport& report);
  // Moves every apex whose flattest pyramid is under options_.apex_pyramid_quality to
  // raise that pyramid, no tetrahedron round it falling below the target or below
  // itself; returns the apexes moved (sliver_point_moves.cpp).
  std::size_t lift_pyramids();

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

  // The pass (sliver_removal.cpp).
  void consider(Change&& change);
  std::vector<int> candidates() const;
  void apply(const Change& change, SliverReport& report);

  // Flips, splits and collapses (sliver_flips.cpp).
  void remove_an_edge(int t);
  void remove_an_edge_by_fans(int t, Index a, Index b, const Tally& old);
  void flip_a_face(int t);
  void split_an_edge(int t);
  void collapse_a_point(int t);
  bool link_condition(Index v, Index w, const std::vector<Index>& around_v);

  // Point moves (sliver_point_moves.cpp).
  double pyramid_quality(std::size_t pyramid) const;
  struct Neighbourhood {
    Vector3 mean;
    double length;
  };
  Neighbourhood neighbourhood(Index p, const std::vector<std::size_t>* pyramids);
  void move_a_point(int t, bool searched, bool apexes = false);
  template <typename Tallies>
  void try_ordinary_moves(const Tetrahedron& nodes, int k, const Vector3& plane, Vector3& x,
                          const Vector3& start, const Vector3& mean, double length, Change& change,
                          const Tallies& tally);
  template <typename Tallies>
  void search_point(int t, Index p, const Vector3& plane, Vector3& x, const Vector3& start, Change& change,
                    const Tallies& tally, double length);
  static const std::vector<Vector3>& sphere_directions();
  bool lift_pyramid(Index p, const std::vector<std::size_t>& pyramids);

  // Point insertion (sliver_insertion.cpp).
  enum class Cavity { circumsphere, smallest };
  void insert_a_point(int t);
  void try_insertion(int t, const Vector3& x, int start, Cavity kind);
  void cone_cavity(const Vector3& x);
  bool insertion_failed(int t) {
    if (insertion_failed_.size() < complex_.size()) insertion_failed_.resize(complex_.size(), 0);
    return insertion_failed_[static_cast<std::size_t>(t)] != 0;
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
};

}  // namespace mixmesh::optimize_detail
