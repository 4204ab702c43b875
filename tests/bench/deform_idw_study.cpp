// deform_idw_study: the rotation, translation and combined-motion experiments of the IDW
// optimal-parameters paper on one planar mesh, for a grid of exponents (st, sr).
//
//   deform_idw_study MESH --centre X,Y --st LIST --sr LIST --max-steps N
//                    [--motion rotation|translation|combined] [--step-degrees D]
//                    [--step-length L] [--direction X,Y] [--reference-step K]
//
// MESH is a plain text planar mesh (written by scripts/idw-study.py):
//   points N        then N lines "x y"
//   triangles M     then M lines "a b c"       (0-based, counter-clockwise)
//   quads K         then K lines "a b c d"
//   edges E         then E lines "a b marker"  (marker 0: moving body, 1: fixed far field)
// LIST is comma-separated; "inf" in the sr list drops the rotation term.
//
// Every step moves the body rigidly and deforms the previous step's mesh with the IDW
// rotation form (the paper moves its bodies step by step):
//   rotation     clockwise by D degrees (default 5) about the centre;
//   translation  by L (default 0.1) along the direction (default 0,1: upwards);
//   combined     both: clockwise by D about the body's current centre, then by L along the
//                direction (the paper's combined movements: 2° and 1 or 5 units per step).
// Steps continue until a cell's signed area is not positive or N steps are done. One CSV
// row per pair:
//   st,sr,steps,max_angle,max_displacement,min_quality,mean_quality,
//   reference_min_quality,reference_mean_quality,failure_distance
// with the angle (degrees) and displacement of the body after the last valid step, the
// quality of that mesh and of the mesh after step K (default 9, i.e. 45° of rotation; nan
// when the mesh failed before): triangles 4√3 A / Σ l², quads the smallest corner sine
// (both 1 for the regular cell); failure_distance is the distance from the body's centre to
// the worst cell of the first failed mesh (nan when all N steps stayed valid).
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
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
  Vector3 worst = Vector3::Zero();  // centroid of the cell of least quality
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
    if (q < quality.minimum) quality.worst = (a + b + c) / 3.0;
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
    if (q < quality.minimum) {
      quality.worst = Vector3::Zero();
      for (int node : cell) quality.worst += points[static_cast<std::size_t>(node)] / 4.0;
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
    double value = 0.0;
    try {
      value = std::stod(item, &used);
    } catch (const std::logic_error&) {
      used = 0;
    }
    if (used != item.size() || !(value > 0.0))
      throw Error("exponent list: '" + item + "' is not a positive number");
    values.push_back(value);
  }
  if (values.empty()) throw Error("exponent list '" + text + "' is empty");
  return values;
}

enum class MotionKind { rotation, translation, combined };

// One rigid step of the body; the centre travels with the body.
struct Motion {
  MotionKind kind = MotionKind::rotation;
  Vector3 centre = Vector3::Zero();
  double step_degrees = 5.0;
  double step_length = 0.1;
  Vector3 direction = Vector3::UnitY();  // unit
  int max_steps = 72;
  int reference_step = 9;

  bool rotates() const { return kind != MotionKind::translation; }
  bool translates() const { return kind != MotionKind::rotation; }
};

struct Outcome {
  int steps = 0;  // valid steps done
  Quality last;   // quality after them
  Quality reference{false, std::numeric_limits<double>::quiet_NaN(),
                    std::numeric_limits<double>::quiet_NaN()};
  // Distance from the body's centre to the cell of least quality of the first failed mesh
  // (near the body or near the far field: where the motion is absorbed); nan when none failed.
  double failure_distance = std::numeric_limits<double>::quiet_NaN();
};

// Moves the body step by step until the mesh fails.
Outcome move_until_failure(const PlanarMesh& mesh, const Motion& motion, double st, double sr) {
  std::vector<Vector3> points = mesh.points;
  const double angle = motion.rotates() ? -motion.step_degrees * pi / 180.0 : 0.0;  // clockwise
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(angle, Vector3::UnitZ()).toRotationMatrix();
  const Vector3 translation =
      motion.translates() ? Vector3(motion.step_length * motion.direction) : Vector3::Zero();
  deform::IdwOptions options;
  options.translation_exponent = st;
  options.rotation_exponent = sr;
  Outcome outcome;
  outcome.last = mesh_quality(mesh, points);
  if (!outcome.last.valid) throw Error("the initial mesh has cells of non-positive area");
  Vector3 centre = motion.centre;
  while (outcome.steps < motion.max_steps) {
    deform::IdwInput input;
    deform::IdwBody body, farfield;
    body.name = "body";
    for (int node : mesh.body_nodes) {
      const Vector3& x = points[static_cast<std::size_t>(node)];
      body.positions.push_back(x);
      body.displacements.push_back(rotation * (x - centre) + centre + translation - x);
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
    if (!quality.valid) {
      outcome.failure_distance = (quality.worst - centre - translation).norm();
      break;
    }
    points = std::move(moved);
    centre += translation;
    outcome.last = quality;
    ++outcome.steps;
    if (outcome.steps == motion.reference_step) outcome.reference = quality;
  }
  return outcome;
}

Vector3 parse_pair(const std::string& option, const std::string& text) {
  const std::size_t comma = text.find(',');
  std::size_t used_x = 0, used_y = 0;
  try {
    if (comma == std::string::npos) throw std::invalid_argument(text);
    const double x = std::stod(text.substr(0, comma), &used_x);
    const double y = std::stod(text.substr(comma + 1), &used_y);
    if (used_x == comma && used_y == text.size() - comma - 1 && std::isfinite(x) && std::isfinite(y))
      return Vector3(x, y, 0.0);
  } catch (const std::logic_error&) {
  }
  throw Error(option + ": '" + text + "' is not 'X,Y'");
}

double parse_number(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  try {
    const double value = std::stod(text, &used);
    if (used == text.size() && std::isfinite(value)) return value;
  } catch (const std::logic_error&) {
  }
  throw Error(option + ": '" + text + "' is not a number");
}

int parse_count(const std::string& option, const std::string& text) {
  const double value = parse_number(option, text);
  if (value != std::floor(value) || std::abs(value) > 1e9)
    throw Error(option + ": '" + text + "' is not a whole number");
  return static_cast<int>(value);
}

constexpr const char* usage =
    "usage: deform_idw_study MESH --centre X,Y --st LIST --sr LIST --max-steps N\n"
    "       [--motion rotation|translation|combined] [--step-degrees D] [--step-length L]\n"
    "       [--direction X,Y] [--reference-step K]\n";

}  // namespace

int main(int argument_count, char** arguments) {
  if (argument_count < 2 || argument_count % 2 != 0) {
    std::cerr << usage;
    return 2;
  }
  try {
    Motion motion;
    std::string st_list, sr_list;
    bool has_centre = false, has_steps = false;
    for (int k = 2; k + 1 < argument_count; k += 2) {
      const std::string option = arguments[k], value = arguments[k + 1];
      if (option == "--centre") {
        motion.centre = parse_pair(option, value);
        has_centre = true;
      } else if (option == "--motion") {
        if (value == "rotation")
          motion.kind = MotionKind::rotation;
        else if (value == "translation")
          motion.kind = MotionKind::translation;
        else if (value == "combined")
          motion.kind = MotionKind::combined;
        else
          throw Error("--motion: '" + value + "' is not rotation, translation or combined");
      } else if (option == "--step-degrees") {
        motion.step_degrees = parse_number(option, value);
      } else if (option == "--step-length") {
        motion.step_length = parse_number(option, value);
      } else if (option == "--direction") {
        motion.direction = parse_pair(option, value);
        if (!(motion.direction.norm() > 0.0)) throw Error("--direction: '" + value + "' is the zero vector");
        motion.direction.normalize();
      } else if (option == "--max-steps") {
        motion.max_steps = parse_count(option, value);
        has_steps = true;
      } else if (option == "--reference-step") {
        motion.reference_step = parse_count(option, value);
      } else if (option == "--st") {
        st_list = value;
      } else if (option == "--sr") {
        sr_list = value;
      } else {
        throw Error("unknown option '" + option + "'");
      }
    }
    if (!has_centre || !has_steps || st_list.empty() || sr_list.empty())
      throw Error("--centre, --st, --sr and --max-steps are required");
    if (motion.rotates() && !(motion.step_degrees > 0.0))
      throw Error("--step-degrees must be positive for a rotating motion");
    if (motion.translates() && !(motion.step_length > 0.0))
      throw Error("--step-length must be positive for a translating motion");
    if (motion.max_steps < 1) throw Error("--max-steps must be at least 1");
    const std::vector<double> st_values = parse_list(st_list), sr_values = parse_list(sr_list);
    const PlanarMesh mesh = read_mesh(arguments[1]);
    std::cout << "st,sr,steps,max_angle,max_displacement,min_quality,mean_quality,reference_min_quality,"
                 "reference_mean_quality,failure_distance\n";
    for (const double st : st_values)
      for (const double sr : sr_values) {
        const Outcome outcome = move_until_failure(mesh, motion, st, sr);
        const double angle = motion.rotates() ? outcome.steps * motion.step_degrees : 0.0;
        const double displacement = motion.translates() ? outcome.steps * motion.step_length : 0.0;
        std::cout << st << ',';
        if (std::isinf(sr))
          std::cout << "inf";
        else
          std::cout << sr;
        std::cout << ',' << outcome.steps << ',' << angle << ',' << displacement << ','
                  << outcome.last.minimum << ',' << outcome.last.mean << ',' << outcome.reference.minimum
                  << ',' << outcome.reference.mean << ',' << outcome.failure_distance << '\n'
                  << std::flush;
      }
  } catch (const std::exception& error) {
    std::cerr << "deform_idw_study: error: " << error.what() << '\n' << usage;
    return 1;
  }
  return 0;
}
