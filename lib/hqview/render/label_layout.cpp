#include "hqview/render/label_layout.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

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

namespace {

// Cell of the placed-things grid holding pixel coordinate v.
constexpr int kGridCell = 64;
int grid_cell(double v) { return static_cast<int>(std::floor(v / kGridCell)); }
std::int64_t grid_key(int cx, int cy) {
  return (static_cast<std::int64_t>(cx) << 32) ^ static_cast<std::int64_t>(static_cast<std::uint32_t>(cy));
}

}  // namespace

LabelPlacer::LabelPlacer(std::span<const PixelRect> taken, const LabelLayoutOptions& options) : options_(options) {
  for (const PixelRect& b : taken) add_box(b);
}

// Calls f(cell key) for every grid cell the rectangle [x0, x1] x [y0, y1] meets.
template <class F>
void for_cells(double x0, double y0, double x1, double y1, F&& f) {
  for (int cy = grid_cell(std::min(y0, y1)); cy <= grid_cell(std::max(y0, y1)); ++cy)
    for (int cx = grid_cell(std::min(x0, x1)); cx <= grid_cell(std::max(x0, x1)); ++cx) f(grid_key(cx, cy));
}

void LabelPlacer::add_box(const PixelRect& box) {
  const auto i = static_cast<std::uint32_t>(boxes_.size());
  boxes_.push_back(box);
  for_cells(box.x, box.y, box.x + box.width, box.y + box.height, [&](std::int64_t k) { box_cells_[k].push_back(i); });
}

void LabelPlacer::add(const PlacedLabel& label) {
  add_box(label.box);
  if (!label.has_leader) return;
  const auto i = static_cast<std::uint32_t>(leaders_.size());
  leaders_.push_back(label);
  for_cells(label.leader_x0, label.leader_y0, label.leader_x1, label.leader_y1,
            [&](std::int64_t k) { leader_cells_[k].push_back(i); });
}

// Whether any item of items registered in cells near [x0, x1] x [y0, y1]
// satisfies pred.
template <class T, class Pred>
bool any_near(const std::unordered_map<std::int64_t, std::vector<std::uint32_t>>& cells, const std::vector<T>& items,
              double x0, double y0, double x1, double y1, Pred&& pred) {
  bool found = false;
  for_cells(x0, y0, x1, y1, [&](std::int64_t k) {
    if (found) return;
    const auto it = cells.find(k);
    if (it == cells.end()) return;
    for (std::uint32_t i : it->second)
      if (pred(items[i])) {
        found = true;
        return;
      }
  });
  return found;
}

template <class Pred>
bool LabelPlacer::any_box_near(double x0, double y0, double x1, double y1, Pred&& pred) const {
  return any_near(box_cells_, boxes_, x0, y0, x1, y1, pred);
}

template <class Pred>
bool LabelPlacer::any_leader_near(double x0, double y0, double x1, double y1, Pred&& pred) const {
  return any_near(leader_cells_, leaders_, x0, y0, x1, y1, pred);
}

std::optional<PlacedLabel> LabelPlacer::place(const LabelRequest& label, std::span<const ScreenDisc> obstacles) const {
  const ScreenDisc& anchor = label.anchor;
  auto is_own = [&](const ScreenDisc& d) {
    return anchor.id >= 0 ? d.id == anchor.id : d.x == anchor.x && d.y == anchor.y;
  };
  // A candidate, checked once: its placement (with a leader when it needs
  // one) and the first pass that takes it (0: clear; 1: its leader may run
  // over glyphs; 2: any free place; 3: not free).
  struct Candidate {
    int pass = 3;
    double room = 0.0;
    PlacedLabel placement;
  };
  auto evaluate = [&](const PixelRect& box) {
    Candidate c;
    if (!inside(box, options_.bounds) || box_meets_disc(box, anchor)) return c;
    const double bx1 = box.x + box.width, by1 = box.y + box.height;
    if (any_box_near(box.x, box.y, bx1, by1, [&](const PixelRect& b) { return boxes_overlap(box, b); })) return c;
    if (std::any_of(obstacles.begin(), obstacles.end(), [&](const ScreenDisc& d) { return box_meets_disc(box, d); }))
      return c;
    const double own = disc_box_gap(anchor, box);
    const bool is_far = own > options_.leader_distance;
    const bool is_beside_other = std::any_of(obstacles.begin(), obstacles.end(), [&](const ScreenDisc& d) {
      return !is_own(d) && disc_box_gap(d, box) < own + options_.leader_distance;
    });
    c.placement = is_far || is_beside_other || label.always_leader
                      ? with_leader(label.leader_from.value_or(anchor), box)
                      : PlacedLabel{box};
    c.room = 3.0 * options_.leader_distance;
    for (const ScreenDisc& o : obstacles)
      if (!is_own(o)) c.room = std::min(c.room, disc_box_gap(o, box));
    const PlacedLabel& r = c.placement;
    // Never (any pass): a leader over a protected disc; with strict_leaders
    // over another leader either.
    if (r.has_leader) {
      if (label.strict_leaders && any_leader_near(r.leader_x0, r.leader_y0, r.leader_x1, r.leader_y1,
                                                  [&](const PlacedLabel& l) { return leaders_cross(l, r); }))
        return c;
      // (A protected disc holding the leader's start, e.g. a marker group
      // inside #0, cannot be avoided: it does not count.)
      if (std::any_of(obstacles.begin(), obstacles.end(), [&](const ScreenDisc& d) {
            return d.id >= 0 && d.id < label.protect_below && !is_own(d) && leader_meets_disc(r, d) &&
                   std::hypot(r.leader_x0 - d.x, r.leader_y0 - d.y) >= d.radius;
          }))
        return c;
    }
    // With strict_leaders: nor a leader through a placed label, nor a box
    // over a placed leader.
    const bool box_crossed =
        any_leader_near(box.x, box.y, bx1, by1, [&](const PlacedLabel& l) { return leader_meets_box(l, box); });
    const bool leader_through_box =
        r.has_leader && any_box_near(r.leader_x0, r.leader_y0, r.leader_x1, r.leader_y1,
                                     [&](const PixelRect& b) { return leader_meets_box(r, b); });
    if (label.strict_leaders && (box_crossed || leader_through_box)) return c;
    c.pass = 2;
    // Clear: a label beside another disc only when far enough to need a
    // leader anyway (a stub leader beside two glyphs says little).
    if (is_beside_other && !is_far) return c;
    if (box_crossed) return c;
    if (r.has_leader) {
      if (any_leader_near(r.leader_x0, r.leader_y0, r.leader_x1, r.leader_y1,
                          [&](const PlacedLabel& l) { return leaders_cross(l, r); }))
        return c;
      if (leader_through_box) return c;
      c.pass = 1;
      if (std::any_of(obstacles.begin(), obstacles.end(),
                      [&](const ScreenDisc& d) { return !is_own(d) && leader_meets_disc(r, d); }))
        return c;
    }
    c.pass = 0;
    return c;
  };
  // The rings' candidates, evaluated as the passes first reach them.
  std::vector<std::array<Candidate, kDirections.size()>> rings;
  for (int pass = 0; pass < 3; ++pass)
    for (int ring = 0; ring <= options_.rings; ++ring) {
      if (static_cast<std::size_t>(ring) == rings.size()) {
        const double distance = anchor.radius + options_.gap + ring * options_.ring_step;
        rings.emplace_back();
        for (std::size_t k = 0; k < kDirections.size(); ++k) {
          const auto& d = kDirections[k];
          rings.back()[k] = evaluate(box_at(anchor.x + d[0] * distance, anchor.y + d[1] * distance, d, label.width,
                                            label.height));
        }
      }
      // Of the ring's candidates this pass takes, the one farthest from the
      // other discs (up to 3 leader distances; ties: the order of
      // kDirections), so a label leans away from its neighbours' glyphs.
      const Candidate* best = nullptr;
      for (const Candidate& c : rings[static_cast<std::size_t>(ring)])
        if (c.pass <= pass && (!best || c.room > best->room)) best = &c;
      if (best) return best->placement;
    }
  return std::nullopt;
}

std::vector<std::optional<PlacedLabel>> place_labels(std::span<const LabelRequest> labels,
                                                     std::span<const ScreenDisc> obstacles,
                                                     std::span<const PixelRect> taken,
                                                     const LabelLayoutOptions& options,
                                                     std::span<const PlacedLabel> earlier) {
  LabelPlacer placer(taken, options);
  for (const PlacedLabel& l : earlier) placer.add(l);
  std::vector<std::optional<PlacedLabel>> placed(labels.size());
  for (std::size_t i = 0; i < labels.size(); ++i) {
    placed[i] = placer.place(labels[i], obstacles);
    if (placed[i]) placer.add(*placed[i]);
  }
  return placed;
}

}  // namespace hq
