// The inputs of the surface stage, and the stage itself.
#pragma once

#include <optional>

#include "mixmesh/geometry/planform.hpp"
#include "mixmesh/surface/imported_surface.hpp"
#include "mixmesh/surface/wing_surface.hpp"

namespace mixmesh {

// Everything the surface stage needs: an optional wing (the generated wing surface),
// the surface options and imported patches (the pipeline's surface_options.hpp reads it
// from a config file).
struct SurfaceSetup {
  std::optional<WingDefinition> wing;
  SurfaceOptions options;
  std::vector<SurfaceImport> imports;
  ImportOptions import_options;
};

// The wing surface (if any) plus the imported patches, merged at coincident nodes.
SurfaceMesh build_surface(const SurfaceSetup& setup);

}  // namespace mixmesh
