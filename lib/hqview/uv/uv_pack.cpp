#include "hqview/uv/uv_pack.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <numeric>
#include <unordered_map>

#include <tbb/parallel_for.h>

namespace hq {

// The corners that may be vertices of their convex hull: those not inside,
// by a margin far above rounding, the polygon of the extreme corners in
// eight directions (Akl and Toussaint's filter). A chart's corners repeat
// each vertex about six times and most lie inside: the hull's sort then
// sees a few hundred points instead of every corner.
std::vector<Uv> hull_candidates(const std::vector<Uv>& corners) {
  if (corners.size() < 64) return corners;
  // Extreme corners along the directions k * 45 degrees, counter-clockwise.
  static constexpr double kDirections[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  std::array<Uv, 8> extreme;
  std::array<double, 8> best;
  best.fill(-INFINITY);
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (const Uv& q : corners) {
    for (int k = 0; k < 8; ++k) {
      const double d = kDirections[k][0] * q[0] + kDirections[k][1] * q[1];
      if (d > best[static_cast<std::size_t>(k)]) best[static_cast<std::size_t>(k)] = d, extreme[static_cast<std::size_t>(k)] = q;
    }
    lo[0] = std::min(lo[0], q[0]), lo[1] = std::min(lo[1], q[1]);
    hi[0] = std::max(hi[0], q[0]), hi[1] = std::max(hi[1], q[1]);
  }
  std::vector<Uv> polygon;
  for (const Uv& e : extreme)
    if (polygon.empty() || (e != polygon.back() && e != polygon.front())) polygon.push_back(e);
  if (polygon.size() < 3) return corners;
  const double extent = std::max(hi[0] - lo[0], hi[1] - lo[1]);
  const double margin = 1e-9 * extent * extent;
  std::vector<Uv> kept;
  for (const Uv& q : corners) {
    bool inside = true;
    for (std::size_t i = 0; i < polygon.size() && inside; ++i) {
      const Uv& a = polygon[i];
      const Uv& b = polygon[(i + 1) % polygon.size()];
      inside = (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]) > margin;
    }
    if (!inside) kept.push_back(q);
  }
  return kept;
}

namespace {

// One chart on the grid: the cells its triangles touch (`mask`) and the same
// dilated by the gutter (`halo`), rows of bits, width x height cells.
struct Footprint {
  int width = 0, height = 0;
  std::vector<std::vector<std::uint8_t>> mask, halo;
  std::vector<std::vector<std::array<int, 2>>> runs;  // per row: [begin, end) columns of the mask
};

// Does the triangle (a, b, c) meet the closed square [x0, x0+s] x [y0, y0+s]?
// Separating axes: the square's two axes and the triangle's three edge normals.
bool triangle_meets_square(const Uv& a, const Uv& b, const Uv& c, double x0, double y0, double s) {
  const Uv p[3] = {a, b, c};
  const Uv q[4] = {{x0, y0}, {x0 + s, y0}, {x0 + s, y0 + s}, {x0, y0 + s}};
  for (int axis = 0; axis < 2; ++axis) {
    const double lo = std::min({a[axis], b[axis], c[axis]}), hi = std::max({a[axis], b[axis], c[axis]});
    const double qlo = axis == 0 ? x0 : y0;
    if (hi < qlo || lo > qlo + s) return false;
  }
  for (int e = 0; e < 3; ++e) {
    const Uv& u = p[e];
    const Uv& v = p[(e + 1) % 3];
    const double nx = v[1] - u[1], ny = u[0] - v[0];
    double tlo = INFINITY, thi = -INFINITY, slo = INFINITY, shi = -INFINITY;
    for (const Uv& r : p) {
      const double d = nx * r[0] + ny * r[1];
      tlo = std::min(tlo, d), thi = std::max(thi, d);
    }
    for (const Uv& r : q) {
      const double d = nx * r[0] + ny * r[1];
      slo = std::min(slo, d), shi = std::max(shi, d);
    }
    if (thi < slo || shi < tlo) return false;
  }
  return true;
}

// Rasterises chart corners (already moved so that their box starts at the
// origin, in cells) turned by `turn` quarter turns.
Footprint rasterise(const std::vector<Uv>& corners, int gutter) {
  double w = 0, h = 0;
  for (const Uv& p : corners) w = std::max(w, p[0]), h = std::max(h, p[1]);
  Footprint f;
  f.width = static_cast<int>(std::floor(w)) + 1 + 2 * gutter;
  f.height = static_cast<int>(std::floor(h)) + 1 + 2 * gutter;
  f.mask.assign(static_cast<std::size_t>(f.height), std::vector<std::uint8_t>(static_cast<std::size_t>(f.width), 0));
  for (std::size_t i = 0; i + 2 < corners.size(); i += 3) {
    const Uv &a = corners[i], &b = corners[i + 1], &c = corners[i + 2];
    const int x0 = static_cast<int>(std::floor(std::min({a[0], b[0], c[0]})));
    const int x1 = static_cast<int>(std::floor(std::max({a[0], b[0], c[0]})));
    const int y0 = static_cast<int>(std::floor(std::min({a[1], b[1], c[1]})));
    const int y1 = static_cast<int>(std::floor(std::max({a[1], b[1], c[1]})));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        if ((x == x0 && x == x1 && y == y0 && y == y1) || triangle_meets_square(a, b, c, x, y, 1.0))
          f.mask[static_cast<std::size_t>(y + gutter)][static_cast<std::size_t>(x + gutter)] = 1;
  }
  f.runs.resize(static_cast<std::size_t>(f.height));
  for (int y = 0; y < f.height; ++y) {
    const auto& row = f.mask[static_cast<std::size_t>(y)];
    for (int x = 0; x < f.width;) {
      if (!row[static_cast<std::size_t>(x)]) {
        ++x;
        continue;
      }
      const int begin = x;
      while (x < f.width && row[static_cast<std::size_t>(x)]) ++x;
      f.runs[static_cast<std::size_t>(y)].push_back({begin, x});
    }
  }
  f.halo = f.mask;
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      if (!f.mask[static_cast<std::size_t>(y)][static_cast<std::size_t>(x)]) continue;
      for (int dy = -gutter; dy <= gutter; ++dy)
        for (int dx = -gutter; dx <= gutter; ++dx) {
          const int yy = y + dy, xx = x + dx;
          if (yy >= 0 && yy < f.height && xx >= 0 && xx < f.width)
            f.halo[static_cast<std::size_t>(yy)][static_cast<std::size_t>(xx)] = 1;
        }
    }
  return f;
}

// Corners turned by `turn` quarter turns (exact: coordinate swaps and
// negations), moved so that their box starts at (0, 0).
std::vector<Uv> turned(const std::vector<Uv>& corners, int turn) {
  std::vector<Uv> out(corners.size());
  double lo[2] = {INFINITY, INFINITY};
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Uv& p = corners[i];
    out[i] = turn == 0 ? p : turn == 1 ? Uv{-p[1], p[0]} : turn == 2 ? Uv{-p[0], -p[1]} : Uv{p[1], -p[0]};
    lo[0] = std::min(lo[0], out[i][0]), lo[1] = std::min(lo[1], out[i][1]);
  }
  for (Uv& p : out) p = {p[0] - lo[0], p[1] - lo[1]};
  return out;
}

// The turn (radians, within a quarter turn either way) that makes the
// bounding box of `corners` smallest: a side of the smallest box lies on a
// side of the convex hull (rotating calipers, every hull edge tried).
double smallest_box_turn(const std::vector<Uv>& corners) {
  std::vector<Uv> p = hull_candidates(corners);
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return 0.0;
  // Andrew's monotone chain.
  const auto cross = [](const Uv& o, const Uv& a, const Uv& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  };
  std::vector<Uv> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);
  const auto box_area = [&](double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (const Uv& q : hull) {
      const double x = c * q[0] - s * q[1], y = s * q[0] + c * q[1];
      lo[0] = std::min(lo[0], x), hi[0] = std::max(hi[0], x), lo[1] = std::min(lo[1], y), hi[1] = std::max(hi[1], y);
    }
    return (hi[0] - lo[0]) * (hi[1] - lo[1]);
  };
  double best = 0.0, best_area = box_area(0.0);
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Uv& a = hull[i];
    const Uv& b = hull[(i + 1) % hull.size()];
    double angle = -std::atan2(b[1] - a[1], b[0] - a[0]);
    // Fold into [-pi/4, pi/4]: a quarter turn more or less gives the same box.
    angle = std::remainder(angle, std::numbers::pi / 2);
    const double area = box_area(angle);
    if (area < best_area) best_area = area, best = angle;
  }
  // Not worth turning for a box under 3 % smaller.
  return best_area < 0.97 * box_area(0.0) ? best : 0.0;
}

// Corners turned by `angle` about the origin, moved so that their box
// starts at (0, 0).
std::vector<Uv> rotated(const std::vector<Uv>& corners, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  std::vector<Uv> out(corners.size());
  double lo[2] = {INFINITY, INFINITY};
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Uv& p = corners[i];
    out[i] = {c * p[0] - s * p[1], s * p[0] + c * p[1]};
    lo[0] = std::min(lo[0], out[i][0]), lo[1] = std::min(lo[1], out[i][1]);
  }
  for (Uv& p : out) p = {p[0] - lo[0], p[1] - lo[1]};
  return out;
}

struct Shape {
  std::vector<Uv> corners;
  Footprint footprint;
};

class Grid {
 public:
  explicit Grid(int width) : width_(width) {}
  int width() const { return width_; }
  int height() const { return static_cast<int>(rows_.size()); }

  // Whether f's mask meets no occupied cell at (x, y): per mask run, the
  // row's prefix count of occupied cells; the middle row first (most often
  // the one that collides).
  bool fits(const Footprint& f, int x, int y) const {
    if (x < 0 || x + f.width > width_) return false;
    const int mid = f.height / 2;
    for (int i = 0; i < f.height; ++i) {
      const int r = i == 0 ? mid : (i <= mid ? i - 1 : i);
      const int gy = y + r;
      if (gy >= height()) continue;  // above the used rows everything is free
      const auto& count = prefix_[static_cast<std::size_t>(gy)];
      for (const auto& [c0, c1] : f.runs[static_cast<std::size_t>(r)])
        if (count[static_cast<std::size_t>(x + c1)] != count[static_cast<std::size_t>(x + c0)]) return false;
    }
    return true;
  }

  // Stores the halo, so that later masks keep the gutter.
  void place(const Footprint& f, int x, int y) {
    while (height() < y + f.height) rows_.emplace_back(static_cast<std::size_t>(width_), 0);
    for (int r = 0; r < f.height; ++r)
      for (int c = 0; c < f.width; ++c)
        if (f.halo[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)])
          rows_[static_cast<std::size_t>(y + r)][static_cast<std::size_t>(x + c)] = 1;
    prefix_.resize(rows_.size());
    for (int r = 0; r < f.height; ++r) {
      const auto& row = rows_[static_cast<std::size_t>(y + r)];
      auto& count = prefix_[static_cast<std::size_t>(y + r)];
      count.assign(row.size() + 1, 0);
      for (std::size_t c = 0; c < row.size(); ++c) count[c + 1] = count[c] + row[c];
    }
  }

  // Lowest row, then leftmost column where f fits, looking at no more than
  // `budget` places; past the budget (or the used rows) it goes on top,
  // where everything is free.
  std::array<int, 2> lowest_place(const Footprint& f, long budget) const {
    long looked = 0;
    for (int y = 0; y < height(); ++y) {
      if (full_[static_cast<std::size_t>(std::min(y + f.height / 2, height() - 1))]) continue;
      for (int x = 0; x + f.width <= width_; ++x) {
        if (fits(f, x, y)) return {x, y};
        if (++looked > budget) return {0, height()};
      }
    }
    return {0, height()};
  }

  // Marks rows without a free cell (skipped by lowest_place).
  void update_full_rows(int from, int to) {
    full_.resize(rows_.size(), 0);
    for (int y = std::max(from, 0); y < std::min(to, height()); ++y) {
      const auto& row = rows_[static_cast<std::size_t>(y)];
      full_[static_cast<std::size_t>(y)] = std::find(row.begin(), row.end(), 0) == row.end();
    }
  }

 private:
  int width_;
  std::vector<std::vector<std::uint8_t>> rows_;
  std::vector<std::uint8_t> full_;
  std::vector<std::vector<int>> prefix_;  // per row: occupied cells left of each column
};

// Places looked at per chart before it goes on top of the packed rows.
constexpr long kPlaceBudget = 100'000;

}  // namespace

// A chart's shapes and what they were made from: equal inputs, equal shapes.
struct PackShapeCache::Impl {
  struct Entry {
    std::vector<Index> triangles;
    std::vector<Uv> corners;  // the chart's layout, 3 per triangle
    double cell = 0.0;
    bool may_turn = false;
    int gutter = 0;
    bool tilt = false;
    std::shared_ptr<const std::vector<Shape>> shapes;
  };
  std::unordered_multimap<std::uint64_t, Entry> entries;  // by a hash of the inputs
  std::size_t reused = 0;  // charts of the last call whose shapes came from here
};

PackShapeCache::PackShapeCache() : impl(std::make_unique<Impl>()) {}
PackShapeCache::~PackShapeCache() = default;
void PackShapeCache::clear() { impl->entries.clear(); }
std::size_t PackShapeCache::num_reused() const { return impl->reused; }

void pack_charts(std::span<const Uv> local, const std::vector<std::vector<Index>>& charts, std::vector<Uv>& packed,
                 const PackOptions& options, PackShapeCache* cache) {
  packed.assign(local.size(), Uv{0.0, 0.0});
  std::vector<double> area(charts.size(), 0.0);
  double total = 0.0, longest = 0.0;
  std::vector<std::array<double, 4>> box(charts.size(), {INFINITY, INFINITY, -INFINITY, -INFINITY});
  for (std::size_t c = 0; c < charts.size(); ++c) {
    for (Index t : charts[c]) {
      const Uv* p = &local[3 * static_cast<std::size_t>(t)];
      area[c] += std::abs(uv_signed_area(p));
      for (int k = 0; k < 3; ++k)
        box[c] = {std::min(box[c][0], p[k][0]), std::min(box[c][1], p[k][1]), std::max(box[c][2], p[k][0]),
                  std::max(box[c][3], p[k][1])};
    }
    total += area[c];
    if (!charts[c].empty()) longest = std::max({longest, box[c][2] - box[c][0], box[c][3] - box[c][1]});
  }
  // Cell size: the ideal square of all chart area is `resolution` cells on a
  // side; a surface of degenerate charts falls back to its longest chart.
  double cell = total > 0.0 ? std::sqrt(total) / options.resolution : 0.0;
  if (!(cell > 0.0) || !std::isfinite(cell)) cell = longest > 0.0 ? longest / options.resolution : 1.0;
  // Never more than ~4 resolution of cells along one chart (thin long charts).
  cell = std::max(cell, longest / (4.0 * options.resolution));

  std::vector<Index> order;
  for (std::size_t c = 0; c < charts.size(); ++c)
    if (!charts[c].empty()) order.push_back(static_cast<Index>(c));
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return area[a] > area[b]; });

  int widest = 0;
  for (Index c : order)
    widest = std::max(widest, static_cast<int>((box[c][2] - box[c][0]) / cell) + 2 + 2 * options.gutter_cells);
  // Each chart's corners (in cells) and footprint, per allowed quarter turn;
  // the same for every grid width tried. From the cache when it has them.
  using Entry = PackShapeCache::Impl::Entry;
  const auto may_turn_of = [&](Index c) { return total > 0.0 && area[c] < options.fixed_orientation_area * total; };
  const auto chart_corners = [&](Index c) {
    std::vector<Uv> corners;
    corners.reserve(3 * charts[c].size());
    for (Index t : charts[c])
      for (int k = 0; k < 3; ++k) corners.push_back(local[3 * static_cast<std::size_t>(t) + k]);
    return corners;
  };
  const auto hash_of = [&](Index c, const std::vector<Uv>& corners) {
    std::uint64_t h = 0x9E3779B97F4A7C15ULL ^ std::bit_cast<std::uint64_t>(cell);
    const auto mix = [&](std::uint64_t x) { h = (h ^ x) * 0xFF51AFD7ED558CCDULL; };
    for (Index t : charts[c]) mix(static_cast<std::uint32_t>(t));
    for (const Uv& p : corners) mix(std::bit_cast<std::uint64_t>(p[0]) ^ (std::bit_cast<std::uint64_t>(p[1]) << 1));
    return h ^ (h >> 29);
  };
  std::vector<std::shared_ptr<const std::vector<Shape>>> shapes_of(charts.size());
  std::vector<std::vector<Uv>> layout_of(charts.size());
  std::vector<std::uint64_t> key_of(charts.size(), 0);
  std::vector<Index> to_make;
  if (cache != nullptr) cache->impl->reused = 0;
  for (Index c : order) {
    if (cache == nullptr) {
      to_make.push_back(c);
      continue;
    }
    layout_of[static_cast<std::size_t>(c)] = chart_corners(c);
    key_of[static_cast<std::size_t>(c)] = hash_of(c, layout_of[static_cast<std::size_t>(c)]);
    const auto [first, last] = cache->impl->entries.equal_range(key_of[static_cast<std::size_t>(c)]);
    for (auto it = first; it != last; ++it) {
      const Entry& e = it->second;
      if (e.cell == cell && e.may_turn == may_turn_of(c) && e.gutter == options.gutter_cells &&
          e.tilt == options.tilt_to_smallest_box && e.triangles == charts[c] &&
          e.corners == layout_of[static_cast<std::size_t>(c)]) {
        shapes_of[static_cast<std::size_t>(c)] = e.shapes;
        ++cache->impl->reused;
        break;
      }
    }
    if (!shapes_of[static_cast<std::size_t>(c)]) to_make.push_back(c);
  }
  tbb::parallel_for(std::size_t{0}, to_make.size(), [&](std::size_t o) {
    const Index c = to_make[o];
    // The layout in cells, its box at the origin.
    std::vector<Uv> corners = cache != nullptr ? layout_of[static_cast<std::size_t>(c)] : chart_corners(c);
    for (Uv& p : corners) p = {(p[0] - box[c][0]) / cell, (p[1] - box[c][1]) / cell};
    const bool may_turn = may_turn_of(c);
    // As laid out (the model's up axis up), and turned by at most an eighth
    // of a turn to the smallest bounding box; small charts also by quarter
    // turns of either.
    const double tilt = options.tilt_to_smallest_box ? smallest_box_turn(corners) : 0.0;
    auto shapes = std::make_shared<std::vector<Shape>>();
    for (int tilted = 0; tilted < (tilt != 0.0 ? 2 : 1); ++tilted) {
      const std::vector<Uv> base = tilted ? rotated(corners, tilt) : corners;
      for (int turn = 0; turn < (may_turn ? 4 : 1); ++turn) {
        Shape shape;
        shape.corners = turned(base, turn);
        shape.footprint = rasterise(shape.corners, options.gutter_cells);
        shapes->push_back(std::move(shape));
      }
    }
    shapes_of[static_cast<std::size_t>(c)] = std::move(shapes);
  });
  if (cache != nullptr)
    for (Index c : to_make)
      cache->impl->entries.emplace(
          key_of[static_cast<std::size_t>(c)],
          Entry{charts[c], std::move(layout_of[static_cast<std::size_t>(c)]), cell, may_turn_of(c),
                options.gutter_cells, options.tilt_to_smallest_box, shapes_of[static_cast<std::size_t>(c)]});
  // Grid widths tried, in parallel (in units of the ideal side; finer steps
  // over a wider range for a few charts, which are cheap to place): per
  // width only where each chart goes (its shape and cell). The width whose
  // packing fills the square best wins (ties: the first), and only its
  // corners are written.
  struct Placement {
    const Shape* shape = nullptr;
    std::array<int, 2> at{};
  };
  const bool few = order.size() <= 64;
  const int steps = few ? 26 : 6;
  std::vector<std::vector<Placement>> placements_of(static_cast<std::size_t>(steps) + 1);
  std::vector<double> extent_of(placements_of.size()), fill_of(placements_of.size());
  tbb::parallel_for(0, steps + 1, [&](int step) {
    const double factor = few ? 0.7 + 0.05 * step : 0.9 + 0.1 * step;
    const int side = static_cast<int>(std::ceil(options.resolution * factor));
    Grid grid(std::max(side, widest));
    std::vector<Placement>& placements = placements_of[static_cast<std::size_t>(step)];
    placements.assign(charts.size(), Placement{});
    int used_width = 0, used_height = 0;
    for (Index c : order) {
      const std::vector<Shape>& shapes = *shapes_of[static_cast<std::size_t>(c)];
      Placement& best = placements[static_cast<std::size_t>(c)];
      long best_score = -1;
      for (const Shape& shape : shapes) {
        if (shape.footprint.width > grid.width()) continue;
        const auto at = grid.lowest_place(shape.footprint, kPlaceBudget);
        // Lowest top edge first, then leftmost.
        const long score = static_cast<long>(at[1] + shape.footprint.height) * 1'000'000L + at[0];
        if (best_score < 0 || score < best_score) best_score = score, best = {&shape, at};
      }
      if (best.shape == nullptr) continue;  // cannot happen: the grid is as wide as the widest chart unturned
      const Footprint& f = best.shape->footprint;
      grid.place(f, best.at[0], best.at[1]);
      grid.update_full_rows(best.at[1], best.at[1] + f.height);
      used_width = std::max(used_width, best.at[0] + f.width);
      used_height = std::max(used_height, best.at[1] + f.height);
    }
    const double extent = std::max({used_width, used_height, 1});
    extent_of[static_cast<std::size_t>(step)] = extent;
    fill_of[static_cast<std::size_t>(step)] = total / (cell * cell) / (extent * extent);
  });
  std::size_t chosen = 0;
  for (std::size_t i = 1; i < fill_of.size(); ++i)
    if (fill_of[i] > fill_of[chosen]) chosen = i;
  const std::vector<Placement>& best_placements = placements_of[chosen];
  const double extent = extent_of[chosen];
  for (Index c : order) {
    const Placement& p = best_placements[static_cast<std::size_t>(c)];
    if (p.shape == nullptr) continue;
    const double ox = p.at[0] + options.gutter_cells, oy = p.at[1] + options.gutter_cells;
    for (std::size_t i = 0; i < charts[c].size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const Uv& q = p.shape->corners[3 * i + k];
        packed[3 * static_cast<std::size_t>(charts[c][i]) + k] = {std::clamp((q[0] + ox) / extent, 0.0, 1.0),
                                                                   std::clamp((q[1] + oy) / extent, 0.0, 1.0)};
      }
  }
}

}  // namespace hq
