// The dataset interface nanoflann's k-d trees read points through, over a vector of
// points or of records that hold one, so that each tree needs no adaptor of its own.
#pragma once

#include <cstddef>
#include <vector>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh {

// The position of a record: the record itself for plain points.
struct PointItself {
  const Vector3& operator()(const Vector3& point) const { return point; }
};

// `elements` must outlive the tree; `Position` maps an element to its point.
template <class Element = Vector3, class Position = PointItself>
struct PointCloud {
  const std::vector<Element>* elements = nullptr;
  Position position{};

  std::size_t kdtree_get_point_count() const { return elements->size(); }
  double kdtree_get_pt(std::size_t index, std::size_t axis) const {
    return position((*elements)[index])(static_cast<Eigen::Index>(axis));
  }
  // No precomputed bounding box: nanoflann computes it.
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

}  // namespace mixmesh
