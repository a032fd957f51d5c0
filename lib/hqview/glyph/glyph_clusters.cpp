#include "hqview/glyph/glyph_clusters.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "hqview/core/box3.h"
#include "hqview/core/error.h"
#include "hqview/glyph/cell_keys.h"

namespace hq {
namespace {

// Cells are this much (relative) larger than the glyph diameters they are
// sized for, so that rounding in the cell coordinates (about 1e-9 of a cell)
// can never put two overlapping glyphs two cells apart.
constexpr double kCellMargin = 1e-6;
// Cell coordinates are packed into 21 bits per axis of a 63-bit key (cell_keys.h).
using glyph_cells::cell_coord;
using glyph_cells::cell_coords;
using glyph_cells::cell_key;
using glyph_cells::kMaxCellCoord;
// Glyphs above this radius percentile (or above a quarter of the largest
// radius) search a box around themselves instead of setting the cell size.
constexpr double kSmallRadiusQuantile = 0.99;

// A union-find that threads may update at the same time (lock-free). A root
// is linked under the smaller of the two roots, so every tree's root is its
// smallest element: the final partition and its representatives do not
// depend on the order of the unions, hence not on thread scheduling.
class ConcurrentUnionFind {
 public:
  explicit ConcurrentUnionFind(Index n) : parent_(std::make_unique<std::atomic<Index>[]>(static_cast<std::size_t>(n))) {
    for (Index i = 0; i < n; ++i) parent_[static_cast<std::size_t>(i)].store(i, std::memory_order_relaxed);
  }

  Index find(Index x) const {
    while (true) {
      Index p = parent_[static_cast<std::size_t>(x)].load(std::memory_order_acquire);
      if (p == x) return x;
      const Index gp = parent_[static_cast<std::size_t>(p)].load(std::memory_order_acquire);
      // Path halving: gp is an ancestor of x, so pointing x at it is valid
      // whatever other threads do; a failed exchange only skips the shortcut.
      if (gp != p)
        parent_[static_cast<std::size_t>(x)].compare_exchange_weak(p, gp, std::memory_order_acq_rel,
                                                                   std::memory_order_relaxed);
      x = gp;
    }
  }

  void unite(Index a, Index b) {
    while (true) {
      a = find(a);
      b = find(b);
      if (a == b) return;
      if (a < b) std::swap(a, b);
      Index expected = a;  // a must still be a root when it is linked
      if (parent_[static_cast<std::size_t>(a)].compare_exchange_strong(expected, b, std::memory_order_acq_rel,
                                                                       std::memory_order_acquire))
        return;
    }
  }

 private:
  std::unique_ptr<std::atomic<Index>[]> parent_;
};

// Open-addressing map from occupied cell keys to cell numbers (built once,
// then only read, so lookups need no synchronisation).
class CellTable {
 public:
  explicit CellTable(std::span<const std::uint64_t> keys) {
    const std::size_t capacity = std::bit_ceil(std::max<std::size_t>(16, 2 * keys.size()));
    mask_ = capacity - 1;
    shift_ = 64 - std::countr_zero(capacity);
    keys_.assign(capacity, kEmpty);
    cells_.assign(capacity, kNoIndex);
    for (std::size_t c = 0; c < keys.size(); ++c) {
      std::size_t slot = hash(keys[c]);
      while (keys_[slot] != kEmpty) slot = (slot + 1) & mask_;
      keys_[slot] = keys[c];
      cells_[slot] = static_cast<Index>(c);
    }
  }

  Index find(std::uint64_t key) const {
    for (std::size_t slot = hash(key);; slot = (slot + 1) & mask_) {
      if (keys_[slot] == key) return cells_[slot];
      if (keys_[slot] == kEmpty) return kNoIndex;
    }
  }

 private:
  static constexpr std::uint64_t kEmpty = std::numeric_limits<std::uint64_t>::max();
  std::size_t hash(std::uint64_t key) const {
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
  }

  std::vector<std::uint64_t> keys_;
  std::vector<Index> cells_;
  std::size_t mask_ = 0;
  int shift_ = 0;
};

struct Entry {
  std::uint64_t key;
  bool is_large;
  double radius;
  Index glyph;
};

struct Ball {
  Vec3 centre;
  double radius;
};

// The box around the centres of a cell's small glyphs and their largest radius.
struct CellBounds : Box3 {
  double max_radius = 0.0;
};

inline double gap(double lo_a, double hi_a, double lo_b, double hi_b) {
  return std::max(std::max(lo_b - hi_a, lo_a - hi_b), 0.0);
}

inline double box_distance_squared(const CellBounds& a, const CellBounds& b) {
  const double x = gap(a.lo.x, a.hi.x, b.lo.x, b.hi.x), y = gap(a.lo.y, a.hi.y, b.lo.y, b.hi.y),
               z = gap(a.lo.z, a.hi.z, b.lo.z, b.hi.z);
  return x * x + y * y + z * z;
}

inline double box_distance_squared(const Vec3& p, const CellBounds& b) {
  const double x = gap(p.x, p.x, b.lo.x, b.hi.x), y = gap(p.y, p.y, b.lo.y, b.hi.y), z = gap(p.z, p.z, b.lo.z, b.hi.z);
  return x * x + y * y + z * z;
}

// True only when no glyph pair across the gap can satisfy glyphs_overlap():
// the box distance is a lower bound of every centre distance, and the factor
// leaves room for rounding (a few 1e-16) in both computations.
inline bool is_out_of_reach(double box_distance_squared, double radius_sum) {
  return box_distance_squared > radius_sum * radius_sum * (1.0 + 1e-12);
}

// What the phases of cluster_glyphs share: the glyphs, the grid they are
// sorted into, and per cell the runs of small and large glyphs.
struct GlyphGrid {
  std::span<const Vec3> positions;
  std::span<const double> radii;
  std::vector<Index> glyph_point;  // glyph g is point glyph_point[g], ascending point ids

  // The grid: cell coordinates are (p - lo) * inv_cell; glyphs of radius
  // up to small_bound set the cell size, larger ones search around them.
  Vec3 lo;
  double inv_cell = 0.0;
  double small_bound = 0.0;

  // Glyphs as balls sorted by cell, in each cell the small ones first, then
  // by decreasing radius; ball k is glyph ball_glyph[k].
  std::vector<Ball> balls;
  std::vector<Index> ball_glyph;
  // Cells in key order: balls [cell_begin[c], cell_small_end[c]) are small,
  // [cell_small_end[c], cell_begin[c+1]) large.
  std::vector<std::uint64_t> cell_keys;
  std::vector<Index> cell_begin, cell_small_end;
  std::vector<Index> large_balls;
  std::array<std::int64_t, 3> max_coord{0, 0, 0};
  std::vector<CellBounds> bounds;  // of each cell's small glyphs
  std::vector<char> is_connected;  // a cell whose small glyphs are already one cluster

  std::size_t num_glyphs() const { return glyph_point.size(); }
  std::size_t num_cells() const { return cell_keys.size(); }
  std::array<double, 3> coords_of(const Vec3& p) const {
    return {(p.x - lo.x) * inv_cell, (p.y - lo.y) * inv_cell, (p.z - lo.z) * inv_cell};
  }
};

// Joins two glyphs' clusters when the glyphs overlap.
bool test_and_unite(const GlyphGrid& grid, ConcurrentUnionFind& sets, const Ball& a, Index glyph_a, std::size_t b) {
  if (!glyphs_overlap(a.centre, a.radius, grid.balls[b].centre, grid.balls[b].radius)) return false;
  sets.unite(glyph_a, grid.ball_glyph[b]);
  return true;
}

// Cell size: twice the radius bound of the "small" glyphs, the 99th
// percentile but at least a quarter of the largest radius (so a large
// glyph's search box spans at most 10 cells per axis).
void choose_cells(GlyphGrid& grid) {
  const std::size_t n = grid.num_glyphs();
  std::vector<double> sorted_radii(n);
  double largest = 0.0;
  Box3 box;
  for (std::size_t g = 0; g < n; ++g) {
    const auto i = static_cast<std::size_t>(grid.glyph_point[g]);
    sorted_radii[g] = grid.radii[i];
    largest = std::max(largest, grid.radii[i]);
    box.add(grid.positions[i]);
  }
  const auto quantile = static_cast<std::ptrdiff_t>(kSmallRadiusQuantile * static_cast<double>(n - 1));
  std::nth_element(sorted_radii.begin(), sorted_radii.begin() + quantile, sorted_radii.end());
  grid.small_bound = std::max(sorted_radii[static_cast<std::size_t>(quantile)], 0.25 * largest);
  double cell = 2.0 * grid.small_bound * (1.0 + kCellMargin);
  // Very spread-out glyphs: coarser cells rather than more than 2^20 per axis.
  const double extent = std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z});
  cell = std::max(cell, extent / static_cast<double>(kMaxCellCoord - 1));
  grid.lo = box.lo;
  grid.inv_cell = 1.0 / cell;  // infinite extents give 0: one cell, still exact
}

// Sorts the glyphs into their cells and finds each cell's runs.
void sort_into_cells(GlyphGrid& grid) {
  const std::size_t n = grid.num_glyphs();
  std::vector<Entry> entries(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t g = r.begin(); g != r.end(); ++g) {
      const auto i = static_cast<std::size_t>(grid.glyph_point[g]);
      const auto u = grid.coords_of(grid.positions[i]);
      entries[g] = {cell_key(cell_coord(u[0]), cell_coord(u[1]), cell_coord(u[2])), grid.radii[i] > grid.small_bound,
                    grid.radii[i], static_cast<Index>(g)};
    }
  });
  // Within a cell, by decreasing radius: a search can stop at the first glyph
  // out of reach. (key, is_large, radius, glyph) is unique, so any correct
  // sort gives this order.
  tbb::parallel_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    if (a.key != b.key) return a.key < b.key;
    if (a.is_large != b.is_large) return b.is_large;
    if (a.radius != b.radius) return a.radius > b.radius;
    return a.glyph < b.glyph;
  });

  grid.balls.resize(n);
  grid.ball_glyph.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const auto i = static_cast<std::size_t>(grid.glyph_point[static_cast<std::size_t>(entries[k].glyph)]);
      grid.balls[k] = {grid.positions[i], grid.radii[i]};
      grid.ball_glyph[k] = entries[k].glyph;
    }
  });

  for (std::size_t k = 0; k < n; ++k) {
    if (k == 0 || entries[k].key != entries[k - 1].key) {
      grid.cell_keys.push_back(entries[k].key);
      grid.cell_begin.push_back(static_cast<Index>(k));
      grid.cell_small_end.push_back(static_cast<Index>(k));
      const auto c = cell_coords(entries[k].key);
      for (int a = 0; a < 3; ++a) grid.max_coord[a] = std::max(grid.max_coord[a], c[a]);
    }
    if (entries[k].is_large)
      grid.large_balls.push_back(static_cast<Index>(k));
    else
      grid.cell_small_end.back() = static_cast<Index>(k) + 1;
  }
  grid.cell_begin.push_back(static_cast<Index>(n));
}

// Bounds of each cell's small glyphs, to skip neighbours out of reach.
void bound_cells(GlyphGrid& grid) {
  grid.bounds.assign(grid.num_cells(), CellBounds{});
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, grid.num_cells(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t c = r.begin(); c != r.end(); ++c) {
                        CellBounds& b = grid.bounds[c];
                        for (Index k = grid.cell_begin[c]; k < grid.cell_small_end[c]; ++k) {
                          const Ball& ball = grid.balls[static_cast<std::size_t>(k)];
                          b.add(ball.centre);
                          b.max_radius = std::max(b.max_radius, ball.radius);
                        }
                      }
                    });
}

// Small with small, within each cell.
void join_within_cells(const GlyphGrid& grid, ConcurrentUnionFind& sets) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, grid.num_cells(), 64),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t c = r.begin(); c != r.end(); ++c) {
                        const auto end = static_cast<std::size_t>(grid.cell_small_end[c]);
                        for (auto a = static_cast<std::size_t>(grid.cell_begin[c]); a < end; ++a)
                          for (std::size_t b = a + 1; b < end; ++b)
                            test_and_unite(grid, sets, grid.balls[a], grid.ball_glyph[a], b);
                      }
                    });
}

// Cells whose small glyphs already form one cluster: a neighbour's glyph
// then joins all of them through its first overlap, so the rest of its
// tests can be skipped (the partition is the same; dense regions of
// overlapping glyphs cost about one test per glyph and neighbour cell).
void mark_connected_cells(GlyphGrid& grid, const ConcurrentUnionFind& sets) {
  grid.is_connected.assign(grid.num_cells(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, grid.num_cells(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t c = r.begin(); c != r.end(); ++c) {
                        const Index first = grid.cell_begin[c], end = grid.cell_small_end[c];
                        bool connected = first < end;
                        for (Index k = first + 1; connected && k < end; ++k)
                          connected = sets.find(grid.ball_glyph[static_cast<std::size_t>(k)]) ==
                                      sets.find(grid.ball_glyph[static_cast<std::size_t>(first)]);
                        grid.is_connected[c] = connected;
                      }
                    });
}

// Small glyphs of cell c with those of its neighbour o: both radii are at
// most small_bound, so an overlapping pair is less than one cell apart on
// each axis.
void join_cell_pair(const GlyphGrid& grid, ConcurrentUnionFind& sets, std::size_t c, std::size_t o) {
  const auto begin = static_cast<std::size_t>(grid.cell_begin[c]),
             end = static_cast<std::size_t>(grid.cell_small_end[c]);
  const auto other_begin = static_cast<std::size_t>(grid.cell_begin[o]),
             other_end = static_cast<std::size_t>(grid.cell_small_end[o]);
  const CellBounds &bc = grid.bounds[c], &bo = grid.bounds[o];
  if (other_begin == other_end || is_out_of_reach(box_distance_squared(bc, bo), bc.max_radius + bo.max_radius)) return;
  if (grid.is_connected[c] && grid.is_connected[o] &&
      sets.find(grid.ball_glyph[begin]) == sets.find(grid.ball_glyph[other_begin]))
    return;  // already one cluster
  // With the neighbour connected, each of our glyphs needs one overlap with
  // it at most; with both connected, the pair of cells needs one.
  const bool once_per_glyph = grid.is_connected[o] != 0;
  const bool once_per_cell = grid.is_connected[c] && grid.is_connected[o];
  for (std::size_t a = begin; a < end; ++a) {
    const Ball& ball = grid.balls[a];
    const double gap_squared = box_distance_squared(ball.centre, bo);
    for (std::size_t b = other_begin; b < other_end; ++b) {
      if (is_out_of_reach(gap_squared, ball.radius + grid.balls[b].radius)) break;  // and so are the smaller ones
      if (test_and_unite(grid, sets, ball, grid.ball_glyph[a], b) && once_per_glyph) {
        if (once_per_cell) return;
        break;
      }
    }
  }
}

// Small with small across neighbouring cells. The forward neighbours of cell
// (x, y, z) are (x+1, y, z) and x−1..x+1 in the rows (y+1, z), (y−1, z+1),
// (y, z+1) and (y+1, z+1). Cells are sorted by key, so a row's cells are a
// contiguous run, and where that run starts only moves forward as c does:
// one pointer per row finds the neighbours with sequential reads (a hash
// lookup per neighbour costs cache misses).
void join_neighbour_cells(const GlyphGrid& grid, ConcurrentUnionFind& sets) {
  constexpr std::array<std::array<std::int64_t, 2>, 4> kForwardRows = {{{1, 0}, {-1, 1}, {0, 1}, {1, 1}}};
  const std::vector<std::uint64_t>& keys = grid.cell_keys;
  const std::size_t num_cells = grid.num_cells();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, num_cells, 256), [&](const tbb::blocked_range<std::size_t>& r) {
    std::array<std::size_t, 4> row_start;
    row_start.fill(num_cells + 1);  // not positioned yet
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      if (grid.cell_begin[c] == grid.cell_small_end[c]) continue;
      const auto [x, y, z] = cell_coords(keys[c]);
      if (c + 1 < num_cells && keys[c + 1] == keys[c] + 1) join_cell_pair(grid, sets, c, c + 1);
      for (std::size_t k = 0; k < kForwardRows.size(); ++k) {
        const std::int64_t row_y = y + kForwardRows[k][0], row_z = z + kForwardRows[k][1];
        if (row_y < 0 || row_y > grid.max_coord[1] || row_z > grid.max_coord[2]) continue;
        const std::uint64_t lo = cell_key(std::max<std::int64_t>(x - 1, 0), row_y, row_z);
        const std::uint64_t hi = cell_key(x + 1, row_y, row_z);
        std::size_t& o = row_start[k];
        if (o > num_cells) o = static_cast<std::size_t>(std::lower_bound(keys.begin(), keys.end(), lo) - keys.begin());
        // A few steps forward usually; a binary search after a long gap.
        for (int step = 0; step < 8 && o < num_cells && keys[o] < lo; ++step) ++o;
        if (o < num_cells && keys[o] < lo)
          o = static_cast<std::size_t>(std::lower_bound(keys.begin() + static_cast<std::ptrdiff_t>(o), keys.end(), lo) -
                                       keys.begin());
        for (std::size_t n = o; n < num_cells && keys[n] <= hi; ++n) join_cell_pair(grid, sets, c, n);
      }
    }
  });
}

// Large glyphs: each tests every small glyph and every large glyph no larger
// than itself (equal radii: the higher glyph id) within 2·r, which covers
// every overlapping partner; so each such pair is tested (or known to be
// joined) exactly once.
void join_large_glyphs(const GlyphGrid& grid, ConcurrentUnionFind& sets) {
  const CellTable table(grid.cell_keys);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, grid.large_balls.size(), 16), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t l = r.begin(); l != r.end(); ++l) {
          const auto k = static_cast<std::size_t>(grid.large_balls[l]);
          const Ball& ball = grid.balls[k];
          const Index glyph = grid.ball_glyph[k];
          const auto u = grid.coords_of(ball.centre);
          const double reach = 2.0 * ball.radius * (1.0 + kCellMargin) * grid.inv_cell;
          std::array<std::int64_t, 3> from{}, to{};
          for (int a = 0; a < 3; ++a) {
            from[a] = cell_coord(u[a] - reach);
            to[a] = std::min(cell_coord(u[a] + reach), grid.max_coord[a]);
          }
          for (std::int64_t z = from[2]; z <= to[2]; ++z)
            for (std::int64_t y = from[1]; y <= to[1]; ++y)
              for (std::int64_t x = from[0]; x <= to[0]; ++x) {
                const Index c = table.find(cell_key(x, y, z));
                if (c == kNoIndex) continue;
                const auto cs = static_cast<std::size_t>(c);
                const auto begin = static_cast<std::size_t>(grid.cell_begin[cs]),
                           small_end = static_cast<std::size_t>(grid.cell_small_end[cs]);
                const double gap_squared = begin < small_end ? box_distance_squared(ball.centre, grid.bounds[cs]) : 0.0;
                if (begin < small_end && !is_out_of_reach(gap_squared, ball.radius + grid.bounds[cs].max_radius) &&
                    !(grid.is_connected[cs] && sets.find(glyph) == sets.find(grid.ball_glyph[begin]))) {
                  for (std::size_t b = begin; b < small_end; ++b) {
                    if (is_out_of_reach(gap_squared, ball.radius + grid.balls[b].radius)) break;  // radii decrease
                    if (test_and_unite(grid, sets, ball, glyph, b) && grid.is_connected[cs]) break;
                  }
                }
                for (std::size_t b = small_end; b < static_cast<std::size_t>(grid.cell_begin[cs + 1]); ++b) {
                  const Ball& other = grid.balls[b];  // large: only the smaller one of the pair, or the higher id
                  if (other.radius > ball.radius || (other.radius == ball.radius && grid.ball_glyph[b] <= glyph))
                    continue;
                  test_and_unite(grid, sets, ball, glyph, b);
                }
              }
        }
      });
}

// Numbers the clusters by their roots, which are their smallest glyphs (so
// smallest point ids), then lists members in ascending point id.
void number_clusters(const GlyphGrid& grid, const ConcurrentUnionFind& sets, GlyphClusters& result) {
  const std::size_t n = grid.num_glyphs();
  std::vector<Index> root(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t g = r.begin(); g != r.end(); ++g) root[g] = sets.find(static_cast<Index>(g));
  });
  std::vector<Index> cluster_of_root(n, kNoIndex);
  std::vector<Index> counts;
  for (std::size_t g = 0; g < n; ++g) {
    if (root[g] == static_cast<Index>(g)) {
      cluster_of_root[g] = static_cast<Index>(counts.size());
      counts.push_back(0);
    }
    const Index cluster = cluster_of_root[static_cast<std::size_t>(root[g])];
    ++counts[static_cast<std::size_t>(cluster)];
    result.point_cluster[static_cast<std::size_t>(grid.glyph_point[g])] = cluster;
  }
  result.offsets.resize(counts.size() + 1);
  for (std::size_t c = 0; c < counts.size(); ++c) result.offsets[c + 1] = result.offsets[c] + counts[c];
  result.members.resize(n);
  std::vector<Index> next(result.offsets.begin(), result.offsets.end() - 1);
  for (std::size_t g = 0; g < n; ++g) {
    const Index cluster = result.point_cluster[static_cast<std::size_t>(grid.glyph_point[g])];
    result.members[static_cast<std::size_t>(next[static_cast<std::size_t>(cluster)]++)] = grid.glyph_point[g];
  }
}

}  // namespace

GlyphClusters cluster_glyphs(std::span<const Vec3> positions, std::span<const double> radii) {
  if (positions.size() != radii.size())
    throw Error("cluster_glyphs: " + std::to_string(positions.size()) + " positions but " +
                std::to_string(radii.size()) + " radii");
  GlyphClusters result;
  result.point_cluster.assign(positions.size(), kNoIndex);
  result.offsets.assign(1, 0);

  GlyphGrid grid{positions, radii, {}};
  for (std::size_t i = 0; i < radii.size(); ++i)
    if (std::isfinite(radii[i]) && radii[i] > 0.0) grid.glyph_point.push_back(static_cast<Index>(i));
  if (grid.glyph_point.empty()) return result;

  choose_cells(grid);
  sort_into_cells(grid);
  bound_cells(grid);
  ConcurrentUnionFind sets(static_cast<Index>(grid.num_glyphs()));
  join_within_cells(grid, sets);
  mark_connected_cells(grid, sets);
  join_neighbour_cells(grid, sets);
  join_large_glyphs(grid, sets);
  number_clusters(grid, sets, result);
  return result;
}

}  // namespace hq
