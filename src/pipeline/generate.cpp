#include "mixmesh/pipeline/generate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>

#include "assemble.hpp"
#include "mixmesh/core/atomic_file.hpp"
#include "mixmesh/core/quoted.hpp"
#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/metric/metric.hpp"
#include "mixmesh/quality/cell_quality.hpp"
#include "mixmesh/surface/surface_conversion.hpp"

namespace mixmesh {

namespace {

// Runs one stage and records its time; an Error from the stage is prefixed with
// the stage's name so the user knows where it failed.
template <typename Body>
auto run_stage(const std::string& stage, GenerateReport& report, Body body) {
  Stopwatch watch;
  try {
    auto result = body();
    report.stages.push_back({stage, watch.seconds()});
    return result;
  } catch (const Error& error) {
    const std::string message = error.what();
    throw Error(message.rfind(stage + ":", 0) == 0 ? message : stage + ": " + message);
  }
}

std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f s", seconds);
  return text;
}

std::string fixed_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", value);
  return text;
}

std::vector<std::string> wall_marker_names(const SurfaceMesh& surface) {
  std::vector<std::string> names;
  for (const StructuredPatch& patch : surface.structured) {
    if (patch.role != PatchRole::wall) continue;
    names.push_back(patch.name);
    names.push_back(patch.name + "_lower");
    names.push_back(patch.name + "_upper");
  }
  for (const TrianglePatch& patch : surface.unstructured)
    if (patch.role == PatchRole::wall) names.push_back(patch.name);
  return names;
}

// Points inside the body for TetGen's holes: on each structured wall patch that wraps
// a section (leading_edge_i set), the middle between a lower and the matching upper
// node at mid-span, which lies inside the section.
std::vector<Vector3> body_points(const SurfaceMesh& surface) {
  std::vector<Vector3> points;
  for (const StructuredPatch& patch : surface.structured) {
    if (patch.role != PatchRole::wall || patch.leading_edge_i <= 0) continue;
    const int lower = patch.leading_edge_i / 2;
    const int upper = patch.ni - 1 - lower;
    const int middle = patch.nj / 2;
    points.push_back(0.5 * (surface.points[static_cast<std::size_t>(patch.node(lower, middle))] +
                            surface.points[static_cast<std::size_t>(patch.node(upper, middle))]));
  }
  return points;
}

double min_scaled_jacobian(const MixedMesh& mesh) {
  double minimum = 1.0;
  for (CellType type : all_cell_types)
    for (std::size_t cell = 0; cell < mesh.cell_count(type); ++cell)
      minimum = std::min(minimum, scaled_jacobian(type, mesh.points, mesh.cell(type, cell)));
  return minimum;
}

}  // namespace

namespace {

// What to change when the layers leave a hull the far field cannot fill.
std::string layer_hint(const MarchReport& march) {
  if (march.stopped.empty())
    return "; check that the wing's sections do not intersect and that the wake does not cross the wing";
  const StoppedRegion& first = march.stopped.front();
  return "; the layers stopped early on " + std::to_string(march.stopped_faces) +
         " faces (the first at layer " + std::to_string(first.layer) + " near " + point_text(first.location) +
         "): fewer or thinner layers (march.layers, march.growth_rate) or a finer surface there keep the "
         "layers clear of each other";
}

// What the march, interface, metric and far-field stages hand on from attempt to
// attempt, and what a retry changes.
struct HullAttempts {
  MarchOptions march_options;
  BoundaryLayer layers;
  InterfaceResult interface;
  FarFieldInput farfield_input;
  std::optional<FarFieldResult> farfield_result;
  std::vector<Vector3> previous_crossings;
};

// Lowers the layers round `crossings` for the next attempt, and says why (`reason`).
// The hull intersects itself where the layers came too close to each other (a
// strongly tapered tip's trailing edge, a stop the blending could not smooth), and an
// outer cell is twisted more than it is thick beside an early stop: the columns round
// the place stop lower and slope down to it, and the stages run again. Each retry
// reaches further and lower.
void lower_layers(const SurfaceMesh& surface, const GenerateOptions& options, const Log& log, int attempt,
                  const std::vector<Vector3>& crossings, const std::string& reason, HullAttempts& attempts) {
  // Every crossing TetGen found gets a stop (one for all the crossings within half a
  // stop's reach of it): a blunt base crosses the sheet's first lines all along the
  // wing, and a stop at the first crossing alone left the others.
  // Reach: three layer thicknesses and the surface cells there (twice the distance
  // to the nearest surface node; thin layers alone reached no face on a small wing),
  // growing with each retry; depth: half the layers, then half as many again each
  // time (behind a blunt base the crossings lie low in the layers, and four layers
  // less per retry never reached them), but no lower than the layer whose stack is
  // half as thick as the crossing is high (a quarter on the second retry, and so on):
  // a crossing high in the layers (a tapered tip's trailing edge) once stopped them
  // where the geometric stack is a twentieth of its thickness, and the split of such a
  // thin stack under the tip's triangles left flat tetrahedra.
  MarchOptions& march_options = attempts.march_options;
  const std::vector<double> steps = layer_steps(march_options.spacing);
  const auto layer_below = [&](double height) {
    int layer = 0;
    for (double thickness = 0.0; layer < static_cast<int>(steps.size()); ++layer) {
      thickness += steps[layer];
      if (thickness > height) break;
    }
    return layer;
  };
  std::vector<ForcedStop> stops;
  for (const Vector3& crossing : crossings) {
    const bool covered = std::any_of(stops.begin(), stops.end(), [&](const ForcedStop& other) {
      return (other.centre - crossing).norm() < 0.5 * other.radius;
    });
    if (covered) continue;
    double nearest_node = std::numeric_limits<double>::infinity();
    for (const Vector3& point : surface.points)
      nearest_node = std::min(nearest_node, (point - crossing).norm());
    ForcedStop stop;
    stop.centre = crossing;
    stop.radius = (attempt + 1) * (3.0 * attempts.layers.report.total_thickness + 2.0 * nearest_node);
    const double height_share = std::ldexp(1.0, -(attempt + 1));
    stop.layer = std::max(
        {1, march_options.spacing.layer_count >> (attempt + 1), layer_below(height_share * nearest_node)});
    stops.push_back(stop);
  }
  // A crossing as high above the wall as the whole stack is thick (in the caps over a
  // wake's thickened layers) gets stops at the last layer, which change nothing: the
  // attempts would repeat the same hull, minutes each on a large wing.
  const int layer_count = march_options.spacing.layer_count;
  if (std::all_of(stops.begin(), stops.end(), [&](const ForcedStop& stop) { return stop.layer >= layer_count; }))
    throw Error(reason + ", higher above the wall than the layers' stack is thick there, so lowering the " +
                "layers cannot mend it" + layer_hint(attempts.layers.report));
  march_options.forced_stops.insert(march_options.forced_stops.end(), stops.begin(), stops.end());
  log.warning(reason + "; the layers within " + std::to_string(stops.front().radius) + " m of " +
              std::to_string(stops.size()) + (stops.size() == 1 ? " place" : " places") + " stop by layer " +
              std::to_string(stops.front().layer) + " (retry " + std::to_string(attempt + 1) + " of " +
              std::to_string(options.hull_retries) + ")");
  attempts.previous_crossings = crossings;
}

BoundaryLayer march_stage(const SurfaceMesh& surface, const MarchOptions& march_options,
                          GenerateReport& report, const Log& log) {
  BoundaryLayer layers =
      run_stage("march", report, [&] { return march_layers(surface, march_options, nullptr); });
  report.march = layers.report;
  log.info("march: " + seconds_text(report.stages.back().seconds) + ", " +
           std::to_string(layers.report.layers_completed) + "/" +
           std::to_string(layers.report.layers_requested) + " layers, " +
           std::to_string(layers.mesh.cell_count(CellType::hexahedron)) + " hexahedra, " +
           std::to_string(layers.mesh.cell_count(CellType::prism)) + " prisms, first spacing " +
           std::to_string(layers.report.first_spacing) + " m, thickness " +
           std::to_string(layers.report.total_thickness) + " m");
  if (layers.report.thinned_lines > 0) {
    std::ostringstream thinnest;
    thinnest.precision(3);
    thinnest << std::scientific << layers.report.thinnest_stack;
    log.info("march: " + std::to_string(layers.report.thinned_lines) +
             " lines near a blunt base's corners with the wake in thinner stacks, down to " + thinnest.str() +
             " m");
  }
  if (layers.report.stopped_faces > 0) {
    const StoppedRegion& lowest = layers.report.stopped.front();  // sorted by layer
    log.warning("march: growth stopped early on " + std::to_string(layers.report.stopped_faces) + " faces (" +
                std::to_string(layers.report.stopped_nodes) + " nodes, " +
                std::to_string(layers.report.blended_faces) +
                " of them to slope down to the others); the lowest " + std::to_string(lowest.faces) +
                " at layer " + std::to_string(lowest.layer) + " near " + point_text(lowest.location) + ", " +
                std::to_string(lowest.thickness_lost) + " m of the wall stack lost");
  }
  return layers;
}

// The interface split; where a cell can be neither split nor capped and a retry is
// left, its location in `unsplittable` and an empty result.
InterfaceResult interface_stage(const BoundaryLayer& layers, const GenerateOptions& options, int attempt,
                                GenerateReport& report, const Log& log,
                                std::optional<Vector3>& unsplittable) {
  InterfaceResult interface = run_stage("interface", report, [&] {
    const OuterLayer outer = pipeline_detail::outer_layer(
        layers.mesh, {options.march.outer_hull_marker, options.march.hull_side_marker});
    InterfaceOptions interface_options = options.interface;
    // The cells the march tagged for capping, under whatever name it tagged them.
    if (!interface_options.capped_marker.empty())
      interface_options.capped_marker = options.march.hull_side_marker;
    if (!interface_options.symmetry_marker.empty())
      interface_options.symmetry_marker = options.march.symmetry_marker;
    try {
      return split_interface(layers.mesh, outer, interface_options);
    } catch (const UnsplittableCellError& error) {
      // An outer cell twisted more than it is thick (next to where the growth stopped
      // at a tip's trailing edge: random wing 3 of seed 20): lower layers there are
      // less twisted.
      if (attempt >= options.hull_retries) throw;
      log.warning(error.what());
      unsplittable = error.location;
      return InterfaceResult();
    }
  });
  if (!unsplittable)
    log.info("interface: " + seconds_text(report.stages.back().seconds) + ", " +
             std::to_string(interface.pyramids) + " pyramids, " + std::to_string(interface.tetrahedra) +
             " tetrahedra, hull of " + std::to_string(interface.hull.size()) + " triangles, " +
             std::to_string(interface.lowered_caps) + " caps lowered (clear of the hull or level with a neighbour), " +
             std::to_string(interface.stacks) + " outer cells split with the " +
             std::to_string(interface.stacked_cells - interface.stacks) + " cells under them");
  return interface;
}

// The metrics of the hull's nodes, for the anisotropic far field.
void metric_stage(const BoundaryLayer& layers, const InterfaceResult& interface, bool cap_metrics,
                  GenerateReport& report, const Log& log, FarFieldInput& farfield_input) {
  run_stage("metric", report, [&] {
    std::set<Index> hull_nodes;
    for (const auto& triangle : interface.hull) hull_nodes.insert(triangle.begin(), triangle.end());
    // Nodes of the layers take the metrics of the layer cells before the split (the
    // hexahedra's own shape), blended with their caps' where a cap stands on them;
    // points the split added (cap apexes) take those of the cells around them after it.
    const Index layer_points = static_cast<Index>(layers.mesh.points.size());
    std::vector<Index> layer_nodes, added_nodes;
    for (Index node : hull_nodes) (node < layer_points ? layer_nodes : added_nodes).push_back(node);
    farfield_input.metric_nodes = layer_nodes;
    farfield_input.metric_nodes.insert(farfield_input.metric_nodes.end(), added_nodes.begin(),
                                       added_nodes.end());
    farfield_input.metrics = node_metrics(layers.mesh, layer_nodes);
    if (cap_metrics)
      farfield_input.capped_nodes =
          blend_cap_metrics(interface.mesh, interface.hull, layer_nodes, farfield_input.metrics);
    const std::vector<Matrix3> added_metrics = node_metrics(interface.mesh, added_nodes);
    farfield_input.metrics.insert(farfield_input.metrics.end(), added_metrics.begin(), added_metrics.end());
    return 0;
  });
  log.info("metric: " + seconds_text(report.stages.back().seconds) + ", " +
           std::to_string(farfield_input.metric_nodes.size()) + " hull node metrics");
}

// The far field; where a retry is left and the hull intersects itself (or TetGen
// fails on a hull the retries are mending), the places to lower in `crossings` and
// no result.
std::optional<FarFieldResult> farfield_stage(const SurfaceMesh& surface, const GenerateOptions& options,
                                             const HullAttempts& attempts, int attempt,
                                             GenerateReport& report, const Log& log,
                                             std::vector<Vector3>& crossings) {
  const std::vector<Vector3>& previous_crossings = attempts.previous_crossings;
  FarFieldOptions farfield_options = options.farfield;
  farfield_options.symmetry_y = surface.symmetry_y;
  // Far-field sizes are in chords of the wing, not of the hull, whose extent in x
  // includes the wake.
  if (farfield_options.reference_chord <= 0.0 && options.surface.wing)
    farfield_options.reference_chord = options.surface.wing->stations.front().chord;
  return run_stage("farfield", report, [&]() -> std::optional<FarFieldResult> {
    try {
      return farfield(attempts.farfield_input, farfield_options, log);
    } catch (const HullIntersectionError& error) {
      if (attempt < options.hull_retries) {
        crossings = error.locations;
        return std::nullopt;
      }
      throw Error(error.what() + layer_hint(attempts.layers.report));
    } catch (const Error& error) {
      const std::string message = error.what();
      // TetGen can fail outright on a hull the retries are still mending (a base's
      // stacks stopped by half the layers: an abort on random wing 22 of seed 11, a
      // quality pass that never ended on wing 20 of seed 14): the same places are
      // lowered further, as if it had found the crossings there again.
      const bool tetgen_failed = message.find("TetGen crashed") != std::string::npos ||
                                 message.find("did not finish within") != std::string::npos;
      if (tetgen_failed && !previous_crossings.empty() && attempt < options.hull_retries) {
        log.warning(message + "; lowering the layers further where the last retry did");
        crossings = previous_crossings;
        return std::nullopt;
      }
      // TetGen 1.5 can abort while it recovers a boundary edge on the anisotropic
      // input (an assertion in recoveredgebyflips on random wing 57 of seed 41, whose
      // isotropic far field builds): isotropic sizing then gives a mesh rather than none.
      if (tetgen_failed && farfield_options.sizing == FarFieldSizing::anisotropic) {
        log.warning(message + "; building the far field with isotropic sizing instead");
        FarFieldOptions isotropic = farfield_options;
        isotropic.sizing = FarFieldSizing::isotropic;
        return farfield(attempts.farfield_input, isotropic, log);
      }
      // A hull the far field cannot fill comes from the layers: say where they stopped
      // and what to change, not only what TetGen found.
      if (message.find("intersect") == std::string::npos && message.find("hull edge") == std::string::npos &&
          message.find("hull is open") == std::string::npos)
        throw;
      throw Error(message + layer_hint(attempts.layers.report));
    }
  });
}

// March, interface, metrics and far field; where the hull handed to the far field
// intersects itself, the layers round the crossing are lowered and the four run again.
HullAttempts grow_to_farfield(const SurfaceMesh& surface, const GenerateOptions& options,
                              GenerateReport& report, const Log& log) {
  HullAttempts attempts;
  attempts.march_options = options.march;
  const std::size_t first_stage = report.stages.size();
  for (int attempt = 0; !attempts.farfield_result; ++attempt) {
    report.hull_retries = attempt;
    // A retry's stage timings replace those of the attempt before.
    report.stages.erase(report.stages.begin() + static_cast<std::ptrdiff_t>(first_stage),
                        report.stages.end());
    attempts.layers = march_stage(surface, attempts.march_options, report, log);

    std::optional<Vector3> unsplittable;
    attempts.interface = interface_stage(attempts.layers, options, attempt, report, log, unsplittable);
    if (unsplittable) {
      lower_layers(surface, options, log, attempt, {*unsplittable},
                   "interface: a cell neither split nor capped", attempts);
      continue;
    }

    FarFieldInput& farfield_input = attempts.farfield_input;
    farfield_input = FarFieldInput();
    if (options.farfield.sizing == FarFieldSizing::anisotropic)
      metric_stage(attempts.layers, attempts.interface, options.farfield.cap_metrics, report, log,
                   farfield_input);
    farfield_input.points = attempts.interface.mesh.points;
    farfield_input.holes = body_points(surface);
    farfield_input.hull = attempts.interface.hull;
    std::vector<Vector3> crossings;  // (previous_crossings: those of the last retry)
    attempts.farfield_result = farfield_stage(surface, options, attempts, attempt, report, log, crossings);
    if (!attempts.farfield_result)
      lower_layers(surface, options, log, attempt, crossings,
                   "farfield: the hull intersects itself near " + point_text(crossings.front()) + " (" +
                       std::to_string(crossings.size()) + " crossing triangles)",
                   attempts);
  }
  const FarFieldResult& farfield_result = *attempts.farfield_result;
  log.info("farfield: " + seconds_text(report.stages.back().seconds) + ", " +
           std::to_string(farfield_result.mesh.cell_count(CellType::tetrahedron)) + " tetrahedra, " +
           std::to_string(farfield_result.mesh.points.size() - farfield_result.input_point_count) +
           " new points");
  return attempts;
}

// With passes = 0 the stage only measures the tetrahedra.
void sliver_stage(const SliverOptions& sliver_options, GenerateReport& report, const Log& log,
                  MixedMesh& mesh) {
  report.slivers = run_stage("slivers", report, [&] { return remove_slivers(mesh, sliver_options); });
  const SliverReport& slivers = report.slivers;
  log.info("slivers: " + seconds_text(report.stages.back().seconds) + ", " +
           std::to_string(slivers.above_target_before) + " -> " + std::to_string(slivers.above_target_after) +
           " tetrahedra above " + fixed_text(sliver_options.target_dihedral_degrees) +
           " deg (largest dihedral " + fixed_text(slivers.largest_dihedral_before) + " -> " +
           fixed_text(slivers.largest_dihedral_after) + " deg), " + std::to_string(slivers.edge_removals) +
           " edge removals, " + std::to_string(slivers.face_flips) + " face flips, " +
           std::to_string(slivers.edge_splits) + " edge splits, " + std::to_string(slivers.point_collapses) +
           " point collapses, " + std::to_string(slivers.smoothed_points) + " points moved, " +
           std::to_string(slivers.point_insertions) + " points inserted, " +
           std::to_string(slivers.lifted_apexes) + " apexes lifted");
}

}  // namespace

GenerateResult generate(const GenerateOptions& options, const Log& log) {
  Stopwatch watch;
  const SurfaceMesh surface = [&] {
    try {
      return build_surface(options.surface);
    } catch (const Error& error) {
      throw Error(std::string("surface: ") + error.what());
    }
  }();
  const double seconds = watch.seconds();
  log.info("surface: " + seconds_text(seconds) + ", " + std::to_string(surface.points.size()) + " points");
  const bool base = options.surface.wing && options.surface.wing->blunt_trailing_edge == TrailingEdge::base;
  for (const StructuredPatch& patch : surface.structured)
    if (base && patch.name == "base" && patch.ni - 1 < options.surface.options.base_cells)
      log.info("surface: " + std::to_string(patch.ni - 1) + " faces across the base instead of base_cells " +
               std::to_string(options.surface.options.base_cells) +
               ", which would be more than base_face_aspect times shorter than the spanwise faces");
  GenerateResult result = generate_from_surface(surface, options, log);
  result.report.stages.insert(result.report.stages.begin(), StageTiming{"surface", seconds});
  result.report.seconds += seconds;
  return result;
}

GenerateResult generate_from_surface(const SurfaceMesh& surface, const GenerateOptions& options,
                                     const Log& log) {
  Stopwatch total;
  GenerateResult result;
  GenerateReport& report = result.report;
  report.surface_elements = to_mixed_mesh(surface).face_count();
  HullAttempts attempts = grow_to_farfield(surface, options, report, log);
  FarFieldResult& farfield_result = *attempts.farfield_result;

  result.mesh = run_stage("assemble", report, [&] {
    return pipeline_detail::assemble(attempts.interface.mesh, options.interface.hull_marker, farfield_result,
                                     wall_marker_names(surface), options.output.merge_wall_markers);
  });
  sliver_stage(options.slivers, report, log, result.mesh);
  result.validity = run_stage("validate", report, [&] { return validate(result.mesh); });
  log.info("validate: " + seconds_text(report.stages.back().seconds) + ", " + result.validity.summary());

  report.points = result.mesh.points.size();
  report.hexahedra = result.mesh.cell_count(CellType::hexahedron);
  report.tetrahedra = result.mesh.cell_count(CellType::tetrahedron);
  report.prisms = result.mesh.cell_count(CellType::prism);
  report.pyramids = result.mesh.cell_count(CellType::pyramid);
  report.min_scaled_jacobian = min_scaled_jacobian(result.mesh);
  farfield_result.mesh = MixedMesh();
  report.farfield_summary = std::move(farfield_result);
  report.seconds = total.seconds();
  return result;
}

std::string validity_details(const ValidityReport& validity) {
  std::ostringstream text;
  for (const Finding& finding : validity.findings) {
    if (finding.count == 0 || finding.severity != Finding::Severity::error) continue;
    text << "  " << finding.count << " " << finding.description << ":";
    for (const Offender& offender : finding.examples)
      text << " " << offender.entity << " " << offender.index << " at (" << offender.location.x() << ", "
           << offender.location.y() << ", " << offender.location.z() << ");";
    text << "\n";
  }
  return text.str();
}

std::vector<std::filesystem::path> write_outputs(const GenerateResult& result, const OutputOptions& options) {
  if (!result.validity.valid())
    throw Error("validate: the assembled mesh is invalid, nothing written: " + result.validity.summary());
  std::filesystem::create_directories(options.folder);
  std::vector<std::filesystem::path> written;
  for (const std::string& format : options.formats) {
    const std::filesystem::path path = options.folder / (options.name + "." + format);
    write_mesh(result.mesh, path);
    written.push_back(path);
  }
  return written;
}

std::string table_row(const GenerateReport& report) {
  std::ostringstream row;
  row << "points " << report.points << "  surface elements " << report.surface_elements << "  hexahedra "
      << report.hexahedra << "  tetrahedra " << report.tetrahedra << "  prisms " << report.prisms
      << "  pyramids " << report.pyramids;
  return row.str();
}

void write_report(const std::filesystem::path& path, const GenerateReport& report,
                  const std::vector<DeformedMesh>& deformed) {
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream file(temporary);
    file << "# mixmesh generate report\n"
         << "points = " << report.points << "\nsurface_elements = " << report.surface_elements
         << "\nhexahedra = " << report.hexahedra << "\ntetrahedra = " << report.tetrahedra
         << "\nprisms = " << report.prisms << "\npyramids = " << report.pyramids
         << "\nmin_scaled_jacobian = " << report.min_scaled_jacobian
         << "\nlayers_completed = " << report.march.layers_completed
         << "\nstopped_faces = " << report.march.stopped_faces
         << "\nblended_faces = " << report.march.blended_faces << "\nthickness_lost = "
         << (report.march.stopped.empty() ? 0.0 : report.march.stopped.front().thickness_lost)
         << "\nthinned_lines = " << report.march.thinned_lines
         << "\nthinnest_stack = " << report.march.thinnest_stack << "\nhull_retries = " << report.hull_retries
         << "\nhull_metric_edges_within_range = " << report.farfield_summary.hull_lengths.within_range
         << "\nlargest_dihedral = " << report.slivers.largest_dihedral_after
         << "\ntetrahedra_above_target_dihedral = " << report.slivers.above_target_after
         << "\nseconds = " << report.seconds << "\n";
    if (!deformed.empty()) {
      double minimum = deformed.front().min_scaled_jacobian;
      for (const DeformedMesh& mesh : deformed) minimum = std::min(minimum, mesh.min_scaled_jacobian);
      file << "deformed_meshes = " << deformed.size() << "\ndeformed_min_scaled_jacobian = " << minimum
           << "\n";
    }
    file << "\n[stages]\n";
    for (const StageTiming& stage : report.stages) file << stage.stage << " = " << stage.seconds << "\n";
    for (const DeformedMesh& mesh : deformed)
      file << "\n[[deform]]\nstep = " << quoted(mesh.step_name) << "\nindex = " << mesh.index
           << "\nsteps = " << mesh.steps << "\nfile_stem = " << quoted(mesh.stem)
           << "\nlargest_displacement = " << mesh.largest_displacement
           << "\nmin_scaled_jacobian = " << mesh.min_scaled_jacobian
           << "\nmax_wall_angle_change = " << mesh.max_wall_angle_change << "\nseconds = " << mesh.seconds
           << "\n";
    if (!file.flush()) throw Error(path.string() + ": cannot write report");
  });
}

}  // namespace mixmesh
