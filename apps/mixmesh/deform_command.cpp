// mixmesh deform MESH --motion MOTION.toml -o OUT: moves the boundary markers named in
// the motion file and the volume mesh with them (ARA or IDW), checks every result.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "commands.hpp"
#include "mixmesh/core/atomic_file.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/deform/ara.hpp"
#include "mixmesh/deform/deform.hpp"
#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/pipeline/deform_options.hpp"

namespace mixmesh::cli {

namespace {

struct DeformArguments {
  std::string mesh;
  std::string motion;
  std::string output;
  bool keep_invalid = false;
  bool verbose = false;
};

std::string format_summary(const deform::QualitySummary& summary) {
  char text[200];
  std::snprintf(
      text, sizeof text, "min scaled Jacobian %.4f, wall-line angle max %.2f deg mean %.2f deg, invalid %zu",
      summary.min_scaled_jacobian, summary.max_wall_angle, summary.mean_wall_angle, summary.invalid_cells);
  return text;
}

std::string histogram(const deform::QualitySummary& summary) {
  std::size_t total = 0;
  for (std::size_t count : summary.sliver_histogram) total += count;
  if (total == 0) return "";
  std::ostringstream text;
  text << "  sliver eta (tetrahedra), bins of 0.0745 from 0:";
  for (std::size_t count : summary.sliver_histogram) text << ' ' << count;
  return text.str();
}

// OUT for one step; OUT's stem + "_0003" + extension for step 3 of a sequence; the
// word "invalid" before the extension for meshes written with --keep-invalid.
std::filesystem::path step_path(const std::filesystem::path& output, int step, int steps, bool valid) {
  const std::string stem = deform::step_stem(output.stem().string(), step, steps);
  const std::filesystem::path path = output.parent_path() / (stem + output.extension().string());
  return valid ? path : kept_invalid_path(path);
}

void write_collection(const std::filesystem::path& file, const std::vector<std::filesystem::path>& steps) {
  write_atomically(file, [&](const std::filesystem::path& temporary) {
    std::ofstream stream(temporary);
    stream << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
    for (std::size_t step = 0; step < steps.size(); ++step)
      stream << "    <DataSet timestep=\"" << step + 1 << "\" part=\"0\" file=\""
             << steps[step].filename().string() << "\"/>\n";
    stream << "  </Collection>\n</VTKFile>\n";
    if (!stream) throw Error(file.string() + ": write failed");
  });
}

void run_deform(const DeformArguments& arguments) {
  const Log log(&std::cout, arguments.verbose ? Log::Level::verbose : Log::Level::normal);
  deform::DeformSetup setup = deform::read_deform_setup(arguments.motion);
  const MixedMesh mesh = read_mesh(arguments.mesh);
  format_from_extension(arguments.output);  // fail on a bad output name before the work
  const std::filesystem::path output(arguments.output);
  const int steps = setup.motion.steps;

  // Every step's points are kept and written at the end, so a step that fails leaves no
  // file of the sequence behind.
  std::vector<std::vector<Vector3>> results;
  std::vector<bool> valid;
  deform::DeformOptions options;
  options.keep_invalid = arguments.keep_invalid;
  auto each_step = [&](int step, const deform::DeformResult& result) {
    std::cout << "step " << step << ": before: " << format_summary(result.before) << '\n'
              << "step " << step << ": after:  " << format_summary(result.after) << '\n';
    char change[160];
    std::snprintf(change, sizeof change,
                  "step %d: wall-line angle change: moving walls %.3f deg at (%.4g, %.4g, "
                  "%.4g), fixed walls %.3f deg\n",
                  step, result.max_wall_angle_change, result.max_wall_angle_change_location.x(),
                  result.max_wall_angle_change_location.y(), result.max_wall_angle_change_location.z(),
                  result.fixed_wall_angle_change);
    std::cout << change;
    const std::string slivers = histogram(result.after);
    if (!slivers.empty()) std::cout << slivers << '\n';
    if (!result.valid)
      std::cout << "step " << step << ": INVALID: " << result.invalid_count
                << " inverted cells (kept: --keep-invalid)\n";
    results.push_back(result.mesh.points);
    valid.push_back(result.valid);
  };
  options.invalid_advice = "--keep-invalid writes it anyway";
  deform::deform_sequence(mesh, setup.motion, *setup.method, log, options, each_step);
  MixedMesh written = mesh;
  std::vector<std::filesystem::path> files;
  for (int step = 1; step <= steps; ++step) {
    written.points = std::move(results[static_cast<std::size_t>(step - 1)]);
    files.push_back(step_path(output, step, steps, valid[static_cast<std::size_t>(step - 1)]));
    write_mesh(written, files.back());
    std::cout << "wrote " << files.back().string() << '\n';
  }
  if (steps > 1 && format_from_extension(output) == MeshFormat::vtu) {
    const std::filesystem::path collection = output.parent_path() / (output.stem().string() + ".pvd");
    write_collection(collection, files);
    std::cout << "wrote " << collection.string() << '\n';
  }
}

}  // namespace

void add_deform_command(CLI::App& application) {
  auto arguments = std::make_shared<DeformArguments>();
  CLI::App* command = application.add_subcommand(
      "deform", "Move boundary markers as a motion file says and deform the mesh with them (ARA or IDW).");
  command->add_option("mesh", arguments->mesh, "Mesh to deform (.vtu, .msh, .su2, .cgns)")->required();
  command->add_option("--motion", arguments->motion, "Motion file (TOML, see docs/deform.md)")->required();
  command
      ->add_option("-o,--output", arguments->output,
                   "Output mesh; a sequence writes OUT_0001.ext, … (and OUT.pvd for .vtu)")
      ->required();
  command->add_flag("--keep-invalid", arguments->keep_invalid,
                    "Write meshes that stay inverted after repair, under a name containing 'invalid'");
  command->add_flag("-v,--verbose", arguments->verbose, "Report the stages of the method");
  command->callback([arguments]() { run_deform(*arguments); });
}

}  // namespace mixmesh::cli
