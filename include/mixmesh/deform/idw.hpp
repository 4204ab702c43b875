// Inverse distance weighting (IDW) mesh deformation on plain data.
//
//   IdwInput   volume_points   #V 3-vectors: the nodes to move
//              bodies          boundary node sets, each moving (prescribed displacements,
//                              optional per-node rotations) or fixed (displacement zero)
//   IdwResult  displacements   #V 3-vectors, one per volume point
//
// Two forms (docs/idw.md):
//   simple    u_i = Σ_j w(r_ij) v_j(x_i) / Σ_j w(r_ij) over every boundary node j of every
//             body, w = r^-p (optimal-parameters paper eq. 1). With per-node rotations R_j,
//             v_j(x) = u_j + (R_j − I)(x − x_j), which reproduces a rigid motion exactly.
//             Evaluated exactly (O(V·B)) or by a tree code (O(V log B)).
//   rotation  per moving body, u_i = u^T (1 − ψ)^st + u^R (1 − ψ)^sr (eq. 2–4) with the
//             reference nodes of the body nearest to x_i, a least-squares rigid fit of
//             their motion, and ψ = d_body / (d_body + d_rest) (reconstructed), the
//             distances to the nearest face of each body where faces are given.
//
// Q: Why does the rotation form sum over moving bodies?
// A: Eq. (2) is written for one moving boundary; ψ of body b counts every other body
//    (fixed or moving) as "fixed", so each body's motion fades to zero at the others and
//    the sum leaves every body's neighbourhood moving with that body.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh::deform {

struct IdwBody {
  std::string name;  // for messages and reports
  bool moving = true;
  std::vector<Vector3> positions;      // #B boundary nodes
  std::vector<Vector3> displacements;  // #B for moving bodies; empty (= zero) for fixed ones
  // Optional #B rotations of the surface around each node (orthonormal, det +1). When
  // present the rotation form uses their average instead of fitting one.
  std::vector<Eigen::Matrix3d> rotations;
  // Optional surface faces of the body: indices into `positions`, unused slots -1
  // (triangles: 3 nodes, quads: 4, split 0-1-2 / 0-2-3; planar meshes: edges, 2). When
  // present, the rotation form's ψ takes the distance to the nearest face instead of
  // the nearest node, so that ψ is smooth between the nodes (docs/idw.md).
  std::vector<std::array<Index, 4>> faces;
};

// n·x = offset; a volume node on the plane keeps its n-coordinate.
struct IdwSymmetryPlane {
  Vector3 normal = Vector3::UnitY();  // need not be unit, must be non-zero
  double offset = 0.0;
};

struct IdwInput {
  std::vector<Vector3> volume_points;
  std::vector<IdwBody> bodies;
  std::vector<IdwSymmetryPlane> symmetry_planes;
};

enum class IdwForm { simple, rotation };

struct IdwOptions {
  IdwForm form = IdwForm::rotation;

  // simple form: w = r^-p (eq. 1).
  double exponent = 3.0;
  // simple form: sum over every boundary node (tests, reference) instead of the tree code.
  bool exact = false;
  // Tree code acceptance: a cluster is replaced by its aggregate when the bound on the
  // error it adds to a node's displacement is at most tolerance × (largest boundary
  // displacement) (idw_tree.hpp). The default keeps the tree within 1e-6 body lengths of the
  // exact sum on the benchmark case (docs/idw.md).
  double tree_tolerance = 4e-6;
  int leaf_size = 16;

  // rotation form: exponents st and sr of eq. (2); automatic per body when unset
  // (idw_exponents). An infinite sr drops the rotation term.
  std::optional<double> translation_exponent;
  std::optional<double> rotation_exponent;
  // Number of nearest boundary nodes of a body that form the reference set of eq. (3–4).
  int reference_count = 8;
  // α_ij ∝ r_ij^-q over the reference set.
  double reference_exponent = 2.0;
  // The distance to the other bodies in ψ is found to within this relative accuracy
  // (reusing the previous point's nearest node when that is provably close enough;
  // 0 = exact search for every point). Exact by default: the reused distance changes
  // from one point to the next by up to this fraction, ψ and the displacement with it,
  // and on the ONERA M6 mixed mesh that noise folded micrometre-thin wake hexahedra.
  double distance_accuracy = 0.0;
  // Automatic exponents (see idw_exponents): rotation counts as dominant when its share
  // of the rigid-fit motion is at least `rotation_dominance`; otherwise sr is
  // `translation_rotation_exponent`, large but finite, so that the small rotation of a
  // translation-dominated step is still carried (docs/idw.md, parameter study).
  double rotation_dominance = 0.1;
  double translation_rotation_exponent = 8.0;

  // Volume nodes within this distance (relative to the boundary's bounding-box
  // diagonal) of a symmetry plane count as on it.
  double symmetry_tolerance = 1e-9;
  // Volume nodes per parallel task.
  std::size_t grain_size = 256;
};

// Rigid-fit split of a body's motion and the exponents chosen from it.
struct IdwBodyReport {
  std::string name;
  double rotation_angle = 0.0;  // radians, of the best rigid fit
  double rotation_share = 0.0;  // rotational part / (rotational + translational), r.m.s.
  double translation_exponent = 1.0;
  double rotation_exponent = 2.0;  // infinity: rotation term dropped
};

struct IdwResult {
  std::vector<Vector3> displacements;  // one per volume point
  std::vector<IdwBodyReport> bodies;   // rotation form: one per moving body
  // Tree code: clusters replaced by aggregates and single node terms, summed over all
  // volume points, and the largest a-posteriori bound on a node's displacement error.
  std::size_t cluster_terms = 0;
  std::size_t node_terms = 0;
  double error_bound = 0.0;
};

// The deformation: displacement of every volume point. Throws mixmesh::Error for sizes
// that disagree, no boundary node, non-finite data, bad options.
IdwResult idw_deform(const IdwInput& input, const IdwOptions& options = {});

// Automatic exponents from the optimal-parameters study: st = 1 (best in [1, 2] for
// rotation and translation alike); sr = 2 when rotation dominates the body's motion
// (rotation_share ≥ rotation_dominance), otherwise a large sr
// (translation_rotation_exponent, the paper's advice for translation). Explicit options
// override either.
IdwBodyReport idw_exponents(const IdwBody& body, const IdwOptions& options);

inline constexpr double idw_no_rotation_term = std::numeric_limits<double>::infinity();

}  // namespace mixmesh::deform
