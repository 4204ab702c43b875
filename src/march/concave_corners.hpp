// Layer thickness near the concave corners a sheet makes with a wall. Where a wake
// leaves the middle of a blunt base, the base faces and the sheet's faces meet at
// about 90 degrees with the domain on the inside of the angle. Layers of thickness T
// offset from both faces swallow every face within about T of the corner: the base
// half is a trailing-edge thickness high (millimetres), while a wing's layers grow to
// several millimetres and more, so the base's cells flattened against the corner's
// lines and the march stopped them (at layers 9-22 of 28 on random wings, and every
// wing with a base and a wake stopped). The lines near such a corner instead keep
// every layer in a thinner stack that thickens away from the corner.
#pragma once

#include <vector>

#include "front.hpp"

namespace mixmesh::march_detail {

// A front edge shared by a wall face and a sheet face on the same side of the sheet
// that meet at a concave angle of at most 150 degrees (the base of a blunt trailing
// edge with the wake leaving its middle). `size` is the smaller of the two faces'
// heights over the edge: the layers at the corner swallow a face about that high.
struct ConcaveCorner {
  Vector3 start, end;
  double size = 0.0;
};

// The concave corners of the front at the lines' surface points `points`.
std::vector<ConcaveCorner> concave_corners(const Front& front, const std::vector<Vector3>& points);

// Per line, the largest layer thickness near the corners: a quarter of the corner's
// size at the corner plus a quarter of the line's distance from it (the least over the
// corners), so the first line off the corner at distance d reaches d / 2 and no face is
// swallowed (before the outermost step is raised to outer_layer_height times the line's
// shortest front edge, which adds up to a quarter of the corner's size). Lines as far as
// about four times the full stack from a corner are thinned. Infinity where there is no
// corner. (Every line against every corner: a few hundred corners on a wing's base.)
std::vector<double> corner_thickness_limits(const std::vector<ConcaveCorner>& corners,
                                            const std::vector<Vector3>& points);

}  // namespace mixmesh::march_detail
