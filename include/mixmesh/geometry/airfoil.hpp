// Airfoil sections: analytic NACA 4- and 5-digit sections and coordinate files
// (Selig and Lednicer formats), normalised to unit chord.
//
//   Airfoil::points   #N (x, z) points, leading edge at (0, 0), trailing edge (the mid-point
//                     of the two trailing-edge points) at (1, 0); ordered from the
//                     trailing edge along the LOWER surface round the leading edge and back
//                     along the UPPER surface (the wing patch's i direction). A sharp
//                     trailing edge has points.front() == points.back().
//   Airfoil::lines    #N source line of each point in `source` (0 for analytic sections),
//                     so geometric errors can name file:line.
#pragma once

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace mixmesh {

using Vector2 = Eigen::Vector2d;

struct Airfoil {
  std::string source;            // the file, or "NACA 2412"
  std::vector<Vector2> points;   // lower trailing edge -> leading edge -> upper trailing edge
  std::vector<long> lines;       // source line per point, 0 when analytic
  std::size_t leading_edge = 0;  // index of the leading-edge point (0, 0)

  // Distance between the two trailing-edge points (0 for a sharp trailing edge).
  double trailing_edge_gap() const { return (points.back() - points.front()).norm(); }
};

struct NacaOptions {
  int points_per_side = 201;         // cosine-spaced in x, leading edge shared
  bool closed_trailing_edge = true;  // -0.1036 x^4 instead of the original -0.1015 x^4
};

// "0012", "2412", "23012", "23112" (5-digit with reflexed camber) or with a "NACA"
// prefix. Throws mixmesh::Error for anything else.
Airfoil naca_airfoil(const std::string& designation, const NacaOptions& options = {});

// Reads a Selig file (name line, then x z from the trailing edge over the upper surface
// to the leading edge and back along the lower surface) or a Lednicer file (name line,
// "upper_count lower_count", then upper and lower surfaces each from the leading edge).
// The format is recognised from the second line. Normalises and validates the result.
// Errors name path:line.
Airfoil read_airfoil_file(const std::filesystem::path& path);

// Brings raw points (ordered lower TE -> LE -> upper TE or the reverse) to unit chord:
// the leading edge is the point farthest from the trailing-edge mid-point; it is moved
// to the origin and the chord is rotated onto +x and scaled to 1. Orders the points
// lower-first. Validates (see validate_airfoil).
Airfoil normalise_airfoil(Airfoil raw);

// Throws mixmesh::Error (naming source:line) if there are fewer than 5 points per
// surface, repeated consecutive points, or if the upper and lower surfaces cross (the
// closed outline is not a simple polygon).
void validate_airfoil(const Airfoil& airfoil);

// A blunt trailing edge closed by shearing each surface linearly in x until both
// trailing-edge points meet at their mid-point; the leading edge stays in place.
Airfoil close_trailing_edge(const Airfoil& airfoil);

// Area enclosed by the outline (the trailing-edge gap closed by a straight line), unit
// chord: the shoelace formula on the points.
double section_area(const Airfoil& airfoil);

}  // namespace mixmesh
