// Greedy label placement: labels never overlap each other, the obstacles or
// their anchor; the first free candidate wins; a moved label gets a leader
// line that starts on its anchor disc and ends on its box.
#include "hqview/render/label_layout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace hq {
namespace HQ_TEST_UNIT {

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


PlacedLabel leader(double x0, double y0, double x1, double y1) {
  PlacedLabel p;
  p.has_leader = true;
  p.leader_x0 = x0, p.leader_y0 = y0, p.leader_x1 = x1, p.leader_y1 = y1;
  return p;
}

// The leader predicates against hand-drawn segments.
TEST(LabelLayout, LeaderPredicatesByHand) {
  // An X crosses; parallel and disjoint segments do not; a shared end counts.
  EXPECT_TRUE(leaders_cross(leader(0, 0, 10, 10), leader(0, 10, 10, 0)));
  EXPECT_FALSE(leaders_cross(leader(0, 0, 10, 0), leader(0, 5, 10, 5)));
  EXPECT_FALSE(leaders_cross(leader(0, 0, 4, 4), leader(6, 0, 10, 4)));
  EXPECT_TRUE(leaders_cross(leader(0, 0, 5, 5), leader(5, 5, 10, 0)));
  PlacedLabel none = leader(0, 10, 10, 0);
  none.has_leader = false;
  EXPECT_FALSE(leaders_cross(leader(0, 0, 10, 10), none));
  // A segment through a box's interior meets it; one that passes beside or
  // stops short does not.
  const PixelRect box{20, 20, 10, 10};
  EXPECT_TRUE(leader_meets_box(leader(0, 25, 40, 25), box));
  EXPECT_FALSE(leader_meets_box(leader(0, 35, 40, 35), box));
  EXPECT_FALSE(leader_meets_box(leader(0, 25, 15, 25), box));
  EXPECT_TRUE(leader_meets_box(leader(25, 0, 25, 22), box));
  // A disc of radius 5 at (50, 50): the segment y = 53 passes 3 px from its
  // centre (inside); y = 56 passes 6 px away (outside); a segment ending 7 px
  // before the centre does not reach it.
  const ScreenDisc disc{50, 50, 5};
  EXPECT_TRUE(leader_meets_disc(leader(0, 53, 100, 53), disc));
  EXPECT_FALSE(leader_meets_disc(leader(0, 56, 100, 56), disc));
  EXPECT_FALSE(leader_meets_disc(leader(0, 50, 43, 50), disc));
  EXPECT_TRUE(leader_meets_disc(leader(0, 50, 46, 50), disc));
}

// Crowded anchors in a row: every placed label is outside every glyph, no two
// boxes overlap, no two leaders cross, no leader runs through another label's
// box, and labels placed by an earlier call keep their boxes free.
TEST(LabelLayout, CrowdedRowKeepsLeadersApartAndRespectsEarlierLabels) {
  std::vector<ScreenDisc> glyphs;
  std::vector<LabelRequest> requests;
  for (int i = 0; i < 8; ++i) {
    glyphs.push_back({200.0 + 18.0 * i, 200.0 + (i % 2) * 10.0, 8.0});
    requests.push_back({glyphs.back(), 40, 14});
  }
  const LabelLayoutOptions options = options_for({0, 0, 600, 400});
  // The first label alone, then the rest with it as "earlier".
  const auto first = place_labels(std::span(requests).first(1), glyphs, {}, options);
  ASSERT_TRUE(first[0].has_value());
  const std::vector<PlacedLabel> earlier{*first[0]};
  const auto rest = place_labels(std::span(requests).subspan(1), glyphs, {}, options, earlier);
  std::vector<PlacedLabel> all = earlier;
  for (const auto& p : rest) {
    ASSERT_TRUE(p.has_value());
    all.push_back(*p);
  }
  for (std::size_t i = 0; i < all.size(); ++i) {
    for (const ScreenDisc& g : glyphs) EXPECT_FALSE(box_meets_disc(all[i].box, g)) << "label " << i;
    for (std::size_t j = i + 1; j < all.size(); ++j) {
      EXPECT_FALSE(boxes_overlap(all[i].box, all[j].box)) << i << " " << j;
      EXPECT_FALSE(leaders_cross(all[i], all[j])) << i << " " << j;
    }
    for (std::size_t j = 0; j < all.size(); ++j)
      if (j != i) {
        EXPECT_FALSE(leader_meets_box(all[i], all[j].box)) << i << " through " << j;
      }
  }
  // The same request again: without `earlier` it takes the first label's
  // very box (placement is deterministic); with it, another free box.
  const auto again = place_labels(std::span(requests).first(1), glyphs, {}, options);
  ASSERT_TRUE(again[0].has_value());
  EXPECT_TRUE(boxes_overlap(again[0]->box, first[0]->box));
  const auto after = place_labels(std::span(requests).first(1), glyphs, {}, options, earlier);
  ASSERT_TRUE(after[0].has_value());
  EXPECT_FALSE(boxes_overlap(after[0]->box, first[0]->box));
  EXPECT_FALSE(leaders_cross(*after[0], *first[0]));
  // A crowded row needs leaders for most of its labels.
  int leaders = 0;
  for (const PlacedLabel& p : all) leaders += p.has_leader ? 1 : 0;
  EXPECT_GE(leaders, 4);
}

}  // namespace
}  // namespace hq

namespace hq {
namespace HQ_TEST_UNIT {

// Callout columns (issue 44 part V): 10 glyphs piled at the left end of an
// 800 x 600 view (dolphin_rot's pile-up), each a disc of radius 6 and a
// label of 70 x 18, with a box already taken above the pile: every label
// is placed, inside the bounds, over no glyph disc and no taken box, the
// boxes pairwise disjoint; each leader starts on its glyph's disc edge and
// ends on its own box's edge; no two leaders cross, no leader runs through
// another label's box; a leader that could avoid the protected disc #0
// does. With no room (a view one label high) nothing is placed.
TEST(LabelLayout, CalloutColumnsHoldAPileUpWithoutCrossings) {
  std::vector<ScreenDisc> discs;
  std::vector<CalloutLabel> labels;
  for (int i = 0; i < 10; ++i) {
    const ScreenDisc d{30.0 + 9.0 * (i % 4), 280.0 + 11.0 * i, 6.0, i};
    discs.push_back(d);
    labels.push_back({ScreenDisc{d.x, d.y, 2.0, i}, 70, 18, i});
  }
  const PixelRect bounds{0, 0, 800, 600};
  const std::vector<PixelRect> taken{{10, 200, 120, 30}};
  const std::vector<PlacedLabel> placed = place_callout_columns(labels, discs, taken, bounds, 4.0);
  ASSERT_EQ(placed.size(), labels.size());
  for (std::size_t i = 0; i < placed.size(); ++i) {
    const PlacedLabel& p = placed[i];
    SCOPED_TRACE(i);
    EXPECT_TRUE(p.has_leader);
    EXPECT_GE(p.box.x, 0);
    EXPECT_GE(p.box.y, 0);
    EXPECT_LE(p.box.x + p.box.width, 800);
    EXPECT_LE(p.box.y + p.box.height, 600);
    EXPECT_EQ(p.box.width, 70);
    for (const ScreenDisc& d : discs) EXPECT_FALSE(box_meets_disc(p.box, d));
    for (const PixelRect& t : taken) EXPECT_FALSE(boxes_overlap(p.box, t));
    EXPECT_NEAR(std::hypot(p.leader_x0 - labels[i].start.x, p.leader_y0 - labels[i].start.y), 2.0, 1e-9);
    EXPECT_LE(disc_box_gap(ScreenDisc{p.leader_x1, p.leader_y1, 0.0}, p.box), 1e-9);
    for (std::size_t j = 0; j < placed.size(); ++j) {
      if (j == i) continue;
      EXPECT_FALSE(boxes_overlap(p.box, placed[j].box)) << j;
      EXPECT_FALSE(leaders_cross(p, placed[j])) << j;
      EXPECT_FALSE(leader_meets_box(p, placed[j].box)) << j;
    }
    // The protected #0: no other leader over it.
    if (i > 0) EXPECT_FALSE(leader_meets_disc(p, discs[0]));
  }
  EXPECT_TRUE(place_callout_columns(labels, discs, taken, PixelRect{0, 0, 800, 20}, 4.0).empty());
}

}  // namespace
}  // namespace hq

namespace hq {
namespace HQ_TEST_UNIT {

// Spokes of glyph discs along the eight directions a label first tries
// (every 8 px from 20 px out to the view's edge), so that every candidate
// on those rays meets a disc; the wedges between them are empty. A label
// has room in a wedge (22.5 degrees between two spokes: about 0.77 d wide
// at distance d, its 30 x 12 box fits from d = 60 px); before the 44l
// review the placer tried the eight rays only and gave up ("no room", as
// Dolphin_padded's #4 and a turned dolphin's #5). Each label of the four
// (one anchor, placed one after another) finds a place in a wedge, its box
// disjoint from every disc and the other boxes, within 80 px of the anchor
// with a leader that keeps leader_clearance off every disc and crosses no
// other leader.
TEST(LabelLayout, ALabelFindsTheFreeWedgeBetweenBlockedDirections) {
  const ScreenDisc anchor{300, 300, 8, 0};
  std::vector<ScreenDisc> spokes;
  for (int k = 0; k < 8; ++k) {
    const double a = k * std::numbers::pi / 4.0;
    for (double d = 20; d < 300; d += 8) spokes.push_back({300 + d * std::cos(a), 300 + d * std::sin(a), 5, k + 1});
  }
  LabelLayoutOptions o = options_for({0, 0, 600, 600});
  o.rings = 28;
  o.leader_clearance = 2.0;
  std::vector<LabelRequest> labels(4, LabelRequest{anchor, 30, 12});
  for (LabelRequest& l : labels) l.strict_leaders = true;
  const auto placed = place_labels(labels, spokes, {}, o);
  for (std::size_t i = 0; i < placed.size(); ++i) {
    SCOPED_TRACE(i);
    ASSERT_TRUE(placed[i]);
    const PlacedLabel& p = *placed[i];
    for (const ScreenDisc& d : spokes) {
      EXPECT_FALSE(box_meets_disc(p.box, d));
      EXPECT_FALSE(leader_meets_disc(p, ScreenDisc{d.x, d.y, d.radius + o.leader_clearance}));
    }
    EXPECT_LE(disc_box_gap(anchor, p.box), 80.0);
    EXPECT_TRUE(p.has_leader);
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_FALSE(boxes_overlap(p.box, placed[j]->box)) << j;
      EXPECT_FALSE(leaders_cross(p, *placed[j])) << j;
    }
  }
  // Candidates between the eight directions: a ring's 8, then 16 more at
  // 22.5 degrees when its length allows, boxes sliding along their edge.
  const LabelRequest one{{300, 300, 8}, 30, 12};
  LabelLayoutOptions near = o;
  near.rings = 0;  // only the first ring (12 px from the centre: 8 candidates)
  EXPECT_FALSE(place_labels(std::span(&one, 1), spokes, {}, near)[0]);
}

// Two leaders that run side by side read as one line (the 44e shots):
// 40 px at 2 px apart do, two leaving one point at a right angle do not,
// nor two parallel ones 8 px apart. A second label whose only near place
// would lay its leader along the first's gets another (clear) place.
TEST(LabelLayout, LeadersDoNotRunTogether) {
  auto leader = [](double x0, double y0, double x1, double y1) {
    PlacedLabel p;
    p.has_leader = true;
    p.leader_x0 = x0, p.leader_y0 = y0, p.leader_x1 = x1, p.leader_y1 = y1;
    return p;
  };
  EXPECT_TRUE(leaders_run_together(leader(100, 100, 60, 100), leader(100, 102, 60, 102)));
  EXPECT_FALSE(leaders_run_together(leader(100, 100, 60, 100), leader(100, 100, 100, 60)));
  EXPECT_TRUE(leaders_run_together(leader(100, 100, 60, 100), leader(100, 106, 60, 106)));  // the 44e review's 6 px
  EXPECT_FALSE(leaders_run_together(leader(100, 100, 60, 100), leader(100, 108, 60, 108)));
  EXPECT_FALSE(leaders_run_together(leader(100, 100, 60, 100), PlacedLabel{}));
}

}  // namespace
}  // namespace hq
