// Chart layout without drawing (what is drawn, where, in which colour), and
// the Cairo output (SVG text, PNG pixels) from the one drawing routine.
#include "hqview/chart/chart.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "hqview/render/colormap.h"

namespace hq {
namespace {

bool inside(const ChartRect& outer, const ChartRect& r) {
  return r.x >= outer.x - 1e-9 && r.y >= outer.y - 1e-9 && r.x + r.width <= outer.x + outer.width + 1e-9 &&
         r.y + r.height <= outer.y + outer.height + 1e-9;
}

bool has_text(const Chart& chart, const std::string& text) {
  return std::any_of(chart.texts.begin(), chart.texts.end(), [&](const ChartText& t) { return t.text == text; });
}

TEST(QualityHistogram, OneBarPerNonEmptyBinInsideThePlot) {
  const std::vector<double> values{0.9, 0.91, 0.92, 0.5, -0.2, 1e30, std::nan("")};
  const Chart chart = quality_histogram_chart(values, false, {800, 400, "title"}, 0.1);
  ASSERT_EQ(chart.rects.size(), 3u);  // bins [0.9,1), [0.5,0.6), [-0.2,-0.1)
  for (const ChartRect& r : chart.rects) EXPECT_TRUE(inside(chart.plot, r));
  // Sorted by x: the inverted bin first, in the inverted colour; the tallest is the 3-count bin.
  EXPECT_EQ(chart.rects[0].fill, to_rgba8(kInvertedColor));
  EXPECT_LT(chart.rects[0].x, chart.rects[1].x);
  EXPECT_NEAR(chart.rects[2].height, 3.0 * chart.rects[1].height, 1e-9);
  EXPECT_EQ(chart.rects[2].fill, to_rgba8(quality_color(0.95)));
  EXPECT_TRUE(has_text(chart, "title"));
  EXPECT_TRUE(has_text(chart, "scaled Jacobian (per hex)"));
  EXPECT_TRUE(has_text(chart, "hexes"));
}

TEST(QualityHistogram, LogScaleCompressesTallBars) {
  std::vector<double> values(1000, 0.95);
  values.push_back(0.05);
  const Chart linear = quality_histogram_chart(values, false, {}, 0.1);
  const Chart log = quality_histogram_chart(values, true, {}, 0.1);
  ASSERT_EQ(log.rects.size(), 2u);
  EXPECT_GT(log.rects[0].height / log.rects[1].height, 5.0 * linear.rects[0].height / linear.rects[1].height);
  EXPECT_TRUE(has_text(log, "hexes (log scale)"));
  EXPECT_TRUE(has_text(log, "1000"));
}

TEST(SortedQuality, WorstFirstAndACurveOverAll) {
  std::vector<double> q;
  for (int i = 0; i < 100; ++i) q.push_back(1.0 - i / 100.0);
  q.push_back(std::nan(""));
  const Chart chart = sorted_quality_chart(q, 10, {});
  ASSERT_EQ(chart.rects.size(), 10u);
  // The worst (0.01) is on the left and tallest above zero... bars grow with quality.
  for (std::size_t i = 1; i < chart.rects.size(); ++i) {
    EXPECT_GT(chart.rects[i].x, chart.rects[i - 1].x);
    EXPECT_GE(chart.rects[i].height, chart.rects[i - 1].height);
  }
  const auto curve = std::max_element(chart.lines.begin(), chart.lines.end(),
                                      [](const auto& a, const auto& b) { return a.points.size() < b.points.size(); });
  EXPECT_EQ(curve->points.size(), 100u);
  EXPECT_GT(curve->points.front().y, curve->points.back().y) << "ascending quality goes up the page";
}

TEST(CornerChart, LabelsEveryCornerWithItsValue) {
  const std::vector<double> values{0.5, -0.25};
  const std::vector<std::string> labels{"hex 3", "hex 7"};
  const Chart chart = corner_chart(values, labels, {});
  ASSERT_EQ(chart.rects.size(), 2u);
  EXPECT_TRUE(has_text(chart, "0.500"));
  EXPECT_TRUE(has_text(chart, "-0.250"));
  EXPECT_TRUE(has_text(chart, "hex 7"));
  EXPECT_EQ(chart.rects[1].fill, to_rgba8(kInvertedColor));
}

TEST(ChartOutput, SvgAndPngFromOneChart) {
  const Chart chart = quality_histogram_chart(std::vector<double>{0.5, 0.7}, false, {320, 200, "t"}, 0.1);
  const std::string svg = chart_svg(chart);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_EQ(svg, chart_svg(chart)) << "deterministic";
  const Image png = chart_image(chart);
  ASSERT_EQ(png.width, 320);
  ASSERT_EQ(png.height, 200);
  // A bar's centre has the bar's colour; the corner keeps the background.
  const ChartRect& bar = chart.rects[0];
  const int x = static_cast<int>(bar.x + bar.width / 2), y = static_cast<int>(bar.y + bar.height / 2);
  const std::uint8_t* p = png.rgba.data() + pixel_offset(png, x, y);
  EXPECT_NEAR(p[0], bar.fill.r, 1);
  EXPECT_NEAR(p[1], bar.fill.g, 1);
  EXPECT_NEAR(p[2], bar.fill.b, 1);
  const std::uint8_t* corner = png.rgba.data() + pixel_offset(png, png.width - 2, png.height - 2);
  EXPECT_EQ(corner[0], 255);
  EXPECT_EQ(corner[3], 255);
}

}  // namespace
}  // namespace hq
