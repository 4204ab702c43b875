// The corrector of the ARA method (Martineau & Georgala §4.3.3, eq. 12–21): the linear
// system behind the smoothing of the mesh velocity and the angular velocity on the dual
// mesh, and two solvers for it. Internal to the deform module.
//
// The fixed point of eq. 19, u_i = Σ_j σ_ij ũ_j / Σ_j σ_ij, is the linear system
//
//   D_i u_i − Σ_{cells j} σ_ij u_j = s_i,   D_i = Σ_j σ_ij (cells and wall faces),
//
// where s_i holds everything that does not change during the solve: the Dirichlet wall
// faces, σ_iw ũ_w, and the rigid transport of every neighbour, σ_ij (R_j − I)(x_i − x_j).
// The matrix is symmetric (σ_ij = σ_ji) and positive definite where a cell connects to a
// wall, so point Gauss–Seidel (the paper's solver) and Jacobi-preconditioned conjugate
// gradients converge to the same field. Both stop on the same measure: the r.m.s. over
// the cells of |(s_i − (A u)_i) / D_i|, the change one Jacobi update would make.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <vector>

#include "deform/dual_mesh.hpp"
#include "deform/wall_faces.hpp"

namespace mixmesh::deform::detail {

// body(item) for item in [0, count), in parallel.
template <class Body>
void parallel_items(std::size_t count, const Body& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t item = range.begin(); item != range.end(); ++item) body(item);
                    });
}

// The matrix in CSR form: interior neighbours with σ_ij (eq. 20), the wall faces of every
// cell with σ_iw, and the diagonal D. It depends on the undeformed mesh alone.
struct SmoothingStencil {
  std::vector<std::size_t> offsets;
  std::vector<Index> neighbour;
  std::vector<double> weight;
  std::vector<std::size_t> wall_offsets;
  std::vector<Index> wall;  // index into WallFaces::faces
  std::vector<double> wall_weight;
  std::vector<double> diagonal;
};

// σ from Baker's diffusivity τ (eq. 13, 17, 20): τ_ij A_ij / |x_i − x_j| with
// τ_ij = ½(τ_i + τ_j); wall faces use the cell's τ and the distance to the face centre.
SmoothingStencil build_smoothing_stencil(const DualMesh& dual, const WallFaces& walls,
                                         const std::vector<Vector3>& centres,
                                         const std::vector<Vector3>& wall_centres,
                                         const std::vector<double>& diffusivity,
                                         const std::vector<Vector3>& points);

// Rigid transport of the neighbours' values (see AraOptions::smoothing): R − I of every
// cell and wall face, and the points they turn about. Null members: plain eq. 19.
struct Transport {
  const std::vector<Eigen::Matrix3d>* cell_turn = nullptr;
  const std::vector<Eigen::Matrix3d>* wall_turn = nullptr;
  const std::vector<Vector3>* centres = nullptr;
  const std::vector<Vector3>* wall_centres = nullptr;
};

// s of the system above for the wall values `wall_values`.
std::vector<Vector3> smoothing_source(const SmoothingStencil& stencil,
                                      const std::vector<Vector3>& wall_values, const Transport& transport);

struct SolveSettings {
  double relaxation = 0.8;  // ε of eq. 19 (Gauss–Seidel only)
  double tolerance = 1e-4;  // on the r.m.s. Jacobi change, relative to `scale`
  double scale = 1.0;
  int max_iterations = 500;
};
struct SolveResult {
  int iterations = 0;
  double residual = 0.0;  // r.m.s. Jacobi change / scale at the end
};

// Point Gauss–Seidel, one colour at a time so that the cells of a colour update in
// parallel and every update sees its neighbours' newest values (eq. 19).
SolveResult gauss_seidel(std::vector<Vector3>& values, const std::vector<Vector3>& source,
                         const SmoothingStencil& stencil, const std::vector<std::vector<Index>>& colours,
                         const SolveSettings& settings);

// Conjugate gradients with the diagonal D as preconditioner, each of the three
// components on its own; sums in a fixed order, so the result does not depend on the
// thread count or the scheduling.
SolveResult conjugate_gradient(std::vector<Vector3>& values, const std::vector<Vector3>& source,
                               const SmoothingStencil& stencil, const SolveSettings& settings);

}  // namespace mixmesh::deform::detail
