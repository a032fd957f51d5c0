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

namespace {

struct Point {
  double x, y;
};

// Twice the signed area of (a, b, c): > 0 counter-clockwise.
double orientation(const Point& a, const Point& b, const Point& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool on_segment(const Point& a, const Point& b, const Point& p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

// Closed segments ab and cd share a point.
bool segments_meet(const Point& a, const Point& b, const Point& c, const Point& d) {
  const double o1 = orientation(a, b, c), o2 = orientation(a, b, d);
  const double o3 = orientation(c, d, a), o4 = orientation(c, d, b);
  if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))) return true;
  return (o1 == 0 && on_segment(a, b, c)) || (o2 == 0 && on_segment(a, b, d)) ||
         (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
}

}  // namespace

bool leaders_cross(const PlacedLabel& a, const PlacedLabel& b) {
  return a.has_leader && b.has_leader &&
         segments_meet({a.leader_x0, a.leader_y0}, {a.leader_x1, a.leader_y1}, {b.leader_x0, b.leader_y0},
                       {b.leader_x1, b.leader_y1});
}

bool leader_meets_box(const PlacedLabel& leader, const PixelRect& box) {
  if (!leader.has_leader) return false;
  // Liang-Barsky clipping against the open box.
  const double x0 = leader.leader_x0, y0 = leader.leader_y0;
  const double dx = leader.leader_x1 - x0, dy = leader.leader_y1 - y0;
  double t0 = 0.0, t1 = 1.0;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {x0 - box.x, box.x + box.width - x0, y0 - box.y, box.y + box.height - y0};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] <= 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
  }
  return t1 - t0 > 1e-9;
}

bool leader_meets_disc(const PlacedLabel& leader, const ScreenDisc& disc) {
  if (!leader.has_leader) return false;
  const double dx = leader.leader_x1 - leader.leader_x0, dy = leader.leader_y1 - leader.leader_y0;
  const double length2 = dx * dx + dy * dy;
  const double t =
      length2 > 0.0 ? std::clamp(((disc.x - leader.leader_x0) * dx + (disc.y - leader.leader_y0) * dy) / length2, 0.0, 1.0)
                    : 0.0;
  return std::hypot(leader.leader_x0 + t * dx - disc.x, leader.leader_y0 + t * dy - disc.y) < disc.radius;
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
                                                     const LabelLayoutOptions& options,
                                                     std::span<const PlacedLabel> earlier) {
  std::vector<std::optional<PlacedLabel>> placed(labels.size());
  std::vector<PixelRect> boxes(taken.begin(), taken.end());
  std::vector<PlacedLabel> leaders;
  for (const PlacedLabel& l : earlier) {
    boxes.push_back(l.box);
    if (l.has_leader) leaders.push_back(l);
  }
  auto is_own = [](const ScreenDisc& d, const ScreenDisc& anchor) {
    return anchor.id >= 0 ? d.id == anchor.id : d.x == anchor.x && d.y == anchor.y;
  };
  // The placement of box (with a leader when it needs one), or nullopt when
  // it is not free or not as clear as the pass asks (pass 0: clear; 1: its
  // leader may run over glyphs; 2: any free place).
  auto candidate = [&](const PixelRect& box, const LabelRequest& request, int pass) -> std::optional<PlacedLabel> {
    const ScreenDisc& anchor = request.anchor;
    if (!inside(box, options.bounds) || box_meets_disc(box, anchor)) return std::nullopt;
    if (std::any_of(boxes.begin(), boxes.end(), [&](const PixelRect& b) { return boxes_overlap(box, b); }))
      return std::nullopt;
    if (std::any_of(obstacles.begin(), obstacles.end(), [&](const ScreenDisc& d) { return box_meets_disc(box, d); }))
      return std::nullopt;
    const double own = disc_box_gap(anchor, box);
    const bool is_far = own > options.leader_distance;
    const bool is_beside_other = std::any_of(obstacles.begin(), obstacles.end(), [&](const ScreenDisc& d) {
      return !is_own(d, anchor) && disc_box_gap(d, box) < own + options.leader_distance;
    });
    const PlacedLabel result = is_far || is_beside_other || request.always_leader
                                   ? with_leader(request.leader_from.value_or(anchor), box)
                                   : PlacedLabel{box};
    if (pass == 2) return result;
    // Clear: a label beside another disc only when far enough to need a
    // leader anyway (a stub leader beside two glyphs says little).
    if (is_beside_other && !is_far) return std::nullopt;
    for (const PlacedLabel& l : leaders)
      if (leader_meets_box(l, box) || leaders_cross(l, result)) return std::nullopt;
    if (result.has_leader) {
      if (std::any_of(boxes.begin(), boxes.end(), [&](const PixelRect& b) { return leader_meets_box(result, b); }))
        return std::nullopt;
      if (pass == 0 && std::any_of(obstacles.begin(), obstacles.end(), [&](const ScreenDisc& d) {
            return !is_own(d, anchor) && leader_meets_disc(result, d);
          }))
        return std::nullopt;
    }
    return result;
  };
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const LabelRequest& label = labels[i];
    for (int pass = 0; pass < 3 && !placed[i]; ++pass)
      for (int ring = 0; ring <= options.rings && !placed[i]; ++ring) {
        const double distance = label.anchor.radius + options.gap + ring * options.ring_step;
        // Of the ring's free candidates, the one farthest from the other
        // discs (up to 3 leader distances; ties: the order of kDirections),
        // so a label leans away from its neighbours' glyphs.
        double best_room = -1.0;
        for (const auto& d : kDirections) {
          const PixelRect box =
              box_at(label.anchor.x + d[0] * distance, label.anchor.y + d[1] * distance, d, label.width, label.height);
          const std::optional<PlacedLabel> c = candidate(box, label, pass);
          if (!c) continue;
          double room = 3.0 * options.leader_distance;
          for (const ScreenDisc& o : obstacles)
            if (!is_own(o, label.anchor)) room = std::min(room, disc_box_gap(o, box));
          if (room > best_room) {
            best_room = room;
            placed[i] = c;
          }
        }
      }
    if (!placed[i]) continue;
    boxes.push_back(placed[i]->box);
    if (placed[i]->has_leader) leaders.push_back(*placed[i]);
  }
  return placed;
}

}  // namespace hq
