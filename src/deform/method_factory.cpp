// Methods by name with their options.
#include <algorithm>
#include <array>
#include <cmath>

#include "mixmesh/core/error.hpp"
#include "mixmesh/deform/ara.hpp"
#include "mixmesh/deform/deform.hpp"
#include "mixmesh/deform/idw.hpp"
#include "mixmesh/deform/methods.hpp"

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

}  // namespace

std::unique_ptr<DeformationMethod> make_method(const MethodOptions& options) {
  if (options.name == "ara") return std::make_unique<AraMethod>(options.ara);
  if (options.name == "idw") return std::make_unique<IdwMethod>(options.idw);
  throw Error("unknown deformation method '" + options.name + "' (ara or idw)");
}

}  // namespace mixmesh::deform
