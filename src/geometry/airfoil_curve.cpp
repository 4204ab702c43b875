#include "mixmesh/geometry/airfoil_curve.hpp"

#include <array>
#include <cmath>

namespace mixmesh {
namespace {

// Arc length of the spline between two knots: 5-point Gauss-Legendre on |c'(s)|.
double interval_length(const CubicSpline& x, const CubicSpline& z, double from, double to) {
  static constexpr std::array<double, 5> abscissae = {0.0, -0.5384693101056831, 0.5384693101056831,
                                                      -0.9061798459386640, 0.9061798459386640};
  static constexpr std::array<double, 5> weights = {
      0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891, 0.2369268850561891};
  const double half = 0.5 * (to - from), middle = 0.5 * (to + from);
  double length = 0.0;
  for (std::size_t k = 0; k < abscissae.size(); ++k) {
    const double s = middle + half * abscissae[k];
    length += weights[k] * std::hypot(x.derivative(s), z.derivative(s));
  }
  return half * length;
}

}  // namespace

AirfoilCurve::AirfoilCurve(const Airfoil& airfoil) {
  const std::size_t count = airfoil.points.size();
  std::vector<double> knots(count, 0.0), xs(count), zs(count);
  for (std::size_t k = 0; k < count; ++k) {
    xs[k] = airfoil.points[k].x();
    zs[k] = airfoil.points[k].y();
    if (k > 0) knots[k] = knots[k - 1] + (airfoil.points[k] - airfoil.points[k - 1]).norm();
  }
  // Chord-length knots approximate arc length; one re-measurement on the spline itself
  // makes s the arc length to well below the accuracy the surface needs.
  const CubicSpline first_x(knots, xs), first_z(knots, zs);
  std::vector<double> arc(count, 0.0);
  for (std::size_t k = 1; k < count; ++k) {
    arc[k] = arc[k - 1] + interval_length(first_x, first_z, knots[k - 1], knots[k]);
  }
  x_ = CubicSpline(arc, xs);
  z_ = CubicSpline(arc, zs);
  length_ = arc.back();
  leading_edge_ = arc[airfoil.leading_edge];
}

}  // namespace mixmesh
