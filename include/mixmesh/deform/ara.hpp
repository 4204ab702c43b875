// The ARA mesh movement method (Martineau & Georgala, AIAA 2004-614, §4.3; method.md §7):
// a predictor–corrector on the dual mesh (cell centres as nodes, faces as edges).
//
//   1. distance metrics   nearest face on the two nearest boundaries of every cell
//                         centre, exact point–face distances; α = d₂/(d₁+d₂) (eq. 2)
//   2. predictor          each centre moves rigidly with its nearest face on each
//                         boundary (eq. 9), blended by β(α) (eq. 10–11); the cell's
//                         rotation is blended the same way
//   3. corrector          smoothing of the mesh velocity u and angular velocity w with
//                         Baker's diffusivity (eq. 12–21): conjugate gradients or the
//                         paper's Gauss–Seidel on the same linear system
//   4. interpolation      each node moves with the rigid motion of its cells, weighted
//                         by pseudo-Laplacian weights (eq. 22–26)
//   5. repair             nodes of inverted cells are re-interpolated with weights that
//                         favour small and inverted cells (eq. 27), up to 10 passes
//
// A "boundary" is a connected set of wall faces (fixed or moving markers; symmetry
// markers are not walls): in a wing case the wing surface is one boundary and the far
// field another.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "mixmesh/deform/deform.hpp"

namespace mixmesh::deform {

namespace detail {
struct AraGeometry;
}

// β(α), eq. 11 (reconstructed; the extracted text reads only "β = [exp(c(α))]^γ").
//   exponential  β = ½ + ½ (1 − e^{−γ s}) / (1 − e^{−γ}),  s = 2α − 1 ∈ [0, 1]
//   linear       β = α (the original algorithm's blend)
// Both give β(1) = 1 at a boundary, β(½) = ½ on the median surface, and increase
// monotonically; a larger γ widens the near field that follows its boundary rigidly.
enum class BlendForm { exponential, linear };
double blend(double alpha, double gamma, BlendForm form);

// Predictor: rotation + translation of the nearest faces (the paper's new scheme) or
// translation only (the original algorithm, for comparison).
enum class Predictor { rotation, translation };

// Velocity smoothing (eq. 19): neighbour velocities as they are (plain), or each
// neighbour's velocity transported rigidly to the cell with the neighbour's smoothed
// rotation, u_j + (R_j − I)(x_i − x_j) (rigid_transport, the default with the
// rotation predictor). The transport makes every rigid motion a fixed point of the
// smoothing, so the rotation the predictor gives the near field survives it; plain
// eq. 19 relaxes the near-wall velocity towards a translation and skews the wall-normal
// grid lines. With the translation predictor both are the same.
enum class Smoothing { rigid_transport, plain };

// Solver of the smoothing system (eq. 19 at its fixed point, a symmetric positive
// definite system): Jacobi-preconditioned conjugate gradients (the default, far fewer
// sweeps on large meshes) or the paper's point Gauss–Seidel with relaxation ε. Both stop
// on the same r.m.s. measure and converge to the same field.
enum class Solver { conjugate_gradient, gauss_seidel };

struct AraOptions {
  Predictor predictor = Predictor::rotation;
  Smoothing smoothing = Smoothing::rigid_transport;
  Solver solver = Solver::conjugate_gradient;
  BlendForm blend_form = BlendForm::exponential;
  double gamma = 4.0;
  // Candidate boundary faces per k-d tree query; the exact distance picks among them.
  int candidates = 8;
  // Smoothing (eq. 19): global relaxation ε (Gauss–Seidel only), tolerance on the r.m.s.
  // change one Jacobi update would make, relative to the largest boundary displacement
  // (rotation: relative to the largest boundary rotation), iteration cap.
  double relaxation = 0.8;
  double tolerance = 1e-4;
  int max_iterations = 500;
  int repair_passes = 10;
  // Cache file: the nearest faces, and the geometry that depends on the undeformed mesh
  // alone (dual mesh, smoothing matrix, interpolation weights). Read when it exists (an
  // error when its faces were made for another mesh; its geometry is used only for the
  // same points and marker roles), written when it does not. Empty: cache in memory
  // only, across the steps of a sequence.
  std::filesystem::path cache_file;
  // false: the cache file keeps the nearest faces only (8 bytes per cell instead of about
  // 290); a repeat run then rebuilds the geometry.
  bool cache_geometry = true;
};

// Nearest boundary faces of every cell: faces[c] = {nearest face on the nearest
// boundary, nearest face on the second-nearest boundary} (-1 when there is only one
// boundary), as indices into the method's list of wall faces. The faces stay valid
// while the connectivity and the wall markers stay the same (mesh_hash); the points
// may move, as in a sequence of deformations.
struct NearestFaces {
  std::size_t point_count = 0;
  std::size_t cell_count = 0;
  std::size_t wall_face_count = 0;
  std::uint64_t mesh_hash = 0;  // of the cells, the boundary faces and the wall faces
  std::vector<std::array<Index, 2>> faces;
};
void write_nearest_faces(const NearestFaces& nearest, const std::filesystem::path& file);
// Throws mixmesh::Error for a file that is not a nearest-face cache.
NearestFaces read_nearest_faces(const std::filesystem::path& file);

struct AraReport {
  // Wall-clock seconds of each stage: dual mesh and wall faces, distances, predictor,
  // smoothing (stencil and both solves), interpolation, repair, and the whole move.
  double setup_seconds = 0.0;
  double distance_seconds = 0.0;
  double predictor_seconds = 0.0;
  double smoothing_seconds = 0.0;
  double interpolation_seconds = 0.0;
  double repair_seconds = 0.0;
  double total_seconds = 0.0;
  bool cache_used = false;          // nearest faces from the cache
  bool geometry_cached = false;     // dual mesh, stencil and weights of the same undeformed mesh
  bool geometry_from_file = false;  // the same, read from the cache file
  int spin_iterations = 0;
  int smoothing_iterations = 0;
  double smoothing_residual = 0.0;
  int repair_passes = 0;
  std::size_t inverted_after_interpolation = 0;
  std::size_t inverted_after_repair = 0;
};

class AraMethod : public DeformationMethod {
 public:
  explicit AraMethod(AraOptions options = {}) : options_(std::move(options)) {}
  std::string name() const override { return "ara"; }
  std::vector<Vector3> move(const MixedMesh& mesh, const BoundaryMotion& boundary, const Log& log) override;
  void offer_dual_mesh(const detail::DualMesh* dual) override { offered_dual_ = dual; }

  const AraReport& last_report() const { return report_; }
  const NearestFaces& nearest_faces() const { return nearest_; }
  // Forget the cached nearest faces and geometry (the next move starts afresh).
  void clear_cache() {
    nearest_ = {};
    geometry_.reset();
  }

 private:
  // The geometry of the undeformed mesh from memory, the cache file or afresh; true when
  // the cache file holds nearest faces only and should get the geometry added.
  bool prepare(const MixedMesh& mesh, const BoundaryMotion& boundary, const Log& log);
  // The nearest faces from memory, the cache file or a search (written to the file).
  void find_nearest(const std::vector<Vector3>& points, bool add_geometry_to_file, const Log& log);
  std::string summary() const;  // the log line of the last move

  AraOptions options_;
  NearestFaces nearest_;
  // What depends only on the undeformed mesh and its markers' roles (dual mesh, wall
  // faces, smoothing stencil, interpolation weights), reused while they stay the same.
  std::shared_ptr<detail::AraGeometry> geometry_;
  const detail::DualMesh* offered_dual_ = nullptr;  // copied into a new geometry
  AraReport report_;
};

}  // namespace mixmesh::deform
