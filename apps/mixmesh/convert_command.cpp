// mixmesh convert IN OUT: reads a mesh in one format and writes it in another,
// formats chosen by the file extensions.
#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "mixmesh/core/log.hpp"
#include "mixmesh/io/mesh_io.hpp"

namespace mixmesh::cli {

namespace {

struct ConvertArguments {
  std::string input;
  std::string output;
  std::string msh_version = "4.1";
  bool ascii = false;
  bool binary = false;
  bool compress = false;
};

std::string summary(const MixedMesh& mesh) {
  std::string text = std::to_string(mesh.points.size()) + " points";
  if (mesh.planar()) {
    text += ", " + std::to_string(mesh.planar_cells[0].markers.size()) + " triangles, " +
            std::to_string(mesh.planar_cells[1].markers.size()) + " quads, " +
            std::to_string(mesh.boundary_edges.markers.size()) + " boundary edges";
  } else {
    constexpr const char* plurals[4] = {"tetrahedra", "pyramids", "prisms", "hexahedra"};
    for (CellType type : all_cell_types)
      text += ", " + std::to_string(mesh.cell_count(type)) + " " + plurals[index(type)];
    text += ", " + std::to_string(mesh.face_count()) + " boundary faces";
  }
  return text + ", " + std::to_string(mesh.marker_names.size()) + " markers";
}

void run_convert(const ConvertArguments& arguments) {
  Log log(&std::cout);
  Stopwatch stopwatch;
  const MixedMesh mesh = read_mesh(arguments.input);
  log.info("read " + arguments.input + ": " + summary(mesh));
  WriteOptions options;
  options.msh_version = arguments.msh_version == "2.2" ? MshVersion::v22 : MshVersion::v41;
  if (arguments.ascii) options.encoding = Encoding::ascii;
  if (arguments.binary) options.encoding = Encoding::binary;
  options.compress = arguments.compress;
  write_mesh(mesh, arguments.output, options);
  log.info("wrote " + arguments.output + " in " + std::to_string(stopwatch.seconds()) + " s");
}

}  // namespace

void add_convert_command(CLI::App& application) {
  auto arguments = std::make_shared<ConvertArguments>();
  CLI::App* command = application.add_subcommand(
      "convert",
      "Convert a mesh between formats, chosen by extension: .vtu (VTK XML), .msh (Gmsh 4.1/2.2), .su2 (SU2), "
      ".cgns (CGNS, volume meshes). Cell types, boundary markers (by name) and region tags are kept where "
      "the "
      "output format can hold them (.su2 has no region tags).");
  command->add_option("input", arguments->input, "Mesh to read (.vtu, .msh, .su2, .cgns)")->required();
  command->add_option("output", arguments->output, "Mesh to write (.vtu, .msh, .su2, .cgns)")->required();
  command->add_option("--msh-version", arguments->msh_version, "Gmsh format version of a .msh output")
      ->check(CLI::IsMember({"4.1", "2.2"}))
      ->capture_default_str();
  CLI::Option* ascii =
      command->add_flag("--ascii", arguments->ascii, "Write text (.msh default; .vtu: inline ASCII)");
  command->add_flag("--binary", arguments->binary, "Write binary (.vtu default; .msh: little-endian binary)")
      ->excludes(ascii);
  command->add_flag("--compress", arguments->compress, "Compress the binary data of a .vtu output with zlib");
  command->callback([arguments] { run_convert(*arguments); });
}

}  // namespace mixmesh::cli
