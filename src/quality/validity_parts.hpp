// The parts validate() is built from, shared by the volume and the planar checks and
// by check_mesh (which matches the faces once for validity and quality).
#pragma once

#include <string>
#include <vector>

#include "mixmesh/mesh/face_connectivity.hpp"
#include "mixmesh/quality/validity.hpp"

namespace mixmesh::quality_detail {

Finding make_finding(const std::string& check, const std::string& description,
                     Finding::Severity severity = Finding::Severity::error);

// Counts one offender and keeps it as an example while fewer than `examples` are kept.
void add_offender(Finding& finding, std::size_t examples, std::string entity, std::size_t index,
                  const Vector3& location, std::string detail = {});

// Throws mixmesh::Error for option values out of range, before any work is done.
void check_options(const ValidityOptions& options);

// Cells and boundary faces (edges for planar meshes) whose node indices lie outside
// the point array; when the count is non-zero nothing else can be checked safely.
Finding check_node_indices(const MixedMesh& mesh, const ValidityOptions& options);

// NaN/infinite coordinates, unused points (used[p] == 0) and duplicate points.
void check_points(const MixedMesh& mesh, const std::vector<char>& used, const ValidityOptions& options,
                  std::vector<Finding>& findings);

// Volume checks given the matched faces (indices must be in range).
ValidityReport validate_volume(const MixedMesh& mesh, const FaceConnectivity& faces,
                               const ValidityOptions& options);

ValidityReport validate_planar(const MixedMesh& mesh, const ValidityOptions& options);

// Centre of a cell face, for locating offenders.
Vector3 face_centre(const MixedMesh& mesh, const CellFace& face);

}  // namespace mixmesh::quality_detail
