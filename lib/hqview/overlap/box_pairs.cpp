#include "hqview/overlap/box_pairs.h"

#include <CGAL/box_intersection_d.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace hq::detail {
namespace {

// A box whose id is its index, so results do not depend on addresses or on
// CGAL's global id counter.
struct IndexedBox {
  using NT = double;
  using ID = std::size_t;
  std::array<double, 3> lo, hi;
  std::size_t index;
  static int dimension() { return 3; }
  double min_coord(int d) const { return lo[static_cast<std::size_t>(d)]; }
  double max_coord(int d) const { return hi[static_cast<std::size_t>(d)]; }
  std::size_t id() const { return index; }
};

IndexedBox indexed(const Box3& b, std::size_t i) {
  return {std::array<double, 3>{b.lo.x, b.lo.y, b.lo.z}, std::array<double, 3>{b.hi.x, b.hi.y, b.hi.z}, i};
}

CGAL::Box_intersection_d::Topology topology_of(BoxContact contact) {
  return contact == BoxContact::closed ? CGAL::Box_intersection_d::CLOSED : CGAL::Box_intersection_d::HALF_OPEN;
}

// CGAL's half-open boxes [lo, hi) intersect exactly when the open boxes do;
// an empty box (lo == hi on an axis) meets nothing.
bool is_empty(const Box3& b) { return !(b.lo[0] < b.hi[0] && b.lo[1] < b.hi[1] && b.lo[2] < b.hi[2]); }

// Collects reported pairs up to a budget; past it, only counts them, and
// stops the search (by exception: CGAL's callbacks cannot) at
// kBudgetCountFactor x the budget.
class BudgetedPairs {
 public:
  explicit BudgetedPairs(std::int64_t max_pairs) : max_pairs_(max_pairs) {}
  struct Stop {};
  void add(std::size_t a, std::size_t b) {
    ++result_.num_found;
    if (result_.num_found <= max_pairs_) result_.pairs.push_back({static_cast<Index>(a), static_cast<Index>(b)});
    if (result_.num_found >= kBudgetCountFactor * max_pairs_) throw Stop{};
  }
  template <class Search>
  BoxPairs run(Search&& search) {
    try {
      search();
    } catch (const Stop&) {
      result_.is_count_exact = false;
    }
    if (result_.num_found > max_pairs_) {
      result_.is_complete = false;
      result_.pairs = {};
    }
    return std::move(result_);
  }

 private:
  std::int64_t max_pairs_;
  BoxPairs result_;
};

// Below this many boxes CGAL's search scans instead of splitting further.
// CGAL's default, 10, splits down to tiny sets: on the 103,424 boundary fan
// triangles of the 1->8 refined Dolphin (766,305 pairs) the search took
// 0.22 s at 10, 0.15 s at 100, 0.10 s at 1,000 (and 0.98 / 0.43 s at 10 /
// 1,000 on the 2.9M-hex copy). A scan compares at most every pair of its
// set, so the worst case (boxes that all overlap on the first axis and on
// no other) costs n x 1,000 box comparisons instead of O(n log^3 n).
constexpr std::ptrdiff_t kScanCutoff = 1000;

// Pairs as {low, high}, sorted (in parallel: the pairs are distinct after
// the swap, so any thread count gives the same order), without repeats.
void normalize(std::vector<std::array<Index, 2>>& pairs) {
  for (auto& p : pairs)
    if (p[0] > p[1]) std::swap(p[0], p[1]);
  tbb::parallel_sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
}

}  // namespace

BoxPairs box_self_pairs(const std::vector<Box3>& boxes, BoxContact contact, std::int64_t max_pairs) {
  std::vector<IndexedBox> items;
  items.reserve(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i)
    if (contact == BoxContact::closed || !is_empty(boxes[i])) items.push_back(indexed(boxes[i], i));
  BudgetedPairs collected(max_pairs);
  auto report = [&](const IndexedBox& a, const IndexedBox& b) { collected.add(a.index, b.index); };
  // Sequential_tag: faster than Parallel_tag on 2 cores (ALGORITHMS.md §4).
  BoxPairs result = collected.run([&] {
    CGAL::box_self_intersection_d<CGAL::Sequential_tag>(items.begin(), items.end(), report,
                                                        CGAL::Box_intersection_d::Box_traits_d<IndexedBox>(), kScanCutoff,
                                                        topology_of(contact));
  });
  normalize(result.pairs);
  return result;
}

namespace {

// The box around group g's boxes; nullopt for a group without boxes.
std::optional<Box3> bounds_of_group(const std::vector<Box3>& boxes, const std::vector<Index>& first, std::size_t g) {
  if (first[g] == first[g + 1]) return std::nullopt;
  Box3 bounds;
  for (Index i = first[g]; i < first[g + 1]; ++i) {
    bounds.add(boxes[static_cast<std::size_t>(i)].lo);
    bounds.add(boxes[static_cast<std::size_t>(i)].hi);
  }
  return bounds;
}

// Each group's bounds but those nullopt, its id the group; the array made
// at its final size (not grown by doubling into fresh pages: 61 MB for a
// 1M-quad surface).
std::vector<IndexedBox> group_bounds(std::size_t num_groups,
                                     const std::function<std::optional<Box3>(std::size_t)>& bounds_of) {
  std::vector<IndexedBox> groups;
  groups.reserve(num_groups);
  for (std::size_t g = 0; g < num_groups; ++g)
    if (const std::optional<Box3> bounds = bounds_of(g)) groups.push_back(indexed(*bounds, g));
  return groups;
}

std::vector<IndexedBox> group_bounds(const std::vector<Box3>& boxes, const std::vector<Index>& first) {
  return group_bounds(first.size() - 1, [&](std::size_t g) { return bounds_of_group(boxes, first, g); });
}

// CGAL's search on the groups' bounds, closed: report(a, b) per pair.
template <class Report>
void group_self_intersection(std::vector<IndexedBox>& groups, Report&& report) {
  CGAL::box_self_intersection_d<CGAL::Sequential_tag>(groups.begin(), groups.end(), report,
                                                      CGAL::Box_intersection_d::Box_traits_d<IndexedBox>(), kScanCutoff,
                                                      CGAL::Box_intersection_d::CLOSED);
}

}  // namespace

BoxPairs grouped_box_self_pairs(const std::vector<Box3>& boxes, const std::vector<Index>& first, std::int64_t max_pairs) {
  const auto at = [&](Index i) -> const Box3& { return boxes[static_cast<std::size_t>(i)]; };
  std::vector<IndexedBox> groups = group_bounds(boxes, first);
  BudgetedPairs collected(max_pairs);
  const auto test = [&](Index i, Index j) {
    if (boxes_overlap_closed(at(i), at(j))) collected.add(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
  };
  BoxPairs result = collected.run([&] {
    for (const IndexedBox& g : groups)
      for (Index i = first[g.index]; i < first[g.index + 1]; ++i)
        for (Index j = i + 1; j < first[g.index + 1]; ++j) test(i, j);
    group_self_intersection(groups, [&](const IndexedBox& a, const IndexedBox& b) {
      for (Index i = first[a.index]; i < first[a.index + 1]; ++i)
        for (Index j = first[b.index]; j < first[b.index + 1]; ++j) test(i, j);
    });
  });
  normalize(result.pairs);
  return result;
}

namespace {

// group_bound_pairs splits its boxes into this many slabs along the first
// axis (a fixed number: the same pairs in the same order for any thread
// count) once there are kMinSlabGroups of them; fewer are searched whole.
constexpr std::size_t kNumSlabs = 16;
constexpr std::size_t kMinSlabGroups = std::size_t{1} << 14;

// The slabs' bounds on the first axis: quantiles of a sample of the boxes'
// lower ends (slab s is [split[s-1], split[s]), the first and last open
// outwards); empty when some lower or upper end is not finite (then one
// slab, the search as it was).
std::vector<double> slab_splits(const std::vector<IndexedBox>& groups) {
  for (const IndexedBox& g : groups)
    if (!std::isfinite(g.lo[0]) || !std::isfinite(g.hi[0])) return {};
  std::vector<double> sample;
  const std::size_t step = std::max<std::size_t>(1, groups.size() / 4096);
  for (std::size_t i = 0; i < groups.size(); i += step) sample.push_back(groups[i].lo[0]);
  std::sort(sample.begin(), sample.end());
  std::vector<double> split;
  for (std::size_t s = 1; s < kNumSlabs; ++s) split.push_back(sample[s * sample.size() / kNumSlabs]);
  return split;
}

}  // namespace

std::optional<std::vector<std::array<Index, 2>>> group_bound_pairs(const std::vector<Box3>& boxes,
                                                                   const std::vector<Index>& first,
                                                                   std::int64_t max_pairs) {
  return group_bound_pairs(
      first.size() - 1, [&](std::size_t g) { return bounds_of_group(boxes, first, g); }, max_pairs);
}

std::optional<std::vector<std::array<Index, 2>>> group_bound_pairs(
    std::size_t num_groups, const std::function<std::optional<Box3>(std::size_t)>& bounds_of, std::int64_t max_pairs) {
  std::vector<IndexedBox> groups = group_bounds(num_groups, bounds_of);
  const std::vector<double> split = groups.size() >= kMinSlabGroups ? slab_splits(groups) : std::vector<double>{};
  const auto slab_of = [&](double x) {
    return static_cast<std::size_t>(std::upper_bound(split.begin(), split.end(), x) - split.begin());
  };
  // Each box goes to every slab its extent on the first axis meets; a pair
  // is kept by the one slab holding the larger of the two lower ends (both
  // boxes reach it when they meet), so each pair is found exactly once, in
  // parallel over the slabs, each searched as one set was before.
  const std::size_t num_slabs = split.size() + 1;
  std::vector<std::vector<IndexedBox>> members(num_slabs);
  if (num_slabs == 1) {
    members[0] = std::move(groups);
  } else {
    // Counted first: each slab's array made once (not grown by doubling
    // into fresh pages), and the groups' array freed before the search.
    std::vector<std::size_t> sizes(num_slabs, 0);
    for (const IndexedBox& g : groups)
      for (std::size_t s = slab_of(g.lo[0]), last = slab_of(g.hi[0]); s <= last; ++s) ++sizes[s];
    for (std::size_t s = 0; s < num_slabs; ++s) members[s].reserve(sizes[s]);
    for (const IndexedBox& g : groups)
      for (std::size_t s = slab_of(g.lo[0]), last = slab_of(g.hi[0]); s <= last; ++s) members[s].push_back(g);
    groups = {};
  }
  std::vector<std::vector<std::array<Index, 2>>> found(num_slabs);
  std::vector<char> stopped(num_slabs, 0);
  struct Stop {};
  tbb::parallel_for(std::size_t{0}, num_slabs, [&](std::size_t s) {
    std::vector<std::array<Index, 2>>& pairs = found[s];
    try {
      group_self_intersection(members[s], [&](const IndexedBox& a, const IndexedBox& b) {
        if (num_slabs > 1 && slab_of(std::max(a.lo[0], b.lo[0])) != s) return;
        if (static_cast<std::int64_t>(pairs.size()) >= max_pairs) throw Stop{};
        pairs.push_back({static_cast<Index>(std::min(a.index, b.index)), static_cast<Index>(std::max(a.index, b.index))});
      });
    } catch (const Stop&) {
      stopped[s] = 1;
    }
    members[s] = {};
  });
  std::size_t total = 0;
  for (std::size_t s = 0; s < num_slabs; ++s) {
    if (stopped[s] != 0) return std::nullopt;
    total += found[s].size();
  }
  if (static_cast<std::int64_t>(total) > max_pairs) return std::nullopt;
  std::vector<std::array<Index, 2>> pairs;
  pairs.reserve(total);
  for (const auto& part : found) pairs.insert(pairs.end(), part.begin(), part.end());
  return pairs;
}

namespace {

// Cells of a coarse grid over the subset's boxes that some subset box
// touches (closed): a box that touches no marked cell meets no subset box, so
// the search's other side keeps only the boxes that may (the same pairs; a
// small subset of a large mesh no longer copies every box).
class SubsetGrid {
 public:
  explicit SubsetGrid(const std::vector<IndexedBox>& some) {
    for (const IndexedBox& b : some) {
      bounds_.add({b.lo[0], b.lo[1], b.lo[2]});
      bounds_.add({b.hi[0], b.hi[1], b.hi[2]});
    }
    // About 8 cells per subset box, at most 64 per axis.
    const double cells = std::min(262144.0, 8.0 * static_cast<double>(some.size()));
    const Vec3 size = bounds_.hi - bounds_.lo;
    const double side = std::cbrt(std::max(size.x, 1e-300) * std::max(size.y, 1e-300) * std::max(size.z, 1e-300) / cells);
    for (std::size_t k = 0; k < 3; ++k) {
      const double extent = size[static_cast<int>(k)];
      n_[k] = side > 0 && std::isfinite(side) ? static_cast<int>(std::clamp(std::ceil(extent / side), 1.0, 64.0)) : 1;
      scale_[k] = extent > 0 && std::isfinite(extent) ? n_[k] / extent : 0.0;
    }
    marked_.assign(static_cast<std::size_t>(n_[0] * n_[1] * n_[2]), 0);
    // Every cell of every subset box marked; when that is more than 64
    // sweeps of the grid (many boxes over most of it), no filter at all.
    std::size_t work = 0;
    for (const IndexedBox& b : some) work += num_cells(b.lo, b.hi);
    if (work > 64 * marked_.size()) {
      std::fill(marked_.begin(), marked_.end(), 1);
      keep_all_ = true;
      return;
    }
    for (const IndexedBox& b : some)
      visit(b.lo, b.hi, std::numeric_limits<std::size_t>::max(), [&](std::size_t c) {
        marked_[c] = 1;
        return false;
      });
  }
  // False only when the closed box touches no marked cell (then it meets no
  // subset box, closed or open). A box over more than kMaxCells cells is
  // kept unvisited.
  bool may_meet(const IndexedBox& b) const {
    if (keep_all_) return true;
    for (std::size_t k = 0; k < 3; ++k)
      if (b.hi[k] < bounds_.lo[static_cast<int>(k)] || b.lo[k] > bounds_.hi[static_cast<int>(k)]) return false;
    return visit(b.lo, b.hi, kMaxCells, [&](std::size_t c) { return marked_[c] != 0; });
  }

 private:
  static constexpr std::size_t kMaxCells = 512;
  std::size_t num_cells(const std::array<double, 3>& lo, const std::array<double, 3>& hi) const {
    std::size_t count = 1;
    for (std::size_t k = 0; k < 3; ++k) count *= static_cast<std::size_t>(index(hi[k], k) - index(lo[k], k) + 1);
    return count;
  }
  // Calls f on the grid cells of the closed box [lo, hi] (clamped to the
  // grid) until it returns true; true then, or when the box spans more than
  // max_cells cells (not visited).
  template <class F>
  bool visit(const std::array<double, 3>& lo, const std::array<double, 3>& hi, std::size_t max_cells, F&& f) const {
    if (num_cells(lo, hi) > max_cells) return true;
    std::array<int, 3> a{}, b{};
    for (std::size_t k = 0; k < 3; ++k) {
      a[k] = index(lo[k], k);
      b[k] = index(hi[k], k);
    }
    for (int z = a[2]; z <= b[2]; ++z)
      for (int y = a[1]; y <= b[1]; ++y)
        for (int x = a[0]; x <= b[0]; ++x)
          if (f(static_cast<std::size_t>((z * n_[1] + y) * n_[0] + x))) return true;
    return false;
  }
  // Monotone in v (NaN to 0): boxes that meet on an axis get index ranges
  // that meet.
  int index(double v, std::size_t k) const {
    const double t = (v - bounds_.lo[static_cast<int>(k)]) * scale_[k];
    if (!(t > 0)) return 0;
    return t >= n_[k] ? n_[k] - 1 : static_cast<int>(t);
  }

  Box3 bounds_;
  std::array<int, 3> n_{1, 1, 1};
  std::array<double, 3> scale_{};
  std::vector<char> marked_;
  bool keep_all_ = false;
};

}  // namespace

BoxPairs box_subset_pairs(const std::vector<Box3>& boxes, const std::vector<Index>& subset, BoxContact contact,
                          std::int64_t max_pairs) {
  return box_subset_pairs(boxes.size(), [&](std::size_t i) { return boxes[i]; }, subset, contact, max_pairs);
}

BoxPairs box_subset_pairs(std::size_t num_boxes, const std::function<Box3(std::size_t)>& box_at,
                          const std::vector<Index>& subset, BoxContact contact, std::int64_t max_pairs) {
  std::vector<IndexedBox> all, some;
  for (Index i : subset) {
    const Box3 b = box_at(static_cast<std::size_t>(i));
    if (contact == BoxContact::closed || !is_empty(b)) some.push_back(indexed(b, static_cast<std::size_t>(i)));
  }
  if (!some.empty()) {
    const SubsetGrid grid(some);
    // The other side's boxes made and filtered in a fixed number of slices
    // at once, joined in index order (the same list for any thread count).
    constexpr std::size_t kSlices = 64;
    const std::size_t slice = (num_boxes + kSlices - 1) / kSlices;
    std::array<std::vector<IndexedBox>, kSlices> kept;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, kSlices, 1), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t k = r.begin(); k != r.end(); ++k)
        for (std::size_t i = k * slice; i < std::min(num_boxes, (k + 1) * slice); ++i) {
          const Box3 box = box_at(i);
          if (contact == BoxContact::open && is_empty(box)) continue;
          const IndexedBox b = indexed(box, i);
          if (contact == BoxContact::closed || grid.may_meet(b)) kept[k].push_back(b);
        }
    });
    std::size_t total = 0;
    for (const auto& part : kept) total += part.size();
    all.reserve(total);
    for (const auto& part : kept) all.insert(all.end(), part.begin(), part.end());
  }
  BudgetedPairs collected(max_pairs);
  auto report = [&](const IndexedBox& a, const IndexedBox& b) { collected.add(a.index, b.index); };
  // Boxes with equal ids (a subset box and its own copy in `all`) are never
  // reported; pairs inside the subset come twice (and count twice against
  // the budget) and are merged below.
  BoxPairs result = collected.run([&] {
    CGAL::box_intersection_d<CGAL::Sequential_tag>(some.begin(), some.end(), all.begin(), all.end(), report,
                                                   CGAL::Box_intersection_d::Box_traits_d<IndexedBox>(), kScanCutoff,
                                                   topology_of(contact), CGAL::Box_intersection_d::BIPARTITE);
  });
  normalize(result.pairs);
  return result;
}

}  // namespace hq::detail
