#include <iostream>

#include "commands.hpp"
#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/pipeline/generate.hpp"

namespace mixmesh::cli {

void add_generate_command(CLI::App& application) {
  struct Arguments {
    std::string config;
    std::vector<std::string> settings;
    std::string output_folder;
    std::string report;
    bool quiet = false;
    bool keep_invalid = false;
    std::string dump_stages;
  };
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = application.add_subcommand(
      "generate",
      "Generate the mixed mesh of a wing config: surface, marched hexahedra and prisms, pyramid/tetrahedron "
      "interface, TetGen far field. Prints one line per stage and Wild's Table-1 row; writes the formats of "
      "[output] only if the assembled mesh is valid.");
  command->add_option("config", arguments->config, "Config file (TOML), e.g. cases/onera_m6.toml")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--set", arguments->settings,
                      "Override a config value, KEY=VALUE in TOML syntax (repeatable), e.g. march.layers=24");
  command->add_option("--output-dir", arguments->output_folder,
                      "Folder for the mesh files (default: [output] folder)");
  command->add_option("--report", arguments->report,
                      "Also write the counts and stage timings as TOML to this file");
  command->add_flag("--quiet", arguments->quiet, "Print only the Table-1 row");
  command->add_option("--dump-stages", arguments->dump_stages,
                      "Write the far-field boundary after each preconditioning transform (boundary.vtk, "
                      "sheared.vtk, preconditioned.vtk) to this folder, as in Wild Fig. 4");
  command->add_flag("--keep-invalid", arguments->keep_invalid,
                    "If the assembled mesh is invalid, still write it, as NAME.invalid.vtu, for inspection");
  command->callback([arguments] {
    GenerateOptions options = load_generate_options(arguments->config, arguments->settings);
    if (!arguments->output_folder.empty()) options.output.folder = arguments->output_folder;
    options.farfield.dump_directory = arguments->dump_stages;
    // Like --output-dir, the folder is made when missing (the dump is written late, after
    // the march and the interface have run).
    if (!arguments->dump_stages.empty()) std::filesystem::create_directories(arguments->dump_stages);
    const Log log(&std::cout, arguments->quiet ? Log::Level::quiet : Log::Level::normal);
    const GenerateResult result = generate(options, log);
    if (!result.validity.valid()) {
      std::cerr << validity_details(result.validity);
      if (arguments->keep_invalid) {
        const auto path = kept_invalid_path(options.output.folder / (options.output.name + ".vtu"));
        std::filesystem::create_directories(options.output.folder);
        write_mesh(result.mesh, path);
        log.warning("wrote the invalid mesh to " + path.string());
      }
    }
    // Every deformation runs and is checked before anything is written: a failing
    // [[deform]] step leaves no files.
    const std::vector<DeformedMesh> deformed = run_deform_steps(result, options, log);
    for (const auto& path : write_outputs(result, options.output)) log.info("wrote " + path.string());
    for (const auto& path : write_deformed(result, deformed, options.output))
      log.info("wrote " + path.string());
    if (!arguments->report.empty()) write_report(arguments->report, result.report, deformed);
    std::cout << table_row(result.report) << '\n';
  });
}

}  // namespace mixmesh::cli
