// The [wing] table of a config file -> WingDefinition.
//
//   [wing]
//   airfoil_file = "airfoils/onera_d.dat"   # Selig or Lednicer, relative to the config
//   # naca = "0012"                          # or an analytic section (4 or 5 digits)
//   naca_points_per_side = 201
//   naca_closed_trailing_edge = true
//   blunt_trailing_edge = "close"           # or "base"
//   twist_axis = 0.25                       # fraction of the chord
//   # classic planform ...
//   root_chord = 0.8059
//   semi_span = 1.1963
//   leading_edge_sweep = 30.0               # degrees
//   trailing_edge_sweep = 15.8              # degrees, or taper = 0.562
//   root_twist = 0.0                        # degrees, linear to tip_twist
//   tip_twist = 0.0
//   dihedral = 0.0                          # degrees
//   # ... or span stations (then none of the classic keys):
//   [[wing.station]]
//   y = 0.0, chord = 1.0, leading_edge_x = 0.0, leading_edge_z = 0.0, twist = 0.0
//   airfoil_file / naca                     # optional, else the wing's section
//
// Every error names config-file:line:column, or airfoil-file:line for bad airfoil data.
#pragma once

#include "mixmesh/config/config.hpp"
#include "mixmesh/geometry/planform.hpp"

namespace mixmesh {

// Reads and checks the table (calls finish(): unknown keys are errors).
WingDefinition read_wing_definition(config::Section& wing);

}  // namespace mixmesh
