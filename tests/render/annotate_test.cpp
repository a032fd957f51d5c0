#include "hqview/render/annotate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "hqview/core/error.h"
#include "hqview/image/colormap.h"
#include "support/image_probe.h"

namespace hq {
namespace HQ_TEST_UNIT {

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
  EXPECT_LT(cie_lightness(to_color(pixel_at(image, x, bottom - 5))),
            cie_lightness(to_color(pixel_at(image, x, top + 5))));
  // The inverted swatch sits below the bar.
  bool has_inverted = false;
  for (int y = bottom; y < image.height; ++y) has_inverted |= pixel_at(image, x, y) == to_rgba8(kInvertedColor);
  EXPECT_TRUE(has_inverted);
}

TEST(Text, FitsAndEllipsizes) {
  const AnnotationStyle style;
  const std::string text = "ball.mesh: glyph clusters and overlaps, view 1 (from +x+z)";
  const int wide = text_extent(text, 30, style).width;
  EXPECT_EQ(fitting_text_size(text, 30, 9, wide, style), 30) << "fits as it is";
  const int size = fitting_text_size(text, 30, 9, wide / 2, style);
  EXPECT_LT(size, 30);
  EXPECT_LE(text_extent(text, size, style).width, wide / 2);
  EXPECT_GT(text_extent(text, size + 1, style).width, wide / 2) << "the largest size that fits";
  EXPECT_EQ(ellipsize(text, 30, wide, style), text);
  const std::string cut = ellipsize(text, 30, wide / 3, style);
  EXPECT_LE(text_extent(cut, 30, style).width, wide / 3);
  ASSERT_GT(cut.size(), 3u);
  EXPECT_EQ(cut.substr(cut.size() - 3), "...");
  EXPECT_EQ(text.rfind(cut.substr(0, cut.size() - 3), 0), 0u) << "a prefix of the text";
}

// A 320x240 figure (--size 320x240): the legend panel gets at most half the
// width, less than the quality bar asks for at the minimum text size. Drawn
// into a figure with spare room right of and below the panel, the legend
// leaves that room untouched, and so does the title right of its band.
TEST(ColorBar, SmallFigureLegendStaysInItsPanel) {
  const AnnotationStyle style = annotation_style_for(240);
  const ColorBar bar = quality_color_bar();
  const FigureLayout layout = figure_layout(320, 240, true, color_bar_width(bar, style), style);
  ASSERT_LT(layout.legend.width, color_bar_width(bar, style)) << "the case this test is about";
  const AnnotationStyle fitted = color_bar_style_for(bar, style, layout.legend);
  EXPECT_LE(color_bar_width(bar, fitted), layout.legend.width);
  EXPECT_LE(color_bar_height(bar, fitted, layout.legend.height), layout.legend.height);
  Image image = make_image(320 + 200, 240 + 100, kWhite);
  draw_color_bar(image, layout.legend, bar, style);
  draw_title(image, layout.title, "ball.mesh: glyph clusters and overlaps, view 1 (from +x+z)", style);
  EXPECT_GT(count_differing(image, layout.legend, kWhite), 500);
  EXPECT_GT(count_differing(image, layout.title, kWhite), 200);
  EXPECT_EQ(count_differing(image, {320, 0, 200, 340}, kWhite), 0) << "nothing right of the figure";
  EXPECT_EQ(count_differing(image, {0, 240, 520, 100}, kWhite), 0) << "nothing below the figure";
  // A 1200-pixel-high figure keeps its style.
  const AnnotationStyle big = annotation_style_for(1200);
  const FigureLayout full = figure_layout(1600, 1200, true, color_bar_width(bar, big), big);
  EXPECT_EQ(color_bar_style_for(bar, big, full.legend).scale, big.scale);
}

// A title too long for one line at the smallest size wraps onto two (the
// 45e review: an 800 x 400 compare view's title was cut at "...; mirror
// i..."): ink in two bands of rows with blank rows between, none cut off.
TEST(Title, TooLongForOneLineWrapsOntoTwo) {
  const AnnotationStyle style = annotation_style_for(400);
  const FigureLayout layout = figure_layout(800, 400, true, 0, style);
  std::string title = "kitten_1.mesh (left, min 0.357) vs kitten_mirror.mesh (right, min -1): vertex quality, one camera";
  title += ", right turned 90 deg about -z (scale 1), refined by ICP; mirror image: no rotation fits (mirrored)";
  ASSERT_GT(text_extent(title, 9, style).width, layout.title.width) << "the case this test is about";
  Image image = make_image(800, 400, kWhite);
  draw_title(image, layout.title, title, style);
  std::vector<int> inked_rows;
  for (int y = layout.title.y; y < layout.title.y + layout.title.height; ++y)
    if (count_differing(image, {0, y, 800, 1}, kWhite) > 0) inked_rows.push_back(y);
  ASSERT_FALSE(inked_rows.empty());
  int bands = 1;
  for (std::size_t i = 1; i < inked_rows.size(); ++i) bands += inked_rows[i] > inked_rows[i - 1] + 1;
  EXPECT_EQ(bands, 2);
  // Both lines end inside the figure: nothing in its last 8 columns.
  EXPECT_EQ(count_differing(image, {792, layout.title.y, 8, layout.title.height}, kWhite), 0);
}

// A ring swatch (view A's rings, issue 44) is a circle outline with the
// background inside; a square swatch of nearly the same near-black (the
// coincident-vertex arrows) is filled: the two differ by shape.
TEST(Legend, RingSwatchIsHollow) {
  const AnnotationStyle style;  // scale 1: 18 px swatches, 34 px pitch
  Image image = make_image(300, 140, kWhite);
  const Rgba8 ring{38, 38, 38, 255}, square{25, 25, 25, 255};
  const std::vector<LegendLine> lines{{ring, "ring: worst cluster #0", 0, SwatchShape::solid_ring}, {square, "coincident vertices"}};
  draw_legend(image, {0, 0, 300, 140}, lines, style);
  // Swatches: x [16, 34), bottoms at y 40 and 74.
  auto near = [](const Rgba8& p, const Rgba8& c) { return std::abs(p.r - c.r) + std::abs(p.g - c.g) <= 20; };
  EXPECT_EQ(pixel_at(image, 25, 31), kWhite) << "the ring's centre shows the background";
  EXPECT_TRUE(near(pixel_at(image, 25, 65), square)) << "the square is filled";
  int outline = 0;
  for (int i = 0; i < 16; ++i) {
    const double a = 2.0 * M_PI * i / 16;
    outline += near(pixel_at(image, static_cast<int>(std::lround(25 + 7.5 * std::cos(a))),
                             static_cast<int>(std::lround(31 + 7.5 * std::sin(a)))),
                    ring)
                   ? 1
                   : 0;
  }
  EXPECT_GE(outline, 12) << "the ring's outline is drawn in its colour";
}

// Each swatch shape has one entry in kSwatchMarks (the table draw_swatch
// reads), and the shapes a legend tells apart look apart: an arrow has a
// head above and below its shaft's end where a thick line has none; a line
// leaves the square's corners empty where a box fills them.
TEST(Legend, EverySwatchShapeHasOneMark) {
  for (SwatchShape shape : {SwatchShape::box, SwatchShape::solid_ring, SwatchShape::dashed_ring, SwatchShape::line,
                            SwatchShape::thick_line, SwatchShape::dashed_line, SwatchShape::thick_dashed_line, SwatchShape::arrow,
                            SwatchShape::text}) {
    int entries = 0;
    for (const SwatchMark& m : kSwatchMarks) entries += m.shape == shape ? 1 : 0;
    EXPECT_EQ(entries, 1) << static_cast<int>(shape);
  }
  const Rgba8 ink{20, 120, 40, 255};
  auto drawn = [&](SwatchShape shape) {
    Image image = make_image(40, 40, kWhite);
    draw_swatch(image, {10, 10, 20, 20}, ink, shape);
    return image;
  };
  const Image arrow = drawn(SwatchShape::arrow), line = drawn(SwatchShape::thick_line), box = drawn(SwatchShape::box);
  // The head's wings at 3 px above and below the shaft, 4 px from its tip.
  EXPECT_NE(pixel_at(arrow, 25, 17), kWhite);
  EXPECT_NE(pixel_at(arrow, 25, 23), kWhite);
  EXPECT_EQ(pixel_at(line, 25, 16), kWhite);
  EXPECT_EQ(pixel_at(line, 25, 24), kWhite);
  EXPECT_EQ(pixel_at(box, 11, 11), ink);
  EXPECT_EQ(pixel_at(line, 11, 11), kWhite);
  EXPECT_EQ(pixel_at(drawn(SwatchShape::text), 20, 20), kWhite);
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

namespace hq {
namespace HQ_TEST_UNIT {

// A bar of 101 rows over [-1, 1] (row 50 (1 - v)), labels 18 px tall (a
// kept label needs 19 rows to the next): the ends at rows 100 and 0 first;
// -0.94 (row 97) and 0.94 (row 3) left out, 0 (row 50) and 0.6 (row 20)
// kept, 0.5 (row 25: 5 from 0.6's) and 0.8 (row 10: 10 from the end's) left out.
TEST(ColorBarTicks, ALabelThatWouldTouchItsNeighboursIsLeftOut) {
  ColorBar bar;
  bar.min_value = -1.0;
  bar.max_value = 1.0;
  bar.ticks = {{-1.0, "<= -1"}, {-0.94, "-0.94"}, {0.0, "0"}, {0.6, "0.6"}, {0.5, "0.5"}, {0.8, "0.8"}, {0.94, "0.94"}, {1.0, ">= 1"}};
  EXPECT_EQ(legible_ticks(bar, 101, 18), (std::vector<std::size_t>{0, 2, 3, 7}));
  // 8 px labels (9 rows): 0.8 (10 from the end's and 0.6's) kept too; 0.94 (3) and 0.5 (5) still not.
  EXPECT_EQ(legible_ticks(bar, 101, 8), (std::vector<std::size_t>{0, 2, 3, 5, 7}));
}

}  // namespace HQ_TEST_UNIT
}  // namespace hq
