#include "deform/dual_mesh.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <numeric>
#include <sstream>

#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

namespace mixmesh::deform::detail {

namespace {

using Key = std::array<Index, 4>;

// The faces (planar: edges) of one cell as local node lists.
int local_faces(const DualMesh& dual, std::size_t cell, std::array<std::array<Index, 4>, 6>& faces,
                std::array<int, 6>& sizes) {
  const Index* nodes = dual.nodes(cell);
  const int kind = dual.cell_kind[cell];
  if (kind >= planar_triangle) {
    const int count = dual.cell_size(cell);
    for (int edge = 0; edge < count; ++edge) {
      faces[static_cast<std::size_t>(edge)] = {nodes[edge], nodes[(edge + 1) % count], -1, -1};
      sizes[static_cast<std::size_t>(edge)] = 2;
    }
    return count;
  }
  const CellDescriptor& descriptor_of = descriptor(static_cast<CellType>(kind));
  for (int face = 0; face < descriptor_of.face_count; ++face) {
    const LocalFace& local = descriptor_of.faces[static_cast<std::size_t>(face)];
    for (int corner = 0; corner < 4; ++corner)
      faces[static_cast<std::size_t>(face)][static_cast<std::size_t>(corner)] =
          corner < local.node_count ? nodes[local.nodes[static_cast<std::size_t>(corner)]] : -1;
    sizes[static_cast<std::size_t>(face)] = local.node_count;
  }
  return descriptor_of.face_count;
}

double shared_face_area(const std::array<Index, 4>& face, int size, const std::vector<Vector3>& points) {
  if (size == 2)
    return (points[static_cast<std::size_t>(face[1])] - points[static_cast<std::size_t>(face[0])]).norm();
  return face_area_vector(points, face.data(), size).norm();
}

}  // namespace

DualMesh build_dual_mesh(const MixedMesh& mesh) {
  DualMesh dual;
  dual.point_count = mesh.points.size();
  dual.cell_offsets.push_back(0);
  auto add_cells = [&](const std::vector<Index>& nodes, int stride, int kind) {
    const std::size_t count = nodes.size() / static_cast<std::size_t>(stride);
    for (std::size_t cell = 0; cell < count; ++cell) {
      for (int local = 0; local < stride; ++local) {
        const Index node = nodes[cell * static_cast<std::size_t>(stride) + static_cast<std::size_t>(local)];
        if (node < 0 || static_cast<std::size_t>(node) >= dual.point_count) {
          std::ostringstream message;
          message << cell_kind_name(kind) << ' ' << cell << " refers to point " << node << " of "
                  << dual.point_count;
          throw Error(message.str());
        }
        dual.cell_nodes.push_back(node);
      }
      dual.cell_offsets.push_back(dual.cell_nodes.size());
      dual.cell_kind.push_back(static_cast<std::uint8_t>(kind));
      dual.index_in_block.push_back(cell);
    }
  };
  dual.planar = mesh.cell_count() == 0;
  if (!dual.planar) {
    for (CellType type : all_cell_types) add_cells(mesh.block(type).nodes, node_count(type), index(type));
    for (FaceType type : all_face_types) {
      const std::size_t stride = static_cast<std::size_t>(node_count(type));
      for (std::size_t face = 0; face < mesh.face_count(type); ++face) {
        dual.face_nodes.insert(dual.face_nodes.end(), mesh.face(type, face), mesh.face(type, face) + stride);
        dual.face_offsets.push_back(dual.face_nodes.size());
        dual.face_marker.push_back(mesh.faces(type).markers[face]);
      }
    }
  } else {
    add_cells(mesh.planar_cells[0].nodes, 3, planar_triangle);
    add_cells(mesh.planar_cells[1].nodes, 4, planar_quad);
    const auto& edges = mesh.boundary_edges;
    for (std::size_t edge = 0; edge < edges.markers.size(); ++edge) {
      dual.face_nodes.push_back(edges.nodes[2 * edge]);
      dual.face_nodes.push_back(edges.nodes[2 * edge + 1]);
      dual.face_offsets.push_back(dual.face_nodes.size());
      dual.face_marker.push_back(edges.markers[edge]);
    }
  }
  if (dual.cell_count() == 0) throw Error("mesh has no cells to deform");
  dual.face_offsets.insert(dual.face_offsets.begin(), 0);

  // Point → cells.
  dual.point_cell_offsets.assign(dual.point_count + 1, 0);
  for (Index node : dual.cell_nodes) ++dual.point_cell_offsets[static_cast<std::size_t>(node) + 1];
  std::partial_sum(dual.point_cell_offsets.begin(), dual.point_cell_offsets.end(),
                   dual.point_cell_offsets.begin());
  dual.point_cells.resize(dual.cell_nodes.size());
  {
    std::vector<std::size_t> fill(dual.point_cell_offsets.begin(), dual.point_cell_offsets.end() - 1);
    for (std::size_t cell = 0; cell < dual.cell_count(); ++cell)
      for (int local = 0; local < dual.cell_size(cell); ++local)
        dual.point_cells[fill[static_cast<std::size_t>(dual.nodes(cell)[local])]++] =
            static_cast<Index>(cell);
  }

  // Faces bucketed by their smallest node; matched inside the bucket.
  struct Record {
    Key key;
    Index cell;
    std::uint8_t local;
  };
  std::vector<std::size_t> start(dual.point_count + 1, 0);
  std::array<std::array<Index, 4>, 6> faces{};
  std::array<int, 6> sizes{};
  for (std::size_t cell = 0; cell < dual.cell_count(); ++cell) {
    const int count = local_faces(dual, cell, faces, sizes);
    for (int face = 0; face < count; ++face) {
      const Key key = sorted_face_key(faces[static_cast<std::size_t>(face)].data(),
                                      sizes[static_cast<std::size_t>(face)]);
      ++start[static_cast<std::size_t>(key[0]) + 1];
    }
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<Record> records(start.back());
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t cell = 0; cell < dual.cell_count(); ++cell) {
      const int count = local_faces(dual, cell, faces, sizes);
      for (int face = 0; face < count; ++face) {
        const Key key = sorted_face_key(faces[static_cast<std::size_t>(face)].data(),
                                        sizes[static_cast<std::size_t>(face)]);
        records[fill[static_cast<std::size_t>(key[0])]++] = {key, static_cast<Index>(cell),
                                                             static_cast<std::uint8_t>(face)};
      }
    }
  }
  std::vector<Index> boundary_owner_by_record(records.size(), -1);
  for (std::size_t point = 0; point < dual.point_count; ++point) {
    const auto begin = records.begin() + static_cast<std::ptrdiff_t>(start[point]);
    const auto end = records.begin() + static_cast<std::ptrdiff_t>(start[point + 1]);
    std::sort(begin, end, [](const Record& a, const Record& b) { return a.key < b.key; });
    for (auto first = begin; first != end;) {
      auto last = first + 1;
      while (last != end && last->key == first->key) ++last;
      if (last - first == 2) {
        local_faces(dual, static_cast<std::size_t>(first->cell), faces, sizes);
        dual.interior_cells.push_back({first->cell, (first + 1)->cell});
        dual.interior_area.push_back(shared_face_area(faces[first->local], sizes[first->local], mesh.points));
      }
      first = last;
    }
  }

  // Owner cell of every tagged boundary face.
  dual.face_cell.assign(dual.face_count(), -1);
  for (std::size_t face = 0; face < dual.face_count(); ++face) {
    const Key key = sorted_face_key(dual.boundary_nodes(face), dual.face_size(face));
    for (Index node : key)
      if (node >= static_cast<Index>(dual.point_count))
        throw Error("boundary face refers to a missing point");
    if (key[0] < 0)
      throw Error("boundary face " + std::to_string(face) + " refers to a negative point index");
    const auto begin = records.begin() + static_cast<std::ptrdiff_t>(start[static_cast<std::size_t>(key[0])]);
    const auto end =
        records.begin() + static_cast<std::ptrdiff_t>(start[static_cast<std::size_t>(key[0]) + 1]);
    const auto found = std::lower_bound(
        begin, end, key, [](const Record& record, const Key& value) { return record.key < value; });
    if (found == end || found->key != key) {
      const Vector3 centre = face_centre(dual, face, mesh.points);
      std::ostringstream message;
      message << (dual.planar ? "boundary edge " : "boundary face ") << face << " at (" << centre.x() << ", "
              << centre.y() << ", " << centre.z() << ") bounds no cell";
      throw Error(message.str());
    }
    dual.face_cell[face] = found->cell;
  }
  return dual;
}

Vector3 cell_centre(const DualMesh& dual, std::size_t cell, const std::vector<Vector3>& points) {
  Vector3 sum = Vector3::Zero();
  const Index* nodes = dual.nodes(cell);
  const int count = dual.cell_size(cell);
  for (int local = 0; local < count; ++local) sum += points[static_cast<std::size_t>(nodes[local])];
  return sum / count;
}

Vector3 face_centre(const DualMesh& dual, std::size_t face, const std::vector<Vector3>& points) {
  Vector3 sum = Vector3::Zero();
  const Index* nodes = dual.boundary_nodes(face);
  const int count = dual.face_size(face);
  for (int local = 0; local < count; ++local) sum += points[static_cast<std::size_t>(nodes[local])];
  return sum / count;
}

double face_area(const DualMesh& dual, std::size_t face, const std::vector<Vector3>& points) {
  const Index* nodes = dual.boundary_nodes(face);
  if (dual.face_size(face) == 2)
    return (points[static_cast<std::size_t>(nodes[1])] - points[static_cast<std::size_t>(nodes[0])]).norm();
  return face_area_vector(points, nodes, dual.face_size(face)).norm();
}

namespace {

// Twice the signed area of the corner (previous, here, next) in the z = 0 plane.
double corner_turn(const Vector3& previous, const Vector3& here, const Vector3& next) {
  const Vector3 in = here - previous;
  const Vector3 out = next - here;
  return in.x() * out.y() - in.y() * out.x();
}

double planar_area(const DualMesh& dual, std::size_t cell, const std::vector<Vector3>& points) {
  const Index* nodes = dual.nodes(cell);
  const int count = dual.cell_size(cell);
  double twice = 0.0;
  for (int corner = 0; corner < count; ++corner) {
    const Vector3& from = points[static_cast<std::size_t>(nodes[corner])];
    const Vector3& to = points[static_cast<std::size_t>(nodes[(corner + 1) % count])];
    twice += from.x() * to.y() - from.y() * to.x();
  }
  return 0.5 * twice;
}

}  // namespace

double cell_measure(const DualMesh& dual, std::size_t cell, const std::vector<Vector3>& points) {
  const int kind = dual.cell_kind[cell];
  if (kind >= planar_triangle) return planar_area(dual, cell, points);
  return signed_volume(static_cast<CellType>(kind), points, dual.nodes(cell));
}

std::vector<Index> cells_of_nodes(const DualMesh& dual, const std::vector<Index>& nodes) {
  std::vector<Index> cells;
  for (Index node : nodes)
    for (std::size_t slot = dual.point_cell_offsets[static_cast<std::size_t>(node)];
         slot < dual.point_cell_offsets[static_cast<std::size_t>(node) + 1]; ++slot)
      cells.push_back(dual.point_cells[slot]);
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

bool cell_valid(const DualMesh& dual, std::size_t cell, const std::vector<Vector3>& points) {
  const int kind = dual.cell_kind[cell];
  if (kind < planar_triangle)
    return cell_shape(static_cast<CellType>(kind), points, dual.nodes(cell)).valid() &&
           inverted_face_pyramids(static_cast<CellType>(kind), points, dual.nodes(cell)) == 0;
  if (planar_area(dual, cell, points) <= 0.0) return false;
  const Index* nodes = dual.nodes(cell);
  const int count = dual.cell_size(cell);
  for (int corner = 0; corner < count; ++corner) {
    const Vector3& previous = points[static_cast<std::size_t>(nodes[(corner + count - 1) % count])];
    const Vector3& here = points[static_cast<std::size_t>(nodes[corner])];
    const Vector3& next = points[static_cast<std::size_t>(nodes[(corner + 1) % count])];
    if (corner_turn(previous, here, next) <= 0.0) return false;
  }
  return true;
}

std::string cell_kind_name(int kind) {
  if (kind == planar_triangle) return "triangle";
  if (kind == planar_quad) return "quad";
  return std::string(name(static_cast<CellType>(kind)));
}

namespace {

// One 64-bit word into the hash: multiply–rotate mixing, order dependent.
std::uint64_t mix(std::uint64_t hash, std::uint64_t word) {
  hash ^= word * 0x9E3779B97F4A7C15ull;
  hash = (hash << 27) | (hash >> 37);
  return hash * 0xBF58476D1CE4E5B9ull + 0x94D049BB133111EBull;
}

template <class Value>
std::uint64_t mix_all(std::uint64_t hash, const std::vector<Value>& values) {
  hash = mix(hash, values.size());
  for (const Value& value : values) hash = mix(hash, static_cast<std::uint64_t>(value));
  return hash;
}

}  // namespace

std::uint64_t connectivity_hash(const MixedMesh& mesh) {
  std::uint64_t hash = mix(0x6D69786D657368ull, mesh.points.size());
  for (CellType type : all_cell_types) hash = mix_all(hash, mesh.block(type).nodes);
  for (FaceType type : all_face_types) {
    hash = mix_all(hash, mesh.faces(type).nodes);
    hash = mix_all(hash, mesh.faces(type).markers);
  }
  for (const auto& block : mesh.planar_cells) hash = mix_all(hash, block.nodes);
  hash = mix_all(hash, mesh.boundary_edges.nodes);
  return mix_all(hash, mesh.boundary_edges.markers);
}

std::uint64_t points_hash(const std::vector<Vector3>& points) {
  std::uint64_t hash = mix(0x706F696E7473ull, points.size());
  for (const Vector3& point : points)
    for (int axis = 0; axis < 3; ++axis) {
      std::uint64_t bits = 0;
      std::memcpy(&bits, &point[axis], sizeof bits);
      hash = mix(hash, bits);
    }
  return hash;
}

std::uint64_t combine_hash(std::uint64_t hash, const std::vector<Index>& values) {
  return mix_all(hash, values);
}

std::uint64_t combine_hash(std::uint64_t hash, const char* bytes, std::size_t count) {
  std::size_t offset = 0;
  for (; offset + 8 <= count; offset += 8) {
    std::uint64_t word = 0;
    std::memcpy(&word, bytes + offset, 8);
    hash = mix(hash, word);
  }
  std::uint64_t tail = 0;
  if (count > offset) std::memcpy(&tail, bytes + offset, count - offset);  // (an empty list has no data)
  return mix(hash, tail);
}

std::vector<std::vector<Index>> colour_cells(const DualMesh& dual) {
  const std::size_t cells = dual.cell_count();
  std::vector<std::size_t> offsets(cells + 1, 0);
  for (const auto& pair : dual.interior_cells) {
    ++offsets[static_cast<std::size_t>(pair[0]) + 1];
    ++offsets[static_cast<std::size_t>(pair[1]) + 1];
  }
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  std::vector<Index> neighbours(offsets.back());
  std::vector<std::size_t> fill(offsets.begin(), offsets.end() - 1);
  for (const auto& pair : dual.interior_cells) {
    neighbours[fill[static_cast<std::size_t>(pair[0])]++] = pair[1];
    neighbours[fill[static_cast<std::size_t>(pair[1])]++] = pair[0];
  }
  std::vector<int> colour(cells, -1);
  std::vector<std::vector<Index>> groups;
  std::vector<char> taken;
  for (std::size_t cell = 0; cell < cells; ++cell) {
    taken.assign(groups.size() + 1, 0);
    for (std::size_t slot = offsets[cell]; slot < offsets[cell + 1]; ++slot) {
      const int other = colour[static_cast<std::size_t>(neighbours[slot])];
      if (other >= 0) taken[static_cast<std::size_t>(other)] = 1;
    }
    const int chosen = static_cast<int>(std::find(taken.begin(), taken.end(), 0) - taken.begin());
    if (chosen == static_cast<int>(groups.size())) groups.emplace_back();
    colour[cell] = chosen;
    groups[static_cast<std::size_t>(chosen)].push_back(static_cast<Index>(cell));
  }
  return groups;
}

}  // namespace mixmesh::deform::detail
