#include "mixmesh/interface/interface_split.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "cap_clearance.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

namespace mixmesh {

namespace {

using FaceKey = std::array<Index, 4>;

// Checks the outer-layer listing against the mesh before anything is built, so a bad
// listing fails with the offending cell named rather than with a broken mesh.
FaceConnectivity validate(const MixedMesh& mesh, const OuterLayer& layer) {
  FaceConnectivity connectivity = match_faces(mesh);
  std::set<std::array<std::size_t, 3>> boundary;
  for (const CellFace& face : connectivity.boundary)
    boundary.insert({static_cast<std::size_t>(index(face.type)), static_cast<std::size_t>(face.cell),
                     static_cast<std::size_t>(face.local_face)});

  auto check = [&](CellType type, const std::vector<OuterCell>& cells) {
    const std::size_t count = mesh.cell_count(type);
    std::set<std::pair<std::size_t, int>> seen;
    for (const OuterCell& outer : cells) {
      const std::string cell_name = std::string(name(type)) + " " + std::to_string(outer.cell);
      if (outer.cell >= count)
        throw Error("interface: outer " + cell_name + " does not exist (the mesh has " +
                    std::to_string(count) + " " + std::string(name(type)) + "s)");
      const CellDescriptor& cell = descriptor(type);
      if (outer.outer_face < 0 || outer.outer_face >= cell.face_count)
        throw Error("interface: outer face " + std::to_string(outer.outer_face) + " of " + cell_name +
                    " is not a face number (0.." + std::to_string(cell.face_count - 1) + ")");
      if (!seen.emplace(outer.cell, outer.outer_face).second)
        throw Error("interface: face " + std::to_string(outer.outer_face) + " of " + cell_name +
                    " is listed twice in the outer layer");
      if (!boundary.count({static_cast<std::size_t>(index(type)), outer.cell,
                           static_cast<std::size_t>(outer.outer_face)}))
        throw Error("interface: outer face " + std::to_string(outer.outer_face) + " of " + cell_name +
                    " is shared with another cell, so it cannot face the far field");
    }
  };
  check(CellType::hexahedron, layer.hexahedra);
  check(CellType::prism, layer.prisms);
  return connectivity;
}

// Position (0 or 1) of the first node of the chosen diagonal q[s]–q[s+2].
int diagonal_start(const std::vector<Vector3>& points, const Index* quad, HullDiagonal rule) {
  const int smallest_position = static_cast<int>(std::min_element(quad, quad + 4) - quad) % 2;
  if (rule == HullDiagonal::smallest_node) return smallest_position;
  auto at = [&](int corner) -> const Vector3& { return points[static_cast<std::size_t>(quad[corner])]; };
  const double first = (at(2) - at(0)).squaredNorm();
  const double second = (at(3) - at(1)).squaredNorm();
  // Equal lengths up to rounding (a rectangle) fall back to the node rule so the
  // choice never depends on the last bit of a coordinate.
  if (std::abs(first - second) <= 1e-12 * std::max(first, second)) return smallest_position;
  return first < second ? 0 : 1;
}

}  // namespace

namespace {

// The pieces a split about `apex` makes: pyramids on the quads that stay, two
// tetrahedra on every outer quad (along its chosen diagonal), one on every triangle.
// Faces in `skipped_faces` (inside a stack, see Level) get none.
// visit(CellType, nodes, is_hull_triangle) with the apex as node index `apex_index`.
// Bit f of `flipped` cuts outer quad f along the other diagonal than the rule's.
template <typename Visit>
void for_each_piece(CellType type, const std::vector<Vector3>& points, const Index* nodes,
                    unsigned outer_faces, unsigned skipped_faces, unsigned flipped,
                    const InterfaceOptions& options, Index apex_index, Visit visit) {
  const CellDescriptor& shape = descriptor(type);
  for (int face = 0; face < shape.face_count; ++face) {
    if ((skipped_faces >> face) & 1u) continue;
    const LocalFace& local = shape.faces[static_cast<std::size_t>(face)];
    Index corners[4] = {-1, -1, -1, -1};  // outward from the cell
    for (int corner = 0; corner < local.node_count; ++corner)
      corners[corner] = nodes[local.nodes[static_cast<std::size_t>(corner)]];
    const bool outer = (outer_faces >> face) & 1u;
    // Tetrahedron face 0-2-1 is outward, so (a, c, b, apex) keeps a-b-c outward.
    auto tetrahedron = [&](Index a, Index b, Index c) {
      const Index piece[4] = {a, c, b, apex_index};
      visit(CellType::tetrahedron, piece, outer);
    };
    if (local.node_count == 3) {
      tetrahedron(corners[0], corners[1], corners[2]);
    } else if (!outer) {
      // The pyramid base 0-1-2-3 turns counter-clockwise seen from the apex, i.e.
      // opposite to the cell's outward winding.
      const Index piece[5] = {corners[0], corners[3], corners[2], corners[1], apex_index};
      visit(CellType::pyramid, piece, false);
    } else {
      const int start =
          diagonal_start(points, corners, options.diagonal) ^ static_cast<int>((flipped >> face) & 1u);
      tetrahedron(corners[start], corners[start + 1], corners[start + 2]);
      tetrahedron(corners[start], corners[start + 2], corners[(start + 3) % 4]);
    }
  }
}

// One cell of what is split about one point: the outer cell alone, or a stack of it and
// the cells under it in its column (the faces between them skipped). Only the first
// level has outer faces.
struct Level {
  const Index* nodes = nullptr;
  unsigned outer_faces = 0u;
  unsigned skipped_faces = 0u;
};

template <typename Visit>
void for_each_stack_piece(CellType type, const std::vector<Vector3>& points, const std::vector<Level>& levels,
                          unsigned flipped, const InterfaceOptions& options, Index apex_index, Visit visit) {
  for (const Level& level : levels)
    for_each_piece(type, points, level.nodes, level.outer_faces, level.skipped_faces, flipped, options,
                   apex_index, visit);
}

// The quality of a split about the last point of `points`: the worst piece's smallest
// corner Jacobian (scaled; negative when a piece is inverted or tangled), the same of its
// pyramids alone, and the largest dihedral angle of its tetrahedra.
struct PieceQuality {
  double worst = 1.0;
  double worst_pyramid = 1.0;
  double largest_dihedral = 0.0;
};

PieceQuality piece_quality(CellType type, const std::vector<Vector3>& points,
                           const std::vector<Level>& levels, unsigned flipped,
                           const InterfaceOptions& options) {
  PieceQuality quality;
  const Index apex = static_cast<Index>(points.size() - 1);
  for_each_stack_piece(
      type, points, levels, flipped, options, apex, [&](CellType piece, const Index* corners, bool) {
        const CellShape shape = cell_shape(piece, points, corners);
        const double corner = shape.valid() ? shape.min_corner_jacobian : -1.0 - shape.negative_corners;
        quality.worst = std::min(quality.worst, corner);
        if (piece == CellType::pyramid) quality.worst_pyramid = std::min(quality.worst_pyramid, corner);
        if (piece == CellType::tetrahedron) {
          auto at = [&](int k) -> const Vector3& { return points[static_cast<std::size_t>(corners[k])]; };
          quality.largest_dihedral =
              std::max(quality.largest_dihedral, largest_dihedral_degrees(at(0), at(1), at(2), at(3)));
        }
      });
  return quality;
}

// How far a split misses the stack bounds: its tetrahedra's degrees above
// options.stack_dihedral per 10 degrees and the halvings its pyramids stand below
// options.stack_pyramid_quality (one unit each is a floor of the robustness suite: 170
// degrees for the share of flat tetrahedra, a scaled Jacobian of 1e-3 for the default
// bound 2e-3); both not positive when it meets the bounds. Infinite when a piece is
// inverted.
struct Shortfall {
  double angle = 0.0;
  double pyramid = 0.0;
  double worst() const { return std::max(angle, pyramid); }
  double sum() const { return std::max(angle, 0.0) + std::max(pyramid, 0.0); }
  bool met() const { return worst() <= 0.0; }
};

Shortfall shortfall(const PieceQuality& quality, const InterfaceOptions& options) {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  if (quality.worst <= 0.0) return {infinity, infinity};
  return {(quality.largest_dihedral - options.stack_dihedral) / 10.0,
          std::log2(options.stack_pyramid_quality / quality.worst_pyramid)};
}

// Whether a split misses the bounds by less than another: by the larger shortfall, and
// where those are alike (a hundredth of a unit) by the sum of both. The tie matters where
// a pyramid no stack can mend sets the larger (the side quads of a stack over a base
// face much narrower than long, docs/interface.md): the tetrahedra still choose.
bool misses_less(const Shortfall& candidate, const Shortfall& best) {
  constexpr double alike = 0.01;
  if (candidate.worst() < best.worst() - alike) return true;
  if (candidate.worst() > best.worst() + alike) return false;
  return candidate.sum() < best.sum() - alike;
}

// The middle of a stack: the mean of the nodes of its top and of its inner face (the
// nodes in one level only).
Vector3 stack_middle(CellType type, const std::vector<Vector3>& points, const std::vector<Level>& levels) {
  std::map<Index, int> uses;
  for (const Level& level : levels)
    for (int corner = 0; corner < node_count(type); ++corner) ++uses[level.nodes[corner]];
  Vector3 sum = Vector3::Zero();
  int count = 0;
  for (const auto& [node, times] : uses)
    if (times == 1) sum += points[static_cast<std::size_t>(node)], ++count;
  return sum / static_cast<double>(count);
}

// The split point: the centre (Wild Fig. 2; of a stack, the mean of its cells' centres)
// unless a piece about it is inverted or nearly so (a thin cell with a warped face), then
// the best point a compass search around the centre finds. The last point of `points`
// is the scratch slot for the candidate. Returns the quality about that point in `best`.
//
// The mean of a stack's centres sits low in it (a fifth of the way up 16 layers growing
// by 1.2), which keeps the tetrahedra on its top steep but leaves the pyramid on its
// inner quad flat under a long cell (a scaled Jacobian of about twice the apex's height
// over the quad's length). Where that pyramid misses options.stack_pyramid_quality, the
// point slides up towards the stack's middle, in quarters of the way there, to the first
// that meets both bounds, else to the one that misses them least. It may go on past the
// middle, as far again: a stack over a blunt base is thinner than a thousandth of its
// spanwise cells, and only there is the inner pyramid steep enough while the tetrahedra
// on the top stay within the bound.
Vector3 split_point(CellType type, std::vector<Vector3>& points, const std::vector<Level>& levels,
                    unsigned flipped, const InterfaceOptions& options, PieceQuality& best) {
  Vector3 centre = Vector3::Zero();
  for (const Level& level : levels) centre += cell_centre(type, points, level.nodes);
  centre /= static_cast<double>(levels.size());
  points.back() = centre;
  best = piece_quality(type, points, levels, flipped, options);
  if (levels.size() > 1 && best.worst > 0.0 && best.worst_pyramid < options.stack_pyramid_quality) {
    const Vector3 low = centre;
    const Vector3 middle = stack_middle(type, points, levels);
    Shortfall missing = shortfall(best, options);
    for (int quarter = 1; quarter <= 8 && !missing.met(); ++quarter) {
      points.back() = low + 0.25 * quarter * (middle - low);
      const PieceQuality quality = piece_quality(type, points, levels, flipped, options);
      const Shortfall here = shortfall(quality, options);
      if (misses_less(here, missing)) best = quality, missing = here, centre = points.back();
    }
  }
  double step = 0.0;
  for (const Level& level : levels)
    for (int corner = 0; corner < node_count(type); ++corner)
      step = std::max(step, (points[static_cast<std::size_t>(level.nodes[corner])] - centre).norm());
  step *= 0.25;
  const Vector3 directions[6] = {Vector3::UnitX(),  -Vector3::UnitX(), Vector3::UnitY(),
                                 -Vector3::UnitY(), Vector3::UnitZ(),  -Vector3::UnitZ()};
  Vector3 best_point = centre;
  for (int iteration = 0; iteration < 60 && best.worst < options.centre_quality; ++iteration) {
    bool improved = false;
    for (const Vector3& direction : directions) {
      points.back() = best_point + step * direction;
      const PieceQuality quality = piece_quality(type, points, levels, flipped, options);
      if (quality.worst > best.worst) {
        best = quality;
        best_point = points.back();
        improved = true;
      }
    }
    if (!improved) step *= 0.5;
  }
  return best_point;
}

// Where and how a cell is split: the split point, the outer quads cut along the other
// diagonal than the rule's (bits as in for_each_piece), the quality of its pieces (worst
// not positive: no split makes every piece valid), and the cells split about the point
// (the outer cell, then any under it in a stack).
struct SplitChoice {
  Vector3 point = Vector3::Zero();
  unsigned flipped = 0u;
  PieceQuality quality{0.0, 0.0, 180.0};
  std::vector<std::size_t> cells;
  std::vector<unsigned> skipped_faces;  // per cell: the faces inside the stack
};

// The split of one cell or stack (`levels`, in mesh numbering). The search works on a
// copy of the stack's nodes alone, numbered in the order of their numbers in the mesh
// (the diagonal rule compares node numbers), with the candidate point after them, so
// that cells can be searched side by side.
SplitChoice choose_split(CellType type, const std::vector<Vector3>& mesh_points,
                         const std::vector<Level>& mesh_levels, const InterfaceOptions& options) {
  const int count = node_count(type);
  std::vector<Index> used;
  for (const Level& level : mesh_levels) used.insert(used.end(), level.nodes, level.nodes + count);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::vector<Vector3> points(used.size() + 1);
  for (std::size_t rank = 0; rank < used.size(); ++rank)
    points[rank] = mesh_points[static_cast<std::size_t>(used[rank])];
  std::vector<std::array<Index, 8>> nodes(mesh_levels.size());
  std::vector<Level> levels = mesh_levels;
  for (std::size_t level = 0; level < levels.size(); ++level) {
    for (int corner = 0; corner < count; ++corner)
      nodes[level][static_cast<std::size_t>(corner)] = static_cast<Index>(
          std::lower_bound(used.begin(), used.end(), mesh_levels[level].nodes[corner]) - used.begin());
    levels[level].nodes = nodes[level].data();
  }
  // The rule's diagonals first; where no split point makes every piece valid (an outer
  // quad twisted by more than the cell is thick, as at a wing tip's trailing edge), the
  // other diagonal of some outer quads: one of the two folds of a twisted quad leans
  // towards the cell's inside. Both triangles stay in this cell, so the hull conforms.
  const unsigned outer_faces = levels.front().outer_faces;
  std::vector<unsigned> outer_quads;
  for (int face = 0; face < descriptor(type).face_count; ++face)
    if (((outer_faces >> face) & 1u) &&
        descriptor(type).faces[static_cast<std::size_t>(face)].node_count == 4)
      outer_quads.push_back(1u << face);
  SplitChoice choice;
  choice.point = split_point(type, points, levels, choice.flipped, options, choice.quality);
  const unsigned combinations = 1u << std::min<std::size_t>(outer_quads.size(), 4);
  for (unsigned combination = 1; combination < combinations && choice.quality.worst <= 0.0; ++combination) {
    unsigned candidate = 0u;
    for (std::size_t quad = 0; quad < outer_quads.size() && quad < 4; ++quad)
      if ((combination >> quad) & 1u) candidate |= outer_quads[quad];
    PieceQuality candidate_quality;
    const Vector3 candidate_point = split_point(type, points, levels, candidate, options, candidate_quality);
    if (candidate_quality.worst > choice.quality.worst)
      choice = {candidate_point, candidate, candidate_quality, {}, {}};
  }
  return choice;
}

// The face of a cell opposite `face` (sharing no node with it), or -1.
int opposite_face(CellType type, int face) {
  const CellDescriptor& shape = descriptor(type);
  const LocalFace& given = shape.faces[static_cast<std::size_t>(face)];
  for (int other = 0; other < shape.face_count; ++other) {
    const LocalFace& candidate = shape.faces[static_cast<std::size_t>(other)];
    bool shared = false;
    for (int a = 0; a < given.node_count; ++a)
      for (int b = 0; b < candidate.node_count; ++b)
        shared = shared ||
                 given.nodes[static_cast<std::size_t>(a)] == candidate.nodes[static_cast<std::size_t>(b)];
    if (!shared) return other;
  }
  return -1;
}

// The cell of the same type across each face of each cell of `type`: (cell, its local
// face), or (-1, -1).
using FaceNeighbours = std::vector<std::pair<Index, int>>;

FaceNeighbours same_type_neighbours(const MixedMesh& mesh, CellType type,
                                    const FaceConnectivity& connectivity) {
  const int faces = descriptor(type).face_count;
  FaceNeighbours neighbours(mesh.cell_count(type) * static_cast<std::size_t>(faces), {-1, -1});
  for (const auto& pair : connectivity.interior) {
    if (pair[0].type != type || pair[1].type != type) continue;
    for (int side = 0; side < 2; ++side) {
      const CellFace& here = pair[static_cast<std::size_t>(side)];
      const CellFace& there = pair[static_cast<std::size_t>(1 - side)];
      neighbours[static_cast<std::size_t>(here.cell) * static_cast<std::size_t>(faces) +
                 static_cast<std::size_t>(here.local_face)] = {there.cell, there.local_face};
    }
  }
  return neighbours;
}

// The split of an outer cell. An outer hexahedron (or prism) whose split about its
// centre leaves a tetrahedron with a dihedral angle above options.stack_dihedral (a layer
// cell much thinner than wide: the outer quad's two tetrahedra have their apex half the
// cell's height under the quad's diagonal, so their angle at the apex edge opposite it is
// 180 degrees less about twice atan(h / w)), or a pyramid flatter than
// options.stack_pyramid_quality (the pyramid on the inner quad of a cell h high and L
// long has a scaled Jacobian of about h / L), is split together with the hexahedra under
// it, as one stack about its middle: the lowest stack that meets both bounds, else the
// best one. The stack's side quads keep their pyramids, so neighbouring columns conform
// whatever their own stack; a side quad that faces the far field (a column above a
// neighbour whose growth stopped) gets its two tetrahedra as in a single cell. The top
// is the largest outer quad; capped cells never join a stack.
SplitChoice choose_stack(const MixedMesh& mesh, CellType type, std::size_t cell,
                         const std::vector<unsigned>& outer_faces, const std::vector<char>& capped,
                         const FaceNeighbours& neighbours, const InterfaceOptions& options) {
  std::vector<Level> levels{{mesh.cell(type, cell), outer_faces[cell], 0u}};
  SplitChoice best = choose_split(type, mesh.points, levels, options);
  best.cells = {cell};
  best.skipped_faces = {0u};
  Shortfall best_shortfall = shortfall(best.quality, options);
  if (best.quality.worst <= 0.0 || best_shortfall.met()) return best;
  const CellDescriptor& shape = descriptor(type);
  int top = -1;
  double top_area = 0.0;
  for (int face = 0; face < shape.face_count; ++face) {
    if (!((outer_faces[cell] >> face) & 1u)) continue;
    Index corners[4];
    const int count = face_nodes(mesh, {type, static_cast<Index>(cell), face}, corners);
    const double area = face_area_vector(mesh.points, corners, count).norm();
    if (area > top_area) top = face, top_area = area;
  }
  std::vector<std::size_t> cells{cell};
  int down = opposite_face(type, top);
  PieceQuality previous = best.quality;
  while (static_cast<int>(cells.size()) < options.stack_cells && down >= 0 &&
         !((levels.back().outer_faces >> down) & 1u)) {
    const auto [below, up] = neighbours[cells.back() * static_cast<std::size_t>(shape.face_count) +
                                        static_cast<std::size_t>(down)];
    if (below < 0 || capped[static_cast<std::size_t>(below)]) break;
    const unsigned below_outer = outer_faces[static_cast<std::size_t>(below)];
    if ((below_outer >> up) & 1u) break;
    levels.back().skipped_faces |= 1u << down;
    levels.push_back({mesh.cell(type, static_cast<std::size_t>(below)), below_outer, 1u << up});
    cells.push_back(static_cast<std::size_t>(below));
    SplitChoice candidate = choose_split(type, mesh.points, levels, options);
    const Shortfall candidate_shortfall = shortfall(candidate.quality, options);
    if (misses_less(candidate_shortfall, best_shortfall)) {
      best = candidate;
      best_shortfall = candidate_shortfall;
      best.cells = cells;
      for (const Level& level : levels) best.skipped_faces.push_back(level.skipped_faces);
    }
    if (best_shortfall.met()) break;
    // The angle falls as the stack grows until it is about as high as wide, and the
    // pyramid on its inner quad stands up as the stack grows until it is about as high
    // as long; past both, a higher stack only loses.
    // (An inverted candidate neither ends the growth nor becomes the reference.)
    const PieceQuality& here = candidate.quality;
    if (here.worst <= 0.0) {
      down = opposite_face(type, up);
      continue;
    }
    const bool angle_falls = here.largest_dihedral < previous.largest_dihedral;
    const bool pyramid_rises = here.worst_pyramid > 1.01 * previous.worst_pyramid &&
                               previous.worst_pyramid < options.stack_pyramid_quality;
    if (!angle_falls && !pyramid_rises) break;
    previous = here;
    down = opposite_face(type, up);
  }
  return best;
}

// Splits one cell or stack about its chosen point: a pyramid on every quad face that
// stays, two tetrahedra on every outer quad, one tetrahedron on every triangle face.
// Outer faces join the hull.
void split_cell(const MixedMesh& mesh, CellType type, const std::vector<unsigned>& outer_faces,
                const InterfaceOptions& options, const SplitChoice& choice, InterfaceResult& result) {
  MixedMesh& out = result.mesh;
  const Vector3& point = choice.point;
  const Index centre = static_cast<Index>(out.points.size());
  out.points.push_back(point);
  result.centres.push_back(centre);
  const std::size_t cell = choice.cells.front();
  for (std::size_t level = 0; level < choice.cells.size(); ++level) {
    const std::size_t here = choice.cells[level];
    const unsigned skipped = choice.skipped_faces.empty() ? 0u : choice.skipped_faces[level];
    const int region = mesh.block(type).regions[here];
    for_each_piece(type, out.points, mesh.cell(type, here), outer_faces[here], skipped, choice.flipped,
                   options, centre, [&](CellType piece, const Index* corners, bool outer) {
                     if (!cell_shape(piece, out.points, corners).valid())
                       throw Error("interface: splitting " + std::string(name(type)) + " " +
                                   std::to_string(cell) + " near " + point_text(point) +
                                   " gives an inverted " + std::string(name(piece)));
                     out.add_cell(piece, corners, region);
                     if (piece == CellType::pyramid) {
                       ++result.pyramids;
                       return;
                     }
                     ++result.tetrahedra;
                     // The tetrahedron (a, c, b, apex) of an outer triangle a-b-c.
                     if (outer) result.hull.push_back({corners[0], corners[2], corners[1]});
                   });
  }
  if (choice.cells.size() > 1) {
    ++result.stacks;
    result.stacked_cells += choice.cells.size();
  }
}

// Which outer cells are capped rather than split (InterfaceOptions::capped_marker).
struct CapRules {
  std::set<FaceKey> capped_quads;  // the boundary quads tagged capped_marker
  // Edges used by one outer face: the footprint on the symmetry plane. A marked
  // hexahedron with its outer quad there gets a cap leaning on the plane (its apex in
  // the plane over the footprint edge, cap_cell): a cap's apex over the quad's middle
  // stood half the quad's width from the plane, and the tetrahedra between it and the
  // plane's triangles were flat (175-176 deg along the ONERA M6 wake's root).
  std::map<std::pair<Index, Index>, int> outer_edge_uses;
  // Per footprint edge, the marker and the outward area vector of the boundary quad of
  // the layers that holds it in the plane (the symmetry plane's quad of the outer cell).
  std::map<std::pair<Index, Index>, std::pair<int, Vector3>> plane_quads;
  // Nodes of the other outer faces: a hexahedron touching them is split as usual, so
  // caps stay away from where the marked hull meets the rest (a wake's trailing edge,
  // the tip trailing edge), whose faces meet at angles a cap could cross (a twisted tip).
  // Prisms are capped regardless: the one marked prism of the march, the first cell
  // between the two sheet lines at a junction, has no split point off its edges.
  std::vector<char> plain_hull_node;

  bool on_footprint(const Index* corners, int count) const {
    for (int k = 0; k < count; ++k) {
      const auto uses = outer_edge_uses.find(std::minmax(corners[k], corners[(k + 1) % count]));
      if (uses != outer_edge_uses.end() && uses->second == 1) return true;
    }
    return false;
  }
  // The one edge k (corners k, k + 1) of an outer quad on the footprint with a plane
  // quad under it, or -1 when there is none or more than one.
  int plane_edge(const Index* corners) const {
    int found = -1;
    for (int k = 0; k < 4; ++k) {
      const auto edge = std::minmax(corners[k], corners[(k + 1) % 4]);
      const auto uses = outer_edge_uses.find(edge);
      if (uses == outer_edge_uses.end() || uses->second != 1) continue;
      if (found >= 0 || !plane_quads.count(edge)) return -1;
      found = k;
    }
    return found;
  }
};

CapRules cap_rules(const MixedMesh& mesh, const OuterLayer& layer, const InterfaceOptions& options) {
  CapRules rules;
  const int capped_marker = options.capped_marker.empty() ? -1 : mesh.find_marker(options.capped_marker);
  if (capped_marker >= 0)
    for (std::size_t face = 0; face < mesh.face_count(FaceType::quad); ++face)
      if (mesh.faces(FaceType::quad).markers[face] == capped_marker)
        rules.capped_quads.insert(sorted_face_key(mesh.face(FaceType::quad, face), 4));
  rules.plain_hull_node.assign(mesh.points.size(), 0);
  std::set<FaceKey> outer_faces;
  for (const auto& [type, cells] :
       {std::pair{CellType::hexahedron, &layer.hexahedra}, std::pair{CellType::prism, &layer.prisms}})
    for (const OuterCell& outer : *cells) {
      Index corners[4] = {-1, -1, -1, -1};
      const int count = face_nodes(mesh, {type, static_cast<Index>(outer.cell), outer.outer_face}, corners);
      outer_faces.insert(sorted_face_key(corners, count));
      for (int k = 0; k < count; ++k)
        ++rules.outer_edge_uses[std::minmax(corners[k], corners[(k + 1) % count])];
      if (count == 4 && rules.capped_quads.count(sorted_face_key(corners, 4))) continue;
      for (int corner = 0; corner < count; ++corner)
        rules.plain_hull_node[static_cast<std::size_t>(corners[corner])] = 1;
    }
  // The plane quads: the symmetry plane's quads with a footprint edge.
  const int symmetry_marker = options.symmetry_marker.empty() ? -1 : mesh.find_marker(options.symmetry_marker);
  if (symmetry_marker < 0) return rules;
  for (std::size_t face = 0; face < mesh.face_count(FaceType::quad); ++face) {
    const Index* nodes = mesh.face(FaceType::quad, face);
    const int marker = mesh.faces(FaceType::quad).markers[face];
    if (marker != symmetry_marker || outer_faces.count(sorted_face_key(nodes, 4))) continue;
    for (int k = 0; k < 4; ++k) {
      const auto edge = std::minmax(nodes[k], nodes[(k + 1) % 4]);
      const auto uses = rules.outer_edge_uses.find(edge);
      if (uses != rules.outer_edge_uses.end() && uses->second == 1)
        rules.plane_quads.emplace(edge, std::pair{marker, face_area_vector(mesh.points, nodes, 4)});
    }
  }
  return rules;
}

constexpr double minimum_cap_reach = 0.4;

// Stands the apex of cap `pyramid` (its last node, the last of `points`) `height` from
// `base` along `direction` and raises it, doubling, while the cap is inverted and the
// next height stays within `limit` (a twisted quad's corner normals lean away from its
// mean normal). Says whether the cap is valid. (A quad with an edge of zero length gets
// no cap: its height would stay zero.)
bool raise_cap_apex(std::vector<Vector3>& points, const Index* pyramid, const Vector3& base,
                    const Vector3& direction, double height, double limit) {
  points.back() = base + height * direction;
  for (; height > 0.0 && !cell_shape(CellType::pyramid, points, pyramid).valid() && 2.0 * height <= limit;) {
    height *= 2.0;
    points.back() = base + height * direction;
  }
  return cell_shape(CellType::pyramid, points, pyramid).valid();
}

// What a cap on a quad (corners outward from its cell) stands on: the quad's middle,
// its unit normal, its shortest and longest edge and its longer diagonal.
struct CapBase {
  Vector3 middle = Vector3::Zero();
  Vector3 normal = Vector3::Zero();
  double shortest = std::numeric_limits<double>::infinity();
  double longest = 0.0;
  double diagonal = 0.0;
};

CapBase cap_base(const std::vector<Vector3>& points, const Index* corners) {
  CapBase base;
  auto at = [&](int corner) -> const Vector3& { return points[static_cast<std::size_t>(corners[corner])]; };
  for (int corner = 0; corner < 4; ++corner) {
    base.middle += 0.25 * at(corner);
    const double edge = (at((corner + 1) % 4) - at(corner)).norm();
    base.shortest = std::min(base.shortest, edge);
    base.longest = std::max(base.longest, edge);
  }
  base.normal = face_area_vector(points, corners, 4).normalized();
  base.diagonal = std::max((at(2) - at(0)).norm(), (at(3) - at(1)).norm());
  return base;
}

// The worst scaled corner Jacobian of the caps an unsplittable cell would get (cap_cell
// with split_tried: apex cap_height times the shortest edge over each outer quad's
// middle, raised while inverted), or -1 when one of them cannot be made valid.
double unsplittable_cap_quality(CellType type, const std::vector<Vector3>& mesh_points, const Index* nodes,
                                unsigned outer_faces, const InterfaceOptions& options) {
  const CellDescriptor& shape = descriptor(type);
  double worst = 1.0;
  for (int face = 0; face < shape.face_count; ++face) {
    const LocalFace& local = shape.faces[static_cast<std::size_t>(face)];
    if (!((outer_faces >> face) & 1u) || local.node_count != 4) continue;
    std::vector<Vector3> points(5, Vector3::Zero());  // the quad's corners and the apex
    for (int corner = 0; corner < 4; ++corner)
      points[static_cast<std::size_t>(corner)] =
          mesh_points[static_cast<std::size_t>(nodes[local.nodes[static_cast<std::size_t>(corner)]])];
    const Index pyramid[5] = {0, 1, 2, 3, 4};
    const CapBase base = cap_base(points, pyramid);
    if (!raise_cap_apex(points, pyramid, base.middle, base.normal, options.cap_height * base.shortest,
                        options.cap_height_limit * base.diagonal))
      return -1.0;
    worst = std::min(worst, cell_shape(CellType::pyramid, points, pyramid).min_corner_jacobian);
  }
  return worst;
}

// Keeps the cell and caps every outer quad with a pyramid outside it, apex above the
// quad's centre at cap_height × its shortest edge (for a marked cell at least
// minimum_cap_reach × its longest); the caps' sides join the hull.
// A marked quad with an edge on the footprint (rules given) leans its cap on the plane:
// the apex stands in the plane over that edge's middle, and the cap's face over the edge
// lies in the plane and takes the plane quad's marker instead of joining the hull.
void cap_cell(CellType type, std::size_t cell, const Index* nodes, unsigned outer_faces, int region,
              const InterfaceOptions& options, double cap_height, bool split_tried, InterfaceResult& result,
              std::vector<interface_detail::TallCap>* tall_caps = nullptr, const CapRules* rules = nullptr) {
  MixedMesh& out = result.mesh;
  const CellDescriptor& shape = descriptor(type);
  for (int face = 0; face < shape.face_count; ++face) {
    if (!((outer_faces >> face) & 1u)) continue;
    const LocalFace& local = shape.faces[static_cast<std::size_t>(face)];
    Index corners[4] = {-1, -1, -1, -1};  // outward from the cell
    for (int corner = 0; corner < local.node_count; ++corner)
      corners[corner] = nodes[local.nodes[static_cast<std::size_t>(corner)]];
    if (local.node_count == 3) {
      result.hull.push_back({corners[0], corners[1], corners[2]});
      continue;
    }
    const CapBase base = cap_base(out.points, corners);
    const double shortest = base.shortest, longest = base.longest;
    Vector3 middle = base.middle;
    // The far field fills the valley between the caps of two neighbouring quads with a
    // tetrahedron of their shared edge and the two apexes; its dihedral angle at the
    // apexes' edge is 180 degrees less twice atan(2 h / L) for apex height h over an edge
    // of length L, and every tetrahedron on a cap face over that edge has an angle near
    // the face's apex angle, 180 degrees less twice atan(2 d / L) for an apex d from the
    // edge. On long, narrow quads (a wake's, 30:1 behind a trailing edge) a height from
    // the shortest edge alone made both slivers, so a marked cell's cap stands at least
    // a part of the longest edge high (minimum_cap_reach 0.4: 0.2 L for a cap height
    // 0.5, 136 deg). Where that crosses the hull (the concave corner behind a tip's
    // trailing edge) lower_crossing_caps brings it down, not below twice the shortest
    // edge. The caps of cells that could not be split (twisted cells at a tip's trailing
    // edge, in a concave corner of the hull) keep their low height.
    const double reach = split_tried ? shortest : std::max(shortest, minimum_cap_reach * longest);
    const double lowest_reach =
        split_tried ? shortest : std::max(shortest, std::min(minimum_cap_reach * longest, 2.0 * shortest));
    const Vector3& quad_normal = base.normal;
    Vector3 normal = quad_normal;
    const int plane_edge = rules ? rules->plane_edge(corners) : -1;
    const std::pair<int, Vector3>* plane_quad =
        plane_edge >= 0 ? &rules->plane_quads.at(std::minmax(corners[plane_edge], corners[(plane_edge + 1) % 4]))
                        : nullptr;
    // A cap over the middle of a quad next to the plane leaves a valley or a slot
    // against the plane that only low caps keep from folding, and low caps over a
    // wake's long end quads are flat (175-176 deg on random wings with the wake's
    // end rows metres long and centimetres wide). Leaning on the plane, the cap fills
    // that space and stands as tall as its neighbours: its apex goes over the middle of
    // the edge on the plane, along the quad's normal turned into the plane.
    const Index apex = static_cast<Index>(out.points.size());
    out.points.push_back(middle);
    // Seen from the apex (outside) the outward winding is counter-clockwise already.
    const Index pyramid[5] = {corners[0], corners[1], corners[2], corners[3], apex};
    // A twisted quad needs a higher apex (its corner normals lean away from the mean
    // normal): raise it, doubling, up to cap_height_limit times the quad's longest
    // diagonal, and stop at the first valid cap. Says whether the cap is valid.
    const auto stand = [&](const Vector3& foot, const Vector3& direction) {
      return raise_cap_apex(out.points, pyramid, foot, direction, cap_height * reach,
                            options.cap_height_limit * base.diagonal);
    };
    bool leans = false;
    if (plane_edge >= 0 && !split_tried) {
      const Vector3& first = out.points[static_cast<std::size_t>(corners[plane_edge])];
      const Vector3& second = out.points[static_cast<std::size_t>(corners[(plane_edge + 1) % 4])];
      const Vector3 plane_normal = plane_quad->second.normalized();
      const Vector3 along = (second - first).normalized();
      Vector3 up = quad_normal - quad_normal.dot(plane_normal) * plane_normal;
      up -= up.dot(along) * along;
      // Not where the quad leans over the plane itself, nor where no leaning cap is
      // valid (a strongly twisted quad): there the cap stands over the quad's middle.
      if (up.norm() > 0.5 && stand(0.5 * (first + second), up.normalized())) {
        leans = true;
        middle = 0.5 * (first + second);
        normal = up.normalized();
      }
    }
    if (!leans) stand(middle, normal);
    if (!cell_shape(CellType::pyramid, out.points, pyramid).valid())
      throw UnsplittableCellError(
          "interface: " + std::string(name(type)) + " " + std::to_string(cell) +
              (split_tried ? " can neither be split about its centre nor capped" : " cannot be capped") +
              " on face " + std::to_string(face) + " near " + point_text(middle),
          middle);
    out.add_cell(CellType::pyramid, pyramid, region);
    ++result.pyramids;
    const double height = (out.points.back() - middle).norm();
    if (tall_caps && cap_height * lowest_reach < height)
      tall_caps->push_back({apex,
                            middle,
                            normal,
                            normal,
                            height,
                            cap_height * lowest_reach,
                            {corners[0], corners[1], corners[2], corners[3], apex},
                            result.hull.size(),
                            leans ? 3u : 4u,
                            leans});
    for (int corner = 0; corner < 4; ++corner) {
      const Index triangle[3] = {corners[corner], corners[(corner + 1) % 4], apex};
      if (leans && corner == plane_edge)
        out.add_face(FaceType::triangle, triangle, plane_quad->first);
      else
        result.hull.push_back({triangle[0], triangle[1], triangle[2]});
    }
  }
  ++result.capped_cells;
}

// The outer cells of one type with their outer faces as bit masks, in the order of
// their first listing.
struct OuterCells {
  CellType type;
  std::vector<unsigned> outer_faces;  // per cell of the type
  std::vector<std::size_t> order;
};

OuterCells outer_cells(const MixedMesh& mesh, CellType type, const std::vector<OuterCell>& cells) {
  OuterCells outer{type, std::vector<unsigned>(mesh.cell_count(type), 0u), {}};
  for (const OuterCell& entry : cells) {
    if (outer.outer_faces[entry.cell] == 0u) outer.order.push_back(entry.cell);
    outer.outer_faces[entry.cell] |= 1u << entry.outer_face;
  }
  return outer;
}

// A cell is split when a quad faces the far field; a prism whose outer faces are
// triangles passes through and adds them to the hull as they are. Cells with an outer
// quad tagged capped_marker are capped instead, except hexahedra that touch another
// outer face or have a marked quad on the footprint that cannot lean on the plane (more
// than one footprint edge, or no plane quad under it).
void choose_treatment(const MixedMesh& mesh, const OuterCells& outer, const CapRules& rules,
                      std::vector<char>& split, std::vector<char>& capped) {
  const CellType type = outer.type;
  split.assign(outer.outer_faces.size(), 0);
  capped.assign(outer.outer_faces.size(), 0);
  for (std::size_t cell : outer.order) {
    bool quad = false, footprint = false;
    for (int face = 0; face < descriptor(type).face_count; ++face) {
      if (!((outer.outer_faces[cell] >> face) & 1u)) continue;
      Index corners[4] = {-1, -1, -1, -1};
      if (face_nodes(mesh, {type, static_cast<Index>(cell), face}, corners) != 4) continue;
      quad = true;
      const bool marked = rules.capped_quads.count(sorted_face_key(corners, 4)) > 0;
      capped[cell] = capped[cell] || marked;
      footprint = footprint || (marked && rules.on_footprint(corners, 4) && rules.plane_edge(corners) < 0);
    }
    const Index* nodes = mesh.cell(type, cell);
    auto plain = [&](Index node) { return rules.plain_hull_node[static_cast<std::size_t>(node)] != 0; };
    if (type == CellType::hexahedron && (footprint || std::any_of(nodes, nodes + node_count(type), plain)))
      capped[cell] = 0;
    split[cell] = quad && !capped[cell];
  }
}

// The split points, found side by side: each search evaluates hundreds of piece shapes
// on the thin cells of free edges, and depends on its own cell alone. Then each cell
// goes to one split: a stack that reaches a cell another split took already is split
// alone, and an outer cell a stack took is not split again (its choice is left empty).
std::vector<SplitChoice> choose_splits(const MixedMesh& mesh, const OuterCells& outer,
                                       const std::vector<char>& split, const std::vector<char>& capped,
                                       const FaceConnectivity& connectivity, const InterfaceOptions& options,
                                       std::vector<char>& stacked) {
  const CellType type = outer.type;
  const FaceNeighbours neighbours = same_type_neighbours(mesh, type, connectivity);
  std::vector<SplitChoice> choices(outer.order.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, outer.order.size(), 64),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t item = range.begin(); item != range.end(); ++item) {
                        const std::size_t cell = outer.order[item];
                        if (split[cell])
                          choices[item] =
                              choose_stack(mesh, type, cell, outer.outer_faces, capped, neighbours, options);
                      }
                    });
  stacked.assign(outer.outer_faces.size(), 0);
  for (std::size_t item = 0; item < outer.order.size(); ++item) {
    const std::size_t cell = outer.order[item];
    SplitChoice& choice = choices[item];
    if (!split[cell]) continue;
    if (stacked[cell]) {
      choice.cells.clear();
      continue;
    }
    if (std::any_of(choice.cells.begin() + 1, choice.cells.end(),
                    [&](std::size_t below) { return stacked[below] != 0; })) {
      choice =
          choose_split(type, mesh.points, {{mesh.cell(type, cell), outer.outer_faces[cell], 0u}}, options);
      choice.cells = {cell};
    }
    for (std::size_t taken : choice.cells) stacked[taken] = 1;
  }
  return choices;
}

// The edges of a cell's outer faces.
std::vector<std::pair<Index, Index>> outer_edges(CellType type, const Index* nodes, unsigned outer_faces) {
  std::vector<std::pair<Index, Index>> edges;
  const CellDescriptor& shape = descriptor(type);
  for (int face = 0; face < shape.face_count; ++face) {
    if (!((outer_faces >> face) & 1u)) continue;
    const LocalFace& local = shape.faces[static_cast<std::size_t>(face)];
    for (int corner = 0; corner < local.node_count; ++corner)
      edges.push_back(
          std::minmax(nodes[local.nodes[static_cast<std::size_t>(corner)]],
                      nodes[local.nodes[static_cast<std::size_t>((corner + 1) % local.node_count)]]));
  }
  return edges;
}

// Whether a valid split (of a cell or a stack) leaves a pyramid below
// split_pyramid_floor where capping its outer cell gives valid caps with better
// pyramids, the cells under it in the stack have no face on the hull, and no cap of
// this kind stands next to it already (`capped_edges`): the valley between two low caps
// over a long shared edge is flat.
bool caps_beat_split(CellType type, const MixedMesh& mesh, const std::vector<unsigned>& outer_faces,
                     const SplitChoice& choice, const std::set<std::pair<Index, Index>>& capped_edges,
                     const InterfaceOptions& options) {
  if (choice.quality.worst_pyramid >= options.split_pyramid_floor) return false;
  for (std::size_t level = 1; level < choice.cells.size(); ++level)
    if (outer_faces[choice.cells[level]] != 0u) return false;
  const std::size_t cell = choice.cells.front();
  for (const auto& edge : outer_edges(type, mesh.cell(type, cell), outer_faces[cell]))
    if (capped_edges.count(edge)) return false;
  return unsplittable_cap_quality(type, mesh.points, mesh.cell(type, cell), outer_faces[cell], options) >
         choice.quality.worst_pyramid;
}

// The cells of one type into the result: untouched cells as they are, then the caps of
// the marked cells, then the splits (or, for an unsplittable cell where allowed, the
// whole cell capped) and the outer faces of the cells that pass through.
void replace_outer_cells(const MixedMesh& mesh, const OuterCells& outer, const CapRules& rules,
                         const FaceConnectivity& connectivity, const InterfaceOptions& options,
                         InterfaceResult& result, std::vector<interface_detail::TallCap>& tall_caps,
                         std::set<std::pair<Index, Index>>& capped_edges) {
  const CellType type = outer.type;
  std::vector<char> split, capped, stacked;
  choose_treatment(mesh, outer, rules, split, capped);
  const std::vector<SplitChoice> choices =
      choose_splits(mesh, outer, split, capped, connectivity, options, stacked);
  const CellBlock& block = mesh.block(type);
  const std::vector<unsigned>& outer_faces = outer.outer_faces;
  for (std::size_t cell = 0; cell < outer_faces.size(); ++cell)
    if (!stacked[cell]) result.mesh.add_cell(type, mesh.cell(type, cell), block.regions[cell]);
  for (std::size_t cell : outer.order)
    if (capped[cell])
      cap_cell(type, cell, mesh.cell(type, cell), outer_faces[cell], block.regions[cell], options,
               options.marked_cap_height, false, result, &tall_caps, &rules);
  for (std::size_t item = 0; item < outer.order.size(); ++item) {
    const std::size_t cell = outer.order[item];
    if (capped[cell]) continue;
    if (split[cell]) {
      if (choices[item].cells.empty()) continue;  // in a stack split with the cell above
      // The centre split unless no split point keeps every piece valid (thin cells with
      // a warped face): then, if allowed, the cell stays whole and its outer quads are
      // capped; if not, split_cell names the inverted piece.
      // So also a cell or stack whose best split leaves a pyramid under the floor, where
      // its outer cell's caps are better (InterfaceOptions::split_pyramid_floor); a
      // stack's other cells stay whole.
      const SplitChoice& choice = choices[item];
      if ((choice.quality.worst > 0.0 &&
           !caps_beat_split(type, mesh, outer_faces, choice, capped_edges, options)) ||
          !options.cap_unsplittable_cells) {
        split_cell(mesh, type, outer_faces, options, choice, result);
      } else {
        for (std::size_t here : choice.cells)
          result.mesh.add_cell(type, mesh.cell(type, here), block.regions[here]);
        cap_cell(type, cell, mesh.cell(type, cell), outer_faces[cell], block.regions[cell], options,
                 options.cap_height, true, result);
        for (const auto& edge : outer_edges(type, mesh.cell(type, cell), outer_faces[cell]))
          capped_edges.insert(edge);
      }
      continue;
    }
    for (int face = 0; face < descriptor(type).face_count; ++face) {
      if (!((outer_faces[cell] >> face) & 1u)) continue;
      const LocalFace& local = descriptor(type).faces[static_cast<std::size_t>(face)];
      const Index* nodes = mesh.cell(type, cell);
      result.hull.push_back({nodes[local.nodes[0]], nodes[local.nodes[1]], nodes[local.nodes[2]]});
    }
  }
}

}  // namespace

InterfaceResult split_interface(const MixedMesh& mesh, const OuterLayer& layer,
                                const InterfaceOptions& options) {
  for (const auto& [option, value] : {std::pair{"cap_height", options.cap_height},
                                      std::pair{"marked_cap_height", options.marked_cap_height}})
    if (!(value > 0.0) || !std::isfinite(value))
      throw Error(std::string("interface: ") + option + " must be > 0, got " + std::to_string(value));
  for (const auto& [option, value] : {std::pair{"stack_pyramid_quality", options.stack_pyramid_quality},
                                      std::pair{"split_pyramid_floor", options.split_pyramid_floor}})
    if (!(value > 0.0 && value <= 1.0))
      throw Error(std::string("interface: ") + option + " is a scaled Jacobian in (0, 1], got " +
                  std::to_string(value));
  const FaceConnectivity connectivity = validate(mesh, layer);

  InterfaceResult result;
  MixedMesh& out = result.mesh;
  out.points = mesh.points;
  out.marker_names = mesh.marker_names;
  for (CellType type : {CellType::tetrahedron, CellType::pyramid}) out.block(type) = mesh.block(type);

  const CapRules rules = cap_rules(mesh, layer, options);
  std::vector<interface_detail::TallCap> tall_caps;
  std::set<std::pair<Index, Index>> capped_edges;  // of the cells capped for a flat split
  std::set<FaceKey> hull_faces;  // to drop the old tags of the outer faces
  for (const auto& [type, cells] :
       {std::pair{CellType::hexahedron, &layer.hexahedra}, std::pair{CellType::prism, &layer.prisms}}) {
    for (const OuterCell& entry : *cells) {
      Index corners[4] = {-1, -1, -1, -1};
      const int count = face_nodes(mesh, {type, static_cast<Index>(entry.cell), entry.outer_face}, corners);
      hull_faces.insert(sorted_face_key(corners, count));
    }
    replace_outer_cells(mesh, outer_cells(mesh, type, *cells), rules, connectivity, options, result,
                        tall_caps, capped_edges);
  }

  for (FaceType type : all_face_types) {
    const int count = node_count(type);
    for (std::size_t face = 0; face < mesh.face_count(type); ++face) {
      const Index* nodes = mesh.face(type, face);
      if (hull_faces.count(sorted_face_key(nodes, count))) continue;
      out.add_face(type, nodes, mesh.faces(type).markers[face]);
    }
  }
  std::optional<interface_detail::Plane> plane;
  if (!rules.plane_quads.empty())
    plane = interface_detail::Plane{mesh.points[static_cast<std::size_t>(rules.plane_quads.begin()->first.first)],
                                    rules.plane_quads.begin()->second.second};
  result.lowered_caps = interface_detail::lower_crossing_caps(out, result.hull, tall_caps, plane);
  const int hull_marker = out.marker(options.hull_marker);
  for (const auto& triangle : result.hull) out.add_face(FaceType::triangle, triangle.data(), hull_marker);
  return result;
}

}  // namespace mixmesh
