#pragma once
// Reference surfaces built in code for the boundary and UV tests.

#include <functional>

#include "hqview/mesh/hex_mesh.h"

namespace hq::test {

// The box [lo, hi]^3, each face an n x n grid of quads split in two,
// points shared, outward counter-clockwise triangles.
TriSurface triangulated_box(Vec3 lo, Vec3 hi, int n);
// An icosahedron subdivided `level` times, projected on the sphere of
// `radius` about `centre`; outward counter-clockwise.
TriSurface icosphere(int level, double radius = 1.0, Vec3 centre = {});
// The triangles of `s` whose centroid fails `remove` (points kept).
TriSurface remove_triangles(const TriSurface& s, const std::function<bool(const Vec3& centroid)>& remove);
// `b` appended to `a` (b's ids shifted).
TriSurface append(const TriSurface& a, const TriSurface& b);
// An n x n x n hex grid of [-1,1]^3 mapped radially onto the ball whose
// boundary radius in direction u is radius(u) (u a unit vector).
HexMesh hex_ball(int n, const std::function<double(const Vec3& u)>& radius);
// The boundary of a 7 x 3 x 1 slab of unit voxels with 3 voxel holes: a
// closed manifold surface of genus 3 (outward counter-clockwise).
TriSurface genus3_slab();
// The cube [-1, 1]^3's faces, each an n x n grid of quads, projected to the
// sphere of `radius` about the origin (corners shared), counter-clockwise
// seen from outside: 8 vertices of valence 3, 6 grids.
Mesh quad_cube_sphere(int n, double radius = 1.0);

}  // namespace hq::test
