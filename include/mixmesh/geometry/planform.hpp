// Wing planform: span stations lofted linearly between them.
//
// A station is a section in the plane y = const: the unit-chord airfoil is twisted
// about the point twist_axis * chord behind the leading edge (positive twist raises
// the leading edge), scaled by the chord and moved to the leading edge (x, z). Between
// two stations every parameter varies linearly in y and the two airfoil shapes blend
// linearly at equal arc-length fractions, so the classic trapezoidal wing (two
// stations) is exact, including linear twist.
#pragma once

#include <optional>
#include <vector>

#include "mixmesh/geometry/airfoil.hpp"

namespace mixmesh {

struct SpanStation {
  double y = 0.0;
  double chord = 1.0;
  double leading_edge_x = 0.0;
  double leading_edge_z = 0.0;
  double twist_degrees = 0.0;
  std::size_t airfoil = 0;  // index into WingDefinition::airfoils
};

// What the blunt trailing edge of an airfoil becomes on the wing.
enum class TrailingEdge { close, base };

struct WingDefinition {
  std::vector<Airfoil> airfoils;
  std::vector<SpanStation> stations;  // y increasing from the root (y = 0) to the tip
  double twist_axis = 0.25;           // fraction of the chord
  TrailingEdge blunt_trailing_edge = TrailingEdge::close;

  double semi_span() const { return stations.back().y - stations.front().y; }
};

// The classic parameters. Exactly one of trailing_edge_sweep_degrees and taper.
struct ClassicPlanform {
  double root_chord = 1.0;
  double semi_span = 1.0;
  double leading_edge_sweep_degrees = 0.0;
  std::optional<double> trailing_edge_sweep_degrees;
  std::optional<double> taper;  // tip chord / root chord
  double root_twist_degrees = 0.0;
  double tip_twist_degrees = 0.0;
  double dihedral_degrees = 0.0;
};

// Root and tip stations of a trapezoidal wing with one airfoil. Throws mixmesh::Error
// if the tip chord comes out non-positive.
WingDefinition classic_wing(const ClassicPlanform& planform, Airfoil airfoil);

// Checks stations (at least two, y strictly increasing from 0, positive chords,
// valid airfoil indices); throws mixmesh::Error naming the station.
void validate_wing(const WingDefinition& wing);

// The station parameters at span position y (linear between stations), with the two
// neighbouring airfoils and the blend weight of the second.
struct StationBlend {
  SpanStation parameters;
  std::size_t first_airfoil = 0;
  std::size_t second_airfoil = 0;
  double weight = 0.0;
};
StationBlend station_at(const WingDefinition& wing, double y);

// A unit-chord section point (x, z) placed on the wing at station `station`.
Eigen::Vector3d place_section_point(const SpanStation& station, double twist_axis, const Vector2& point);

}  // namespace mixmesh
