#include "mixmesh/geometry/distribution.hpp"

#include <cmath>
#include <sstream>

#include "mixmesh/core/error.hpp"

namespace mixmesh {
namespace {

// The root x > 0 of f(x) = value, f monotone on (low, high), by bisection: robust
// for every stretching strength and cheap at this size.
template <typename Function>
double solve_monotone(Function function, double value, double low, double high) {
  const bool increasing = function(high) > function(low);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double middle = 0.5 * (low + high);
    if ((function(middle) < value) == increasing) {
      low = middle;
    } else {
      high = middle;
    }
  }
  return 0.5 * (low + high);
}

double sinh_ratio(double x) {
  return std::sinh(x) / x;
}
double sin_ratio(double x) {
  return std::sin(x) / x;
}

// The stretching parameter of Vinokur's functions for end-slope measure b: delta with
// sinh(delta)/delta = b (b > 1, tanh form) or sin(delta)/delta = b (b < 1, tan form);
// 0 selects the near-uniform polynomial.
double stretching_parameter(double b) {
  if (b > 1.0 + 1e-6) return solve_monotone(sinh_ratio, b, 1e-9, 60.0);
  if (b < 1.0 - 1e-6) return -solve_monotone(sin_ratio, b, 1e-9, M_PI - 1e-9);
  return 0.0;
}

// Vinokur's symmetric stretching u(xi) on [0, 1] with end slope du/dxi = 1 / (cells b);
// negative delta marks the tan form.
double symmetric_stretching(double xi, double delta, double b) {
  if (delta > 0.0) return 0.5 * (1.0 + std::tanh(delta * (xi - 0.5)) / std::tanh(0.5 * delta));
  if (delta < 0.0) return 0.5 * (1.0 + std::tan(-delta * (xi - 0.5)) / std::tan(-0.5 * delta));
  return xi * (1.0 + 2.0 * (b - 1.0) * (xi - 0.5) * (1.0 - xi));
}

// One-sided stretching s(xi) with end slope ds/dxi = 1 / b at xi = 0.
double one_sided_stretching(double xi, double delta, double b) {
  if (delta > 0.0) return 1.0 + std::tanh(0.5 * delta * (xi - 1.0)) / std::tanh(0.5 * delta);
  if (delta < 0.0) return 1.0 + std::tan(-0.5 * delta * (xi - 1.0)) / std::tan(-0.5 * delta);
  return xi * (1.0 + (b - 1.0) * (xi - 1.0));
}

// Vinokur's closed form for given end spacings (fractions), before correction.
std::vector<double> vinokur_closed_form(int cells, double first, double last) {
  std::vector<double> positions(static_cast<std::size_t>(cells) + 1);
  const double n = cells;
  const bool two_sided = first > 0.0 && last > 0.0;
  // Ratio of end slopes A = sqrt(last / first); s = u / (A + (1 - A) u).
  const double a = two_sided ? std::sqrt(last / first) : 1.0;
  const double b = two_sided ? 1.0 / (n * std::sqrt(first * last)) : 1.0 / (n * (first > 0.0 ? first : last));
  const double delta = stretching_parameter(b);
  for (int node = 0; node <= cells; ++node) {
    const double xi = node / n;
    double s = 0.0;
    if (two_sided) {
      const double u = symmetric_stretching(xi, delta, b);
      s = u / (a + (1.0 - a) * u);
    } else if (first > 0.0) {
      s = one_sided_stretching(xi, delta, b);
    } else {
      s = 1.0 - one_sided_stretching(1.0 - xi, delta, b);
    }
    positions[static_cast<std::size_t>(node)] = s;
  }
  positions.front() = 0.0;
  positions.back() = 1.0;
  return positions;
}

}  // namespace

std::vector<double> uniform_distribution(int cells) {
  if (cells < 1) throw Error("a point distribution needs at least one cell, got " + std::to_string(cells));
  std::vector<double> positions(static_cast<std::size_t>(cells) + 1);
  for (int node = 0; node <= cells; ++node) positions[static_cast<std::size_t>(node)] = double(node) / cells;
  return positions;
}

std::vector<double> vinokur_distribution(int cells, double first_spacing, double last_spacing) {
  if (cells < 1) throw Error("a point distribution needs at least one cell, got " + std::to_string(cells));
  if (first_spacing <= 0.0 && last_spacing <= 0.0) return uniform_distribution(cells);
  const double first = std::max(first_spacing, 0.0);
  const double last = std::max(last_spacing, 0.0);
  if (first + last >= 1.0 || (cells == 1) || (cells == 2 && first > 0.0 && last > 0.0)) {
    std::ostringstream message;
    message << "end spacings " << first_spacing << " and " << last_spacing << " (fractions of the length) "
            << "do not fit in " << cells << " cells";
    throw Error(message.str());
  }
  // The closed form matches end derivatives; correct its inputs so that the discrete
  // first and last intervals equal the requested spacings.
  double first_input = first;
  double last_input = last;
  std::vector<double> positions;
  for (int iteration = 0; iteration < 100; ++iteration) {
    positions = vinokur_closed_form(cells, first_input, last_input);
    const double first_actual = positions[1] - positions[0];
    const double last_actual = positions[cells] - positions[cells - 1];
    bool converged = true;
    if (first > 0.0) {
      converged = converged && std::abs(first_actual / first - 1.0) < 1e-11;
      first_input *= first / first_actual;
    }
    if (last > 0.0) {
      converged = converged && std::abs(last_actual / last - 1.0) < 1e-11;
      last_input *= last / last_actual;
    }
    if (converged) break;
  }
  for (int node = 1; node <= cells; ++node) {
    if (!(positions[node] > positions[node - 1])) {
      std::ostringstream message;
      message << "end spacings " << first_spacing << " and " << last_spacing << " give no monotone "
              << "distribution of " << cells << " cells";
      throw Error(message.str());
    }
  }
  return positions;
}

std::vector<double> geometric_distribution(double first_spacing, double growth) {
  if (!(first_spacing > 0.0 && first_spacing < 1.0)) {
    throw Error("geometric distribution: first spacing must lie in (0, 1), got " +
                std::to_string(first_spacing));
  }
  if (!(growth >= 1.0 && growth < 10.0)) {
    throw Error("geometric distribution: growth must lie in [1, 10), got " + std::to_string(growth));
  }
  std::vector<double> positions{0.0};
  double spacing = first_spacing;
  while (positions.back() + 0.5 * spacing < 1.0) {
    positions.push_back(positions.back() + spacing);
    spacing *= growth;
  }
  const double scale = 1.0 / positions.back();
  for (double& position : positions) position *= scale;
  positions.back() = 1.0;
  return positions;
}

}  // namespace mixmesh
