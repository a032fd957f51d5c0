#pragma once
// Inside/outside of a query point with respect to a triangle surface: the
// angle-weighted pseudo-normal test for closed manifold surfaces (Bærentzen
// & Aanæs 2005) and the generalized winding number for open or non-manifold
// ones (Jacobson et al. 2013), with the tree approximation of Barill et al.
// 2018. Plain code, no CGAL.

#include <array>
#include <vector>

#include "hqview/boundary/surface_distance.h"
#include "hqview/mesh/hex_mesh.h"

namespace hq {

// Pseudo-normals of an outward-oriented closed manifold triangle surface.
struct PseudoNormals {
  std::vector<Vec3> face;    // per triangle, unit
  std::vector<Vec3> edge;    // per triangle corner k: the edge (t[k], t[k+1]); sum of the adjacent face normals
  std::vector<Vec3> vertex;  // per point, angle-weighted sum of incident face normals
};
PseudoNormals compute_pseudo_normals(const TriSurface& surface);

// +1 when `query` lies outside (on the side the pseudo-normal of the closest
// feature points to), -1 inside, 0 when it lies on the surface.
// `uncertain` is set when the offset is almost tangent to the pseudo-normal.
int pseudo_normal_sign(const TriSurface& surface, const PseudoNormals& normals, const Vec3& query,
                       const ClosestPoint& closest, bool& uncertain);

// A bounding-volume hierarchy carrying each node's dipole (area-weighted
// centre and area vector) for fast winding numbers.
struct WindingTree {
  struct Node {
    Vec3 centre;       // area-weighted centroid of the node's triangles
    Vec3 area_vector;  // sum of the triangles' area vectors (n * area)
    // Second-order term: sum over triangles of area_vector_t (centroid_t - centre)^T, row-major 3x3.
    std::array<double, 9> moment{};
    double radius = 0;           // max distance from `centre` to a vertex of the node
    Index first = 0, count = 0;  // triangles order[first, first + count) when a leaf
    Index left = kNoIndex, right = kNoIndex;
  };
  std::vector<Node> nodes;   // nodes[0] is the root
  std::vector<Index> order;  // triangle ids, leaf ranges contiguous
};
WindingTree build_winding_tree(const TriSurface& surface);

// Generalized winding number of `surface` at `query` (1 inside a closed
// outward surface, 0 outside). Exact solid angles near the query; for nodes
// farther than beta * radius, the dipole expansion to second order (Barill
// et al. 2018, eq. 9-10).
double winding_number(const TriSurface& surface, const WindingTree& tree, const Vec3& query, double beta = 3.0);

// The winding number as the sign needs it: beta = 2 (worst error ~0.07 on a
// sphere, measured), evaluated again with beta = 4 (~0.02) when the first
// value is within 0.25 of 1/2. About half the cost of beta = 3 everywhere.
double winding_number_for_sign(const TriSurface& surface, const WindingTree& tree, const Vec3& query);

}  // namespace hq
