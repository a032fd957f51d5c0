#pragma once
// A length of a hex mesh that does not depend on how the mesh is placed:
// L = sqrt(12 tr C), C the second central moment of the mesh's volume
// (C = int (x - c)(x - c)^T dV / V, c the centroid, V the volume), i.e. the
// diagonal of the box that has the mesh's second moments (a box a x b x c
// has tr C = (a^2 + b^2 + c^2) / 12: L is its diagonal exactly). A rotation,
// reflection or translation leaves tr C unchanged, so L too (the
// bounding-box diagonal changes: a cube's from a sqrt 3 to a sqrt 5 when
// turned 45 degrees); a uniform scale s scales it by s. It depends on the
// geometry, not on where the vertices are (unlike the moments of the
// points, which follow the mesh's grading). The integrals: the trilinear map
// of each hex by 2 x 2 x 2 Gauss-Legendre (exact for a parallelepiped, det J
// with its sign), summed over fixed chunks of hexes (the same bits for any
// thread count), about the mesh's first point (no cancellation far from the
// origin), in one pass. Model units. NaN when the volume is
// not positive (no hexes, or a mesh that folds over itself). The batch's
// h/L divides by it (report.json fem.poisson.mesh_length).

#include "hqview/mesh/hex_mesh.h"

namespace hq {

double moment_length(const HexMesh& mesh);

}  // namespace hq
