// SU2 native mesh format: "KEY= value" lines, '%' comments, elements and markers as
// "vtk_type node... [index]" lines with 0-based nodes in VTK order (the prism too).
#include <algorithm>
#include <array>
#include <optional>

#include "io/file_access.hpp"
#include "io/text_cursor.hpp"
#include "mixmesh/core/atomic_file.hpp"
#include "mixmesh/io/mesh_io.hpp"

namespace mixmesh {

namespace {

using io_detail::quoted;
using io_detail::TextCursor;

// What a VTK type number stands for in an SU2 file.
struct Su2Element {
  enum class Kind { volume, face, line } kind;
  int type_index;  // CellType or FaceType index
  int node_count;
};

std::optional<Su2Element> su2_element(long long vtk_type) {
  switch (vtk_type) {
    case 3:
      return Su2Element{Su2Element::Kind::line, 0, 2};
    case 5:
      return Su2Element{Su2Element::Kind::face, index(FaceType::triangle), 3};
    case 9:
      return Su2Element{Su2Element::Kind::face, index(FaceType::quad), 4};
    case 10:
      return Su2Element{Su2Element::Kind::volume, index(CellType::tetrahedron), 4};
    case 12:
      return Su2Element{Su2Element::Kind::volume, index(CellType::hexahedron), 8};
    case 13:
      return Su2Element{Su2Element::Kind::volume, index(CellType::prism), 6};
    case 14:
      return Su2Element{Su2Element::Kind::volume, index(CellType::pyramid), 5};
    default:
      return std::nullopt;
  }
}

class Su2Reader {
 public:
  Su2Reader(std::string_view contents, const std::string& name) : cursor_(contents, name) {}

  MixedMesh read() {
    std::string_view line;
    while (next_statement(line)) {
      const auto [key, value] = key_value(line);
      if (key == "NDIME") {
        dimension_ = static_cast<int>(count_value(value, "NDIME"));
        if (dimension_ != 2 && dimension_ != 3)
          throw cursor_.error("NDIME must be 2 or 3, found " + quoted(value));
      } else if (key == "NZONE") {
        if (count_value(value, "NZONE") != 1)
          throw cursor_.error("multi-zone SU2 files are not supported (NZONE= " + std::string(value) + ")");
      } else if (key == "IZONE") {
        continue;
      } else if (key == "NELEM") {
        read_elements(count_value(value, "NELEM"));
      } else if (key == "NPOIN") {
        read_points(count_value(value, "NPOIN"));
      } else if (key == "NMARK") {
        read_markers(count_value(value, "NMARK"));
      } else if (key.substr(0, 4) == "FFD_") {
        break;  // free-form deformation boxes of SU2's shape design end the mesh
      } else {
        throw cursor_.error("unknown SU2 keyword " + quoted(key));
      }
    }
    if (dimension_ == 0) throw cursor_.error("no NDIME= line: not an SU2 mesh");
    if (!have_points_) throw cursor_.error("no NPOIN= section");
    if (!have_elements_) throw cursor_.error("no NELEM= section");
    if (largest_node_ >= static_cast<long long>(mesh_.points.size()))
      throw file_error(cursor_.name(), largest_node_line_,
                       "node index " + std::to_string(largest_node_) +
                           " out of range (NPOIN= " + std::to_string(mesh_.points.size()) + ")");
    return std::move(mesh_);
  }

 private:
  // The next line that is not blank or a comment, comments stripped.
  bool next_statement(std::string_view& line) {
    while (cursor_.line(line)) {
      const std::size_t comment = line.find('%');
      if (comment != std::string_view::npos) line = line.substr(0, comment);
      if (line.find_first_not_of(" \t\r\f\v") != std::string_view::npos) return true;
    }
    return false;
  }

  bool expect_statement(std::string_view& line, const std::string& what) {
    if (!next_statement(line)) throw cursor_.error("unexpected end of file, expected " + what);
    return true;
  }

  std::pair<std::string_view, std::string_view> key_value(std::string_view line) const {
    const std::size_t equals = line.find('=');
    if (equals == std::string_view::npos)
      throw cursor_.error("expected a 'KEYWORD= value' line, found " + quoted(line));
    return {trim(line.substr(0, equals)), trim(line.substr(equals + 1))};
  }

  static std::string_view trim(std::string_view text) {
    const std::size_t first = text.find_first_not_of(" \t\r\f\v");
    if (first == std::string_view::npos) return {};
    const std::size_t last = text.find_last_not_of(" \t\r\f\v");
    return text.substr(first, last - first + 1);
  }

  // A non-negative count; "NPOIN= 10 8" (total, then owned points) keeps the first.
  long long count_value(std::string_view value, std::string_view key) const {
    std::string_view tokens[2];
    long long count = -1;
    if (io_detail::split(value, tokens, 2) == 0 || !io_detail::parse_integer(tokens[0], count) || count < 0)
      throw cursor_.error(std::string(key) + "= needs a non-negative integer, found " + quoted(value));
    return count;
  }

  // The element lines of NELEM or MARKER_ELEMS; calls store(element, nodes).
  template <typename Store>
  void read_element_lines(long long count, const char* section, Store store) {
    std::string_view tokens[11];
    Index nodes[8];
    for (long long element = 0; element < count; ++element) {
      std::string_view line;
      expect_statement(line,
                       std::to_string(count) + " " + section + " lines, found " + std::to_string(element));
      const std::size_t found = io_detail::split(line, tokens, 10);
      long long type = 0;
      if (!io_detail::parse_integer(tokens[0], type))
        throw cursor_.error("expected an element type, found " + quoted(tokens[0]));
      const std::optional<Su2Element> kind = su2_element(type);
      if (!kind)
        throw cursor_.error("unknown or unsupported SU2 element type " + std::to_string(type) + " (" +
                            section + " element " + std::to_string(element) + ")");
      if (found < static_cast<std::size_t>(kind->node_count) + 1 ||
          found > static_cast<std::size_t>(kind->node_count) + 2)
        throw cursor_.error("element type " + std::to_string(type) + " needs " +
                            std::to_string(kind->node_count) + " nodes, the line has " +
                            std::to_string(found > 10 ? 10 : found - 1) + " numbers after the type");
      for (int corner = 0; corner < kind->node_count; ++corner) {
        long long node = -1;
        if (!io_detail::parse_integer(tokens[corner + 1], node) || node < 0 || node > 0x7fffffff)
          throw cursor_.error("invalid node index " + quoted(tokens[corner + 1]));
        if (node > largest_node_) {
          largest_node_ = node;
          largest_node_line_ = cursor_.line_number();
        }
        nodes[corner] = static_cast<Index>(node);
      }
      store(*kind, nodes);
    }
  }

  void read_elements(long long count) {
    if (dimension_ == 0) throw cursor_.error("NELEM= before NDIME=");
    have_elements_ = true;
    read_element_lines(count, "NELEM", [&](const Su2Element& kind, const Index* nodes) {
      if (dimension_ == 3 && kind.kind == Su2Element::Kind::volume) {
        mesh_.add_cell(static_cast<CellType>(kind.type_index), nodes, 0);
      } else if (dimension_ == 2 && kind.kind == Su2Element::Kind::face) {
        FaceBlock& block = mesh_.planar_cells[static_cast<std::size_t>(kind.type_index)];
        block.nodes.insert(block.nodes.end(), nodes, nodes + kind.node_count);
        block.markers.push_back(0);
      } else {
        throw cursor_.error("element of " + std::to_string(kind.node_count) +
                            " nodes is not a cell of an NDIME= " + std::to_string(dimension_) + " mesh");
      }
    });
  }

  void read_points(long long count) {
    if (dimension_ == 0) throw cursor_.error("NPOIN= before NDIME=");
    have_points_ = true;
    mesh_.points.reserve(static_cast<std::size_t>(std::min<long long>(count, cursor_.remaining() / 4 + 1)));
    std::string_view tokens[5];
    for (long long point = 0; point < count; ++point) {
      std::string_view line;
      expect_statement(line, std::to_string(count) + " point lines, found " + std::to_string(point));
      const std::size_t found = io_detail::split(line, tokens, 4);
      if (found < static_cast<std::size_t>(dimension_))
        throw cursor_.error("point " + std::to_string(point) + " needs " + std::to_string(dimension_) +
                            " coordinates");
      Vector3 position = Vector3::Zero();
      for (int axis = 0; axis < dimension_; ++axis)
        if (!io_detail::parse_real(tokens[axis], position[axis]))
          throw cursor_.error("point " + std::to_string(point) + ": invalid coordinate " +
                              quoted(tokens[axis]));
      mesh_.points.push_back(position);
    }
  }

  void read_markers(long long count) {
    if (dimension_ == 0) throw cursor_.error("NMARK= before NDIME=");
    for (long long marker = 0; marker < count; ++marker) {
      std::string_view line;
      expect_statement(line, "MARKER_TAG= of marker " + std::to_string(marker));
      auto [key, value] = key_value(line);
      if (key != "MARKER_TAG") throw cursor_.error("expected MARKER_TAG=, found " + quoted(key));
      if (value.empty()) throw cursor_.error("empty MARKER_TAG=");
      const int id = mesh_.marker(std::string(value));
      expect_statement(line, "MARKER_ELEMS= of marker " + std::string(value));
      std::tie(key, value) = key_value(line);
      if (key != "MARKER_ELEMS") throw cursor_.error("expected MARKER_ELEMS=, found " + quoted(key));
      read_element_lines(
          count_value(value, "MARKER_ELEMS"), "MARKER_ELEMS",
          [&](const Su2Element& kind, const Index* nodes) {
            if (dimension_ == 3 && kind.kind == Su2Element::Kind::face) {
              mesh_.add_face(static_cast<FaceType>(kind.type_index), nodes, id);
            } else if (dimension_ == 2 && kind.kind == Su2Element::Kind::line) {
              mesh_.boundary_edges.nodes.insert(mesh_.boundary_edges.nodes.end(), nodes, nodes + 2);
              mesh_.boundary_edges.markers.push_back(id);
            } else {
              throw cursor_.error("marker element of " + std::to_string(kind.node_count) +
                                  " nodes does not bound an NDIME= " + std::to_string(dimension_) + " mesh");
            }
          });
    }
  }

  TextCursor cursor_;
  MixedMesh mesh_;
  int dimension_ = 0;
  bool have_points_ = false;
  bool have_elements_ = false;
  long long largest_node_ = -1;
  long largest_node_line_ = 0;
};

void append_element(std::string& out, int vtk_type, const Index* nodes, int count, std::size_t number) {
  io_detail::append_integer(out, vtk_type);
  for (int corner = 0; corner < count; ++corner) {
    out += ' ';
    io_detail::append_integer(out, nodes[corner]);
  }
  out += ' ';
  io_detail::append_integer(out, static_cast<long long>(number));
  out += '\n';
}

std::string su2_text(const MixedMesh& mesh) {
  const bool planar = mesh.planar();
  std::string out;
  out.reserve(mesh.points.size() * 64 + mesh.cell_count() * 48);
  out += "% SU2 mesh written by mixmesh\nNDIME= ";
  out += planar ? "2\n" : "3\n";

  std::size_t number = 0;
  if (planar) {
    const std::size_t count = mesh.planar_cells[0].markers.size() + mesh.planar_cells[1].markers.size();
    out += "NELEM= " + std::to_string(count) + "\n";
    for (FaceType type : all_face_types) {
      const FaceBlock& block = mesh.planar_cells[static_cast<std::size_t>(index(type))];
      for (std::size_t cell = 0; cell < block.markers.size(); ++cell)
        append_element(out, vtk_face_number(type),
                       &block.nodes[cell * static_cast<std::size_t>(node_count(type))], node_count(type),
                       number++);
    }
  } else {
    out += "NELEM= " + std::to_string(mesh.cell_count()) + "\n";
    for (CellType type : all_cell_types)
      for (std::size_t cell = 0; cell < mesh.cell_count(type); ++cell)
        append_element(out, vtk_cell_number(type), mesh.cell(type, cell), node_count(type), number++);
  }

  out += "NPOIN= " + std::to_string(mesh.points.size()) + "\n";
  for (std::size_t point = 0; point < mesh.points.size(); ++point) {
    for (int axis = 0; axis < (planar ? 2 : 3); ++axis) {
      io_detail::append_real(out, mesh.points[point][axis]);
      out += ' ';
    }
    io_detail::append_integer(out, static_cast<long long>(point));
    out += '\n';
  }

  // Markers in id order; a marker without elements is left out (SU2 needs none).
  std::vector<std::size_t> per_marker(mesh.marker_names.size(), 0);
  auto count_markers = [&](const std::vector<int>& markers) {
    for (int marker : markers) ++per_marker[static_cast<std::size_t>(marker)];
  };
  if (planar) {
    count_markers(mesh.boundary_edges.markers);
  } else {
    for (const FaceBlock& block : mesh.boundary) count_markers(block.markers);
  }
  out += "NMARK= " +
         std::to_string(
             std::count_if(per_marker.begin(), per_marker.end(), [](std::size_t n) { return n > 0; })) +
         "\n";
  for (std::size_t marker = 0; marker < per_marker.size(); ++marker) {
    if (per_marker[marker] == 0) continue;
    out += "MARKER_TAG= " + mesh.marker_names[marker] +
           "\nMARKER_ELEMS= " + std::to_string(per_marker[marker]) + "\n";
    std::size_t element = 0;
    if (planar) {
      for (std::size_t edge = 0; edge < mesh.boundary_edges.markers.size(); ++edge)
        if (mesh.boundary_edges.markers[edge] == static_cast<int>(marker))
          append_element(out, 3, &mesh.boundary_edges.nodes[2 * edge], 2, element++);
    } else {
      for (FaceType type : all_face_types)
        for (std::size_t face = 0; face < mesh.face_count(type); ++face)
          if (mesh.faces(type).markers[face] == static_cast<int>(marker))
            append_element(out, vtk_face_number(type), mesh.face(type, face), node_count(type), element++);
    }
  }
  return out;
}

}  // namespace

MixedMesh parse_su2(std::string_view contents, const std::string& name) {
  return Su2Reader(contents, name).read();
}

MixedMesh read_su2(const std::filesystem::path& path) {
  return parse_su2(io_detail::read_file(path), path.string());
}

void write_su2(const MixedMesh& mesh, const std::filesystem::path& path) {
  io_detail::check_writable(mesh, path);
  for (const std::string& marker : mesh.marker_names)
    if (marker.empty() || marker.find_first_of(" \t\r\n%=") != std::string::npos)
      throw Error(path.string() + ": marker name '" + marker +
                  "' cannot be written to SU2 (blank, '%' or '=')");
  const std::string text = su2_text(mesh);
  write_atomically(path,
                   [&](const std::filesystem::path& temporary) { io_detail::write_file(temporary, text); });
}

}  // namespace mixmesh
