// Airfoils: analytic NACA sections, Selig and Lednicer files, normalisation, the
// arc-length spline and the rejection of bad sections.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <sstream>
#include <tuple>

#include "error_message.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/geometry/airfoil.hpp"
#include "mixmesh/geometry/airfoil_curve.hpp"

using namespace mixmesh;

namespace {

std::filesystem::path write_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::path(::testing::TempDir()) / name;
  std::ofstream(path) << text;
  return path;
}

// Half-thickness of the NACA 00xx section (closed trailing edge form).
double naca_half_thickness(double x, double t) {
  return 5.0 * t *
         (0.2969 * std::sqrt(x) - 0.1260 * x - 0.3516 * x * x + 0.2843 * x * x * x - 0.1036 * x * x * x * x);
}

// A symmetric section written in Selig order (upper TE -> LE -> lower TE), `count` per side.
std::string selig_text(int count, double scale = 1.0, double shift = 0.0) {
  std::ostringstream text;
  text << std::setprecision(17) << "TEST SECTION\n";
  for (int k = count - 1; k >= 0; --k) {
    const double x = 0.5 * (1.0 - std::cos(M_PI * k / (count - 1)));
    text << scale * x + shift << " " << scale * naca_half_thickness(x, 0.12) << "\n";
  }
  for (int k = 1; k < count; ++k) {
    const double x = 0.5 * (1.0 - std::cos(M_PI * k / (count - 1)));
    text << scale * x + shift << " " << -scale * naca_half_thickness(x, 0.12) << "\n";
  }
  return text.str();
}

}  // namespace

TEST(NacaAirfoil, SymmetricSectionMatchesTheThicknessFormula) {
  const Airfoil airfoil = naca_airfoil("0012");
  EXPECT_EQ(airfoil.points.front(), Vector2(1.0, 0.0));
  EXPECT_EQ(airfoil.points.back(), Vector2(1.0, 0.0));
  EXPECT_EQ(airfoil.points[airfoil.leading_edge], Vector2(0.0, 0.0));
  double thickest = 0.0;
  for (std::size_t k = 0; k < airfoil.points.size(); ++k) {
    const Vector2& point = airfoil.points[k];
    const double expected = naca_half_thickness(point.x(), 0.12);
    EXPECT_NEAR(std::abs(point.y()), expected, 1e-15);
    if (point.y() != 0.0) {
      EXPECT_EQ(point.y() < 0.0, k < airfoil.leading_edge) << "lower surface first";
    }
    thickest = std::max(thickest, 2.0 * std::abs(point.y()));
  }
  EXPECT_NEAR(thickest, 0.12, 2e-4);
}

TEST(NacaAirfoil, CamberedSectionsHaveTheirCamberAndThickness) {
  // NACA 2412: 2 % camber at 40 % chord; 23012: maximum camber 1.83 % near 15 %.
  for (const auto& [digits, camber, position] : std::vector<std::tuple<std::string, double, double>>{
           {"2412", 0.02, 0.4}, {"NACA 23012", 0.0183, 0.15}}) {
    const Airfoil airfoil = naca_airfoil(digits);
    const std::size_t le = airfoil.leading_edge;
    double best = 0.0, best_x = 0.0;
    for (std::size_t k = 1; k < le; ++k) {
      const Vector2& upper = airfoil.points[2 * le - k];
      const Vector2& lower = airfoil.points[k];
      const double middle = 0.5 * (upper.y() + lower.y());
      if (middle > best) {
        best = middle;
        best_x = 0.5 * (upper.x() + lower.x());
      }
    }
    EXPECT_NEAR(best, camber, 2e-4) << digits;
    EXPECT_NEAR(best_x, position, 0.03) << digits;
  }
}

TEST(NacaAirfoil, OpenTrailingEdgeHasTheClassicGap) {
  NacaOptions options;
  options.closed_trailing_edge = false;
  const Airfoil airfoil = naca_airfoil("0012", options);
  EXPECT_NEAR(airfoil.trailing_edge_gap(), 2.0 * 5.0 * 0.12 * (0.2969 - 0.1260 - 0.3516 + 0.2843 - 0.1015),
              1e-12);
  const Airfoil closed = close_trailing_edge(airfoil);
  EXPECT_EQ(closed.trailing_edge_gap(), 0.0);
  EXPECT_EQ(closed.points[closed.leading_edge], Vector2(0.0, 0.0));
  EXPECT_NEAR(closed.points[closed.leading_edge / 2].y(), airfoil.points[airfoil.leading_edge / 2].y(), 2e-3);
}

TEST(NacaAirfoil, RejectsUnknownDesignations) {
  EXPECT_THROW(naca_airfoil("12"), Error);
  EXPECT_THROW(naca_airfoil("00x2"), Error);
  EXPECT_THROW(naca_airfoil("2012"), Error);   // camber without position
  EXPECT_THROW(naca_airfoil("26012"), Error);  // no such 5-digit mean line
  EXPECT_THROW(naca_airfoil("0000"), Error);
  NacaOptions few;
  few.points_per_side = 3;
  EXPECT_THROW(naca_airfoil("0012", few), Error);
}

TEST(AirfoilFile, SeligFileIsNormalisedToUnitChordLowerFirst) {
  // Scaled by 2 and shifted: normalisation brings it back to unit chord.
  const Airfoil airfoil = read_airfoil_file(write_file("selig.dat", selig_text(41, 2.0, 0.5)));
  ASSERT_EQ(airfoil.points.size(), 81u);
  EXPECT_EQ(airfoil.leading_edge, 40u);
  EXPECT_EQ(airfoil.trailing_edge_gap(), 0.0);
  EXPECT_LT(airfoil.points[20].y(), 0.0);
  EXPECT_GT(airfoil.points[60].y(), 0.0);
  for (const Vector2& point : airfoil.points)
    EXPECT_NEAR(std::abs(point.y()), naca_half_thickness(point.x(), 0.12), 1e-12);
  // Points keep their file lines: the first point read (line 2) is the upper trailing edge.
  EXPECT_EQ(airfoil.lines.back(), 2);
  EXPECT_EQ(airfoil.lines.front(), 82);
}

TEST(AirfoilFile, LednicerFileGivesTheSameSection) {
  std::ostringstream text;
  const int count = 41;
  text << std::setprecision(17) << "LEDNICER TEST\n" << count << ". " << count << ".\n\n";
  for (int side = 0; side < 2; ++side) {
    for (int k = 0; k < count; ++k) {
      const double x = 0.5 * (1.0 - std::cos(M_PI * k / (count - 1)));
      text << x << " " << (side == 0 ? 1.0 : -1.0) * naca_half_thickness(x, 0.12) << "\n";
    }
    text << "\n";
  }
  const Airfoil lednicer = read_airfoil_file(write_file("lednicer.dat", text.str()));
  const Airfoil selig = read_airfoil_file(write_file("selig_same.dat", selig_text(count)));
  ASSERT_EQ(lednicer.points.size(), selig.points.size());
  for (std::size_t k = 0; k < selig.points.size(); ++k)
    EXPECT_NEAR((lednicer.points[k] - selig.points[k]).norm(), 0.0, 1e-12);
}

TEST(AirfoilFile, OneraDFileIsReadAsASharpSymmetricSection) {
  const Airfoil airfoil = read_airfoil_file(std::string(MIXMESH_SOURCE_DIR) + "/cases/airfoils/onera_d.dat");
  EXPECT_EQ(airfoil.points.size(), 143u);
  EXPECT_EQ(airfoil.trailing_edge_gap(), 0.0);
  double thickest = 0.0;
  for (const Vector2& point : airfoil.points) thickest = std::max(thickest, 2.0 * std::abs(point.y()));
  EXPECT_NEAR(thickest, 0.0979, 5e-4);
}

TEST(AirfoilFile, BadFilesNameTheFileAndLine) {
  EXPECT_NE(
      error_message([] { read_airfoil_file("/nonexistent/section.dat"); }).find("/nonexistent/section.dat"),
      std::string::npos);
  const auto garbage = write_file("garbage.dat", "NAME\n1.0 0.0\n0.5 zero\n");
  EXPECT_NE(error_message([&] { read_airfoil_file(garbage); }).find("garbage.dat:3:"), std::string::npos);
  const auto few = write_file("few.dat", "NAME\n1 0\n0.5 0.05\n0 0\n0.5 -0.05\n1 0\n");
  EXPECT_NE(error_message([&] { read_airfoil_file(few); }).find("too few points"), std::string::npos);
  // Upper and lower surfaces swap sides half way: the outline crosses itself.
  std::ostringstream crossing;
  crossing << "CROSSING\n";
  for (int k = 10; k >= 0; --k)
    crossing << 0.1 * k << " " << 0.05 * std::sin(M_PI * 0.1 * k) * (k > 5 ? -1 : 1) << "\n";
  for (int k = 1; k <= 10; ++k)
    crossing << 0.1 * k << " " << -0.05 * std::sin(M_PI * 0.1 * k) * (k > 5 ? -1 : 1) << "\n";
  const auto crossed = write_file("crossing.dat", crossing.str());
  const std::string message = error_message([&] { read_airfoil_file(crossed); });
  EXPECT_NE(message.find("cross"), std::string::npos) << message;
  EXPECT_NE(message.find("crossing.dat:"), std::string::npos) << message;
  const auto lednicer = write_file("short_lednicer.dat", "L\n10. 10.\n0 0\n1 0\n");
  EXPECT_NE(error_message([&] { read_airfoil_file(lednicer); }).find("short_lednicer.dat:2:"),
            std::string::npos);
}

TEST(AirfoilCurve, InterpolatesThePointsAndMeasuresArcLength) {
  const Airfoil airfoil = naca_airfoil("0012");
  const AirfoilCurve curve(airfoil);
  for (std::size_t k = 0; k < airfoil.points.size(); ++k) {
    EXPECT_NEAR((curve.point(curve.knots()[k]) - airfoil.points[k]).norm(), 0.0, 1e-14);
  }
  EXPECT_NEAR((curve.point(curve.leading_edge()) - Vector2(0.0, 0.0)).norm(), 0.0, 1e-14);
  // Unit-speed parametrisation: |c'(s)| = 1 and the length exceeds twice the chord.
  for (double s = 0.0; s < curve.length(); s += curve.length() / 97.0)
    EXPECT_NEAR(curve.tangent(s).norm(), 1.0, 2e-3);
  EXPECT_GT(curve.length(), 2.0);
  EXPECT_LT(curve.length(), 2.1);
  // Between the points the spline stays on the analytic section.
  for (double s = 0.01; s < curve.length(); s += 0.013) {
    const Vector2 point = curve.point(s);
    EXPECT_NEAR(std::abs(point.y()), naca_half_thickness(std::max(point.x(), 0.0), 0.12), 2e-5) << "s " << s;
  }
}
