// The hybrid baseline's triangulated wing (isotropic_surface.hpp): the wing unfolded
// along its leading edge into a plane, CGAL Delaunay refinement at a uniform size in
// that plane, mapped back through the section placement of the planform.
#include "mixmesh/surface/isotropic_surface.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "mixmesh/core/error.hpp"
#include "mixmesh/geometry/airfoil_curve.hpp"
#include "surface/constrained_mesher.hpp"

namespace mixmesh {
namespace {

using namespace surface_detail;

// Delaunay refinement bounded by the longest edge S gives a mean edge near 0.75 S on
// these wings; the bound is set so the mean edge meets the requested length.
constexpr double longest_to_mean_edge = 1.35;
constexpr double minimum_angle_degrees = 25.0;  // wing triangles (Delaunay refinement: < 30 terminates)

// The wing as a function of (signed arc length from the leading edge, span y): s < 0
// on the lower surface, s > 0 on the upper one, in metres. Sections of neighbouring
// airfoils blend at equal arc-length fractions of each surface, as in the planform.
class WingMap {
 public:
  explicit WingMap(const WingDefinition& wing) : wing_(wing) {
    for (const Airfoil& airfoil : wing.airfoils) curves_.emplace_back(airfoil);
    const double span = wing.semi_span();
    root_leading_edge_x_ = point(0.0, 0.0).x();
    const double tan_sweep = (point(0.0, span).x() - root_leading_edge_x_) / span;
    tan_sweep_ = tan_sweep;
    direction_ = Vector2(tan_sweep, 1.0).normalized();
  }

  // Physical lengths of the lower and upper surface of the section at y.
  std::pair<double, double> surface_lengths(double y) const {
    const StationBlend blend = station_at(wing_, y);
    const AirfoilCurve& first = curves_[blend.first_airfoil];
    const AirfoilCurve& second = curves_[blend.second_airfoil];
    const double w = blend.weight, chord = blend.parameters.chord;
    const double lower = (1.0 - w) * first.leading_edge() + w * second.leading_edge();
    const double upper =
        (1.0 - w) * (first.length() - first.leading_edge()) + w * (second.length() - second.leading_edge());
    return {chord * lower, chord * upper};
  }

  Vector3 point(double s, double y) const {
    const StationBlend blend = station_at(wing_, y);
    const auto [lower, upper] = surface_lengths(y);
    const auto unit_arc = [&](const AirfoilCurve& curve) {
      if (s < 0.0) return curve.leading_edge() * (1.0 - std::min(-s / lower, 1.0));
      return curve.leading_edge() + std::min(s / upper, 1.0) * (curve.length() - curve.leading_edge());
    };
    const AirfoilCurve& first = curves_[blend.first_airfoil];
    const AirfoilCurve& second = curves_[blend.second_airfoil];
    const Vector2 unit =
        (1.0 - blend.weight) * first.point(unit_arc(first)) + blend.weight * second.point(unit_arc(second));
    return place_section_point(blend.parameters, wing_.twist_axis, unit);
  }

  // Unfolding: the upper surface is laid out beside the fold line, the lower surface
  // is laid out the same way and mirrored across it.
  Vector2 to_plane(double s, double y) const {
    const Vector2 laid_out(fold_x(y) + std::abs(s), y);
    return s < 0.0 ? reflect(laid_out) : laid_out;
  }

  std::pair<double, double> from_plane(const Vector2& q) const {
    const Vector2 relative = q - Vector2(root_leading_edge_x_, 0.0);
    const bool upper = relative.x() * direction_.y() - relative.y() * direction_.x() >= 0.0;
    const Vector2 laid_out = upper ? q : reflect(q);
    const double y = std::clamp(laid_out.y(), 0.0, wing_.semi_span());
    const double offset = std::max(laid_out.x() - fold_x(y), 0.0);
    return {upper ? offset : -offset, y};
  }

 private:
  double fold_x(double y) const { return root_leading_edge_x_ + y * tan_sweep_; }
  Vector2 reflect(const Vector2& p) const {
    const Vector2 origin(root_leading_edge_x_, 0.0);
    const Vector2 relative = p - origin;
    return origin + 2.0 * relative.dot(direction_) * direction_ - relative;
  }

  const WingDefinition& wing_;
  std::vector<AirfoilCurve> curves_;
  double root_leading_edge_x_ = 0.0;
  double tan_sweep_ = 0.0;
  Vector2 direction_{0.0, 1.0};
};

// n + 1 values from `from` to `to`, n = the length over `spacing`, at least `minimum`.
std::vector<double> uniform_values(double from, double to, double spacing, int minimum) {
  const int cells = std::max(minimum, static_cast<int>(std::lround(std::abs(to - from) / spacing)));
  std::vector<double> values(static_cast<std::size_t>(cells) + 1);
  for (int k = 0; k <= cells; ++k) values[static_cast<std::size_t>(k)] = from + (to - from) * k / cells;
  values.back() = to;
  return values;
}

// Span positions of the trailing-edge nodes: equal 3D spacing along the trailing edge.
std::vector<double> trailing_edge_positions(const WingMap& map, double span, double spacing) {
  constexpr int samples = 2000;
  std::vector<double> ys(samples + 1), lengths(samples + 1, 0.0);
  Vector3 previous = map.point(map.surface_lengths(0.0).second, 0.0);
  for (int k = 0; k <= samples; ++k) {
    ys[static_cast<std::size_t>(k)] = span * k / samples;
    const double y = ys[static_cast<std::size_t>(k)];
    const Vector3 current = map.point(map.surface_lengths(y).second, y);
    if (k > 0)
      lengths[static_cast<std::size_t>(k)] =
          lengths[static_cast<std::size_t>(k - 1)] + (current - previous).norm();
    previous = current;
  }
  const std::vector<double> targets = uniform_values(0.0, lengths.back(), spacing, 2);
  std::vector<double> positions;
  std::size_t sample = 0;
  for (double target : targets) {
    while (sample + 1 < lengths.size() - 1 && lengths[sample + 1] < target) ++sample;
    const double piece = lengths[sample + 1] - lengths[sample];
    const double t = piece > 0.0 ? std::clamp((target - lengths[sample]) / piece, 0.0, 1.0) : 0.0;
    positions.push_back(ys[sample] + t * (ys[sample + 1] - ys[sample]));
  }
  positions.front() = 0.0;
  positions.back() = span;
  return positions;
}

// Signed arc lengths of the nodes of one section: lower trailing edge -> leading edge
// (s = 0, always a node) -> upper trailing edge.
std::vector<double> section_arc_lengths(const WingMap& map, double y, double spacing) {
  const auto [lower, upper] = map.surface_lengths(y);
  std::vector<double> values = uniform_values(-lower, 0.0, spacing, 2);
  const std::vector<double> upper_values = uniform_values(0.0, upper, spacing, 2);
  values.insert(values.end(), upper_values.begin() + 1, upper_values.end());
  return values;
}

}  // namespace

double default_isotropic_edge_length(const WingDefinition& wing, const SurfaceOptions& options) {
  validate_wing(wing);
  if (options.chordwise_cells < 1) throw Error("surface options: chordwise_cells must be positive");
  const WingMap map(wing);
  const auto [lower, upper] = map.surface_lengths(0.5 * wing.semi_span());
  return (lower + upper) / options.chordwise_cells;
}

SurfaceMesh generate_isotropic_wing_surface(const WingDefinition& wing_input, const SurfaceOptions& options,
                                            double edge_length, std::size_t maximum_triangles) {
  validate_wing(wing_input);
  if (!(edge_length >= 0.0)) {
    std::ostringstream message;
    message << "isotropic surface: edge length " << edge_length << " must be positive (0: the default)";
    throw Error(message.str());
  }
  WingDefinition wing = wing_input;
  for (Airfoil& airfoil : wing.airfoils)
    if (airfoil.trailing_edge_gap() != 0.0) airfoil = close_trailing_edge(airfoil);
  const double target = edge_length > 0.0 ? edge_length : default_isotropic_edge_length(wing, options);
  const double span = wing.semi_span();
  const WingMap map(wing);

  // Equilateral triangles of edge h cover sqrt(3)/4 h^2 each.
  const auto [mid_lower, mid_upper] = map.surface_lengths(0.5 * span);
  const double estimate = (mid_lower + mid_upper) * span / (std::sqrt(3.0) / 4.0 * target * target);
  if (estimate > static_cast<double>(maximum_triangles)) {
    std::ostringstream message;
    message << "isotropic surface: edge length " << target << " m would give about " << std::llround(estimate)
            << " triangles (at most " << maximum_triangles << ")";
    throw Error(message.str());
  }

  SurfaceMesh surface;
  surface.symmetry_y = 0.0;
  surface.symmetry_tolerance = 1e-9 * wing.stations.front().chord;
  // The outline in the plane, with the 3D node of each of its vertices.
  std::vector<Vector2> outline;
  std::vector<Index> outline_nodes;
  const auto add_node = [&](double s, double y) {
    surface.points.push_back(map.point(s, y));
    surface.points.back().y() = y;  // sections lie in y = const; keep root and tip exact
    return static_cast<Index>(surface.points.size() - 1);
  };

  const std::vector<double> root = section_arc_lengths(map, 0.0, target);
  const std::vector<double> tip = section_arc_lengths(map, span, target);
  const std::vector<double> trailing_edge = trailing_edge_positions(map, span, target);
  // Root, lower trailing edge to upper trailing edge (the last node is the first).
  std::vector<Index> root_nodes;
  for (std::size_t k = 0; k + 1 < root.size(); ++k) root_nodes.push_back(add_node(root[k], 0.0));
  for (std::size_t k = 0; k < root.size(); ++k) {
    outline.push_back(map.to_plane(root[k], 0.0));
    outline_nodes.push_back(k + 1 < root.size() ? root_nodes[k] : root_nodes.front());
  }
  std::vector<Index> trailing_edge_nodes;
  for (std::size_t k = 1; k + 1 < trailing_edge.size(); ++k)
    trailing_edge_nodes.push_back(add_node(map.surface_lengths(trailing_edge[k]).second, trailing_edge[k]));
  std::vector<Index> tip_nodes;
  for (std::size_t k = 0; k + 1 < tip.size(); ++k) tip_nodes.push_back(add_node(tip[k], span));
  // Upper trailing edge, root to tip.
  for (std::size_t k = 1; k + 1 < trailing_edge.size(); ++k) {
    outline.push_back(map.to_plane(map.surface_lengths(trailing_edge[k]).second, trailing_edge[k]));
    outline_nodes.push_back(trailing_edge_nodes[k - 1]);
  }
  // Tip, upper trailing edge to lower trailing edge.
  for (std::size_t k = tip.size(); k-- > 0;) {
    outline.push_back(map.to_plane(tip[k], span));
    outline_nodes.push_back(k + 1 < tip.size() ? tip_nodes[k] : tip_nodes.front());
  }
  // Lower trailing edge, tip to root.
  for (std::size_t k = trailing_edge.size() - 1; k-- > 1;) {
    outline.push_back(map.to_plane(-map.surface_lengths(trailing_edge[k]).first, trailing_edge[k]));
    outline_nodes.push_back(trailing_edge_nodes[k - 1]);
  }

  Triangulation triangulation;
  std::vector<Triangulation::Vertex_handle> handles;
  for (std::size_t k = 0; k < outline.size(); ++k) {
    auto handle = triangulation.insert(Kernel::Point_2(outline[k].x(), outline[k].y()));
    handle->info() = outline_nodes[k];
    handles.push_back(handle);
  }
  if (triangulation.number_of_vertices() != outline.size())
    throw Error("isotropic surface: the unfolded wing outline touches itself (" +
                std::to_string(triangulation.number_of_vertices()) + " vertices for " +
                std::to_string(outline.size()) + " outline points)");
  for (std::size_t k = 0; k < handles.size(); ++k)
    triangulation.insert_constraint(handles[k], handles[(k + 1) % handles.size()]);
  const double angle = minimum_angle_degrees * M_PI / 180.0;
  const double longest_edge = longest_to_mean_edge * target;
  Mesher mesher(triangulation, Criteria(std::sin(angle) * std::sin(angle), longest_edge));
  mesher.refine_mesh();

  // Vertices that are not on the outline are new interior points.
  const std::set<Triangulation::Vertex_handle> outline_handles(handles.begin(), handles.end());
  for (auto vertex = triangulation.finite_vertices_begin(); vertex != triangulation.finite_vertices_end();
       ++vertex) {
    if (outline_handles.count(vertex) != 0) continue;
    const auto [s, y] = map.from_plane(Vector2(vertex->point().x(), vertex->point().y()));
    vertex->info() = static_cast<Index>(surface.points.size());
    surface.points.push_back(map.point(s, y));
  }

  TrianglePatch wing_patch;
  wing_patch.name = "wing";
  // Counter-clockwise in the plane is counter-clockwise in (s, y) on both surfaces (the
  // lower one is mirrored twice), which is the outward orientation of the wing patch.
  for (auto face = triangulation.finite_faces_begin(); face != triangulation.finite_faces_end(); ++face) {
    if (!face->is_in_domain()) continue;
    wing_patch.triangles.insert(wing_patch.triangles.end(),
                                {face->vertex(0)->info(), face->vertex(1)->info(), face->vertex(2)->info()});
  }
  surface.unstructured.push_back(std::move(wing_patch));

  TipCapOptions tip_options = options.tip;
  if (!(tip_options.maximum_edge > 0.0)) tip_options.maximum_edge = longest_edge;
  TrianglePatch tip_patch;
  tip_patch.name = "tip";
  const std::size_t first_cap_point = surface.points.size();
  tip_patch.triangles = triangulate_planar_cap(surface.points, tip_nodes, tip_options, true);
  if (tip_options.rounded) round_cap(surface.points, tip_nodes, first_cap_point, true);
  surface.unstructured.push_back(std::move(tip_patch));
  return surface;
}

}  // namespace mixmesh
