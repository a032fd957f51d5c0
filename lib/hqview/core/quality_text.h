#pragma once
// A quality value (scaled Jacobian) as the detail views print it: view C's
// title, view D's corner labels and view E's bars. Rounded to 3 decimals
// (printf %.3f: -0.778853 is "-0.779", never the truncated "-0.778"), one
// rule for all three, so that one value reads alike in each (47g review #9).

#include <cmath>
#include <cstdio>
#include <string>

namespace hq {

inline std::string quality_text(double v) {
  if (!std::isfinite(v)) return "–";
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.3f", v);
  return buffer;
}

}  // namespace hq
