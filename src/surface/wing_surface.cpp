#include "mixmesh/surface/wing_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "mixmesh/core/error.hpp"
#include "mixmesh/geometry/airfoil_curve.hpp"
#include "mixmesh/geometry/distribution.hpp"

namespace mixmesh {
namespace {

void check_options(const SurfaceOptions& options, bool has_base) {
  const auto fail = [](const std::string& message) { throw Error("surface options: " + message); };
  if (options.chordwise_cells < 8) fail("chordwise_cells must be at least 8");
  if (options.spanwise_cells < 2) fail("spanwise_cells must be at least 2");
  if (!(options.leading_edge_spacing > 0.0)) fail("leading_edge_spacing must be positive");
  if (!(options.trailing_edge_spacing > 0.0)) fail("trailing_edge_spacing must be positive");
  if (!(options.root_spacing > 0.0) || !(options.tip_spacing > 0.0))
    fail("root and tip spacings must be positive");
  if (has_base && (options.base_cells < 2 || options.base_cells % 2 != 0)) {
    fail("base_cells must be even and at least 2");
  }
  if (!(options.base_face_aspect >= 0.0) || !std::isfinite(options.base_face_aspect))
    fail("base_face_aspect must be finite and at least 0");
  if (options.wake.enabled && !(options.wake.length > 0.0)) fail("wake length must be positive");
  if (options.wake.enabled && !(options.wake.growth >= 1.0)) fail("wake growth must be at least 1");
  if (options.wake.first_spacing && !(*options.wake.first_spacing > 0.0))
    fail("wake first_spacing must be > 0");
}

// Unit-chord node positions of one airfoil: lower surface from the trailing edge to
// the leading edge, then the upper surface, each clustered at both ends.
std::vector<Vector2> section_nodes(const Airfoil& airfoil, const SurfaceOptions& options, int lower_cells,
                                   int upper_cells) {
  const AirfoilCurve curve(airfoil);
  const double lower_length = curve.leading_edge();
  const double upper_length = curve.length() - lower_length;
  const std::vector<double> lower = vinokur_distribution(
      lower_cells, options.trailing_edge_spacing / lower_length, options.leading_edge_spacing / lower_length);
  const std::vector<double> upper = vinokur_distribution(
      upper_cells, options.leading_edge_spacing / upper_length, options.trailing_edge_spacing / upper_length);
  std::vector<Vector2> nodes;
  nodes.reserve(lower.size() + upper.size() - 1);
  for (double fraction : lower) nodes.push_back(curve.point(fraction * lower_length));
  for (std::size_t k = 1; k < upper.size(); ++k)
    nodes.push_back(curve.point(lower_length + upper[k] * upper_length));
  // The knots are exact: keep the trailing edge and leading edge where the airfoil has them.
  nodes.front() = airfoil.points.front();
  nodes[static_cast<std::size_t>(lower_cells)] = airfoil.points[airfoil.leading_edge];
  nodes.back() = airfoil.points.back();
  return nodes;
}

// Span positions: clustered at root and tip, with the node nearest each interior
// station moved onto it so that kinks of the planform are nodes.
std::vector<double> span_positions(const WingDefinition& wing, const SurfaceOptions& options) {
  const double span = wing.semi_span();
  std::vector<double> fractions =
      vinokur_distribution(options.spanwise_cells, options.root_spacing, options.tip_spacing);
  std::vector<double> ys(fractions.size());
  for (std::size_t j = 0; j < ys.size(); ++j) ys[j] = fractions[j] * span;
  for (std::size_t k = 1; k + 1 < wing.stations.size(); ++k) {
    const double y = wing.stations[k].y;
    const auto nearest = std::min_element(
        ys.begin() + 1, ys.end() - 1, [y](double a, double b) { return std::abs(a - y) < std::abs(b - y); });
    const std::size_t j = static_cast<std::size_t>(nearest - ys.begin());
    if (y > ys[j - 1] && y < ys[j + 1]) ys[j] = y;
  }
  ys.front() = 0.0;
  ys.back() = span;
  return ys;
}

// Blunt trailing edges: closed on the section, or kept as a base patch. Returns
// whether the wing keeps a base.
bool close_or_keep_trailing_edges(WingDefinition& wing) {
  bool blunt = false;
  for (Airfoil& airfoil : wing.airfoils) {
    if (airfoil.trailing_edge_gap() == 0.0) continue;
    if (wing.blunt_trailing_edge == TrailingEdge::close) {
      airfoil = close_trailing_edge(airfoil);
    } else {
      blunt = true;
    }
  }
  if (blunt) {
    for (const Airfoil& airfoil : wing.airfoils) {
      if (airfoil.trailing_edge_gap() == 0.0) {
        throw Error(airfoil.source + ": a base trailing edge needs every section blunt, this one is sharp");
      }
    }
  }
  return blunt;
}

// The wing's own patch round the sections, its points appended to surface.points,
// and each span station's frame in `frames`.
StructuredPatch place_wing_patch(const WingDefinition& wing, const SurfaceOptions& options, bool blunt,
                                 SurfaceMesh& surface, std::vector<SpanStation>& frames) {
  const int lower_cells = options.chordwise_cells / 2;
  const int upper_cells = options.chordwise_cells - lower_cells;
  const int ni = options.chordwise_cells + 1;
  std::vector<std::vector<Vector2>> sections;
  for (const Airfoil& airfoil : wing.airfoils)
    sections.push_back(section_nodes(airfoil, options, lower_cells, upper_cells));
  const std::vector<double> ys = span_positions(wing, options);
  const int nj = static_cast<int>(ys.size());
  const int unique_i = blunt ? ni : ni - 1;  // a sharp trailing edge is one node

  StructuredPatch wing_patch;
  wing_patch.name = "wing";
  wing_patch.ni = ni;
  wing_patch.nj = nj;
  wing_patch.leading_edge_i = lower_cells;
  wing_patch.nodes.resize(static_cast<std::size_t>(ni) * static_cast<std::size_t>(nj));
  frames.resize(static_cast<std::size_t>(nj));
  surface.points.reserve(static_cast<std::size_t>(unique_i) * static_cast<std::size_t>(nj));
  for (int j = 0; j < nj; ++j) {
    const StationBlend blend = station_at(wing, ys[static_cast<std::size_t>(j)]);
    frames[static_cast<std::size_t>(j)] = blend.parameters;
    const auto& first = sections[blend.first_airfoil];
    const auto& second = sections[blend.second_airfoil];
    for (int i = 0; i < unique_i; ++i) {
      const Vector2 unit = (1.0 - blend.weight) * first[static_cast<std::size_t>(i)] +
                           blend.weight * second[static_cast<std::size_t>(i)];
      wing_patch.nodes[static_cast<std::size_t>(j * ni + i)] = static_cast<Index>(surface.points.size());
      surface.points.push_back(place_section_point(blend.parameters, wing.twist_axis, unit));
    }
    if (!blunt) wing_patch.nodes[static_cast<std::size_t>(j * ni + ni - 1)] = wing_patch.node(0, j);
  }
  // Root nodes lie exactly on the symmetry plane.
  for (int i = 0; i < ni; ++i) surface.points[static_cast<std::size_t>(wing_patch.node(i, 0))].y() = 0.0;
  return wing_patch;
}

// The trailing-edge line the wake starts from, and the tip outline for the cap.
struct WingEdges {
  std::vector<Index> trailing_edge;
  std::vector<Index> tip_outline;
};

// The faces across a blunt base: options.base_cells, fewer by twos (down to 2) while the
// base's narrowest face would be more than options.base_face_aspect times shorter than
// the spanwise faces beside it. The outer cells over a base are split about a point
// half a face from their long sides (docs/interface.md), so the pyramids on those sides
// have a scaled Jacobian of about the face's width over the spanwise face's length; a
// base 1.9 mm thick under spanwise faces 2.1 m long gave 2.3e-4 with 4 faces.
int base_cell_count(const StructuredPatch& wing_patch, const std::vector<Vector3>& points,
                    const SurfaceOptions& options) {
  if (options.base_face_aspect <= 0.0) return options.base_cells;
  auto at = [&](int i, int j) -> const Vector3& {
    return points[static_cast<std::size_t>(wing_patch.node(i, j))];
  };
  const int top = wing_patch.ni - 1;
  double thinnest = std::numeric_limits<double>::infinity();  // base thickness / spanwise face
  for (int j = 0; j < wing_patch.nj; ++j) {
    double length = 0.0;
    for (int other : {j - 1, j + 1})
      if (other >= 0 && other < wing_patch.nj)
        length = std::max({length, (at(top, other) - at(top, j)).norm(), (at(0, other) - at(0, j)).norm()});
    if (length > 0.0) thinnest = std::min(thinnest, (at(top, j) - at(0, j)).norm() / length);
  }
  int cells = options.base_cells;
  while (cells > 2 && thinnest / cells * options.base_face_aspect < 1.0) cells -= 2;
  return cells;
}

// The wing patch and, for a blunt trailing edge, the base patch between its ends.
WingEdges add_wall_patches(const StructuredPatch& wing_patch, const SurfaceOptions& options, bool blunt,
                           SurfaceMesh& surface) {
  const int ni = wing_patch.ni;
  const int nj = wing_patch.nj;
  const int unique_i = blunt ? ni : ni - 1;
  WingEdges edges;
  std::vector<Index>& trailing_edge = edges.trailing_edge;
  std::vector<Index>& tip_outline = edges.tip_outline;
  trailing_edge.resize(static_cast<std::size_t>(nj));
  for (int i = 0; i < unique_i; ++i) tip_outline.push_back(wing_patch.node(i, nj - 1));
  if (blunt) {
    const int base_cells = base_cell_count(wing_patch, surface.points, options);
    StructuredPatch base;
    base.name = "base";
    base.ni = base_cells + 1;
    base.nj = nj;
    base.nodes.resize(static_cast<std::size_t>(base.ni) * static_cast<std::size_t>(nj));
    for (int j = 0; j < nj; ++j) {
      const Index top = wing_patch.node(ni - 1, j), bottom = wing_patch.node(0, j);
      base.nodes[static_cast<std::size_t>(j * base.ni)] = top;
      base.nodes[static_cast<std::size_t>(j * base.ni + base.ni - 1)] = bottom;
      for (int i = 1; i + 1 < base.ni; ++i) {
        const double fraction = double(i) / base_cells;
        base.nodes[static_cast<std::size_t>(j * base.ni + i)] = static_cast<Index>(surface.points.size());
        const Vector3 point = (1.0 - fraction) * surface.points[static_cast<std::size_t>(top)] +
                              fraction * surface.points[static_cast<std::size_t>(bottom)];
        surface.points.push_back(point);
      }
      trailing_edge[static_cast<std::size_t>(j)] = base.node(base_cells / 2, j);
    }
    for (int i = 1; i + 1 < base.ni; ++i) tip_outline.push_back(base.node(i, nj - 1));
    surface.structured.push_back(wing_patch);
    surface.structured.push_back(base);
  } else {
    for (int j = 0; j < nj; ++j) trailing_edge[static_cast<std::size_t>(j)] = wing_patch.node(0, j);
    surface.structured.push_back(wing_patch);
  }
  return edges;
}

void add_wake(const WingDefinition& wing, const SurfaceOptions& options,
              const std::vector<Index>& trailing_edge, const std::vector<SpanStation>& frames,
              SurfaceMesh& surface) {
  const int nj = static_cast<int>(trailing_edge.size());
  double downstream_end = -1e300;
  for (Index node : trailing_edge)
    downstream_end = std::max(downstream_end, surface.points[static_cast<std::size_t>(node)].x());
  const double root_chord = wing.stations.front().chord;
  downstream_end += options.wake.length * root_chord;
  const double wake_spacing = options.wake.first_spacing.value_or(options.trailing_edge_spacing);
  // The cell count follows from geometric growth on the root line; every other line
  // keeps that count and its own first spacing (proportional to its chord).
  const Vector3 root_edge = surface.points[static_cast<std::size_t>(trailing_edge.front())];
  const int cells =
      static_cast<int>(geometric_distribution(wake_spacing * root_chord / (downstream_end - root_edge.x()),
                                              options.wake.growth)
                           .size()) -
      1;
  StructuredPatch wake;
  wake.name = "wake";
  wake.role = PatchRole::wake;
  wake.ni = cells + 1;
  wake.nj = nj;
  wake.nodes.resize(static_cast<std::size_t>(wake.ni) * static_cast<std::size_t>(nj));
  for (int j = 0; j < nj; ++j) {
    const Vector3 start =
        surface.points[static_cast<std::size_t>(trailing_edge[static_cast<std::size_t>(j)])];
    const double length = downstream_end - start.x();
    const double first = wake_spacing * frames[static_cast<std::size_t>(j)].chord / length;
    const std::vector<double> positions = vinokur_distribution(cells, std::min(first, 0.5 / cells), 0.0);
    wake.nodes[static_cast<std::size_t>(j * wake.ni)] = trailing_edge[static_cast<std::size_t>(j)];
    for (int i = 1; i <= cells; ++i) {
      wake.nodes[static_cast<std::size_t>(j * wake.ni + i)] = static_cast<Index>(surface.points.size());
      surface.points.emplace_back(start.x() + positions[static_cast<std::size_t>(i)] * length, start.y(),
                                  start.z());
    }
  }
  surface.structured.push_back(wake);
}

void add_tip_cap(const StructuredPatch& wing_patch, const SurfaceOptions& options, bool blunt,
                 const WingEdges& edges, SurfaceMesh& surface) {
  const int ni = wing_patch.ni;
  const int nj = wing_patch.nj;
  const std::vector<Index>& trailing_edge = edges.trailing_edge;
  const std::vector<Index>& tip_outline = edges.tip_outline;
  TrianglePatch tip;
  tip.name = "tip";
  const std::size_t first_cap_point = surface.points.size();
  // Where a wake leaves a blunt base's middle, the march splits the cap triangle at that
  // node that straddles the sheet's plane between the lines above and below the sheet.
  // Left to the refinement, the cap there is often two triangles, each with an edge on
  // the base, and the split one's column then has a straight corner on the base's edge
  // that folds as the layers grow. Two edges leaving the node upstream at 45 degrees
  // above and below the sheet's plane, half the base's half-height long, make the split
  // triangle stand off the base on both sides.
  std::vector<std::array<Vector3, 2>> inner_edges;
  if (blunt && options.wake.enabled) {
    const Vector3& node = surface.points[static_cast<std::size_t>(trailing_edge.back())];
    const double half_height =
        0.5 * (surface.points[static_cast<std::size_t>(wing_patch.node(ni - 1, nj - 1))] -
               surface.points[static_cast<std::size_t>(wing_patch.node(0, nj - 1))])
                  .norm();
    const double reach = 0.5 * half_height * std::sqrt(0.5);
    const Vector3 above = node + Vector3(-reach, 0.0, reach), below = node + Vector3(-reach, 0.0, -reach);
    inner_edges = {{node, above}, {node, below}, {above, below}};
  }
  tip.triangles = triangulate_planar_cap(surface.points, tip_outline, options.tip, true, inner_edges);
  if (options.tip.rounded) round_cap(surface.points, tip_outline, first_cap_point, true);
  surface.unstructured.push_back(std::move(tip));
}

}  // namespace

SurfaceMesh generate_wing_surface(const WingDefinition& wing_input, const SurfaceOptions& options) {
  validate_wing(wing_input);
  WingDefinition wing = wing_input;
  const bool blunt = close_or_keep_trailing_edges(wing);
  check_options(options, blunt);

  SurfaceMesh surface;
  surface.symmetry_y = 0.0;
  surface.symmetry_tolerance = 1e-9 * wing.stations.front().chord;
  std::vector<SpanStation> frames;
  const StructuredPatch wing_patch = place_wing_patch(wing, options, blunt, surface, frames);
  const WingEdges edges = add_wall_patches(wing_patch, options, blunt, surface);
  if (options.wake.enabled) add_wake(wing, options, edges.trailing_edge, frames, surface);
  add_tip_cap(wing_patch, options, blunt, edges, surface);
  return surface;
}

}  // namespace mixmesh
