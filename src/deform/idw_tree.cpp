#include "mixmesh/deform/idw_tree.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

namespace mixmesh::deform {

namespace {

// Traversal depth is bounded by the tree height, under 64 + 32 (idw_tree_build.cpp).
constexpr int stack_capacity = 128;
// A group of points sums a cluster into its expansion only when the cluster's radius is at
// least this many times the group's.
constexpr double group_scale = 4.0;
// Opening angle of the first pass that estimates the denominator.
constexpr double coarse_opening = 0.8;
// Bound on a cluster's share of the denominator error (relative to the coarse estimate), so
// that the certified bound's D − E_D stays well away from zero.
constexpr double denominator_tolerance = 1e-3;
// Clusters seen under a larger ratio radius/distance are never aggregated (the bound
// grows without limit as the ratio approaches 1).
constexpr double max_opening = 0.75;

// x^k for a small whole k.
double whole_power(double x, int k) {
  double product = 1.0;
  for (int m = 0; m < k; ++m) product *= x;
  return product;
}

// function(std::integral_constant<int, n>{}) for the whole exponent n the weights are
// specialised for (2, 3, 4; 0 for any other exponent).
template <class Function>
auto with_whole_exponent(int exponent, Function&& function) {
  switch (exponent) {
    case 2:
      return function(std::integral_constant<int, 2>{});
    case 3:
      return function(std::integral_constant<int, 3>{});
    case 4:
      return function(std::integral_constant<int, 4>{});
    default:
      return function(std::integral_constant<int, 0>{});
  }
}

}  // namespace

// Monopole estimates of the denominator and of the displacement.
struct IdwTree::Estimate {
  double denominator = 0.0;
  Vector3 displacement = Vector3::Zero();
};

// Running sums of one evaluation: D = Σ w, N = Σ w a, W = Σ w B, and the error bounds.
struct IdwTree::Sums {
  Eigen::Vector4d totals = Eigen::Vector4d::Zero();  // (N, D): N = Σ w a, D = Σ w
  Eigen::Matrix3d weighted_b = Eigen::Matrix3d::Zero();
  double denominator_bound = 0.0;
  double value_bound = 0.0;            // Σ V over accepted clusters (see header)
  Vector3 estimate = Vector3::Zero();  // ũ
  int hit = -1;                        // a boundary node at the evaluation point: its value is the answer
  std::size_t cluster_terms = 0;
  std::size_t node_terms = 0;
};

// G(θ) as numerator / denominator, so that acceptance tests need no division.
template <int WholeExponent>
std::pair<double, double> IdwTree::tail_factor(double ratio) const {
  const double complement = 1.0 - ratio;
  if constexpr (WholeExponent == 3)  // the default exponent, spelled out for speed
    return {10.0 + ratio * (-15.0 + 6.0 * ratio), complement * complement * complement};
  if (whole_exponent_ > 0) {
    double polynomial = 0.0;
    for (int k = whole_exponent_ - 1; k >= 0; --k)
      polynomial = polynomial * ratio + tail_polynomial_[static_cast<std::size_t>(k)];
    return {polynomial, whole_power(complement, whole_exponent_)};
  }
  return {lagrange_factor_, std::pow(complement, exponent_ + 3.0)};
}

// d^-p from 1/d.
template <int WholeExponent>
double IdwTree::inverse_distance_power(double inverse_distance) const {
  if constexpr (WholeExponent > 0) return whole_power(inverse_distance, WholeExponent);
  return std::pow(inverse_distance, exponent_);
}

// w = r^-p from r²; the common exponents avoid pow, which dominates the cost otherwise.
template <int WholeExponent>
double IdwTree::weight(double squared_distance) const {
  if constexpr (WholeExponent == 2) return 1.0 / squared_distance;
  if constexpr (WholeExponent == 3) return 1.0 / (squared_distance * std::sqrt(squared_distance));
  if constexpr (WholeExponent == 4) return 1.0 / (squared_distance * squared_distance);
  return std::pow(squared_distance, -0.5 * exponent_);
}

template <bool WithRotations, int WholeExponent>
void IdwTree::add_nodes(const Vector3& point, int begin, int end, Sums& sums) const {
  const double px = point.x(), py = point.y(), pz = point.z();
  double denominator = 0.0, nx = 0.0, ny = 0.0, nz = 0.0;
  double nearest = std::numeric_limits<double>::infinity();
  for (int k = begin; k < end; ++k) {
    const std::size_t j = static_cast<std::size_t>(k);
    const double dx = px - x_[j], dy = py - y_[j], dz = pz - z_[j];
    const double squared_distance = dx * dx + dy * dy + dz * dz;
    nearest = std::min(nearest, squared_distance);
    // At a coincident node w is infinite; the sums are discarded below.
    const double w = weight<WholeExponent>(squared_distance);
    denominator += w;
    nx += w * ax_[j], ny += w * ay_[j], nz += w * az_[j];
    if constexpr (WithRotations) sums.weighted_b += w * b_[j];
  }
  if (nearest == 0.0) {
    for (int k = begin; k < end; ++k) {
      const std::size_t j = static_cast<std::size_t>(k);
      if (px == x_[j] && py == y_[j] && pz == z_[j]) {
        sums.hit = k;
        return;
      }
    }
  }
  sums.totals += Eigen::Vector4d(nx, ny, nz, denominator);
  sums.node_terms += static_cast<std::size_t>(end - begin);
}

template <bool WithRotations>
void IdwTree::add_cluster(const Vector3& offset, double inverse_distance, double w, std::size_t index,
                          Sums& sums) const {
  const double rx = offset.x() * inverse_distance, ry = offset.y() * inverse_distance,
               rz = offset.z() * inverse_distance;
  // ∇_y |x − y|^-p at y = c is g = p w/d r̂, and ½ δᵀHδ = h [(p+2)(r̂·δ)² − |δ|²], h = ½ p w/d²:
  // q holds the coefficients of the six second moments (off-diagonal ones counted twice).
  const double gradient_scale = exponent_ * w * inverse_distance;
  const double gx = gradient_scale * rx, gy = gradient_scale * ry, gz = gradient_scale * rz;
  const double h = 0.5 * exponent_ * w * inverse_distance * inverse_distance;
  const double hp = h * (exponent_ + 2.0), hp2 = 2.0 * hp;
  Eigen::Matrix<double, 10, 1> coefficients;
  coefficients << w, gx, gy, gz, hp * rx * rx - h, hp * ry * ry - h, hp * rz * rz - h, hp2 * rx * ry,
      hp2 * rx * rz, hp2 * ry * rz;
  sums.totals.noalias() += moments_[index] * coefficients;
  if constexpr (WithRotations) {
    const RotationMoments& rotation = rotation_moments_[index];
    Eigen::Matrix3d weighted = w * rotation.sum_b + gx * rotation.moment_b[0] + gy * rotation.moment_b[1] +
                               gz * rotation.moment_b[2];
    for (int entry = 0; entry < 6; ++entry)
      weighted += coefficients[4 + entry] * rotation.moment2_b[static_cast<std::size_t>(entry)];
    sums.weighted_b += weighted;
  }
  ++sums.cluster_terms;
}

template <bool WithRotations, int WholeExponent>
IdwTree::Estimate IdwTree::coarse_estimate(const Vector3& point) const {
  Estimate estimate;
  Vector3 numerator = Vector3::Zero();
  int stack[stack_capacity];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const std::size_t index = static_cast<std::size_t>(stack[--top]);
    const Cluster& cluster = clusters_[index];
    const Vector3 offset = point - cluster.centroid;
    const double squared_distance = offset.squaredNorm();
    if (cluster.radius * cluster.radius <= coarse_opening * coarse_opening * squared_distance) {
      const double weight_sum = weight<WholeExponent>(squared_distance) * (cluster.end - cluster.begin);
      estimate.denominator += weight_sum;
      Vector3 value = cluster.mean_displacement;
      if constexpr (WithRotations) value += rotation_moments_[index].mean_b * offset;
      numerator += weight_sum * value;
    } else if (cluster.first_child < 0) {
      for (int k = cluster.begin; k < cluster.end; ++k) {
        const std::size_t j = static_cast<std::size_t>(k);
        const Vector3 node_offset(point.x() - x_[j], point.y() - y_[j], point.z() - z_[j]);
        const double node_squared = node_offset.squaredNorm();
        if (node_squared == 0.0) continue;
        const double w = weight<WholeExponent>(node_squared);
        estimate.denominator += w;
        Vector3 value = displacements_[j];
        if constexpr (WithRotations) value += b_[j] * node_offset;
        numerator += w * value;
      }
    } else {
      stack[top++] = cluster.first_child;
      stack[top++] = cluster.first_child + 1;
    }
  }
  if (estimate.denominator > 0.0) estimate.displacement = numerator / estimate.denominator;
  return estimate;
}

template <bool WithRotations, int WholeExponent>
void IdwTree::traverse(const Vector3& point, double value_budget, double denominator_budget, int root,
                       Sums& sums) const {
  int stack[stack_capacity];
  int top = 0;
  stack[top++] = root;
  while (top > 0 && sums.hit < 0) {
    const std::size_t index = static_cast<std::size_t>(stack[--top]);
    const Cluster& cluster = clusters_[index];
    const Vector3 offset = point - cluster.centroid;
    const double squared_distance = offset.squaredNorm();
    if (cluster.radius * cluster.radius < max_opening * max_opening * squared_distance) {
      // 1/d² and d are independent, so the division and the square root overlap.
      const double inverse_squared = 1.0 / squared_distance;
      const double inverse_distance = std::sqrt(squared_distance) * inverse_squared;
      const double w = inverse_distance_power<WholeExponent>(inverse_distance);
      // Bound on each node's weight remainder per |δ_j|³: r = d^-(p+3) G(θ) (see header), kept
      // as a fraction r = scaled / tail_denominator.
      const auto [tail_numerator, tail_denominator] =
          tail_factor<WholeExponent>(cluster.radius * inverse_distance);
      const double scaled = w * inverse_distance * inverse_distance * inverse_distance * tail_numerator;
      if (scaled * cluster.cubic_spread <= denominator_budget * tail_denominator) {
        // V = r (T + T' d + S |v̄ − ũ|), see header.
        Vector3 mean_value = cluster.mean_displacement;
        double spread = cluster.value_spread;
        if constexpr (WithRotations) {
          const RotationMoments& rotation = rotation_moments_[index];
          mean_value += rotation.mean_b * offset;
          spread += rotation.rotation_spread * squared_distance * inverse_distance;
        }
        const double value_factor = spread + cluster.cubic_spread * (mean_value - sums.estimate).norm();
        if (scaled * value_factor <= value_budget * tail_denominator) {
          const double remainder_per_cube = scaled / tail_denominator;
          add_cluster<WithRotations>(offset, inverse_distance, w, index, sums);
          sums.denominator_bound += remainder_per_cube * cluster.cubic_spread;
          sums.value_bound += remainder_per_cube * value_factor;
          continue;
        }
      }
    }
    if (cluster.first_child < 0) {
      add_nodes<WithRotations, WholeExponent>(point, cluster.begin, cluster.end, sums);
    } else {
      stack[top++] = cluster.first_child;
      stack[top++] = cluster.first_child + 1;
    }
  }
}

template <bool WithRotations, int WholeExponent>
IdwTree::Evaluation IdwTree::evaluate_tree(const Vector3& point, double tolerance) const {
  Sums sums;
  const Estimate estimate = coarse_estimate<WithRotations, WholeExponent>(point);
  sums.estimate = estimate.displacement;
  traverse<WithRotations, WholeExponent>(point, tolerance * value_scale_ * estimate.denominator,
                                         denominator_tolerance * estimate.denominator, 0, sums);
  return finish<WithRotations>(point, sums);
}

// Far field of a group of points as a quadratic in ε = x − g about the group centre g: row k
// of the outputs (N_x, N_y, N_z, D) is constant_k + linear_k·ε + ½ εᵀ quadratic[k] ε.
struct IdwTree::LocalExpansion {
  Eigen::Vector4d constant = Eigen::Vector4d::Zero();
  Eigen::Matrix<double, 4, 3> linear = Eigen::Matrix<double, 4, 3>::Zero();
  std::array<Eigen::Matrix3d, 4> quadratic{Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(),
                                           Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
  double denominator_bound = 0.0;  // Σ r S' over the accepted clusters
  double value_bound = 0.0;        // Σ r (T' + S' |ū − ũ_g|)
  std::size_t cluster_terms = 0;

  Eigen::Vector4d at(const Vector3& epsilon) const {
    Eigen::Vector4d value = constant + linear * epsilon;
    for (int k = 0; k < 4; ++k)
      value[k] += 0.5 * epsilon.dot(quadratic[static_cast<std::size_t>(k)] * epsilon);
    return value;
  }
};

// A cluster seen from every point x = g + ε of a group: w(x − x_j) is expanded to second order
// in η_j = δ_j − ε about R = g − c, w ≈ w₀ + ∇·η + ½ ηᵀHη, and summed over the cluster's nodes.
template <int WholeExponent>
void IdwTree::add_cluster_to_group(const Vector3& offset, double inverse_distance, double w,
                                   std::size_t index, LocalExpansion& local) const {
  const Moments& moments = moments_[index];
  const Vector3 direction = offset * inverse_distance;
  const Vector3 gradient = (exponent_ * w * inverse_distance) * direction;
  const double h = exponent_ * w * inverse_distance * inverse_distance;
  // H = p w/d² [(p+2) r̂r̂ᵀ − I].
  const Eigen::Matrix3d hessian =
      h * ((exponent_ + 2.0) * direction * direction.transpose() - Eigen::Matrix3d::Identity());
  Eigen::Matrix<double, 10, 1> coefficients;
  coefficients << w, gradient, 0.5 * hessian(0, 0), 0.5 * hessian(1, 1), 0.5 * hessian(2, 2), hessian(0, 1),
      hessian(0, 2), hessian(1, 2);
  local.constant.noalias() += moments * coefficients;
  for (int k = 0; k < 4; ++k) {
    // Σ a_k [∇·(δ − ε) + ½(δ − ε)ᵀH(δ − ε)]: the ε terms are −ε·(∇ Σa_k + H Σδ a_k) + ½ εᵀ(H Σa_k)ε.
    const double sum = moments(k, 0);
    const Vector3 first(moments(k, 1), moments(k, 2), moments(k, 3));
    local.linear.row(k) -= (sum * gradient + hessian * first).transpose();
    local.quadratic[static_cast<std::size_t>(k)] += sum * hessian;
  }
  ++local.cluster_terms;
}

template <int WholeExponent>
void IdwTree::evaluate_group_tree(const Vector3* points, std::size_t count, double tolerance,
                                  Evaluation* evaluations) const {
  Vector3 centre = Vector3::Zero();
  for (std::size_t i = 0; i < count; ++i) centre += points[i];
  centre /= static_cast<double>(count);
  double group_radius = 0.0;
  for (std::size_t i = 0; i < count; ++i) group_radius = std::max(group_radius, (points[i] - centre).norm());
  std::array<Estimate, max_group_size> estimates;
  double smallest_denominator = std::numeric_limits<double>::infinity();
  Vector3 group_estimate = Vector3::Zero();
  for (std::size_t i = 0; i < count; ++i) {
    estimates[i] = coarse_estimate<false, WholeExponent>(points[i]);
    smallest_denominator = std::min(smallest_denominator, estimates[i].denominator);
    group_estimate += estimates[i].displacement;
  }
  group_estimate /= static_cast<double>(count);
  double estimate_spread = 0.0;
  for (std::size_t i = 0; i < count; ++i)
    estimate_spread = std::max(estimate_spread, (estimates[i].displacement - group_estimate).norm());
  const double value_budget = tolerance * value_scale_ * smallest_denominator;
  const double denominator_budget = denominator_tolerance * smallest_denominator;
  const double radius_cube = group_radius * group_radius * group_radius;

  // Clusters far from the whole group go into the local expansion; the others, once no
  // larger than the group, are left to each point's own traversal.
  LocalExpansion local;
  std::vector<int> near;
  int stack[stack_capacity];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const std::size_t index = static_cast<std::size_t>(stack[--top]);
    const Cluster& cluster = clusters_[index];
    const Vector3 offset = centre - cluster.centroid;
    const double squared_distance = offset.squaredNorm();
    const double reach = cluster.radius + group_radius;  // |η_j| ≤ |δ_j| + |ε| ≤ ρ + σ
    // The part of the remainder that depends on ε is common to all nodes and adds up
    // coherently over the clusters, unlike the part in δ_j: only clusters much larger than
    // the group go into the expansion, so that the ε part stays small.
    const bool large = cluster.radius >= group_scale * group_radius;
    if (large && reach * reach < max_opening * max_opening * squared_distance) {
      const double inverse_squared = 1.0 / squared_distance;
      const double inverse_distance = std::sqrt(squared_distance) * inverse_squared;
      const double w = inverse_distance_power<WholeExponent>(inverse_distance);
      const auto [tail_numerator, tail_denominator] = tail_factor<WholeExponent>(reach * inverse_distance);
      const double scaled = w * inverse_distance * inverse_distance * inverse_distance * tail_numerator;
      // (|δ_j| + σ)³ ≤ 4 (|δ_j|³ + σ³): S' and T' bound the sums of (|δ_j| + σ)³ and of
      // (|δ_j| + σ)³ |u_j − ū|.
      const double node_count = cluster.end - cluster.begin;
      const double cubes = 4.0 * (cluster.cubic_spread + node_count * radius_cube);
      const double spread = 4.0 * (cluster.value_spread + radius_cube * cluster.displacement_spread);
      if (scaled * cubes <= denominator_budget * tail_denominator) {
        const double offset_value = (cluster.mean_displacement - group_estimate).norm();
        if (scaled * (spread + cubes * (offset_value + estimate_spread)) <= value_budget * tail_denominator) {
          const double remainder_per_cube = scaled / tail_denominator;
          add_cluster_to_group<WholeExponent>(offset, inverse_distance, w, index, local);
          local.denominator_bound += remainder_per_cube * cubes;
          local.value_bound += remainder_per_cube * (spread + cubes * offset_value);
          continue;
        }
      }
    }
    if (cluster.first_child < 0 || !large) {
      near.push_back(static_cast<int>(index));
    } else {
      stack[top++] = cluster.first_child;
      stack[top++] = cluster.first_child + 1;
    }
  }

  for (std::size_t i = 0; i < count; ++i) {
    Sums sums;
    sums.estimate = estimates[i].displacement;
    sums.totals = local.at(points[i] - centre);
    // |v_j − u| ≤ |u_j − ū| + |ū − ũ_g| + |ũ_g − ũ| + |ũ − u|; finish adds the last term.
    sums.denominator_bound = local.denominator_bound;
    sums.value_bound =
        local.value_bound + (group_estimate - estimates[i].displacement).norm() * local.denominator_bound;
    sums.cluster_terms = local.cluster_terms;
    const double point_value_budget = tolerance * value_scale_ * estimates[i].denominator;
    const double point_denominator_budget = denominator_tolerance * estimates[i].denominator;
    for (const int root : near) {
      traverse<false, WholeExponent>(points[i], point_value_budget, point_denominator_budget, root, sums);
      if (sums.hit >= 0) break;
    }
    evaluations[i] = finish<false>(points[i], sums);
  }
}

void IdwTree::evaluate_group(const Vector3* points, std::size_t count, double tolerance,
                             Evaluation* evaluations) const {
  if (with_rotations_ || count < 2) {
    for (std::size_t i = 0; i < count; ++i) evaluations[i] = evaluate(points[i], tolerance);
    return;
  }
  for (std::size_t first = 0; first < count; first += max_group_size) {
    const std::size_t size = std::min(max_group_size, count - first);
    with_whole_exponent(whole_exponent_, [&](auto exponent) {
      evaluate_group_tree<decltype(exponent)::value>(points + first, size, tolerance, evaluations + first);
    });
  }
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
  const double denominator = sums.totals[3];
  Vector3 numerator = sums.totals.head<3>();
  if constexpr (WithRotations) numerator += sums.weighted_b * point;
  evaluation.displacement = numerator / denominator;
  if (sums.denominator_bound > 0.0) {
    const double margin = denominator - sums.denominator_bound;
    evaluation.error_bound =
        margin > 0.0
            ? (sums.value_bound + (evaluation.displacement - sums.estimate).norm() * sums.denominator_bound) /
                  margin
            : std::numeric_limits<double>::infinity();
  }
  return evaluation;
}

template <bool WithRotations, int WholeExponent>
IdwTree::Evaluation IdwTree::evaluate_exact_sum(const Vector3& point) const {
  Sums sums;
  add_nodes<WithRotations, WholeExponent>(point, 0, static_cast<int>(x_.size()), sums);
  return finish<WithRotations>(point, sums);
}

IdwTree::Evaluation IdwTree::evaluate(const Vector3& point, double tolerance) const {
  return with_whole_exponent(whole_exponent_, [&](auto exponent) {
    constexpr int whole = decltype(exponent)::value;
    return with_rotations_ ? evaluate_tree<true, whole>(point, tolerance)
                           : evaluate_tree<false, whole>(point, tolerance);
  });
}

IdwTree::Evaluation IdwTree::evaluate_exact(const Vector3& point) const {
  return with_whole_exponent(whole_exponent_, [&](auto exponent) {
    constexpr int whole = decltype(exponent)::value;
    return with_rotations_ ? evaluate_exact_sum<true, whole>(point) : evaluate_exact_sum<false, whole>(point);
  });
}

}  // namespace mixmesh::deform
