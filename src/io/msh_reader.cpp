// Gmsh .msh reader: format 4.1 and 2.2, ASCII and binary (little-endian, 8-byte
// size_t), linear elements. Physical groups become markers (names from
// $PhysicalNames) and region tags; the prism is permuted from Gmsh to VTK order.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>

#include "io/file_access.hpp"
#include "io/text_cursor.hpp"
#include "mixmesh/io/mesh_io.hpp"

namespace mixmesh {

namespace {

using io_detail::quoted;
using io_detail::TextCursor;

// Where a Gmsh element of one type goes: slots 0-3 volume cells (CellType index),
// 4-5 triangle/quad, 6 line; points are read and dropped.
constexpr int line_slot = 6;
constexpr int point_slot = 7;
constexpr int slot_count = 8;
constexpr std::array<int, slot_count> slot_nodes = {4, 5, 6, 8, 3, 4, 2, 1};

std::optional<int> gmsh_slot(long long type) {
  switch (type) {
    case 1:
      return line_slot;
    case 2:
      return 4;
    case 3:
      return 5;
    case 4:
      return index(CellType::tetrahedron);
    case 5:
      return index(CellType::hexahedron);
    case 6:
      return index(CellType::prism);
    case 7:
      return index(CellType::pyramid);
    case 15:
      return point_slot;
    default:
      return std::nullopt;
  }
}

std::string unsupported_type(long long type) {
  static const std::map<long long, const char*> known = {
      {8, "3-node line"},          {9, "6-node triangle"},     {10, "9-node quad"},
      {11, "10-node tetrahedron"}, {12, "27-node hexahedron"}, {13, "18-node prism"},
      {14, "14-node pyramid"},     {16, "8-node quad"},        {17, "20-node hexahedron"},
      {18, "15-node prism"},       {19, "13-node pyramid"}};
  const auto found = known.find(type);
  std::string message = "unsupported Gmsh element type " + std::to_string(type);
  if (found != known.end()) message += std::string(" (") + found->second + ")";
  return message +
         ": only linear tetrahedra, pyramids, prisms, hexahedra, triangles, quads, lines and points";
}

struct RawElements {
  std::vector<Index> nodes;
  std::vector<int> physical;  // 0: none
  std::vector<int> entity;
};

class MshReader {
 public:
  MshReader(std::string_view contents, const std::string& name) : cursor_(contents, name) {}

  MixedMesh read() {
    if (cursor_.token() != "$MeshFormat") throw cursor_.error("not a Gmsh .msh file (no $MeshFormat)");
    read_format();
    bool have_nodes = false;
    bool have_elements = false;
    for (std::string_view section = cursor_.token(); !section.empty(); section = cursor_.token()) {
      if (section == "$PhysicalNames") {
        read_physical_names();
      } else if (section == "$Entities") {
        if (version_ < 4) throw cursor_.error("$Entities in a version 2 file");
        read_entities();
      } else if (section == "$Nodes") {
        if (have_nodes) throw cursor_.error("second $Nodes section");
        version_ >= 4 ? read_nodes_41() : read_nodes_22();
        index_node_tags();
        have_nodes = true;
      } else if (section == "$Elements") {
        if (!have_nodes) throw cursor_.error("$Elements before $Nodes");
        if (have_elements) throw cursor_.error("second $Elements section");
        version_ >= 4 ? read_elements_41() : binary_ ? read_elements_22_binary() : read_elements_22_ascii();
        have_elements = true;
      } else if (section.size() > 1 && section[0] == '$' && section.substr(0, 4) != "$End") {
        const std::string end = "$End" + std::string(section.substr(1));
        if (!cursor_.skip_past(end))
          throw cursor_.error("section " + std::string(section) + " has no " + end);
        continue;
      } else {
        throw cursor_.error("expected a section ($Nodes, $Elements, ...), found " + quoted(section));
      }
      expect_end(section);
    }
    if (!have_nodes) throw cursor_.error("no $Nodes section");
    if (!have_elements) throw cursor_.error("no $Elements section");
    return build();
  }

 private:
  void expect_end(std::string_view section) {
    const std::string end = "$End" + std::string(section.substr(1));
    const std::string_view found = cursor_.token();
    if (found != end)
      throw cursor_.error("expected " + end + ", found " +
                          (found.empty() ? "the end of the file" : quoted(found)) + " (wrong count in " +
                          std::string(section) + "?)");
  }

  void read_format() {
    const std::string_view version = cursor_.expect_token("the format version");
    if (version == "4.1") {
      version_ = 4.1;
    } else if (version.substr(0, 2) == "2.") {
      version_ = 2.2;
    } else {
      throw cursor_.error("unsupported .msh format version " + quoted(version) + " (4.1 and 2.2 are read)");
    }
    const long long file_type = cursor_.integer("the file type (0 ASCII, 1 binary)");
    const long long data_size = cursor_.integer("the data size");
    if (file_type != 0 && file_type != 1) throw cursor_.error("file type must be 0 or 1");
    binary_ = file_type == 1;
    if (binary_) {
      if (data_size != 8)
        throw cursor_.error("binary files need data size 8, found " + std::to_string(data_size));
      cursor_.skip_line_end();
      std::int32_t one = 0;
      cursor_.read_bytes(&one, sizeof one, "the endianness check");
      if (one != 1) throw cursor_.error("big-endian or corrupt binary .msh (endianness check is not 1)");
    }
    expect_end("$MeshFormat");
  }

  // A count, tag or type: text token, or 4-byte int / 8-byte size_t in binary files.
  long long integer(std::string_view what, bool size_type) {
    if (!binary_) return cursor_.integer(what);
    if (size_type) {
      std::uint64_t value = 0;
      cursor_.read_bytes(&value, sizeof value, what);
      if (value > (std::uint64_t{1} << 62)) throw cursor_.error(std::string(what) + " out of range");
      return static_cast<long long>(value);
    }
    std::int32_t value = 0;
    cursor_.read_bytes(&value, sizeof value, what);
    return value;
  }
  long long count(std::string_view what, bool size_type = true) {
    const long long value = integer(what, size_type);
    if (value < 0) throw cursor_.error(std::string(what) + " is negative: " + std::to_string(value));
    return value;
  }
  double real(std::string_view what) {
    if (!binary_) return cursor_.real(what);
    double value = 0;
    cursor_.read_bytes(&value, sizeof value, what);
    if (!std::isfinite(value)) throw cursor_.error(std::string(what) + " is not finite");
    return value;
  }
  // Reserves no more than the remaining bytes could hold, whatever a header claims.
  std::size_t plausible(long long claimed) const {
    return static_cast<std::size_t>(
        std::min<long long>(claimed, static_cast<long long>(cursor_.remaining() / 2 + 1)));
  }

  void read_physical_names() {
    const long long names = cursor_.integer("the number of physical names");
    for (long long name = 0; name < names; ++name) {
      const long long dimension = cursor_.integer("a physical dimension");
      const long long tag = cursor_.integer("a physical tag");
      std::string_view rest;
      if (!cursor_.line(rest)) throw cursor_.error("unexpected end of file in $PhysicalNames");
      const std::size_t open = rest.find('"');
      const std::size_t close = rest.rfind('"');
      if (open == std::string_view::npos || close == open)
        throw cursor_.error("physical name must be in double quotes, found " + quoted(rest));
      physical_names_[{dimension, tag}] = std::string(rest.substr(open + 1, close - open - 1));
    }
  }

  void read_entities() {
    if (binary_) cursor_.skip_line_end();
    std::array<long long, 4> counts{};
    for (long long& value : counts) value = count("an entity count");
    for (int dimension = 0; dimension < 4; ++dimension) {
      for (long long entity = 0; entity < counts[static_cast<std::size_t>(dimension)]; ++entity) {
        const long long tag = integer("an entity tag", false);
        for (int coordinate = 0; coordinate < (dimension == 0 ? 3 : 6); ++coordinate)
          real("an entity bounding box");
        const long long physicals = count("a number of physical tags");
        for (long long physical = 0; physical < physicals; ++physical) {
          const long long value = integer("a physical tag", false);
          if (physical == 0) entity_physical_[{dimension, tag}] = static_cast<int>(value);
        }
        if (dimension == 0) continue;
        const long long bounding = count("a number of bounding entities");
        for (long long bound = 0; bound < bounding; ++bound) integer("a bounding entity tag", false);
      }
    }
  }

  void add_node(long long tag, const Vector3& position) {
    if (tag <= 0) throw cursor_.error("node tag " + std::to_string(tag) + " is not positive");
    node_tags_.push_back(static_cast<std::uint64_t>(tag));
    points_.push_back(position);
  }

  void read_nodes_41() {
    if (binary_) cursor_.skip_line_end();
    const long long blocks = count("the number of node blocks");
    const long long total = count("the number of nodes");
    count("the minimum node tag");
    count("the maximum node tag");
    points_.reserve(plausible(total));
    node_tags_.reserve(plausible(total));
    std::vector<long long> block_tags;
    for (long long block = 0; block < blocks; ++block) {
      const long long dimension = integer("an entity dimension", false);
      integer("an entity tag", false);
      const long long parametric = integer("the parametric flag", false);
      const long long nodes = count("the number of nodes in a block");
      block_tags.clear();
      block_tags.reserve(plausible(nodes));
      for (long long node = 0; node < nodes; ++node) block_tags.push_back(integer("a node tag", true));
      const int parameters = parametric != 0 ? static_cast<int>(std::clamp<long long>(dimension, 0, 3)) : 0;
      for (long long node = 0; node < nodes; ++node) {
        Vector3 position;
        for (int axis = 0; axis < 3; ++axis) position[axis] = real("a node coordinate");
        for (int parameter = 0; parameter < parameters; ++parameter) real("a node parameter");
        add_node(block_tags[static_cast<std::size_t>(node)], position);
      }
    }
    if (static_cast<long long>(points_.size()) != total)
      throw cursor_.error("$Nodes header announces " + std::to_string(total) + " nodes, the blocks hold " +
                          std::to_string(points_.size()));
  }

  void read_nodes_22() {
    const long long total = cursor_.integer("the number of nodes");
    if (total < 0) throw cursor_.error("negative number of nodes");
    if (binary_) cursor_.skip_line_end();
    points_.reserve(plausible(total));
    node_tags_.reserve(plausible(total));
    for (long long node = 0; node < total; ++node) {
      const long long tag = integer("a node tag", false);
      Vector3 position;
      for (int axis = 0; axis < 3; ++axis) position[axis] = real("a node coordinate");
      add_node(tag, position);
    }
  }

  // Tags → indices: a dense table when tags are compact, else a sorted list.
  void index_node_tags() {
    const std::uint64_t largest =
        node_tags_.empty() ? 0 : *std::max_element(node_tags_.begin(), node_tags_.end());
    if (largest <= 2 * node_tags_.size() + 1024) {
      dense_.assign(static_cast<std::size_t>(largest) + 1, -1);
      for (std::size_t node = 0; node < node_tags_.size(); ++node) {
        Index& slot = dense_[static_cast<std::size_t>(node_tags_[node])];
        if (slot >= 0) throw cursor_.error("duplicate node tag " + std::to_string(node_tags_[node]));
        slot = static_cast<Index>(node);
      }
    } else {
      sparse_.reserve(node_tags_.size());
      for (std::size_t node = 0; node < node_tags_.size(); ++node)
        sparse_.emplace_back(node_tags_[node], static_cast<Index>(node));
      std::sort(sparse_.begin(), sparse_.end());
      for (std::size_t entry = 1; entry < sparse_.size(); ++entry)
        if (sparse_[entry].first == sparse_[entry - 1].first)
          throw cursor_.error("duplicate node tag " + std::to_string(sparse_[entry].first));
    }
    node_tags_ = {};
  }

  Index node_index(long long tag) const {
    Index found = -1;
    if (tag > 0 && !dense_.empty()) {
      if (static_cast<std::uint64_t>(tag) < dense_.size()) found = dense_[static_cast<std::size_t>(tag)];
    } else if (tag > 0) {
      const auto entry =
          std::lower_bound(sparse_.begin(), sparse_.end(),
                           std::pair<std::uint64_t, Index>(static_cast<std::uint64_t>(tag), -1));
      if (entry != sparse_.end() && entry->first == static_cast<std::uint64_t>(tag)) found = entry->second;
    }
    if (found < 0)
      throw cursor_.error("element refers to node " + std::to_string(tag) + ", which is not in $Nodes");
    return found;
  }

  int slot_of(long long type) const {
    const std::optional<int> slot = gmsh_slot(type);
    if (!slot) throw cursor_.error(unsupported_type(type));
    return *slot;
  }

  // Reads the node tags of one element (after its own tag) into its slot.
  void read_element_nodes(int slot, long long physical, long long entity, bool size_type) {
    Index nodes[8];
    const int count = slot_nodes[static_cast<std::size_t>(slot)];
    for (int corner = 0; corner < count; ++corner)
      nodes[corner] = node_index(integer("a node tag", size_type));
    if (slot == point_slot) return;
    RawElements& target = elements_[static_cast<std::size_t>(slot)];
    if (slot == index(CellType::prism)) {
      for (int corner = 0; corner < 6; ++corner)
        target.nodes.push_back(nodes[io_detail::prism_permutation[static_cast<std::size_t>(corner)]]);
    } else {
      target.nodes.insert(target.nodes.end(), nodes, nodes + count);
    }
    target.physical.push_back(static_cast<int>(physical));
    target.entity.push_back(static_cast<int>(entity));
  }

  void read_elements_41() {
    if (binary_) cursor_.skip_line_end();
    const long long blocks = count("the number of element blocks");
    const long long total = count("the number of elements");
    count("the minimum element tag");
    count("the maximum element tag");
    long long read = 0;
    for (long long block = 0; block < blocks; ++block) {
      const long long dimension = integer("an entity dimension", false);
      const long long entity = integer("an entity tag", false);
      const int slot = slot_of(integer("an element type", false));
      const long long elements = count("the number of elements in a block");
      const auto physical = entity_physical_.find({dimension, entity});
      const long long physical_tag = physical == entity_physical_.end() ? 0 : physical->second;
      for (long long element = 0; element < elements; ++element) {
        integer("an element tag", true);
        read_element_nodes(slot, physical_tag, entity, true);
      }
      read += elements;
    }
    if (read != total)
      throw cursor_.error("$Elements header announces " + std::to_string(total) +
                          " elements, the blocks hold " + std::to_string(read));
  }

  void read_elements_22_ascii() {
    const long long total = count("the number of elements");
    for (long long element = 0; element < total; ++element) {
      cursor_.integer("an element number");
      const int slot = slot_of(cursor_.integer("an element type"));
      const long long tags = cursor_.integer("the number of element tags");
      if (tags < 0 || tags > 64)
        throw cursor_.error("implausible number of element tags " + std::to_string(tags));
      long long physical = 0;
      long long entity = 0;
      for (long long tag = 0; tag < tags; ++tag) {
        const long long value = cursor_.integer("an element tag");
        if (tag == 0) physical = value;
        if (tag == 1) entity = value;
      }
      read_element_nodes(slot, physical, entity, false);
    }
  }

  void read_elements_22_binary() {
    const long long total = cursor_.integer("the number of elements");
    if (total < 0) throw cursor_.error("negative number of elements");
    cursor_.skip_line_end();
    long long read = 0;
    while (read < total) {
      const int slot = slot_of(integer("an element type", false));
      const long long elements = count("the number of elements following", false);
      const long long tags = count("the number of element tags", false);
      if (elements == 0 || elements > total - read)
        throw cursor_.error("element block of " + std::to_string(elements) +
                            " elements does not fit the total " + std::to_string(total));
      if (tags > 64) throw cursor_.error("implausible number of element tags " + std::to_string(tags));
      for (long long element = 0; element < elements; ++element) {
        integer("an element number", false);
        long long physical = 0;
        long long entity = 0;
        for (long long tag = 0; tag < tags; ++tag) {
          const long long value = integer("an element tag", false);
          if (tag == 0) physical = value;
          if (tag == 1) entity = value;
        }
        read_element_nodes(slot, physical, entity, false);
      }
      read += elements;
    }
  }

  std::string group_name(int dimension, int physical, int entity) const {
    if (physical == 0) return (dimension == 2 ? "surface_" : "curve_") + std::to_string(entity);
    const auto found = physical_names_.find({dimension, physical});
    return found != physical_names_.end() ? found->second : "group_" + std::to_string(physical);
  }

  // Marker ids by (physical, entity) key, named once per group.
  int marker_of(MixedMesh& mesh, int dimension, int physical, int entity) {
    const std::pair<int, int> key{physical, physical == 0 ? entity : 0};
    const auto found = marker_ids_.find(key);
    if (found != marker_ids_.end()) return found->second;
    const int id = mesh.marker(group_name(dimension, physical, entity));
    marker_ids_.emplace(key, id);
    return id;
  }

  MixedMesh build() {
    MixedMesh mesh;
    mesh.points = std::move(points_);
    bool volume = false;
    for (CellType type : all_cell_types)
      volume = volume || !elements_[static_cast<std::size_t>(index(type))].physical.empty();
    // Without volume cells: a planar mesh lies in z = 0, anything else is a surface.
    const bool flat = std::all_of(mesh.points.begin(), mesh.points.end(),
                                  [](const Vector3& point) { return point.z() == 0.0; });
    if (volume || !flat) {
      for (CellType type : all_cell_types) {
        RawElements& raw = elements_[static_cast<std::size_t>(index(type))];
        mesh.block(type).nodes = std::move(raw.nodes);
        mesh.block(type).regions = std::move(raw.physical);
      }
      for (FaceType type : all_face_types) {
        RawElements& raw = elements_[static_cast<std::size_t>(4 + index(type))];
        FaceBlock& faces = mesh.faces(type);
        faces.nodes = std::move(raw.nodes);
        for (std::size_t face = 0; face < raw.physical.size(); ++face)
          faces.markers.push_back(marker_of(mesh, 2, raw.physical[face], raw.entity[face]));
      }
      return mesh;
    }
    for (FaceType type : all_face_types) {
      RawElements& raw = elements_[static_cast<std::size_t>(4 + index(type))];
      mesh.planar_cells[static_cast<std::size_t>(index(type))].nodes = std::move(raw.nodes);
      mesh.planar_cells[static_cast<std::size_t>(index(type))].markers = std::move(raw.physical);
    }
    RawElements& lines = elements_[line_slot];
    mesh.boundary_edges.nodes = std::move(lines.nodes);
    for (std::size_t edge = 0; edge < lines.physical.size(); ++edge)
      mesh.boundary_edges.markers.push_back(marker_of(mesh, 1, lines.physical[edge], lines.entity[edge]));
    return mesh;
  }

  TextCursor cursor_;
  double version_ = 0;
  bool binary_ = false;
  std::map<std::pair<long long, long long>, std::string> physical_names_;
  std::map<std::pair<long long, long long>, int> entity_physical_;
  std::map<std::pair<int, int>, int> marker_ids_;
  std::vector<Vector3> points_;
  std::vector<std::uint64_t> node_tags_;
  std::vector<Index> dense_;
  std::vector<std::pair<std::uint64_t, Index>> sparse_;
  std::array<RawElements, slot_count> elements_;
};

}  // namespace

MixedMesh parse_msh(std::string_view contents, const std::string& name) {
  return MshReader(contents, name).read();
}

MixedMesh read_msh(const std::filesystem::path& path) {
  return parse_msh(io_detail::read_file(path), path.string());
}

}  // namespace mixmesh
