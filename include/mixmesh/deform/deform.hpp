// The deformation framework: from a Motion to the prescribed motion of every boundary
// node, then a method (ara | idw) moves the volume nodes, then the result is checked.
//
//   Motion ─► boundary_motion(mesh, motion, step) ─► BoundaryMotion
//   BoundaryMotion + mesh ─► DeformationMethod::move ─► new points
//   new points ─► slide symmetry nodes into their plane ─► validate ─► DeformResult
//
// Works on volume meshes (tet, pyramid, prism, hex with boundary faces) and on planar
// meshes (MixedMesh::planar_cells in z = 0 with boundary_edges).
//
// A method is pluggable: derive from DeformationMethod and implement move(). The
// object lives across the steps of a sequence, so it may cache whatever depends only
// on the connectivity (ARA keeps its nearest boundary faces). Each method's header
// declares its options struct; make_method() (methods.hpp) builds a method by name.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mixmesh/core/log.hpp"
#include "mixmesh/deform/motion.hpp"
#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh::deform {

enum class NodeRole : std::uint8_t {
  interior,    // moved by the method
  prescribed,  // boundary node of a moving body or of a fixed marker: displacement given
  sliding,     // symmetry node: moved by the method, then projected into its plane
};

// What a boundary marker does.
enum class MarkerRole : std::uint8_t { fixed, moving, sliding };

// The boundary conditions one step hands to a method. Every vector has one entry per
// mesh point (or per marker for marker_roles).
struct BoundaryMotion {
  std::vector<NodeRole> roles;
  // Prescribed nodes: the displacement from the input mesh; zero elsewhere.
  std::vector<Vector3> displacement;
  // Prescribed nodes: the rotation vector (axis × angle, radians) of the surface
  // around the node from the input mesh to the target (exact for rigid bodies; for mode
  // and surface motions a least-squares fit of the node's boundary neighbours, each
  // weighted by its direction, 1/r², detail::fit_rotation); zero for fixed nodes and
  // elsewhere. ARA's faces and IDW's rotation form carry it over lever arms of metres.
  std::vector<Vector3> rotation;
  // Sliding nodes: unit normal of their symmetry plane; zero elsewhere.
  std::vector<Vector3> slide_normal;
  // Prescribed nodes of a moving body: its index in Motion::bodies; -1 elsewhere.
  std::vector<int> body;
  // Indexed by marker id (mesh.marker_names).
  std::vector<MarkerRole> marker_roles;

  std::size_t count(NodeRole role) const;
  // Largest prescribed displacement length.
  double largest_displacement() const;
};

// The boundary conditions of step `step` (1-based) of `motion` on `mesh`, where
// `mesh` is the mesh the step deforms and `reference` the initial mesh (the same
// object unless motion.incremental). Throws mixmesh::Error for an unknown marker, a
// node moved by two bodies in different ways, a field node index out of range, a
// curved symmetry marker.
BoundaryMotion boundary_motion(const MixedMesh& mesh, const MixedMesh& reference, const Motion& motion,
                               int step);

namespace detail {
struct DualMesh;
}

class DeformationMethod {
 public:
  virtual ~DeformationMethod() = default;
  virtual std::string name() const = 0;
  // The framework's dual mesh (cells as nodes) of the mesh the next move() gets, for a
  // method that would build one itself; null when there is none. The framework builds
  // it for its quality measures anyway, and on a 430 k-point mesh a build takes half a
  // second. Valid until that move() returns.
  virtual void offer_dual_mesh(const detail::DualMesh* dual) { (void)dual; }
  // New positions of all points of `mesh`. Prescribed nodes must end at
  // mesh.points + displacement; sliding nodes may leave their plane (the framework
  // projects them back). Throws mixmesh::Error when the method cannot proceed.
  virtual std::vector<Vector3> move(const MixedMesh& mesh, const BoundaryMotion& boundary,
                                    const Log& log) = 0;
};

// ---------------------------------------------------------------- quality and result

struct QualitySummary {
  double min_scaled_jacobian = 0.0;
  std::size_t invalid_cells = 0;
  // Near-wall orthogonality: for every node of a fixed or moving wall, the angle in
  // degrees between the wall normal and the grid line leaving the wall at that node.
  double max_wall_angle = 0.0;
  double mean_wall_angle = 0.0;
  // Tetrahedra only: η (Martineau & Georgala eq. 28) in 10 bins of width 0.0745 on
  // [0, 0.745]; η ≤ 0 counts into the first bin.
  std::array<std::size_t, 10> sliver_histogram{};
};

struct DeformOptions {
  // Write even when cells stay inverted (the CLI then names the file "…invalid…").
  bool keep_invalid = false;
  // Appended in brackets to the error of a step whose cells stay inverted (what the
  // caller offers instead, e.g. a command-line flag).
  std::string invalid_advice;
};

struct InvalidCell {
  std::string entity;  // "hexahedron", "quad", …
  std::size_t index = 0;
  Vector3 location = Vector3::Zero();
};

struct DeformResult {
  MixedMesh mesh;
  bool valid = false;
  std::size_t invalid_count = 0;
  std::vector<InvalidCell> invalid_examples;  // the first few
  QualitySummary before;
  QualitySummary after;
  // Largest change of the wall angle (WallLines) of a node of a moving body between
  // input and output, degrees, and where it happens; the same for fixed walls.
  double max_wall_angle_change = 0.0;
  Vector3 max_wall_angle_change_location = Vector3::Zero();
  double fixed_wall_angle_change = 0.0;
  double seconds = 0.0;
};

QualitySummary summarise_quality(const MixedMesh& mesh, const std::vector<MarkerRole>& marker_roles);

// Near-wall grid lines: for every node of a fixed or moving wall, the edge that leaves
// the wall most nearly along its normal, chosen once on the undeformed mesh and kept
// for the deformed one. wall_angles gives, per wall node, the angle in degrees between
// that edge and the wall normal (the mean of the adjacent wall faces' normals).
struct WallLines {
  std::vector<Index> wall_nodes;
  std::vector<Index> line_ends;  // -1 where no edge leaves the wall
  // The wall faces (planar: edges), CSR, each oriented into the domain.
  std::vector<std::size_t> face_offsets;
  std::vector<Index> face_nodes;
};
WallLines wall_lines(const MixedMesh& mesh, const std::vector<MarkerRole>& marker_roles);
// One angle per entry of lines.wall_nodes (NaN where line_ends is -1).
std::vector<double> wall_angles(const MixedMesh& mesh, const WallLines& lines);

// One step: boundary motion, method, symmetry projection, validation, quality.
DeformResult deform_step(const MixedMesh& mesh, const MixedMesh& reference, const Motion& motion, int step,
                         DeformationMethod& method, const Log& log);

// A [[deform]] step of a generation config: a motion (keys as in a motion file, bodies
// as [[deform.body]], method options as [deform.ara]/[deform.idw]) and a `name` for its
// output files. It keeps the method's settings, not a method: each run of the step
// makes a fresh one (an ARA method keeps the nearest faces of the mesh it last moved).
// The pipeline's deform_options.hpp reads it.
struct DeformStep {
  std::string name;
  std::string where;  // file:line:column of the step, for messages
  Motion motion;
  std::function<std::unique_ptr<DeformationMethod>()> make_method;
};

// The file stem of step `step` of a motion of `steps` steps: `stem` itself for a single
// step, `stem` + "_0003" for step 3 of a sequence.
std::string step_stem(const std::string& stem, int step, int steps);

// Every step of a motion: step k deforms the initial mesh (or, when
// motion.incremental, the mesh of step k − 1) and hands its result to `each_step`,
// which may keep or write it. Stops with mixmesh::Error at the first step whose mesh
// stays invalid, unless options.keep_invalid (then each_step sees result.valid false).
void deform_sequence(const MixedMesh& mesh, const Motion& motion, DeformationMethod& method, const Log& log,
                     const DeformOptions& options,
                     const std::function<void(int step, const DeformResult& result)>& each_step);

}  // namespace mixmesh::deform
