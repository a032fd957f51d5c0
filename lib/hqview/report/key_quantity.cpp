#include "hqview/report/key_quantity.h"

namespace hq {

std::string cells_plural(MeshCells cells) {
  switch (cells) {
    case MeshCells::hex: return "hexes";
    case MeshCells::volume: return "cells";
    case MeshCells::surface: return "faces";
  }
  return "cells";
}

std::string key_quantity(std::string_view key, MeshCells cells) {
  auto starts = [&](std::string_view prefix) { return key.substr(0, prefix.size()) == prefix; };
  auto ends = [&](std::string_view suffix) {
    return key.size() >= suffix.size() && key.substr(key.size() - suffix.size()) == suffix;
  };
  const std::string plural = cells_plural(cells);
  if (key == "quality.num_degenerate" || key == "quality.scaled_jacobian.num_degenerate")
    return plural + " whose scaled Jacobian is Verdict's 1e30 (a zero-length edge or principal axis)";
  if (starts("quality.scaled_jacobian.") || key == "headline.min_scaled_jacobian" ||
      key == "headline.mean_scaled_jacobian" || starts("quality.metrics.scaled_jacobian.")) {
    switch (cells) {
      case MeshCells::hex: return "per hex: Verdict's scaled Jacobian, the min over its 8 corners and its centre";
      case MeshCells::volume:
        return "per cell: Verdict's scaled Jacobian of its kind (a hex: the min over its 8 corners and its centre)";
      case MeshCells::surface:
        return "per face: its lowest signed corner scaled Jacobian (against the plane's normal on a planar mesh), "
               "negative for an inverted or reversed face";
    }
  }
  if (starts("quality.corner_scaled_jacobian."))
    return cells == MeshCells::hex       ? "per corner: 8 values per hex"
           : cells == MeshCells::volume ? "per corner: one value per corner of each cell"
                                        : "per corner: 4 values per quad, 3 per triangle";
  if (starts("quality.vertex_quality."))
    return std::string("per vertex: the min corner scaled Jacobian of its ") + plural;
  if (starts("quality.metrics.") && ends(".num_degenerate")) {
    const std::string_view metric =
        key.substr(16, key.size() - 16 - std::string_view(".num_degenerate").size());
    return plural + " where Verdict's " + std::string(metric) +
           " is undefined (1e30: e.g. a non-positive Jacobian), not degenerate " + plural;
  }
  return "";
}

}  // namespace hq
