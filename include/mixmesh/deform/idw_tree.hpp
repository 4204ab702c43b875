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
// |C_n^(p/2)| ≤ C_n^(p/2)(1) = binom(n + p − 1, n), so with t = |δ|/d the remainder of a weight is
// at most d^-p T(t), T(t) = (1 − t)^-p − 1 − pt − p(p+1)t²/2 = Σ_{n≥3} binom(n + p − 1, n) t^n.
// T(t)/t³ has positive coefficients, so it grows with t and every node of a cluster with
// θ = ρ/d < 1 obeys T(t) ≤ t³ G(θ), G(θ) = T(θ)/θ³: the remainder of node j is at most
// d^-(p+3) G(θ) |δ_j|³. For whole p, G(θ) = P(θ)/(1 − θ)^p with P a polynomial of degree p − 1
// (p = 3: P = 10 − 15θ + 6θ²); otherwise G is bounded by the Lagrange form binom(p+2, 3)(1 − θ)^-(p+3).
//
// The approximate u = N/D differs from the exact u* = N*/D* by Σ_j ε_j (v_j − u) / D* (ε_j the
// weight errors), so what matters is each node's error weighted by how far its value is from u.
// With r = d^-(p+3) G(θ), ũ a first estimate of u and v̄(x) = ū + B̄(x − c) a cluster's mean value,
//   |v_j(x) − u| ≤ |u_j − ū| + ‖B_j‖|δ_j| + ‖B_j − B̄‖ d + |v̄ − ũ| + |ũ − u|,
// so a cluster adds at most V = r (T + T' d + S |v̄ − ũ|) plus r S |ũ − u|, where it stores
// S = Σ|δ_j|³, T = Σ|δ_j|³(|u_j − ū| + ‖B_j‖|δ_j|), T' = Σ|δ_j|³‖B_j − B̄‖. A cluster is accepted
// when V ≤ tolerance × U × D̃ and its denominator bound r S ≤ 10⁻³ D̃, with U the largest boundary
// displacement (value scale) and D̃, ũ monopole estimates from a first pass (opening angle 0.8).
// Each evaluation reports the certified bound (Σ V + |ũ − u| Σ r S) / (D − Σ r S) on
// |u − u*|. Near the body v̄ ≈ u for the many small clusters around the point, which is why
// weighting by values accepts far more of them than a bound on the denominator alone.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <utility>
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
  // The tree evaluation of consecutive points, best for points close together (the volume
  // nodes in Morton order): clusters far from a whole group of up to max_group_size points
  // are summed once into a quadratic expansion about the group's centre (the same error
  // bound, with ρ + σ in place of ρ, σ the group's radius); each point then adds the nearer
  // clusters itself. Without rotations; with them, each point is evaluated alone.
  void evaluate_group(const Vector3* points, std::size_t count, double tolerance,
                      Evaluation* evaluations) const;
  static constexpr std::size_t max_group_size = 16;
  // Sum over every boundary node (eq. 1 as written).
  Evaluation evaluate_exact(const Vector3& point) const;

  std::size_t node_count() const { return x_.size(); }
  std::size_t cluster_count() const { return clusters_.size(); }

 private:
  struct Cluster {
    Vector3 centroid = Vector3::Zero();
    double radius = 0.0;
    double cubic_spread = 0.0;                    // S = Σ |δ_j|³
    Vector3 mean_displacement = Vector3::Zero();  // ū = Σ u_j / n
    double value_spread = 0.0;                    // T = Σ |δ_j|³ (|u_j − ū| + ‖B_j‖_F |δ_j|)
    double displacement_spread = 0.0;             // T₀ = Σ |u_j − ū|
    int begin = 0, end = 0;                       // range in the permuted node arrays
    int first_child = -1;  // children are first_child and first_child + 1; -1 for a leaf
  };
  // Aggregates of each cluster, kept apart from the traversal data above so that a traversal
  // touches little memory. Column k holds (Σ f_k(δ_j) a_j, Σ f_k(δ_j)) for the ten terms
  // f = (1, δ_x, δ_y, δ_z, δ_x², δ_y², δ_z², δ_xδ_y, δ_xδ_z, δ_yδ_z) of the expansion, so that one
  // 4 × 10 product with the expansion coefficients adds a cluster to (numerator, denominator).
  using Moments = Eigen::Matrix<double, 4, 10>;
  struct RotationMoments {
    Eigen::Matrix3d sum_b = Eigen::Matrix3d::Zero();
    std::array<Eigen::Matrix3d, 3> moment_b{Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(),
                                            Eigen::Matrix3d::Zero()};  // Σ δ_jk B_j, k = 0..2
    std::array<Eigen::Matrix3d, 6> moment2_b{
        Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(),
        Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};  // Σ δ_k δ_l B_j
    Eigen::Matrix3d mean_b = Eigen::Matrix3d::Zero();                                // B̄ = Σ B_j / n
    double rotation_spread = 0.0;  // T' = Σ |δ_j|³ ‖B_j − B̄‖_F
  };
  struct Sums;
  struct LocalExpansion;

  void summarise(std::size_t index);
  template <int WholeExponent>
  std::pair<double, double> tail_factor(double ratio) const;
  template <int WholeExponent>
  double inverse_distance_power(double inverse_distance) const;
  template <int WholeExponent>
  double weight(double squared_distance) const;
  template <bool WithRotations, int WholeExponent>
  void add_nodes(const Vector3& point, int begin, int end, Sums& sums) const;
  template <bool WithRotations>
  void add_cluster(const Vector3& offset, double inverse_distance, double w, std::size_t index,
                   Sums& sums) const;
  struct Estimate;
  template <bool WithRotations, int WholeExponent>
  Estimate coarse_estimate(const Vector3& point) const;
  template <bool WithRotations, int WholeExponent>
  void traverse(const Vector3& point, double value_budget, double denominator_budget, int root,
                Sums& sums) const;
  template <bool WithRotations, int WholeExponent>
  Evaluation evaluate_tree(const Vector3& point, double tolerance) const;
  template <int WholeExponent>
  void add_cluster_to_group(const Vector3& offset, double inverse_distance, double w, std::size_t index,
                            LocalExpansion& local) const;
  template <int WholeExponent>
  void evaluate_group_tree(const Vector3* points, std::size_t count, double tolerance,
                           Evaluation* evaluations) const;
  template <bool WithRotations, int WholeExponent>
  Evaluation evaluate_exact_sum(const Vector3& point) const;
  template <bool WithRotations>
  Evaluation finish(const Vector3& point, const Sums& sums) const;

  double exponent_;
  int whole_exponent_;  // exponent_ when it is a whole number up to 8, else 0
  // G(θ) = P(θ)/(1 − θ)^p for whole p: coefficients of P, lowest first; otherwise the
  // Lagrange factor binom(p+2, 3).
  std::array<double, 8> tail_polynomial_{};
  double lagrange_factor_ = 0.0;
  bool with_rotations_;
  double value_scale_ = 0.0;  // U = max |u_j| + max ‖B_j‖_F × boundary box diagonal
  // Node data in tree order, one array per coordinate so the direct sums stream through memory.
  std::vector<double> x_, y_, z_;       // positions x_j
  std::vector<double> ax_, ay_, az_;    // a_j = u_j − B_j x_j
  std::vector<Vector3> displacements_;  // u_j
  std::vector<Eigen::Matrix3d> b_;      // B_j = R_j − I, rotations only
  std::vector<Cluster> clusters_;       // clusters_[0] is the root
  std::vector<Moments, Eigen::aligned_allocator<Moments>> moments_;
  std::vector<RotationMoments> rotation_moments_;  // rotations only
};

}  // namespace mixmesh::deform
