#include "split_choice.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "mixmesh/mesh/cell_geometry.hpp"

namespace mixmesh::interface_detail {

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

namespace {


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

}  // namespace

bool meets_bounds(const PieceQuality& quality, const InterfaceOptions& options) {
  return shortfall(quality, options).met();
}

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

namespace {

// The area of each face of a cell, in its descriptor's order.
std::vector<double> face_areas(const MixedMesh& mesh, CellType type, std::size_t cell) {
  std::vector<double> areas(static_cast<std::size_t>(descriptor(type).face_count));
  for (int face = 0; face < descriptor(type).face_count; ++face) {
    Index corners[4];
    const int count = face_nodes(mesh, {type, static_cast<Index>(cell), face}, corners);
    areas[static_cast<std::size_t>(face)] = face_area_vector(mesh.points, corners, count).norm();
  }
  return areas;
}

// The largest face among those whose bit is set in `faces` (all: ~0u), or -1.
int largest_face(const std::vector<double>& areas, unsigned faces) {
  int largest = -1;
  for (int face = 0; face < static_cast<int>(areas.size()); ++face)
    if (((faces >> face) & 1u) &&
        (largest < 0 || areas[static_cast<std::size_t>(face)] > areas[static_cast<std::size_t>(largest)]))
      largest = face;
  return largest;
}

std::optional<std::pair<int, int>> column_axis(CellType type, const std::vector<double>& areas,
                                               unsigned outer_faces) {
  if (type != CellType::hexahedron || outer_faces == 0u) return std::nullopt;
  const int largest = largest_face(areas, ~0u);
  const int across = largest >= 0 ? opposite_face(type, largest) : -1;
  if (across < 0 || ((outer_faces >> largest) & 1u) || ((outer_faces >> across) & 1u)) return std::nullopt;
  // Ends, not sides: an outermost cell taller than wide has its top beside its largest
  // face too, and is no column.
  const int largest_outer = largest_face(areas, outer_faces);
  if (areas[static_cast<std::size_t>(largest_outer)] > 0.25 * areas[static_cast<std::size_t>(largest)])
    return std::nullopt;
  return std::pair{largest, across};
}

}  // namespace

std::optional<std::pair<int, int>> column_axis(const MixedMesh& mesh, CellType type, std::size_t cell,
                                               unsigned outer_faces) {
  if (type != CellType::hexahedron || outer_faces == 0u) return std::nullopt;
  return column_axis(type, face_areas(mesh, type, cell), outer_faces);
}

SplitChoice choose_stack(const MixedMesh& mesh, CellType type, std::size_t cell,
                         const std::vector<unsigned>& outer_faces, const std::vector<char>& barred,
                         const FaceNeighbours& neighbours, const InterfaceOptions& options) {
  const std::vector<Level> alone{{mesh.cell(type, cell), outer_faces[cell], 0u}};
  SplitChoice best = choose_split(type, mesh.points, alone, options);
  best.cells = {cell};
  best.skipped_faces = {0u};
  Shortfall best_shortfall = shortfall(best.quality, options);
  if (best.quality.worst <= 0.0 || best_shortfall.met()) return best;
  const PieceQuality single = best.quality;

  // From the cell through the face `down` and on through the face opposite the one it
  // entered by, while the cells are of the type, free, and do not face the far field
  // across the face between them.
  auto grow = [&](int down, bool column) {
    std::vector<Level> levels = alone;
    std::vector<std::size_t> cells{cell};
    PieceQuality previous = single;
    while (static_cast<int>(cells.size()) < options.stack_cells && down >= 0 &&
           !((levels.back().outer_faces >> down) & 1u)) {
      const auto [below, up] =
          neighbours[cells.back() * static_cast<std::size_t>(descriptor(type).face_count) +
                     static_cast<std::size_t>(down)];
      if (below < 0) break;
      // A capped cell joins only a column's stack, and only as a cell of the column: entered
      // across its own column's axis.
      const char bar = barred[static_cast<std::size_t>(below)];
      if (bar == 2) break;
      if (bar == 1) {
        const auto axis = column_axis(mesh, type, static_cast<std::size_t>(below),
                                      outer_faces[static_cast<std::size_t>(below)]);
        if (!column || !axis || (up != axis->first && up != axis->second)) break;
      }
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
      if (best_shortfall.met()) return;
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
      if (!angle_falls && !pyramid_rises) return;
      previous = here;
      down = opposite_face(type, up);
    }
  };

  // The stack grows across the cell's thin side, where its pieces are flat: under the
  // largest outer quad (an outer layer cell's top), or both ways along a column of
  // outer cells.
  const std::vector<double> areas = face_areas(mesh, type, cell);
  if (const auto axis = column_axis(type, areas, outer_faces[cell])) {
    grow(axis->first, true);
    if (!best_shortfall.met()) grow(axis->second, true);
    return best;
  }
  grow(opposite_face(type, largest_face(areas, outer_faces[cell])), false);
  return best;
}

std::optional<SplitChoice> joined_stack(const MixedMesh& mesh, CellType type, const SplitChoice& first,
                                        const SplitChoice& second, const FaceNeighbours& neighbours,
                                        const std::vector<unsigned>& outer_faces,
                                        const InterfaceOptions& options) {
  const int faces = descriptor(type).face_count;
  if (first.cells.size() + second.cells.size() > static_cast<std::size_t>(std::max(options.stack_cells, 1)))
    return std::nullopt;
  std::vector<std::size_t> cells = first.cells;
  cells.insert(cells.end(), second.cells.begin(), second.cells.end());
  std::vector<unsigned> skipped;
  for (const SplitChoice* part : {&first, &second})
    for (std::size_t level = 0; level < part->cells.size(); ++level)
      skipped.push_back(part->skipped_faces.empty() ? 0u : part->skipped_faces[level]);
  // The faces between the two go, as between a stack's cells; none may face the far field.
  bool touching = false;
  for (std::size_t level = 0; level < first.cells.size(); ++level)
    for (int face = 0; face < faces; ++face) {
      const auto [neighbour, neighbour_face] =
          neighbours[first.cells[level] * static_cast<std::size_t>(faces) + static_cast<std::size_t>(face)];
      if (neighbour < 0) continue;
      const auto there =
          std::find(second.cells.begin(), second.cells.end(), static_cast<std::size_t>(neighbour));
      if (there == second.cells.end()) continue;
      const auto here_axis = column_axis(mesh, type, first.cells[level], outer_faces[first.cells[level]]);
      const auto there_axis = column_axis(mesh, type, static_cast<std::size_t>(neighbour),
                                          outer_faces[static_cast<std::size_t>(neighbour)]);
      if (!here_axis || !there_axis || (face != here_axis->first && face != here_axis->second) ||
          (neighbour_face != there_axis->first && neighbour_face != there_axis->second))
        return std::nullopt;
      skipped[level] |= 1u << face;
      skipped[first.cells.size() + static_cast<std::size_t>(there - second.cells.begin())] |=
          1u << neighbour_face;
      touching = true;
    }
  if (!touching) return std::nullopt;
  std::vector<Level> levels;
  for (std::size_t level = 0; level < cells.size(); ++level)
    levels.push_back({mesh.cell(type, cells[level]), outer_faces[cells[level]], skipped[level]});
  SplitChoice joined = choose_split(type, mesh.points, levels, options);
  // Better than the two apart: than the one of them that misses the bounds more.
  const Shortfall apart_first = shortfall(first.quality, options);
  const Shortfall apart_second = shortfall(second.quality, options);
  const Shortfall& apart = misses_less(apart_first, apart_second) ? apart_second : apart_first;
  if (joined.quality.worst <= 0.0 || !misses_less(shortfall(joined.quality, options), apart))
    return std::nullopt;
  joined.cells = cells;
  joined.skipped_faces = skipped;
  return joined;
}

}  // namespace mixmesh::interface_detail
