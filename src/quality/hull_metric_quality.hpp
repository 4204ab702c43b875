// The far-field tetrahedra on the hull judged in the metric of the cell beneath each
// (Wild §II.D–F): what `measure_quality` reports as metric_edge_length and
// metric_shape of "hull tetrahedra".
#pragma once

#include <vector>

#include "mixmesh/mesh/face_connectivity.hpp"

namespace mixmesh::quality_detail {

struct HullMetricValues {
  std::vector<double> edge_lengths;  // the six edges of each (tetrahedron, cell beneath) pair
  std::vector<double> shapes;        // the mean ratio of each pair's tetrahedron in that metric
};

HullMetricValues hull_metric_values(const MixedMesh& mesh, const FaceConnectivity& faces);

}  // namespace mixmesh::quality_detail
