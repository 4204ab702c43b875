// Natural cubic spline through (t_k, v_k), t strictly increasing. Evaluation outside
// [t_0, t_n] extrapolates the end cubic.
#pragma once

#include <vector>

namespace mixmesh {

class CubicSpline {
 public:
  CubicSpline() = default;
  // knots: strictly increasing, at least two; values: one per knot.
  CubicSpline(std::vector<double> knots, std::vector<double> values);

  double value(double t) const;
  double derivative(double t) const;
  const std::vector<double>& knots() const { return knots_; }

 private:
  std::size_t interval(double t) const;
  std::vector<double> knots_;
  std::vector<double> values_;
  std::vector<double> second_derivatives_;
};

}  // namespace mixmesh
