// Whole-file reads and writes shared by the readers and writers of src/io, and the
// node permutations between VTK order (MixedMesh) and the other formats.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <string_view>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh::io_detail {

// The bytes of a file; a missing or unreadable file is a mixmesh::Error.
std::string read_file(const std::filesystem::path& path);
// Writes bytes to path (called inside write_atomically); failure is a mixmesh::Error.
void write_file(const std::filesystem::path& path, std::string_view contents);

// Before writing: every node index names a point, every marker id a name, every
// point is finite (a writer would otherwise emit a file no reader accepts).
void check_writable(const MixedMesh& mesh, const std::filesystem::path& path);

// Gmsh's and CGNS's prism (PENTA_6) numbers the bottom triangle so that its
// right-hand normal points to the top; VTK's wedge the reverse. Node k of one order
// is node prism_permutation[k] of the other (the map is its own inverse).
inline constexpr std::array<int, 6> prism_permutation = {0, 2, 1, 3, 5, 4};

// Appends the shortest text that reads back to exactly value.
void append_real(std::string& out, double value);
void append_integer(std::string& out, long long value);

}  // namespace mixmesh::io_detail
