#include "mixmesh/surface/surface_conversion.hpp"

#include <array>

namespace mixmesh {

MixedMesh to_mixed_mesh(const SurfaceMesh& surface) {
  MixedMesh mesh;
  mesh.points = surface.points;
  for (const StructuredPatch& patch : surface.structured) {
    const bool split = patch.leading_edge_i >= 0;
    const int lower = mesh.marker(split ? patch.name + "_lower" : patch.name);
    const int upper = split ? mesh.marker(patch.name + "_upper") : lower;
    for (int j = 0; j + 1 < patch.nj; ++j) {
      for (int i = 0; i + 1 < patch.ni; ++i) {
        const std::array<Index, 4> quad = {patch.node(i, j), patch.node(i + 1, j), patch.node(i + 1, j + 1),
                                           patch.node(i, j + 1)};
        mesh.add_face(FaceType::quad, quad.data(), split && i >= patch.leading_edge_i ? upper : lower);
      }
    }
  }
  for (const TrianglePatch& patch : surface.unstructured) {
    const int marker = mesh.marker(patch.name);
    for (std::size_t t = 0; t + 2 < patch.triangles.size(); t += 3) {
      mesh.add_face(FaceType::triangle, patch.triangles.data() + t, marker);
    }
  }
  return mesh;
}

}  // namespace mixmesh
