#include "mixmesh/march/spacing.hpp"

#include <cmath>
#include <sstream>

#include "mixmesh/core/error.hpp"

namespace mixmesh {

namespace {

std::string number(double value) {
  std::ostringstream stream;
  stream << value;
  return stream.str();
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
  const double first = options.first_spacing > 0.0
                           ? options.first_spacing
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
  const double thickness = options.total_thickness;
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

}  // namespace mixmesh
