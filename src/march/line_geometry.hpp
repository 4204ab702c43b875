// The marching lines' geometry that does not change from layer to layer or that each
// layer works out afresh from the front: normals, sheet ends, wake steps, pinched lines.
#pragma once

#include <vector>

#include "front.hpp"
#include "mixmesh/march/march_layers.hpp"

namespace mixmesh::march_detail {

Vector3 unit_or(const Vector3& vector, const Vector3& fallback);

// Column normals of the current layer from its active faces: angle-weighted corner
// normals (the direction most nearly orthogonal to all faces around a node) or, for
// the baseline, area-weighted face normals. Symmetry columns keep y = 0.
// Wake faces count with weight `wake_weight` at lines that also start on a wall face
// (the trailing edge), so the first grid line there is orthogonal to the wall.
std::vector<Vector3> column_normals(const Front& front, const std::vector<Vector3>& positions,
                                    const std::vector<char>& face_active, bool angle_weighted,
                                    const std::vector<Vector3>& fallback, const std::vector<char>& on_wall,
                                    double wake_weight);

// The step from `from` to `to` without its parts along the orthonormal `basis` of a
// line's end conormals, scaled back to its length.
Vector3 keep_in_sheet_end(const Vector3& from, const Vector3& to, const std::vector<Vector3>& basis);

// A line that starts on a wall and on a sheet leaves the sheet's plane by at least 45
// degrees on its own side. Where the wall there faces along the sheet (a blunt base
// with the wake leaving from its middle) the wall's normal lies in the sheet's plane,
// and the lines above and below would march along the same direction.
Vector3 off_the_sheet(const Vector3& normal, const Vector3& sheet_normal);

// A first line below the plane of one of its wall faces inverts that face's first cell.
// The angle-weighted normal can do that where faces of very different size and direction
// meet: at a swept wing's sharp trailing edge on the symmetry plane, the line (held in
// the plane) leaned under the upper surface's last face (random wing 12 of seed 12).
// Such a line takes the direction that sees its wall faces best (in the plane for a
// symmetry line).
void see_every_wall_face(const Front& front, const std::vector<Vector3>& points,
                         const std::vector<char>& face_active, const std::vector<char>& on_wall,
                         const std::vector<char>& junction_line, std::vector<Vector3>& normal);

// The last layer's step of each line: at least `fraction` of the shortest edge of the
// active front faces at the line (MarchOptions::outer_layer_height). Lines on no active
// face keep their step.
void raise_to_outer_height(const Front& front, const std::vector<Vector3>& current,
                           const std::vector<char>& face_active, double fraction, std::vector<double>& step);

// The step of a line towards a symmetry plane fades where the layers grow as thick as
// the line is far from the plane: the lines in the plane march in it, so a neighbour
// that keeps moving towards it (the upper side of a wing or wake with dihedral) closes
// the row of cells between them. On a wake, whose layers thicken to a metre, this
// stopped the row next to the plane on ordinary wings with 2-8 degrees of dihedral.
Vector3 fade_towards_symmetry(const Vector3& direction, double distance, double height);

// Adds to `stopping` (faces that stop at this layer) the faces that would otherwise
// meet a line in two separate fans: where the faces still growing round a line are
// split by stopped ones into groups that share no edge at the line, the layer's cells
// of different groups touch along that line alone and the hull pinches there (an edge
// on four hull faces). All but the largest group stop too, until no line is pinched.
void close_pinched_lines(const Front& front, const std::vector<char>& face_active,
                         std::vector<int>& stopping);

// Per line (and per face) what the surface fixes for all layers.
struct LineData {
  std::vector<std::vector<int>> face_neighbours;
  std::vector<char> on_wall;
  std::vector<std::vector<Vector3>> conormals;
  // Wake lines thicken and relax their growth downstream (spacing.hpp, wake_layer_steps),
  // and lines near a concave corner of a sheet and a wall keep a thinner stack
  // (concave_corners.hpp); only those lines keep their own steps (empty: the wall's).
  std::vector<std::vector<double>> own_steps;
  int thinned_lines = 0;        // lines near a concave corner whose stack was thinned
  double thinnest_stack = 0.0;  // the thinnest of those stacks (m)
  std::vector<char> junction_line;
  std::vector<Vector3> sheet_normal;
};

// `points`: the lines' surface points.
LineData line_data(const Front& front, const MarchOptions& options, const std::vector<double>& steps,
                   const std::vector<Vector3>& points);

}  // namespace mixmesh::march_detail
