// deform_idw_study: the rotation experiment of the IDW optimal-parameters paper on one
// planar mesh, for a grid of exponents (st, sr).
//
//   deform_idw_study MESH CX CY STEP_DEGREES MAX_DEGREES ST_LIST SR_LIST [REFERENCE_DEGREES]
//
// MESH is a plain text planar mesh (written by scripts/idw-study.py):
//   points N        then N lines "x y"
//   triangles M     then M lines "a b c"       (0-based, counter-clockwise)
//   quads K         then K lines "a b c d"
//   edges E         then E lines "a b marker"  (marker 0: moving body, 1: fixed far field)
// ST_LIST and SR_LIST are comma-separated; "inf" drops the rotation term.
//
// For every (st, sr) the body is rotated clockwise about (CX, CY) by STEP_DEGREES per step;
// each step deforms the previous step's mesh with the IDW rotation form, until a cell's
// signed area is not positive or MAX_DEGREES is reached. One CSV row per pair:
//   st,sr,max_angle,min_quality,mean_quality,reference_min_quality,reference_mean_quality
// with the quality of the last valid mesh and of the mesh at REFERENCE_DEGREES (default 45;
// nan when the mesh failed before): triangles 4√3 A / Σ l², quads the smallest corner sine
// (both 1 for the regular cell).
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "mixmesh/core/error.hpp"
#include "mixmesh/deform/idw.hpp"

namespace {

using mixmesh::Error;
using mixmesh::Vector3;
namespace deform = mixmesh::deform;

constexpr double pi = 3.14159265358979323846;

struct PlanarMesh {
  std::vector<Vector3> points;
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<int, 4>> quads;
  std::vector<int> body_nodes, farfield_nodes, volume_nodes;
};

std::size_t read_count(std::istream& in, const std::string& keyword, const std::string& path) {
  std::string word;
  std::size_t count = 0;
  if (!(in >> word >> count) || word != keyword)
    throw Error(path + ": expected '" + keyword + " COUNT', found '" + word + "'");
  return count;
}

PlanarMesh read_mesh(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open");
  PlanarMesh mesh;
  const std::size_t point_count = read_count(in, "points", path);
  for (std::size_t k = 0; k < point_count; ++k) {
    double x = 0.0, y = 0.0;
    if (!(in >> x >> y)) throw Error(path + ": point " + std::to_string(k) + " unreadable");
    mesh.points.emplace_back(x, y, 0.0);
  }
  const auto check = [&](int node) {
    if (node < 0 || static_cast<std::size_t>(node) >= point_count)
      throw Error(path + ": node " + std::to_string(node) + " out of range");
    return node;
  };
  const std::size_t triangle_count = read_count(in, "triangles", path);
  for (std::size_t k = 0; k < triangle_count; ++k) {
    std::array<int, 3> cell{};
    for (int& node : cell)
      if (!(in >> node)) throw Error(path + ": triangle " + std::to_string(k) + " unreadable");
    for (int node : cell) check(node);
    mesh.triangles.push_back(cell);
  }
  const std::size_t quad_count = read_count(in, "quads", path);
  for (std::size_t k = 0; k < quad_count; ++k) {
    std::array<int, 4> cell{};
    for (int& node : cell)
      if (!(in >> node)) throw Error(path + ": quad " + std::to_string(k) + " unreadable");
    for (int node : cell) check(node);
    mesh.quads.push_back(cell);
  }
  const std::size_t edge_count = read_count(in, "edges", path);
  std::vector<int> role(point_count, -1);
  for (std::size_t k = 0; k < edge_count; ++k) {
    int a = 0, b = 0, marker = 0;
    if (!(in >> a >> b >> marker) || (marker != 0 && marker != 1))
      throw Error(path + ": edge " + std::to_string(k) + " unreadable or marker not 0/1");
    // A node on both (never in the study meshes) counts as fixed.
    role[static_cast<std::size_t>(check(a))] = std::max(role[static_cast<std::size_t>(a)], marker);
    role[static_cast<std::size_t>(check(b))] = std::max(role[static_cast<std::size_t>(b)], marker);
  }
  for (std::size_t k = 0; k < point_count; ++k) {
    std::vector<int>& list = role[k] == 0   ? mesh.body_nodes
                             : role[k] == 1 ? mesh.farfield_nodes
                                            : mesh.volume_nodes;
    list.push_back(static_cast<int>(k));
  }
  if (mesh.body_nodes.empty() || mesh.farfield_nodes.empty())
    throw Error(path + ": needs body and far-field edges");
  return mesh;
}

double cross(const Vector3& a, const Vector3& b) {
  return a.x() * b.y() - a.y() * b.x();
}

struct Quality {
  bool valid = true;
  double minimum = 1.0;
  double mean = 0.0;
};

Quality mesh_quality(const PlanarMesh& mesh, const std::vector<Vector3>& points) {
  Quality quality;
  double sum = 0.0;
  for (const auto& cell : mesh.triangles) {
    const Vector3& a = points[static_cast<std::size_t>(cell[0])];
    const Vector3& b = points[static_cast<std::size_t>(cell[1])];
    const Vector3& c = points[static_cast<std::size_t>(cell[2])];
    const double area = 0.5 * cross(b - a, c - a);
    const double q =
        4.0 * std::sqrt(3.0) * area / ((b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm());
    quality.valid = quality.valid && area > 0.0;
    quality.minimum = std::min(quality.minimum, q);
    sum += q;
  }
  for (const auto& cell : mesh.quads) {
    double q = 1.0;
    for (int corner = 0; corner < 4; ++corner) {
      const Vector3& here = points[static_cast<std::size_t>(cell[static_cast<std::size_t>(corner)])];
      const Vector3 next =
          points[static_cast<std::size_t>(cell[static_cast<std::size_t>((corner + 1) % 4)])] - here;
      const Vector3 previous =
          points[static_cast<std::size_t>(cell[static_cast<std::size_t>((corner + 3) % 4)])] - here;
      const double sine = cross(next, previous) / (next.norm() * previous.norm());
      quality.valid = quality.valid && sine > 0.0;
      q = std::min(q, sine);
    }
    quality.minimum = std::min(quality.minimum, q);
    sum += q;
  }
  quality.mean = sum / static_cast<double>(mesh.triangles.size() + mesh.quads.size());
  return quality;
}

std::vector<double> parse_list(const std::string& text) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    if (item == "inf") {
      values.push_back(deform::idw_no_rotation_term);
      continue;
    }
    std::size_t used = 0;
    const double value = std::stod(item, &used);
    if (used != item.size() || !(value > 0.0))
      throw Error("exponent list: '" + item + "' is not a positive number");
    values.push_back(value);
  }
  if (values.empty()) throw Error("exponent list '" + text + "' is empty");
  return values;
}

struct Outcome {
  double angle = 0.0;  // largest valid angle
  Quality last;        // quality at that angle
  Quality reference{false, std::numeric_limits<double>::quiet_NaN(),
                    std::numeric_limits<double>::quiet_NaN()};
};

// Rotates step by step until the mesh fails.
Outcome rotate_until_failure(const PlanarMesh& mesh, const Vector3& centre, double step, double limit,
                             double reference_angle, double st, double sr) {
  std::vector<Vector3> points = mesh.points;
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(-step * pi / 180.0, Vector3::UnitZ()).toRotationMatrix();
  deform::IdwOptions options;
  options.translation_exponent = st;
  options.rotation_exponent = sr;
  Outcome outcome;
  outcome.last = mesh_quality(mesh, points);
  if (!outcome.last.valid) throw Error("the initial mesh has cells of non-positive area");
  double& angle = outcome.angle;
  while (angle + step <= limit + 1e-9) {
    deform::IdwInput input;
    deform::IdwBody body, farfield;
    body.name = "body";
    for (int node : mesh.body_nodes) {
      const Vector3& x = points[static_cast<std::size_t>(node)];
      body.positions.push_back(x);
      body.displacements.push_back(rotation * (x - centre) + centre - x);
    }
    farfield.name = "farfield";
    farfield.moving = false;
    for (int node : mesh.farfield_nodes) farfield.positions.push_back(points[static_cast<std::size_t>(node)]);
    input.bodies = {body, farfield};
    for (int node : mesh.volume_nodes) input.volume_points.push_back(points[static_cast<std::size_t>(node)]);
    const deform::IdwResult result = deform::idw_deform(input, options);
    std::vector<Vector3> moved = points;
    for (std::size_t k = 0; k < mesh.body_nodes.size(); ++k)
      moved[static_cast<std::size_t>(mesh.body_nodes[k])] += body.displacements[k];
    for (std::size_t k = 0; k < mesh.volume_nodes.size(); ++k)
      moved[static_cast<std::size_t>(mesh.volume_nodes[k])] += result.displacements[k];
    const Quality quality = mesh_quality(mesh, moved);
    if (!quality.valid) break;
    points = std::move(moved);
    outcome.last = quality;
    angle += step;
    if (std::abs(angle - reference_angle) < 1e-9) outcome.reference = quality;
  }
  return outcome;
}

}  // namespace

int main(int argument_count, char** arguments) {
  if (argument_count != 8 && argument_count != 9) {
    std::cerr << "usage: deform_idw_study MESH CX CY STEP_DEGREES MAX_DEGREES ST_LIST SR_LIST "
                 "[REFERENCE_DEGREES]\n";
    return 2;
  }
  try {
    const PlanarMesh mesh = read_mesh(arguments[1]);
    const Vector3 centre(std::stod(arguments[2]), std::stod(arguments[3]), 0.0);
    const double step = std::stod(arguments[4]), limit = std::stod(arguments[5]);
    if (!(step > 0.0) || !(limit >= step)) throw Error("step must be positive and at most the largest angle");
    const double reference_angle = argument_count == 9 ? std::stod(arguments[8]) : 45.0;
    std::cout << "st,sr,max_angle,min_quality,mean_quality,reference_min_quality,reference_mean_quality\n";
    for (const double st : parse_list(arguments[6]))
      for (const double sr : parse_list(arguments[7])) {
        const Outcome outcome = rotate_until_failure(mesh, centre, step, limit, reference_angle, st, sr);
        std::cout << st << ',';
        if (std::isinf(sr))
          std::cout << "inf";
        else
          std::cout << sr;
        std::cout << ',' << outcome.angle << ',' << outcome.last.minimum << ',' << outcome.last.mean << ','
                  << outcome.reference.minimum << ',' << outcome.reference.mean << '\n'
                  << std::flush;
      }
  } catch (const std::exception& error) {
    std::cerr << "deform_idw_study: error: " << error.what() << '\n';
    return 1;
  }
  return 0;
}
