// The [surface] table of a config file -> SurfaceOptions (defaults in SurfaceOptions),
// and the surface stage's whole setup from a config file.
//
//   [surface]
//   chordwise_cells = 200            # around the section, lower + upper
//   spanwise_cells = 80
//   leading_edge_spacing = 0.001     # arc length / local chord
//   trailing_edge_spacing = 0.002
//   root_spacing = 0.01              # fraction of the semi-span
//   tip_spacing = 0.004
//   base_cells = 4                   # across a blunt base (even), at most:
//   base_face_aspect = 500.0         # fewer while a base face is more than this many times
//                                    # shorter than the spanwise faces (0: off)
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

#include "mixmesh/config/config.hpp"
#include "mixmesh/surface/surface_setup.hpp"

namespace mixmesh {

// Reads and checks the wing-surface keys of the table and its sub-tables [surface.wake]
// and [surface.tip] (finish(): unknown keys are errors; "import" and "merge_tolerance"
// are left to read_surface_setup).
SurfaceOptions read_surface_options(config::Section& surface);

// An optional [wing], the [surface] options and the [[surface.import]] patches; at least
// one of [wing] and [[surface.import]] must be given.
SurfaceSetup read_surface_setup(config::Section& root);

}  // namespace mixmesh
