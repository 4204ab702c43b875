// Mesh-then-deform: the [[deform]] steps of a generation config on the generated mesh.
#include <cstdio>
#include <sstream>

#include "mixmesh/core/error.hpp"
#include "mixmesh/io/mesh_io.hpp"
#include "mixmesh/pipeline/generate.hpp"

namespace mixmesh {

std::vector<std::filesystem::path> run_deform_steps(const GenerateResult& result, const GenerateOptions& options,
                                                    const Log& log) {
  std::vector<std::filesystem::path> written;
  if (options.deform.empty()) return written;
  if (!result.validity.valid())
    throw Error("deform: the generated mesh is invalid, no deformation run: " + result.validity.summary());
  for (const deform::DeformStep& step : options.deform) {
    const std::unique_ptr<deform::DeformationMethod> method = step.make_method();
    std::vector<std::vector<Vector3>> points;
    deform::deform_sequence(result.mesh, step.motion, *method, log, {},
                            [&](int index, const deform::DeformResult& deformed) {
                              std::ostringstream line;
                              line << "deform " << step.name << " step " << index << '/' << step.motion.steps
                                   << ": min scaled Jacobian " << deformed.after.min_scaled_jacobian
                                   << ", wall-line angle max " << deformed.after.max_wall_angle << " deg";
                              log.info(line.str());
                              points.push_back(deformed.mesh.points);
                            });
    // Written only once every mesh of the step is known to be valid.
    MixedMesh moved = result.mesh;
    for (std::size_t index = 0; index < points.size(); ++index) {
      moved.points = std::move(points[index]);
      std::string stem = options.output.name + "_" + step.name;
      if (points.size() > 1) {
        char suffix[32];
        std::snprintf(suffix, sizeof suffix, "_%04zu", index + 1);
        stem += suffix;
      }
      for (const std::string& format : options.output.formats) {
        written.push_back(options.output.folder / (stem + "." + format));
        write_mesh(moved, written.back());
      }
    }
  }
  return written;
}

}  // namespace mixmesh
