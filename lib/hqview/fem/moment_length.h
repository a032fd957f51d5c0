#pragma once
// The moments of a hex mesh's volume, and a length from them that does not
// depend on how the mesh is placed.
//   volume_moments: V, the centroid c, the second central moments
//     C = int (x - c)(x - c)^T dV / V and the third int (x - c)_i (x - c)_j
//     (x - c)_k dV / V. The integrals: the trilinear map of each hex by
//     2 x 2 x 2 Gauss-Legendre (exact for a parallelepiped's volume, centroid
//     and C, det J with its sign), summed over fixed chunks of hexes (the same
//     bits for any thread count), the centroid first (about the mesh's first
//     point: no cancellation far from the origin), then the moments about it.
//     A rotation, reflection or translation turns them with the mesh (to
//     rounding); they depend on the geometry, not on where the vertices are
//     (unlike the moments of the points, which follow the mesh's grading).
//     The principal frame of the Poisson check is C's (principal_frame.h).
//   moment_length: L = sqrt(12 tr C), the diagonal of the box that has the
//     mesh's second moments (a box a x b x c has tr C = (a^2 + b^2 + c^2) /
//     12: L is its diagonal exactly). A rotation, reflection or translation
//     leaves tr C unchanged, so L too (the bounding-box diagonal changes: a
//     cube's from a sqrt 3 to a sqrt 5 when turned 45 degrees); a uniform
//     scale s scales it by s. Model units. NaN when the volume is not
//     positive (no hexes, or a mesh that folds over itself). The batch's h/L
//     divides by it (report.json fem.poisson.mesh_length).

#include <array>

#include "hqview/core/vec3.h"
#include "hqview/mesh/hex_mesh.h"

namespace hq {

struct VolumeMoments {
  double volume = 0;  // signed: <= 0 for no hexes or a mesh that folds over itself
  Vec3 centroid;
  std::array<std::array<double, 3>, 3> second{};  // C[i][j], model units^2
  // Third central moments, model units^3: third[i][j][k], symmetric.
  std::array<std::array<std::array<double, 3>, 3>, 3> third{};
};

// Centroid and moments NaN when the volume is not positive (no hexes, or a
// mesh that folds over itself).
VolumeMoments volume_moments(const HexMesh& mesh);

// int ((x - c) . e)^3 dV / V for a direction e.
double third_moment_along(const VolumeMoments& m, const Vec3& e);

// L = sqrt(12 tr C) of the moments; NaN when the volume is not positive.
double moment_length(const VolumeMoments& m);

}  // namespace hq
