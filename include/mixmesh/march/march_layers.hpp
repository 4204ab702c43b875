// Marching of the boundary layer: hexahedra from the quads and prisms from the
// triangles of a SurfaceMesh, layer by layer away from the wall (Wild §II.A–B).
//
//   march_layers(surface, options, log) -> BoundaryLayer
//
// Each surface node marches along one line per side: wall nodes have one line, the
// nodes of wake patches (floating sheets, C-type) have one line above and one below
// the sheet; wall faces that touch a wake node (the trailing edge) take the line on
// their side of the sheet, so the wing's layers and the wake's layers join with no gap;
// where wall faces across the sheet (a tip cap) meet the sheet's free edge, one cap
// triangle marches on both lines (a junction), so the layers stay closed there too.
// Every cell that is emitted has passed cell_shape (positive volume, subtetrahedra
// and corner Jacobians) and a self-intersection test of the new layer front; where a
// layer cannot be added the column of that face stops (see BoundaryLayer).
#pragma once

#include <string>
#include <vector>

#include "mixmesh/core/log.hpp"
#include "mixmesh/march/spacing.hpp"
#include "mixmesh/mesh/mixed_mesh.hpp"
#include "mixmesh/surface/surface_mesh.hpp"

namespace mixmesh {

enum class MarchMethod {
  smoothed,  // parabolic marching with the face-weighted Laplace corrector
  normal     // baseline: plain extrusion along area-averaged normals, no smoothing
};

// How the corrector solves the equations of a new layer.
enum class LayerSolve {
  sweeps,  // Jacobi sweeps, the weights updated every sweep
  sparse   // per outer iteration: weights frozen, one sparse solve of the whole layer
};

// Columns near `centre` stop by `layer` at the latest, and their neighbours slope down
// to them as round any stop (how generate lowers the layers where the hull it built
// intersected itself).
struct ForcedStop {
  Vector3 centre = Vector3::Zero();
  double radius = 0.0;  // surface faces whose centroid or a node lies within it
  int layer = 0;
};

struct MarchOptions {
  SpacingOptions spacing;
  MarchMethod method = MarchMethod::smoothed;
  // Jacobi sweeps of the implicit corrector per layer (each sweep is parallel); with
  // LayerSolve::sparse the most outer iterations per layer.
  int sweeps = 12;
  LayerSolve layer_solve = LayerSolve::sweeps;
  // LayerSolve::sparse stops when no node moved by more than this fraction of its
  // marching step in the last outer iteration.
  double layer_tolerance = 1e-4;
  // Control functions: the first `orthogonal_layers` layers march exactly along the
  // wall-orthogonal direction; over the next `release_layers` layers the smoothed
  // direction takes over (smoothstep blend).
  int orthogonal_layers = 3;
  int release_layers = 20;
  // Predictor: weight of the previous marching direction against the new layer
  // normal (keeps marching lines straight where the normals turn).
  double direction_memory = 0.5;
  // Passes of direction averaging with the neighbouring lines per released layer.
  int direction_smoothing_passes = 10;
  // Smoothed march: largest angle (degrees) between successive segments of a line; a
  // line the corrector and the smoothing would turn further is turned by this much, and
  // the rest of the turn is left to the next layers (the projections into a sheet end or
  // the symmetry plane and the retries of failing columns come after it). 0: no limit.
  double maximum_turn_degrees = 1.0;
  // Wake sheets: the layers of a wake line thicken downstream like a wedge of this
  // half-angle (degrees) and their growth relaxes towards equal steps
  // (wake_layer_steps, with the line's distance from the nearest trailing-edge line);
  // lines that start on a wall keep the wall's steps. 0: every line keeps the wall's
  // steps to the sheet's end.
  double wake_spread_degrees = 6.0;
  // The outermost layer is at least this fraction of the shortest front edge at its
  // line high. The interface splits that layer's cells about their centre, and the two
  // tetrahedra on an outer quad are as flat as the cell is against the quad's short
  // side: on a cell a twentieth as high as that side their largest dihedral angle is
  // 176-177 deg, at a quarter 161-166 deg. 0: the outermost layer keeps the growth
  // law's step.
  double outer_layer_height = 0.25;
  // Safety: halve the step of the nodes of a failed cell this many times before the
  // column stops.
  int step_reductions = 3;
  bool check_self_intersection = true;
  std::vector<ForcedStop> forced_stops;
  // Marker names of the boundary faces the march creates (wall faces keep their
  // patch names).
  std::string symmetry_marker = "symmetry";
  std::string outer_hull_marker = "outer_hull";
  std::string hull_side_marker = "hull_side";
};

// Nodes whose growth stopped early, summarised for the report.
struct StoppedRegion {
  int layer = 0;                // layer the columns stopped at
  int faces = 0;                // surface faces whose column stopped there
  Vector3 location{0, 0, 0};    // centre of those faces on the wall
  double thickness_lost = 0.0;  // metres: the wall steps of the layers they did not reach
};

struct MarchReport {
  int layers_requested = 0;
  int layers_completed = 0;  // layers every column reached
  double first_spacing = 0.0;
  double total_thickness = 0.0;        // sum of the steps of the full layers
  int reduced_steps = 0;               // node steps shortened to keep a cell valid
  int stopped_faces = 0;               // surface faces whose column stopped early
  int stopped_nodes = 0;               // surface nodes on such faces
  int blended_faces = 0;               // of those, stopped to slope down to a stopped neighbour
  std::vector<StoppedRegion> stopped;  // grouped by layer
  // Lines near a concave corner of a sheet and a wall (a blunt base with the wake
  // leaving its middle) that keep every layer in a thinner stack, and the thinnest
  // such stack (m; 0 when there is none).
  int thinned_lines = 0;
  double thinnest_stack = 0.0;
  // Corrector: sweeps or outer iterations over all layers, and the largest last change
  // of a layer (node change of its last iteration / node step).
  int corrector_iterations = 0;
  double corrector_change = 0.0;
  // Junctions closed (a wall fan across a sheet meeting the sheet's free edge: the tip
  // trailing edge), the smallest corner Jacobian / edge lengths of the pyramids of their
  // cut stacks (1 when there are none) and the largest dihedral angle of their two
  // tetrahedra (0 when there are none; the one on the wrap's triangle is a needle, whose
  // scaled Jacobian is small by design).
  int junctions = 0;
  double junction_minimum_scaled_jacobian = 1.0;
  double junction_largest_dihedral_degrees = 0.0;
  double seconds = 0.0;
};

// The marched layers.
//
//   mesh              hexahedra (from quads) and prisms (from triangles), VTK order;
//                     points 0 .. surface.points.size()-1 are the surface points;
//                     boundary faces: wall faces (marker = patch name), side faces in
//                     the symmetry plane, the outer hull (top of every column and the
//                     sides exposed where a neighbouring column stopped lower) and
//                     the sides along free edges of the front (wake end, wake tip):
//                     outer_hull, except that the hull faces of a sheet's columns (their
//                     tops and free-edge sides) are hull_side, whose cells the interface
//                     caps instead of splitting them (InterfaceOptions::capped_marker)
//   column_points     per marching line: its point per layer (0 = the wall point)
//   column_node       per marching line: its surface node
//   column_side       per marching line: 0 wall, +1 above a wake sheet, -1 below
//   face_columns      per front face: its marching lines (3 or 4, flow-side normal)
//   face_layers       per front face: number of cells in its column
//   face_patch        per front face: its patch (index into region_names)
//   face_wall         per front face: 1 on a wall patch, 0 on a wake sheet
//   hexahedron_face / prism_face, hexahedron_layer / prism_layer
//                     per cell: its front face and layer (0 = on the wall); a cell
//                     is outermost when its layer + 1 == face_layers[face]
//   pyramid_face, tetrahedron_face
//                     per cell: the split face whose first cell it is part of, at a
//                     junction of a wall fan across a sheet with the sheet's free edge
//                     (the tip trailing edge); the prism between the two sheet lines
//                     there is listed with that face and layer 0
//   region_names      region tag of every cell = index of its patch here
struct BoundaryLayer {
  MixedMesh mesh;
  std::vector<std::vector<Index>> column_points;
  std::vector<Index> column_node;
  std::vector<int> column_side;
  std::vector<std::vector<int>> face_columns;
  std::vector<int> face_layers;
  std::vector<int> face_patch;
  std::vector<char> face_wall;
  std::vector<int> hexahedron_face, hexahedron_layer;
  std::vector<int> prism_face, prism_layer;
  std::vector<int> pyramid_face, tetrahedron_face;
  std::vector<std::string> region_names;
  MarchReport report;
};

// Throws mixmesh::Error for a surface that cannot be marched: indices out of range,
// degenerate faces, an edge shared by more than two faces on one side, bad options.
BoundaryLayer march_layers(const SurfaceMesh& surface, const MarchOptions& options, const Log* log = nullptr);

}  // namespace mixmesh
