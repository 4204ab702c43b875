#include "mixmesh/march/spacing.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "mixmesh/core/error.hpp"

namespace mixmesh {

namespace {

std::string number(double value) {
  std::ostringstream stream;
  stream << value;
  return stream.str();
}

// The sum of `steps`, each checked to be positive and finite (`what` names them).
double positive_sum(const std::vector<double>& steps, const std::string& what) {
  double sum = 0.0;
  for (double step : steps) {
    if (!(step > 0.0) || !std::isfinite(step)) throw Error("march: " + what + " must be positive, got " + number(step));
    sum += step;
  }
  return sum;
}

}  // namespace

double first_spacing_from_y_plus(double y_plus, double reynolds_number, double reference_length) {
  if (!(y_plus > 0.0)) throw Error("march: target y+ must be positive, got " + number(y_plus));
  if (!(reynolds_number > 0.0))
    throw Error("march: Reynolds number must be positive, got " + number(reynolds_number));
  if (!(reference_length > 0.0))
    throw Error("march: reference length must be positive, got " + number(reference_length));
  // Flat-plate turbulent skin friction (Schlichting's 1/7-power estimate).
  const double skin_friction = 0.026 / std::pow(reynolds_number, 1.0 / 7.0);
  // u_tau / U = sqrt(Cf / 2); nu / U = L / Re.
  return y_plus * reference_length / (reynolds_number * std::sqrt(0.5 * skin_friction));
}

std::vector<double> layer_steps(const SpacingOptions& options) {
  if (options.layer_count < 1)
    throw Error("march: layer count must be at least 1, got " + std::to_string(options.layer_count));
  if (options.first_spacing && !(*options.first_spacing > 0.0))
    throw Error("march: first spacing must be positive, got " + number(*options.first_spacing));
  const double first = options.first_spacing
                           ? *options.first_spacing
                           : first_spacing_from_y_plus(options.target_y_plus, options.reynolds_number,
                                                       options.reference_length);
  const auto count = static_cast<std::size_t>(options.layer_count);
  std::vector<double> steps(count);
  if (options.growth_law == GrowthLaw::geometric) {
    if (!(options.growth_rate >= 1.0) || !std::isfinite(options.growth_rate))
      throw Error("march: growth rate must be at least 1, got " + number(options.growth_rate));
    double step = first;
    for (double& value : steps) {
      value = step;
      step *= options.growth_rate;
    }
    return steps;
  }
  // One-sided tanh stretching: s(t) = T (1 + tanh(delta (t - 1)) / tanh(delta)),
  // t = k / N; delta is chosen so that the first step equals the first spacing.
  if (!options.total_thickness) throw Error("march: tanh growth needs a total thickness");
  const double thickness = *options.total_thickness;
  if (!(thickness > first * static_cast<double>(count)))
    throw Error("march: tanh growth needs a total thickness above layer count x first spacing (" +
                number(first * static_cast<double>(count)) + " m), got " + number(thickness));
  const double n = static_cast<double>(count);
  auto first_step = [&](double delta) {
    return thickness * (1.0 + std::tanh(delta * (1.0 / n - 1.0)) / std::tanh(delta));
  };
  // first_step falls from T / N (delta -> 0) towards 0 as delta grows: bisection.
  double low = 1e-8, high = 1.0;
  while (first_step(high) > first) {
    high *= 2.0;
    if (high > 1e3) throw Error("march: tanh growth cannot reach a first spacing of " + number(first));
  }
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double middle = 0.5 * (low + high);
    (first_step(middle) > first ? low : high) = middle;
  }
  const double delta = 0.5 * (low + high);
  auto position = [&](double t) {
    return thickness * (1.0 + std::tanh(delta * (t - 1.0)) / std::tanh(delta));
  };
  for (std::size_t k = 0; k < count; ++k)
    steps[k] = position(static_cast<double>(k + 1) / n) - position(static_cast<double>(k) / n);
  return steps;
}

std::vector<double> wake_layer_steps(const std::vector<double>& wall_steps, double distance,
                                     double spread_degrees) {
  if (!(distance >= 0.0) || !std::isfinite(distance))
    throw Error("march: wake distance must be finite and >= 0, got " + number(distance));
  if (!(spread_degrees >= 0.0 && spread_degrees < 45.0))
    throw Error("march: wake spread must lie in [0, 45) degrees, got " + number(spread_degrees));
  const double thickness = positive_sum(wall_steps, "wall steps");
  if (wall_steps.empty()) return wall_steps;
  // The wedge's added thickness in wall thicknesses, x, starts as x^2 / (x + 1): flat at
  // the trailing edge, so the lines next to it (and the wing's cells that share their
  // nodes) march as the wall's do, and x - 1 downstream.
  const double wedge = distance * std::tan(spread_degrees * M_PI / 180.0) / thickness;
  const double spread = wedge * wedge / (wedge + 1.0);
  if (spread == 0.0) return wall_steps;
  // The blend reaches half way to equal steps where the wedge has added 16 wall
  // thicknesses: the outer layers stay thick enough for the interface's split, and the
  // first step grows by at most 1.56 from one wake cell to the next (streamwise cells
  // growing by 1.2, docs/march.md).
  const double blend = spread / (spread + 16.0);
  const double count = static_cast<double>(wall_steps.size());
  std::vector<double> steps(wall_steps.size());
  double sum = 0.0;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    // In logarithms: the share w_k^(1-b) (1/N)^b without underflow for tiny shares.
    steps[k] = std::exp((1.0 - blend) * std::log(wall_steps[k] / thickness) - blend * std::log(count));
    sum += steps[k];
  }
  const double scale = thickness * (1.0 + spread) / sum;
  for (double& step : steps) step *= scale;
  return steps;
}

std::vector<double> steps_within_thickness(const std::vector<double>& steps, double thickness) {
  if (!(thickness > 0.0) || !std::isfinite(thickness))
    throw Error("march: a layer thickness limit must be positive, got " + number(thickness));
  if (positive_sum(steps, "steps") <= thickness) return steps;
  const double first = steps.front();
  const auto scaled = [&](double exponent) {
    std::vector<double> result(steps.size());
    for (std::size_t k = 0; k < steps.size(); ++k) result[k] = first * std::pow(steps[k] / first, exponent);
    return result;
  };
  const auto sum = [](const std::vector<double>& values) {
    double result = 0.0;
    for (double value : values) result += value;
    return result;
  };
  if (sum(scaled(0.0)) >= thickness)
    return std::vector<double>(steps.size(), thickness / static_cast<double>(steps.size()));
  double low = 0.0, high = 1.0;
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double middle = 0.5 * (low + high);
    (sum(scaled(middle)) > thickness ? high : low) = middle;
  }
  return scaled(low);
}

}  // namespace mixmesh
