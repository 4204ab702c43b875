// Methods by name, and motion files with their method table.
#include <algorithm>
#include <array>
#include <cmath>

#include "mixmesh/config/config.hpp"
#include "mixmesh/core/error.hpp"
#include "mixmesh/deform/ara.hpp"
#include "mixmesh/deform/deform.hpp"
#include "mixmesh/deform/idw.hpp"

namespace mixmesh::deform {

namespace {

// The IDW method behind the framework's interface: moving bodies and fixed markers
// become IdwBody sets, symmetry nodes become IdwSymmetryPlane constraints.
class IdwMethod : public DeformationMethod {
 public:
  explicit IdwMethod(IdwOptions options) : options_(std::move(options)) {}
  std::string name() const override { return "idw"; }

  std::vector<Vector3> move(const MixedMesh& mesh, const BoundaryMotion& boundary, const Log& log) override {
    IdwInput input;
    std::vector<Index> volume_nodes;
    int body_count = 0;
    for (int body : boundary.body) body_count = std::max(body_count, body + 1);
    input.bodies.resize(static_cast<std::size_t>(body_count) + 1);
    IdwBody& fixed = input.bodies.back();
    fixed.name = "fixed";
    fixed.moving = false;
    for (int body = 0; body < body_count; ++body)
      input.bodies[static_cast<std::size_t>(body)].name = "body " + std::to_string(body + 1);
    // Per mesh node: its body set (the fixed set last) and its index there.
    std::vector<int> node_set(mesh.points.size(), -1);
    std::vector<Index> node_slot(mesh.points.size(), -1);
    for (std::size_t node = 0; node < mesh.points.size(); ++node) {
      if (boundary.roles[node] == NodeRole::prescribed) {
        node_set[node] = boundary.body[node] < 0 ? body_count : boundary.body[node];
        node_slot[node] = static_cast<Index>(input.bodies[static_cast<std::size_t>(node_set[node])].positions.size());
      }
      if (boundary.roles[node] != NodeRole::prescribed) {
        volume_nodes.push_back(static_cast<Index>(node));
        input.volume_points.push_back(mesh.points[node]);
        continue;
      }
      const int body = boundary.body[node];
      if (body < 0) {
        fixed.positions.push_back(mesh.points[node]);
        continue;
      }
      IdwBody& target = input.bodies[static_cast<std::size_t>(body)];
      target.positions.push_back(mesh.points[node]);
      target.displacements.push_back(boundary.displacement[node]);
      const Vector3& turn = boundary.rotation[node];
      target.rotations.push_back(
          Eigen::AngleAxisd(turn.norm(), turn.norm() > 0.0 ? Vector3(turn.normalized()) : Vector3::UnitZ())
              .toRotationMatrix());
    }
    // The boundary faces whose nodes all lie on one set: its surface, for the distances
    // of the rotation form's ψ.
    auto add_face = [&](const Index* nodes, int count) {
      const int set = node_set[static_cast<std::size_t>(nodes[0])];
      if (set < 0) return;
      std::array<Index, 4> face{-1, -1, -1, -1};
      for (int k = 0; k < count; ++k) {
        const std::size_t node = static_cast<std::size_t>(nodes[k]);
        if (node_set[node] != set) return;
        face[static_cast<std::size_t>(k)] = node_slot[node];
      }
      input.bodies[static_cast<std::size_t>(set)].faces.push_back(face);
    };
    for (FaceType type : {FaceType::triangle, FaceType::quad}) {
      const FaceBlock& block = mesh.faces(type);
      const int stride = type == FaceType::triangle ? 3 : 4;
      for (std::size_t first = 0; first + static_cast<std::size_t>(stride) <= block.nodes.size(); first += stride)
        add_face(block.nodes.data() + first, stride);
    }
    for (std::size_t first = 0; first + 2 <= mesh.boundary_edges.nodes.size(); first += 2)
      add_face(mesh.boundary_edges.nodes.data() + first, 2);
    input.bodies.erase(std::remove_if(input.bodies.begin(), input.bodies.end(),
                                      [](const IdwBody& body) { return body.positions.empty(); }),
                       input.bodies.end());
    // One plane per distinct (normal, offset) of the sliding nodes.
    for (std::size_t node = 0; node < mesh.points.size(); ++node) {
      if (boundary.roles[node] != NodeRole::sliding) continue;
      const Vector3& normal = boundary.slide_normal[node];
      const double offset = normal.dot(mesh.points[node]);
      const bool known =
          std::any_of(input.symmetry_planes.begin(), input.symmetry_planes.end(), [&](const auto& plane) {
            return (plane.normal - normal).norm() < 1e-9 &&
                   std::abs(plane.offset - offset) < 1e-9 * (1.0 + std::abs(offset));
          });
      if (!known) input.symmetry_planes.push_back({normal, offset});
    }
    const IdwResult result = idw_deform(input, options_);
    std::vector<Vector3> points = mesh.points;
    for (std::size_t slot = 0; slot < volume_nodes.size(); ++slot)
      points[static_cast<std::size_t>(volume_nodes[slot])] += result.displacements[slot];
    for (std::size_t node = 0; node < points.size(); ++node)
      if (boundary.roles[node] == NodeRole::prescribed) points[node] += boundary.displacement[node];
    log.detail("idw: " + std::to_string(volume_nodes.size()) + " nodes moved by " +
               std::to_string(input.bodies.size()) + " boundary sets");
    return points;
  }

 private:
  IdwOptions options_;
};

IdwOptions read_idw_options(config::Section& section) {
  IdwOptions options;
  std::string form = "rotation";
  section.read_choice("form", form, {"rotation", "simple"});
  options.form = form == "rotation" ? IdwForm::rotation : IdwForm::simple;
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

}  // namespace

std::unique_ptr<DeformationMethod> make_method(const std::string& name, config::Section* options) {
  if (name == "ara") return make_ara_method(options);
  if (name == "idw") return std::make_unique<IdwMethod>(options ? read_idw_options(*options) : IdwOptions{});
  throw Error("unknown deformation method '" + name + "' (ara or idw)");
}

DeformSetup read_deform_setup(const std::filesystem::path& motion_file) {
  const config::Document document = config::Document::load(motion_file);
  config::Section root = document.root();
  DeformSetup setup;
  setup.motion = read_motion(root);
  std::optional<config::Section> options = root.optional_section(setup.motion.method);
  setup.method = make_method(setup.motion.method, options ? &*options : nullptr);
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
  if (step.motion.method == "ara") {
    const AraOptions settings = options ? read_ara_options(*options) : AraOptions{};
    if (!settings.cache_file.empty())
      options->fail("cache", "no nearest-face cache in a [[deform]] step: every generated mesh differs");
    step.make_method = [settings] { return std::make_unique<AraMethod>(settings); };
  } else {
    const IdwOptions settings = options ? read_idw_options(*options) : IdwOptions{};
    step.make_method = [settings] { return std::make_unique<IdwMethod>(settings); };
  }
  section.finish();
  return step;
}

}  // namespace mixmesh::deform
