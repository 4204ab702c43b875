// mixmesh march CONFIG -o bl.vtu: the marched boundary layer (hexahedra and prisms)
// of the wing of a config file, from its [wing], [surface] and [march] tables.
// --compare also marches the plain-normal baseline and prints both methods' figures.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "mixmesh/config/config.hpp"
#include "mixmesh/core/log.hpp"
#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/march/march_metrics.hpp"
#include "mixmesh/pipeline/generate.hpp"
#include "mixmesh/quality/validity.hpp"

namespace mixmesh::cli {

namespace {

struct MarchArguments {
  std::filesystem::path config;
  std::filesystem::path output = "boundary_layer.vtu";
  std::vector<std::string> settings;
  bool normal = false;
  bool compare = false;
  bool keep_invalid = false;
  bool quiet = false;
  bool verbose = false;
};

std::string metrics_row(const std::string& name, const BoundaryLayer& layer, const MarchMetrics& metrics) {
  char row[256];
  std::snprintf(row, sizeof row, "%-9s %9zu %7d %9.4f %8.3f %8.3f %9.3f %8.2f %8.3f %7d", name.c_str(),
                layer.mesh.cell_count(), metrics.invalid_cells, metrics.minimum_scaled_jacobian,
                metrics.maximum_normal_deviation_degrees, metrics.percentile99_normal_deviation_degrees,
                metrics.maximum_growth_jump, metrics.maximum_line_turn_degrees,
                metrics.percentile99_line_turn_degrees, layer.report.stopped_faces);
  return row;
}

void run_march(const MarchArguments& arguments) {
  const Log log(&std::cout, arguments.quiet     ? Log::Level::quiet
                            : arguments.verbose ? Log::Level::verbose
                                                : Log::Level::normal);
  GenerateOptions options = load_generate_options(arguments.config, arguments.settings);
  if (arguments.normal) options.march.method = MarchMethod::normal;
  const SurfaceMesh surface = build_surface(options.surface);
  const BoundaryLayer layer = march_layers(surface, options.march, &log);
  // The same checks as every generated mesh before it is written (volumes, conforming
  // faces, every boundary face tagged: wall, symmetry, outer hull, free-edge sides).
  const ValidityReport validity = validate(layer.mesh);
  log.info("validate: " + validity.summary());
  if (!validity.valid()) {
    std::cerr << validity_details(validity);
    if (arguments.keep_invalid) {
      const std::filesystem::path kept = kept_invalid_path(arguments.output);
      try {  // the error below is the one to report, not a failed write
        if (kept.has_parent_path()) std::filesystem::create_directories(kept.parent_path());
        write_mesh(layer.mesh, kept);
        log.warning("wrote the invalid layers to " + kept.string());
      } catch (const std::exception& error) {
        log.warning(std::string("could not write the invalid layers: ") + error.what());
      }
    }
    throw Error("march: the layers are invalid, " + arguments.output.string() +
                " not written: " + validity.summary());
  }
  write_mesh(layer.mesh, arguments.output);  // written under a temporary name, then renamed
  log.info("wrote " + arguments.output.string());
  if (!arguments.compare) return;
  MarchOptions baseline = options.march;
  baseline.method = options.march.method == MarchMethod::normal ? MarchMethod::smoothed : MarchMethod::normal;
  const BoundaryLayer other = march_layers(surface, baseline);
  const std::string patch = "wing";
  const bool has_wing =
      std::find(layer.region_names.begin(), layer.region_names.end(), patch) != layer.region_names.end();
  const std::string measured = has_wing ? patch : "";
  std::cout
      << "method        cells invalid  min s.J.  dev.max  dev.p99  growth.jump turn.max turn.p99 stopped\n";
  const bool smoothed_first = options.march.method == MarchMethod::smoothed;
  const BoundaryLayer& smoothed = smoothed_first ? layer : other;
  const BoundaryLayer& normal = smoothed_first ? other : layer;
  std::cout << metrics_row("smoothed", smoothed, measure_march(smoothed, surface, measured)) << '\n'
            << metrics_row("normal", normal, measure_march(normal, surface, measured)) << '\n';
}

}  // namespace

void add_march_command(CLI::App& application) {
  auto arguments = std::make_shared<MarchArguments>();
  CLI::App* command = application.add_subcommand(
      "march", "March the boundary layer (hexahedra from quads, prisms from triangles) of a wing config");
  command->add_option("config", arguments->config, "Config file with [wing], [surface] and [march] tables")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-o,--output", arguments->output, "Output mesh (.vtu, .msh, .su2, .cgns)")
      ->capture_default_str();
  command->add_option("--set", arguments->settings,
                      "Override a config value, KEY=VALUE in TOML syntax (repeatable), e.g. march.layers=24");
  command->add_flag("--normal", arguments->normal,
                    "March the plain-normal baseline instead of the smoothed method");
  command->add_flag("--compare", arguments->compare,
                    "Also march the other method and print both methods' quality figures");
  command->add_flag("--keep-invalid", arguments->keep_invalid,
                    "If the layers are invalid, write them beside the output with invalid before the extension");
  command->add_flag("-q,--quiet", arguments->quiet, "Print nothing but errors (and the --compare table)");
  command->add_flag("-v,--verbose", arguments->verbose,
                    "Also report every layer: corrector iterations, invalid cells and crossing faces");
  command->callback([arguments]() { run_march(*arguments); });
}

}  // namespace mixmesh::cli
