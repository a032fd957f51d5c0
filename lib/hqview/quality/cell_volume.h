#pragma once
// The signed Verdict 1.4.5 volume of one volume cell (model units cubed),
// per kind: hexes as 24 tetrahedra through the face and cell centres
// (hex_volume), tets, wedges and pyramids by their own Verdict formulas.
// Corners in VTK order (core/cell_kinds.h); an inverted cell is negative.
// Also the volume of the kind's regular cell of unit edge length, to compare
// the sizes of cells of different kinds.

#include <array>
#include <cmath>

#include "hqview/core/cell_kinds.h"
#include "hqview/core/vec3.h"
#include "hqview/quality/hex_metrics.h"
#include "hqview/quality/pyramid_metrics.h"
#include "hqview/quality/tet_metrics.h"
#include "hqview/quality/wedge_metrics.h"

namespace hq {

template <CellKind K>
double cell_volume(const std::array<Vec3, CellKindTable<K>::num_corners>& p) {
  static_assert(CellKindTable<K>::dimension == 3, "a volume cell");
  if constexpr (K == CellKind::hex) return hex_volume(p);
  else if constexpr (K == CellKind::tet) return tet_volume(p);
  else if constexpr (K == CellKind::wedge) return wedge_metric(WedgeMetric::volume, p);
  else return pyramid_metric(PyramidMetric::volume, p);
}

// The volume of the regular cell of kind K with every edge of length 1: the
// unit cube 1, the regular tetrahedron sqrt(2)/12, the right prism over an
// equilateral triangle sqrt(3)/4, the square pyramid with equilateral
// sides sqrt(2)/6. V / regular_unit_volume<K>() is the volume of the cube
// whose edge is the edge length of the regular cell of K with volume V.
template <CellKind K>
constexpr double regular_unit_volume() {
  static_assert(CellKindTable<K>::dimension == 3, "a volume cell");
  if constexpr (K == CellKind::hex) return 1.0;
  else if constexpr (K == CellKind::tet) return 1.4142135623730951 / 12.0;
  else if constexpr (K == CellKind::wedge) return 1.7320508075688772 / 4.0;
  else return 1.4142135623730951 / 6.0;
}

}  // namespace hq
