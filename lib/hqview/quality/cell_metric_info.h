#pragma once
// What the per-kind metric tables (tet_metrics.h, wedge_metrics.h,
// pyramid_metrics.h, quad_metrics.h, triangle_metrics.h) say about each
// metric. The hex table (hex_metrics.h) has its own richer struct.

#include <string_view>

namespace hq {

struct CellMetricInfo {
  std::string_view name;   // Verdict's name, snake_case (as `--metrics` spells it)
  bool uses_average_size;  // a size metric: compares with the mean size of the cells of its kind
};

}  // namespace hq
