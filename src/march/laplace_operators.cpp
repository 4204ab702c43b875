#include "mixmesh/march/laplace_operators.hpp"

#include <cmath>

namespace mixmesh {

namespace {

// The centre that solves the frozen equation for the given neighbour points.
Vector3 apply_weights(const LaplaceWeights& weights, const std::vector<Vector3>& points,
                      const Vector3& target) {
  Vector3 sum = weights.target_weight * target;
  for (std::size_t k = 0; k < weights.neighbour.size(); ++k) sum += weights.neighbour[k] * points[k];
  return sum / weights.denominator;
}

std::vector<Vector3> stencil_points(const StructuredStencil& layer) {
  return {layer.east,       layer.west,       layer.north,      layer.south,
          layer.north_east, layer.north_west, layer.south_east, layer.south_west};
}

}  // namespace

LaplaceWeights structured_laplace_weights(const StructuredStencil& layer, const Vector3& target,
                                          const Vector3& below) {
  const Vector3 x_xi = 0.5 * (layer.east - layer.west);
  const Vector3 x_eta = 0.5 * (layer.north - layer.south);
  const Vector3 x_zeta = target - below;
  // Wild eq. (2): face vectors of the computational cell.
  const Vector3 s1 = x_eta.cross(x_zeta);
  const Vector3 s2 = x_zeta.cross(x_xi);
  const Vector3 s3 = x_xi.cross(x_eta);
  const double a1 = s1.squaredNorm();
  const double a2 = s2.squaredNorm();
  const double a3 = s3.squaredNorm();
  LaplaceWeights weights;
  // Wild eq. (1) without control terms, solved for the centre:
  // a1 (E + W - 2x) + a2 (N + S - 2x) + 2 a3 (target - x) + 2 s1.s2 x_xi_eta = 0,
  // x_xi_eta = (NE - SE - NW + SW) / 4.
  const double denominator = 2.0 * (a1 + a2 + a3);
  if (!(denominator > 0.0)) {
    weights.neighbour.assign(8, 0.0);
    return weights;
  }
  const double cross = 0.5 * s1.dot(s2);
  weights.neighbour = {a1, a1, a2, a2, cross, -cross, -cross, cross};
  weights.target_weight = 2.0 * a3;
  weights.denominator = denominator;
  return weights;
}

Vector3 structured_laplace_update(const StructuredStencil& layer, const Vector3& target,
                                  const Vector3& below) {
  return apply_weights(structured_laplace_weights(layer, target, below), stencil_points(layer), target);
}

LaplaceWeights prism_laplace_weights(const std::vector<Vector3>& ring, const Vector3& centre,
                                     const Vector3& target, const Vector3& below) {
  const int count = static_cast<int>(ring.size());
  LaplaceWeights weights;
  weights.neighbour.assign(ring.size(), 0.0);
  if (count < 3) return weights;
  const double pi = std::acos(-1.0);
  std::vector<Vector3> radial(static_cast<std::size_t>(count)),
      circumferential(static_cast<std::size_t>(count));
  // Wild eq. (3): edge vectors of the ring.
  for (int n = 0; n < count; ++n) {
    const Vector3& here = ring[static_cast<std::size_t>(n)];
    const Vector3& next = ring[static_cast<std::size_t>((n + 1) % count)];
    radial[static_cast<std::size_t>(n)] = 0.5 * (here + next) - centre;
    circumferential[static_cast<std::size_t>(n)] = next - here;
  }
  const Vector3 marching = target - below;  // Delta t
  const double marching_scale = 1.0 / std::pow(std::cos(pi / count), 2);
  double target_weight = 0.0, denominator = 0.0;
  for (int n = 0; n < count; ++n) {
    // Wild eq. (5): averaged edge vectors, the first Fourier mode of the ring.
    Vector3 radial_mean = Vector3::Zero(), circumferential_mean = Vector3::Zero();
    for (int i = 0; i < count; ++i) {
      const double weight = 2.0 / count * std::cos(2.0 * pi * (i - n) / count);
      radial_mean += weight * radial[static_cast<std::size_t>(i)];
      circumferential_mean += weight * circumferential[static_cast<std::size_t>(i)];
    }
    // Wild eq. (4) with the averaged vectors.
    const Vector3 o = circumferential_mean.cross(marching);
    const Vector3 p = marching.cross(radial_mean);
    const Vector3 q = radial_mean.cross(circumferential_mean);
    const double oo = o.squaredNorm();
    const double qq = marching_scale * q.squaredNorm();
    const double op = o.dot(p);
    // Wild eq. (6): 0.5 oo (here + next) + o.p (next - here) + 0.5 qq target; the
    // marching differences enter through target (see header).
    weights.neighbour[static_cast<std::size_t>(n)] += 0.5 * oo - op;
    weights.neighbour[static_cast<std::size_t>((n + 1) % count)] += 0.5 * oo + op;
    target_weight += 0.5 * qq;
    denominator += oo + 0.5 * qq;
  }
  if (!(denominator > 0.0)) {
    weights.neighbour.assign(ring.size(), 0.0);
    return weights;
  }
  weights.target_weight = target_weight;
  weights.denominator = denominator;
  return weights;
}

Vector3 prism_laplace_update(const std::vector<Vector3>& ring, const Vector3& centre, const Vector3& target,
                             const Vector3& below) {
  return apply_weights(prism_laplace_weights(ring, centre, target, below), ring, target);
}

}  // namespace mixmesh
