// The deformation keys of config files: a motion file (the motion, and the [ara] or
// [idw] table of the method it names) and the [[deform]] steps of a generation config.
// Every error names file:line:column. The keys themselves are documented in
// docs/deform.md.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "mixmesh/config/config.hpp"
#include "mixmesh/deform/deform.hpp"
#include "mixmesh/deform/methods.hpp"
#include "mixmesh/deform/motion.hpp"

namespace mixmesh::deform {

// Reads a motion from a table (a motion file's root, or a [[deform]] step of a
// generation config); CSV files it names are resolved against the config's folder.
// Errors name file:line:column. Does not call finish() on `section`, so a caller can
// read the method's options (the [ara] or [idw] table) from it afterwards;
// read_deform_setup (below) does both for a motion file.
Motion read_motion(config::Section& section);

// Reads gamma, predictor, smoothing, solver, blend, candidates, relaxation, tolerance,
// max_iterations, repair_passes, cache and cache_geometry from an [ara] table.
AraOptions read_ara_options(config::Section& section);
// Reads form, exponent, exact, tree_tolerance, translation_exponent, rotation_exponent
// and reference_count from an [idw] table.
IdwOptions read_idw_options(config::Section& section);
// The options of method `name` ("ara" or "idw"; read_motion has checked it) from its
// table, or its defaults when `table` is null.
MethodOptions read_method_options(const std::string& name, config::Section* table);

// A motion file: the motion, and the method it names built from its [ara]/[idw] table.
// Unknown keys are errors with their file:line:column.
struct DeformSetup {
  Motion motion;
  std::unique_ptr<DeformationMethod> method;
};
DeformSetup read_deform_setup(const std::filesystem::path& motion_file);

// A [[deform]] step (DeformStep, deform.hpp) of a generation config. Unknown keys are
// errors with their file:line:column; an ARA `cache` file is refused (every generated
// mesh differs).
DeformStep read_deform_step(config::Section& section);

}  // namespace mixmesh::deform
