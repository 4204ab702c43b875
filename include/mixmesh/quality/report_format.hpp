// The check report as people and programs read it: a text table and JSON.
//
// JSON layout (numbers that are not finite are written as null):
//   { "file", "valid", "summary",
//     "timings": { "read_seconds", "validity_seconds", "quality_seconds" },
//     "counts": { "points", "tetrahedron", "pyramid", "prism", "hexahedron",
//                 "triangle_faces", "quad_faces", "planar_triangles", "planar_quads",
//                 "boundary_edges", "interior_faces", "boundary_faces" },
//     "total_volume", "planar",
//     "findings": [ { "check", "description", "severity", "count",
//                     "examples": [ { "entity", "index", "location": [x, y, z], "detail" } ] } ],
//     "quality": [ { "metric", "entity", "count", "non_finite", "min", "max", "mean",
//                    "percentiles": { "1", "5", "50", "95", "99" },
//                    "histogram": { "min", "max", "counts": [ … ] } } ] }
#pragma once

#include <string>

#include "mixmesh/quality/quality.hpp"

namespace mixmesh {

struct ReportContext {
  std::string file;
  double read_seconds = 0.0;
};

std::string format_table(const MixedMesh& mesh, const CheckReport& report, const ReportContext& context);
std::string format_json(const MixedMesh& mesh, const CheckReport& report, const ReportContext& context);

}  // namespace mixmesh
