// Far field (Wild §II.F, method.md §6): tetrahedra between the interface hull and an
// outer boundary, by TetGen's constrained Delaunay tetrahedralisation.
//
//   input   points (the layered mesh's, so hull indices are global), the hull triangles
//           (right-hand normal into the far field), optionally a metric per hull node
//   output  MixedMesh whose points are the input points followed by the new ones, with
//           tetrahedra (VTK order, positive volume) and boundary triangles tagged
//           `symmetry_marker` / `farfield_marker`. The hull faces are left untagged: they
//           are interior once the layers are added, so assembly is a concatenation of
//           cells plus the layers' own boundary faces.
//
// The boundary handed to TetGen is closed: the hull; if the hull is open, a symmetry
// plane y = symmetry_y triangulated between the hull's footprint and the far-field edge
// (CGAL 2D constrained Delaunay, graded by the size field); and a half sphere (full
// sphere for a closed hull) or a box of half-width radius_in_chords × chord. TetGen runs
// with -p (PLC), -Y (the boundary triangles are kept exactly, so the tetrahedra match
// the layers' faces), -q (radius-edge bound) and -m (a size per boundary point, growing
// linearly away from the hull). A self-intersecting boundary is located with -d and
// reported as mixmesh::Error.
//
// Anisotropic sizing (the default of mixmesh::generate; it needs the hull's metrics)
// continues the layer growth in metric space: from
// every hull node, points are placed along the smoothed outward normal at the normal
// spacing its metric gives, growing by `layer_growth`, for `maximum_layers` points or
// until the spacing reaches the node's smallest tangential spacing (the cell is
// isotropic); then the isotropic grading takes over.
// A second TetGen run (no -q, sliver flips on) in the original coordinates takes the
// layer points and the quality run's points away from them.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "mixmesh/core/error.hpp"
#include "mixmesh/core/log.hpp"
#include "mixmesh/mesh/mixed_mesh.hpp"
#include "mixmesh/metric/metric.hpp"
#include "mixmesh/precondition/precondition.hpp"

namespace mixmesh {

enum class FarFieldShape { sphere, box };
enum class FarFieldSizing { isotropic, anisotropic };

// The boundary handed to TetGen intersects itself (TetGen's own test, -d, found it);
// `location` is the centre of the first intersecting boundary triangle.
class HullIntersectionError : public Error {
 public:
  HullIntersectionError(const std::string& message, const Vector3& where)
      : Error(message), location(where), locations{where} {}
  HullIntersectionError(const std::string& message, std::vector<Vector3> where)
      : Error(message),
        location(where.empty() ? Vector3::Zero() : where.front()),
        locations(std::move(where)) {}
  Vector3 location;                // the first crossing
  std::vector<Vector3> locations;  // every crossing found (centres of the crossing triangles)
};

struct FarFieldOptions {
  FarFieldShape shape = FarFieldShape::sphere;
  FarFieldSizing sizing = FarFieldSizing::isotropic;  // generate's default is anisotropic
  double reference_chord = 0.0;                       // 0: the hull's extent in x
  double radius_in_chords = 20.0;                     // sphere radius or box half-width
  double farfield_size_in_chords = 2.0;               // edge length on the outer boundary
  double size_gradient = 0.25;        // size grows by this much per unit distance from the hull
  double radius_edge_ratio = 1.5;     // TetGen -q bound
  // TetGen's flips after each pass act on tetrahedra whose largest dihedral angle is
  // above this (TetGen's own -q default is 165°). Flips are cheaper than the sliver
  // pass's weighed operations, which then start from fewer slivers (docs/farfield.md).
  double flip_dihedral = 150.0;
  double symmetry_y = 0.0;            // the symmetry plane of an open hull
  double symmetry_tolerance = 1e-9;   // × chord: how far off the plane a footprint node may be
  double plane_minimum_angle = 25.0;  // degrees, quality bound of the symmetry-plane triangles
  // Anisotropic sizing.
  double layer_growth = 1.25;  // ratio of successive normal spacings
  // Points per column. One layer continuing the hull's cells gives the tetrahedra on the
  // hull the cells' size and orientation; the isotropic grading does the rest. Taller
  // columns add points and flat tetrahedra without changing those on the hull (ONERA M6:
  // docs/farfield.md, "How many layers").
  int maximum_layers = 1;
  // The first point of a column stands this fraction of its normal spacing over its
  // node. At a whole spacing its tetrahedra to the hull nodes across a cell's diagonal
  // are √3 long in the metric; at h they are √(2 + h²), within [0.6, 1.6] with the
  // vertical edge h for h in [0.6, 0.75] (docs/farfield.md, "First height").
  double first_layer_height = 0.7;
  double minimum_metric_distance = 0.6;  // inserted points closer than this (metric) are dropped
  // Layer points lower than edge_protection × (L²/(8τ) − τ/2) over the hull (L the
  // longest hull edge at the node, τ the body's thickness below it) are dropped: they
  // would make hull edges non-Delaunay over thin parts of the body (docs/farfield.md).
  double edge_protection = 0.25;
  // Points of the exact pass closer to the hull surface than this fraction of their
  // distance to the nearest hull node are dropped (they would make flat tetrahedra).
  double hull_clearance = 0.2;
  // Hull nodes under a cap (FarFieldInput::capped_nodes) carry their caps' metric, set
  // by generate's metric stage; false: the layer cells' alone, as before caps counted.
  bool cap_metrics = true;
  // A column of a capped node stops where its point would lie within this fraction of
  // its height of the plane of one of the node's hull faces: beside the steep long face
  // of a cap over a narrow quad it would make a flat tetrahedron with that face.
  double cap_face_clearance = 0.2;
  // Preconditioning of the point set before TetGen (method.md §5; shear + whitening
  // when on). The quality pass runs in the mapped space; where the map's rounding
  // leaves tetrahedra flat once mapped back (coplanar boundary parts), and always for
  // anisotropic sizing, the final pass triangulates again in the original coordinates.
  // Off by default: it costs time and changes little on the test wings (docs/farfield.md).
  bool precondition = false;
  PreconditionOptions preconditioning;
  // The preconditioned quality pass is abandoned after this many seconds (TetGen's
  // refinement can cycle in the mapped space) or when TetGen fails there, and run
  // again without the map (a warning says so). 0: no limit.
  unsigned precondition_time_limit = 600;
  // Every other TetGen pass is stopped after this many seconds: its refinement can cycle
  // without end on a hull with thin features (a random wing's stacks lowered round
  // crossings: the quality pass ran for over 50 minutes), and a design loop must not
  // wait for ever. The M6's passes take about 10 s. 0: no limit.
  unsigned tetgen_time_limit = 900;
  // When set, the closed boundary is written there as legacy VTK after each transform:
  // boundary.vtk (as built), sheared.vtk (S⁻¹ P) and preconditioned.vtk (F P).
  std::filesystem::path dump_directory;
  std::string symmetry_marker = "symmetry";
  std::string farfield_marker = "farfield";
};

struct FarFieldInput {
  std::vector<Vector3> points;
  std::vector<std::array<Index, 3>> hull;
  // Metrics of hull nodes (parallel lists); required for anisotropic sizing.
  std::vector<Index> metric_nodes;
  std::vector<Matrix3> metrics;
  // Hull nodes at the base of a cap: the cap's apex stands over them, and a
  // column of their own would run up beside the cap's steep faces.
  std::vector<Index> capped_nodes;
  // Points inside the body (inside the hull, not in the far field), which TetGen
  // leaves empty. When none is given, a point just behind the largest hull triangle.
  std::vector<Vector3> holes;
};

// Distribution of the metric lengths of the edges of tetrahedra with a face on the
// hull, each measured in the log-Euclidean mean metric of that face's nodes.
struct MetricLengthReport {
  std::size_t edges = 0;
  double within_range = 0.0;  // fraction in [0.6, 1.6]
  double median = 0.0;
  double lower_decile = 0.0;
  double upper_decile = 0.0;
};

struct FarFieldResult {
  MixedMesh mesh;
  std::size_t input_point_count = 0;
  std::size_t boundary_points = 0;  // symmetry-plane and far-field points added to the boundary
  std::size_t layer_points = 0;     // anisotropic points offered to TetGen
  std::size_t steiner_points = 0;   // points TetGen added in the volume
  std::size_t flat_tetrahedra = 0;  // with no positive volume (0 unless TetGen failed silently)
  double chord = 0.0;
  MetricLengthReport hull_lengths;  // only when metrics were given
};

FarFieldResult farfield(const FarFieldInput& input, const FarFieldOptions& options = {},
                        const Log& log = Log());

MetricLengthReport hull_metric_lengths(const MixedMesh& mesh, const std::vector<std::array<Index, 3>>& hull,
                                       const std::vector<Index>& metric_nodes,
                                       const std::vector<Matrix3>& metrics);

}  // namespace mixmesh
