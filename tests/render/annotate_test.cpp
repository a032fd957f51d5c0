#include "hqview/render/annotate.h"

#include <gtest/gtest.h>

#include "hqview/core/error.h"
#include "image_probe.h"
#include "hqview/render/colormap.h"

namespace hq {
namespace {

using test::count_differing;
using test::kWhite;
using test::pixel_at;

TEST(ImageOps, MakeFillPasteClip) {
  Image image = make_image(10, 6, kWhite);
  ASSERT_EQ(image.rgba.size(), 10u * 6u * 4u);
  fill_rect(image, {-3, 4, 5, 10}, {1, 2, 3, 255});  // clipped to x [0, 2), y [4, 6)
  EXPECT_EQ(pixel_at(image, 1, 5), (Rgba8{1, 2, 3, 255}));
  EXPECT_EQ(pixel_at(image, 2, 5), kWhite);
  EXPECT_EQ(pixel_at(image, 1, 3), kWhite);
  const Image patch = make_image(4, 4, {9, 9, 9, 255});
  paste(image, patch, 8, -2);  // clipped to x [8, 10), y [0, 2)
  EXPECT_EQ(pixel_at(image, 9, 1), (Rgba8{9, 9, 9, 255}));
  EXPECT_EQ(pixel_at(image, 7, 1), kWhite);
  EXPECT_EQ(pixel_at(image, 9, 2), kWhite);
}

TEST(Text, DrawsGlyphsAndMeasures) {
  const AnnotationStyle style;
  Image image = make_image(300, 80, kWhite);
  draw_text(image, 10, 50, "Quality 0.25", 30, style);
  EXPECT_GT(count_differing(image, {0, 0, 300, 80}, kWhite), 200);
  EXPECT_EQ(count_differing(image, {0, 60, 300, 20}, kWhite), 0) << "nothing far below the baseline";
  const PixelRect one = text_extent("Quality", 30, style), two = text_extent("Quality\nQuality", 30, style);
  EXPECT_GT(one.width, 60);
  EXPECT_LT(one.width, 160);
  EXPECT_EQ(two.width, one.width);
  EXPECT_GT(two.height, one.height + 25);
}

TEST(Text, MissingFontThrowsRenderError) {
  AnnotationStyle style;
  style.font_path = "/nonexistent/font.ttf";
  Image image = make_image(100, 40, kWhite);
  EXPECT_THROW(draw_text(image, 5, 30, "x", 20, style), RenderError);
}

TEST(ColorBar, QualityBarDrawsTheMapTopToBottom) {
  const AnnotationStyle style = annotation_style_for(1200);
  const ColorBar bar = quality_color_bar();
  const int width = color_bar_width(bar, style);
  EXPECT_GT(width, 150);
  EXPECT_LT(width, 500);
  Image image = make_image(width, 1100, kWhite);
  draw_color_bar(image, {0, 0, width, 1100}, bar, style);
  // Find the bar: the column 10 pixels inside its left edge, scanning down
  // for the quality map's calm end.
  const int x = 20 + 17;  // inset + half the bar width at scale 1
  int top = -1, bottom = -1;
  for (int y = 0; y < image.height; ++y) {
    const Rgba8 c = pixel_at(image, x, y);
    if (top < 0 && c == to_rgba8(sample_quality_map(1.0))) top = y;
    if (c == to_rgba8(sample_quality_map(0.0))) bottom = y;
  }
  ASSERT_GE(top, 0);
  ASSERT_GT(bottom, top + 300);
  EXPECT_LT(cie_lightness(to_color(pixel_at(image, x, bottom - 5))), cie_lightness(to_color(pixel_at(image, x, top + 5))));
  // The inverted swatch sits below the bar.
  bool has_inverted = false;
  for (int y = bottom; y < image.height; ++y) has_inverted |= pixel_at(image, x, y) == to_rgba8(kInvertedColor);
  EXPECT_TRUE(has_inverted);
}

TEST(FigureLayout, PartsTileTheFigure) {
  const AnnotationStyle style = annotation_style_for(1200);
  const FigureLayout layout = figure_layout(1600, 1200, true, 340, style);
  EXPECT_EQ(layout.title.y, 0);
  EXPECT_EQ(layout.title.width, 1600);
  EXPECT_EQ(layout.view.y, layout.title.height);
  EXPECT_EQ(layout.view.width + layout.legend.width, 1600);
  EXPECT_EQ(layout.view.y + layout.view.height, 1200);
  EXPECT_EQ(layout.legend.x, layout.view.width);
  const FigureLayout bare = figure_layout(640, 480, false, 0, style);
  EXPECT_EQ(bare.view.width, 640);
  EXPECT_EQ(bare.view.height, 480);
}

}  // namespace
}  // namespace hq
