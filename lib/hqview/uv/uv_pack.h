#pragma once
// Packing of UV charts into [0,1]² on a raster (the way xatlas packs): each
// chart is rasterised conservatively on a grid, dilated by a gutter, and
// dropped at the lowest free place that its footprint fits (holes left by
// earlier charts are filled by later small ones); large charts keep their
// orientation, small ones may turn by quarter turns. Charts on the grid never
// share a cell, so packed charts are disjoint with at least `gutter_cells`
// of empty grid between them.

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/uv/uv_validation.h"

namespace hq {

struct PackOptions {
  // Grid cells along the side of an ideal square holding all chart area.
  int resolution = 256;
  int gutter_cells = 1;
  // Charts holding at least this share of the total area keep their
  // orientation; smaller ones may be turned by quarter turns to fit.
  double fixed_orientation_area = 0.2;
  // Also try each chart turned (at most an eighth of a turn) to its
  // smallest bounding box.
  bool tilt_to_smallest_box = true;
};

// The rasterised shapes of charts packed before, for packings that differ
// in a few charts (the atlas's tries of halved charts): a chart whose
// triangles, layout, cell size and options are those of an earlier call
// reuses its shapes instead of rasterising them again (the same result).
class PackShapeCache {
 public:
  PackShapeCache();
  ~PackShapeCache();
  PackShapeCache(const PackShapeCache&) = delete;
  PackShapeCache& operator=(const PackShapeCache&) = delete;
  void clear();
  std::size_t num_reused() const;  // charts of the last pack_charts call whose shapes were reused
  struct Impl;
  std::unique_ptr<Impl> impl;
};

// `local` holds each chart's layout (3 corners per triangle, any scale, one
// scale for all charts); `charts[c]` lists chart c's triangles. Writes the
// packed corners to `packed` (same indexing as `local`) in [0,1]² with one
// uniform scale for all charts. With a cache, charts met before keep their
// shapes (and the new ones are added).
void pack_charts(std::span<const Uv> local, const std::vector<std::vector<Index>>& charts, std::vector<Uv>& packed,
                 const PackOptions& options = {}, PackShapeCache* cache = nullptr);

// The corners that may be vertices of their convex hull (every hull vertex
// among them): those not inside, by a margin far above rounding, the
// polygon of the extreme corners in eight directions. The packer's search
// for the smallest bounding box sorts these instead of every corner.
std::vector<Uv> hull_candidates(const std::vector<Uv>& corners);

}  // namespace hq
