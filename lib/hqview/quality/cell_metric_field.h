#pragma once
// Every Verdict metric, the per-corner scaled Jacobians and the orientation
// of every cell of one block of a kind (tets, wedges, pyramids, quads or
// triangles; hexes: hex_metric_field.h), plus the block's statistics.
// Parallel over cells (TBB), identical results for any thread count: each
// value is written by one task, the mean size is summed sequentially in id
// order. Takes the points and the block's connectivity (VTK corner order,
// core/cell_kinds.h), not a mesh struct, so any mesh model can call it.
// Precondition: every index is in [0, points.size()) (the readers check).

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/core/cell_kinds.h"
#include "hqview/core/types.h"
#include "hqview/core/vec3.h"
#include "hqview/quality/cell_corner_jacobian.h"
#include "hqview/quality/statistics.h"

namespace hq {

struct CellBlockMetricField {
  CellKind kind = CellKind::tet;
  std::int64_t count = 0;
  // Mean of the kind's Verdict size (volume; area for quads and triangles)
  // over the block, inverted cells counting negative (as vtkMeshQuality):
  // the reference of the size metrics (relative_size_squared, ...).
  double average_size = 0;
  // The kind's Verdict metric names in its enum's order (tet_metrics.h, ...)
  // and values[m][cell], Verdict's sentinels (+-1e30) and NaNs kept.
  std::vector<std::string_view> names;
  std::vector<std::vector<double>> values;
  // corners_per_cell values per cell (cell c's corner k at
  // c * corners_per_cell + k; a pyramid has its 4 base corners), and per cell
  // the mask of corners with a zero-length frame edge.
  int corners_per_cell = 0;
  std::vector<double> corner_scaled_jacobian;
  std::vector<std::uint8_t> corner_degenerate_mask;
  std::vector<CellValidity> validity;  // per cell
  std::int64_t num_inverted = 0;       // cells with validity inverted
  std::int64_t num_flat = 0;           // cells with validity flat

  // The values of metric `name`, or nullptr when the kind has no such metric.
  const std::vector<double>* of(std::string_view name) const;
};

CellBlockMetricField compute_tet_block_metrics(std::span<const Vec3> points,
                                               std::span<const std::array<Index, 4>> tets);
CellBlockMetricField compute_wedge_block_metrics(std::span<const Vec3> points,
                                                 std::span<const std::array<Index, 6>> wedges);
CellBlockMetricField compute_pyramid_block_metrics(std::span<const Vec3> points,
                                                   std::span<const std::array<Index, 5>> pyramids);
// Surface kinds: corners and orientation against `normal` when given (a
// planar mesh's plane), else against each cell's own normal
// (cell_corner_jacobian.h).
CellBlockMetricField compute_quad_block_metrics(std::span<const Vec3> points,
                                                std::span<const std::array<Index, 4>> quads,
                                                const std::optional<Vec3>& normal = std::nullopt);
CellBlockMetricField compute_triangle_block_metrics(std::span<const Vec3> points,
                                                    std::span<const std::array<Index, 3>> triangles,
                                                    const std::optional<Vec3>& normal = std::nullopt);

// A metric's statistics in one block.
struct CellMetricSummary {
  std::string name;
  Statistics stats;
};

// A block's slice of the quality field (quality_field.h), which the same
// corner and validity kernels computed: corner values (the kind's corner
// count per cell), per cell the degenerate-corner mask and the validity.
struct BlockCornerValues {
  std::span<const double> scaled_jacobian;
  std::span<const std::uint8_t> degenerate_mask;
  std::span<const CellValidity> validity;
  // Per cell, Verdict's scaled Jacobian as the quality field holds it (the
  // very kernel of a tet's scaled_jacobian metric, which is then copied from
  // here instead of computed again); empty when not given.
  std::span<const double> cell_scaled_jacobian = {};
};

// A block's metrics summarised as they were computed.
struct SummarizedCellBlock {
  // count, names, average_size, num_inverted, num_flat and corners_per_cell
  // as compute_*_block_metrics gives them; values[m] only for the metrics
  // `keep` accepted (the others empty); no corner or validity arrays.
  CellBlockMetricField field;
  // summarize_cell_block's summaries of the whole field, byte for byte.
  std::vector<CellMetricSummary> summaries;
};

// The metrics of a block of kind K (tet, wedge, pyramid, quad, triangle)
// computed a few metrics per pass over the cells (parallel), each
// summarised and then dropped unless `keep` accepts its name: memory for
// the kept columns and two more, not every column at once (2.18 M tets:
// 21 columns, 366 MB, before). The values are those of
// compute_*_block_metrics (each kind's all-metrics kernel is its one-metric
// kernel in a loop); the corner summary and the inverted and flat counts
// come from `corners`. Columns at hand are not computed again: a tet's
// volume (the block's sizes), its scaled_jacobian (from
// corners.cell_scaled_jacobian when given), its shape_and_size (the kept
// factors' product). Surface kinds are summarised against whatever normal
// `corners` was computed with. Deterministic for any thread count.
template <CellKind K>
SummarizedCellBlock summarize_cell_block_metrics(std::span<const Vec3> points,
                                                 std::span<const std::array<Index, CellKindTable<K>::num_corners>> cells,
                                                 const BlockCornerValues& corners,
                                                 const std::function<bool(std::string_view)>& keep);

// One summary per metric of the block, in the kind's order (statistics.h:
// sentinels counted in num_degenerate and kept out of everything else;
// histograms of 20 bins over [-1, 1] for scaled_jacobian, [min, max]
// otherwise), then one named "corner_scaled_jacobian" over every corner
// value (degenerate corners left out, histogram over [-1, 1]).
std::vector<CellMetricSummary> summarize_cell_block(const CellBlockMetricField& field);

}  // namespace hq
