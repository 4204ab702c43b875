// Small hand-built surfaces for the marching tests: a flat plate with a wake-like
// sheet, a cylinder patch, a regular triangle patch, and wings from the surface
// generator at test resolution.
#pragma once

#include <cmath>
#include <string>

#include "mixmesh/geometry/airfoil.hpp"
#include "mixmesh/geometry/planform.hpp"
#include "mixmesh/march/march_layers.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"
#include "mixmesh/surface/wing_surface.hpp"

namespace mixmesh::march_surfaces {

// A structured ni x nj patch of points given by shape(i, j), appended to `surface`.
template <class Shape>
StructuredPatch grid_patch(SurfaceMesh& surface, const std::string& name, int ni, int nj, Shape shape) {
  StructuredPatch patch;
  patch.name = name;
  patch.ni = ni;
  patch.nj = nj;
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      patch.nodes.push_back(static_cast<Index>(surface.points.size()));
      surface.points.push_back(shape(i, j));
    }
  return patch;
}

// The plate z = 0, 0 <= x <= 1, 0 <= y <= 1, normal +z, root edge in the symmetry plane.
inline SurfaceMesh flat_plate(int ni = 11, int nj = 9) {
  SurfaceMesh surface;
  surface.structured.push_back(grid_patch(surface, "plate", ni, nj, [&](int i, int j) {
    return Vector3(static_cast<double>(i) / (ni - 1), static_cast<double>(j) / (nj - 1), 0.0);
  }));
  surface.symmetry_tolerance = 1e-9;
  return surface;
}

// A quarter of the cylinder x^2 + z^2 = 1 (convex side out), axis along y.
inline SurfaceMesh cylinder_patch(int ni = 17, int nj = 9) {
  SurfaceMesh surface;
  surface.structured.push_back(grid_patch(surface, "cylinder", ni, nj, [&](int i, int j) {
    const double angle = 0.5 * std::acos(-1.0) * (1.0 - static_cast<double>(i) / (ni - 1));
    return Vector3(std::cos(angle), static_cast<double>(j) / (nj - 1), std::sin(angle));
  }));
  surface.symmetry_tolerance = 1e-9;
  return surface;
}

// A regular triangulated hexagon patch of `rings` rings in the plane z = 0, normal +z.
inline SurfaceMesh triangle_patch(int rings = 4, double size = 1.0) {
  SurfaceMesh surface;
  TrianglePatch patch;
  patch.name = "triangles";
  // Points on a triangular lattice inside the hexagon of radius rings * size.
  const double h = size;
  std::vector<std::pair<int, int>> lattice;
  auto inside = [&](int a, int b) {
    return std::abs(a) <= rings && std::abs(b) <= rings && std::abs(a + b) <= rings;
  };
  std::vector<std::vector<Index>> id(static_cast<std::size_t>(2 * rings + 1),
                                     std::vector<Index>(static_cast<std::size_t>(2 * rings + 1), -1));
  for (int a = -rings; a <= rings; ++a)
    for (int b = -rings; b <= rings; ++b)
      if (inside(a, b)) {
        id[static_cast<std::size_t>(a + rings)][static_cast<std::size_t>(b + rings)] =
            static_cast<Index>(surface.points.size());
        surface.points.emplace_back(h * (a + 0.5 * b), h * (0.5 * std::sqrt(3.0) * b), 0.0);
      }
  auto node = [&](int a, int b) {
    return inside(a, b) ? id[static_cast<std::size_t>(a + rings)][static_cast<std::size_t>(b + rings)] : -1;
  };
  for (int a = -rings; a <= rings; ++a)
    for (int b = -rings; b <= rings; ++b) {
      const Index p = node(a, b), q = node(a + 1, b), r = node(a, b + 1), s = node(a + 1, b - 1);
      if (p >= 0 && q >= 0 && r >= 0) patch.triangles.insert(patch.triangles.end(), {p, q, r});
      if (p >= 0 && s >= 0 && q >= 0) patch.triangles.insert(patch.triangles.end(), {p, s, q});
    }
  surface.unstructured.push_back(patch);
  return surface;
}

struct TestWing {
  double root_chord = 1.0;
  double semi_span = 3.0;
  double sweep_degrees = 0.0;
  double taper = 1.0;
  double tip_twist_degrees = 0.0;
  std::string naca = "0012";
  int chordwise_cells = 64;
  int spanwise_cells = 16;
  bool blunt_base = false;  // the open NACA trailing edge closed by a base
};

inline SurfaceMesh wing(const TestWing& test) {
  ClassicPlanform planform;
  planform.root_chord = test.root_chord;
  planform.semi_span = test.semi_span;
  planform.leading_edge_sweep_degrees = test.sweep_degrees;
  planform.taper = test.taper;
  planform.tip_twist_degrees = test.tip_twist_degrees;
  SurfaceOptions options;
  options.chordwise_cells = test.chordwise_cells;
  options.spanwise_cells = test.spanwise_cells;
  options.wake.length = 2.0;
  NacaOptions naca;
  naca.closed_trailing_edge = !test.blunt_base;
  WingDefinition definition = classic_wing(planform, naca_airfoil(test.naca, naca));
  if (test.blunt_base) definition.blunt_trailing_edge = TrailingEdge::base;
  return generate_wing_surface(definition, options);
}

// Counts cells that are not valid by cell_shape.
inline int invalid_cell_count(const MixedMesh& mesh) {
  int invalid = 0;
  for (CellType type : all_cell_types)
    for (std::size_t cell = 0; cell < mesh.cell_count(type); ++cell)
      invalid += !cell_shape(type, mesh.points, mesh.cell(type, cell)).valid();
  return invalid;
}

}  // namespace mixmesh::march_surfaces
