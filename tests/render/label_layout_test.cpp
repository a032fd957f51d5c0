// Greedy label placement: labels never overlap each other, the obstacles or
// their anchor; the first free candidate wins; a moved label gets a leader
// line that starts on its anchor disc and ends on its box.
#include "hqview/render/label_layout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace hq {
namespace {

LabelLayoutOptions options_for(PixelRect bounds) {
  LabelLayoutOptions o;
  o.bounds = bounds;
  o.gap = 4;
  o.ring_step = 10;
  o.rings = 60;
  o.leader_distance = 8;
  return o;
}

TEST(LabelLayout, AloneALabelSitsRightOfItsAnchor) {
  const LabelRequest label{{100, 100, 10}, 40, 16};
  const auto placed = place_labels(std::span(&label, 1), {}, {}, options_for({0, 0, 400, 400}));
  ASSERT_TRUE(placed[0]);
  EXPECT_EQ(placed[0]->box.x, 114);  // 100 + 10 + 4
  EXPECT_EQ(placed[0]->box.y, 92);   // centred on the anchor's row
  EXPECT_FALSE(placed[0]->has_leader);
}

TEST(LabelLayout, ObstaclesAndBoundsPushALabelToTheNextCandidate) {
  const LabelRequest label{{100, 100, 10}, 40, 16};
  // A disc right of the anchor blocks right, upper right and lower right
  // (their boxes come within 10 pixels of its centre): left is next.
  const ScreenDisc right{135, 100, 12};
  auto placed = place_labels(std::span(&label, 1), std::span(&right, 1), {}, options_for({0, 0, 400, 400}));
  ASSERT_TRUE(placed[0]);
  EXPECT_FALSE(box_meets_disc(placed[0]->box, right));
  EXPECT_EQ(placed[0]->box.x + placed[0]->box.width, 86);  // 100 − 10 − 4
  EXPECT_EQ(placed[0]->box.y, 92);
  // At the right edge of the bounds, the label goes to the left.
  const LabelRequest edge{{380, 100, 10}, 40, 16};
  placed = place_labels(std::span(&edge, 1), {}, {}, options_for({0, 0, 400, 400}));
  ASSERT_TRUE(placed[0]);
  EXPECT_EQ(placed[0]->box.x + placed[0]->box.width, 366);  // 380 − 10 − 4
}

TEST(LabelLayout, CrowdedLabelsAreDisjointAndMovedOnesHaveLeaders) {
  // 40 anchors within a 30-pixel square among 30 glyph discs: most labels
  // cannot sit next to their anchor.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> near(300, 330), far(50, 750);
  std::vector<LabelRequest> labels;
  for (int i = 0; i < 40; ++i) labels.push_back({{near(rng), near(rng), 3}, 30 + i % 20, 14});
  std::vector<ScreenDisc> obstacles;
  for (int i = 0; i < 30; ++i) obstacles.push_back({far(rng), far(rng), 15});
  const LabelLayoutOptions o = options_for({0, 0, 800, 800});
  const PixelRect legend{600, 0, 200, 200};
  const auto placed = place_labels(labels, obstacles, std::span(&legend, 1), o);
  int leaders = 0;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    ASSERT_TRUE(placed[i]) << i;
    const PixelRect& b = placed[i]->box;
    EXPECT_FALSE(boxes_overlap(b, legend));
    EXPECT_GE(b.x, 0);
    EXPECT_LE(b.x + b.width, 800);
    for (const ScreenDisc& d : obstacles) EXPECT_FALSE(box_meets_disc(b, d));
    EXPECT_FALSE(box_meets_disc(b, labels[i].anchor));
    for (std::size_t j = 0; j < i; ++j) EXPECT_FALSE(boxes_overlap(b, placed[j]->box)) << i << " " << j;
    const double gap = disc_box_gap(labels[i].anchor, b);
    EXPECT_EQ(placed[i]->has_leader, gap > o.leader_distance) << i;
    if (placed[i]->has_leader) {
      ++leaders;
      // Starts on the anchor's circle, ends on the box's edge.
      EXPECT_NEAR(std::hypot(placed[i]->leader_x0 - labels[i].anchor.x, placed[i]->leader_y0 - labels[i].anchor.y),
                  labels[i].anchor.radius, 1e-9);
      EXPECT_GE(placed[i]->leader_x1, b.x);
      EXPECT_LE(placed[i]->leader_x1, b.x + b.width);
      EXPECT_GE(placed[i]->leader_y1, b.y);
      EXPECT_LE(placed[i]->leader_y1, b.y + b.height);
    }
  }
  EXPECT_GT(leaders, 10);
}

TEST(LabelLayout, NoRoomMeansNoPlace) {
  const LabelRequest label{{50, 50, 5}, 200, 20};
  const auto placed = place_labels(std::span(&label, 1), {}, {}, options_for({0, 0, 100, 100}));
  EXPECT_FALSE(placed[0]);
}

TEST(LabelLayout, BoxAndDiscPredicates) {
  EXPECT_TRUE(boxes_overlap({0, 0, 10, 10}, {9, 9, 5, 5}));
  EXPECT_FALSE(boxes_overlap({0, 0, 10, 10}, {10, 0, 5, 5}));  // touching edges share no pixel
  EXPECT_TRUE(box_meets_disc({0, 0, 10, 10}, {15, 5, 5.5}));
  EXPECT_FALSE(box_meets_disc({0, 0, 10, 10}, {15, 5, 5.0}));
  EXPECT_DOUBLE_EQ(disc_box_gap({20, 5, 4}, {0, 0, 10, 10}), 6.0);
  EXPECT_DOUBLE_EQ(disc_box_gap({5, 5, 4}, {0, 0, 10, 10}), 0.0);
}

}  // namespace
}  // namespace hq
