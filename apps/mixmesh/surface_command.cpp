// mixmesh surface CONFIG -o surface.vtu: the mixed surface mesh from the [wing] and
// [surface] tables of a config file (generated wing and/or imported patches), written
// as boundary faces (markers wing_lower, wing_upper, tip, wake, base, imported names).
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "mixmesh/config/config.hpp"
#include "mixmesh/core/log.hpp"
#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/pipeline/surface_options.hpp"
#include "mixmesh/surface/surface_conversion.hpp"

namespace mixmesh::cli {

namespace {

struct SurfaceArguments {
  std::filesystem::path config;
  std::filesystem::path output = "surface.vtu";
  bool quiet = false;
};

void run_surface(const SurfaceArguments& arguments) {
  const Log log(&std::cout, arguments.quiet ? Log::Level::quiet : Log::Level::normal);
  config::Document document = config::Document::load(arguments.config);
  config::Section root = document.root();
  const SurfaceSetup setup = read_surface_setup(root);
  const Stopwatch stopwatch;
  const SurfaceMesh surface = build_surface(setup);
  const MixedMesh mesh = to_mixed_mesh(surface);
  std::ostringstream summary;
  summary << "surface: " << mesh.points.size() << " points, " << mesh.face_count(FaceType::quad) << " quads, "
          << mesh.face_count(FaceType::triangle) << " triangles in " << stopwatch.seconds() << " s";
  log.info(summary.str());
  write_mesh(mesh, arguments.output);
  log.info("wrote " + arguments.output.string());
}

}  // namespace

void add_surface_command(CLI::App& application) {
  auto arguments = std::make_shared<SurfaceArguments>();
  CLI::App* command = application.add_subcommand(
      "surface", "Generate the mixed surface mesh (structured wing and wake, triangulated tip) of a wing");
  command->add_option("config", arguments->config, "Config file with [wing] and/or [surface] tables")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("-o,--output", arguments->output, "Output mesh (.vtu, .msh, .su2)");
  command->add_flag("-q,--quiet", arguments->quiet, "Print nothing but errors");
  command->callback([arguments]() { run_surface(*arguments); });
}

}  // namespace mixmesh::cli
