// Caps: pyramids outside an outer quad, for the cells kept whole (Wild's split is the
// rule; a sheet's marked cells and the cells no split makes valid are capped).
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "cap_clearance.hpp"
#include "mixmesh/interface/interface_split.hpp"

namespace mixmesh::interface_detail {

using FaceKey = std::array<Index, 4>;

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

CapRules cap_rules(const MixedMesh& mesh, const OuterLayer& layer, const InterfaceOptions& options);

// The worst scaled corner Jacobian of the caps an unsplittable cell would get (cap_cell
// with split_tried: apex cap_height times the shortest edge over each outer quad's
// middle, raised while inverted), or -1 when one of them cannot be made valid.
double unsplittable_cap_quality(CellType type, const std::vector<Vector3>& mesh_points, const Index* nodes,
                                unsigned outer_faces, const InterfaceOptions& options);

// Keeps the cell and caps every outer quad with a pyramid outside it, apex above the
// quad's centre at cap_height × its shortest edge (for a marked cell at least
// minimum_cap_reach × its longest); the caps' sides join the hull.
// A marked quad with an edge on the footprint (rules given) leans its cap on the plane:
// the apex stands in the plane over that edge's middle, and the cap's face over the edge
// lies in the plane and takes the plane quad's marker instead of joining the hull.
void cap_cell(CellType type, std::size_t cell, const Index* nodes, unsigned outer_faces, int region,
              const InterfaceOptions& options, double cap_height, bool split_tried, InterfaceResult& result,
              std::vector<TallCap>* tall_caps = nullptr, const CapRules* rules = nullptr);

}  // namespace mixmesh::interface_detail
