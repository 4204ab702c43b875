// Planform: classic parameters to stations, interpolation between stations, placing a
// section point (twist about the axis, scale, leading edge), and invalid wings.
#include <gtest/gtest.h>

#include <cmath>

#include "mixmesh/core/error.hpp"
#include "mixmesh/geometry/airfoil.hpp"
#include "mixmesh/geometry/planform.hpp"

using namespace mixmesh;

namespace {

double radians(double degrees) {
  return degrees * M_PI / 180.0;
}

}  // namespace

TEST(ClassicPlanform, OneraM6GivesItsPublishedTipChordAndTaper) {
  ClassicPlanform planform;
  planform.root_chord = 0.8059;
  planform.semi_span = 1.1963;
  planform.leading_edge_sweep_degrees = 30.0;
  planform.trailing_edge_sweep_degrees = 15.8;
  const WingDefinition wing = classic_wing(planform, naca_airfoil("0010"));
  ASSERT_EQ(wing.stations.size(), 2u);
  const SpanStation& tip = wing.stations[1];
  EXPECT_NEAR(tip.chord, 0.4537, 5e-4);
  EXPECT_NEAR(tip.chord / 0.8059, 0.562, 1.5e-3);  // published to three digits (0.563 from the sweeps)
  EXPECT_DOUBLE_EQ(tip.y, 1.1963);
  EXPECT_NEAR(tip.leading_edge_x, 1.1963 * std::tan(radians(30.0)), 1e-15);
  // Mean aerodynamic chord of a trapezoid: 2/3 c_r (1 + l + l^2) / (1 + l); published 0.646 m.
  const double taper = tip.chord / 0.8059;
  EXPECT_NEAR(2.0 / 3.0 * 0.8059 * (1.0 + taper + taper * taper) / (1.0 + taper), 0.646, 1e-3);
}

TEST(ClassicPlanform, TaperTwistAndDihedralSetTheTipStation) {
  ClassicPlanform planform;
  planform.root_chord = 2.0;
  planform.semi_span = 4.0;
  planform.taper = 0.25;
  planform.root_twist_degrees = 1.0;
  planform.tip_twist_degrees = -3.0;
  planform.dihedral_degrees = 5.0;
  const WingDefinition wing = classic_wing(planform, naca_airfoil("0012"));
  EXPECT_DOUBLE_EQ(wing.stations[1].chord, 0.5);
  EXPECT_NEAR(wing.stations[1].leading_edge_z, 4.0 * std::tan(radians(5.0)), 1e-15);
  const StationBlend middle = station_at(wing, 1.0);
  EXPECT_NEAR(middle.parameters.chord, 2.0 - 1.5 * 0.25, 1e-15);
  EXPECT_NEAR(middle.parameters.twist_degrees, 0.0, 1e-15);
  EXPECT_NEAR(middle.weight, 0.25, 1e-15);
}

TEST(ClassicPlanform, RejectsImpossiblePlanforms) {
  ClassicPlanform planform;
  planform.taper = 0.5;
  planform.trailing_edge_sweep_degrees = 10.0;
  EXPECT_THROW(classic_wing(planform, naca_airfoil("0012")), Error);  // both given
  planform.taper.reset();
  planform.trailing_edge_sweep_degrees.reset();
  EXPECT_THROW(classic_wing(planform, naca_airfoil("0012")), Error);  // neither given
  planform.leading_edge_sweep_degrees = 60.0;
  planform.trailing_edge_sweep_degrees = 0.0;
  EXPECT_THROW(classic_wing(planform, naca_airfoil("0012")), Error);  // no tip chord left
  planform.trailing_edge_sweep_degrees.reset();
  planform.taper = 0.5;
  planform.root_chord = -1.0;
  EXPECT_THROW(classic_wing(planform, naca_airfoil("0012")), Error);
}

TEST(SectionPlacement, TwistsAboutTheAxisNoseUpThenScalesAndMoves) {
  SpanStation station;
  station.y = 0.7;
  station.chord = 2.0;
  station.leading_edge_x = 0.3;
  station.leading_edge_z = -0.1;
  station.twist_degrees = 10.0;
  // The axis point does not move; the leading edge rises by axis * chord * sin(twist).
  const Eigen::Vector3d axis = place_section_point(station, 0.25, Vector2(0.25, 0.0));
  EXPECT_NEAR((axis - Eigen::Vector3d(0.3 + 0.5, 0.7, -0.1)).norm(), 0.0, 1e-15);
  const Eigen::Vector3d nose = place_section_point(station, 0.25, Vector2(0.0, 0.0));
  EXPECT_NEAR(nose.z(), -0.1 + 0.5 * std::sin(radians(10.0)), 1e-15);
  EXPECT_NEAR(nose.x(), 0.8 - 0.5 * std::cos(radians(10.0)), 1e-15);
  const Eigen::Vector3d tail = place_section_point(station, 0.25, Vector2(1.0, 0.0));
  EXPECT_LT(tail.z(), -0.1);
  EXPECT_NEAR((tail - nose).norm(), 2.0, 1e-14);  // lengths scale by the chord only
}

TEST(WingValidation, NamesTheBadStation) {
  WingDefinition wing;
  wing.airfoils.push_back(naca_airfoil("0012"));
  wing.stations.resize(3);
  wing.stations[1].y = 1.0;
  wing.stations[2].y = 0.5;
  try {
    validate_wing(wing);
    FAIL() << "decreasing y accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("span station 3"), std::string::npos) << error.what();
  }
  wing.stations[2].y = 2.0;
  wing.stations[1].chord = 0.0;
  EXPECT_THROW(validate_wing(wing), Error);
  wing.stations[1].chord = 1.0;
  wing.stations[0].y = 0.1;
  EXPECT_THROW(validate_wing(wing), Error);
  wing.stations[0].y = 0.0;
  wing.stations[2].airfoil = 4;
  EXPECT_THROW(validate_wing(wing), Error);
  wing.stations[2].airfoil = 0;
  EXPECT_NO_THROW(validate_wing(wing));
  wing.stations.resize(1);
  EXPECT_THROW(validate_wing(wing), Error);
}
