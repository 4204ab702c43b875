#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "plot_scripts.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/pipeline/compare.hpp"
#include "mixmesh/surface/surface_conversion.hpp"

namespace mixmesh::cli {

namespace {

// Runs one picture script; a failure is a warning (the tables are the result).
bool run_picture_script(const std::vector<std::string>& command, const Log& log) {
  try {
    run_plot_script(command);
    return true;
  } catch (const Error& error) {
    log.warning(std::string("picture not written: ") + error.what());
    return false;
  }
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

}  // namespace

void add_compare_command(CLI::App& application) {
  struct Arguments {
    std::string config;
    std::vector<std::string> settings;
    std::string output_folder;
    double hybrid_edge = 0.0;
    double cut_position = 0.44;
    bool no_pictures = false;
    bool hybrid_surface_only = false;
    std::vector<std::string> only;
    // Debian's interpreter has the modules the scripts need (numpy, matplotlib, meshio).
    std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    std::string scripts;
  };
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = application.add_subcommand(
      "compare",
      "Wild's Table 1 for a wing config: generates and validates the mixed mesh with anisotropic and with "
      "isotropic tets and the hybrid baseline (isotropic surface triangles, O-type prism layers of the same "
      "wall spacing, growth and layer count, isotropic tets); prints the counts with the paper's rows and "
      "writes compare.csv, compare.json, the meshes (VTU), a bar chart and a cut picture of each mesh.");
  command->add_option("config", arguments->config, "Config file (TOML), e.g. cases/onera_m6.toml")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--set", arguments->settings,
                      "Override a config value, KEY=VALUE in TOML syntax (repeatable)");
  command->add_option("--output-dir", arguments->output_folder,
                      "Folder for all outputs (default: [output] folder)");
  command
      ->add_option("--hybrid-edge", arguments->hybrid_edge,
                   "Edge length of the hybrid's surface triangles in metres (default 0: the mixed surface's "
                   "mean chordwise edge at mid-span)")
      ->check(CLI::NonNegativeNumber);
  command
      ->add_option("--cut-position", arguments->cut_position,
                   "Span station of the cut pictures, fraction of the semi-span (default 0.44)")
      ->check(CLI::Range(0.0, 1.0));
  command->add_flag("--no-pictures", arguments->no_pictures, "Write no PNG pictures");
  command->add_flag(
      "--hybrid-surface-only", arguments->hybrid_surface_only,
      "Only write the hybrid's triangulated surface (<name>_hybrid_surface.vtu) and its edge lengths");
  command->add_option("--only", arguments->only,
                      "Build only these meshes (repeatable): mixed_anisotropic, mixed_isotropic, hybrid");
  command->add_option(
      "--python", arguments->python,
      "Python interpreter for the pictures (default /usr/bin/python3 if it exists, else python3)");
  command->add_option("--scripts", arguments->scripts, "Folder of plot-compare.py and plot-mesh-cut.py");
  command->callback([arguments] {
    GenerateOptions options = load_generate_options(arguments->config, arguments->settings);
    if (!arguments->output_folder.empty()) options.output.folder = arguments->output_folder;
    std::filesystem::create_directories(options.output.folder);
    const Log log(&std::cout);
    CompareOptions compare_options;
    compare_options.hybrid_edge_length = arguments->hybrid_edge;
    if (!arguments->only.empty()) {
      compare_options.variants.clear();
      for (const std::string& key : arguments->only)
        compare_options.variants.push_back(variant_from_key(key));
    }
    const CutWindow window = cut_window(compare_wing(options), arguments->cut_position);
    if (arguments->hybrid_surface_only) {
      const SurfaceMesh surface = hybrid_surface(options, compare_options);
      const EdgeStatistics edges = triangle_edge_statistics(surface);
      const std::filesystem::path path =
          options.output.folder / (options.output.name + "_hybrid_surface.vtu");
      write_mesh(to_mixed_mesh(surface), path);
      std::cout << "hybrid surface: " << to_mixed_mesh(surface).face_count() << " triangles, "
                << surface.points.size() << " points, edge length mean " << number(edges.mean)
                << " m, minimum " << number(edges.minimum) << " m, maximum " << number(edges.maximum)
                << " m\nwrote " << path.string() << '\n';
      return;
    }

    const std::vector<CompareRow> rows = run_compare(options, compare_options, log);
    std::cout << '\n' << compare_table(rows);
    const bool has_hybrid =
        std::any_of(rows.begin(), rows.end(), [](const CompareRow& row) { return row.key == "hybrid"; });
    for (const CompareRow& row : rows)
      if (row.key != "hybrid" && has_hybrid)
        std::cout << row.label << ": " << number(100.0 * point_ratio_to_hybrid(row, rows))
                  << " % of the hybrid's points\n";
    std::cout << compare_summary(rows);
    const std::filesystem::path folder = options.output.folder;
    write_compare_csv(folder / "compare.csv", rows);
    write_compare_json(folder / "compare.json", rows);
    log.info("wrote " + (folder / "compare.csv").string() + ", " + (folder / "compare.json").string());
    if (arguments->no_pictures) return;

    const std::filesystem::path scripts = find_plot_scripts("plot-compare.py", arguments->scripts);
    if (scripts.empty()) {
      log.warning("plot scripts not found (set --scripts or MIXMESH_SCRIPTS); no pictures written");
      return;
    }
    const std::string& python = arguments->python;
    if (run_picture_script({python, (scripts / "plot-compare.py").string(), (folder / "compare.csv").string(),
                            "-o", (folder / "compare_bars.png").string()},
                           log))
      log.info("wrote " + (folder / "compare_bars.png").string());
    for (const CompareRow& row : rows) {
      const std::filesystem::path picture = folder / (options.output.name + "_" + row.key + "_cut.png");
      const CutWindow close_up = leading_edge_close_up(window, row.layer_thickness);
      const std::vector<std::string> command = {
          python, (scripts / "plot-mesh-cut.py").string(), row.mesh_file.string(), "--axis", "y", "--position",
          number(window.y), "--window", number(window.x_minimum), number(window.x_maximum),
          number(window.z_minimum), number(window.z_maximum), "--zoom", number(close_up.x_minimum),
          number(close_up.x_maximum), number(close_up.z_minimum), number(close_up.z_maximum), "--size",
          "1800x700", "--title", row.label + ", cut y = " + number(window.y) + " m", "-o", picture.string()};
      if (run_picture_script(command, log))
        log.info("wrote " + picture.string());
    }
  });
}

}  // namespace mixmesh::cli
