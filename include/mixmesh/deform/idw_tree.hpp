// Tree code for the simple IDW form (optimal-parameters paper eq. 1), in the manner of
// Luke, Collins & Blades 2012: a k-d tree over the boundary nodes; a cluster far enough
// from the evaluation point is replaced by an aggregate.
//
//   positions      #B boundary nodes x_j
//   displacements  #B u_j
//   rotations      #B R_j or empty; the value of node j at x is v_j(x) = u_j + (R_j − I)(x − x_j)
//
// Aggregate of a cluster C (centroid c, radius ρ = max |x_j − c|, n nodes): with
// δ_j = x_j − c, the weight w(y) = |x − y|^-p is expanded to second order about c
// (gradient g, Hessian H = p d^-(p+2) [(p+2) r̂r̂ᵀ − I], d = |x − c|, r̂ = (x − c)/d):
//   Σ w_j          ≈ n w(c) + ½ Σ δ_jᵀ H δ_j        (the first-order term vanishes at the centroid)
//   Σ w_j a_j      ≈ w(c) Σ a_j + Σ (g·δ_j) a_j + ½ Σ (δ_jᵀ H δ_j) a_j,   a_j = u_j − (R_j − I) x_j
//   Σ w_j (R_j−I)  likewise with B_j = R_j − I
// so a cluster stores its sums of a_j, δ_j a_jᵀ and δ_j δ_jᵀ a_j (and of B_j).
// Error bound: |x − c − δ|^-p = d^-p Σ_n (|δ|/d)^n C_n^(p/2)(cos γ) (Gegenbauer), and
// |C_n^(p/2)| ≤ C_n^(p/2)(1) = binom(n + p − 1, n), so with θ = ρ/d < 1 the remainder of every
// weight is at most d^-p [(1 − θ)^-p − 1 − pθ − p(p+1)θ²/2] ≤ e = d^-p binom(p+2, 3) θ³ (1 − θ)^-(p+3)
// (Lagrange remainder of (1 − θ)^-p). A cluster is accepted when n e,
// its bound on the error of the denominator, is at most tolerance × D̃, D̃ a coarse estimate
// of the denominator (a first pass with opening angle ½). Each evaluation sums the bounds of
// the denominator (E_D) and numerator (E_N = Σ e Σ|v_j|) it accepted and reports the
// certified error bound (E_N + |u| E_D) / (D − E_D) of the displacement.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh::deform {

class IdwTree {
 public:
  struct Evaluation {
    Vector3 displacement = Vector3::Zero();
    double error_bound = 0.0;  // certified bound on |displacement − exact|
    std::size_t cluster_terms = 0;
    std::size_t node_terms = 0;
  };

  // Throws mixmesh::Error when sizes disagree, there are no nodes, exponent ≤ 0 or
  // leaf_size < 1.
  IdwTree(const std::vector<Vector3>& positions, const std::vector<Vector3>& displacements,
          const std::vector<Eigen::Matrix3d>& rotations, double exponent, int leaf_size);

  // Tree evaluation with the acceptance tolerance described above.
  Evaluation evaluate(const Vector3& point, double tolerance) const;
  // Sum over every boundary node (eq. 1 as written).
  Evaluation evaluate_exact(const Vector3& point) const;

  std::size_t node_count() const { return positions_.size(); }
  std::size_t cluster_count() const { return clusters_.size(); }

 private:
  struct Cluster {
    Vector3 centroid = Vector3::Zero();
    double radius = 0.0;
    int begin = 0, end = 0;  // range in the permuted node arrays
    int first_child = -1;    // children are first_child and first_child + 1; -1 for a leaf
  };
  // Aggregates, kept apart from the traversal data above so that a traversal touches
  // little memory; indexed like clusters_.
  struct Moments {
    Vector3 sum_a = Vector3::Zero();
    Eigen::Matrix3d moment_a = Eigen::Matrix3d::Zero();  // Σ δ_j a_jᵀ
    // Symmetric second moments, entries (xx, yy, zz, xy, xz, yz): Σ δ_k δ_l and Σ δ_k δ_l a_j.
    Eigen::Matrix<double, 6, 1> moment2 = Eigen::Matrix<double, 6, 1>::Zero();
    Eigen::Matrix<double, 3, 6> moment2_a = Eigen::Matrix<double, 3, 6>::Zero();
    double sum_displacement_norm = 0.0;  // Σ |u_j|
  };
  struct RotationMoments {
    Eigen::Matrix3d sum_b = Eigen::Matrix3d::Zero();
    std::array<Eigen::Matrix3d, 3> moment_b{Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(),
                                            Eigen::Matrix3d::Zero()};  // Σ δ_jk B_j, k = 0..2
    std::array<Eigen::Matrix3d, 6> moment2_b{
        Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(),
        Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};  // Σ δ_k δ_l B_j
    double sum_b_norm = 0.0;                                                         // Σ ‖B_j‖_F
  };
  struct Sums;

  void summarise(std::size_t index);
  double weight(double squared_distance) const;
  double inverse_distance_power(double inverse_distance) const;
  template <bool WithRotations>
  void add_nodes(const Vector3& point, int begin, int end, Sums& sums) const;
  template <bool WithRotations>
  void add_cluster(const Vector3& offset, double inverse_distance, double w, std::size_t index,
                   Sums& sums) const;
  double coarse_denominator(const Vector3& point) const;
  template <bool WithRotations>
  Evaluation evaluate_tree(const Vector3& point, double tolerance) const;
  template <bool WithRotations>
  Evaluation finish(const Vector3& point, const Sums& sums) const;

  double exponent_;
  int whole_exponent_;  // exponent_ when it is a whole number up to 8, else 0
  bool with_rotations_;
  std::vector<Vector3> positions_;      // permuted into tree order
  std::vector<Vector3> a_;              // a_j = u_j − B_j x_j
  std::vector<Vector3> displacements_;  // u_j
  std::vector<Eigen::Matrix3d> b_;      // B_j = R_j − I, rotations only
  std::vector<Cluster> clusters_;       // clusters_[0] is the root
  std::vector<Moments> moments_;
  std::vector<RotationMoments> rotation_moments_;  // rotations only
};

}  // namespace mixmesh::deform
