// VTK XML unstructured grid (.vtu) through VTK's own reader and writer. Arrays are
// copied in bulk (one pass over the cell types, no per-cell virtual calls) so that a
// million-cell file reads in well under a second after VTK has parsed it.
#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cstring>

#include "io/file_access.hpp"
#include "mixmesh/core/atomic_file.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/io/mesh_io.hpp"

namespace mixmesh {

namespace {

static_assert(sizeof(Vector3) == 3 * sizeof(double), "points must be packed xyz triples");

// Collects the error and warning messages of a VTK algorithm instead of letting VTK
// print them, so the library stays quiet and the message reaches the caller.
class VtkMessages {
 public:
  explicit VtkMessages(vtkObject* algorithm) {
    callback_->SetClientData(this);
    callback_->SetCallback([](vtkObject*, unsigned long event, void* client, void* call_data) {
      auto* self = static_cast<VtkMessages*>(client);
      if (event == vtkCommand::ErrorEvent && call_data != nullptr && self->first_error_.empty())
        self->first_error_ = static_cast<const char*>(call_data);
    });
    observe(algorithm);
  }
  void observe(vtkObject* object) {
    object->AddObserver(vtkCommand::ErrorEvent, callback_);
    object->AddObserver(vtkCommand::WarningEvent, callback_);
  }
  vtkCommand* command() { return callback_; }
  // The first error, trimmed to its last line (VTK prefixes object addresses).
  std::string error() const {
    std::string message = first_error_;
    while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
    const std::size_t last_line = message.rfind('\n');
    if (last_line != std::string::npos) message = message.substr(last_line + 1);
    const std::size_t address_end = message.find("): ");  // "vtkClass (0x...): " carries nothing
    return address_end == std::string::npos ? message : message.substr(address_end + 3);
  }
  bool failed() const { return !first_error_.empty(); }

 private:
  vtkNew<vtkCallbackCommand> callback_;
  std::string first_error_;
};

const char* vtk_type_name(int type) {
  switch (type) {
    case 1:
      return "vertex";
    case 2:
      return "poly-vertex";
    case 3:
      return "line";
    case 4:
      return "poly-line";
    case 5:
      return "triangle";
    case 6:
      return "triangle strip";
    case 7:
      return "polygon";
    case 8:
      return "pixel";
    case 9:
      return "quad";
    case 10:
      return "tetrahedron";
    case 11:
      return "voxel";
    case 12:
      return "hexahedron";
    case 13:
      return "wedge";
    case 14:
      return "pyramid";
    case 42:
      return "polyhedron";
    default:
      return type >= 20 && type < 42 ? "higher-order cell" : "unknown cell";
  }
}

// Integer cell data as one int per cell; missing arrays give fill.
std::vector<int> integer_cell_data(vtkUnstructuredGrid& grid, const char* name, vtkIdType cells) {
  vtkDataArray* array = grid.GetCellData()->GetArray(name);
  std::vector<int> values;
  if (array == nullptr || array->GetNumberOfTuples() != cells || array->GetNumberOfComponents() != 1)
    return values;
  values.resize(static_cast<std::size_t>(cells));
  if (auto* integers = vtkIntArray::SafeDownCast(array)) {
    std::memcpy(values.data(), integers->GetPointer(0), values.size() * sizeof(int));
  } else {
    for (vtkIdType cell = 0; cell < cells; ++cell)
      values[static_cast<std::size_t>(cell)] = static_cast<int>(array->GetComponent(cell, 0));
  }
  return values;
}

std::vector<Vector3> copy_points(vtkUnstructuredGrid& grid, const std::string& path) {
  std::vector<Vector3> points(static_cast<std::size_t>(grid.GetNumberOfPoints()));
  if (points.empty()) return points;
  vtkDataArray* data = grid.GetPoints()->GetData();
  if (auto* doubles = vtkDoubleArray::SafeDownCast(data)) {
    std::memcpy(points.data()->data(), doubles->GetPointer(0), points.size() * sizeof(Vector3));
  } else if (auto* floats = vtkFloatArray::SafeDownCast(data)) {
    const float* values = floats->GetPointer(0);
    for (std::size_t point = 0; point < points.size(); ++point)
      points[point] = Vector3(values[3 * point], values[3 * point + 1], values[3 * point + 2]);
  } else {
    for (std::size_t point = 0; point < points.size(); ++point)
      data->GetTuple(static_cast<vtkIdType>(point), points[point].data());
  }
  for (std::size_t point = 0; point < points.size(); ++point)
    if (!points[point].allFinite())
      throw file_error(path, 0, "point " + std::to_string(point) + " has a coordinate that is not finite");
  return points;
}

// Offsets and connectivity of the grid as 64-bit values (copied once if stored as 32).
template <typename Array>
void widen(Array* array, std::vector<long long>& out) {
  out.resize(static_cast<std::size_t>(array->GetNumberOfValues()));
  for (std::size_t value = 0; value < out.size(); ++value)
    out[value] = array->GetValue(static_cast<vtkIdType>(value));
}

// Field data names the marker ids: one integer array "marker:NAME" = id per marker
// (what meshio and ParaView both keep), or a string array "marker_names".
std::vector<std::string> marker_names(vtkUnstructuredGrid& grid) {
  std::vector<std::string> names;
  vtkFieldData* fields = grid.GetFieldData();
  if (auto* strings = vtkStringArray::SafeDownCast(fields->GetAbstractArray("marker_names")))
    for (vtkIdType name = 0; name < strings->GetNumberOfValues(); ++name)
      names.push_back(strings->GetValue(name));
  const std::string prefix = "marker:";
  for (int array = 0; array < fields->GetNumberOfArrays(); ++array) {
    vtkDataArray* data = fields->GetArray(array);
    const char* array_name = fields->GetArrayName(array);
    if (data == nullptr || array_name == nullptr || std::string(array_name).rfind(prefix, 0) != 0 ||
        data->GetNumberOfTuples() < 1)
      continue;
    const double id = data->GetComponent(0, 0);
    if (!(id >= 0 && id < 1e6)) continue;
    if (names.size() <= static_cast<std::size_t>(id)) names.resize(static_cast<std::size_t>(id) + 1);
    names[static_cast<std::size_t>(id)] = std::string(array_name).substr(prefix.size());
  }
  return names;
}

MixedMesh mesh_from_grid(vtkUnstructuredGrid& grid, const std::string& path) {
  MixedMesh mesh;
  mesh.points = copy_points(grid, path);
  const vtkIdType cells = grid.GetNumberOfCells();
  if (cells == 0) return mesh;
  vtkCellArray* cell_array = grid.GetCells();
  std::vector<long long> offsets;
  std::vector<long long> connectivity;
  if (cell_array->IsStorage64Bit()) {
    widen(cell_array->GetOffsetsArray64(), offsets);
    widen(cell_array->GetConnectivityArray64(), connectivity);
  } else {
    widen(cell_array->GetOffsetsArray32(), offsets);
    widen(cell_array->GetConnectivityArray32(), connectivity);
  }
  const unsigned char* types = grid.GetCellTypesArray()->GetPointer(0);
  const std::vector<int> regions = integer_cell_data(grid, "region", cells);
  const std::vector<int> markers = integer_cell_data(grid, "marker", cells);
  const std::vector<std::string> names = marker_names(grid);

  // Pass 1: check every cell; decide whether triangles/quads are boundary faces.
  const auto point_count = static_cast<long long>(mesh.points.size());
  bool volume = false;
  for (vtkIdType cell = 0; cell < cells; ++cell) {
    const int type = types[cell];
    int expected = 0;
    switch (type) {
      case 3:
        expected = 2;
        break;
      case 5:
        expected = 3;
        break;
      case 9:
        expected = 4;
        break;
      case 10:
        expected = 4;
        volume = true;
        break;
      case 12:
        expected = 8;
        volume = true;
        break;
      case 13:
        expected = 6;
        volume = true;
        break;
      case 14:
        expected = 5;
        volume = true;
        break;
      default:
        throw file_error(path, 0,
                         "cell " + std::to_string(cell) + " has VTK cell type " + std::to_string(type) +
                             " (" + vtk_type_name(type) +
                             "); mixmesh reads tetrahedra, pyramids, wedges, hexahedra, triangles, "
                             "quads and lines");
    }
    const long long first = offsets[static_cast<std::size_t>(cell)];
    const long long last = offsets[static_cast<std::size_t>(cell) + 1];
    if (last - first != expected || first < 0 || last > static_cast<long long>(connectivity.size()))
      throw file_error(path, 0,
                       "cell " + std::to_string(cell) + " (" + vtk_type_name(type) + ") has " +
                           std::to_string(last - first) + " nodes, expected " + std::to_string(expected));
    for (long long slot = first; slot < last; ++slot) {
      const long long node = connectivity[static_cast<std::size_t>(slot)];
      if (node < 0 || node >= point_count)
        throw file_error(path, 0,
                         "cell " + std::to_string(cell) + " refers to point " + std::to_string(node) +
                             ", out of range (" + std::to_string(point_count) + " points)");
    }
  }

  // Marker ids of the file → ids of the mesh (files without names get "marker_N").
  std::vector<int> marker_ids;
  auto marker_of = [&](vtkIdType cell) {
    const int value = markers.empty() ? -1 : markers[static_cast<std::size_t>(cell)];
    if (value < 0) return mesh.marker("boundary");
    if (static_cast<std::size_t>(value) >= marker_ids.size())
      marker_ids.resize(static_cast<std::size_t>(value) + 1, -1);
    int& id = marker_ids[static_cast<std::size_t>(value)];
    if (id < 0)
      id = mesh.marker(static_cast<std::size_t>(value) < names.size() ? names[static_cast<std::size_t>(value)]
                                                                      : "marker_" + std::to_string(value));
    return id;
  };

  // Pass 2: copy nodes into the blocks.
  for (vtkIdType cell = 0; cell < cells; ++cell) {
    const int type = types[cell];
    const long long first = offsets[static_cast<std::size_t>(cell)];
    const long long last = offsets[static_cast<std::size_t>(cell) + 1];
    const int region = regions.empty() ? 0 : regions[static_cast<std::size_t>(cell)];
    std::vector<Index>* target = nullptr;
    switch (type) {
      case 10:
      case 12:
      case 13:
      case 14: {
        const CellType cell_type = type == 10   ? CellType::tetrahedron
                                   : type == 12 ? CellType::hexahedron
                                   : type == 13 ? CellType::prism
                                                : CellType::pyramid;
        target = &mesh.block(cell_type).nodes;
        mesh.block(cell_type).regions.push_back(region);
        break;
      }
      case 5:
      case 9: {
        const FaceType face_type = type == 5 ? FaceType::triangle : FaceType::quad;
        // Boundary face when the mesh has volume cells or the face carries a marker
        // (a surface mesh); otherwise a cell of a planar mesh.
        const bool boundary = volume || (!markers.empty() && markers[static_cast<std::size_t>(cell)] >= 0);
        FaceBlock& block =
            boundary ? mesh.faces(face_type) : mesh.planar_cells[static_cast<std::size_t>(index(face_type))];
        target = &block.nodes;
        block.markers.push_back(boundary ? marker_of(cell) : region);
        break;
      }
      default:  // line
        if (volume) continue;
        target = &mesh.boundary_edges.nodes;
        mesh.boundary_edges.markers.push_back(marker_of(cell));
        break;
    }
    for (long long slot = first; slot < last; ++slot)
      target->push_back(static_cast<Index>(connectivity[static_cast<std::size_t>(slot)]));
  }
  return mesh;
}

vtkSmartPointer<vtkUnstructuredGrid> grid_from_mesh(const MixedMesh& mesh) {
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  if (!mesh.points.empty())  // borrowed, not copied: the grid lives only while writing
    coordinates->SetArray(const_cast<double*>(mesh.points.front().data()),
                          static_cast<vtkIdType>(3 * mesh.points.size()), 1);
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);
  grid->SetPoints(points);

  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  vtkNew<vtkUnsignedCharArray> types;
  vtkNew<vtkIntArray> regions;
  vtkNew<vtkIntArray> markers;
  regions->SetName("region");
  markers->SetName("marker");
  std::size_t cell_total = mesh.boundary_edges.markers.size();
  std::size_t node_total = mesh.boundary_edges.nodes.size();
  for (const CellBlock& block : mesh.cells)
    cell_total += block.regions.size(), node_total += block.nodes.size();
  for (const FaceBlock& block : mesh.boundary)
    cell_total += block.markers.size(), node_total += block.nodes.size();
  for (const FaceBlock& block : mesh.planar_cells)
    cell_total += block.markers.size(), node_total += block.nodes.size();
  offsets->SetNumberOfValues(static_cast<vtkIdType>(cell_total + 1));
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(node_total));
  types->SetNumberOfValues(static_cast<vtkIdType>(cell_total));
  regions->SetNumberOfValues(static_cast<vtkIdType>(cell_total));
  markers->SetNumberOfValues(static_cast<vtkIdType>(cell_total));

  vtkIdType cell = 0;
  vtkIdType slot = 0;
  offsets->SetValue(0, 0);
  auto append = [&](const std::vector<Index>& nodes, int stride, int vtk_type, const std::vector<int>& tags,
                    bool marker) {
    for (std::size_t element = 0; element < tags.size(); ++element) {
      for (int corner = 0; corner < stride; ++corner)
        connectivity->SetValue(
            slot++, nodes[element * static_cast<std::size_t>(stride) + static_cast<std::size_t>(corner)]);
      types->SetValue(cell, static_cast<unsigned char>(vtk_type));
      regions->SetValue(cell, marker ? -1 : tags[element]);
      markers->SetValue(cell, marker ? tags[element] : -1);
      offsets->SetValue(++cell, slot);
    }
  };
  for (CellType type : all_cell_types)
    append(mesh.block(type).nodes, node_count(type), vtk_cell_number(type), mesh.block(type).regions, false);
  for (FaceType type : all_face_types)
    append(mesh.faces(type).nodes, node_count(type), vtk_face_number(type), mesh.faces(type).markers, true);
  for (FaceType type : all_face_types) {
    const FaceBlock& block = mesh.planar_cells[static_cast<std::size_t>(index(type))];
    append(block.nodes, node_count(type), vtk_face_number(type), block.markers, false);
  }
  append(mesh.boundary_edges.nodes, 2, 3, mesh.boundary_edges.markers, true);

  vtkNew<vtkCellArray> cell_array;
  cell_array->SetData(offsets, connectivity);
  grid->SetCells(types, cell_array);
  grid->GetCellData()->AddArray(regions);
  grid->GetCellData()->AddArray(markers);
  for (std::size_t marker = 0; marker < mesh.marker_names.size(); ++marker) {
    vtkNew<vtkIntArray> id;
    id->SetName(("marker:" + mesh.marker_names[marker]).c_str());
    id->InsertNextValue(static_cast<int>(marker));
    grid->GetFieldData()->AddArray(id);
  }
  return grid;
}

}  // namespace

MixedMesh read_vtu(const std::filesystem::path& path) {
  std::error_code code;
  if (!std::filesystem::is_regular_file(path, code))
    throw file_error(path.string(), 0, "cannot open: no such file");
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  VtkMessages messages(reader);
  messages.observe(reader->GetExecutive());
  reader->SetReaderErrorObserver(messages.command());
  reader->SetParserErrorObserver(messages.command());
  if (reader->CanReadFile(path.string().c_str()) == 0)
    throw file_error(path.string(), 0, "not a VTK XML unstructured grid (.vtu) file");
  reader->SetFileName(path.string().c_str());
  reader->Update();
  if (messages.failed() || reader->GetErrorCode() != 0)
    throw file_error(
        path.string(), 0,
        "VTK could not read the file: " + (messages.failed() ? messages.error() : std::string("read error")));
  vtkUnstructuredGrid* grid = reader->GetOutput();
  if (grid == nullptr) throw file_error(path.string(), 0, "VTK returned no grid");
  return mesh_from_grid(*grid, path.string());
}

void write_vtu(const MixedMesh& mesh, const std::filesystem::path& path, const WriteOptions& options) {
  io_detail::check_writable(mesh, path);
  const vtkSmartPointer<vtkUnstructuredGrid> grid = grid_from_mesh(mesh);
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    VtkMessages messages(writer);
    messages.observe(writer->GetExecutive());
    writer->SetInputData(grid);
    writer->SetFileName(temporary.string().c_str());
    if (options.encoding == Encoding::ascii) {
      writer->SetDataModeToAscii();
    } else {
      // Appended base64, VTK's default: raw appended data trips meshio 5.0, which
      // renumbers raw offsets and can match a small array's new offset to another.
      writer->SetDataModeToAppended();
      writer->EncodeAppendedDataOn();
    }
    if (options.compress) {
      writer->SetCompressorTypeToZLib();
    } else {
      writer->SetCompressorTypeToNone();
    }
    if (writer->Write() == 0 || messages.failed())
      throw Error(path.string() + ": cannot write: " +
                  (messages.failed() ? messages.error() : std::string("VTK write failed")));
  });
}

}  // namespace mixmesh
