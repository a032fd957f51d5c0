// The grouped box search (stage E's broad phase) against every pair tested
// directly, and against the flat search it replaces.
#include "hqview/overlap/box_pairs.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace hq::detail {
namespace {

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

}  // namespace
}  // namespace hq::detail
