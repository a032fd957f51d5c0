#pragma once
// The colour of a glyph cluster in every output (report.json `color`, the
// HTML swatches, later the views): the fixed qualitative palette
// (render/colormap.h) by cluster rank, as "#rrggbb".

#include <cstdio>
#include <string>

#include "hqview/core/types.h"
#include "hqview/image/colormap.h"

namespace hq {

inline std::string cluster_color_hex(Index cluster_id) {
  const Rgba8 c = to_rgba8(qualitative_color(cluster_id));
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", c.r, c.g, c.b);
  return text;
}

}  // namespace hq
