#include "mixmesh/io/mesh_io.hpp"

#include <algorithm>
#include <cctype>

#include "mixmesh/core/error.hpp"

namespace mixmesh {

MeshFormat format_from_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char character) { return static_cast<char>(std::tolower(character)); });
  if (extension == ".vtu") return MeshFormat::vtu;
  if (extension == ".msh") return MeshFormat::msh;
  if (extension == ".su2") return MeshFormat::su2;
  if (extension == ".cgns") return MeshFormat::cgns;
  throw Error(path.string() + ": unknown mesh format '" + extension + "' (use .vtu, .msh, .su2 or .cgns)");
}

MixedMesh read_mesh(const std::filesystem::path& path) {
  switch (format_from_extension(path)) {
    case MeshFormat::vtu:
      return read_vtu(path);
    case MeshFormat::msh:
      return read_msh(path);
    case MeshFormat::su2:
      return read_su2(path);
    case MeshFormat::cgns:
      break;
  }
  return read_cgns(path);
}

void write_mesh(const MixedMesh& mesh, const std::filesystem::path& path, const WriteOptions& options) {
  switch (format_from_extension(path)) {
    case MeshFormat::vtu:
      return write_vtu(mesh, path, options);
    case MeshFormat::msh:
      return write_msh(mesh, path, options);
    case MeshFormat::su2:
      return write_su2(mesh, path);
    case MeshFormat::cgns:
      break;
  }
  write_cgns(mesh, path);
}

}  // namespace mixmesh
