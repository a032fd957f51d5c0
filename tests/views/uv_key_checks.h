#pragma once
// The UV key's numbers judged pixel by pixel (issue 45c), shared by
// uv_key_view_test (an icosphere) and uv_key_hand_test (the hand, slow).
#include <gtest/gtest.h>

#include <memory>
#include <set>

#include "hqview/render/osmesa_renderer.h"
#include "hqview/uv/uv_atlas.h"
#include "hqview/views/uv_key_view.h"

namespace hq {

// Issue 45c: on the hand, numbers moved off a crowded finger sat on other
// charts with no leader ("10" on chart 11's fingertip). Now every number's
// box lies on its own chart's pixels, or a leader ends on a pixel of its
// chart. Judged pixel by pixel on each frame's chart ids (the frame drawn
// again with each chart in its id colour), which the atlas frame of the
// figure is checked against.
inline void expect_numbers_on_their_charts(const TriSurface& surface, const UvAtlas& atlas, int min_numbered) {
  BoundaryViewOptions options;
  options.width = 1200;
  options.height = 900;
  options.up = {0.0, 1.0, 0.0};
  options.title = "uv key";
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  std::vector<UvKeyFrame> frames;
  const Image figure = render_uv_key(surface, atlas, options, *renderer, &frames);
  ASSERT_EQ(frames.size(), 3u);
  int numbered = 0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const UvKeyFrame& frame = frames[f];
    auto id = [&](int x, int y) { return frame.ids.at(x - frame.area.x, y - frame.area.y); };
    for (const UvKeyNumber& n : frame.numbers) {
      if (!n.placed) continue;
      ++numbered;
      if (n.has_leader) {
        EXPECT_EQ(id(n.anchor_x, n.anchor_y), n.chart) << "frame " << f << ": the leader of " << n.chart
                                                        << " ends on another chart";
        continue;
      }
      int own = 0, other = 0;
      for (int y = n.box.y; y < n.box.y + n.box.height; ++y)
        for (int x = n.box.x; x < n.box.x + n.box.width; ++x) (id(x, y) == n.chart ? own : other) += 1;
      EXPECT_EQ(other, 0) << "frame " << f << ": number " << n.chart << " covers " << other << " pixels not of its chart";
      EXPECT_GT(own, 0);
    }
  }
  EXPECT_GE(numbered, min_numbered);
  // The atlas shows every chart: each with a pixel of its own there (not
  // only edges blended with others: thinner than 3 px) has its number.
  std::set<Index> in_atlas, shown;
  for (const UvKeyNumber& n : frames[2].numbers)
    if (n.placed) in_atlas.insert(n.chart);
  for (Index c : frames[2].ids.ids)
    if (c != kNoIndex) shown.insert(c);
  EXPECT_EQ(in_atlas, shown);
  EXPECT_GE(shown.size() + 2, static_cast<std::size_t>(atlas.num_charts));
  // The ids are the figure's: in the atlas frame (unlit), the pixels of a
  // chart show its tint except under outlines and numbers.
  const UvKeyFrame& uv = frames[2];
  int known = 0, tinted = 0;
  for (int y = 0; y < uv.ids.height; ++y)
    for (int x = 0; x < uv.ids.width; ++x) {
      const Index c = uv.ids.at(x, y);
      if (c == kNoIndex) continue;
      ++known;
      const std::uint8_t* p = &figure.rgba[4 * (static_cast<std::size_t>(uv.area.y + y) * figure.width + uv.area.x + x)];
      const Rgba8 t = chart_tint(c);
      tinted += p[0] == t.r && p[1] == t.g && p[2] == t.b;
    }
  ASSERT_GT(known, 1000);
  EXPECT_GT(tinted, 0.8 * known);
}

}  // namespace hq
