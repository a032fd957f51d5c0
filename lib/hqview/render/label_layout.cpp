#include "hqview/render/label_layout.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

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
// (px, py), for direction d: for the eight directions of kDirections its
// corner (diagonals) or edge centre; between them the point facing the
// anchor slides along the edge, so that boxes of neighbouring directions
// differ little.
double box_shift(double d) {
  const double s = std::clamp(-0.5 + kDiagonal * d, -1.0, 0.0);
  return std::abs(s) < 1e-6 ? 0.0 : std::abs(s + 1.0) < 1e-6 ? -1.0 : std::abs(s + 0.5) < 1e-6 ? -0.5 : s;
}
PixelRect box_at(double px, double py, const std::array<double, 2>& d, int w, int h) {
  return {static_cast<int>(std::lround(px + box_shift(d[0]) * w)), static_cast<int>(std::lround(py + box_shift(d[1]) * h)),
          w, h};
}

// The directions tried on a ring at `distance` from the anchor's centre:
// kDirections, then halving the angles between them (22.5, 11.25 ...
// degrees) until neighbouring candidates lie at most `spacing` apart on the
// ring, at most kMaxDirections (the 44l review: with eight, Dolphin_padded's
// #4 and a turned dolphin's #5 found "no room" in a view with room to
// spare). Coarse ones first: they keep the order of ties.
constexpr std::size_t kMaxDirections = 64;
std::vector<std::array<double, 2>> ring_directions(double distance, double spacing) {
  std::vector<std::array<double, 2>> out(kDirections.begin(), kDirections.end());
  for (std::size_t n = 16; n <= kMaxDirections && 2.0 * std::numbers::pi * distance / (n / 2) > spacing; n *= 2)
    for (std::size_t k = 1; k < n; k += 2) {
      const double a = 2.0 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n);
      out.push_back({std::cos(a), std::sin(a)});
    }
  return out;
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

bool leaders_run_together(const PlacedLabel& a, const PlacedLabel& b) {
  if (!a.has_leader || !b.has_leader) return false;
  const double dx = a.leader_x1 - a.leader_x0, dy = a.leader_y1 - a.leader_y0, length2 = dx * dx + dy * dy;
  const double length = std::hypot(b.leader_x1 - b.leader_x0, b.leader_y1 - b.leader_y0);
  const int steps = static_cast<int>(std::ceil(length / 2.0));
  int together = 0;
  for (int i = 0; i <= steps; ++i) {
    const double s = steps > 0 ? static_cast<double>(i) / steps : 0.0;
    const double x = b.leader_x0 + s * (b.leader_x1 - b.leader_x0), y = b.leader_y0 + s * (b.leader_y1 - b.leader_y0);
    const double t = length2 > 0.0 ? std::clamp(((x - a.leader_x0) * dx + (y - a.leader_y0) * dy) / length2, 0.0, 1.0) : 0.0;
    together += std::hypot(a.leader_x0 + t * dx - x, a.leader_y0 + t * dy - y) < 8.0 ? 1 : 0;
  }
  return 2 * together > 15;  // more than 15 px of b within 8 px of a
}

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

bool leader_over_disc(const PlacedLabel& leader, const ScreenDisc& disc) {
  if (!leader_meets_disc(leader, disc)) return false;
  const double start = std::hypot(leader.leader_x0 - disc.x, leader.leader_y0 - disc.y);
  return start >= disc.radius ||
         leader_meets_disc(leader, ScreenDisc{disc.x, disc.y, start - 1.0, disc.id});
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

// Calls f(cell key) for every grid cell the rectangle [x0, x1] x [y0, y1] meets.
template <class F>
void for_cells(double x0, double y0, double x1, double y1, F&& f) {
  for (int cy = grid_cell(std::min(y0, y1)); cy <= grid_cell(std::max(y0, y1)); ++cy)
    for (int cx = grid_cell(std::min(x0, x1)); cx <= grid_cell(std::max(x0, x1)); ++cx) f(grid_key(cx, cy));
}

LabelPlacer::LabelPlacer(std::span<const PixelRect> taken, const LabelLayoutOptions& options,
                         std::span<const PixelRect> avoid)
    : options_(options), avoid_(avoid.begin(), avoid.end()) {
  for (const PixelRect& b : taken) add_box(b);
  for (std::uint32_t i = 0; i < avoid_.size(); ++i) {
    const PixelRect& b = avoid_[i];
    for_cells(b.x, b.y, b.x + b.width, b.y + b.height, [&](std::int64_t k) { avoid_cells_[k].push_back(i); });
  }
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
bool any_near(const std::unordered_map<std::int64_t, std::vector<std::uint32_t>>& cells, std::span<const T> items,
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
  return any_near(box_cells_, std::span<const PixelRect>(boxes_), x0, y0, x1, y1, pred);
}

template <class Pred>
bool LabelPlacer::any_leader_near(double x0, double y0, double x1, double y1, Pred&& pred) const {
  return any_near(leader_cells_, std::span<const PlacedLabel>(leaders_), x0, y0, x1, y1, pred);
}

DiscIndex::DiscIndex(std::span<const ScreenDisc> discs) : discs_(discs.begin(), discs.end()) {
  for (std::size_t i = 0; i < discs_.size(); ++i) {
    const ScreenDisc& d = discs_[i];
    for_cells(d.x - d.radius, d.y - d.radius, d.x + d.radius, d.y + d.radius,
              [&](std::int64_t k) { cells_[k].push_back(static_cast<std::uint32_t>(i)); });
  }
}

template <class Pred>
bool DiscIndex::any_near(double x0, double y0, double x1, double y1, Pred&& pred) const {
  return hq::any_near(cells_, std::span<const ScreenDisc>(discs_), x0, y0, x1, y1, pred);
}

std::optional<PlacedLabel> LabelPlacer::place(const LabelRequest& label, const DiscIndex& obstacles) const {
  const ScreenDisc& anchor = label.anchor;
  auto is_own = [&](const ScreenDisc& d) {
    return anchor.id >= 0 ? d.id == anchor.id : d.x == anchor.x && d.y == anchor.y;
  };
  auto any_disc_near = [&](double x0, double y0, double x1, double y1, auto&& pred) {
    return obstacles.any_near(x0, y0, x1, y1, pred);
  };
  // A leader keeps options_.leader_clearance off the discs it must not cross.
  const double reach = options_.leader_clearance + 1.0;
  // A candidate, checked once: its placement (with a leader when it needs
  // one) and the first pass that takes it (0: clear; 1: its leader may run
  // over glyphs; 2: any free place whose leader runs along no earlier one;
  // 3: any free place; 4: not free).
  struct Candidate {
    int pass = 4;
    double room = 0.0;
    PlacedLabel placement;
  };
  auto evaluate = [&](const PixelRect& box) {
    Candidate c;
    if (!inside(box, options_.bounds) || box_meets_disc(box, anchor)) return c;
    const double bx1 = box.x + box.width, by1 = box.y + box.height;
    if (any_box_near(box.x, box.y, bx1, by1, [&](const PixelRect& b) { return boxes_overlap(box, b); })) return c;
    if (any_near(avoid_cells_, std::span<const PixelRect>(avoid_), box.x, box.y, bx1, by1, [&](const PixelRect& b) { return boxes_overlap(box, b); }))
      return c;
    if (any_disc_near(box.x, box.y, bx1, by1, [&](const ScreenDisc& d) { return box_meets_disc(box, d); })) return c;
    const double own = disc_box_gap(anchor, box);
    const bool is_far = own > options_.leader_distance;
    // (Far, it has a leader anyway: only a near box asks who else is beside it.)
    const double beside = own + options_.leader_distance;
    const bool is_beside_other =
        !is_far && any_disc_near(box.x - beside, box.y - beside, bx1 + beside, by1 + beside, [&](const ScreenDisc& d) {
          return !is_own(d) && disc_box_gap(d, box) < beside;
        });
    c.placement = is_far || is_beside_other || label.always_leader
                      ? with_leader(label.leader_from.value_or(anchor), box)
                      : PlacedLabel{box};
    c.room = 3.0 * options_.leader_distance;
    const double room = c.room;
    any_disc_near(box.x - room, box.y - room, bx1 + room, by1 + room, [&](const ScreenDisc& o) {
      if (!is_own(o)) c.room = std::min(c.room, disc_box_gap(o, box));
      return false;
    });
    const PlacedLabel& r = c.placement;
    auto any_disc_on_leader = [&](auto&& pred) {
      return any_disc_near(std::min(r.leader_x0, r.leader_x1) - reach, std::min(r.leader_y0, r.leader_y1) - reach,
                           std::max(r.leader_x0, r.leader_x1) + reach, std::max(r.leader_y0, r.leader_y1) + reach, pred);
    };
    // Never (any pass): a leader over a protected disc; with strict_leaders
    // over another leader either.
    if (r.has_leader) {
      if (label.strict_leaders && any_leader_near(r.leader_x0, r.leader_y0, r.leader_x1, r.leader_y1,
                                                  [&](const PlacedLabel& l) { return leaders_cross(l, r); }))
        return c;
      // (A protected disc holding the leader's start, e.g. a marker group
      // inside #0, cannot be avoided: it counts only when the leader heads
      // into it, leader_over_disc.)
      if (any_disc_on_leader([&](const ScreenDisc& d) {
            return d.id >= 0 && d.id < label.protect_below && !is_own(d) && leader_over_disc(r, d);
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
    c.pass = 3;
    // Only the last resort: a leader that runs along an earlier one (the
    // 44e shots: a fan's "x13" leader 2 px under "#1 (10)"'s reads as one
    // line; the 44e review: 6 px beside it, taken as any free place).
    if (r.has_leader &&
        any_leader_near(std::min(r.leader_x0, r.leader_x1) - 8.0, std::min(r.leader_y0, r.leader_y1) - 8.0,
                        std::max(r.leader_x0, r.leader_x1) + 8.0, std::max(r.leader_y0, r.leader_y1) + 8.0,
                        [&](const PlacedLabel& l) { return leaders_run_together(l, r); }))
      return c;
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
      // (Nor here does a disc holding the leader's start count, unless the
      // leader heads into it.)
      if (any_disc_on_leader([&](const ScreenDisc& d) {
            return !is_own(d) &&
                   leader_over_disc(r, ScreenDisc{d.x, d.y, d.radius + options_.leader_clearance, d.id});
          }))
        return c;
    }
    c.pass = 0;
    return c;
  };
  // The rings' candidates (ring_directions), evaluated as the passes first
  // reach them.
  std::vector<std::vector<Candidate>> rings;
  const double spacing = std::max({static_cast<double>(label.height), options_.ring_step, 1.0});
  for (int pass = 0; pass <= 3; ++pass)
    for (int ring = 0; ring <= options_.rings; ++ring) {
      if (static_cast<std::size_t>(ring) == rings.size()) {
        const double distance = anchor.radius + options_.gap + ring * options_.ring_step;
        rings.emplace_back();
        for (const auto& d : ring_directions(distance, spacing))
          rings.back().push_back(evaluate(box_at(anchor.x + d[0] * distance, anchor.y + d[1] * distance, d,
                                                 label.width, label.height)));
      }
      // Of the ring's candidates this pass takes, the one farthest from the
      // other discs (up to 3 leader distances; ties: the order of
      // ring_directions), so a label leans away from its neighbours' glyphs.
      const Candidate* best = nullptr;
      for (const Candidate& c : rings[static_cast<std::size_t>(ring)])
        if (c.pass <= pass && (!best || c.room > best->room)) best = &c;
      if (best) return best->placement;
    }
  return std::nullopt;
}

namespace {

// A callout's leader: from start's edge towards (x, y), ending there.
PlacedLabel callout_leader(const ScreenDisc& start, const PixelRect& box, double x, double y) {
  const double dx = x - start.x, dy = y - start.y;
  const double length = std::max(std::hypot(dx, dy), 1e-9);
  const double r = std::min(start.radius, length);
  PlacedLabel p{box};
  p.has_leader = true;
  p.leader_x0 = start.x + dx / length * r;
  p.leader_y0 = start.y + dy / length * r;
  p.leader_x1 = x;
  p.leader_y1 = y;
  return p;
}

}  // namespace

namespace {

constexpr double kNoCallout = std::numeric_limits<double>::infinity();
// Added to a callout's cost when its leader crosses a protected disc.
constexpr double kProtectedPenalty = 1e6;

// place_callout_columns' columns; cost: their total (kNoCallout: no room).
std::vector<PlacedLabel> callout_columns(std::span<const CalloutLabel> labels, std::span<const ScreenDisc> obstacles,
                                         std::span<const PixelRect> taken, const PixelRect& bounds, double gap,
                                         const std::function<double(const PixelRect&)>& box_cost, double& total) {
  total = kNoCallout;
  const std::size_t n = labels.size();
  if (n == 0) return {};
  int tallest = 0, widest = 0;
  for (const CalloutLabel& l : labels) {
    tallest = std::max(tallest, l.height);
    widest = std::max(widest, l.width);
  }
  const int margin = static_cast<int>(std::lround(gap));
  const int step = tallest + static_cast<int>(std::lround(3.0 * gap));
  // Slots start every quarter step (a label sits nearer its glyph's y);
  // two labels of a column are a step apart.
  const int fine = std::max(1, step / 4);
  // The columns' inner edges (x of the leaders' ends) and their free slots.
  struct Column {
    double inner = 0;
    bool is_left = true;
    std::vector<int> slot_y;        // free slots' top
    std::vector<double> slot_cost;  // box_cost of each
  };
  // Each side's candidate columns: at the edge of bounds, then every
  // max(20, widest / 2) px inwards up to the middle (a column near the
  // glyphs over empty space shortens the leaders).
  std::vector<Column> sides[2];
  const double shift = std::max(20.0, 0.5 * widest);
  for (double inner = bounds.x + margin + widest; inner <= bounds.x + 0.5 * bounds.width; inner += shift) {
    sides[0].push_back({inner, true, {}, {}});
    sides[1].push_back({2.0 * bounds.x + bounds.width - inner, false, {}, {}});
  }
  if (sides[0].empty()) return {};
  for (auto& side : sides)
    for (Column& c : side)
    for (int y = bounds.y + margin; y + tallest <= bounds.y + bounds.height - margin; y += fine) {
      const PixelRect box{static_cast<int>(c.is_left ? c.inner - widest : c.inner), y, widest, tallest};
      if (std::any_of(taken.begin(), taken.end(), [&](const PixelRect& t) { return boxes_overlap(box, t); }) ||
          std::any_of(obstacles.begin(), obstacles.end(), [&](const ScreenDisc& d) { return box_meets_disc(box, d); }))
        continue;
      c.slot_y.push_back(y);
      c.slot_cost.push_back(box_cost ? box_cost(box) : 0.0);
    }
  auto box_of = [&](const Column& c, std::size_t label, int y) {
    const CalloutLabel& l = labels[label];
    // Boxes hug the inner edge and sit centred in their slot.
    const int top = y + (tallest - l.height) / 2;
    return PixelRect{static_cast<int>(c.is_left ? c.inner - l.width : c.inner), top, l.width, l.height};
  };
  auto attach_y = [&](int y) { return y + 0.5 * tallest; };
  // Labels by their start's x (ties: y, then index).
  std::vector<std::size_t> by_x(n);
  for (std::size_t i = 0; i < n; ++i) by_x[i] = i;
  std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) {
    const ScreenDisc &p = labels[a].start, &q = labels[b].start;
    return p.x != q.x ? p.x < q.x : p.y != q.y ? p.y < q.y : a < b;
  });
  constexpr double kNone = kNoCallout;
  // A leader's cost: its length; kNone when its start is not on the
  // column's inner side (it would run through the column's boxes); plus
  // kProtectedPenalty when it crosses a protected disc that does not hold
  // its start.
  auto leader_cost = [&](const Column& c, std::size_t label, int y) {
    const ScreenDisc& s = labels[label].start;
    if (c.is_left ? s.x < c.inner + gap : s.x > c.inner - gap) return kNone;
    const PlacedLabel p = callout_leader(s, PixelRect{}, c.inner, attach_y(y));
    double cost = std::hypot(c.inner - s.x, attach_y(y) - s.y);
    for (const ScreenDisc& d : obstacles)
      if (d.id >= 0 && d.id < labels[label].protect_below && d.id != s.id && leader_over_disc(p, d)) {
        cost += kProtectedPenalty;
        break;
      }
    return cost;
  };
  // The order-preserving assignment of members (sorted by y) to c's slots
  // of least cost: the slot index of each member, or empty.
  auto assign = [&](const Column& c, std::vector<std::size_t> members, double& cost) {
    std::sort(members.begin(), members.end(), [&](std::size_t a, std::size_t b) {
      const ScreenDisc &p = labels[a].start, &q = labels[b].start;
      return p.y != q.y ? p.y < q.y : p.x != q.x ? p.x < q.x : a < b;
    });
    const std::size_t m = members.size(), k = c.slot_y.size();
    cost = 0.0;
    std::vector<std::pair<std::size_t, std::size_t>> result;  // (label, slot)
    if (m == 0) return result;
    if (m > k) {
      cost = kNone;
      return result;
    }
    // before[j]: the slots at least a step above slot j (a prefix).
    std::vector<std::size_t> before(k);
    for (std::size_t j = 0; j < k; ++j)
      before[j] = static_cast<std::size_t>(std::upper_bound(c.slot_y.begin(), c.slot_y.end(), c.slot_y[j] - step) -
                                           c.slot_y.begin());
    // best[i][j]: least cost of members 0..i-1 in slots 0..j-1, a step apart.
    std::vector<std::vector<double>> best(m + 1, std::vector<double>(k + 1, kNone));
    std::vector<std::vector<char>> took(m + 1, std::vector<char>(k + 1, 0));
    for (std::size_t j = 0; j <= k; ++j) best[0][j] = 0.0;
    for (std::size_t i = 1; i <= m; ++i)
      for (std::size_t j = i; j <= k; ++j) {
        const double here =
            best[i - 1][before[j - 1]] + leader_cost(c, members[i - 1], c.slot_y[j - 1]) + c.slot_cost[j - 1];
        best[i][j] = best[i][j - 1];
        if (here < best[i][j]) {
          best[i][j] = here;
          took[i][j] = 1;
        }
      }
    cost = best[m][k];
    if (!(cost < kNone)) return result;
    std::size_t j = k;
    for (std::size_t i = m; i > 0; --i) {
      while (!took[i][j]) --j;
      result.push_back({members[i - 1], j - 1});
      j = before[j - 1];
    }
    return result;
  };
  double best_cost = kNone;
  std::vector<std::pair<std::size_t, std::size_t>> best_sides[2];
  std::size_t best_column[2] = {0, 0};
  for (std::size_t split = 0; split <= n; ++split) {
    double costs[2] = {kNone, kNone};
    std::vector<std::pair<std::size_t, std::size_t>> chosen[2];
    std::size_t column[2] = {0, 0};
    for (int side = 0; side < 2; ++side) {
      const std::vector<std::size_t> members =
          side == 0 ? std::vector<std::size_t>(by_x.begin(), by_x.begin() + static_cast<std::ptrdiff_t>(split))
                    : std::vector<std::size_t>(by_x.begin() + static_cast<std::ptrdiff_t>(split), by_x.end());
      for (std::size_t k = 0; k < sides[side].size(); ++k) {
        double cost = kNone;
        auto a = assign(sides[side][k], members, cost);
        if (cost < costs[side]) {
          costs[side] = cost;
          chosen[side] = std::move(a);
          column[side] = k;
        }
        if (members.empty()) break;
      }
    }
    const double total = costs[0] + costs[1];
    if (total < best_cost) {
      best_cost = total;
      for (int side = 0; side < 2; ++side) {
        best_sides[side] = std::move(chosen[side]);
        best_column[side] = column[side];
      }
    }
  }
  if (!(best_cost < kNone)) return {};
  total = best_cost;
  std::vector<PlacedLabel> placed(n);
  for (int side = 0; side < 2; ++side) {
    const Column& c = sides[side][best_column[side]];
    auto& members = best_sides[side];
    auto leader = [&](std::size_t label, std::size_t slot) {
      return callout_leader(labels[label].start, box_of(c, label, c.slot_y[slot]), c.inner, attach_y(c.slot_y[slot]));
    };
    // Uncross: swap the slots of two crossing leaders (bounded; each swap
    // shortens the total length).
    for (std::size_t round = 0; round < 4 * n * n + 4; ++round) {
      bool swapped = false;
      for (std::size_t a = 0; a < members.size() && !swapped; ++a)
        for (std::size_t b = a + 1; b < members.size() && !swapped; ++b)
          if (leaders_cross(leader(members[a].first, members[a].second), leader(members[b].first, members[b].second))) {
            std::swap(members[a].second, members[b].second);
            swapped = true;
          }
      if (!swapped) break;
    }
    for (const auto& [label, slot] : members) placed[label] = leader(label, slot);
  }
  return placed;
}

// x and y swapped (rows as columns).
PixelRect transposed(const PixelRect& r) { return {r.y, r.x, r.height, r.width}; }
ScreenDisc transposed(const ScreenDisc& d) { return {d.y, d.x, d.radius, d.id}; }

}  // namespace

std::vector<PlacedLabel> place_callout_columns(std::span<const CalloutLabel> labels,
                                               std::span<const ScreenDisc> obstacles,
                                               std::span<const PixelRect> taken, const PixelRect& bounds, double gap,
                                               const std::function<double(const PixelRect&)>& box_cost) {
  double column_cost = kNoCallout, row_cost = kNoCallout;
  std::vector<PlacedLabel> columns = callout_columns(labels, obstacles, taken, bounds, gap, box_cost, column_cost);
  // Rows: the same with x and y swapped.
  std::vector<CalloutLabel> t_labels;
  for (const CalloutLabel& l : labels) t_labels.push_back({transposed(l.start), l.height, l.width, l.protect_below});
  std::vector<ScreenDisc> t_obstacles;
  for (const ScreenDisc& d : obstacles) t_obstacles.push_back(transposed(d));
  std::vector<PixelRect> t_taken;
  for (const PixelRect& r : taken) t_taken.push_back(transposed(r));
  std::function<double(const PixelRect&)> t_cost;
  if (box_cost) t_cost = [&](const PixelRect& r) { return box_cost(transposed(r)); };
  std::vector<PlacedLabel> rows =
      callout_columns(t_labels, t_obstacles, t_taken, transposed(bounds), gap, t_cost, row_cost);
  if (!(row_cost < column_cost)) return columns;
  for (PlacedLabel& p : rows) {
    p.box = transposed(p.box);
    std::swap(p.leader_x0, p.leader_y0);
    std::swap(p.leader_x1, p.leader_y1);
  }
  return rows;
}

std::vector<std::optional<PlacedLabel>> place_labels(std::span<const LabelRequest> labels,
                                                     std::span<const ScreenDisc> obstacles,
                                                     std::span<const PixelRect> taken,
                                                     const LabelLayoutOptions& options,
                                                     std::span<const PlacedLabel> earlier) {
  LabelPlacer placer(taken, options);
  for (const PlacedLabel& l : earlier) placer.add(l);
  const DiscIndex index(obstacles);
  std::vector<std::optional<PlacedLabel>> placed(labels.size());
  for (std::size_t i = 0; i < labels.size(); ++i) {
    placed[i] = placer.place(labels[i], index);
    if (placed[i]) placer.add(*placed[i]);
  }
  return placed;
}

}  // namespace hq
