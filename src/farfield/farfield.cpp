#include "mixmesh/farfield/farfield.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include "farfield/farfield_parts.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/mesh/face_connectivity.hpp"

namespace mixmesh {

namespace {

using farfield_detail::Triangle;

std::string seconds_text(double seconds) {
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(2);
  text << seconds << " s";
  return text.str();
}

void validate(const FarFieldInput& input, const FarFieldOptions& options) {
  if (input.hull.empty()) throw Error("farfield: the hull has no triangles");
  for (std::size_t face = 0; face < input.hull.size(); ++face)
    for (Index node : input.hull[face])
      if (node < 0 || static_cast<std::size_t>(node) >= input.points.size())
        throw Error("farfield: hull triangle " + std::to_string(face) + " uses node " + std::to_string(node) +
                    ", not one of the " + std::to_string(input.points.size()) + " points");
  if (input.metric_nodes.size() != input.metrics.size())
    throw Error("farfield: " + std::to_string(input.metric_nodes.size()) + " metric nodes but " +
                std::to_string(input.metrics.size()) + " metrics");
  for (Index node : input.metric_nodes)
    if (node < 0 || static_cast<std::size_t>(node) >= input.points.size())
      throw Error("farfield: a metric is given at node " + std::to_string(node) + ", not one of the " +
                  std::to_string(input.points.size()) + " points");
  if (!(options.flip_dihedral > 90.0 && options.flip_dihedral < 180.0))
    throw Error("farfield: flip_dihedral must lie in (90, 180) degrees, not " +
                std::to_string(options.flip_dihedral));
  if (!(options.radius_in_chords > 0.0) || !(options.farfield_size_in_chords > 0.0) ||
      !(options.size_gradient > 0.0) || !(options.radius_edge_ratio > 1.0) || options.reference_chord < 0.0)
    throw Error(
        "farfield: radius, far-field size and size gradient must be positive, the radius-edge bound above 1");
  if (!(options.hull_clearance >= 0.0 && options.hull_clearance < 1.0))
    throw Error("farfield: hull_clearance must be in [0, 1), not " + std::to_string(options.hull_clearance));
  if (!(options.edge_protection >= 0.0))
    throw Error("farfield: edge_protection must not be negative, not " +
                std::to_string(options.edge_protection));
  if (!(options.first_layer_height > 0.0 && options.first_layer_height <= 1.0))
    throw Error("farfield: first_layer_height must be in (0, 1], not " +
                std::to_string(options.first_layer_height));
  if (options.sizing == FarFieldSizing::anisotropic && !(options.layer_growth > 1.0))
    throw Error("farfield: layer_growth must be above 1, not " + std::to_string(options.layer_growth));
  std::map<std::pair<Index, Index>, int> edge_use;
  for (const auto& triangle : input.hull)
    for (int corner = 0; corner < 3; ++corner) {
      const Index a = triangle[static_cast<std::size_t>(corner)],
                  b = triangle[static_cast<std::size_t>((corner + 1) % 3)];
      if (++edge_use[{std::min(a, b), std::max(a, b)}] > 2)
        throw Error("farfield: the hull edge " + std::to_string(a) + "-" + std::to_string(b) + " at " +
                    point_text(input.points[static_cast<std::size_t>(a)]) +
                    " belongs to more than two triangles");
    }
}

// The hull in TetGen's numbering: its nodes first, in order of use.
struct LocalHull {
  std::vector<Index> global_of;  // local → global for the boundary points that exist already
  std::map<Index, Index> local_of;
  std::vector<Vector3> points;  // the hull's nodes, then the boundary points the stage adds
  std::vector<Triangle> hull;
};

// Where the far-field boundary stands round the hull.
struct Placement {
  std::vector<std::array<Index, 2>> footprint;  // the hull's free edges, on the symmetry plane
  bool symmetric = false;
  Vector3 centre = Vector3::Zero();
  double radius = 0.0;
};

// The maps to TetGen's space and back (identities without preconditioning).
struct SpaceMap {
  Eigen::Matrix3d forward = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d backward = Eigen::Matrix3d::Identity();
};

// What the TetGen passes give: the tetrahedra and every one of their points in the
// original coordinates.
struct Tetrahedralisation {
  farfield_detail::TetgenOutput tetrahedra;
  std::vector<Vector3> original;
  std::vector<Vector3> volume_points;  // the isolated input points of pass 2
};

// Hull nodes first in the TetGen point list (local numbering), in order of use.
LocalHull local_hull(const FarFieldInput& input) {
  LocalHull local;
  for (const auto& triangle : input.hull)
    for (Index node : triangle)
      if (local.local_of.emplace(node, static_cast<Index>(local.global_of.size())).second)
        local.global_of.push_back(node);
  for (Index node : local.global_of) local.points.push_back(input.points[static_cast<std::size_t>(node)]);
  for (const auto& triangle : input.hull)
    local.hull.push_back(
        {local.local_of[triangle[0]], local.local_of[triangle[1]], local.local_of[triangle[2]]});
  return local;
}

// The chord (in result.chord), the footprint, and the centre and radius of the boundary.
Placement place_boundary(const LocalHull& local, const FarFieldOptions& options, const Log& log,
                         FarFieldResult& result) {
  const std::vector<Vector3>& points = local.points;
  Vector3 low = points.front(), high = points.front();
  for (const Vector3& point : points) {
    low = low.cwiseMin(point);
    high = high.cwiseMax(point);
  }
  result.chord = options.reference_chord > 0.0 ? options.reference_chord : high.x() - low.x();
  if (!(result.chord > 0.0)) throw Error("farfield: the hull has no extent in x; set a reference chord");

  Placement placement;
  // An open hull must be open along the symmetry plane only.
  placement.footprint = triangle_free_edges(local.hull);
  placement.symmetric = !placement.footprint.empty();
  for (const auto& edge : placement.footprint)
    for (Index node : edge)
      if (std::abs(points[static_cast<std::size_t>(node)].y() - options.symmetry_y) >
          options.symmetry_tolerance * result.chord)
        throw Error("farfield: the hull is open at node " +
                    std::to_string(local.global_of[static_cast<std::size_t>(node)]) + " " +
                    point_text(points[static_cast<std::size_t>(node)]) +
                    ", which is off the symmetry plane y = " + std::to_string(options.symmetry_y));
  Vector3 centre = 0.5 * (low + high);
  if (placement.symmetric) centre.y() = options.symmetry_y;
  placement.centre = centre;
  // The boundary stands radius_in_chords chords from the hull's centre, and at least
  // 2.2 times as far as the hull's farthest point: a slender, swept wing with its wake
  // (44 deg sweep, 5.8 chords of semi-span, 10 chords of wake) reaches beyond half of 20
  // chords, and a batch of ordinary wings must not stop on a default.
  double extent = 0.0;
  for (const Vector3& point : points) extent = std::max(extent, (point - centre).norm());
  double radius = options.radius_in_chords * result.chord;
  if (2.0 * extent > radius) {
    radius = 2.2 * extent;
    log.info("farfield: radius raised to " + std::to_string(radius) + " m (" +
             std::to_string(radius / result.chord) + " chords), 2.2 times the hull's extent");
  }
  placement.radius = radius;
  return placement;
}

// Size field: each hull node's mean edge length, growing linearly away from the hull.
std::vector<double> hull_sizes(const std::vector<Vector3>& points, const std::vector<Triangle>& hull) {
  std::vector<double> hull_size(points.size(), 0.0);
  std::vector<int> hull_edges(points.size(), 0);
  for (const Triangle& triangle : hull)
    for (int corner = 0; corner < 3; ++corner) {
      const Index a = triangle[static_cast<std::size_t>(corner)],
                  b = triangle[static_cast<std::size_t>((corner + 1) % 3)];
      const double length =
          (points[static_cast<std::size_t>(a)] - points[static_cast<std::size_t>(b)]).norm();
      for (Index node : {a, b}) {
        hull_size[static_cast<std::size_t>(node)] += length;
        ++hull_edges[static_cast<std::size_t>(node)];
      }
    }
  for (std::size_t node = 0; node < points.size(); ++node) hull_size[node] /= hull_edges[node];
  return hull_size;
}

farfield_detail::SizeField size_field(const std::vector<Vector3>& points,
                                      const std::vector<std::array<Index, 2>>& footprint,
                                      const std::vector<double>& hull_size, double gradient,
                                      double farfield_size) {
  farfield_detail::SizeField size{{}, {}, gradient, farfield_size};
  // Sources: every footprint node and at most ~2000 hull nodes, so evaluating the field
  // stays cheap; the growth is slow, so a sparse sample changes sizes little.
  std::vector<char> is_source(points.size(), 0);
  for (const auto& edge : footprint) is_source[static_cast<std::size_t>(edge[0])] = 1;
  const std::size_t stride = std::max<std::size_t>(1, points.size() / 2000);
  for (std::size_t node = 0; node < points.size(); node += stride) is_source[node] = 1;
  for (std::size_t node = 0; node < points.size(); ++node)
    if (is_source[node]) {
      size.sources.push_back(points[node]);
      size.sizes.push_back(hull_size[node]);
    }
  return size;
}

// The anisotropic layer points of the hull nodes that have a metric.
farfield_detail::LayerPoints anisotropic_layer_points(const FarFieldInput& input, const LocalHull& local,
                                                      const Placement& placement,
                                                      const std::vector<double>& hull_size,
                                                      const FarFieldOptions& options) {
  FarFieldInput local_input{local.points, local.hull, {}, {}, {}, {}};
  for (std::size_t entry = 0; entry < input.metric_nodes.size(); ++entry) {
    const auto found = local.local_of.find(input.metric_nodes[entry]);
    if (found == local.local_of.end()) continue;
    local_input.metric_nodes.push_back(found->second);
    local_input.metrics.push_back(input.metrics[entry]);
  }
  for (Index node : input.capped_nodes) {
    const auto found = local.local_of.find(node);
    if (found != local.local_of.end()) local_input.capped_nodes.push_back(found->second);
  }
  return farfield_detail::layer_points(local_input, placement.footprint, placement.symmetric, hull_size,
                                       options);
}

// The closed boundary with a size at every point, and the holes.
farfield_detail::TetgenInput tetgen_input(const FarFieldInput& input, const LocalHull& local,
                                          const std::vector<double>& hull_size, std::size_t hull_point_count,
                                          const farfield_detail::SizeField& size,
                                          const std::vector<Triangle>& plane,
                                          const farfield_detail::OuterBoundary& outer,
                                          const FarFieldOptions& options) {
  const std::vector<Vector3>& points = local.points;
  const std::vector<Triangle>& hull = local.hull;
  farfield_detail::TetgenInput tetgen;
  tetgen.radius_edge_ratio = options.radius_edge_ratio;
  tetgen.flip_dihedral = options.flip_dihedral;
  tetgen.points = points;
  for (std::size_t node = 0; node < points.size(); ++node)
    tetgen.sizes.push_back(node < hull_point_count ? hull_size[node] : size(points[node]));
  tetgen.triangles = hull;
  tetgen.triangles.insert(tetgen.triangles.end(), plane.begin(), plane.end());
  tetgen.triangles.insert(tetgen.triangles.end(), outer.triangles.begin(), outer.triangles.end());
  // Holes keep TetGen out of the body: the caller's points inside it, or else a
  // point just behind the largest hull triangle.
  tetgen.holes = input.holes;
  std::size_t largest = 0;
  double largest_area = -1.0;
  for (std::size_t face = 0; face < hull.size(); ++face) {
    const double area = face_area_vector(points, hull[face].data(), 3).norm();
    if (area > largest_area) largest_area = area, largest = face;
  }
  const Vector3 hole_normal = face_area_vector(points, hull[largest].data(), 3).normalized();
  Vector3 hole_centre = Vector3::Zero();
  for (Index node : hull[largest]) hole_centre += points[static_cast<std::size_t>(node)] / 3.0;
  if (tetgen.holes.empty())
    tetgen.holes.push_back(hole_centre - 1e-3 * std::sqrt(largest_area) * hole_normal);
  return tetgen;
}

// The preconditioning map of the boundary when asked (and the boundary's dumps).
SpaceMap space_map(const std::vector<Vector3>& points, const std::vector<Triangle>& triangles,
                   const FarFieldOptions& options, const Log& log) {
  SpaceMap space;
  const bool dump = !options.dump_directory.empty();
  if (dump) dump_surface(options.dump_directory / "boundary.vtk", points, triangles);
  if (options.precondition) {
    const Preconditioning map = precondition(points, triangles, options.preconditioning);
    space.forward = map.forward;
    space.backward = map.backward;
    log.detail("farfield: preconditioned with sweep " + std::to_string(map.sweep_degrees) + " degrees");
    if (dump) {
      dump_surface(options.dump_directory / "sheared.vtk", transform_points(map.shear.inverse(), points),
                   triangles);
      dump_surface(options.dump_directory / "preconditioned.vtk", transform_points(map.forward, points),
                   triangles);
    }
  }
  return space;
}

// Pass 1: the quality run (-q, -m), in the preconditioned space when asked. Without
// the map when TetGen fails in that space (`space` then the identity).
farfield_detail::TetgenOutput quality_pass(farfield_detail::TetgenInput& tetgen,
                                           const std::vector<Vector3>& points,
                                           const std::vector<Vector3>& holes, const FarFieldOptions& options,
                                           const Log& log, SpaceMap& space) {
  Stopwatch watch;
  farfield_detail::TetgenOutput tetrahedra;
  tetgen.time_limit_seconds =
      options.precondition ? options.precondition_time_limit : options.tetgen_time_limit;
  if (options.precondition) {
    try {
      tetrahedra = farfield_detail::run_tetgen(tetgen);
    } catch (const Error& error) {
      log.warning(std::string(error.what()) + " in the preconditioned space; running it without the map");
      space.forward = space.backward = Eigen::Matrix3d::Identity();
      tetgen.points = points;
      tetgen.holes = holes;
      tetgen.time_limit_seconds = options.tetgen_time_limit;
      watch = Stopwatch();
      tetrahedra = farfield_detail::run_tetgen(tetgen);
    }
  } else {
    tetrahedra = farfield_detail::run_tetgen(tetgen);
  }
  log.info("farfield: quality pass " + seconds_text(watch.seconds()) + ", " +
           std::to_string(tetrahedra.tetrahedra.size()) + " tetrahedra");
  return tetrahedra;
}

// Pass 2 (the exact pass), in the original coordinates, without -q and with every
// point as an input point (TetGen adds none on the boundary and refines nothing;
// its flips remove slivers):
// - anisotropic: the layer points plus the quality pass's points away from them
//   (refinement would split the thin layer tetrahedra again; -i under -Y would
//   reject the points that encroach a boundary triangle, where the first layers lie);
// - preconditioned, when a tetrahedron is flat or inverted once mapped back: the
//   map's rounding moves coplanar boundary points (symmetry plane, the flat ends of
//   the wake) slightly off their plane, and TetGen fills the dent with a sliver that
//   has no volume in the original coordinates. The quality pass's points away from
//   the hull are kept; the connectivity is made again where the geometry is exact.
// Returns pass 2's isolated input points, none when it does not run.
std::optional<std::vector<Vector3>> exact_pass_points(const std::vector<Vector3>& points,
                                                      std::size_t hull_point_count,
                                                      const farfield_detail::LayerPoints& layers,
                                                      const farfield_detail::SizeField& size,
                                                      const Tetrahedralisation& quality,
                                                      const FarFieldOptions& options, const Log& log) {
  const std::vector<Vector3>& original = quality.original;
  std::vector<Vector3> volume_points;
  if (options.sizing == FarFieldSizing::anisotropic) {
    const std::vector<Vector3> isotropic_points(original.begin() + static_cast<std::ptrdiff_t>(points.size()),
                                                original.end());
    std::vector<Vector3> near_layers(points.begin(),
                                     points.begin() + static_cast<std::ptrdiff_t>(hull_point_count));
    near_layers.insert(near_layers.end(), layers.volume.begin(), layers.volume.end());
    near_layers.insert(near_layers.end(), layers.plane.begin(), layers.plane.end());
    volume_points = layers.volume;
    const std::vector<Vector3> kept =
        farfield_detail::points_beyond(isotropic_points, near_layers, size, 0.7);
    volume_points.insert(volume_points.end(), kept.begin(), kept.end());
    return volume_points;
  }
  if (!options.precondition) return std::nullopt;
  Vector3 where = Vector3::Zero();
  const std::size_t flat = farfield_detail::flat_tetrahedra(
      original, quality.tetrahedra.tetrahedra,
      farfield_detail::negative_orientation(original, quality.tetrahedra.tetrahedra), &where);
  if (flat == 0) return std::nullopt;
  log.info("farfield: " + std::to_string(flat) +
           " tetrahedra flat or inverted after the map back (the first near " + point_text(where) +
           "); triangulating again in the original space");
  // As for the anisotropic pass, points closer than 0.7 × size to a hull node are
  // left out: near the hull (and its thin faces at the wake's ends) re-inserting
  // TetGen's points exactly trips its degenerate cases.
  const std::vector<Vector3> steiner(original.begin() + static_cast<std::ptrdiff_t>(points.size()),
                                     original.end());
  const std::vector<Vector3> hull_nodes(points.begin(),
                                        points.begin() + static_cast<std::ptrdiff_t>(hull_point_count));
  return farfield_detail::points_beyond(steiner, hull_nodes, size, 0.7);
}

// Pass 2 itself: replaces the quality pass's tetrahedra when TetGen succeeds.
void exact_pass(const farfield_detail::TetgenInput& tetgen, const LocalHull& local,
                const std::vector<Vector3>& holes, const FarFieldOptions& options, const Log& log,
                Tetrahedralisation& result) {
  const std::vector<Vector3>& points = local.points;
  std::vector<Vector3>& volume_points = result.volume_points;
  const std::size_t offered = volume_points.size();
  volume_points = farfield_detail::points_off_hull(volume_points, points, local.hull, options.hull_clearance);
  if (volume_points.size() < offered)
    log.info("farfield: " + std::to_string(offered - volume_points.size()) +
             " volume points left out as too close to a hull triangle");
  const Stopwatch watch;
  farfield_detail::TetgenInput exact = tetgen;
  exact.points = points;
  exact.points.insert(exact.points.end(), volume_points.begin(), volume_points.end());
  exact.holes = holes;
  exact.quality = false;
  exact.time_limit_seconds = options.tetgen_time_limit;
  // TetGen 1.5 can fail an assertion on near-degenerate input (flip41 on the points of
  // a wing whose layers stopped round a crossing); with the anisotropic sizing the
  // quality pass's tetrahedra are a sound mesh of the same boundary in the original
  // coordinates, so they are kept, isotropic, with a warning.
  try {
    farfield_detail::TetgenOutput exact_tetrahedra = farfield_detail::run_tetgen(exact);
    result.tetrahedra = std::move(exact_tetrahedra);
    result.original = result.tetrahedra.points;  // already in the original coordinates
    for (std::size_t node = 0; node < exact.points.size(); ++node) result.original[node] = exact.points[node];
    log.info("farfield: exact pass " + seconds_text(watch.seconds()) + ", " +
             std::to_string(volume_points.size()) + " input volume points, " +
             std::to_string(result.tetrahedra.tetrahedra.size()) + " tetrahedra");
  } catch (const Error& error) {
    // Only the anisotropic pass may fall back: the preconditioned one runs because
    // the quality pass's tetrahedra are flat once mapped back.
    if (options.sizing != FarFieldSizing::anisotropic) throw;
    log.warning(std::string(error.what()) + " in the exact pass; keeping the quality pass's tetrahedra");
    volume_points.clear();
  }
}

// Back to global numbering: hull nodes keep theirs; every other point a tetrahedron
// uses is appended in TetGen's order (points TetGen left unused are dropped). Returns
// the global number of every TetGen point (-1: dropped).
std::vector<Index> add_tetrahedra(const FarFieldInput& input, const std::vector<Index>& global_of,
                                  std::size_t hull_point_count, std::size_t input_count,
                                  const Tetrahedralisation& tetrahedralisation, const Log& log,
                                  FarFieldResult& result) {
  const farfield_detail::TetgenOutput& tetrahedra = tetrahedralisation.tetrahedra;
  const std::vector<Vector3>& original = tetrahedralisation.original;
  MixedMesh& mesh = result.mesh;
  mesh.points = input.points;
  std::vector<char> used(tetrahedra.points.size(), 0);
  for (const auto& local : tetrahedra.tetrahedra)
    for (Index node : local) used[static_cast<std::size_t>(node)] = 1;
  std::vector<Index> global(tetrahedra.points.size(), -1);
  for (std::size_t node = 0; node < tetrahedra.points.size(); ++node) {
    if (node < hull_point_count) {
      global[node] = global_of[node];
    } else if (used[node]) {
      global[node] = static_cast<Index>(mesh.points.size());
      mesh.points.push_back(original[node]);
      if (node >= input_count) ++result.steiner_points;
    }
  }
  // One orientation for all (TetGen's convention, turned to VTK's): a tetrahedron
  // left with non-positive volume is reported by the validation, not hidden by a swap.
  const bool turn = farfield_detail::negative_orientation(original, tetrahedra.tetrahedra);
  for (const auto& local : tetrahedra.tetrahedra) {
    Index nodes[4] = {global[static_cast<std::size_t>(local[0])], global[static_cast<std::size_t>(local[1])],
                      global[static_cast<std::size_t>(local[2])], global[static_cast<std::size_t>(local[3])]};
    if (turn) std::swap(nodes[1], nodes[2]);
    mesh.add_cell(CellType::tetrahedron, nodes);
  }
  Vector3 where = Vector3::Zero();
  result.flat_tetrahedra = farfield_detail::flat_tetrahedra(original, tetrahedra.tetrahedra, turn, &where);
  if (result.flat_tetrahedra > 0)
    log.warning("farfield: " + std::to_string(result.flat_tetrahedra) +
                " tetrahedra have no positive volume, the first near " + point_text(where));
  return global;
}

}  // namespace

FarFieldResult farfield(const FarFieldInput& input, const FarFieldOptions& options, const Log& log) {
  validate(input, options);
  FarFieldResult result;
  result.input_point_count = input.points.size();
  LocalHull local = local_hull(input);
  std::vector<Vector3>& points = local.points;
  const std::vector<Triangle>& hull = local.hull;
  const Placement placement = place_boundary(local, options, log, result);
  const double farfield_size = options.farfield_size_in_chords * result.chord;
  const std::vector<double> hull_size = hull_sizes(points, hull);
  const farfield_detail::SizeField size =
      size_field(points, placement.footprint, hull_size, options.size_gradient, farfield_size);

  farfield_detail::LayerPoints layers;
  if (options.sizing == FarFieldSizing::anisotropic) {
    layers = anisotropic_layer_points(input, local, placement, hull_size, options);
    result.layer_points = layers.volume.size() + layers.plane.size();
    log.info("farfield: " + std::to_string(result.layer_points) + " layer points");
  }

  const std::size_t hull_point_count = points.size();
  const farfield_detail::OuterBoundary outer = farfield_detail::outer_boundary(
      options.shape, placement.centre, placement.radius, farfield_size, placement.symmetric, points);
  std::vector<Triangle> plane;
  if (placement.symmetric)
    plane = farfield_detail::symmetry_plane(options.symmetry_y, outer.rim, placement.footprint, layers.plane,
                                            size, options.plane_minimum_angle, points);
  result.boundary_points = points.size() - hull_point_count;
  log.detail("farfield: " + std::to_string(hull.size()) + " hull, " + std::to_string(plane.size()) +
             " symmetry, " + std::to_string(outer.triangles.size()) + " far-field triangles");

  farfield_detail::TetgenInput tetgen =
      tetgen_input(input, local, hull_size, hull_point_count, size, plane, outer, options);
  SpaceMap space = space_map(points, tetgen.triangles, options, log);
  const std::vector<Vector3> holes = tetgen.holes;
  tetgen.points = transform_points(space.forward, tetgen.points);
  tetgen.holes = transform_points(space.forward, tetgen.holes);

  Tetrahedralisation tetrahedralisation;
  tetrahedralisation.tetrahedra = quality_pass(tetgen, points, holes, options, log, space);
  // Every output point in the original coordinates: input points exactly, TetGen's
  // own mapped back.
  std::vector<Vector3>& original = tetrahedralisation.original;
  original = points;
  for (std::size_t node = points.size(); node < tetrahedralisation.tetrahedra.points.size(); ++node)
    original.push_back(space.backward * tetrahedralisation.tetrahedra.points[node]);
  if (std::optional<std::vector<Vector3>> volume_points =
          exact_pass_points(points, hull_point_count, layers, size, tetrahedralisation, options, log)) {
    tetrahedralisation.volume_points = std::move(*volume_points);
    exact_pass(tetgen, local, holes, options, log, tetrahedralisation);
  }
  const std::size_t input_count = points.size() + tetrahedralisation.volume_points.size();

  MixedMesh& mesh = result.mesh;
  const std::vector<Index> global =
      add_tetrahedra(input, local.global_of, hull_point_count, input_count, tetrahedralisation, log, result);
  farfield_detail::add_boundary_faces(global, hull, plane, outer.triangles, options, mesh);

  if (!input.metrics.empty()) {
    result.hull_lengths = hull_metric_lengths(mesh, input.hull, input.metric_nodes, input.metrics);
    const MetricLengthReport& lengths = result.hull_lengths;
    std::ostringstream text;
    text.precision(3);
    text << "farfield: metric edge lengths at the hull: " << lengths.within_range * 100.0
         << " % in [0.6, 1.6], median " << lengths.median << ", deciles " << lengths.lower_decile << " - "
         << lengths.upper_decile << " (" << lengths.edges << " edges)";
    log.info(text.str());
  }
  log.info("farfield: " + std::to_string(mesh.cell_count(CellType::tetrahedron)) + " tetrahedra, " +
           std::to_string(mesh.points.size() - input.points.size()) + " new points");
  return result;
}

}  // namespace mixmesh
