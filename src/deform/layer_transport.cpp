// The transport of the layer lines with their base (layer_lines.hpp says why).
#include <Eigen/Geometry>

#include <algorithm>
#include <array>

#include <nanoflann.hpp>

#include "deform/ara_smoothing.hpp"
#include "deform/layer_lines.hpp"
#include "deform/rotation.hpp"
#include "mixmesh/mesh/point_cloud.hpp"

namespace mixmesh::deform::detail {

namespace {

// Whether `node` lies on a wall's line (its base is prescribed).
bool on_wall_line(const LayerLines& lines, const BoundaryMotion& boundary, std::size_t node) {
  return lines.base[node] >= 0 &&
         boundary.roles[static_cast<std::size_t>(lines.base[node])] == NodeRole::prescribed;
}

// A wall's line is moved rigidly to its top, and what the method had there that the
// rigid motion has not (d_t = method − rigid at the top t) goes to the nodes outside the
// layers instead: x′ = x_method − φ(z / L) Σ w_t d_t / Σ w_t over the eight nearest tops,
// w_t = 1 / r_t², z the node's height above its nearest top along that line, L the
// size of the wall's faces at the line's base, φ(q) = (1 − q)² (1 + 2q) up to q = 1.
// Why: a method's field is accurate on the scale of the wall's faces, not of the
// layers. ARA moves a cell with the rigid motion of its nearest wall face; a bending
// mode's curvature puts the face's corners up to 2 mm off that motion on a coarse wing
// (0.17 m faces), and the layers there are 0.2 mm thick: spread along the line, that
// difference tilted the first cells by up to 85 degrees and folded 1,642 of them. Above
// the layers, where the cells are as large as the faces, the same difference is a small
// strain, and it fades out one face size above the wall.
void carry_top_offsets(const LayerLines& lines, const BoundaryMotion& boundary,
                       const std::vector<Vector3>& original, const std::vector<Vector3>& carried,
                       std::vector<Vector3>& moved) {
  const std::size_t point_count = original.size();
  struct Top {
    Vector3 position;     // undeformed
    Vector3 base;         // undeformed
    Vector3 direction;    // undeformed, base to top
    double height = 0.0;  // H, base to top
    Vector3 offset;       // d_t
    double reach = 0.0;   // L
  };
  std::vector<char> seen(point_count, 0);
  std::vector<Top> tops;
  for (std::size_t node = 0; node < point_count; ++node) {
    if (!on_wall_line(lines, boundary, node)) continue;
    const std::size_t base = static_cast<std::size_t>(lines.base[node]);
    const std::size_t top = static_cast<std::size_t>(lines.top[node]);
    if (seen[top]) continue;
    seen[top] = 1;
    Top entry;
    entry.position = original[top];
    entry.base = original[base];
    entry.direction = (original[top] - original[base]).normalized();
    entry.height = (original[top] - original[base]).norm();
    entry.offset = carried[top];
    entry.reach = lines.height[top];
    for (std::size_t slot = lines.star_offsets[base]; slot < lines.star_offsets[base + 1]; ++slot)
      entry.reach = std::max(
          entry.reach, (original[static_cast<std::size_t>(lines.star_nodes[slot])] - original[base]).norm());
    tops.push_back(entry);
  }
  if (tops.empty()) return;
  auto fade = [](double fraction) {
    return fraction >= 1.0 ? 0.0 : (1.0 - fraction) * (1.0 - fraction) * (1.0 + 2.0 * fraction);
  };
  struct TopPosition {
    const Vector3& operator()(const Top& top) const { return top.position; }
  };
  using Cloud = PointCloud<Top, TopPosition>;
  using Tree =
      nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 3, Index>;
  const Cloud cloud{&tops};
  const Tree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  constexpr std::size_t nearest_count = 8;
  parallel_items(point_count, [&](std::size_t node) {
    if (boundary.roles[node] == NodeRole::prescribed || on_wall_line(lines, boundary, node)) return;
    std::array<Index, nearest_count> found{};
    std::array<double, nearest_count> squared{};
    const std::size_t count = tree.knnSearch(original[node].data(), std::min(nearest_count, tops.size()),
                                             found.data(), squared.data());
    if (count == 0) return;
    // Where the node stands against its nearest line: height a along it from the base,
    // distance l from it. Within the layers' height the node takes the share a / H a
    // line node would; above them and beyond one face size to the side the offset fades.
    const Top& nearest = tops[static_cast<std::size_t>(found[0])];
    const Vector3 from_base = original[node] - nearest.base;
    const double along = from_base.dot(nearest.direction);
    const double aside = (from_base - along * nearest.direction).norm();
    const double share = along <= 0.0             ? 0.0
                         : along < nearest.height ? along / nearest.height
                                                  : fade((along - nearest.height) / nearest.reach);
    const double weight = share * (aside <= nearest.reach ? 1.0 : fade(aside / nearest.reach - 1.0));
    if (weight <= 0.0) return;
    Vector3 sum = Vector3::Zero();
    double total = 0.0;
    for (std::size_t item = 0; item < count; ++item) {
      const Top& top = tops[static_cast<std::size_t>(found[item])];
      if (squared[item] == 0.0) {
        sum = top.offset;
        total = 1.0;
        break;
      }
      sum += top.offset / squared[item];
      total += 1.0 / squared[item];
    }
    moved[node] -= weight * sum / total;
  });
}

}  // namespace

void transport_layer_lines(const LayerLines& lines, const BoundaryMotion& boundary,
                           const std::vector<Vector3>& original, std::vector<Vector3>& moved) {
  if (lines.line_nodes == 0) return;
  const std::size_t point_count = original.size();
  auto on_wall = [&](std::size_t node) { return on_wall_line(lines, boundary, node); };
  // The rotation of the base surface at every base node of `wall` (or of a sheet),
  // fitted to its star in `field`.
  std::vector<char> is_base(point_count, 0);
  for (std::size_t node = 0; node < point_count; ++node)
    if (lines.base[node] >= 0) is_base[static_cast<std::size_t>(lines.base[node])] = 1;
  std::vector<Eigen::Matrix3d> turn(point_count);
  auto fit_turns = [&](bool wall, const std::vector<Vector3>& field) {
    parallel_items(point_count, [&](std::size_t node) {
      if (!is_base[node] || (boundary.roles[node] == NodeRole::prescribed) != wall) return;
      std::vector<Vector3> before;
      std::vector<Vector3> after;
      for (std::size_t slot = lines.star_offsets[node]; slot < lines.star_offsets[node + 1]; ++slot) {
        const std::size_t other = static_cast<std::size_t>(lines.star_nodes[slot]);
        before.push_back(original[other] - original[node]);
        after.push_back(field[other] - field[node]);
      }
      turn[node] = rotation_matrix(fit_rotation(before, after, false));
    });
  };

  // 1. A wall's lines move rigidly with their base, top included; what the method had
  // at the tops goes to the nodes outside the wall's layers (carry_top_offsets).
  fit_turns(true, moved);
  std::vector<Vector3> carried(point_count, Vector3::Zero());
  parallel_items(point_count, [&](std::size_t node) {
    if (!on_wall(node) || boundary.roles[node] == NodeRole::prescribed) return;
    const std::size_t base = static_cast<std::size_t>(lines.base[node]);
    const Vector3 rigid = moved[base] + turn[base] * (original[node] - original[base]);
    if (static_cast<std::size_t>(lines.top[node]) == node) carried[node] = moved[node] - rigid;
    moved[node] = rigid;  // bases are prescribed: no line node is read after it moved
  });
  carry_top_offsets(lines, boundary, original, carried, moved);

  // 2. A sheet's base moves by the method, not by the motion, and the rotation fitted to
  // its star is only as good as the method's field across the star: at the ONERA M6
  // wake's tip edge the sheet nodes differ by 5 cm over 5.6 mm of span under ARA, and
  // the fit tilted the lines above them. The line's turn is that fit corrected by the
  // shortest arc that takes the fitted chord (base to top) to the method's chord: the
  // line's own direction from the method, the fit's twist about it; its top keeps the
  // method's position and the difference is spread along the line by arc length. A
  // rigid motion is kept exactly (the fitted chord is then the moved chord). The pass
  // reads bases, tops and stars only and writes neither, so it reads `moved` in place.
  fit_turns(false, moved);
  parallel_items(point_count, [&](std::size_t node) {
    if (lines.base[node] < 0 || on_wall(node) || boundary.roles[node] == NodeRole::prescribed) return;
    const std::size_t base = static_cast<std::size_t>(lines.base[node]);
    const std::size_t top = static_cast<std::size_t>(lines.top[node]);
    if (top == node) return;
    Eigen::Matrix3d line_turn = turn[base];
    const Vector3 fitted_chord = turn[base] * (original[top] - original[base]);
    const Vector3 moved_chord = moved[top] - moved[base];
    if (fitted_chord.norm() > 0.0 && moved_chord.norm() > 0.0)
      line_turn =
          Eigen::Quaterniond::FromTwoVectors(fitted_chord, moved_chord).toRotationMatrix() * turn[base];
    auto rigid = [&](std::size_t point) -> Vector3 {
      return moved[base] + line_turn * (original[point] - original[base]);
    };
    const double share = lines.height[node] / lines.height[top];
    moved[node] = rigid(node) + share * (moved[top] - rigid(top));
  });
}

}  // namespace mixmesh::deform::detail
