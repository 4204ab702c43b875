// A smooth parametrisation of an airfoil outline by arc length: a natural cubic
// spline through the points in x(s) and z(s), with s the arc length of the spline
// itself (knots re-measured once by Gauss quadrature), so nodes can be placed at any
// arc-length fraction with any distribution.
//
//   s = 0                  lower trailing edge
//   s = leading_edge()     the leading-edge point (a knot: it stays exact)
//   s = length()           upper trailing edge
#pragma once

#include "mixmesh/geometry/airfoil.hpp"
#include "mixmesh/geometry/cubic_spline.hpp"

namespace mixmesh {

class AirfoilCurve {
 public:
  explicit AirfoilCurve(const Airfoil& airfoil);

  Vector2 point(double s) const { return {x_.value(s), z_.value(s)}; }
  Vector2 tangent(double s) const { return {x_.derivative(s), z_.derivative(s)}; }
  double length() const { return length_; }
  double leading_edge() const { return leading_edge_; }
  // Arc length of each input point.
  const std::vector<double>& knots() const { return x_.knots(); }

 private:
  CubicSpline x_;
  CubicSpline z_;
  double length_ = 0.0;
  double leading_edge_ = 0.0;
};

}  // namespace mixmesh
