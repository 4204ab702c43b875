// Boundary motion of a deformation: what each named boundary marker does, step by step.
//
// A Motion lists bodies; each body is a set of boundary markers that move together
// by one of five laws. Markers that no body names stay fixed; markers listed under
// `symmetry` are planes (lines in 2D) whose nodes slide in their plane.
//
//   rigid          rotation (axis, centre, angle) and translation, ramped linearly
//                  over the steps: step k of n applies k/n of both
//   pitch_plunge   flutter: θ = A sin(2π k / period_steps), h = H sin(2π k / period_steps + φ)
//   trajectory     rigid poses read from CSV, one per step; each step deforms the
//                  previous step's mesh (store release)
//   mode           a displacement field on boundary nodes from CSV (structural mode
//                  shape) times `scale`, ramped over the steps
//   surface        new positions of boundary nodes from CSV (design change, same
//                  topology), ramped over the steps
//
// The motion file format (TOML) is described in docs/deform.md.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh::deform {

// x ↦ rotation (x − centre) + centre + translation.
struct RigidPose {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vector3 centre = Vector3::Zero();
  Vector3 translation = Vector3::Zero();

  Vector3 apply(const Vector3& point) const { return rotation * (point - centre) + centre + translation; }
  // Rotation vector (axis × angle in radians) of `rotation`.
  Vector3 rotation_vector() const;
};

// A rotation of `angle_degrees` about `axis` (need not be unit, must be non-zero).
Eigen::Matrix3d axis_rotation(const Vector3& axis, double angle_degrees);

enum class MotionLaw { rigid, pitch_plunge, trajectory, mode, surface };

// Per-node data read from CSV for the mode and surface laws: one row per node, either
// "node,x,y,z" (0-based mesh point index, then a displacement or a new position) or
// "x,y,z,vx,vy,vz" (the node at that position, then the value; positions match the
// nearest node of the body within 1e-6 of its size).
struct NodeField {
  std::vector<Index> nodes;        // rows by index
  std::vector<Vector3> positions;  // rows by position (nodes is then empty)
  std::vector<Vector3> values;
};

struct Body {
  std::string name;                  // for messages
  std::vector<std::string> markers;  // boundary markers that move with the body
  MotionLaw law = MotionLaw::rigid;

  // rigid and pitch_plunge: rotation about `axis` through `centre`.
  Vector3 centre = Vector3::Zero();
  Vector3 axis = Vector3::UnitZ();
  double angle = 0.0;                     // degrees (rigid: the final angle)
  Vector3 translation = Vector3::Zero();  // rigid: the final translation

  // pitch_plunge
  double pitch_amplitude = 0.0;   // degrees
  double plunge_amplitude = 0.0;  // length
  Vector3 plunge_direction = Vector3::UnitY();
  double phase = 0.0;  // degrees, plunge ahead of pitch
  int period_steps = 16;

  // trajectory: poses relative to the initial position, one per step.
  std::vector<RigidPose> poses;

  // mode (displacements × scale) and surface (new positions).
  NodeField field;
  double scale = 1.0;
};

struct Motion {
  std::vector<Body> bodies;
  std::vector<std::string> symmetry;  // markers whose nodes slide in their plane
  int steps = 1;                      // number of deformed meshes to produce
  // Each step deforms the previous step's mesh rather than the initial one. Set when
  // a body follows a trajectory.
  bool incremental = false;
  std::string method = "ara";  // "ara" or "idw"
};

// "tx,ty,tz,roll,pitch,yaw" rows (degrees; R = Rz(yaw) Ry(pitch) Rx(roll) about
// `centre`), with an optional header line.
std::vector<RigidPose> read_trajectory(const std::filesystem::path& file, const Vector3& centre);
// "node,x,y,z" or "x,y,z,vx,vy,vz" rows, with an optional header line.
NodeField read_node_field(const std::filesystem::path& file);

// The pose of a rigid or pitch_plunge body at step `step` (1-based) of `steps`,
// relative to the initial position; the trajectory pose for trajectory bodies.
RigidPose body_pose(const Body& body, int step, int steps);

}  // namespace mixmesh::deform
