// The tetrahedra of a mixed mesh with the adjacency the flips need: which tetrahedra
// share a face, which use a point, the ring of tetrahedra round an edge. Faces that a
// single tetrahedron uses (boundary faces, faces shared with other cell types) have no
// neighbour and are never crossed.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh::optimize_detail {

using Tetrahedron = std::array<Index, 4>;

// The face of a tetrahedron opposite its vertex `vertex`: the other three, in order.
inline std::array<Index, 3> face_opposite(const Tetrahedron& nodes, int vertex) {
  std::array<Index, 3> face{};
  for (int k = 0, n = 0; k < 4; ++k)
    if (k != vertex) face[static_cast<std::size_t>(n++)] = nodes[static_cast<std::size_t>(k)];
  return face;
}

class TetrahedronComplex {
 public:
  // Tetrahedra of `mesh`, and its points (kept by reference: smoothing moves them).
  explicit TetrahedronComplex(MixedMesh& mesh);

  std::vector<Vector3>& points() { return mesh_.points; }
  const std::vector<Vector3>& points() const { return mesh_.points; }
  std::size_t size() const { return tetrahedra_.size(); }
  bool alive(int t) const { return alive_[static_cast<std::size_t>(t)] != 0; }
  const Tetrahedron& nodes(int t) const { return tetrahedra_[static_cast<std::size_t>(t)]; }
  int region(int t) const { return regions_[static_cast<std::size_t>(t)]; }
  // +1 or -1: the sign of tetrahedron_volume6 for the mesh's (valid) tetrahedra.
  double orientation() const { return orientation_; }
  // Tetrahedra using point p (alive ones only).
  const std::vector<int>& around(Index p) const { return around_[static_cast<std::size_t>(p)]; }
  // True for a point no other cell type and no boundary face uses.
  bool free_point(Index p) const { return free_[static_cast<std::size_t>(p)] != 0; }
  // For a point no other cell type uses whose boundary faces are triangles in one plane
  // (a symmetry plane, a flat side of the far field): that plane's unit normal, along
  // which the point must not move; zero for every other point.
  const Vector3& plane_normal(Index p) const { return plane_normal_[static_cast<std::size_t>(p)]; }
  // For a point that is the apex of pyramids and is used otherwise by tetrahedra only,
  // on no boundary face (the split point of an interface cell, the apex of a cap): those
  // pyramids, as indices into the mesh's pyramid block; null for every other point.
  const std::vector<std::size_t>* apex_pyramids(Index p) const;
  const MixedMesh& mesh() const { return mesh_; }

  // The tetrahedron across face (a, b, c) from t, or -1.
  int neighbour(int t, Index a, Index b, Index c) const;
  // The tetrahedron across t's face opposite its vertex `vertex`, or -1.
  int neighbour_opposite(int t, int vertex) const;
  // Positive when x lies on the same side of t's face opposite `vertex` as the vertex,
  // negative on the far side, zero on the face's plane.
  double face_side(int t, int vertex, const Vector3& x) const;
  // The tetrahedron holding x, walking from t across faces two tetrahedra share; -1
  // when the walk leaves the tetrahedra or does not arrive.
  int locate(int t, const Vector3& x) const;
  // The cavity of a new point x (Bowyer-Watson): the tetrahedra whose circumsphere
  // holds it, grown from `start` (the tetrahedron holding it) across shared faces until
  // it has `largest` tetrahedra.
  void circumsphere_cavity(const Vector3& x, int start, std::size_t largest, std::vector<int>& cavity) const;
  // Grows a cavity until x sees every face of its boundary from inside; false when it
  // would cross a face no two tetrahedra share or grow past `largest` tetrahedra.
  bool make_star_shaped(const Vector3& x, std::size_t largest, std::vector<int>& cavity) const;
  // The apexes round edge (a, b), in order, starting in tetrahedron t, and the
  // tetrahedra between them (tetrahedra[i] has apexes i and i + 1); empty when the
  // ring does not close (the edge is on a boundary or a face of another cell type).
  bool ring(int t, Index a, Index b, std::vector<Index>& apexes, std::vector<int>& tetrahedra) const;

  // Appends a point used by tetrahedra only.
  Index add_point(const Vector3& point);
  int add(const Tetrahedron& nodes, int region);
  void remove(int t);
  // Writes the alive tetrahedra back into the mesh.
  void write_back();

 private:
  struct FaceKey {
    std::array<Index, 3> nodes;
    bool operator==(const FaceKey& other) const { return nodes == other.nodes; }
  };
  struct FaceHash {
    std::size_t operator()(const FaceKey& key) const;
  };
  static FaceKey key(Index a, Index b, Index c);
  void find_planar_points();
  void find_apex_points();

  MixedMesh& mesh_;
  std::vector<Tetrahedron> tetrahedra_;
  std::vector<int> regions_;
  std::vector<char> alive_;
  std::vector<std::vector<int>> around_;
  std::vector<char> free_;
  std::vector<Vector3> plane_normal_;
  std::unordered_map<Index, std::vector<std::size_t>> apex_pyramids_;
  std::unordered_map<FaceKey, std::array<int, 2>, FaceHash> faces_;
  double orientation_ = 1.0;
};

}  // namespace mixmesh::optimize_detail
