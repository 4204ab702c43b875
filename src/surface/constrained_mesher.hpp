// The CGAL 2D constrained Delaunay mesher the surface stage uses for triangle
// patches (tip cap, isotropic wing): vertices carry their global point index.
#pragma once

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_no_edge_refinement_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include "mixmesh/mesh/mixed_mesh.hpp"

namespace mixmesh::surface_detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexInfo = CGAL::Triangulation_vertex_base_with_info_2<Index, Kernel>;
using VertexBase = CGAL::Delaunay_mesh_vertex_base_2<Kernel, VertexInfo>;
using FaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Triangulation =
    CGAL::Constrained_Delaunay_triangulation_2<Kernel, DataStructure, CGAL::Exact_predicates_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Triangulation>;
using Mesher = CGAL::Delaunay_mesher_no_edge_refinement_2<Triangulation, Criteria>;

}  // namespace mixmesh::surface_detail
