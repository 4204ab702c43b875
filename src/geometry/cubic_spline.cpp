#include "mixmesh/geometry/cubic_spline.hpp"

#include <algorithm>

#include "mixmesh/core/error.hpp"

namespace mixmesh {

CubicSpline::CubicSpline(std::vector<double> knots, std::vector<double> values)
    : knots_(std::move(knots)), values_(std::move(values)) {
  const std::size_t count = knots_.size();
  if (count < 2 || values_.size() != count) throw Error("cubic spline: needs two or more knots with values");
  for (std::size_t k = 1; k < count; ++k) {
    if (!(knots_[k] > knots_[k - 1])) throw Error("cubic spline: knots must increase strictly");
  }
  // Tridiagonal system for the second derivatives, natural ends (M_0 = M_n = 0),
  // solved by the Thomas algorithm.
  second_derivatives_.assign(count, 0.0);
  if (count == 2) return;
  std::vector<double> diagonal(count, 1.0), upper(count, 0.0), right(count, 0.0);
  for (std::size_t k = 1; k + 1 < count; ++k) {
    const double left_width = knots_[k] - knots_[k - 1];
    const double right_width = knots_[k + 1] - knots_[k];
    const double lower = left_width / 6.0;
    diagonal[k] = (left_width + right_width) / 3.0;
    upper[k] = right_width / 6.0;
    right[k] = (values_[k + 1] - values_[k]) / right_width - (values_[k] - values_[k - 1]) / left_width;
    // Eliminate the sub-diagonal entry with the previous row.
    const double factor = lower / diagonal[k - 1];
    diagonal[k] -= factor * upper[k - 1];
    right[k] -= factor * right[k - 1];
  }
  for (std::size_t k = count - 2; k >= 1; --k) {
    second_derivatives_[k] = (right[k] - upper[k] * second_derivatives_[k + 1]) / diagonal[k];
  }
}

std::size_t CubicSpline::interval(double t) const {
  const auto upper = std::upper_bound(knots_.begin(), knots_.end(), t);
  const std::ptrdiff_t index = (upper - knots_.begin()) - 1;
  return static_cast<std::size_t>(
      std::clamp<std::ptrdiff_t>(index, 0, static_cast<std::ptrdiff_t>(knots_.size()) - 2));
}

double CubicSpline::value(double t) const {
  const std::size_t k = interval(t);
  const double width = knots_[k + 1] - knots_[k];
  const double a = (knots_[k + 1] - t) / width;
  const double b = (t - knots_[k]) / width;
  return a * values_[k] + b * values_[k + 1] +
         ((a * a * a - a) * second_derivatives_[k] + (b * b * b - b) * second_derivatives_[k + 1]) * width *
             width / 6.0;
}

double CubicSpline::derivative(double t) const {
  const std::size_t k = interval(t);
  const double width = knots_[k + 1] - knots_[k];
  const double a = (knots_[k + 1] - t) / width;
  const double b = (t - knots_[k]) / width;
  return (values_[k + 1] - values_[k]) / width +
         (-(3.0 * a * a - 1.0) * second_derivatives_[k] + (3.0 * b * b - 1.0) * second_derivatives_[k + 1]) *
             width / 6.0;
}

}  // namespace mixmesh
