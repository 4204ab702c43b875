#include "mixmesh/deform/idw_tree.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "mixmesh/core/error.hpp"

namespace mixmesh::deform {

namespace {

// Traversal depth is bounded by the tree height (balanced splits), far below this.
constexpr int stack_capacity = 128;
// Opening angle of the first pass that estimates the denominator.
constexpr double coarse_opening = 0.5;
// Clusters seen under a larger ratio radius/distance are never aggregated (the bound
// grows without limit as the ratio approaches 1).
constexpr double max_opening = 0.75;

// (xx, yy, zz, xy, xz, yz) products of a vector with itself.
Eigen::Matrix<double, 6, 1> symmetric_products(const Vector3& v) {
  Eigen::Matrix<double, 6, 1> products;
  products << v.x() * v.x(), v.y() * v.y(), v.z() * v.z(), v.x() * v.y(), v.x() * v.z(), v.y() * v.z();
  return products;
}

// x^-q, by repeated multiplication for the usual whole exponents.
double inverse_power(double x, double q) {
  if (q == std::floor(q) && q <= 16.0) {
    double product = 1.0;
    for (int k = 0; k < static_cast<int>(q); ++k) product *= x;
    return 1.0 / product;
  }
  return std::pow(x, -q);
}

}  // namespace

// Running sums of one evaluation: D = Σ w, N = Σ w a, W = Σ w B, and the error bounds.
struct IdwTree::Sums {
  double denominator = 0.0;
  Vector3 numerator = Vector3::Zero();
  Eigen::Matrix3d weighted_b = Eigen::Matrix3d::Zero();
  double denominator_bound = 0.0;
  double numerator_bound = 0.0;
  int hit = -1;  // a boundary node at the evaluation point: its value is the answer
  std::size_t cluster_terms = 0;
  std::size_t node_terms = 0;
};

IdwTree::IdwTree(const std::vector<Vector3>& positions, const std::vector<Vector3>& displacements,
                 const std::vector<Eigen::Matrix3d>& rotations, double exponent, int leaf_size)
    : exponent_(exponent),
      whole_exponent_(exponent == std::floor(exponent) && exponent <= 8.0 ? static_cast<int>(exponent) : 0),
      with_rotations_(!rotations.empty()) {
  if (positions.empty()) throw Error("idw tree: no boundary nodes");
  if (displacements.size() != positions.size())
    throw Error("idw tree: " + std::to_string(displacements.size()) + " displacements for " +
                std::to_string(positions.size()) + " boundary nodes");
  if (with_rotations_ && rotations.size() != positions.size())
    throw Error("idw tree: " + std::to_string(rotations.size()) + " rotations for " +
                std::to_string(positions.size()) + " boundary nodes");
  if (!(exponent > 0.0) || !std::isfinite(exponent))
    throw Error("idw tree: exponent must be positive, got " + std::to_string(exponent));
  if (leaf_size < 1) throw Error("idw tree: leaf size must be at least 1, got " + std::to_string(leaf_size));

  std::vector<int> order(positions.size());
  std::iota(order.begin(), order.end(), 0);
  clusters_.reserve(2 * positions.size() / static_cast<std::size_t>(leaf_size) + 2);
  // Build on an index permutation, then gather the node data into tree order so that
  // every cluster is a contiguous range.
  {
    // Recursive median splits along the longest box side; `order` follows the swaps.
    struct Range {
      int begin, end, cluster;
    };
    clusters_.push_back(Cluster{});
    std::vector<Range> pending{{0, static_cast<int>(positions.size()), 0}};
    while (!pending.empty()) {
      const Range range = pending.back();
      pending.pop_back();
      clusters_[static_cast<std::size_t>(range.cluster)].begin = range.begin;
      clusters_[static_cast<std::size_t>(range.cluster)].end = range.end;
      if (range.end - range.begin <= leaf_size) continue;
      Eigen::Vector3d low = positions[static_cast<std::size_t>(order[static_cast<std::size_t>(range.begin)])];
      Eigen::Vector3d high = low;
      for (int k = range.begin; k < range.end; ++k) {
        const Vector3& p = positions[static_cast<std::size_t>(order[static_cast<std::size_t>(k)])];
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
      }
      int axis = 0;
      (high - low).maxCoeff(&axis);
      const int middle = range.begin + (range.end - range.begin) / 2;
      std::nth_element(order.begin() + range.begin, order.begin() + middle, order.begin() + range.end,
                       [&](int left, int right) {
                         return positions[static_cast<std::size_t>(left)][axis] <
                                positions[static_cast<std::size_t>(right)][axis];
                       });
      const int first_child = static_cast<int>(clusters_.size());
      clusters_[static_cast<std::size_t>(range.cluster)].first_child = first_child;
      clusters_.push_back(Cluster{});
      clusters_.push_back(Cluster{});
      pending.push_back({range.begin, middle, first_child});
      pending.push_back({middle, range.end, first_child + 1});
    }
  }
  const std::size_t count = positions.size();
  positions_.resize(count);
  displacements_.resize(count);
  a_.resize(count);
  if (with_rotations_) b_.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t source = static_cast<std::size_t>(order[k]);
    positions_[k] = positions[source];
    displacements_[k] = displacements[source];
    if (!positions_[k].allFinite() || !displacements_[k].allFinite())
      throw Error("idw tree: boundary node " + std::to_string(source) + " has a non-finite coordinate");
    if (with_rotations_) {
      b_[k] = rotations[source] - Eigen::Matrix3d::Identity();
      a_[k] = displacements_[k] - b_[k] * positions_[k];
    } else {
      a_[k] = displacements_[k];
    }
  }
  moments_.resize(clusters_.size());
  if (with_rotations_) rotation_moments_.resize(clusters_.size());
  for (std::size_t index = 0; index < clusters_.size(); ++index) summarise(index);
}

void IdwTree::summarise(std::size_t index) {
  Cluster& cluster = clusters_[index];
  Moments& moments = moments_[index];
  const double count = cluster.end - cluster.begin;
  Vector3 centroid = Vector3::Zero();
  for (int k = cluster.begin; k < cluster.end; ++k) centroid += positions_[static_cast<std::size_t>(k)];
  cluster.centroid = centroid / count;
  for (int k = cluster.begin; k < cluster.end; ++k) {
    const std::size_t j = static_cast<std::size_t>(k);
    const Vector3 offset = positions_[j] - cluster.centroid;
    cluster.radius = std::max(cluster.radius, offset.norm());
    const Eigen::Matrix<double, 6, 1> products = symmetric_products(offset);
    moments.sum_a += a_[j];
    moments.moment_a += offset * a_[j].transpose();
    moments.moment2 += products;
    moments.moment2_a += a_[j] * products.transpose();
    moments.sum_displacement_norm += displacements_[j].norm();
    if (with_rotations_) {
      RotationMoments& rotation = rotation_moments_[index];
      rotation.sum_b += b_[j];
      for (int axis = 0; axis < 3; ++axis)
        rotation.moment_b[static_cast<std::size_t>(axis)] += offset[axis] * b_[j];
      for (int entry = 0; entry < 6; ++entry)
        rotation.moment2_b[static_cast<std::size_t>(entry)] += products[entry] * b_[j];
      rotation.sum_b_norm += b_[j].norm();
    }
  }
}

double IdwTree::inverse_distance_power(double inverse_distance) const {
  if (whole_exponent_ > 0) {
    double product = inverse_distance;
    for (int k = 1; k < whole_exponent_; ++k) product *= inverse_distance;
    return product;
  }
  return std::pow(inverse_distance, exponent_);
}

double IdwTree::weight(double squared_distance) const {
  // The common exponents avoid pow, which dominates the cost otherwise.
  if (exponent_ == 3.0) return 1.0 / (squared_distance * std::sqrt(squared_distance));
  if (exponent_ == 2.0) return 1.0 / squared_distance;
  if (exponent_ == 4.0) return 1.0 / (squared_distance * squared_distance);
  if (exponent_ == 5.0) return 1.0 / (squared_distance * squared_distance * std::sqrt(squared_distance));
  return std::pow(squared_distance, -0.5 * exponent_);
}

template <bool WithRotations>
void IdwTree::add_nodes(const Vector3& point, int begin, int end, Sums& sums) const {
  for (int k = begin; k < end; ++k) {
    const std::size_t j = static_cast<std::size_t>(k);
    const double squared_distance = (point - positions_[j]).squaredNorm();
    if (squared_distance == 0.0) {
      sums.hit = k;
      return;
    }
    const double w = weight(squared_distance);
    sums.denominator += w;
    sums.numerator += w * a_[j];
    if constexpr (WithRotations) sums.weighted_b += w * b_[j];
  }
  sums.node_terms += static_cast<std::size_t>(end - begin);
}

template <bool WithRotations>
void IdwTree::add_cluster(const Vector3& offset, double inverse_distance, double w, std::size_t index,
                          Sums& sums) const {
  const Cluster& cluster = clusters_[index];
  const Moments& moments = moments_[index];
  const Vector3 direction = offset * inverse_distance;
  // ∇_y |x − y|^-p at y = c, and ½ δᵀHδ = half_hessian [(p+2)(r̂·δ)² − |δ|²].
  const Vector3 gradient = (exponent_ * w * inverse_distance) * direction;
  const double half_hessian = 0.5 * exponent_ * w * inverse_distance * inverse_distance;
  // (r̂·δ)² = quadratic · (δ_k δ_l) with off-diagonal entries counted twice.
  Eigen::Matrix<double, 6, 1> quadratic = symmetric_products(direction);
  quadratic.tail<3>() *= 2.0;
  quadratic *= exponent_ + 2.0;
  quadratic.head<3>().array() -= 1.0;
  quadratic *= half_hessian;
  sums.denominator += w * (cluster.end - cluster.begin) + quadratic.dot(moments.moment2);
  sums.numerator +=
      w * moments.sum_a + moments.moment_a.transpose() * gradient + moments.moment2_a * quadratic;
  if constexpr (WithRotations) {
    const RotationMoments& rotation = rotation_moments_[index];
    Eigen::Matrix3d weighted = w * rotation.sum_b;
    for (int axis = 0; axis < 3; ++axis)
      weighted += gradient[axis] * rotation.moment_b[static_cast<std::size_t>(axis)];
    for (int entry = 0; entry < 6; ++entry)
      weighted += quadratic[entry] * rotation.moment2_b[static_cast<std::size_t>(entry)];
    sums.weighted_b += weighted;
  }
  ++sums.cluster_terms;
}

double IdwTree::coarse_denominator(const Vector3& point) const {
  double denominator = 0.0;
  int stack[stack_capacity];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Cluster& cluster = clusters_[static_cast<std::size_t>(stack[--top])];
    const double distance = (point - cluster.centroid).norm();
    if (cluster.radius <= coarse_opening * distance) {
      denominator += weight(distance * distance) * (cluster.end - cluster.begin);
    } else if (cluster.first_child < 0) {
      for (int k = cluster.begin; k < cluster.end; ++k) {
        const double squared_distance = (point - positions_[static_cast<std::size_t>(k)]).squaredNorm();
        if (squared_distance > 0.0) denominator += weight(squared_distance);
      }
    } else {
      stack[top++] = cluster.first_child;
      stack[top++] = cluster.first_child + 1;
    }
  }
  return denominator;
}

template <bool WithRotations>
IdwTree::Evaluation IdwTree::evaluate_tree(const Vector3& point, double tolerance) const {
  Sums sums;
  const double budget = tolerance * coarse_denominator(point);
  const double p = exponent_;
  // Lagrange remainder of (1 − θ)^-p after the θ² term: binom(p+2, 3) θ³ (1 − θ)^-(p+3).
  const double remainder_factor = p * (p + 1.0) * (p + 2.0) / 6.0;
  const double tail_power = p + 3.0;
  int stack[stack_capacity];
  int top = 0;
  stack[top++] = 0;
  while (top > 0 && sums.hit < 0) {
    const std::size_t index = static_cast<std::size_t>(stack[--top]);
    const Cluster& cluster = clusters_[index];
    const Vector3 offset = point - cluster.centroid;
    const double squared_distance = offset.squaredNorm();
    if (cluster.radius * cluster.radius < max_opening * max_opening * squared_distance) {
      const double inverse_distance = 1.0 / std::sqrt(squared_distance);
      const double ratio = cluster.radius * inverse_distance;
      const double w = inverse_distance_power(inverse_distance);
      // Bound on the remainder of each weight in the cluster (Gegenbauer tail, see header).
      const double remainder =
          w * remainder_factor * ratio * ratio * ratio * inverse_power(1.0 - ratio, tail_power);
      const double count = cluster.end - cluster.begin;
      if (count * remainder <= budget) {
        const double distance = squared_distance * inverse_distance;
        add_cluster<WithRotations>(offset, inverse_distance, w, index, sums);
        sums.denominator_bound += count * remainder;
        double value_bound = moments_[index].sum_displacement_norm;
        if constexpr (WithRotations)
          value_bound += rotation_moments_[index].sum_b_norm * (distance + cluster.radius);
        sums.numerator_bound += remainder * value_bound;
        continue;
      }
    }
    if (cluster.first_child < 0) {
      add_nodes<WithRotations>(point, cluster.begin, cluster.end, sums);
    } else {
      stack[top++] = cluster.first_child;
      stack[top++] = cluster.first_child + 1;
    }
  }
  return finish<WithRotations>(point, sums);
}

template <bool WithRotations>
IdwTree::Evaluation IdwTree::finish(const Vector3& point, const Sums& sums) const {
  Evaluation evaluation;
  evaluation.cluster_terms = sums.cluster_terms;
  evaluation.node_terms = sums.node_terms;
  if (sums.hit >= 0) {
    // The point is a boundary node: eq. (1) tends to that node's value.
    evaluation.displacement = displacements_[static_cast<std::size_t>(sums.hit)];
    return evaluation;
  }
  Vector3 numerator = sums.numerator;
  if constexpr (WithRotations) numerator += sums.weighted_b * point;
  evaluation.displacement = numerator / sums.denominator;
  if (sums.denominator_bound > 0.0) {
    const double margin = sums.denominator - sums.denominator_bound;
    evaluation.error_bound =
        margin > 0.0
            ? (sums.numerator_bound + evaluation.displacement.norm() * sums.denominator_bound) / margin
            : std::numeric_limits<double>::infinity();
  }
  return evaluation;
}

IdwTree::Evaluation IdwTree::evaluate(const Vector3& point, double tolerance) const {
  return with_rotations_ ? evaluate_tree<true>(point, tolerance) : evaluate_tree<false>(point, tolerance);
}

IdwTree::Evaluation IdwTree::evaluate_exact(const Vector3& point) const {
  Sums sums;
  const int count = static_cast<int>(positions_.size());
  if (with_rotations_) {
    add_nodes<true>(point, 0, count, sums);
    return finish<true>(point, sums);
  }
  add_nodes<false>(point, 0, count, sums);
  return finish<false>(point, sums);
}

}  // namespace mixmesh::deform
