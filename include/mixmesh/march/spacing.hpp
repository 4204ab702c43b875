// Wall-normal spacing of the marched layers: the first spacing (given, or from a
// target y+) and the growth law that turns it into one step per layer.
#pragma once

#include <optional>
#include <vector>

namespace mixmesh {

enum class GrowthLaw { geometric, tanh };

struct SpacingOptions {
  // First spacing in metres; when absent it comes from target_y_plus, reynolds_number
  // and reference_length (first_spacing_from_y_plus).
  std::optional<double> first_spacing;
  double target_y_plus = 1.0;
  double reynolds_number = 11.72e6;  // ONERA M6 test point, on the MAC
  double reference_length = 0.646;   // ONERA M6 mean aerodynamic chord (m)
  int layer_count = 32;
  GrowthLaw growth_law = GrowthLaw::geometric;
  double growth_rate = 1.25;              // geometric: step(k+1) = growth_rate * step(k)
  std::optional<double> total_thickness;  // tanh: required total thickness (m)
};

// Flat-plate estimate: Cf = 0.026 / Re^(1/7), u_tau = U sqrt(Cf / 2),
// spacing = y+ nu / u_tau = y+ L / (Re sqrt(Cf / 2)) (U cancels with nu = U L / Re).
// Throws mixmesh::Error for a non-positive y+, Reynolds number or length.
double first_spacing_from_y_plus(double y_plus, double reynolds_number, double reference_length);

// The step of every layer, layer_count entries, from the options. Throws
// mixmesh::Error for inconsistent options (no layers, growth rate < 1, a tanh law
// whose thickness cannot hold the first spacing).
std::vector<double> layer_steps(const SpacingOptions& options);

// The steps of a line on a wake sheet at `distance` d (m) from the trailing edge, from
// the N steps of the wall lines (thickness T0): the stack thickens like a wedge of
// half-angle `spread_degrees` and its growth relaxes towards equal steps, each step's
// share of the thickness moving geometrically from the wall's share w_k to 1/N:
//   x = d tan(spread) / T0,  s = x^2 / (x + 1),  T(d) = T0 (1 + s),  b = s / (s + 16),
//   step_k = T(d) w_k^(1-b) N^(-b) / sum_j w_j^(1-b) N^(-b)
// s starts flat at the trailing edge (the lines there march as the wall's) and tends to
// x - 1 (thickness T0 + d tan(spread) - T0 far downstream). A geometric wall stack of
// growth g stays geometric with growth g^(1-b). At d = 0 and for spread 0 the steps are
// the wall's. Far downstream the first step tends to T(d) / N: the thin first layers
// the wall needs do not reach the sheet's free edges, where any deformation of the
// mesh would fold them (docs/march.md, "Wake layers").
// Throws mixmesh::Error for a negative distance, a spread outside [0, 45) degrees or
// non-positive wall steps.
std::vector<double> wake_layer_steps(const std::vector<double>& wall_steps, double distance,
                                     double spread_degrees);

// The N steps rescaled to sum to `thickness` when they sum to more, with the first
// step kept: step_k = s_0 (s_k / s_0)^e, the exponent e in [0, 1] found by bisection (a
// geometric stack of growth g stays geometric with growth g^e). Only when N s_0 alone
// exceeds the thickness are all steps equal, thickness / N. Steps that already fit are
// returned unchanged. Throws mixmesh::Error for a non-positive thickness or step.
std::vector<double> steps_within_thickness(const std::vector<double>& steps, double thickness);

}  // namespace mixmesh
