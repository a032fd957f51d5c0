#include "hqview/render/label_layout.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace hq {

bool boxes_overlap(const PixelRect& a, const PixelRect& b) {
  return a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height && b.y < a.y + a.height;
}

namespace {

// The point of box nearest to (x, y).
std::array<double, 2> nearest_point(const PixelRect& box, double x, double y) {
  return {std::clamp(x, static_cast<double>(box.x), static_cast<double>(box.x + box.width)),
          std::clamp(y, static_cast<double>(box.y), static_cast<double>(box.y + box.height))};
}

bool inside(const PixelRect& box, const PixelRect& bounds) {
  return box.x >= bounds.x && box.y >= bounds.y && box.x + box.width <= bounds.x + bounds.width &&
         box.y + box.height <= bounds.y + bounds.height;
}

// Unit directions, in the order tried: right, upper right, lower right,
// left, upper left, lower left, above, below (y grows downwards).
constexpr double kDiagonal = 0.70710678118654752;
constexpr std::array<std::array<double, 2>, 8> kDirections{{{1, 0},
                                                            {kDiagonal, -kDiagonal},
                                                            {kDiagonal, kDiagonal},
                                                            {-1, 0},
                                                            {-kDiagonal, -kDiagonal},
                                                            {-kDiagonal, kDiagonal},
                                                            {0, -1},
                                                            {0, 1}}};

// The box of size w x h whose corner or edge centre facing the anchor is at
// (px, py), for direction d.
PixelRect box_at(double px, double py, const std::array<double, 2>& d, int w, int h) {
  const double sx = d[0] > 0.1 ? 0.0 : d[0] < -0.1 ? -1.0 : -0.5;
  const double sy = d[1] > 0.1 ? 0.0 : d[1] < -0.1 ? -1.0 : -0.5;
  return {static_cast<int>(std::lround(px + sx * w)), static_cast<int>(std::lround(py + sy * h)), w, h};
}

}  // namespace

bool box_meets_disc(const PixelRect& box, const ScreenDisc& disc) {
  const auto p = nearest_point(box, disc.x, disc.y);
  return std::hypot(p[0] - disc.x, p[1] - disc.y) < disc.radius;
}

double disc_box_gap(const ScreenDisc& disc, const PixelRect& box) {
  const auto p = nearest_point(box, disc.x, disc.y);
  return std::max(0.0, std::hypot(p[0] - disc.x, p[1] - disc.y) - disc.radius);
}

PlacedLabel with_leader(const ScreenDisc& anchor, const PixelRect& box) {
  const auto end = nearest_point(box, anchor.x, anchor.y);
  const double dx = end[0] - anchor.x, dy = end[1] - anchor.y;
  const double length = std::max(std::hypot(dx, dy), 1e-9);
  PlacedLabel result{box};
  result.has_leader = true;
  result.leader_x0 = anchor.x + dx / length * anchor.radius;
  result.leader_y0 = anchor.y + dy / length * anchor.radius;
  result.leader_x1 = end[0];
  result.leader_y1 = end[1];
  return result;
}

std::vector<std::optional<PlacedLabel>> place_labels(std::span<const LabelRequest> labels,
                                                     std::span<const ScreenDisc> obstacles,
                                                     std::span<const PixelRect> taken,
                                                     const LabelLayoutOptions& options) {
  std::vector<std::optional<PlacedLabel>> placed(labels.size());
  std::vector<PixelRect> boxes(taken.begin(), taken.end());
  auto is_free = [&](const PixelRect& box, const ScreenDisc& anchor) {
    if (!inside(box, options.bounds) || box_meets_disc(box, anchor)) return false;
    if (std::any_of(boxes.begin(), boxes.end(), [&](const PixelRect& b) { return boxes_overlap(box, b); }))
      return false;
    return std::none_of(obstacles.begin(), obstacles.end(),
                        [&](const ScreenDisc& disc) { return box_meets_disc(box, disc); });
  };
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const LabelRequest& label = labels[i];
    for (int ring = 0; ring <= options.rings && !placed[i]; ++ring) {
      const double distance = label.anchor.radius + options.gap + ring * options.ring_step;
      for (const auto& d : kDirections) {
        const PixelRect box =
            box_at(label.anchor.x + d[0] * distance, label.anchor.y + d[1] * distance, d, label.width, label.height);
        if (!is_free(box, label.anchor)) continue;
        const PlacedLabel result =
            disc_box_gap(label.anchor, box) > options.leader_distance ? with_leader(label.anchor, box) : PlacedLabel{box};
        boxes.push_back(box);
        placed[i] = result;
        break;
      }
    }
  }
  return placed;
}

}  // namespace hq
