// Hand-built far-field hulls for the far-field tests and benchmarks: a thin box
// ("slab"), optionally swept, turned and open on its symmetry side, and a small domain.
#pragma once

#include <array>
#include <cmath>
#include <map>

#include "mixmesh/farfield/farfield.hpp"

namespace mixmesh::farfield_hulls {

// The surface of an axis-aligned box from `lower` with the given size and cells per
// axis, triangles facing outward; `open_bottom` leaves out the face y = lower.y, and
// `sweep_degrees` shears x by tan(sweep) · y (a swept slab).
inline FarFieldInput slab(const Vector3& lower, const Vector3& size, const std::array<int, 3>& cells,
                          bool open_bottom, double sweep_degrees, double incidence_degrees = 0.0) {
  FarFieldInput input;
  std::map<std::array<int, 3>, Index> lattice;
  auto node = [&](const std::array<int, 3>& at) {
    const auto found = lattice.find(at);
    if (found != lattice.end()) return found->second;
    Vector3 point = lower;
    for (int axis = 0; axis < 3; ++axis)
      point(axis) += size(axis) * at[static_cast<std::size_t>(axis)] / cells[static_cast<std::size_t>(axis)];
    point.x() += std::tan(sweep_degrees * M_PI / 180.0) * (point.y() - lower.y());
    // Incidence: a turn about the y axis, which keeps the plane y = lower.y.
    const double turn = incidence_degrees * M_PI / 180.0;
    point = Vector3(std::cos(turn) * point.x() + std::sin(turn) * point.z(), point.y(),
                    -std::sin(turn) * point.x() + std::cos(turn) * point.z());
    input.points.push_back(point);
    return lattice[at] = static_cast<Index>(input.points.size() - 1);
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      if (open_bottom && axis == 1 && side == 0) continue;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i < cells[static_cast<std::size_t>(u)]; ++i)
        for (int j = 0; j < cells[static_cast<std::size_t>(v)]; ++j) {
          std::array<Index, 4> quad{};
          const int corners[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
          for (int corner = 0; corner < 4; ++corner) {
            std::array<int, 3> at{};
            at[static_cast<std::size_t>(axis)] = side * cells[static_cast<std::size_t>(axis)];
            at[static_cast<std::size_t>(u)] = corners[corner][0];
            at[static_cast<std::size_t>(v)] = corners[corner][1];
            quad[static_cast<std::size_t>(corner)] = node(at);
          }
          if (side == 1) {
            input.hull.push_back({quad[0], quad[1], quad[2]});
            input.hull.push_back({quad[0], quad[2], quad[3]});
          } else {
            input.hull.push_back({quad[0], quad[2], quad[1]});
            input.hull.push_back({quad[0], quad[3], quad[2]});
          }
        }
    }
  return input;
}

// A small, coarse domain round a unit-size hull, so the tests run fast.
inline FarFieldOptions small_options() {
  FarFieldOptions options;
  options.radius_in_chords = 5.0;
  options.farfield_size_in_chords = 1.5;
  options.size_gradient = 0.4;
  return options;
}

}  // namespace mixmesh::farfield_hulls
