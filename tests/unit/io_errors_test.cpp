// Malformed input: every reader answers with one mixmesh::Error "path:line: message"
// (line where the text formats know it), never a crash, a hang or a partial mesh.
#include <gtest/gtest.h>

#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "mixmesh/core/error.hpp"
#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"

using namespace mixmesh;

namespace {

// Runs read and checks that it throws Error starting with where and containing what.
void expect_error(const std::function<void()>& read, const std::string& where, const std::string& what) {
  try {
    read();
    ADD_FAILURE() << "no error; expected " << where << " ... " << what;
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind(where, 0), 0u) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  }
}

std::filesystem::path scratch(const std::string& file) {
  const std::filesystem::path directory = std::filesystem::temp_directory_path() / "mixmesh_io_errors";
  std::filesystem::create_directories(directory);
  return directory / file;
}

// A valid one-tetrahedron Gmsh 2.2 file; tests break one line of it.
std::string msh22(const std::string& nodes = "1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n",
                  const std::string& element = "1 4 2 1 1 1 2 3 4\n", const std::string& node_count = "4",
                  const std::string& element_count = "1") {
  return "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" + node_count + "\n" + nodes +
         "$EndNodes\n$Elements\n" + element_count + "\n" + element + "$EndElements\n";
}

TEST(MshErrors, ValidBaseFileReads) {
  const MixedMesh mesh = parse_msh(msh22(), "t.msh");
  EXPECT_EQ(mesh.cell_count(CellType::tetrahedron), 1u);
}

TEST(MshErrors, EmptyOrForeignFile) {
  expect_error([] { parse_msh("", "t.msh"); }, "t.msh:1: ", "not a Gmsh .msh file");
  expect_error([] { parse_msh("solid cube\nfacet normal 0 0 1\n", "t.msh"); },
               "t.msh:1: ", "not a Gmsh .msh file");
}

TEST(MshErrors, UnsupportedVersion) {
  expect_error([] { parse_msh("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n", "t.msh"); },
               "t.msh:2: ", "unsupported .msh format version '3.0'");
}

TEST(MshErrors, TruncatedFile) {
  const std::string whole = msh22();
  const std::string cut = whole.substr(0, whole.find("3 0 1 0") + 5);
  expect_error([&] { parse_msh(cut, "t.msh"); }, "t.msh:8: ", "unexpected end of file");
  expect_error([&] { parse_msh(whole.substr(0, whole.find("$Elements")), "t.msh"); },
               "t.msh:", "no $Elements section");
}

TEST(MshErrors, WrongCounts) {
  // Five nodes announced, four given: $EndNodes is read as a node tag.
  expect_error(
      [] { parse_msh(msh22("1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", "1 4 2 1 1 1 2 3 4\n", "5"), "t.msh"); },
      "t.msh:10: ", "expected a node tag");
  // Three nodes announced: the fourth node line is where $EndNodes should be.
  expect_error(
      [] { parse_msh(msh22("1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", "1 4 2 1 1 1 2 3 4\n", "3"), "t.msh"); },
      "t.msh:9: ", "expected $EndNodes");
  expect_error(
      [] {
        parse_msh(msh22("1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", "1 4 2 1 1 1 2 3 4\n", "4", "2"), "t.msh");
      },
      "t.msh:14: ", "expected an element number");
  expect_error(
      [] { parse_msh(msh22("1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", "1 4 2 1 1 1 2 3 4\n", "-4"), "t.msh"); },
      "t.msh:", "");
}

TEST(MshErrors, NodeIndexOutOfRange) {
  expect_error(
      [] { parse_msh(msh22("1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", "1 4 2 1 1 1 2 3 99\n"), "t.msh"); },
      "t.msh:13: ", "element refers to node 99, which is not in $Nodes");
  expect_error(
      [] { parse_msh(msh22("1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", "1 4 2 1 1 1 2 3 -4\n"), "t.msh"); },
      "t.msh:13: ", "not in $Nodes");
  expect_error([] { parse_msh(msh22("1 0 0 0\n2 1 0 0\n2 0 1 0\n4 0 0 1\n"), "t.msh"); },
               "t.msh:", "duplicate node tag 2");
}

TEST(MshErrors, NonFiniteCoordinates) {
  expect_error([] { parse_msh(msh22("1 0 0 0\n2 nan 0 0\n3 0 1 0\n4 0 0 1\n"), "t.msh"); },
               "t.msh:7: ", "a finite number");
  expect_error([] { parse_msh(msh22("1 0 0 0\n2 1 0 0\n3 0 inf 0\n4 0 0 1\n"), "t.msh"); },
               "t.msh:8: ", "a finite number");
  expect_error([] { parse_msh(msh22("1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1e999\n"), "t.msh"); },
               "t.msh:9: ", "a finite number");
}

TEST(MshErrors, UnknownElementType) {
  expect_error(
      [] {
        parse_msh(msh22("1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", "1 11 2 1 1 1 2 3 4 1 2 3 4 1 2\n"), "t.msh");
      },
      "t.msh:13: ", "unsupported Gmsh element type 11 (10-node tetrahedron)");
  expect_error(
      [] { parse_msh(msh22("1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n", "1 99 2 1 1 1 2 3 4\n"), "t.msh"); },
      "t.msh:13: ", "unsupported Gmsh element type 99");
}

TEST(MshErrors, Version41CountMismatchAndBadPhysicalName) {
  const std::string v41 =
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 5 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 "
      "1\n"
      "$EndNodes\n";
  expect_error([&] { parse_msh(v41, "t.msh"); }, "t.msh:14: ", "announces 5 nodes, the blocks hold 4");
  expect_error(
      [] {
        parse_msh("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n2 1 wall\n$EndPhysicalNames\n",
                  "t.msh");
      },
      "t.msh:6: ", "double quotes");
}

TEST(MshErrors, TruncatedBinary) {
  std::string binary = "$MeshFormat\n4.1 1 8\n";
  const int one = 1;
  binary.append(reinterpret_cast<const char*>(&one), sizeof one);
  binary += "\n$EndMeshFormat\n$Nodes\n";
  const std::uint64_t header[4] = {1, 1000000000, 1, 1000000000};
  binary.append(reinterpret_cast<const char*>(header), sizeof header);
  const int block[3] = {3, 1, 0};
  binary.append(reinterpret_cast<const char*>(block), sizeof block);
  expect_error([&] { parse_msh(binary, "t.msh"); }, "t.msh:", "unexpected end of file in binary data");
}

// A valid one-tetrahedron SU2 file; tests break one part of it.
std::string su2(const std::string& element = "10 0 1 2 3 0",
                const std::string& points = "0 0 0 0\n1 0 0 1\n0 1 0 2\n0 0 1 3\n",
                const std::string& header = "NDIME= 3",
                const std::string& markers = "NMARK= 1\nMARKER_TAG= wall\nMARKER_ELEMS= 1\n5 0 2 1\n") {
  return header + "\nNELEM= 1\n" + element + "\nNPOIN= 4\n" + points + markers;
}

TEST(Su2Errors, ValidBaseFileReads) {
  const MixedMesh mesh = parse_su2(su2(), "t.su2");
  EXPECT_EQ(mesh.cell_count(CellType::tetrahedron), 1u);
  EXPECT_NEAR(signed_volume(CellType::tetrahedron, mesh.points, mesh.cell(CellType::tetrahedron, 0)), 1.0 / 6,
              1e-15);
  EXPECT_EQ(mesh.marker_names, std::vector<std::string>{"wall"});
  // Comments, "NPOIN= total owned" and trailing FFD boxes of SU2's shape design.
  const MixedMesh commented = parse_su2(
      "% mesh\nNDIME= 3 % three\nNELEM= 1\n10 0 1 2 3 0\nNPOIN= 4 4\n0 0 0 0\n1 0 0 1\n0 1 0 2\n0 0 1 3\n"
      "NMARK= 0\nFFD_NBOX= 1\nFFD_NLEVEL= 1\nFFD_TAG= box\n",
      "t.su2");
  EXPECT_EQ(commented.points.size(), 4u);
  EXPECT_TRUE(commented.marker_names.empty());
}

TEST(Su2Errors, EmptyOrForeignFile) {
  expect_error([] { parse_su2("", "t.su2"); }, "t.su2:1: ", "no NDIME= line");
  expect_error([] { parse_su2("% only a comment\n", "t.su2"); }, "t.su2:1: ", "no NDIME= line");
  expect_error([] { parse_su2("hello world\n", "t.su2"); }, "t.su2:1: ", "expected a 'KEYWORD= value' line");
  expect_error([] { parse_su2(su2("10 0 1 2 3", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n", "NDIME= 4"), "t.su2"); },
               "t.su2:1: ", "NDIME must be 2 or 3");
}

TEST(Su2Errors, TruncatedFile) {
  const std::string whole = su2();
  expect_error([&] { parse_su2(whole.substr(0, whole.find("0 1 0 2")), "t.su2"); },
               "t.su2:6: ", "unexpected end of file, expected 4 point lines, found 2");
  expect_error([&] { parse_su2(whole.substr(0, whole.find("5 0 2 1")), "t.su2"); },
               "t.su2:", "unexpected end of file, expected 1 MARKER_ELEMS lines");
}

TEST(Su2Errors, WrongCounts) {
  expect_error(
      [] { parse_su2("NDIME= 3\nNELEM= 2\n10 0 1 2 3\nNPOIN= 4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n", "t.su2"); },
      "t.su2:4: ", "expected an element type, found 'NPOIN='");
  expect_error([] { parse_su2("NDIME= 3\nNELEM= -1\n", "t.su2"); }, "t.su2:2: ", "non-negative integer");
}

TEST(Su2Errors, NodeIndexOutOfRange) {
  expect_error([] { parse_su2(su2("10 0 1 2 7"), "t.su2"); },
               "t.su2:3: ", "node index 7 out of range (NPOIN= 4)");
  expect_error([] { parse_su2(su2("10 0 1 2 -3"), "t.su2"); }, "t.su2:3: ", "invalid node index '-3'");
  expect_error(
      [] {
        parse_su2(su2("10 0 1 2 3", "0 0 0 0\n1 0 0 1\n0 1 0 2\n0 0 1 3\n", "NDIME= 3",
                      "NMARK= 1\nMARKER_TAG= wall\nMARKER_ELEMS= 1\n5 0 2 12\n"),
                  "t.su2");
      },
      "t.su2:12: ", "node index 12 out of range");
}

TEST(Su2Errors, NonFiniteCoordinates) {
  expect_error([] { parse_su2(su2("10 0 1 2 3", "0 0 0\n1 nan 0\n0 1 0\n0 0 1\n"), "t.su2"); },
               "t.su2:6: ", "point 1: invalid coordinate 'nan'");
  expect_error([] { parse_su2(su2("10 0 1 2 3", "0 0 0\n1 0 0\n0 1 -inf\n0 0 1\n"), "t.su2"); },
               "t.su2:7: ", "invalid coordinate '-inf'");
  expect_error([] { parse_su2(su2("10 0 1 2 3", "0 0 0\n1 0 0\n0 1\n0 0 1\n"), "t.su2"); },
               "t.su2:7: ", "point 2 needs 3 coordinates");
}

TEST(Su2Errors, UnknownOrMisplacedElementTypes) {
  expect_error([] { parse_su2(su2("42 0 1 2 3"), "t.su2"); }, "t.su2:3: ", "unsupported SU2 element type 42");
  expect_error([] { parse_su2(su2("10 0 1 2"), "t.su2"); }, "t.su2:3: ", "needs 4 nodes");
  expect_error([] { parse_su2(su2("5 0 1 2"), "t.su2"); }, "t.su2:3: ", "is not a cell of an NDIME= 3 mesh");
  expect_error(
      [] {
        parse_su2(su2("10 0 1 2 3", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n", "NDIME= 3",
                      "NMARK= 1\nMARKER_TAG= wall\nMARKER_ELEMS= 1\n10 0 1 2 3\n"),
                  "t.su2");
      },
      "t.su2:12: ", "does not bound an NDIME= 3 mesh");
  expect_error(
      [] { parse_su2(su2("10 0 1 2 3", "0 0 0\n1 0 0\n0 1 0\n0 0 1\n", "NDIME= 3", "NZONE= 2\n"), "t.su2"); },
      "t.su2:9: ", "multi-zone");
}

TEST(VtuErrors, MissingGarbageAndUnsupportedCells) {
  expect_error([] { read_vtu(scratch("does_not_exist.vtu")); }, scratch("does_not_exist.vtu").string() + ": ",
               "cannot open");
  const std::filesystem::path garbage = scratch("garbage.vtu");
  std::ofstream(garbage)
      << "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece NumberOfPoints=\"4\"";
  expect_error([&] { read_vtu(garbage); }, garbage.string() + ": ", "");

  // A voxel (VTK type 11) and float points: the float points are fine, the voxel not.
  vtkNew<vtkUnstructuredGrid> grid;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  for (int corner = 0; corner < 8; ++corner)
    points->InsertNextPoint(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
  grid->SetPoints(points);
  const vtkIdType tetrahedron[4] = {0, 1, 2, 4};
  const vtkIdType voxel[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  grid->InsertNextCell(10, 4, tetrahedron);
  grid->InsertNextCell(11, 8, voxel);
  const std::filesystem::path path = scratch("voxel.vtu");
  vtkNew<vtkXMLUnstructuredGridWriter> writer;
  writer->SetInputData(grid);
  writer->SetFileName(path.string().c_str());
  ASSERT_EQ(writer->Write(), 1);
  expect_error([&] { read_vtu(path); }, path.string() + ": ", "cell 1 has VTK cell type 11 (voxel)");

  // Only the tetrahedron, with a node index past the points.
  vtkNew<vtkUnstructuredGrid> broken;
  broken->SetPoints(points);
  const vtkIdType outside[4] = {0, 1, 2, 40};
  broken->InsertNextCell(10, 4, outside);
  writer->SetInputData(broken);
  ASSERT_EQ(writer->Write(), 1);
  expect_error([&] { read_vtu(path); }, path.string() + ": ",
               "cell 0 refers to point 40, out of range (8 points)");

  // As ParaView saves: float points, raw appended data, 64-bit headers, zlib.
  vtkNew<vtkUnstructuredGrid> good;
  good->SetPoints(points);
  good->InsertNextCell(10, 4, tetrahedron);
  writer->SetInputData(good);
  writer->SetHeaderTypeToUInt64();
  writer->EncodeAppendedDataOff();
  writer->SetCompressorTypeToZLib();
  ASSERT_EQ(writer->Write(), 1);
  const MixedMesh mesh = read_vtu(path);
  EXPECT_EQ(mesh.cell_count(CellType::tetrahedron), 1u);
  EXPECT_NEAR(signed_volume(CellType::tetrahedron, mesh.points, mesh.cell(CellType::tetrahedron, 0)), 1.0 / 6,
              1e-7);
}

TEST(CgnsErrors, MissingAndForeignFiles) {
  expect_error([] { read_cgns(scratch("does_not_exist.cgns")); },
               scratch("does_not_exist.cgns").string() + ": ", "cannot open");
  const std::filesystem::path garbage = scratch("garbage.cgns");
  std::ofstream(garbage) << "this is not an HDF5 or ADF file\n";
  expect_error([&] { read_cgns(garbage); }, garbage.string() + ": ", "CGNS");
}

TEST(WriteErrors, InvalidMeshesAndUnknownFormatsAreRefused) {
  MixedMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Index nodes[4] = {0, 1, 2, 9};
  mesh.add_cell(CellType::tetrahedron, nodes);
  for (const char* file : {"bad.vtu", "bad.msh", "bad.su2", "bad.cgns"}) {
    expect_error([&] { write_mesh(mesh, scratch(file)); }, scratch(file).string() + ": ",
                 "node 9 out of range");
    EXPECT_FALSE(std::filesystem::exists(scratch(file))) << file;
  }
  expect_error([&] { write_mesh(mesh, scratch("bad.stl")); }, scratch("bad.stl").string() + ": ",
               "unknown mesh format '.stl'");
}

}  // namespace
