// Reads the deformation keys of config files: motions, method tables, [[deform]] steps
// (deform_options.hpp).
#include "mixmesh/pipeline/deform_options.hpp"

#include <algorithm>
#include <optional>

#include "mixmesh/core/error.hpp"

namespace mixmesh::deform {

namespace {

Vector3 read_vector(config::Section& section, std::string_view key, const Vector3& fallback) {
  std::vector<double> values;
  section.read(key, values);
  if (values.empty()) return fallback;
  if (values.size() != 3) section.fail(key, "'" + std::string(key) + "' must hold three numbers [x, y, z]");
  return {values[0], values[1], values[2]};
}

Body read_body(config::Section& section, std::size_t number) {
  Body body;
  body.name = "body " + std::to_string(number + 1);
  section.read("name", body.name);
  section.read("markers", body.markers);
  if (body.markers.empty()) section.fail("markers", "body '" + body.name + "' needs markers = [\"name\", …]");
  std::string law = "rigid";
  section.read_choice("motion", law, {"rigid", "pitch_plunge", "trajectory", "mode", "surface"});
  body.centre = read_vector(section, "centre", body.centre);
  body.axis = read_vector(section, "axis", body.axis);
  if (law == "rigid") {
    body.law = MotionLaw::rigid;
    section.read("angle", body.angle);
    body.translation = read_vector(section, "translation", body.translation);
  } else if (law == "pitch_plunge") {
    body.law = MotionLaw::pitch_plunge;
    section.read("pitch_amplitude", body.pitch_amplitude);
    section.read("plunge_amplitude", body.plunge_amplitude);
    body.plunge_direction = read_vector(section, "plunge_direction", body.plunge_direction);
    section.read("phase", body.phase);
    section.read("period_steps", body.period_steps, config::Bounds::at_least(1));
  } else if (law == "trajectory") {
    body.law = MotionLaw::trajectory;
    std::filesystem::path file;
    section.read_path("file", file);
    if (file.empty()) section.fail("file", "trajectory body '" + body.name + "' needs file = \"poses.csv\"");
    body.poses = read_trajectory(file, body.centre);
  } else {
    body.law = law == "mode" ? MotionLaw::mode : MotionLaw::surface;
    std::filesystem::path file;
    section.read_path("file", file);
    if (file.empty()) section.fail("file", law + " body '" + body.name + "' needs file = \"nodes.csv\"");
    body.field = read_node_field(file);
    if (body.law == MotionLaw::mode) section.read("scale", body.scale);
  }
  if ((body.law == MotionLaw::rigid || body.law == MotionLaw::pitch_plunge) && body.axis.norm() == 0.0)
    section.fail("axis", "body '" + body.name + "': the rotation axis must not be zero");
  section.finish();
  return body;
}

}  // namespace

Motion read_motion(config::Section& section) {
  Motion motion;
  section.read_choice("method", motion.method, {"ara", "idw"});
  section.read("symmetry", motion.symmetry);
  const bool steps_given = section.has("steps");
  section.read("steps", motion.steps, config::Bounds::at_least(1));
  for (config::Section& body : section.sections("body"))
    motion.bodies.push_back(read_body(body, motion.bodies.size()));
  if (motion.bodies.empty()) section.fail("", "the motion has no [[body]]: nothing would move");
  std::size_t longest_trajectory = 0;
  for (const Body& body : motion.bodies)
    if (body.law == MotionLaw::trajectory)
      longest_trajectory = std::max(longest_trajectory, body.poses.size());
  motion.incremental = longest_trajectory > 0;
  section.read("incremental", motion.incremental);
  if (longest_trajectory > 0) {
    if (!steps_given) motion.steps = static_cast<int>(longest_trajectory);
    for (const Body& body : motion.bodies)
      if (body.law == MotionLaw::trajectory && body.poses.size() < static_cast<std::size_t>(motion.steps))
        section.fail("steps", "body '" + body.name + "' has " + std::to_string(body.poses.size()) +
                                  " trajectory poses for " + std::to_string(motion.steps) + " steps");
  }
  return motion;
}

AraOptions read_ara_options(config::Section& section) {
  AraOptions options;
  section.read_choice("predictor", options.predictor,
                      {{"rotation", Predictor::rotation}, {"translation", Predictor::translation}});
  section.read_choice("smoothing", options.smoothing,
                      {{"rigid_transport", Smoothing::rigid_transport}, {"plain", Smoothing::plain}});
  section.read_choice(
      "solver", options.solver,
      {{"conjugate_gradient", Solver::conjugate_gradient}, {"gauss_seidel", Solver::gauss_seidel}});
  section.read_choice("blend", options.blend_form,
                      {{"exponential", BlendForm::exponential}, {"linear", BlendForm::linear}});
  section.read("gamma", options.gamma, config::Bounds::positive());
  section.read("candidates", options.candidates, config::Bounds::between(1, 256));
  section.read("relaxation", options.relaxation, config::Bounds::between(0.0, 1.0));
  section.read("tolerance", options.tolerance, config::Bounds::positive());
  section.read("max_iterations", options.max_iterations, config::Bounds::non_negative());
  section.read("repair_passes", options.repair_passes, config::Bounds::between(0, 100));
  section.read_path("cache", options.cache_file);
  section.read("cache_geometry", options.cache_geometry);
  section.finish();
  return options;
}

IdwOptions read_idw_options(config::Section& section) {
  IdwOptions options;
  section.read_choice("form", options.form, {{"rotation", IdwForm::rotation}, {"simple", IdwForm::simple}});
  section.read("exponent", options.exponent, config::Bounds::positive());
  section.read("exact", options.exact);
  section.read("tree_tolerance", options.tree_tolerance, config::Bounds::positive());
  if (section.has("translation_exponent")) {
    double value = 1.0;
    section.read("translation_exponent", value, config::Bounds::non_negative());
    options.translation_exponent = value;
  }
  if (section.has("rotation_exponent")) {
    double value = 2.0;
    section.read("rotation_exponent", value, config::Bounds::non_negative());
    options.rotation_exponent = value;
  }
  section.read("reference_count", options.reference_count, config::Bounds::at_least(1));
  section.finish();
  return options;
}

MethodOptions read_method_options(const std::string& name, config::Section* table) {
  MethodOptions options;
  options.name = name;
  if (table == nullptr) return options;
  if (name == "ara")
    options.ara = read_ara_options(*table);
  else
    options.idw = read_idw_options(*table);
  return options;
}

DeformSetup read_deform_setup(const std::filesystem::path& motion_file) {
  const config::Document document = config::Document::load(motion_file);
  config::Section root = document.root();
  DeformSetup setup;
  setup.motion = read_motion(root);
  std::optional<config::Section> options = root.optional_section(setup.motion.method);
  setup.method = make_method(read_method_options(setup.motion.method, options ? &*options : nullptr));
  root.finish();
  return setup;
}

DeformStep read_deform_step(config::Section& section) {
  DeformStep step;
  step.where = section.where();
  section.read("name", step.name);
  if (step.name.empty() || step.name.find_first_of("/\\") != std::string::npos)
    section.fail("name", "a [[deform]] step needs a name for its output files (no slashes)");
  step.motion = read_motion(section);
  std::optional<config::Section> options = section.optional_section(step.motion.method);
  const MethodOptions settings = read_method_options(step.motion.method, options ? &*options : nullptr);
  if (!settings.ara.cache_file.empty())
    options->fail("cache", "no nearest-face cache in a [[deform]] step: every generated mesh differs");
  step.make_method = [settings] { return make_method(settings); };
  section.finish();
  return step;
}

}  // namespace mixmesh::deform
