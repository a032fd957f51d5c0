#include "hqview/quality/kind_vertex_quality.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace hq {

KindVertexQuality kind_vertex_quality(const Mesh& mesh, const QualityField& field) {
  KindVertexQuality out;
  int kinds_present = 0;
  for_each_cell_kind([&](auto kind) {
    if constexpr (kind() == CellKind::hex || kind() == CellKind::tet || kind() == CellKind::wedge ||
                  kind() == CellKind::pyramid)
      kinds_present += !cell_block<kind()>(mesh).empty();
  });
  if (kinds_present < 2) return out;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  for_each_cell_kind([&](auto kind) {
    if constexpr (kind() == CellKind::hex || kind() == CellKind::tet || kind() == CellKind::wedge ||
                  kind() == CellKind::pyramid) {
      const auto& cells = cell_block<kind()>(mesh);
      if (cells.empty()) return;
      std::vector<double>& q = out.by_kind[static_cast<std::size_t>(kind())];
      q.assign(mesh.points.size(), kNaN);
      const auto lower = [&](Index v, double value) {
        double& w = q[static_cast<std::size_t>(v)];
        if (std::isnan(w) || value < w) w = value;
      };
      constexpr int C = kCornerValuesPerCell<kind()>;
      const std::size_t corner0 = field.corner_begin[static_cast<std::size_t>(kind())];
      for (std::size_t c = 0; c < cells.size(); ++c)
        for (int i = 0; i < C; ++i)
          lower(cells[c][static_cast<std::size_t>(i)], field.corner_scaled_jacobian[corner0 + C * c + static_cast<std::size_t>(i)]);
      if constexpr (kind() == CellKind::pyramid) {
        // The apex: its pyramids' lowest base corner, where no pyramid has a corner value.
        std::vector<double> apex(mesh.points.size(), kNaN);
        for (std::size_t c = 0; c < cells.size(); ++c) {
          const double* base = field.corner_scaled_jacobian.data() + corner0 + 4 * c;
          double& a = apex[static_cast<std::size_t>(cells[c][4])];
          const double lowest = *std::min_element(base, base + 4);
          if (std::isnan(a) || lowest < a) a = lowest;
        }
        for (std::size_t v = 0; v < apex.size(); ++v)
          if (std::isnan(q[v])) q[v] = apex[v];
      }
    }
  });
  return out;
}

}  // namespace hq
