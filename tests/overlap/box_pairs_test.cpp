// The grouped box search (stage E's broad phase) against every pair tested
// directly, and against the flat search it replaces.
#include "hqview/overlap/box_pairs.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <random>
#include <vector>

namespace hq::detail {
namespace HQ_TEST_UNIT {

// Clusters of 0-4 boxes, as a boundary quad's fan triangles: near
// neighbours inside a cluster, clusters on a coarse lattice so that
// neighbouring clusters touch; coordinates on a grid of 1/8 so that many
// boxes touch exactly (closed contact), some flat on an axis.
struct GroupedBoxes {
  std::vector<Box3> boxes;
  std::vector<Index> first{0};
};

GroupedBoxes make_boxes(unsigned seed, int num_groups) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> count(0, 4), cell(0, 9), offset(0, 8), size(0, 6);
  GroupedBoxes g;
  for (int k = 0; k < num_groups; ++k) {
    const double cx = cell(rng), cy = cell(rng), cz = cell(rng);
    for (int n = count(rng); n > 0; --n) {
      Box3 b;
      b.lo = {cx + offset(rng) / 8.0, cy + offset(rng) / 8.0, cz + offset(rng) / 8.0};
      b.hi = {b.lo.x + size(rng) / 8.0, b.lo.y + size(rng) / 8.0, b.lo.z + size(rng) / 8.0};
      g.boxes.push_back(b);
    }
    g.first.push_back(static_cast<Index>(g.boxes.size()));
  }
  return g;
}

std::vector<std::array<Index, 2>> every_pair_tested(const std::vector<Box3>& boxes) {
  std::vector<std::array<Index, 2>> pairs;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size(); ++j)
      if (boxes[i].overlaps(boxes[j])) pairs.push_back({static_cast<Index>(i), static_cast<Index>(j)});
  return pairs;
}

TEST(BoxPairs, GroupedSearchFindsEveryPairOfTouchingBoxes) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    // 1,500 groups: past CGAL's scan cutoff (1,000), so it splits too.
    const GroupedBoxes g = make_boxes(seed, 1500);
    const std::vector<std::array<Index, 2>> expected = every_pair_tested(g.boxes);
    ASSERT_GT(expected.size(), 1000u);
    const BoxPairs grouped = grouped_box_self_pairs(g.boxes, g.first, 1 << 30);
    EXPECT_TRUE(grouped.is_complete);
    EXPECT_EQ(grouped.num_found, static_cast<std::int64_t>(expected.size()));
    EXPECT_EQ(grouped.pairs, expected) << "seed " << seed;
    EXPECT_EQ(box_self_pairs(g.boxes, BoxContact::closed, 1 << 30).pairs, expected) << "seed " << seed;
  }
}

TEST(BoxPairs, GroupedSearchCountsBoxPairsAgainstTheBudget) {
  const GroupedBoxes g = make_boxes(7, 400);
  const auto n = static_cast<std::int64_t>(every_pair_tested(g.boxes).size());
  // Exactly at the budget: complete.
  const BoxPairs at = grouped_box_self_pairs(g.boxes, g.first, n);
  EXPECT_TRUE(at.is_complete);
  EXPECT_EQ(static_cast<std::int64_t>(at.pairs.size()), n);
  // One below: nothing handed out, every pair still counted (the search
  // stops only at kBudgetCountFactor x the budget).
  const BoxPairs over = grouped_box_self_pairs(g.boxes, g.first, n - 1);
  EXPECT_FALSE(over.is_complete);
  EXPECT_TRUE(over.pairs.empty());
  EXPECT_EQ(over.num_found, n);
  EXPECT_TRUE(over.is_count_exact);
  // Far below: stopped, with a lower bound of at least the stopping count.
  const std::int64_t small = n / 20;
  const BoxPairs stopped = grouped_box_self_pairs(g.boxes, g.first, small);
  EXPECT_FALSE(stopped.is_complete);
  EXPECT_FALSE(stopped.is_count_exact);
  EXPECT_GE(stopped.num_found, kBudgetCountFactor * small);
  EXPECT_LE(stopped.num_found, n);
}

TEST(BoxPairs, GroupedSearchSkipsEmptyGroups) {
  GroupedBoxes g;
  g.first = {0, 0, 0};  // two empty groups
  EXPECT_TRUE(grouped_box_self_pairs(g.boxes, g.first, 10).pairs.empty());
  Box3 a, b;
  a.lo = {0, 0, 0}, a.hi = {1, 1, 1};
  b.lo = {1, 1, 1}, b.hi = {2, 2, 2};  // touching at a corner
  g.boxes = {a, b};
  g.first = {0, 0, 1, 1, 2};
  EXPECT_EQ(grouped_box_self_pairs(g.boxes, g.first, 10).pairs, (std::vector<std::array<Index, 2>>{{0, 1}}));
}

// The group pairs whose bounds meet, by a sweep over the groups sorted by
// their lower end on the first axis: the reference for group_bound_pairs.
std::vector<std::array<Index, 2>> group_pairs_swept(const GroupedBoxes& g) {
  std::vector<std::pair<Box3, Index>> bounds;
  for (std::size_t k = 0; k + 1 < g.first.size(); ++k) {
    Box3 b;
    for (Index i = g.first[k]; i < g.first[k + 1]; ++i) {
      b.add(g.boxes[static_cast<std::size_t>(i)].lo);
      b.add(g.boxes[static_cast<std::size_t>(i)].hi);
    }
    if (g.first[k] < g.first[k + 1]) bounds.push_back({b, static_cast<Index>(k)});
  }
  std::sort(bounds.begin(), bounds.end(), [](const auto& a, const auto& b) { return a.first.lo.x < b.first.lo.x; });
  std::vector<std::array<Index, 2>> pairs;
  for (std::size_t i = 0; i < bounds.size(); ++i)
    for (std::size_t j = i + 1; j < bounds.size() && bounds[j].first.lo.x <= bounds[i].first.hi.x; ++j)
      if (bounds[i].first.overlaps(bounds[j].first))
        pairs.push_back({std::min(bounds[i].second, bounds[j].second), std::max(bounds[i].second, bounds[j].second)});
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// Past 16,384 groups the search runs over 16 slabs of the first axis in
// parallel: every pair found once (boxes spanning several slabs, boxes
// touching exactly on a slab's bound among them), the same list in the same
// order on one thread, and the budget as before.
TEST(BoxPairs, SlabbedGroupSearchFindsEveryGroupPairOnce) {
  std::mt19937 rng(46);
  std::uniform_int_distribution<int> count(0, 4), cell(0, 3), along(0, 3999), offset(0, 8), size(0, 6), wide(0, 99);
  GroupedBoxes g;
  for (int k = 0; k < 20000; ++k) {
    const double cx = along(rng), cy = cell(rng), cz = cell(rng);
    for (int n = count(rng); n > 0; --n) {
      Box3 b;
      b.lo = {cx + offset(rng) / 8.0, cy + offset(rng) / 8.0, cz + offset(rng) / 8.0};
      // One box in a hundred spans hundreds of cells along the first axis.
      const double length = wide(rng) == 0 ? 400.0 : size(rng) / 8.0;
      b.hi = {b.lo.x + length, b.lo.y + size(rng) / 8.0, b.lo.z + size(rng) / 8.0};
      g.boxes.push_back(b);
    }
    g.first.push_back(static_cast<Index>(g.boxes.size()));
  }
  const std::vector<std::array<Index, 2>> expected = group_pairs_swept(g);
  ASSERT_GT(expected.size(), 20000u);
  const auto found = group_bound_pairs(g.boxes, g.first, 1 << 30);
  ASSERT_TRUE(found.has_value());
  std::vector<std::array<Index, 2>> sorted = *found;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, expected);  // each once: a repeat would lengthen the list
  {
    const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    EXPECT_EQ(group_bound_pairs(g.boxes, g.first, 1 << 30), found);
  }
  const auto n = static_cast<std::int64_t>(expected.size());
  EXPECT_TRUE(group_bound_pairs(g.boxes, g.first, n).has_value());
  EXPECT_FALSE(group_bound_pairs(g.boxes, g.first, n - 1).has_value());
}

}  // namespace
}  // namespace hq::detail

namespace hq::detail {
namespace HQ_TEST_UNIT {

// The subset search (stage G's broad phase, open contact) against every
// pair tested directly: subsets of 1 to every box, boxes on a coarse lattice
// (many touch exactly: not reported in open contact), flat ones (never
// reported), and a box over everything (more grid cells than the grid
// visits per box).
TEST(BoxPairs, SubsetSearchFindsEveryPairWithASubsetBoxAsTestedDirectly) {
  for (unsigned seed : {1u, 2u, 3u}) {
    GroupedBoxes g = make_boxes(seed, 400);
    Box3 everything;
    everything.lo = {-1, -1, -1};
    everything.hi = {20, 20, 20};
    g.boxes.push_back(everything);
    const auto n = static_cast<Index>(g.boxes.size());
    const auto open_overlap = [](const Box3& a, const Box3& b) {
      return a.lo.x < b.hi.x && b.lo.x < a.hi.x && a.lo.y < b.hi.y && b.lo.y < a.hi.y && a.lo.z < b.hi.z &&
             b.lo.z < a.hi.z && a.lo.x < a.hi.x && a.lo.y < a.hi.y && a.lo.z < a.hi.z && b.lo.x < b.hi.x &&
             b.lo.y < b.hi.y && b.lo.z < b.hi.z;
    };
    std::mt19937 rng(seed);
    for (const int size : {1, 3, 40, 300, static_cast<int>(n)}) {
      std::vector<Index> subset;
      for (Index i = 0; i < n; ++i) subset.push_back(i);
      std::shuffle(subset.begin(), subset.end(), rng);
      subset.resize(static_cast<std::size_t>(size));
      if (size == 3) subset.back() = n - 1;  // the box over everything
      std::sort(subset.begin(), subset.end());
      std::vector<char> in(static_cast<std::size_t>(n), 0);
      for (Index i : subset) in[static_cast<std::size_t>(i)] = 1;
      std::vector<std::array<Index, 2>> expected;
      for (Index i = 0; i < n; ++i)
        for (Index j = i + 1; j < n; ++j)
          if ((in[static_cast<std::size_t>(i)] || in[static_cast<std::size_t>(j)]) &&
              open_overlap(g.boxes[static_cast<std::size_t>(i)], g.boxes[static_cast<std::size_t>(j)]))
            expected.push_back({i, j});
      const BoxPairs got = box_subset_pairs(g.boxes, subset, BoxContact::open, 1 << 30);
      EXPECT_TRUE(got.is_complete);
      EXPECT_EQ(got.pairs, expected) << "seed " << seed << ", subset of " << size;
      if (size > 1) {
        EXPECT_FALSE(expected.empty());
      }
    }
  }
}

}  // namespace
}  // namespace hq::detail
