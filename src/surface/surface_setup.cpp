// The surface stage from its setup: the generated wing and the imported patches.
#include "mixmesh/surface/surface_setup.hpp"

namespace mixmesh {

SurfaceMesh build_surface(const SurfaceSetup& setup) {
  if (setup.imports.empty()) return generate_wing_surface(*setup.wing, setup.options);
  ImportOptions import_options = setup.import_options;
  SurfaceMesh surface;
  if (setup.wing) {
    surface = generate_wing_surface(*setup.wing, setup.options);
    import_options.symmetry_y = surface.symmetry_y;
    import_options.symmetry_tolerance = surface.symmetry_tolerance;
  }
  SurfaceMesh imported = import_surfaces(setup.imports, import_options);
  append_surface(surface, imported);
  surface.symmetry_y = import_options.symmetry_y;
  surface.symmetry_tolerance = import_options.symmetry_tolerance;
  merge_coincident_nodes(surface, import_options.merge_tolerance);
  return surface;
}

}  // namespace mixmesh
