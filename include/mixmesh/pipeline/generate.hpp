// The whole generator: config → wing (or imported patches) → surface → march → interface → metrics →
// far field → one validated MixedMesh (architecture.md). Each stage reports one
// progress line (stage, elapsed seconds, counts) through the log.
//
//   GenerateOptions options = read_generate_options(document);
//   GenerateResult result = generate(options, log);   // throws mixmesh::Error
//   write_outputs(result, options.output);            // nothing is written if invalid
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "mixmesh/config/config.hpp"
#include "mixmesh/core/log.hpp"
#include "mixmesh/deform/deform.hpp"
#include "mixmesh/farfield/farfield.hpp"
#include "mixmesh/geometry/planform.hpp"
#include "mixmesh/interface/interface_split.hpp"
#include "mixmesh/march/march_layers.hpp"
#include "mixmesh/mesh/mixed_mesh.hpp"
#include "mixmesh/optimize/sliver_removal.hpp"
#include "mixmesh/pipeline/surface_options.hpp"
#include "mixmesh/quality/validity.hpp"

namespace mixmesh {

struct OutputOptions {
  std::filesystem::path folder = ".";          // --output-dir overrides
  std::string name;                            // file stem; default: the config's stem
  std::vector<std::string> formats = {"vtu"};  // vtu, su2, cgns, msh
  // true: one "wall" marker for every wall patch (wing_upper, wing_lower, tip);
  // false: keep the patch names.
  bool merge_wall_markers = true;
};

inline FarFieldOptions anisotropic_farfield() {
  FarFieldOptions options;
  options.sizing = FarFieldSizing::anisotropic;
  return options;
}

struct GenerateOptions {
  SurfaceSetup surface;  // the wing ([wing], [surface]) and/or imported patches
  MarchOptions march;
  InterfaceOptions interface;
  // Anisotropic tetrahedra by default (Wild §II.F; the stage's own default is isotropic,
  // as it can run without the hull's metrics).
  FarFieldOptions farfield = anisotropic_farfield();
  SliverOptions slivers;  // the post-pass over the assembled tetrahedra
  // Times the layers are lowered round a crossing of the hull and the stages from the
  // march to the far field run again (see generate.md, "When the hull intersects
  // itself"); 0: the first crossing is the error.
  int hull_retries = 3;
  OutputOptions output;
  // [[deform]] steps: each deforms the generated mesh (mesh-then-deform pipelines).
  std::vector<deform::DeformStep> deform;
};

// Reads every table of a generate config ([wing], [surface], [march], [interface],
// [farfield], [slivers], [output], [[deform]]); unknown keys and tables are errors with their position.
GenerateOptions read_generate_options(config::Document& document);

// Loads a config file, applies the command line's KEY=VALUE overrides (--set) and
// reads it: what every command that takes a generate config starts with.
GenerateOptions load_generate_options(const std::filesystem::path& config,
                                      const std::vector<std::string>& settings);

struct StageTiming {
  std::string stage;
  double seconds = 0.0;
};

// Wild Table 1's row plus what a user checks first.
struct GenerateReport {
  std::size_t points = 0;
  std::size_t surface_elements = 0;  // wall faces (wing, tip) and wake faces
  std::size_t hexahedra = 0;
  std::size_t tetrahedra = 0;
  std::size_t prisms = 0;
  std::size_t pyramids = 0;
  double min_scaled_jacobian = 0.0;
  MarchReport march;
  int hull_retries = 0;  // times the layers were lowered round a crossing of the hull
  FarFieldResult farfield_summary;  // counts and hull metric lengths (mesh emptied)
  SliverReport slivers;
  std::vector<StageTiming> stages;
  double seconds = 0.0;
};

struct GenerateResult {
  MixedMesh mesh;
  ValidityReport validity;
  GenerateReport report;
};

// Runs every stage and validates the assembled mesh (result.validity); throws
// mixmesh::Error naming the stage when a stage fails.
GenerateResult generate(const GenerateOptions& options, const Log& log);

// The stages after the surface, on a given surface mesh (the hybrid baseline of
// `mixmesh compare` marches an all-triangle surface this way). options.surface is
// not used.
GenerateResult generate_from_surface(const SurfaceMesh& surface, const GenerateOptions& options,
                                     const Log& log);

// The files of options.formats in options.folder, each written atomically. Returns
// the paths written. Throws, writing nothing, when the mesh is invalid.
std::vector<std::filesystem::path> write_outputs(const GenerateResult& result, const OutputOptions& options);

// Mesh-then-deform: every [[deform]] step of `options` run on the generated (valid)
// mesh, each mesh checked; nothing is written (the points of every deformed mesh are
// kept in memory until then: 24 bytes per point and mesh). Throws mixmesh::Error naming the step
// (config file:line and name) when a step fails.
struct DeformedMesh {
  std::string stem;  // NAME_STEPNAME, or NAME_STEPNAME_0003 for step 3 of a sequence
  std::string step_name;
  int index = 1;  // step `index` of the `steps` of its motion
  int steps = 1;
  std::vector<Vector3> points;
  double largest_displacement = 0.0;
  // Figures of the checked mesh (deform::DeformResult): smallest scaled Jacobian,
  // largest change of a moving wall's grid-line angle (degrees), time of the step.
  double min_scaled_jacobian = 0.0;
  double max_wall_angle_change = 0.0;
  double seconds = 0.0;
};
std::vector<DeformedMesh> run_deform_steps(const GenerateResult& result, const GenerateOptions& options,
                                           const Log& log);
// The deformed meshes in every output format, each file written atomically. Returns
// the paths written.
std::vector<std::filesystem::path> write_deformed(const GenerateResult& result,
                                                  const std::vector<DeformedMesh>& meshes,
                                                  const OutputOptions& options);

// The first offenders of each failed validity check, one per line, for error messages.
std::string validity_details(const ValidityReport& validity);

// "points 456212  surface 32826  hexahedra ..." (Table 1 order), and the same as TOML
// for batch summaries: the generated mesh's figures, its stage times and, when the
// config has [[deform]] steps, one [[deform]] table per deformed mesh (with the count
// and the smallest scaled Jacobian over them as top-level keys).
std::string table_row(const GenerateReport& report);
void write_report(const std::filesystem::path& path, const GenerateReport& report,
                  const std::vector<DeformedMesh>& deformed = {});

}  // namespace mixmesh
