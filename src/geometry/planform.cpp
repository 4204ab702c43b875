#include "mixmesh/geometry/planform.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mixmesh/core/error.hpp"

namespace mixmesh {
namespace {

double radians(double degrees) {
  return degrees * M_PI / 180.0;
}

}  // namespace

WingDefinition classic_wing(const ClassicPlanform& planform, Airfoil airfoil) {
  if (!(planform.root_chord > 0.0)) throw Error("root chord must be positive");
  if (!(planform.semi_span > 0.0)) throw Error("semi-span must be positive");
  if (planform.trailing_edge_sweep_degrees.has_value() == planform.taper.has_value()) {
    throw Error("give exactly one of trailing-edge sweep and taper");
  }
  const double span = planform.semi_span;
  const double tip_leading_edge = span * std::tan(radians(planform.leading_edge_sweep_degrees));
  double tip_chord = 0.0;
  if (planform.taper) {
    tip_chord = *planform.taper * planform.root_chord;
  } else {
    tip_chord = planform.root_chord + span * std::tan(radians(*planform.trailing_edge_sweep_degrees)) -
                tip_leading_edge;
  }
  if (!(tip_chord > 0.0)) {
    std::ostringstream message;
    message << "the planform gives a tip chord of " << tip_chord
            << " (sweeps or taper leave no wing at the tip)";
    throw Error(message.str());
  }
  WingDefinition wing;
  wing.airfoils.push_back(std::move(airfoil));
  SpanStation root;
  root.chord = planform.root_chord;
  root.twist_degrees = planform.root_twist_degrees;
  SpanStation tip;
  tip.y = span;
  tip.chord = tip_chord;
  tip.leading_edge_x = tip_leading_edge;
  tip.leading_edge_z = span * std::tan(radians(planform.dihedral_degrees));
  tip.twist_degrees = planform.tip_twist_degrees;
  wing.stations = {root, tip};
  return wing;
}

void validate_wing(const WingDefinition& wing) {
  if (wing.stations.size() < 2) throw Error("a wing needs at least two span stations");
  if (wing.stations.front().y != 0.0) {
    throw Error("the first span station must lie on the symmetry plane y = 0, got y = " +
                std::to_string(wing.stations.front().y));
  }
  for (std::size_t k = 0; k < wing.stations.size(); ++k) {
    const SpanStation& station = wing.stations[k];
    const std::string name = "span station " + std::to_string(k + 1);
    if (!(station.chord > 0.0))
      throw Error(name + ": chord must be positive, got " + std::to_string(station.chord));
    if (station.airfoil >= wing.airfoils.size()) throw Error(name + ": no such airfoil");
    if (k > 0 && !(station.y > wing.stations[k - 1].y)) {
      throw Error(name + ": y must increase from station to station");
    }
  }
  if (!(wing.twist_axis >= 0.0 && wing.twist_axis <= 1.0)) throw Error("twist axis must lie in [0, 1]");
}

StationBlend station_at(const WingDefinition& wing, double y) {
  const auto& stations = wing.stations;
  std::size_t upper = 1;
  while (upper + 1 < stations.size() && stations[upper].y < y) ++upper;
  const SpanStation& a = stations[upper - 1];
  const SpanStation& b = stations[upper];
  const double weight = std::clamp((y - a.y) / (b.y - a.y), 0.0, 1.0);
  const auto mix = [weight](double first, double second) { return (1.0 - weight) * first + weight * second; };
  StationBlend blend;
  blend.parameters.y = y;
  blend.parameters.chord = mix(a.chord, b.chord);
  blend.parameters.leading_edge_x = mix(a.leading_edge_x, b.leading_edge_x);
  blend.parameters.leading_edge_z = mix(a.leading_edge_z, b.leading_edge_z);
  blend.parameters.twist_degrees = mix(a.twist_degrees, b.twist_degrees);
  blend.parameters.airfoil = weight < 0.5 ? a.airfoil : b.airfoil;
  blend.first_airfoil = a.airfoil;
  blend.second_airfoil = b.airfoil;
  blend.weight = weight;
  return blend;
}

Eigen::Vector3d place_section_point(const SpanStation& station, double twist_axis, const Vector2& point) {
  const double angle = radians(station.twist_degrees);
  const double cosine = std::cos(angle), sine = std::sin(angle);
  const double x = point.x() - twist_axis;
  // Positive twist rotates nose up: the leading edge (x < axis) rises.
  const double twisted_x = twist_axis + cosine * x + sine * point.y();
  const double twisted_z = -sine * x + cosine * point.y();
  return {station.leading_edge_x + station.chord * twisted_x, station.y,
          station.leading_edge_z + station.chord * twisted_z};
}

}  // namespace mixmesh
