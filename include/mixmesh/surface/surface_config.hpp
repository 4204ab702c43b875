// The [surface] table of a config file -> SurfaceOptions (defaults in SurfaceOptions).
//
//   [surface]
//   chordwise_cells = 200            # around the section, lower + upper
//   spanwise_cells = 80
//   leading_edge_spacing = 0.001     # arc length / local chord
//   trailing_edge_spacing = 0.002
//   root_spacing = 0.01              # fraction of the semi-span
//   tip_spacing = 0.004
//   base_cells = 4                   # across a blunt base (even)
//   [surface.wake]
//   enabled = true
//   length = 10.0                    # root chords behind the last trailing edge
//   first_spacing = 0.0              # fraction of the local chord, 0: trailing_edge_spacing
//   growth = 1.2
//   [surface.tip]
//   minimum_angle = 20.0             # degrees, at most 20.7
//   maximum_edge = 0.0               # metres, 0: longest tip-section edge
//   shape = "flat"                   # or "rounded" (half body of revolution)
//   merge_tolerance = 1e-8           # metres: imported nodes closer than this are one node
//   [[surface.import]]               # patches from files (imported_surface.hpp)
//   file = "fuselage.stl"            # relative to the config file
//   name = "fuselage"                # marker; default the file stem
//   role = "wall"                    # or "wake"
//   flip = false                     # reverse the orientation
#pragma once

#include <optional>

#include "mixmesh/config/config.hpp"
#include "mixmesh/geometry/planform.hpp"
#include "mixmesh/surface/imported_surface.hpp"
#include "mixmesh/surface/wing_surface.hpp"

namespace mixmesh {

// Reads and checks the wing-surface keys of the table and its sub-tables [surface.wake]
// and [surface.tip] (finish(): unknown keys are errors; "import" and "merge_tolerance"
// are left to read_surface_setup).
SurfaceOptions read_surface_options(config::Section& surface);

// Everything the surface stage needs from a config file: an optional [wing] (the
// generated wing surface), [surface] options and imported patches. At least one of
// [wing] and [[surface.import]] must be given.
struct SurfaceSetup {
  std::optional<WingDefinition> wing;
  SurfaceOptions options;
  std::vector<SurfaceImport> imports;
  ImportOptions import_options;
};
SurfaceSetup read_surface_setup(config::Section& root);

// The wing surface (if any) plus the imported patches, merged at coincident nodes.
SurfaceMesh build_surface(const SurfaceSetup& setup);

}  // namespace mixmesh
