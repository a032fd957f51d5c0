#include "hqview/report/key_quantity.h"

namespace hq {

std::string key_quantity(std::string_view key) {
  auto starts = [&](std::string_view prefix) { return key.substr(0, prefix.size()) == prefix; };
  auto ends = [&](std::string_view suffix) {
    return key.size() >= suffix.size() && key.substr(key.size() - suffix.size()) == suffix;
  };
  if (key == "quality.num_degenerate" || key == "quality.scaled_jacobian.num_degenerate")
    return "hexes whose scaled Jacobian is Verdict's 1e30 (a zero-length edge or principal axis)";
  if (starts("quality.scaled_jacobian.") || key == "headline.min_scaled_jacobian" ||
      key == "headline.mean_scaled_jacobian" || starts("quality.metrics.scaled_jacobian."))
    return "per hex: Verdict's scaled Jacobian, the min over its 8 corners and its centre";
  if (starts("quality.corner_scaled_jacobian.")) return "per corner: 8 values per hex";
  if (starts("quality.vertex_quality.")) return "per vertex: the min corner scaled Jacobian of its hexes";
  if (starts("quality.metrics.") && ends(".num_degenerate")) {
    const std::string_view metric =
        key.substr(16, key.size() - 16 - std::string_view(".num_degenerate").size());
    return "hexes where Verdict's " + std::string(metric) +
           " is undefined (1e30: e.g. a non-positive Jacobian), not degenerate hexes";
  }
  return "";
}

}  // namespace hq
