// validate: is a MixedMesh usable by a flow solver?
//
//   volume meshes  cells with non-positive volume or tangled (a negative corner or
//                  face-centre sub-tetrahedron), node indices out of range, NaN
//                  coordinates, faces on three or more cells, interior faces wound the
//                  same way by both cells, a triangle against a quad, cracks (boundary
//                  edges not on exactly two boundary faces), boundary faces without a
//                  marker, markers on faces that are not boundary faces, unused and
//                  duplicate points
//   planar meshes  the same in the z = 0 plane: positive signed area, convex corners,
//                  edges on at most two cells and wound oppositely, boundary edges
//                  tagged, points in the plane
//
// Every problem is a Finding with a count and the first few offending entities.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh {

struct ValidityOptions {
  // Two points closer than this fraction of the bounding-box diagonal are duplicates.
  double duplicate_tolerance = 1e-12;
  // Planar meshes: points farther than this fraction of the diagonal from z = 0 are
  // reported.
  double planar_tolerance = 1e-9;
  // How many offending entities each finding lists.
  std::size_t examples = 5;
  // Boundary faces without a marker make the mesh invalid (a solver needs a boundary
  // condition on every face); when false they are a warning.
  bool require_markers = true;
};

// One offending entity: what it is ("hexahedron", "quad face", "point", "edge"),
// its index in its block (the smaller node of an edge), where it is (cell, face or
// edge centre, or the point) and which part of it is meant ("face 2" of a cell,
// "nodes 4-9" of an edge; empty for whole entities).
struct Offender {
  std::string entity;
  std::size_t index = 0;
  Vector3 location = Vector3::Zero();
  std::string detail;
};

struct Finding {
  enum class Severity { error, warning };
  std::string check;        // stable identifier, e.g. "non_positive_volume"
  std::string description;  // what the count counts, for people
  Severity severity = Severity::error;
  std::size_t count = 0;
  std::vector<Offender> examples;
};

struct ValidityReport {
  // Every check that ran, in a fixed order, with count 0 where nothing was found.
  std::vector<Finding> findings;
  std::size_t points = 0;
  std::size_t interior_faces = 0;  // interior edges for planar meshes
  std::size_t boundary_faces = 0;  // boundary edges for planar meshes
  double total_volume = 0.0;       // total area for planar meshes
  bool planar = false;

  // No error finding has a non-zero count.
  bool valid() const;
  // "valid: 0 errors, 1 warning (12 unused points)" or "INVALID: 3 non-positive …".
  std::string summary() const;
  // The finding with this identifier, or nullptr.
  const Finding* find(const std::string& check) const;
};

ValidityReport validate(const MixedMesh& mesh, const ValidityOptions& options = {});

}  // namespace mixmesh
