#pragma once
// The frame the Poisson check places its manufactured solutions in
// (docs/analysis.md "Finite-element check", issue 48): the principal axes
// of the mesh's volume, so that a rotated, mirrored or moved copy of a mesh
// gets the same normalised coordinates (to rounding) and hence the same
// errors.
//   - Axes: the eigenvectors of the volume's covariance C
//     (moment_length.h; Eigen's SelfAdjointEigenSolver), by descending
//     eigenvalue: x^ along the longest extent.
//   - Signs: each axis turned so that the volume's third central moment
//     along it is positive (the side the volume is skewed to); where that
//     is below kSkewTolerance sigma^3 (a shape symmetric about the plane,
//     e.g. a box), the third moment of the points used by hexes about their
//     mean decides (a perturbed or graded mesh of a symmetric shape), and
//     where that is also below it, the model axes' rule: the axis's largest
//     component positive (signs_from_input counts these; a mirror image of
//     such a mesh may then differ).
//   - Degenerate eigenvalues (a gap below kDegenerateGap lambda_max: a cube,
//     a sphere, a cylinder's cross-section): the eigenvectors are arbitrary
//     there, so inside that eigenspace the model axes are used: all three
//     for a triple eigenvalue; for a double one the model axis most
//     orthogonal to the distinct axis a, projected onto a's plane, then
//     a x that (axes_from_input counts these; a turned copy of such a mesh
//     may differ).
//   - Centre and diagonal: of the bounding box of the points used by hexes
//     in that frame.
// When the mesh has no positive volume (no moments to take axes from): the
// model axes and the bounding box of the used points. Pure, deterministic.

#include "hqview/fem/harmonic_solution.h"
#include "hqview/fem/moment_length.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"

namespace hq {

inline constexpr double kDegenerateGap = 1e-5;  // relative to the largest principal variance
inline constexpr double kSkewTolerance = 1e-8;  // |third moment| / sigma^3 below it: no sign

// `moments`: the mesh's (volume_moments).
Normalization principal_normalization(const HexMesh& mesh, const Topology& topology, const VolumeMoments& moments);

}  // namespace hq
