// Reading and writing MixedMesh in the exchange formats of CFD codes.
//
//   .vtu   VTK XML unstructured grid (VTK's own reader and writer)
//   .msh   Gmsh 4.1 or 2.2, ASCII or binary
//   .su2   SU2 native, NDIME 2 or 3
//   .cgns  CGNS unstructured, one base, one zone (libcgns)
//
// Every format carries the four volume cell types, boundary triangles and quads with
// named markers, and (except CGNS) planar meshes: triangles/quads plus marked boundary
// edges. Node order inside MixedMesh is VTK's; readers and writers permute where a
// format differs (the prism in Gmsh and CGNS). Readers throw mixmesh::Error
// "path:line: message" on malformed input; writers go through write_atomically.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh {

enum class MeshFormat { vtu, msh, su2, cgns };

enum class MshVersion { v41, v22 };

// automatic: binary (appended, base64) for .vtu, ASCII for .msh; .su2 is always
// text and .cgns always binary.
enum class Encoding { automatic, ascii, binary };

struct WriteOptions {
  MshVersion msh_version = MshVersion::v41;
  Encoding encoding = Encoding::automatic;
  // .vtu only: zlib-compress the binary data (smaller, slower to write and read).
  bool compress = false;
};

// The format of a file name's extension (case-insensitive); throws for others.
MeshFormat format_from_extension(const std::filesystem::path& path);

// Chooses the reader or writer from the extension.
MixedMesh read_mesh(const std::filesystem::path& path);
void write_mesh(const MixedMesh& mesh, const std::filesystem::path& path, const WriteOptions& options = {});

// VTK XML unstructured grid. Volume and planar cells carry cell data "region",
// boundary faces and edges "marker"; field data arrays "marker:NAME" hold the id of
// each name (a string array "marker_names" is read too). Reads any file of these VTK
// cell types (ParaView's included), float or double points.
MixedMesh read_vtu(const std::filesystem::path& path);
void write_vtu(const MixedMesh& mesh, const std::filesystem::path& path, const WriteOptions& options = {});

// Gmsh. parse_msh reads a whole file image (text or binary); name is used in errors.
MixedMesh read_msh(const std::filesystem::path& path);
MixedMesh parse_msh(std::string_view contents, const std::string& name);
void write_msh(const MixedMesh& mesh, const std::filesystem::path& path, const WriteOptions& options = {});

// SU2 native.
MixedMesh read_su2(const std::filesystem::path& path);
MixedMesh parse_su2(std::string_view contents, const std::string& name);
void write_su2(const MixedMesh& mesh, const std::filesystem::path& path);

// CGNS (HDF5 or ADF files, whatever libcgns opens). Volume meshes only.
MixedMesh read_cgns(const std::filesystem::path& path);
void write_cgns(const MixedMesh& mesh, const std::filesystem::path& path);

}  // namespace mixmesh
