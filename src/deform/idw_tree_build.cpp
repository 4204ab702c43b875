// Construction of the IDW tree code (idw_tree.hpp): the k-d tree over the boundary nodes and
// each cluster's moments and error-bound data.
#include "mixmesh/deform/idw_tree.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>

#include "mixmesh/core/error.hpp"

namespace mixmesh::deform {

namespace {

// Depth down to which the tree splits at box midpoints (see the constructor); with median
// splits below, the depth stays under midpoint_depth + 32, within the traversal stack
// (idw_tree.cpp).
constexpr int midpoint_depth = 64;
// (xx, yy, zz, xy, xz, yz) products of a vector with itself.
Eigen::Matrix<double, 6, 1> symmetric_products(const Vector3& v) {
  Eigen::Matrix<double, 6, 1> products;
  products << v.x() * v.x(), v.y() * v.y(), v.z() * v.z(), v.x() * v.y(), v.x() * v.z(), v.y() * v.z();
  return products;
}

// Coefficients (lowest first) of P with (1 − t)^-p − 1 − pt − p(p+1)t²/2 = t³ P(t) / (1 − t)^p
// for a whole p ≤ 8: 1 − (1 + pt + p(p+1)t²/2)(1 − t)^p has no terms below t³.
std::array<double, 8> tail_polynomial(int p) {
  std::array<double, 11> binomial{};  // coefficients of (1 − t)^p
  binomial[0] = 1.0;
  for (int k = 1; k <= p; ++k)
    binomial[static_cast<std::size_t>(k)] = -binomial[static_cast<std::size_t>(k - 1)] * (p - k + 1) / k;
  const std::array<double, 3> quadratic{1.0, static_cast<double>(p), 0.5 * p * (p + 1)};
  std::array<double, 11> product{};
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j < 3; ++j)
      product[static_cast<std::size_t>(i + j)] +=
          binomial[static_cast<std::size_t>(i)] * quadratic[static_cast<std::size_t>(j)];
  std::array<double, 8> coefficients{};
  for (int k = 3; k <= p + 2; ++k)
    coefficients[static_cast<std::size_t>(k - 3)] = -product[static_cast<std::size_t>(k)];
  return coefficients;
}

}  // namespace

IdwTree::IdwTree(const std::vector<Vector3>& positions, const std::vector<Vector3>& displacements,
                 const std::vector<Eigen::Matrix3d>& rotations, double exponent, int leaf_size)
    : exponent_(exponent),
      whole_exponent_(exponent == std::floor(exponent) && exponent >= 1.0 && exponent <= 8.0
                          ? static_cast<int>(exponent)
                          : 0),
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
    // Splits at the middle of the longest side of the nodes' box (sliding midpoint), so that
    // separate bodies (a wing and its far-field boundary) fall into separate subtrees within a
    // few levels; median splits would carry far-field nodes down with the dense body nodes.
    // Below midpoint_depth, and when a midpoint split leaves a side empty, median splits
    // bound the depth (and so the traversal stack) by midpoint_depth + log2(#B).
    struct Range {
      int begin, end, cluster, depth;
    };
    clusters_.push_back(Cluster{});
    std::vector<Range> pending{{0, static_cast<int>(positions.size()), 0, 0}};
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
      int middle = range.begin;
      if (range.depth < midpoint_depth) {
        const double split = 0.5 * (low[axis] + high[axis]);
        middle =
            static_cast<int>(std::partition(order.begin() + range.begin, order.begin() + range.end,
                                            [&](int node) {
                                              return positions[static_cast<std::size_t>(node)][axis] < split;
                                            }) -
                             order.begin());
      }
      if (middle == range.begin || middle == range.end) {
        middle = range.begin + (range.end - range.begin) / 2;
        std::nth_element(order.begin() + range.begin, order.begin() + middle, order.begin() + range.end,
                         [&](int left, int right) {
                           return positions[static_cast<std::size_t>(left)][axis] <
                                  positions[static_cast<std::size_t>(right)][axis];
                         });
      }
      const int first_child = static_cast<int>(clusters_.size());
      clusters_[static_cast<std::size_t>(range.cluster)].first_child = first_child;
      clusters_.push_back(Cluster{});
      clusters_.push_back(Cluster{});
      pending.push_back({range.begin, middle, first_child, range.depth + 1});
      pending.push_back({middle, range.end, first_child + 1, range.depth + 1});
    }
  }
  if (whole_exponent_ > 0)
    tail_polynomial_ = tail_polynomial(whole_exponent_);
  else
    lagrange_factor_ = exponent * (exponent + 1.0) * (exponent + 2.0) / 6.0;
  const std::size_t count = positions.size();
  for (std::vector<double>* array : {&x_, &y_, &z_, &ax_, &ay_, &az_}) array->resize(count);
  displacements_.resize(count);
  if (with_rotations_) b_.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t source = static_cast<std::size_t>(order[k]);
    const Vector3& position = positions[source];
    displacements_[k] = displacements[source];
    if (!position.allFinite() || !displacements_[k].allFinite())
      throw Error("idw tree: boundary node " + std::to_string(source) + " has a non-finite coordinate");
    Vector3 a = displacements_[k];
    if (with_rotations_) {
      b_[k] = rotations[source] - Eigen::Matrix3d::Identity();
      a -= b_[k] * position;
    }
    x_[k] = position.x(), y_[k] = position.y(), z_[k] = position.z();
    ax_[k] = a.x(), ay_[k] = a.y(), az_[k] = a.z();
  }
  double largest_displacement = 0.0, largest_rotation = 0.0;
  Eigen::AlignedBox3d box;
  for (std::size_t k = 0; k < count; ++k) {
    largest_displacement = std::max(largest_displacement, displacements_[k].norm());
    if (with_rotations_) largest_rotation = std::max(largest_rotation, b_[k].norm());
    box.extend(Vector3(x_[k], y_[k], z_[k]));
  }
  value_scale_ = largest_displacement + largest_rotation * box.diagonal().norm();
  moments_.assign(clusters_.size(), Moments::Zero());
  if (with_rotations_) rotation_moments_.resize(clusters_.size());
  for (std::size_t index = 0; index < clusters_.size(); ++index) summarise(index);
}

void IdwTree::summarise(std::size_t index) {
  Cluster& cluster = clusters_[index];
  Moments& moments = moments_[index];
  const double count = cluster.end - cluster.begin;
  Vector3 centroid = Vector3::Zero();
  Eigen::Matrix3d mean_b = Eigen::Matrix3d::Zero();
  for (int k = cluster.begin; k < cluster.end; ++k) {
    const std::size_t j = static_cast<std::size_t>(k);
    centroid += Vector3(x_[j], y_[j], z_[j]);
    cluster.mean_displacement += displacements_[j];
    if (with_rotations_) mean_b += b_[j];
  }
  cluster.centroid = centroid / count;
  cluster.mean_displacement /= count;
  if (with_rotations_) rotation_moments_[index].mean_b = mean_b / count;
  for (int k = cluster.begin; k < cluster.end; ++k) {
    const std::size_t j = static_cast<std::size_t>(k);
    const Vector3 offset = Vector3(x_[j], y_[j], z_[j]) - cluster.centroid;
    const Vector3 a(ax_[j], ay_[j], az_[j]);
    const double length = offset.norm();
    const double cube = length * length * length;
    cluster.radius = std::max(cluster.radius, length);
    cluster.cubic_spread += cube;
    const Eigen::Matrix<double, 6, 1> products = symmetric_products(offset);
    Eigen::Matrix<double, 10, 1> terms;
    terms << 1.0, offset, products;
    moments += Eigen::Vector4d(a.x(), a.y(), a.z(), 1.0) * terms.transpose();
    const double rotation_norm = with_rotations_ ? b_[j].norm() : 0.0;
    cluster.displacement_spread += (displacements_[j] - cluster.mean_displacement).norm();
    cluster.value_spread +=
        cube * ((displacements_[j] - cluster.mean_displacement).norm() + rotation_norm * length);
    if (with_rotations_) {
      RotationMoments& rotation = rotation_moments_[index];
      rotation.sum_b += b_[j];
      for (int axis = 0; axis < 3; ++axis)
        rotation.moment_b[static_cast<std::size_t>(axis)] += offset[axis] * b_[j];
      for (int entry = 0; entry < 6; ++entry)
        rotation.moment2_b[static_cast<std::size_t>(entry)] += products[entry] * b_[j];
      rotation.rotation_spread += cube * (b_[j] - rotation.mean_b).norm();
    }
  }
}

}  // namespace mixmesh::deform
