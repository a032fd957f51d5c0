#include "hqview/report/cell_rows.h"

namespace hq {

CellRows::CellRows(const Analysis& a) : a_(a) {
  std::array<std::size_t, kNumCellKinds> counts{};
  for (CellKind kind : kCellKinds) counts[static_cast<std::size_t>(kind)] = static_cast<std::size_t>(num_cells_of(a.mesh, kind));
  for (std::size_t k = 0; k < counts.size(); ++k) first_[k + 1] = first_[k] + counts[k];
  for (const CellBlockMetricField& block : a.cell_metrics) {
    const auto k = static_cast<std::size_t>(block.kind);
    for (int m = 0; m < kNumHexMetrics; ++m) {
      const std::vector<double>* values = block.of(hex_metric_name(static_cast<HexMetric>(m)));
      if (values && values->size() == counts[k]) columns_[k][static_cast<std::size_t>(m)] = values;
    }
  }
}

int CellRows::num_corner_values(std::size_t c) const {
  int n = 0;
  const CellKind kind = ref(c).kind;
  for_each_cell_kind([&](auto k) {
    if (k() == kind) n = kCornerValuesPerCell<k()>;
  });
  return n;
}

double CellRows::corner(std::size_t c, int i) const {
  const CellRef r = ref(c);
  const int n = num_corner_values(c);
  if (i >= n) return std::numeric_limits<double>::quiet_NaN();
  const QualityField& q = a_.field;
  return q.corner_scaled_jacobian[q.corner_begin[static_cast<std::size_t>(r.kind)] +
                                  static_cast<std::size_t>(n) * r.index + static_cast<std::size_t>(i)];
}

double CellRows::metric(int m, std::size_t c) const {
  if (c < num_hexes()) {
    const std::vector<double>& values = a_.metrics.of(static_cast<HexMetric>(m));
    return values.empty() ? std::numeric_limits<double>::quiet_NaN() : values[c];
  }
  const CellRef r = ref(c);
  const std::vector<double>* values = columns_[static_cast<std::size_t>(r.kind)][static_cast<std::size_t>(m)];
  return values ? (*values)[r.index] : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace hq
