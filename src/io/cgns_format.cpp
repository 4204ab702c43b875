// CGNS unstructured volume meshes through libcgns: one base, one zone, one element
// section per cell type, then one section per marker and face type; each marker is
// a BC_t (PointRange of face elements, GridLocation FaceCenter) on a family of the
// marker's name. Region tags travel as the cell-centred integer field "Region".
// PENTA_6 numbers its bottom triangle towards the top (CGNS SIDS, section 3.3), the
// reverse of VTK's wedge, so prisms are permuted both ways.
#include <cgnslib.h>

#include <algorithm>
#include <array>
#include <map>
#include <tuple>

#include "io/file_access.hpp"
#include "mixmesh/core/atomic_file.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/io/mesh_io.hpp"

namespace mixmesh {

namespace {

using ElementType = CGNS_ENUMT(ElementType_t);

// Closes the file on every path out.
class CgnsFile {
 public:
  CgnsFile(const std::filesystem::path& path, int mode) : path_(path.string()) {
    if (cg_open(path_.c_str(), mode, &handle_) != CG_OK) {
      handle_ = -1;
      throw file_error(path_, 0, std::string("CGNS: cannot open: ") + cg_get_error());
    }
  }
  ~CgnsFile() {
    if (handle_ >= 0) cg_close(handle_);
  }
  CgnsFile(const CgnsFile&) = delete;
  CgnsFile& operator=(const CgnsFile&) = delete;

  int handle() const { return handle_; }
  // Throws with libcgns's message when a call failed.
  void check(int status, const std::string& what) const {
    if (status != CG_OK) throw file_error(path_, 0, "CGNS: " + what + ": " + cg_get_error());
  }
  void close() {
    const int status = cg_close(handle_);
    handle_ = -1;
    check(status, "closing the file");
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int handle_ = -1;
};

ElementType cgns_cell_type(CellType type) {
  constexpr std::array<ElementType, 4> types = {CGNS_ENUMV(TETRA_4), CGNS_ENUMV(PYRA_5), CGNS_ENUMV(PENTA_6),
                                                CGNS_ENUMV(HEXA_8)};
  return types[static_cast<std::size_t>(index(type))];
}

// Volume cell (0-3), face (4-5) or -1 for a CGNS element type.
int slot_of(ElementType type) {
  switch (type) {
    case CGNS_ENUMV(TETRA_4):
      return index(CellType::tetrahedron);
    case CGNS_ENUMV(PYRA_5):
      return index(CellType::pyramid);
    case CGNS_ENUMV(PENTA_6):
      return index(CellType::prism);
    case CGNS_ENUMV(HEXA_8):
      return index(CellType::hexahedron);
    case CGNS_ENUMV(TRI_3):
      return 4;
    case CGNS_ENUMV(QUAD_4):
      return 5;
    default:
      return -1;
  }
}

constexpr std::array<int, 6> slot_nodes = {4, 5, 6, 8, 3, 4};

std::string element_type_name(ElementType type) {
  const int value = static_cast<int>(type);
  if (value >= 0 && value < NofValidElementTypes) return ElementTypeName[value];
  return "element type " + std::to_string(value);
}

// A run of face elements [start, end] and where the faces went in the mesh.
struct FaceSection {
  cgsize_t start;
  cgsize_t end;
  std::vector<std::pair<FaceType, std::size_t>> faces;
  std::string name;
};

class CgnsReader {
 public:
  explicit CgnsReader(const std::filesystem::path& path) : file_(path, CG_MODE_READ) {}

  MixedMesh read() {
    int bases = 0;
    file_.check(cg_nbases(file_.handle(), &bases), "counting bases");
    if (bases < 1) throw file_error(file_.path(), 0, "CGNS file has no base");
    char name[33];
    int cell_dimension = 0;
    int physical_dimension = 0;
    file_.check(cg_base_read(file_.handle(), 1, name, &cell_dimension, &physical_dimension),
                "reading base 1");
    if (cell_dimension != 3)
      throw file_error(file_.path(), 0,
                       "CGNS base has cell dimension " + std::to_string(cell_dimension) +
                           "; mixmesh reads volume (3D) CGNS meshes");
    int zones = 0;
    file_.check(cg_nzones(file_.handle(), 1, &zones), "counting zones");
    if (zones != 1)
      throw file_error(file_.path(), 0,
                       "CGNS base has " + std::to_string(zones) + " zones; mixmesh reads one-zone files");
    CGNS_ENUMT(ZoneType_t) zone_type;
    file_.check(cg_zone_type(file_.handle(), 1, 1, &zone_type), "reading the zone type");
    if (zone_type != CGNS_ENUMV(Unstructured))
      throw file_error(file_.path(), 0, "CGNS zone is not unstructured");
    cgsize_t size[3];
    file_.check(cg_zone_read(file_.handle(), 1, 1, name, size), "reading the zone");
    read_points(size[0]);
    read_sections();
    read_regions();
    read_boundary_conditions();
    for (FaceSection& section : face_sections_) {
      for (const auto& [type, face] : section.faces) {
        int& marker = mesh_.faces(type).markers[face];
        if (marker < 0) marker = mesh_.marker(section.name);
      }
    }
    return std::move(mesh_);
  }

 private:
  void read_points(cgsize_t count) {
    std::vector<double> coordinates[3];
    const char* names[3] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
    cgsize_t first = 1;
    for (int axis = 0; axis < 3; ++axis) {
      coordinates[axis].resize(static_cast<std::size_t>(count));
      if (count > 0)
        file_.check(cg_coord_read(file_.handle(), 1, 1, names[axis], CGNS_ENUMV(RealDouble), &first, &count,
                                  coordinates[axis].data()),
                    std::string("reading ") + names[axis]);
    }
    mesh_.points.resize(static_cast<std::size_t>(count));
    for (std::size_t point = 0; point < mesh_.points.size(); ++point) {
      mesh_.points[point] = Vector3(coordinates[0][point], coordinates[1][point], coordinates[2][point]);
      if (!mesh_.points[point].allFinite())
        throw file_error(file_.path(), 0, "CGNS vertex " + std::to_string(point + 1) + " is not finite");
    }
  }

  // One element of a section; nodes are 1-based CGNS vertex numbers.
  void add_element(int slot, const cgsize_t* nodes, const std::string& section, cgsize_t number,
                   FaceSection* faces) {
    Index local[8];
    const int count = slot_nodes[static_cast<std::size_t>(slot)];
    for (int corner = 0; corner < count; ++corner) {
      const cgsize_t node = nodes[corner];
      if (node < 1 || node > static_cast<cgsize_t>(mesh_.points.size()))
        throw file_error(file_.path(), 0,
                         "CGNS section '" + section + "' element " + std::to_string(number) +
                             " refers to vertex " + std::to_string(node) + ", out of range");
      local[corner] = static_cast<Index>(node - 1);
    }
    if (slot < 4) {
      const auto type = static_cast<CellType>(slot);
      if (type == CellType::prism) {
        Index vtk[6];
        for (int corner = 0; corner < 6; ++corner)
          vtk[corner] = local[io_detail::prism_permutation[static_cast<std::size_t>(corner)]];
        mesh_.add_cell(type, vtk, 0);
      } else {
        mesh_.add_cell(type, local, 0);
      }
      volume_order_.emplace_back(number, type, mesh_.cell_count(type) - 1);
      return;
    }
    const auto type = static_cast<FaceType>(slot - 4);
    mesh_.add_face(type, local, -1);
    faces->faces.emplace_back(type, mesh_.face_count(type) - 1);
  }

  void read_sections() {
    int sections = 0;
    file_.check(cg_nsections(file_.handle(), 1, 1, &sections), "counting element sections");
    for (int section = 1; section <= sections; ++section) {
      char name[33];
      ElementType type;
      cgsize_t start = 0;
      cgsize_t end = 0;
      int boundary_count = 0;
      int parent_flag = 0;
      file_.check(cg_section_read(file_.handle(), 1, 1, section, name, &type, &start, &end, &boundary_count,
                                  &parent_flag),
                  "reading section " + std::to_string(section));
      if (end < start)
        throw file_error(file_.path(), 0, "CGNS section '" + std::string(name) + "' has an empty range");
      cgsize_t data_size = 0;
      file_.check(cg_ElementDataSize(file_.handle(), 1, 1, section, &data_size),
                  "sizing section " + std::string(name));
      std::vector<cgsize_t> elements(static_cast<std::size_t>(data_size));
      FaceSection faces{start, end, {}, name};
      const cgsize_t count = end - start + 1;
      if (type == CGNS_ENUMV(MIXED)) {
        std::vector<cgsize_t> offsets(static_cast<std::size_t>(count) + 1);
        file_.check(
            cg_poly_elements_read(file_.handle(), 1, 1, section, elements.data(), offsets.data(), nullptr),
            "reading section " + std::string(name));
        for (cgsize_t element = 0; element < count; ++element) {
          const cgsize_t first = offsets[static_cast<std::size_t>(element)];
          const auto element_type = static_cast<ElementType>(elements[static_cast<std::size_t>(first)]);
          const int slot = slot_of(element_type);
          if (slot < 0 || offsets[static_cast<std::size_t>(element) + 1] - first !=
                              slot_nodes[static_cast<std::size_t>(std::max(slot, 0))] + 1)
            throw file_error(file_.path(), 0,
                             "CGNS section '" + std::string(name) + "': unsupported element " +
                                 element_type_name(element_type));
          add_element(slot, &elements[static_cast<std::size_t>(first) + 1], name, start + element, &faces);
        }
      } else {
        const int slot = slot_of(type);
        if (slot < 0) {
          if (type == CGNS_ENUMV(BAR_2) || type == CGNS_ENUMV(NODE)) continue;  // edges of a volume mesh
          throw file_error(file_.path(), 0,
                           "CGNS section '" + std::string(name) + "' has unsupported element type " +
                               element_type_name(type));
        }
        const auto stride = static_cast<cgsize_t>(slot_nodes[static_cast<std::size_t>(slot)]);
        if (data_size != count * stride)
          throw file_error(file_.path(), 0,
                           "CGNS section '" + std::string(name) + "' has the wrong data size");
        file_.check(cg_elements_read(file_.handle(), 1, 1, section, elements.data(), nullptr),
                    "reading section " + std::string(name));
        for (cgsize_t element = 0; element < count; ++element)
          add_element(slot, &elements[static_cast<std::size_t>(element * stride)], name, start + element,
                      &faces);
      }
      if (!faces.faces.empty()) face_sections_.push_back(std::move(faces));
    }
    std::sort(volume_order_.begin(), volume_order_.end());
  }

  // Cell-centred integer field "Region", in element-number order of the volume cells.
  void read_regions() {
    int solutions = 0;
    if (cg_nsols(file_.handle(), 1, 1, &solutions) != CG_OK) return;
    for (int solution = 1; solution <= solutions; ++solution) {
      char name[33];
      CGNS_ENUMT(GridLocation_t) location;
      file_.check(cg_sol_info(file_.handle(), 1, 1, solution, name, &location), "reading a flow solution");
      if (location != CGNS_ENUMV(CellCenter)) continue;
      int fields = 0;
      file_.check(cg_nfields(file_.handle(), 1, 1, solution, &fields), "counting fields");
      for (int field = 1; field <= fields; ++field) {
        CGNS_ENUMT(DataType_t) type;
        char field_name[33];
        file_.check(cg_field_info(file_.handle(), 1, 1, solution, field, &type, field_name),
                    "reading a field");
        if (std::string(field_name) != "Region" || volume_order_.empty()) continue;
        std::vector<int> regions(volume_order_.size());
        cgsize_t first = 1;
        auto last = static_cast<cgsize_t>(regions.size());
        file_.check(cg_field_read(file_.handle(), 1, 1, solution, "Region", CGNS_ENUMV(Integer), &first,
                                  &last, regions.data()),
                    "reading field Region");
        for (std::size_t cell = 0; cell < regions.size(); ++cell) {
          const auto& [number, type_of_cell, position] = volume_order_[cell];
          mesh_.block(type_of_cell).regions[position] = regions[cell];
        }
        return;
      }
    }
  }

  std::pair<FaceType, std::size_t>* face_of(cgsize_t number) {
    for (FaceSection& section : face_sections_)
      if (number >= section.start && number <= section.end)
        return &section.faces[static_cast<std::size_t>(number - section.start)];
    return nullptr;
  }

  void read_boundary_conditions() {
    int conditions = 0;
    file_.check(cg_nbocos(file_.handle(), 1, 1, &conditions), "counting boundary conditions");
    for (int condition = 1; condition <= conditions; ++condition) {
      char name[33];
      CGNS_ENUMT(BCType_t) type;
      CGNS_ENUMT(PointSetType_t) set_type;
      cgsize_t point_count = 0;
      int normal_index[3];
      cgsize_t normal_size = 0;
      CGNS_ENUMT(DataType_t) normal_type;
      int datasets = 0;
      file_.check(cg_boco_info(file_.handle(), 1, 1, condition, name, &type, &set_type, &point_count,
                               normal_index, &normal_size, &normal_type, &datasets),
                  "reading boundary condition " + std::to_string(condition));
      CGNS_ENUMT(GridLocation_t) location = CGNS_ENUMV(Vertex);
      file_.check(cg_boco_gridlocation_read(file_.handle(), 1, 1, condition, &location),
                  "reading a BC location");
      std::vector<cgsize_t> points(static_cast<std::size_t>(std::max<cgsize_t>(point_count, 2)));
      file_.check(cg_boco_read(file_.handle(), 1, 1, condition, points.data(), nullptr),
                  "reading boundary condition " + std::string(name));
      std::string marker_name = name;
      char family[33];
      if (cg_goto(file_.handle(), 1, "Zone_t", 1, "ZoneBC_t", 1, "BC_t", condition, "end") == CG_OK &&
          cg_famname_read(family) == CG_OK)
        marker_name = family;
      const bool range = set_type == CGNS_ENUMV(PointRange) || set_type == CGNS_ENUMV(ElementRange);
      std::vector<cgsize_t> numbers;
      if (range) {
        for (cgsize_t number = points[0]; number <= points[1]; ++number) numbers.push_back(number);
      } else {
        numbers.assign(points.begin(), points.begin() + point_count);
      }
      const int marker = mesh_.marker(marker_name);
      if (location == CGNS_ENUMV(Vertex) && set_type != CGNS_ENUMV(ElementRange) &&
          set_type != CGNS_ENUMV(ElementList)) {
        mark_faces_on_vertices(numbers, marker);
        continue;
      }
      for (cgsize_t number : numbers) {
        std::pair<FaceType, std::size_t>* face = face_of(number);
        if (face == nullptr)
          throw file_error(file_.path(), 0,
                           "CGNS boundary condition '" + std::string(name) + "' names element " +
                               std::to_string(number) + ", which is not a boundary face");
        mesh_.faces(face->first).markers[face->second] = marker;
      }
    }
  }

  // A vertex-based BC marks the faces (not yet marked) whose nodes all lie in it.
  void mark_faces_on_vertices(const std::vector<cgsize_t>& vertices, int marker) {
    std::vector<char> in_set(mesh_.points.size(), 0);
    for (cgsize_t vertex : vertices)
      if (vertex >= 1 && vertex <= static_cast<cgsize_t>(in_set.size()))
        in_set[static_cast<std::size_t>(vertex - 1)] = 1;
    for (FaceType type : all_face_types) {
      FaceBlock& block = mesh_.faces(type);
      for (std::size_t face = 0; face < block.markers.size(); ++face) {
        if (block.markers[face] >= 0) continue;
        bool inside = true;
        for (int corner = 0; corner < node_count(type); ++corner)
          inside =
              inside &&
              in_set[static_cast<std::size_t>(block.nodes[face * static_cast<std::size_t>(node_count(type)) +
                                                          static_cast<std::size_t>(corner)])];
        if (inside) block.markers[face] = marker;
      }
    }
  }

  CgnsFile file_;
  MixedMesh mesh_;
  std::vector<FaceSection> face_sections_;
  std::vector<std::tuple<cgsize_t, CellType, std::size_t>> volume_order_;
};

void write_cgns_file(const MixedMesh& mesh, const std::filesystem::path& path) {
  CgnsFile file(path, CG_MODE_WRITE);
  const int handle = file.handle();
  int base = 0;
  file.check(cg_base_write(handle, "Base", 3, 3, &base), "writing the base");
  cgsize_t size[3] = {static_cast<cgsize_t>(mesh.points.size()), static_cast<cgsize_t>(mesh.cell_count()), 0};
  int zone = 0;
  file.check(cg_zone_write(handle, base, "Zone", size, CGNS_ENUMV(Unstructured), &zone), "writing the zone");
  const char* names[3] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
  std::vector<double> coordinate(mesh.points.size());
  for (int axis = 0; axis < 3; ++axis) {
    for (std::size_t point = 0; point < mesh.points.size(); ++point)
      coordinate[point] = mesh.points[point][axis];
    int index_out = 0;
    file.check(cg_coord_write(handle, base, zone, CGNS_ENUMV(RealDouble), names[axis], coordinate.data(),
                              &index_out),
               std::string("writing ") + names[axis]);
  }

  cgsize_t next = 1;
  std::vector<cgsize_t> connectivity;
  auto write_section = [&](const std::string& name, ElementType type, const Index* nodes, std::size_t count,
                           int stride, bool prism) {
    connectivity.resize(count * static_cast<std::size_t>(stride));
    for (std::size_t element = 0; element < count; ++element)
      for (int corner = 0; corner < stride; ++corner) {
        const int from = prism ? io_detail::prism_permutation[static_cast<std::size_t>(corner)] : corner;
        connectivity[element * static_cast<std::size_t>(stride) + static_cast<std::size_t>(corner)] =
            nodes[element * static_cast<std::size_t>(stride) + static_cast<std::size_t>(from)] + 1;
      }
    int section = 0;
    const cgsize_t last = next + static_cast<cgsize_t>(count) - 1;
    file.check(cg_section_write(handle, base, zone, name.c_str(), type, next, last, 0, connectivity.data(),
                                &section),
               "writing section " + name);
    next = last + 1;
  };
  std::vector<int> regions;
  for (CellType type : all_cell_types) {
    if (mesh.cell_count(type) == 0) continue;
    std::string name(descriptor(type).name);
    name[0] = static_cast<char>(name[0] - 'a' + 'A');
    write_section(name, cgns_cell_type(type), mesh.block(type).nodes.data(), mesh.cell_count(type),
                  node_count(type), type == CellType::prism);
    regions.insert(regions.end(), mesh.block(type).regions.begin(), mesh.block(type).regions.end());
  }

  // Per marker: its triangles then its quads, one contiguous element range.
  std::vector<Index> nodes;
  for (std::size_t marker = 0; marker < mesh.marker_names.size(); ++marker) {
    const std::string& name = mesh.marker_names[marker];
    const cgsize_t first = next;
    for (FaceType type : all_face_types) {
      nodes.clear();
      const FaceBlock& block = mesh.faces(type);
      for (std::size_t face = 0; face < block.markers.size(); ++face)
        if (block.markers[face] == static_cast<int>(marker))
          nodes.insert(nodes.end(), mesh.face(type, face), mesh.face(type, face) + node_count(type));
      if (nodes.empty()) continue;
      write_section(name + (type == FaceType::triangle ? "_triangles" : "_quads"),
                    type == FaceType::triangle ? CGNS_ENUMV(TRI_3) : CGNS_ENUMV(QUAD_4), nodes.data(),
                    nodes.size() / static_cast<std::size_t>(node_count(type)), node_count(type), false);
    }
    if (next == first) continue;
    int family = 0;
    file.check(cg_family_write(handle, base, name.c_str(), &family), "writing family " + name);
    const cgsize_t range[2] = {first, next - 1};
    int condition = 0;
    file.check(cg_boco_write(handle, base, zone, name.c_str(), CGNS_ENUMV(FamilySpecified),
                             CGNS_ENUMV(PointRange), 2, range, &condition),
               "writing boundary condition " + name);
    file.check(cg_boco_gridlocation_write(handle, base, zone, condition, CGNS_ENUMV(FaceCenter)),
               "writing the location of " + name);
    file.check(cg_goto(handle, base, "Zone_t", zone, "ZoneBC_t", 1, "BC_t", condition, "end"),
               "locating " + name);
    file.check(cg_famname_write(name.c_str()), "naming the family of " + name);
  }

  if (!regions.empty()) {
    int solution = 0;
    file.check(cg_sol_write(handle, base, zone, "Regions", CGNS_ENUMV(CellCenter), &solution),
               "writing regions");
    int field = 0;
    file.check(
        cg_field_write(handle, base, zone, solution, CGNS_ENUMV(Integer), "Region", regions.data(), &field),
        "writing field Region");
  }
  file.close();
}

}  // namespace

MixedMesh read_cgns(const std::filesystem::path& path) {
  std::error_code code;
  if (!std::filesystem::is_regular_file(path, code))
    throw file_error(path.string(), 0, "cannot open: no such file");
  return CgnsReader(path).read();
}

void write_cgns(const MixedMesh& mesh, const std::filesystem::path& path) {
  io_detail::check_writable(mesh, path);
  if (mesh.planar())
    throw Error(path.string() +
                ": planar meshes cannot be written to CGNS by mixmesh (use .su2, .msh or .vtu)");
  for (const std::string& name : mesh.marker_names)
    if (name.empty() || name.size() + 10 > 32)
      throw Error(path.string() + ": marker name '" + name +
                  "' is empty or too long for CGNS (22 characters at most)");
  write_atomically(path, [&](const std::filesystem::path& temporary) { write_cgns_file(mesh, temporary); });
}

}  // namespace mixmesh
