#include "mixmesh/march/laplace_operators.hpp"

#include <cmath>

namespace mixmesh {

Vector3 structured_laplace_update(const StructuredStencil& layer, const Vector3& target,
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
  const Vector3 x_xi_eta = 0.25 * (layer.north_east - layer.south_east - layer.north_west + layer.south_west);
  // Wild eq. (1) without control terms, solved for the centre:
  // a1 (E + W - 2x) + a2 (N + S - 2x) + 2 a3 (target - x) + 2 s1.s2 x_xi_eta = 0.
  const double denominator = 2.0 * (a1 + a2 + a3);
  if (!(denominator > 0.0)) return target;
  return (a1 * (layer.east + layer.west) + a2 * (layer.north + layer.south) + 2.0 * a3 * target +
          2.0 * s1.dot(s2) * x_xi_eta) /
         denominator;
}

Vector3 prism_laplace_update(const std::vector<Vector3>& ring, const Vector3& centre, const Vector3& target,
                             const Vector3& below) {
  const int count = static_cast<int>(ring.size());
  if (count < 3) return target;
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
  Vector3 numerator = Vector3::Zero();
  double denominator = 0.0;
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
    const Vector3& here = ring[static_cast<std::size_t>(n)];
    const Vector3& next = ring[static_cast<std::size_t>((n + 1) % count)];
    // Wild eq. (6): the marching differences enter through target (see header).
    numerator += 0.5 * oo * (here + next) + o.dot(p) * circumferential[static_cast<std::size_t>(n)] +
                 0.5 * qq * target;
    denominator += oo + 0.5 * qq;
  }
  if (!(denominator > 0.0)) return target;
  return numerator / denominator;
}

}  // namespace mixmesh
