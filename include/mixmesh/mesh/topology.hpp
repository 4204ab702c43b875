// Element topology: one constexpr table per cell type, in VTK node order.
// Every algorithm (face matching, volumes, quality, writers, the interface split)
// reads these tables; nothing else encodes node numbering.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace mixmesh {

enum class CellType : std::uint8_t { tetrahedron = 0, pyramid = 1, prism = 2, hexahedron = 3 };
enum class FaceType : std::uint8_t { triangle = 0, quad = 1 };

inline constexpr std::array<CellType, 4> all_cell_types = {CellType::tetrahedron, CellType::pyramid,
                                                           CellType::prism, CellType::hexahedron};
inline constexpr std::array<FaceType, 2> all_face_types = {FaceType::triangle, FaceType::quad};

// A face of a cell: local node numbers, ordered so that the right-hand normal points
// out of the cell. node_count is 3 or 4; unused slots hold -1.
struct LocalFace {
  int node_count;
  std::array<int, 4> nodes;
};

// A corner: a node and its three neighbours, ordered so that the determinant of the
// three edge vectors is positive in a valid cell (used for corner Jacobians).
struct Corner {
  int node;
  std::array<int, 3> neighbours;
};

struct CellDescriptor {
  std::string_view name;
  int node_count;
  int face_count;
  int edge_count;
  int corner_count;
  std::array<LocalFace, 6> faces;
  std::array<std::array<int, 2>, 12> edges;
  std::array<Corner, 8> corners;
};

// clang-format off: the tables keep one face or edge list per line.

//  Tetrahedron           3
//                       /|\        nodes 0-1-2 seen from 3 run counter-clockwise
//                      / | \       (positive volume: (x1-x0)x(x2-x0).(x3-x0) > 0)
//                     /  2  \      .
//                    / .   . \     .
//                   0---------1
inline constexpr CellDescriptor tetrahedron_descriptor{
    "tetrahedron",
    4,
    4,
    6,
    4,
    {{{3, {0, 2, 1, -1}}, {3, {0, 1, 3, -1}}, {3, {1, 2, 3, -1}}, {3, {0, 3, 2, -1}}}},
    {{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}}},
    {{{0, {1, 2, 3}}, {1, {2, 0, 3}}, {2, {0, 1, 3}}, {3, {0, 2, 1}}}}};

//  Pyramid                 4
//                        // \\        base 0-1-2-3 counter-clockwise seen from the
//                      / /   \ \      apex 4
//                    3--/-----\-2
//                   / /        \/
//                  0-----------1
inline constexpr CellDescriptor pyramid_descriptor{
    "pyramid",
    5,
    5,
    8,
    4,
    {{{4, {0, 3, 2, 1}}, {3, {0, 1, 4, -1}}, {3, {1, 2, 4, -1}}, {3, {2, 3, 4, -1}}, {3, {3, 0, 4, -1}}}},
    {{{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 4}, {2, 4}, {3, 4}}},
    {{{0, {1, 3, 4}}, {1, {2, 0, 4}}, {2, {3, 1, 4}}, {3, {0, 2, 4}}}}};

//  Prism (VTK wedge)        3---------5      VTK's order: triangle 0-1-2 is
//                           |\       /|      clockwise seen from the top 3-4-5,
//                           | \     / |      i.e. its right-hand normal points away
//                           |  \   /  |      from the top (the reverse of Gmsh and
//                           |    4    |      CGNS, whose writers permute).
//                           0----|----2      Edges 0-3, 1-4, 2-5 are the
//                            \   |   /       marching lines of a boundary layer.
//                             \  |  /
//                               \1/
inline constexpr CellDescriptor prism_descriptor{
    "prism",
    6,
    5,
    9,
    6,
    {{{3, {0, 1, 2, -1}}, {3, {3, 5, 4, -1}}, {4, {0, 3, 4, 1}}, {4, {1, 4, 5, 2}}, {4, {2, 5, 3, 0}}}},
    {{{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}}},
    {{{0, {2, 1, 3}}, {1, {0, 2, 4}}, {2, {1, 0, 5}}, {3, {4, 5, 0}}, {4, {5, 3, 1}}, {5, {3, 4, 2}}}}};

//  Hexahedron          7-----------6      bottom 0-1-2-3 counter-clockwise seen
//                     /|          /|      from the top 4-5-6-7; node k+4 above k
//                    / |         / |
//                   4-----------5  |
//                   |  3--------|--2
//                   | /         | /
//                   |/          |/
//                   0-----------1
inline constexpr CellDescriptor hexahedron_descriptor{
    "hexahedron",
    8,
    6,
    12,
    8,
    {{{4, {0, 3, 2, 1}},
      {4, {4, 5, 6, 7}},
      {4, {0, 1, 5, 4}},
      {4, {1, 2, 6, 5}},
      {4, {2, 3, 7, 6}},
      {4, {3, 0, 4, 7}}}},
    {{{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}}},
    {{{0, {1, 3, 4}},
      {1, {2, 0, 5}},
      {2, {3, 1, 6}},
      {3, {0, 2, 7}},
      {4, {7, 5, 0}},
      {5, {4, 6, 1}},
      {6, {5, 7, 2}},
      {7, {6, 4, 3}}}}};

// clang-format on

inline constexpr const CellDescriptor& descriptor(CellType type) {
  switch (type) {
    case CellType::tetrahedron:
      return tetrahedron_descriptor;
    case CellType::pyramid:
      return pyramid_descriptor;
    case CellType::prism:
      return prism_descriptor;
    case CellType::hexahedron:
      break;
  }
  return hexahedron_descriptor;
}

inline constexpr int node_count(CellType type) {
  return descriptor(type).node_count;
}
inline constexpr int node_count(FaceType type) {
  return type == FaceType::triangle ? 3 : 4;
}
inline constexpr std::string_view name(CellType type) {
  return descriptor(type).name;
}
inline constexpr std::string_view name(FaceType type) {
  return type == FaceType::triangle ? "triangle" : "quad";
}
inline constexpr int index(CellType type) {
  return static_cast<int>(type);
}
inline constexpr int index(FaceType type) {
  return static_cast<int>(type);
}

// VTK cell type numbers (vtkCellType.h), shared by the .vtu and .su2 formats.
inline constexpr int vtk_cell_number(CellType type) {
  constexpr std::array<int, 4> numbers = {10, 14, 13, 12};
  return numbers[index(type)];
}
inline constexpr int vtk_face_number(FaceType type) {
  return type == FaceType::triangle ? 5 : 9;
}

}  // namespace mixmesh
