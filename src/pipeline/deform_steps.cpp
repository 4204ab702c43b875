// Mesh-then-deform: the [[deform]] steps of a generation config on the generated mesh.
#include <algorithm>
#include <sstream>

#include "mixmesh/core/error.hpp"
#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/pipeline/generate.hpp"

namespace mixmesh {

std::vector<DeformedMesh> run_deform_steps(const GenerateResult& result, const GenerateOptions& options,
                                           const Log& log) {
  std::vector<DeformedMesh> meshes;
  if (options.deform.empty()) return meshes;
  if (!result.validity.valid())
    throw Error("deform: the generated mesh is invalid, no deformation run: " + result.validity.summary());
  for (const deform::DeformStep& step : options.deform) {
    const std::unique_ptr<deform::DeformationMethod> method = step.make_method();
    const std::string stem = options.output.name + "_" + step.name;
    try {
      deform::deform_sequence(
          result.mesh, step.motion, *method, log, {}, [&](int index, const deform::DeformResult& deformed) {
            DeformedMesh mesh;
            mesh.stem = deform::step_stem(stem, index, step.motion.steps);
            mesh.step_name = step.name;
            mesh.index = index;
            mesh.steps = step.motion.steps;
            mesh.points = deformed.mesh.points;
            mesh.min_scaled_jacobian = deformed.after.min_scaled_jacobian;
            mesh.max_wall_angle_change = deformed.max_wall_angle_change;
            mesh.seconds = deformed.seconds;
            for (std::size_t node = 0; node < mesh.points.size(); ++node)
              mesh.largest_displacement =
                  std::max(mesh.largest_displacement, (mesh.points[node] - result.mesh.points[node]).norm());
            std::ostringstream line;
            line << "deform " << step.name << " step " << index << '/' << step.motion.steps
                 << ": largest displacement " << mesh.largest_displacement << " m, min scaled Jacobian "
                 << deformed.after.min_scaled_jacobian << ", wall-line angle max "
                 << deformed.after.max_wall_angle << " deg";
            log.info(line.str());
            meshes.push_back(std::move(mesh));
          });
    } catch (const Error& error) {
      throw Error(step.where + ": [[deform]] '" + step.name + "': " + error.what());
    }
  }
  return meshes;  // (read_generate_options refuses steps that would write one file twice)
}

std::vector<std::filesystem::path> write_deformed(const GenerateResult& result,
                                                  const std::vector<DeformedMesh>& meshes,
                                                  const OutputOptions& options) {
  std::vector<std::filesystem::path> written;
  if (meshes.empty()) return written;
  std::filesystem::create_directories(options.folder);
  MixedMesh moved = result.mesh;
  for (const DeformedMesh& mesh : meshes) {
    moved.points = mesh.points;
    for (const std::string& format : options.formats) {
      written.push_back(options.folder / (mesh.stem + "." + format));
      write_mesh(moved, written.back());
    }
  }
  return written;
}

}  // namespace mixmesh
