#include "tetrahedron_complex.hpp"

#include <algorithm>
#include <optional>

#include "mixmesh/mesh/cell_geometry.hpp"

namespace mixmesh::optimize_detail {

namespace {

// Faces of a tetrahedron: the one opposite each vertex.
constexpr std::array<std::array<int, 3>, 4> opposite{{{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}}};

}  // namespace

std::size_t TetrahedronComplex::FaceHash::operator()(const FaceKey& key) const {
  std::uint64_t hash = 1469598103934665603ull;
  for (Index node : key.nodes) hash = (hash ^ static_cast<std::uint64_t>(node)) * 1099511628211ull;
  return static_cast<std::size_t>(hash);
}

TetrahedronComplex::FaceKey TetrahedronComplex::key(Index a, Index b, Index c) {
  FaceKey result{{a, b, c}};
  std::sort(result.nodes.begin(), result.nodes.end());
  return result;
}

TetrahedronComplex::TetrahedronComplex(MixedMesh& mesh) : mesh_(mesh) {
  const CellBlock& block = mesh.block(CellType::tetrahedron);
  const std::size_t count = mesh.cell_count(CellType::tetrahedron);
  around_.resize(mesh.points.size());
  free_.assign(mesh.points.size(), 1);
  for (CellType type : {CellType::pyramid, CellType::prism, CellType::hexahedron})
    for (Index node : mesh.block(type).nodes) free_[static_cast<std::size_t>(node)] = 0;
  for (FaceType type : all_face_types)
    for (Index node : mesh.faces(type).nodes) free_[static_cast<std::size_t>(node)] = 0;
  find_planar_points();
  find_apex_points();
  faces_.reserve(2 * count + 16);
  bool oriented = false;
  for (std::size_t t = 0; t < count; ++t) {
    const Index* n = block.nodes.data() + 4 * t;
    const Tetrahedron nodes{n[0], n[1], n[2], n[3]};
    if (!oriented) {
      const double volume = tetrahedron_volume6(
          mesh.points[static_cast<std::size_t>(n[0])], mesh.points[static_cast<std::size_t>(n[1])],
          mesh.points[static_cast<std::size_t>(n[2])], mesh.points[static_cast<std::size_t>(n[3])]);
      if (volume != 0.0) {
        orientation_ = volume > 0.0 ? 1.0 : -1.0;
        oriented = true;
      }
    }
    add(nodes, block.regions.empty() ? 0 : block.regions[t]);
  }
}

void TetrahedronComplex::find_planar_points() {
  // 1: a candidate so far; 0: not planar (another cell type, a quad, or faces in two planes).
  std::vector<char> planar(mesh_.points.size(), 1);
  plane_normal_.assign(mesh_.points.size(), Vector3::Zero());
  for (CellType type : {CellType::pyramid, CellType::prism, CellType::hexahedron})
    for (Index node : mesh_.block(type).nodes) planar[static_cast<std::size_t>(node)] = 0;
  for (Index node : mesh_.faces(FaceType::quad).nodes) planar[static_cast<std::size_t>(node)] = 0;
  const FaceBlock& triangles = mesh_.faces(FaceType::triangle);
  for (std::size_t face = 0; face < triangles.nodes.size() / 3; ++face) {
    const Index* n = triangles.nodes.data() + 3 * face;
    const Vector3& a = mesh_.points[static_cast<std::size_t>(n[0])];
    const Vector3 area = (mesh_.points[static_cast<std::size_t>(n[1])] - a)
                             .cross(mesh_.points[static_cast<std::size_t>(n[2])] - a);
    const double norm = area.norm();
    for (int k = 0; k < 3; ++k) {
      const auto node = static_cast<std::size_t>(n[k]);
      if (!planar[node]) continue;
      if (!(norm > 0.0)) {
        planar[node] = 0;
        continue;
      }
      const Vector3 normal = area / norm;
      Vector3& known = plane_normal_[node];
      if (known.isZero())
        known = normal;
      else if (known.cross(normal).norm() > 1e-9)
        planar[node] = 0;
    }
  }
  for (std::size_t point = 0; point < planar.size(); ++point)
    if (!planar[point] || free_[point]) plane_normal_[point] = Vector3::Zero();
}

void TetrahedronComplex::find_apex_points() {
  std::vector<char> other_use(mesh_.points.size(), 0);
  for (CellType type : {CellType::prism, CellType::hexahedron})
    for (Index node : mesh_.block(type).nodes) other_use[static_cast<std::size_t>(node)] = 1;
  for (FaceType type : all_face_types)
    for (Index node : mesh_.faces(type).nodes) other_use[static_cast<std::size_t>(node)] = 1;
  const std::size_t pyramids = mesh_.cell_count(CellType::pyramid);
  for (std::size_t pyramid = 0; pyramid < pyramids; ++pyramid) {
    const Index* nodes = mesh_.cell(CellType::pyramid, pyramid);
    for (int corner = 0; corner < 4; ++corner) other_use[static_cast<std::size_t>(nodes[corner])] = 1;
  }
  for (std::size_t pyramid = 0; pyramid < pyramids; ++pyramid) {
    const Index apex = mesh_.cell(CellType::pyramid, pyramid)[4];
    if (!other_use[static_cast<std::size_t>(apex)]) apex_pyramids_[apex].push_back(pyramid);
  }
}

const std::vector<std::size_t>* TetrahedronComplex::apex_pyramids(Index p) const {
  const auto found = apex_pyramids_.find(p);
  return found == apex_pyramids_.end() ? nullptr : &found->second;
}

Index TetrahedronComplex::add_point(const Vector3& point) {
  mesh_.points.push_back(point);
  around_.emplace_back();
  free_.push_back(1);
  plane_normal_.push_back(Vector3::Zero());
  return static_cast<Index>(mesh_.points.size() - 1);
}

int TetrahedronComplex::add(const Tetrahedron& nodes, int region) {
  const int t = static_cast<int>(tetrahedra_.size());
  tetrahedra_.push_back(nodes);
  regions_.push_back(region);
  alive_.push_back(1);
  for (Index node : nodes) around_[static_cast<std::size_t>(node)].push_back(t);
  for (const auto& face : opposite) {
    auto [slot, inserted] = faces_.try_emplace(
        key(nodes[static_cast<std::size_t>(face[0])], nodes[static_cast<std::size_t>(face[1])],
            nodes[static_cast<std::size_t>(face[2])]),
        std::array<int, 2>{-1, -1});
    (slot->second[0] < 0 ? slot->second[0] : slot->second[1]) = t;
  }
  return t;
}

void TetrahedronComplex::remove(int t) {
  const Tetrahedron& nodes = tetrahedra_[static_cast<std::size_t>(t)];
  alive_[static_cast<std::size_t>(t)] = 0;
  for (Index node : nodes) {
    std::vector<int>& list = around_[static_cast<std::size_t>(node)];
    list.erase(std::find(list.begin(), list.end(), t));
  }
  for (const auto& face : opposite) {
    auto slot =
        faces_.find(key(nodes[static_cast<std::size_t>(face[0])], nodes[static_cast<std::size_t>(face[1])],
                        nodes[static_cast<std::size_t>(face[2])]));
    if (slot->second[0] == t) slot->second[0] = slot->second[1];
    slot->second[1] = -1;
    if (slot->second[0] < 0) faces_.erase(slot);
  }
}

int TetrahedronComplex::neighbour(int t, Index a, Index b, Index c) const {
  const auto slot = faces_.find(key(a, b, c));
  if (slot == faces_.end()) return -1;
  return slot->second[0] == t ? slot->second[1] : slot->second[0];
}

int TetrahedronComplex::neighbour_opposite(int t, int vertex) const {
  const std::array<Index, 3> face = face_opposite(nodes(t), vertex);
  return neighbour(t, face[0], face[1], face[2]);
}

double TetrahedronComplex::face_side(int t, int vertex, const Vector3& x) const {
  const Tetrahedron& n = nodes(t);
  const std::array<Index, 3> face = face_opposite(n, vertex);
  const auto& p = points();
  const Vector3& a = p[static_cast<std::size_t>(face[0])];
  const Vector3& b = p[static_cast<std::size_t>(face[1])];
  const Vector3& c = p[static_cast<std::size_t>(face[2])];
  return tetrahedron_volume6(a, b, c, p[static_cast<std::size_t>(n[static_cast<std::size_t>(vertex)])]) *
         tetrahedron_volume6(a, b, c, x);
}

int TetrahedronComplex::locate(int t, const Vector3& x) const {
  for (int step = 0; step < 64; ++step) {
    int vertex = 0;
    while (vertex < 4 && !(face_side(t, vertex, x) < 0.0)) ++vertex;
    if (vertex == 4) return t;
    t = neighbour_opposite(t, vertex);
    if (t < 0) return -1;
  }
  return -1;
}

namespace {

bool holds(const std::vector<int>& cavity, int cell) {
  return std::find(cavity.begin(), cavity.end(), cell) != cavity.end();
}

}  // namespace

void TetrahedronComplex::circumsphere_cavity(const Vector3& x, int start, std::size_t largest,
                                             std::vector<int>& cavity) const {
  auto in_circumsphere = [&](int cell) {
    const Tetrahedron& n = nodes(cell);
    const auto& p = points();
    const std::optional<Vector3> centre =
        tetrahedron_circumcentre(p[static_cast<std::size_t>(n[0])], p[static_cast<std::size_t>(n[1])],
                                 p[static_cast<std::size_t>(n[2])], p[static_cast<std::size_t>(n[3])]);
    return centre && (x - *centre).squaredNorm() <
                         (p[static_cast<std::size_t>(n[0])] - *centre).squaredNorm() * (1.0 - 1e-9);
  };
  cavity.assign(1, start);
  for (std::size_t k = 0; k < cavity.size() && cavity.size() < largest; ++k)
    for (int vertex = 0; vertex < 4; ++vertex) {
      const int other = neighbour_opposite(cavity[k], vertex);
      if (other >= 0 && !holds(cavity, other) && in_circumsphere(other)) cavity.push_back(other);
    }
}

bool TetrahedronComplex::make_star_shaped(const Vector3& x, std::size_t largest,
                                          std::vector<int>& cavity) const {
  // A face seen from behind takes the tetrahedron beyond it in. (Faces seen the right
  // way round stay so as the cavity grows: one sweep does.)
  for (std::size_t k = 0; k < cavity.size(); ++k)
    for (int vertex = 0; vertex < 4; ++vertex) {
      const int other = neighbour_opposite(cavity[k], vertex);
      if ((other >= 0 && holds(cavity, other)) || face_side(cavity[k], vertex, x) > 0.0) continue;
      if (other < 0 || cavity.size() >= largest) return false;
      cavity.push_back(other);
    }
  return true;
}

bool TetrahedronComplex::ring(int t, Index a, Index b, std::vector<Index>& apexes,
                              std::vector<int>& tetrahedra) const {
  apexes.clear();
  tetrahedra.clear();
  auto others = [&](int cell, std::array<Index, 2>& pair) {
    int k = 0;
    for (Index node : tetrahedra_[static_cast<std::size_t>(cell)])
      if (node != a && node != b) pair[static_cast<std::size_t>(k++)] = node;
  };
  std::array<Index, 2> pair{};
  others(t, pair);
  apexes.push_back(pair[0]);
  Index current = pair[1];
  int cell = t;
  while (true) {
    tetrahedra.push_back(cell);
    if (current == apexes.front()) return true;  // closed
    if (tetrahedra.size() > 64) return false;
    apexes.push_back(current);
    const int next = neighbour(cell, a, b, current);
    if (next < 0) {
      apexes.clear();
      tetrahedra.clear();
      return false;
    }
    others(next, pair);
    current = pair[0] == current ? pair[1] : pair[0];
    cell = next;
  }
}

void TetrahedronComplex::write_back() {
  CellBlock block;
  for (std::size_t t = 0; t < tetrahedra_.size(); ++t) {
    if (!alive_[t]) continue;
    block.nodes.insert(block.nodes.end(), tetrahedra_[t].begin(), tetrahedra_[t].end());
    block.regions.push_back(regions_[t]);
  }
  mesh_.block(CellType::tetrahedron) = std::move(block);
}

}  // namespace mixmesh::optimize_detail
