// Gmsh .msh writer, format 4.1 or 2.2, ASCII or binary. Markers become physical
// groups (tag = marker id + 1, named in $PhysicalNames) on one entity each; regions
// become volume (planar: surface) entities whose physical tag is the region when
// positive; the prism is permuted from VTK to Gmsh order.
#include <algorithm>
#include <cstring>
#include <map>

#include "io/file_access.hpp"
#include "mixmesh/core/atomic_file.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/io/mesh_io.hpp"

namespace mixmesh {

namespace {

// Numbers as text separated by blanks (a line per end_line), or raw little-endian.
class MshOutput {
 public:
  explicit MshOutput(bool binary) : binary_(binary) {}
  void int32(long long value) {
    if (binary_) return raw_value(static_cast<std::int32_t>(value));
    io_detail::append_integer(text_, value);
    text_ += ' ';
  }
  void size(std::uint64_t value) {
    if (binary_) return raw_value(value);
    io_detail::append_integer(text_, static_cast<long long>(value));
    text_ += ' ';
  }
  void real(double value) {
    if (binary_) return raw_value(value);
    io_detail::append_real(text_, value);
    text_ += ' ';
  }
  void end_line() {
    if (binary_) return;
    if (!text_.empty() && text_.back() == ' ') text_.back() = '\n';
  }
  // Section headers and the counts of version 2.2 are text in either encoding.
  void text(std::string_view line) { text_ += line; }
  void reserve(std::size_t bytes) { text_.reserve(bytes); }
  const std::string& contents() const { return text_; }
  bool binary() const { return binary_; }

 private:
  template <typename Value>
  void raw_value(Value value) {
    char bytes[sizeof(Value)];
    std::memcpy(bytes, &value, sizeof(Value));
    text_.append(bytes, sizeof(Value));
  }
  bool binary_;
  std::string text_;
};

// One group of elements written as one Gmsh entity.
struct Group {
  int entity_dimension;
  int entity_tag;
  int physical;  // 0: none
  int gmsh_type;
  const std::vector<Index>* nodes;
  int node_count;
  std::vector<std::size_t> members;  // element indices into nodes (stride node_count)
  bool prism = false;
};

int gmsh_cell_type(CellType type) {
  constexpr std::array<int, 4> types = {4, 7, 6, 5};
  return types[static_cast<std::size_t>(index(type))];
}

class MshWriter {
 public:
  MshWriter(const MixedMesh& mesh, const WriteOptions& options, const std::filesystem::path& path)
      : mesh_(mesh),
        output_(options.encoding == Encoding::binary),
        v41_(options.msh_version == MshVersion::v41) {
    planar_ = mesh.planar();
    collect_groups(path);
  }

  std::string write() {
    output_.reserve(mesh_.points.size() * (output_.binary() ? 32 : 60) + mesh_.cell_count() * 60);
    output_.text(v41_ ? "$MeshFormat\n4.1 " : "$MeshFormat\n2.2 ");
    output_.text(output_.binary() ? "1 8\n" : "0 8\n");
    if (output_.binary()) {
      output_.int32(1);
      output_.text("\n");
    }
    output_.text("$EndMeshFormat\n");
    write_physical_names();
    if (v41_) {
      write_entities();
      write_nodes_41();
      write_elements_41();
    } else {
      write_nodes_22();
      write_elements_22();
    }
    return output_.contents();
  }

 private:
  void collect_groups(const std::filesystem::path& path) {
    // Regions → entities 1..R of the cell dimension.
    std::map<int, int> region_entities;
    auto add_regions = [&](const std::vector<int>& regions) {
      for (int region : regions) {
        if (region < 0)
          throw Error(path.string() + ": cannot write region " + std::to_string(region) +
                      " to .msh (physical tags are positive; 0 means none)");
        region_entities.emplace(region, 0);
      }
    };
    if (planar_) {
      for (const FaceBlock& block : mesh_.planar_cells) add_regions(block.markers);
    } else {
      for (const CellBlock& block : mesh_.cells) add_regions(block.regions);
    }
    if (region_entities.empty()) region_entities.emplace(0, 0);
    int next = 1;
    for (auto& [region, entity] : region_entities) {
      entity = next++;
      region_entities_.push_back({entity, region});
    }

    auto add_group = [&](int dimension, int entity, int physical, int gmsh_type,
                         const std::vector<Index>& nodes, int node_count, const std::vector<int>& keys,
                         int key, bool prism) {
      Group group{dimension, entity, physical, gmsh_type, &nodes, node_count, {}, prism};
      for (std::size_t element = 0; element < keys.size(); ++element)
        if (keys[element] == key) group.members.push_back(element);
      if (!group.members.empty()) groups_.push_back(std::move(group));
    };
    for (const auto& [region, entity] : region_entities) {
      if (planar_) {
        for (FaceType type : all_face_types) {
          const FaceBlock& block = mesh_.planar_cells[static_cast<std::size_t>(index(type))];
          add_group(2, entity, region, type == FaceType::triangle ? 2 : 3, block.nodes, node_count(type),
                    block.markers, region, false);
        }
      } else {
        for (CellType type : all_cell_types)
          add_group(3, entity, region, gmsh_cell_type(type), mesh_.block(type).nodes, node_count(type),
                    mesh_.block(type).regions, region, type == CellType::prism);
      }
    }
    // Markers → entities and physical groups marker + 1 of the dimension below.
    for (std::size_t marker = 0; marker < mesh_.marker_names.size(); ++marker) {
      const int tag = static_cast<int>(marker) + 1;
      if (planar_) {
        add_group(1, tag, tag, 1, mesh_.boundary_edges.nodes, 2, mesh_.boundary_edges.markers,
                  static_cast<int>(marker), false);
      } else {
        for (FaceType type : all_face_types)
          add_group(2, tag, tag, type == FaceType::triangle ? 2 : 3, mesh_.faces(type).nodes,
                    node_count(type), mesh_.faces(type).markers, static_cast<int>(marker), false);
      }
    }
  }

  void write_physical_names() {
    if (mesh_.marker_names.empty()) return;
    output_.text("$PhysicalNames\n" + std::to_string(mesh_.marker_names.size()) + "\n");
    for (std::size_t marker = 0; marker < mesh_.marker_names.size(); ++marker)
      output_.text(std::string(planar_ ? "1 " : "2 ") + std::to_string(marker + 1) + " \"" +
                   mesh_.marker_names[marker] + "\"\n");
    output_.text("$EndPhysicalNames\n");
  }

  void write_bounding_box() {
    Vector3 low = Vector3::Zero();
    Vector3 high = Vector3::Zero();
    if (!mesh_.points.empty()) low = high = mesh_.points.front();
    for (const Vector3& point : mesh_.points) {
      low = low.cwiseMin(point);
      high = high.cwiseMax(point);
    }
    for (int axis = 0; axis < 3; ++axis) output_.real(low[axis]);
    for (int axis = 0; axis < 3; ++axis) output_.real(high[axis]);
  }

  void write_entity(int tag, int physical) {
    output_.int32(tag);
    write_bounding_box();
    output_.size(physical > 0 ? 1 : 0);
    if (physical > 0) output_.int32(physical);
    output_.size(0);  // no bounding entities: the mesh alone is described
    output_.end_line();
  }

  void write_entities() {
    output_.text("$Entities\n");
    const std::size_t markers = mesh_.marker_names.size();
    const std::size_t regions = region_entities_.size();
    output_.size(0);
    output_.size(planar_ ? markers : 0);
    output_.size(planar_ ? regions : markers);
    output_.size(planar_ ? 0 : regions);
    output_.end_line();
    // Boundary entities (one dimension below the cells) come first in dimension order.
    for (std::size_t marker = 0; marker < markers; ++marker)
      write_entity(static_cast<int>(marker) + 1, static_cast<int>(marker) + 1);
    for (const auto& [entity, region] : region_entities_) write_entity(entity, region);
    output_.text(output_.binary() ? "\n$EndEntities\n" : "$EndEntities\n");
  }

  void write_nodes_41() {
    const std::size_t count = mesh_.points.size();
    output_.text("$Nodes\n");
    output_.size(count > 0 ? 1 : 0);
    output_.size(count);
    output_.size(count > 0 ? 1 : 0);
    output_.size(count);
    output_.end_line();
    if (count > 0) {
      // All nodes on the first cell entity; Gmsh needs no finer classification.
      output_.int32(planar_ ? 2 : 3);
      output_.int32(region_entities_.front().first);
      output_.int32(0);
      output_.size(count);
      output_.end_line();
      for (std::size_t node = 0; node < count; ++node) {
        output_.size(node + 1);
        output_.end_line();
      }
      for (const Vector3& point : mesh_.points) {
        for (int axis = 0; axis < 3; ++axis) output_.real(point[axis]);
        output_.end_line();
      }
    }
    output_.text(output_.binary() ? "\n$EndNodes\n" : "$EndNodes\n");
  }

  void write_element_nodes(const Group& group, std::size_t member, bool size_type) {
    const Index* nodes = group.nodes->data() + member * static_cast<std::size_t>(group.node_count);
    for (int corner = 0; corner < group.node_count; ++corner) {
      const Index node =
          group.prism ? nodes[io_detail::prism_permutation[static_cast<std::size_t>(corner)]] : nodes[corner];
      if (size_type) {
        output_.size(static_cast<std::uint64_t>(node) + 1);
      } else {
        output_.int32(node + 1);
      }
    }
    output_.end_line();
  }

  std::size_t element_count() const {
    std::size_t total = 0;
    for (const Group& group : groups_) total += group.members.size();
    return total;
  }

  void write_elements_41() {
    const std::size_t total = element_count();
    output_.text("$Elements\n");
    output_.size(groups_.size());
    output_.size(total);
    output_.size(total > 0 ? 1 : 0);
    output_.size(total);
    output_.end_line();
    std::size_t tag = 1;
    for (const Group& group : groups_) {
      output_.int32(group.entity_dimension);
      output_.int32(group.entity_tag);
      output_.int32(group.gmsh_type);
      output_.size(group.members.size());
      output_.end_line();
      for (std::size_t member : group.members) {
        output_.size(tag++);
        write_element_nodes(group, member, true);
      }
    }
    output_.text(output_.binary() ? "\n$EndElements\n" : "$EndElements\n");
  }

  void write_nodes_22() {
    output_.text("$Nodes\n" + std::to_string(mesh_.points.size()) + "\n");
    for (std::size_t node = 0; node < mesh_.points.size(); ++node) {
      output_.int32(static_cast<long long>(node) + 1);
      for (int axis = 0; axis < 3; ++axis) output_.real(mesh_.points[node][axis]);
      output_.end_line();
    }
    output_.text(output_.binary() ? "\n$EndNodes\n" : "$EndNodes\n");
  }

  void write_elements_22() {
    output_.text("$Elements\n" + std::to_string(element_count()) + "\n");
    long long tag = 1;
    for (const Group& group : groups_) {
      if (output_.binary() && !group.members.empty()) {
        output_.int32(group.gmsh_type);
        output_.int32(static_cast<long long>(group.members.size()));
        output_.int32(2);
      }
      for (std::size_t member : group.members) {
        output_.int32(tag++);
        if (!output_.binary()) {
          output_.int32(group.gmsh_type);
          output_.int32(2);
        }
        output_.int32(group.physical);
        output_.int32(group.entity_tag);
        write_element_nodes(group, member, false);
      }
    }
    output_.text(output_.binary() ? "\n$EndElements\n" : "$EndElements\n");
  }

  const MixedMesh& mesh_;
  MshOutput output_;
  bool v41_;
  bool planar_ = false;
  std::vector<std::pair<int, int>> region_entities_;  // (entity tag, region)
  std::vector<Group> groups_;
};

}  // namespace

void write_msh(const MixedMesh& mesh, const std::filesystem::path& path, const WriteOptions& options) {
  io_detail::check_writable(mesh, path);
  for (const std::string& marker : mesh.marker_names)
    if (marker.find_first_of("\"\n") != std::string::npos)
      throw Error(path.string() + ": marker name '" + marker +
                  "' cannot be written to .msh (quote or newline)");
  const std::string contents = MshWriter(mesh, options, path).write();
  write_atomically(
      path, [&](const std::filesystem::path& temporary) { io_detail::write_file(temporary, contents); });
}

}  // namespace mixmesh
