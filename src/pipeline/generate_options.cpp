// The tables of a generate config. Defaults live in the stage option structs; this
// file only maps keys onto them.
#include <algorithm>

#include "mixmesh/mesh/cell_geometry.hpp"
#include "mixmesh/pipeline/deform_options.hpp"
#include "mixmesh/pipeline/generate.hpp"
#include "mixmesh/pipeline/surface_options.hpp"

namespace mixmesh {

namespace {

using config::Bounds;

//   [march]
//   layers = 32
//   first_spacing = 0.0        # metres; 0: from y_plus, reynolds_number, reference_length
//   y_plus = 1.0
//   reynolds_number = 11.72e6
//   reference_length = 0.646
//   growth_law = "geometric"   # or "tanh" (then total_thickness)
//   growth_rate = 1.25
//   total_thickness = 0.0
//   method = "smoothed"        # or "normal": the plain extrusion baseline
//   layer_solve = "sweeps"     # or "sparse" (then layer_tolerance = 1e-4)
//   sweeps = 12, orthogonal_layers = 3, release_layers = 20, direction_memory = 0.5
//   step_reductions = 3, maximum_turn = 1.0 (degrees per layer; 0: no limit),
//   wake_spread = 6.0 (degrees: wake layers thicken downstream; 0: the wall's steps),
//   outer_layer_height = 0.25 (the last layer at least this times the shortest front edge),
//   self_intersection_check = true
MarchOptions read_march_options(config::Section& table) {
  MarchOptions options;
  SpacingOptions& spacing = options.spacing;
  table.read("layers", spacing.layer_count, Bounds::at_least(1));
  double first_spacing = 0.0;
  table.read("first_spacing", first_spacing, Bounds::non_negative());
  if (first_spacing > 0.0) spacing.first_spacing = first_spacing;
  table.read("y_plus", spacing.target_y_plus, Bounds::positive());
  table.read("reynolds_number", spacing.reynolds_number, Bounds::positive());
  table.read("reference_length", spacing.reference_length, Bounds::positive());
  table.read_choice("growth_law", spacing.growth_law,
                    {{"geometric", GrowthLaw::geometric}, {"tanh", GrowthLaw::tanh}});
  table.read("growth_rate", spacing.growth_rate, Bounds::at_least(1.0));
  double thickness = 0.0;
  table.read("total_thickness", thickness, Bounds::non_negative());
  if (thickness > 0.0) spacing.total_thickness = thickness;
  table.read_choice("method", options.method,
                    {{"smoothed", MarchMethod::smoothed}, {"normal", MarchMethod::normal}});
  table.read("sweeps", options.sweeps, Bounds::at_least(0));
  table.read_choice("layer_solve", options.layer_solve,
                    {{"sweeps", LayerSolve::sweeps}, {"sparse", LayerSolve::sparse}});
  table.read("layer_tolerance", options.layer_tolerance, Bounds::non_negative());
  table.read("orthogonal_layers", options.orthogonal_layers, Bounds::at_least(0));
  table.read("release_layers", options.release_layers, Bounds::at_least(0));
  table.read("direction_memory", options.direction_memory, Bounds::between(0, 1));
  table.read("step_reductions", options.step_reductions, Bounds::at_least(0));
  table.read("maximum_turn", options.maximum_turn_degrees, Bounds::between(0, 180));
  table.read("wake_spread", options.wake_spread_degrees, Bounds{0.0, 45.0, false, true});
  table.read("outer_layer_height", options.outer_layer_height, Bounds::between(0, 1));
  table.read("self_intersection_check", options.check_self_intersection);
  table.finish();
  return options;
}

//   [interface]
//   diagonal = "shorter"       # or "smallest_node"
InterfaceOptions read_interface_options(config::Section& table) {
  InterfaceOptions options;
  table.read_choice("diagonal", options.diagonal,
                    {{"shorter", HullDiagonal::shorter}, {"smallest_node", HullDiagonal::smallest_node}});
  table.finish();
  return options;
}

//   [farfield]
//   shape = "sphere"           # or "box"
//   sizing = "anisotropic"     # or "isotropic" (see docs/farfield.md)
//   radius = 20.0              # reference chords (sphere radius, box half-width)
//   reference_chord = 0.0      # metres; 0: the wing's root chord
//   farfield_size = 2.0        # edge length on the outer boundary, chords
//   size_gradient = 0.25
//   radius_edge_ratio = 1.5    # TetGen -q
//   layer_growth = 1.25, maximum_layers = 1
//   first_layer_height = 0.7   # the first layer point's height, × its normal spacing
//   precondition = false       # see docs/farfield.md: true can invert slivers
//   cap_metrics = true         # nodes under the wake's caps take the caps' metric too
//   sweep = nan                # degrees; absent: estimated from the hull
//   affine = "whitening"       # or "inverse" (Wild eq. 15) or "none"
FarFieldOptions read_farfield_options(config::Section& table) {
  FarFieldOptions options = anisotropic_farfield();
  table.read_choice("shape", options.shape, {{"sphere", FarFieldShape::sphere}, {"box", FarFieldShape::box}});
  table.read_choice("sizing", options.sizing,
                    {{"anisotropic", FarFieldSizing::anisotropic}, {"isotropic", FarFieldSizing::isotropic}});
  table.read("radius", options.radius_in_chords, Bounds::positive());
  table.read("reference_chord", options.reference_chord, Bounds::non_negative());
  table.read("farfield_size", options.farfield_size_in_chords, Bounds::positive());
  table.read("size_gradient", options.size_gradient, Bounds::positive());
  table.read("radius_edge_ratio", options.radius_edge_ratio, Bounds::at_least(1.0));
  table.read("layer_growth", options.layer_growth, Bounds::at_least(1.0));
  table.read("maximum_layers", options.maximum_layers, Bounds::at_least(0));
  table.read("first_layer_height", options.first_layer_height, Bounds{0.0, 1.0, true, false});
  table.read("precondition", options.precondition);
  table.read("cap_metrics", options.cap_metrics);
  if (table.has("sweep"))
    table.read("sweep", options.preconditioning.sweep_degrees, Bounds::between(-80, 80));
  table.read_choice(
      "affine", options.preconditioning.affine,
      {{"whitening", AffineMap::whitening}, {"inverse", AffineMap::inverse}, {"none", AffineMap::none}});
  table.finish();
  return options;
}

//   [slivers]
//   target_dihedral = 160.0    # degrees: tetrahedra above it are flipped / smoothed
//   passes = 12                # 0: no sliver removal
//   maximum_ring = 7
//   smooth_points = true
//   search_points = true       # last, for slivers nothing else mends: search free points
//                              # (whatever smooth_points says); above 170 degrees also
//                              # split points and cap apexes
//   insert_points = true
//   lift_pyramids = true       # after the passes: move split points and cap apexes
//                              # whose flattest pyramid is under apex_pyramid_quality
//   apex_dihedral = 170.0      # degrees: slivers above it may move split points and apexes
//   apex_pyramid_quality = 2e-3  # scaled Jacobian (Verdict's) their pyramids keep
SliverOptions read_sliver_options(config::Section& table) {
  SliverOptions options;
  table.read("target_dihedral", options.target_dihedral_degrees, Bounds{90.0, 180.0, false, false});
  table.read("passes", options.passes, Bounds::at_least(0));
  table.read("maximum_ring", options.maximum_ring, Bounds::at_least(3));
  table.read("smooth_points", options.smooth_points);
  table.read("search_points", options.search_points);
  table.read("insert_points", options.insert_points);
  table.read("lift_pyramids", options.lift_pyramids);
  table.read("apex_dihedral", options.apex_dihedral_degrees, Bounds{90.0, 180.0, true, true});
  // The key is in Verdict's units, as check_mesh.py and `mixmesh check` print it.
  if (table.has("apex_pyramid_quality")) {
    double pyramid_quality = 0.0;
    table.read("apex_pyramid_quality", pyramid_quality, Bounds{0.0, 1.0, true, false});
    options.apex_pyramid_quality = pyramid_quality / verdict_corner_factor;
  }
  table.finish();
  return options;
}

//   [output]
//   folder = "."               # relative to the working directory
//   name = "onera_m6"          # default: the config's stem
//   formats = ["vtu", "su2"]   # vtu, su2, cgns, msh
//   merge_wall_markers = true
OutputOptions read_output_options(config::Section& table, const std::filesystem::path& config_file) {
  OutputOptions options;
  options.name = config_file.stem().string();
  std::string folder = options.folder.string();
  table.read("folder", folder);
  options.folder = folder;
  table.read("name", options.name);
  table.read("formats", options.formats);
  for (const std::string& format : options.formats)
    if (format != "vtu" && format != "su2" && format != "cgns" && format != "msh")
      table.fail("formats", "unknown output format '" + format + "' (vtu, su2, cgns, msh)");
  if (options.formats.empty()) table.fail("formats", "'output.formats' names no format");
  table.read("merge_wall_markers", options.merge_wall_markers);
  table.finish();
  return options;
}

}  // namespace

GenerateOptions read_generate_options(config::Document& document) {
  GenerateOptions options;
  config::Section root = document.root();
  options.surface = read_surface_setup(root);
  // Absent tables read as empty ones, so every default is set in one place.
  const config::Document empty = config::Document::parse("", document.file());
  config::Section no_table = empty.root();
  auto march = root.optional_section("march");
  options.march = read_march_options(march ? *march : no_table);
  auto interface = root.optional_section("interface");
  options.interface = read_interface_options(interface ? *interface : no_table);
  auto farfield = root.optional_section("farfield");
  options.farfield = read_farfield_options(farfield ? *farfield : no_table);
  auto slivers = root.optional_section("slivers");
  options.slivers = read_sliver_options(slivers ? *slivers : no_table);
  auto output = root.optional_section("output");
  options.output = read_output_options(output ? *output : no_table, document.file());
  // The files a step writes: NAME_STEP, or NAME_STEP_0001 … for a sequence.
  auto stems = [](const deform::DeformStep& step) {
    std::vector<std::string> names;
    for (int index = 1; index <= step.motion.steps; ++index)
      names.push_back(deform::step_stem(step.name, index, step.motion.steps));
    return names;
  };
  for (config::Section& step : root.sections("deform")) {
    options.deform.push_back(deform::read_deform_step(step));
    const std::vector<std::string> mine = stems(options.deform.back());
    for (std::size_t other = 0; other + 1 < options.deform.size(); ++other) {
      if (options.deform[other].name == options.deform.back().name)
        step.fail("name", "two [[deform]] steps named '" + options.deform.back().name + "'");
      for (const std::string& stem : stems(options.deform[other]))
        if (std::find(mine.begin(), mine.end(), stem) != mine.end())
          step.fail("name", "[[deform]] '" + options.deform.back().name + "' would write the files of '" +
                                options.deform[other].name + "' (" + options.deform[other].where +
                                "): " + stem);
    }
  }
  // Cluster settings of a batch (`mixmesh batch --slurm`), read by the batch, not the mesh's.
  root.optional_section("slurm");
  root.finish();
  return options;
}

GenerateOptions load_generate_options(const std::filesystem::path& config,
                                      const std::vector<std::string>& settings) {
  config::Document document = config::Document::load(config);
  for (const std::string& setting : settings) document.set(setting);
  return read_generate_options(document);
}

}  // namespace mixmesh
