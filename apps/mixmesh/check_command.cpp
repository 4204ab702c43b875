// mixmesh check MESH: validity and quality of a mesh file, as a table, JSON and
// histograms. Exit status 0 valid, 1 invalid, 2 unreadable file, bad option value or
// an output that could not be written.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "plot_scripts.hpp"
#include "mixmesh/core/atomic_file.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/core/log.hpp"
#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/quality/quality.hpp"
#include "mixmesh/quality/report_format.hpp"

namespace mixmesh::cli {

namespace {

constexpr int exit_invalid = 1;
constexpr int exit_bad_input = 2;
constexpr const char* histogram_script = "plot-quality-histograms.py";

struct CheckArguments {
  std::string mesh;
  std::string json;
  std::string histograms;
  bool quiet = false;
  std::string python = "/usr/bin/python3";
  CheckOptions options;
};

void write_histograms(const std::string& json, const CheckArguments& arguments) {
  const std::filesystem::path folder = find_plot_scripts(histogram_script);
  if (folder.empty())
    throw Error(std::string("cannot find ") + histogram_script +
                " (set MIXMESH_SCRIPTS; looked in share/mixmesh/scripts beside the program and in scripts/ of "
                "its parent folders)");
  const std::filesystem::path script = folder / histogram_script;
  const std::filesystem::path png = arguments.histograms;
  std::filesystem::path data = arguments.json;
  const bool temporary = data.empty();
  if (temporary) {
    data = png;
    data += ".data.json";
    write_text_atomically(data, json);
  }
  try {
    write_atomically(png, [&](const std::filesystem::path& output) {
      run_plot_script({arguments.python, script.string(), data.string(), output.string()});
    });
  } catch (...) {
    if (temporary) std::filesystem::remove(data);
    throw;
  }
  if (temporary) std::filesystem::remove(data);
}

int run_check(const CheckArguments& arguments) {
  Stopwatch read_clock;
  MixedMesh mesh;
  try {
    mesh = read_mesh(arguments.mesh);
  } catch (const Error& error) {
    std::cerr << "mixmesh: error: " << error.what() << '\n';
    return exit_bad_input;
  }
  ReportContext context{arguments.mesh, read_clock.seconds()};
  CheckReport report;
  try {
    report = check_mesh(mesh, arguments.options);
  } catch (const Error& error) {  // options out of range
    std::cerr << "mixmesh: error: " << error.what() << '\n';
    return exit_bad_input;
  }
  if (arguments.quiet)
    std::cout << report.validity.summary() << '\n';
  else
    std::cout << format_table(mesh, report, context);
  const bool outputs = !arguments.json.empty() || !arguments.histograms.empty();
  const std::string json = outputs ? format_json(mesh, report, context) : std::string();
  try {
    if (!arguments.json.empty()) write_text_atomically(arguments.json, json);
    if (!arguments.histograms.empty()) write_histograms(json, arguments);
  } catch (const Error& error) {  // the verdict stands, but what was asked for is missing
    std::cerr << "mixmesh: error: " << error.what() << '\n';
    return exit_bad_input;
  }
  return report.validity.valid() ? 0 : exit_invalid;
}

}  // namespace

void add_check_command(CLI::App& application) {
  auto arguments = std::make_shared<CheckArguments>();
  CLI::App* command = application.add_subcommand(
      "check",
      "Check a mesh (.vtu, .msh, .su2, .cgns): validity (inverted or tangled cells, face conformity, "
      "boundary "
      "markers, unused/duplicate points) and quality per cell type (scaled Jacobian, skewness, aspect ratio, "
      "sliver, non-orthogonality, growth ratio). Exit status: 0 valid, 1 invalid, 2 unreadable file, bad "
      "option value or an output that could not be written.");
  command->add_option("MESH", arguments->mesh, "mesh file to check")->required();
  command
      ->add_option("--json", arguments->json,
                   "also write the whole report (counts, findings with examples, statistics, histograms, "
                   "timings) as JSON to FILE")
      ->type_name("FILE");
  command
      ->add_option("--hist", arguments->histograms,
                   "also draw the quality histograms into FILE.png (needs Python 3 with matplotlib)")
      ->type_name("FILE.png");
  command->add_flag("-q,--quiet", arguments->quiet, "print only the one-line verdict instead of the table");
  command
      ->add_option("--duplicate-tolerance", arguments->options.validity.duplicate_tolerance,
                   "points closer than this fraction of the bounding-box diagonal are duplicates")
      ->capture_default_str();
  command
      ->add_option("--examples", arguments->options.validity.examples,
                   "offending entities listed per finding")
      ->capture_default_str();
  command->add_option("--bins", arguments->options.quality.histogram_bins, "histogram bins per metric")
      ->capture_default_str();
  command->add_flag(
      "--allow-unmarked", [arguments](std::int64_t) { arguments->options.validity.require_markers = false; },
      "boundary faces without a marker are a warning, not an error");
  command->add_option("--python", arguments->python, "Python interpreter for --hist")->capture_default_str();
  command->callback([arguments] {
    const int status = run_check(*arguments);
    if (status != 0) throw CLI::RuntimeError(status);
  });
}

}  // namespace mixmesh::cli
