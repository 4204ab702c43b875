// Motions: the poses of their bodies, and the CSV data some laws need.
#include "mixmesh/deform/motion.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "deform/rotation.hpp"
#include "mixmesh/core/error.hpp"

namespace mixmesh::deform {

namespace {

constexpr double pi = 3.14159265358979323846;

// Splits a CSV line into numbers; false when a field is not a number (a header line).
bool parse_numbers(const std::string& line, std::vector<double>& numbers) {
  numbers.clear();
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) {
    const auto first = field.find_first_not_of(" \t\r");
    if (first == std::string::npos) return false;
    const auto last = field.find_last_not_of(" \t\r");
    const std::string trimmed = field.substr(first, last - first + 1);
    std::size_t used = 0;
    try {
      numbers.push_back(std::stod(trimmed, &used));
    } catch (const std::exception&) {
      return false;
    }
    if (used != trimmed.size()) return false;
  }
  return true;
}

// Rows of `columns` numbers (or of `alternative` numbers, when not 0; every row the
// same); the first line may be a header, blank lines and lines starting with '#' are
// skipped.
std::vector<std::vector<double>> read_csv(const std::filesystem::path& file, std::size_t columns,
                                          std::size_t alternative = 0) {
  std::ifstream stream(file);
  if (!stream) throw file_error(file.string(), 0, "cannot open");
  std::vector<std::vector<double>> rows;
  std::string line;
  long line_number = 0;
  std::vector<double> numbers;
  while (std::getline(stream, line)) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[line.find_first_not_of(" \t")] == '#')
      continue;
    if (!parse_numbers(line, numbers)) {
      if (rows.empty() && line_number == 1) continue;  // header
      throw file_error(file.string(), line_number,
                       "expected " + std::to_string(columns) + " numbers separated by commas");
    }
    if (rows.empty() && alternative != 0 && numbers.size() == alternative) columns = alternative;
    if (numbers.size() != columns)
      throw file_error(
          file.string(), line_number,
          "expected " + std::to_string(columns) + " columns, found " + std::to_string(numbers.size()));
    for (double number : numbers)
      if (!std::isfinite(number)) throw file_error(file.string(), line_number, "value is not finite");
    rows.push_back(numbers);
  }
  if (rows.empty()) throw file_error(file.string(), 0, "no data rows");
  return rows;
}

}  // namespace

Vector3 RigidPose::rotation_vector() const {
  return detail::rotation_vector(rotation);
}

Eigen::Matrix3d axis_rotation(const Vector3& axis, double angle_degrees) {
  if (axis.norm() == 0.0) throw Error("rotation axis must not be zero");
  return Eigen::AngleAxisd(angle_degrees * pi / 180.0, axis.normalized()).toRotationMatrix();
}

std::vector<RigidPose> read_trajectory(const std::filesystem::path& file, const Vector3& centre) {
  std::vector<RigidPose> poses;
  for (const auto& row : read_csv(file, 6)) {
    RigidPose pose;
    pose.centre = centre;
    pose.translation = {row[0], row[1], row[2]};
    pose.rotation = axis_rotation(Vector3::UnitZ(), row[5]) * axis_rotation(Vector3::UnitY(), row[4]) *
                    axis_rotation(Vector3::UnitX(), row[3]);
    poses.push_back(pose);
  }
  return poses;
}

NodeField read_node_field(const std::filesystem::path& file) {
  NodeField field;
  for (const auto& row : read_csv(file, 4, 6)) {
    if (row.size() == 6) {
      field.positions.emplace_back(row[0], row[1], row[2]);
      field.values.emplace_back(row[3], row[4], row[5]);
      continue;
    }
    if (row[0] < 0 || row[0] != std::floor(row[0]) || row[0] > 2e9)
      throw file_error(file.string(), 0, "node index " + std::to_string(row[0]) + " is not a point index");
    field.nodes.push_back(static_cast<Index>(row[0]));
    field.values.emplace_back(row[1], row[2], row[3]);
  }
  return field;
}

RigidPose body_pose(const Body& body, int step, int steps) {
  RigidPose pose;
  pose.centre = body.centre;
  if (step <= 0) return pose;
  switch (body.law) {
    case MotionLaw::rigid: {
      const double fraction = static_cast<double>(step) / std::max(steps, 1);
      pose.rotation = axis_rotation(body.axis, body.angle * fraction);
      pose.translation = body.translation * fraction;
      break;
    }
    case MotionLaw::pitch_plunge: {
      const double phase = 2.0 * pi * step / body.period_steps;
      pose.rotation = axis_rotation(body.axis, body.pitch_amplitude * std::sin(phase));
      const Vector3 direction =
          body.plunge_direction.norm() > 0 ? body.plunge_direction.normalized() : Vector3::Zero();
      pose.translation = direction * body.plunge_amplitude * std::sin(phase + body.phase * pi / 180.0);
      break;
    }
    case MotionLaw::trajectory:
      if (static_cast<std::size_t>(step) > body.poses.size())
        throw Error("body '" + body.name + "' has no trajectory pose for step " + std::to_string(step));
      pose = body.poses[static_cast<std::size_t>(step) - 1];
      break;
    case MotionLaw::mode:
    case MotionLaw::surface:
      break;
  }
  return pose;
}

}  // namespace mixmesh::deform
