// The deformation methods by name, with their options.
#pragma once

#include <memory>
#include <string>

#include "mixmesh/deform/ara.hpp"
#include "mixmesh/deform/idw.hpp"

namespace mixmesh::deform {

// A method and its options: `name` ("ara" or "idw") says which of the two applies.
struct MethodOptions {
  std::string name = "ara";
  AraOptions ara;
  IdwOptions idw;
};

// A fresh method; mixmesh::Error for an unknown name.
std::unique_ptr<DeformationMethod> make_method(const MethodOptions& options);

}  // namespace mixmesh::deform
