// Reads the [surface] table and the surface stage's setup (surface_options.hpp).
#include "mixmesh/pipeline/surface_options.hpp"

#include "mixmesh/pipeline/wing_options.hpp"

namespace mixmesh {

SurfaceOptions read_surface_options(config::Section& table) {
  SurfaceOptions options;
  table.read("chordwise_cells", options.chordwise_cells, config::Bounds::at_least(8));
  table.read("spanwise_cells", options.spanwise_cells, config::Bounds::at_least(2));
  const config::Bounds fraction{0.0, 0.5, true, false};
  table.read("leading_edge_spacing", options.leading_edge_spacing, fraction);
  table.read("trailing_edge_spacing", options.trailing_edge_spacing, fraction);
  table.read("root_spacing", options.root_spacing, fraction);
  table.read("tip_spacing", options.tip_spacing, fraction);
  table.read("base_cells", options.base_cells, config::Bounds::at_least(2));
  if (options.base_cells % 2 != 0) table.fail("base_cells", "'surface.base_cells' must be even");
  table.read("base_face_aspect", options.base_face_aspect, config::Bounds::non_negative());
  if (std::optional<config::Section> wake = table.optional_section("wake")) {
    wake->read("enabled", options.wake.enabled);
    wake->read("length", options.wake.length, config::Bounds::positive());
    double first_spacing = 0.0;  // 0 in a config file: the trailing-edge spacing
    wake->read("first_spacing", first_spacing, config::Bounds::non_negative());
    if (first_spacing > 0.0) options.wake.first_spacing = first_spacing;
    wake->read("growth", options.wake.growth, config::Bounds::between(1.0, 3.0));
    wake->finish();
  }
  if (std::optional<config::Section> tip = table.optional_section("tip")) {
    tip->read("minimum_angle", options.tip.minimum_angle_degrees, {0.0, 20.7, true, false});
    tip->read("maximum_edge", options.tip.maximum_edge, config::Bounds::non_negative());
    std::string shape = "flat";
    tip->read_choice("shape", shape, {"flat", "rounded"});
    options.tip.rounded = shape == "rounded";
    tip->finish();
  }
  table.finish();
  return options;
}

SurfaceSetup read_surface_setup(config::Section& root) {
  SurfaceSetup setup;
  if (std::optional<config::Section> wing = root.optional_section("wing"))
    setup.wing = read_wing_definition(*wing);
  if (std::optional<config::Section> surface = root.optional_section("surface")) {
    for (config::Section& entry : surface->sections("import")) {
      SurfaceImport import;
      if (!entry.has("file")) entry.fail({}, "[[surface.import]] needs 'file'");
      entry.read_path("file", import.file);
      entry.read("name", import.name);
      entry.read_choice("role", import.role, {{"wall", PatchRole::wall}, {"wake", PatchRole::wake}});
      entry.read("flip", import.flip);
      entry.finish();
      setup.imports.push_back(import);
    }
    surface->read("merge_tolerance", setup.import_options.merge_tolerance, config::Bounds::positive());
    setup.options = read_surface_options(*surface);
  }
  if (!setup.wing && setup.imports.empty())
    root.fail({}, "the surface needs a [wing] table or [[surface.import]] entries");
  return setup;
}

}  // namespace mixmesh
