// Meshes for the deformation tests: O-grids around an ellipse (an airfoil-like body),
// planar (quads near the wall, triangles outside) and extruded in z as hexahedra,
// prisms, tetrahedra or pyramids, with markers "wall", "farfield" and, for volume
// meshes, the end planes "bottom" (z = 0) and "top" (z = height).
#pragma once

#include <cmath>
#include <vector>

#include "reference_cells.hpp"

namespace mixmesh::testing {

struct OGrid {
  int around = 48;          // nodes around the body
  int outward = 16;         // node rings from the wall to the far field
  double semi_major = 1.0;  // ellipse x semi-axis
  double semi_minor = 0.2;  // ellipse y semi-axis
  double outer_radius = 8.0;
  double first_spacing = 0.01;  // wall-normal height of the first layer
  int quad_layers = 6;          // planar: quads below this ring, triangles above
  int layers_z = 3;             // volume: cell layers in z
  double height = 1.0;
};

// Ring j, node i: geometric stretching from the ellipse to a circle.
inline Vector3 o_grid_point(const OGrid& grid, int i, int j) {
  const double angle = 2.0 * M_PI * i / grid.around;
  const Vector3 wall(grid.semi_major * std::cos(angle), grid.semi_minor * std::sin(angle), 0.0);
  const Vector3 outer(grid.outer_radius * std::cos(angle), grid.outer_radius * std::sin(angle), 0.0);
  // Fraction s_j of the way out, geometric from first_spacing / distance.
  const double span = grid.outer_radius - grid.semi_major;
  const double first = grid.first_spacing / span;
  double ratio = 1.1;
  for (int iteration = 0; iteration < 200; ++iteration)  // solve first (r^n − 1)/(r − 1) = 1
    ratio = std::pow(1.0 + (ratio - 1.0) / first, 1.0 / (grid.outward - 1));
  const double s = first * (std::pow(ratio, j) - 1.0) / (ratio - 1.0);
  // Wall-normal start: offset along the ellipse normal, blended into the circle.
  const Vector3 normal =
      Vector3(std::cos(angle) / grid.semi_major, std::sin(angle) / grid.semi_minor, 0).normalized();
  const Vector3 along_normal = wall + normal * s * span;
  const double blend = std::min(1.0, s * 4.0);
  return (1.0 - blend) * along_normal + blend * ((1.0 - s) * wall + s * outer);
}

inline MixedMesh planar_o_grid(const OGrid& grid) {
  MixedMesh mesh;
  for (int j = 0; j < grid.outward; ++j)
    for (int i = 0; i < grid.around; ++i) mesh.points.push_back(o_grid_point(grid, i, j));
  auto id = [&](int i, int j) { return static_cast<Index>(j * grid.around + (i % grid.around)); };
  for (int j = 0; j + 1 < grid.outward; ++j)
    for (int i = 0; i < grid.around; ++i) {
      // Counter-clockwise: outward first, then along +θ.
      const Index quad[4] = {id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)};
      if (j < grid.quad_layers) {
        mesh.planar_cells[1].nodes.insert(mesh.planar_cells[1].nodes.end(), quad, quad + 4);
        mesh.planar_cells[1].markers.push_back(0);
      } else {
        const Index first[3] = {quad[0], quad[1], quad[2]};
        const Index second[3] = {quad[0], quad[2], quad[3]};
        for (const Index* triangle : {first, second}) {
          mesh.planar_cells[0].nodes.insert(mesh.planar_cells[0].nodes.end(), triangle, triangle + 3);
          mesh.planar_cells[0].markers.push_back(0);
        }
      }
    }
  const int wall = mesh.marker("wall");
  const int farfield = mesh.marker("farfield");
  for (int i = 0; i < grid.around; ++i) {
    mesh.boundary_edges.nodes.insert(mesh.boundary_edges.nodes.end(), {id(i + 1, 0), id(i, 0)});
    mesh.boundary_edges.markers.push_back(wall);
    mesh.boundary_edges.nodes.insert(mesh.boundary_edges.nodes.end(),
                                     {id(i, grid.outward - 1), id(i + 1, grid.outward - 1)});
    mesh.boundary_edges.markers.push_back(farfield);
  }
  return mesh;
}

// Tags every boundary face of the cells by position: wall (inside r < 0.9 outer
// radius), farfield, bottom (z = 0), top (z = height).
inline void tag_o_grid_boundary(MixedMesh& mesh, const OGrid& grid) {
  const FaceConnectivity faces = match_faces(mesh);
  const int wall = mesh.marker("wall");
  const int farfield = mesh.marker("farfield");
  const int bottom = mesh.marker("bottom");
  const int top = mesh.marker("top");
  for (const CellFace& face : faces.boundary) {
    Index nodes[4];
    const int count = face_nodes(mesh, face, nodes);
    Vector3 centre = Vector3::Zero();
    bool flat_bottom = true;
    bool flat_top = true;
    for (int local = 0; local < count; ++local) {
      const Vector3& point = mesh.points[static_cast<std::size_t>(nodes[local])];
      centre += point / count;
      flat_bottom = flat_bottom && std::abs(point.z()) < 1e-12;
      flat_top = flat_top && std::abs(point.z() - grid.height) < 1e-12;
    }
    const int marker = flat_bottom                                         ? bottom
                       : flat_top                                          ? top
                       : centre.head<2>().norm() < 0.9 * grid.outer_radius ? wall
                                                                           : farfield;
    mesh.add_face(count == 3 ? FaceType::triangle : FaceType::quad, nodes, marker);
  }
}

enum class VolumeKind { hexahedron, prism, tetrahedron, pyramid, hex_and_prism };

inline MixedMesh volume_o_grid(const OGrid& grid, VolumeKind kind) {
  MixedMesh mesh;
  const int rings = grid.outward;
  for (int k = 0; k <= grid.layers_z; ++k)
    for (int j = 0; j < rings; ++j)
      for (int i = 0; i < grid.around; ++i) {
        Vector3 point = o_grid_point(grid, i, j);
        point.z() = grid.height * k / grid.layers_z;
        mesh.points.push_back(point);
      }
  auto id = [&](int i, int j, int k) {
    return static_cast<Index>((k * rings + j) * grid.around + (i % grid.around));
  };
  for (int k = 0; k < grid.layers_z; ++k)
    for (int j = 0; j + 1 < rings; ++j)
      for (int i = 0; i < grid.around; ++i) {
        // Corner (a, b, c) = offsets along i, j, k; bottom face counter-clockwise from +z.
        auto corner = [&](int a, int b, int c) { return id(i + a, j + b, k + c); };
        const Index hex[8] = {corner(0, 0, 0), corner(1, 0, 0), corner(1, 1, 0), corner(0, 1, 0),
                              corner(0, 0, 1), corner(1, 0, 1), corner(1, 1, 1), corner(0, 1, 1)};
        VolumeKind here = kind;
        if (kind == VolumeKind::hex_and_prism)
          here = j < grid.quad_layers ? VolumeKind::hexahedron : VolumeKind::prism;
        switch (here) {
          case VolumeKind::hexahedron:
          case VolumeKind::hex_and_prism:
            mesh.add_cell(CellType::hexahedron, hex);
            break;
          case VolumeKind::prism: {
            const Index first[6] = {hex[0], hex[1], hex[2], hex[4], hex[5], hex[6]};
            const Index second[6] = {hex[0], hex[2], hex[3], hex[4], hex[6], hex[7]};
            mesh.add_cell(CellType::prism, first);
            mesh.add_cell(CellType::prism, second);
            break;
          }
          case VolumeKind::tetrahedron: {
            // Freudenthal split along the (0,0,0)–(1,1,1) diagonal: conforming between cells.
            const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
            for (const auto& order : axes) {
              int offset[3] = {0, 0, 0};
              Index tet[4];
              tet[0] = corner(0, 0, 0);
              for (int step = 0; step < 3; ++step) {
                offset[order[step]] = 1;
                tet[step + 1] = corner(offset[0], offset[1], offset[2]);
              }
              mesh.add_cell(CellType::tetrahedron, tet);
            }
            break;
          }
          case VolumeKind::pyramid: {
            Vector3 centre = Vector3::Zero();
            for (Index node : hex) centre += mesh.points[static_cast<std::size_t>(node)] / 8.0;
            const Index apex = static_cast<Index>(mesh.points.size());
            mesh.points.push_back(centre);
            for (const LocalFace& face : hexahedron_descriptor.faces) {
              const Index pyramid[5] = {hex[face.nodes[0]], hex[face.nodes[1]], hex[face.nodes[2]],
                                        hex[face.nodes[3]], apex};
              mesh.add_cell(CellType::pyramid, pyramid);
            }
            break;
          }
        }
      }
  reference::orient_positively(mesh);
  tag_o_grid_boundary(mesh, grid);
  return mesh;
}

}  // namespace mixmesh::testing
