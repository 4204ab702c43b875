// CGNS files written by other tools: a MIXED element section in CGNS numbering,
// an element-list boundary condition on a family and a vertex-based one.
#include <gtest/gtest.h>

#include <cgnslib.h>

#include <filesystem>

#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"

using namespace mixmesh;

namespace {

void check(int status) {
  ASSERT_EQ(status, CG_OK) << cg_get_error();
}

// A unit cube cut into a tetrahedron-free pair: prism (PENTA_6, bottom triangle
// counter-clockwise seen from the top, the CGNS convention) and a tetrahedron on top.
void write_foreign_file(const std::filesystem::path& path) {
  int file = 0;
  check(cg_open(path.string().c_str(), CG_MODE_WRITE, &file));
  int base = 0;
  check(cg_base_write(file, "Base", 3, 3, &base));
  cgsize_t size[3] = {7, 2, 0};
  int zone = 0;
  check(cg_zone_write(file, base, "Zone", size, CGNS_ENUMV(Unstructured), &zone));
  const double x[7] = {0, 1, 0, 0, 1, 0, 0};
  const double y[7] = {0, 0, 1, 0, 0, 1, 0};
  const double z[7] = {0, 0, 0, 1, 1, 1, 2};
  int coordinate = 0;
  check(cg_coord_write(file, base, zone, CGNS_ENUMV(RealDouble), "CoordinateX", x, &coordinate));
  check(cg_coord_write(file, base, zone, CGNS_ENUMV(RealDouble), "CoordinateY", y, &coordinate));
  check(cg_coord_write(file, base, zone, CGNS_ENUMV(RealDouble), "CoordinateZ", z, &coordinate));
  // Element 1: PENTA_6 1-2-3 / 4-5-6; element 2: TETRA_4 4-5-6-7.
  const cgsize_t cells[] = {CGNS_ENUMV(PENTA_6), 1, 2, 3, 4, 5, 6, CGNS_ENUMV(TETRA_4), 4, 5, 6, 7};
  const cgsize_t cell_offsets[] = {0, 7, 12};
  int section = 0;
  check(cg_poly_section_write(file, base, zone, "Cells", CGNS_ENUMV(MIXED), 1, 2, 0, cells, cell_offsets,
                              &section));
  // Element 3: the floor triangle (outward: 1-3-2); elements 4-5: two side faces.
  const cgsize_t floor[] = {1, 3, 2};
  check(cg_section_write(file, base, zone, "Floor", CGNS_ENUMV(TRI_3), 3, 3, 0, floor, &section));
  const cgsize_t sides[] = {1, 2, 5, 4, 3, 1, 4, 6};
  check(cg_section_write(file, base, zone, "Sides", CGNS_ENUMV(QUAD_4), 4, 5, 0, sides, &section));
  int family = 0;
  check(cg_family_write(file, base, "Ground", &family));
  const cgsize_t floor_elements[] = {3};
  int condition = 0;
  check(cg_boco_write(file, base, zone, "floor_bc", CGNS_ENUMV(FamilySpecified), CGNS_ENUMV(PointList), 1,
                      floor_elements, &condition));
  check(cg_boco_gridlocation_write(file, base, zone, condition, CGNS_ENUMV(FaceCenter)));
  check(cg_goto(file, base, "Zone_t", zone, "ZoneBC_t", 1, "BC_t", condition, "end"));
  check(cg_famname_write("Ground"));
  // Vertex condition on the x = 0 plane: marks quad 5 (nodes 3 1 4 6), not quad 4.
  const cgsize_t plane[] = {1, 3, 4, 6, 7};
  check(cg_boco_write(file, base, zone, "symmetry", CGNS_ENUMV(BCWall), CGNS_ENUMV(PointList), 5, plane,
                      &condition));
  check(cg_close(file));
}

TEST(CgnsForeign, MixedSectionFamiliesAndVertexConditionsRead) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "mixmesh_io_foreign.cgns";
  write_foreign_file(path);
  if (HasFatalFailure()) return;
  const MixedMesh mesh = read_cgns(path);
  ASSERT_EQ(mesh.cell_count(CellType::prism), 1u);
  ASSERT_EQ(mesh.cell_count(CellType::tetrahedron), 1u);
  EXPECT_NEAR(signed_volume(CellType::prism, mesh.points, mesh.cell(CellType::prism, 0)), 0.5, 1e-15);
  EXPECT_NEAR(signed_volume(CellType::tetrahedron, mesh.points, mesh.cell(CellType::tetrahedron, 0)), 1.0 / 6,
              1e-15);
  ASSERT_EQ(mesh.face_count(FaceType::triangle), 1u);
  ASSERT_EQ(mesh.face_count(FaceType::quad), 2u);
  auto marker_name = [&](FaceType type, std::size_t face) {
    return mesh.marker_names.at(static_cast<std::size_t>(mesh.faces(type).markers.at(face)));
  };
  EXPECT_EQ(marker_name(FaceType::triangle, 0), "Ground");  // family name, not the BC name
  EXPECT_EQ(marker_name(FaceType::quad, 0), "Sides");       // unmarked: its section's name
  EXPECT_EQ(marker_name(FaceType::quad, 1), "symmetry");    // all nodes in the vertex set
}

}  // namespace
