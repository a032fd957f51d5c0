#pragma once
// A surface mesh's faces as the views and the viewer draw them: every quad
// and triangle is a face of the drawn "boundary" (a surface is all
// boundary), so boundary_polygons() and boundary_edges_all_kinds() give a
// surface mesh's faces and edges as they give a volume mesh's boundary.

#include "hqview/mesh/mesh.h"
#include "hqview/mesh/topology.h"

namespace hq {

// Fills topology.boundary_quads_non_hex / boundary_quad_non_hex_cells with
// mesh.quads (cell ids 0..#quads-1, corners as read) and
// boundary_triangles / boundary_triangle_cells with mesh.triangles (cell
// ids #quads..), each in cell order; a quad with a repeated corner is kept
// (drawn as the triangle it is). Nothing for a volume mesh. Called after
// summarize_mesh, so that report.json's mesh.num_boundary_faces keeps its
// meaning (0 on a surface mesh); leaves every other table as it is.
void add_surface_faces_as_boundary(const Mesh& mesh, Topology& topology);

}  // namespace hq
