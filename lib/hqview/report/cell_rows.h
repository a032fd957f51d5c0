#pragma once
// The per-cell values cells.csv and annotated.vtu write, for every cell in
// cell-id order (hexes, then tets, wedges, pyramids; a surface mesh's quads
// and triangles; mesh.h): its
// kind, source index, corner values and the value of each cells.csv metric
// column. A hex-only result (the Verdict hex metrics a non-hex kind does not
// share, size gradation, the finite-element check) has no value for a
// non-hex cell: NaN (an empty CSV field).

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "hqview/analysis/analysis.h"
#include "hqview/quality/cell_composition.h"

namespace hq {

class CellRows {
 public:
  explicit CellRows(const Analysis& a);

  std::size_t num_cells() const { return first_[kNumCellKinds]; }
  std::size_t num_hexes() const { return first_[1]; }
  CellRef ref(std::size_t c) const {
    int k = 0;
    while (c >= first_[static_cast<std::size_t>(k) + 1]) ++k;
    return {static_cast<CellKind>(k), c - first_[static_cast<std::size_t>(k)]};
  }
  std::int64_t source_index(std::size_t c) const {
    const CellRef r = ref(c);
    return cell_source_index(a_.mesh, r.kind, r.index);
  }
  // Corner i's value (corner_frames order of its kind), NaN past its corners.
  double corner(std::size_t c, int i) const;
  int num_corner_values(std::size_t c) const;
  // The metric named as hex metric m (HexMetric order) of cell c: a hex's from
  // Analysis::metrics (NaN when left out by --metrics), another kind's when
  // the kind has a Verdict metric of that name, else NaN.
  double metric(int m, std::size_t c) const;
  // values[c] for a hex, NaN for any other cell (values empty: NaN).
  static double hex_only(const std::vector<double>& values, std::size_t c, std::size_t num_hexes) {
    return c < num_hexes && c < values.size() ? values[c] : std::numeric_limits<double>::quiet_NaN();
  }

 private:
  const Analysis& a_;
  std::array<std::size_t, kNumCellKinds + 1> first_{};
  // Per non-hex kind (tet, wedge, pyramid, quad, triangle) and hex metric: the
  // kind's values of that name, or nullptr.
  std::array<std::array<const std::vector<double>*, kNumHexMetrics>, kNumCellKinds> columns_{};
};

}  // namespace hq
