// Writes the four-type reference mesh in every format and encoding into a folder,
// for the independent checks of tests/regression/io.cmake. With --compare-cgns
// FILE it instead reads FILE back and compares it with the reference mesh (meshio
// cannot read mixed-element CGNS, so our reader checks the CGNS copy).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "mixmesh/core/error.hpp"
#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "reference_cells.hpp"

using namespace mixmesh;

namespace {

int compare(const std::filesystem::path& path) {
  const MixedMesh reference = reference::four_type_mesh();
  const MixedMesh copy = read_mesh(path);
  int failures = 0;
  for (CellType type : all_cell_types) {
    if (copy.cell_count(type) != reference.cell_count(type)) {
      std::printf("%s: %zu cells, expected %zu\n", std::string(name(type)).c_str(), copy.cell_count(type),
                  reference.cell_count(type));
      ++failures;
      continue;
    }
    for (std::size_t cell = 0; cell < copy.cell_count(type); ++cell) {
      const double found = signed_volume(type, copy.points, copy.cell(type, cell));
      const double expected = signed_volume(type, reference.points, reference.cell(type, cell));
      if (!(std::abs(found - expected) < 1e-12 && found > 0)) {
        std::printf("%s %zu: volume %g, expected %g\n", std::string(name(type)).c_str(), cell, found,
                    expected);
        ++failures;
      }
    }
  }
  for (const std::string& marker : reference.marker_names)
    if (copy.find_marker(marker) < 0) {
      std::printf("marker %s missing\n", marker.c_str());
      ++failures;
    }
  if (copy.face_count() != reference.face_count()) {
    std::printf("%zu boundary faces, expected %zu\n", copy.face_count(), reference.face_count());
    ++failures;
  }
  std::printf("%s: %s\n", path.string().c_str(), failures == 0 ? "matches the reference mesh" : "DIFFERS");
  return failures == 0 ? 0 : 1;
}

}  // namespace

int main(int argument_count, char** arguments) {
  try {
    if (argument_count == 3 && std::string(arguments[1]) == "--compare-cgns") return compare(arguments[2]);
    if (argument_count != 2) {
      std::fprintf(stderr, "usage: io_write_reference FOLDER | --compare-cgns FILE\n");
      return 2;
    }
    const std::filesystem::path folder = arguments[1];
    std::filesystem::create_directories(folder);
    const MixedMesh mesh = reference::four_type_mesh();
    WriteOptions options;
    write_mesh(mesh, folder / "four_types.vtu", options);
    write_mesh(mesh, folder / "four_types.su2", options);
    write_mesh(mesh, folder / "four_types.cgns", options);
    write_mesh(mesh, folder / "four_types_msh41.msh", options);
    options.encoding = Encoding::binary;
    write_mesh(mesh, folder / "four_types_msh41_binary.msh", options);
    options.msh_version = MshVersion::v22;
    write_mesh(mesh, folder / "four_types_msh22_binary.msh", options);
    options.encoding = Encoding::ascii;
    write_mesh(mesh, folder / "four_types_msh22.msh", options);
    write_mesh(mesh, folder / "four_types_ascii.vtu", options);
    std::printf("wrote the four-type mesh in 8 files to %s\n", folder.string().c_str());
    return 0;
  } catch (const Error& error) {
    std::fprintf(stderr, "io_write_reference: %s\n", error.what());
    return 1;
  }
}
