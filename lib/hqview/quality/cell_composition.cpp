#include "hqview/quality/cell_composition.h"

#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hqview/quality/cell_volume.h"

namespace hq {

CellComposition compute_cell_composition(const Mesh& mesh) {
  CellComposition c;
  for_each_cell_kind([&](auto kind) {
    if constexpr (CellKindTable<kind()>::dimension == 3) {
      constexpr int N = CellKindTable<kind()>::num_corners;
      const auto& cells = cell_block<kind()>(mesh);
      std::vector<double> volumes(cells.size());
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 4096),
                        [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i != r.end(); ++i) {
                            std::array<Vec3, N> p;
                            for (int k = 0; k < N; ++k) p[k] = mesh.points[static_cast<std::size_t>(cells[i][k])];
                            volumes[i] = cell_volume<kind()>(p);
                          }
                        });
      const auto k = static_cast<std::size_t>(kind());
      c.count[k] = static_cast<std::int64_t>(cells.size());
      for (double v : volumes) c.volume[k] += std::abs(v);
      c.num_cells += c.count[k];
    }
  });
  // The fractions are of the volume cells (none for a surface mesh).
  if (c.num_cells > 0) c.hex_fraction = static_cast<double>(c.count[0]) / static_cast<double>(c.num_cells);
  c.num_quads = static_cast<std::int64_t>(mesh.quads.size());
  c.num_triangles = static_cast<std::int64_t>(mesh.triangles.size());
  c.num_cells += c.num_quads + c.num_triangles;
  const double total = c.volume[0] + c.volume[1] + c.volume[2] + c.volume[3];
  if (total > 0) c.hex_volume_fraction = c.volume[0] / total;
  return c;
}

}  // namespace hq
