#pragma once
// The colour of a glyph cluster in every output (report.json `color`, the
// HTML swatches, the views): cluster_color (image/colormap.h) by rank and
// the run's --top-clusters K, as "#rrggbb".

#include <cstdio>
#include <string>

#include "hqview/core/types.h"
#include "hqview/image/colormap.h"

namespace hq {

inline std::string cluster_color_hex(Index cluster_id, std::int64_t top_clusters) {
  const Rgba8 c = to_rgba8(cluster_color(cluster_id, top_clusters));
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", c.r, c.g, c.b);
  return text;
}

}  // namespace hq
