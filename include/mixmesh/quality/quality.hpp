// measure_quality: distributions of cell quality metrics over a mesh, per cell type.
//
// Entries (metric, entity):
//   scaled_jacobian, skewness, aspect_ratio   per cell type (cell_quality.hpp)
//   sliver                                    tetrahedra
//   non_orthogonality                         "interior faces", "boundary faces":
//       OpenFOAM's angle in degrees between the owner→neighbour centroid vector
//       (owner→face centre on the boundary) and the face area vector
//   growth_ratio                              prisms, hexahedra stacked in columns:
//       height of a cell / height of the cell below it, where the top face of the
//       lower cell (prism face 3-5-4, hex face 4-5-6-7) is the bottom face of the
//       upper one; reported under the type of the upper cell
//   metric_edge_length, metric_shape          "hull tetrahedra": every far-field
//       tetrahedron sharing a triangle with a cell the far field was matched to (a
//       tetrahedron on an interface split point, a cap's pyramid, a prism), in that
//       cell's metric (Wild eq. 11-12): its six edge lengths (1 in a unit mesh) and its
//       mean ratio 12 (3V)^(2/3) / sum of squared edges (1 for the regular tetrahedron),
//       once per such triangle. A stretched tetrahedron that follows the cell beneath it
//       measures as regular, where the scaled Jacobian calls it bad.
// Planar meshes give the same entries for triangles and quads ("interior edges",
// "boundary edges" for the non-orthogonality). Non-finite values (NaN coordinates,
// zero-length edges) are counted apart and left out of the statistics.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "mixmesh/mesh/face_connectivity.hpp"
#include "mixmesh/mesh/mixed_mesh.hpp"
#include "mixmesh/quality/validity.hpp"

namespace mixmesh {

struct QualityOptions {
  int histogram_bins = 20;
};

inline constexpr std::array<double, 5> statistics_percentiles = {1, 5, 50, 95, 99};

struct Statistics {
  std::size_t count = 0;       // finite values
  std::size_t non_finite = 0;  // NaN or infinite values, not in the figures below
  double min = 0.0;
  double max = 0.0;
  double mean = 0.0;
  // At statistics_percentiles, linear interpolation between order statistics.
  std::array<double, 5> percentiles{};
  // histogram_bins equal bins over [min, max]; the last bin includes max.
  std::vector<std::size_t> histogram;
};

Statistics compute_statistics(std::vector<double> values, int histogram_bins);

struct QualityEntry {
  std::string metric;  // "scaled_jacobian", "skewness", …
  std::string entity;  // "hexahedron", "interior faces", …
  Statistics statistics;
};

struct QualityReport {
  std::vector<QualityEntry> entries;
  const QualityEntry* find(const std::string& metric, const std::string& entity) const;
};

QualityReport measure_quality(const MixedMesh& mesh, const QualityOptions& options = {});

// Per interior face of `faces.interior` (same order), the non-orthogonality in degrees.
std::vector<double> non_orthogonality(const MixedMesh& mesh, const FaceConnectivity& faces);

// Validity and quality together, matching the faces once; what `mixmesh check` runs.
struct CheckOptions {
  ValidityOptions validity;
  QualityOptions quality;
};

struct CheckReport {
  ValidityReport validity;
  QualityReport quality;  // empty when node indices are out of range
  double validity_seconds = 0.0;
  double quality_seconds = 0.0;
};

CheckReport check_mesh(const MixedMesh& mesh, const CheckOptions& options = {});

}  // namespace mixmesh
