// Chart layout without drawing (what is drawn, where, in which colour), and
// the Cairo output (SVG text, PNG pixels) from the one drawing routine.
#include "hqview/chart/chart.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <string>

#include "hqview/image/colormap.h"
#include "support/image_probe.h"

namespace hq {
namespace HQ_TEST_UNIT {

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

TEST(SortedQuality, EachBarHasAHotspotOverItsColumnNamingItsVertex) {
  // Vertex i has quality q[i]; by hand, ascending with ties by id:
  // 3 (-0.5), 0 (0.2), 4 (0.2), 1 (0.7); vertex 2 (NaN) has no bar.
  const std::vector<double> q{0.2, 0.7, std::nan(""), -0.5, 0.2};
  const Chart chart = sorted_quality_chart(q, 4, {});
  ASSERT_EQ(chart.rects.size(), 4u);
  ASSERT_EQ(chart.hotspots.size(), 4u);
  const std::vector<std::int32_t> expected{3, 0, 4, 1};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(chart.hotspots[i].key, expected[i]) << i;
    // The hotspot is the bar's column: it holds the bar, spans the plot's
    // height, and the columns tile the bar panel without overlapping.
    const ChartRect& spot = chart.hotspots[i].rect;
    EXPECT_TRUE(inside(spot, chart.rects[i])) << i;
    EXPECT_TRUE(inside(chart.plot, spot)) << i;
    EXPECT_DOUBLE_EQ(spot.y, chart.plot.y);
    EXPECT_DOUBLE_EQ(spot.height, chart.plot.height);
    if (i > 0) {
      EXPECT_NEAR(spot.x, chart.hotspots[i - 1].rect.x + chart.hotspots[i - 1].rect.width, 1e-9);
    }
  }
}

TEST(CornerChart, LabelsEveryCornerWithItsValue) {
  const std::vector<double> values{0.5, -0.25};
  const std::vector<std::string> labels{"hex 3", "hex 7"};
  const Chart chart = corner_chart(values, labels, {});
  ASSERT_GE(chart.rects.size(), 2u);  // the bars first, then the colour key's
  EXPECT_TRUE(has_text(chart, "0.500"));
  EXPECT_TRUE(has_text(chart, "-0.250"));
  EXPECT_TRUE(has_text(chart, "hex 7"));
  EXPECT_EQ(chart.rects[1].fill, to_rgba8(kInvertedColor));
}

// Chart E of a fold's vertex (the goblet's: three corners 0.999 and a
// reversed one at -0.999, plus 1 and -1 exactly), at its size in the views
// (480 x 420 with a title). Each text's box is about 0.6 size per character
// wide and size tall above its baseline (generous: the SVG's sans font is
// narrower). No value label overlaps a category label (47g review #7:
// "-0.999" on "quad 244"); every value label lies at least 6 px below the
// title's baseline (#12: the 0.999 labels crowded it); no grid line crosses
// a bar or a value label; the bars' colours have a key (the inverted colour
// on a rect that is no bar, beside "< 0: inverted").
TEST(CornerChart, ValueLabelsClearOfCategoriesTitleAndGrid) {
  const std::vector<double> values{0.999, 0.999, -0.999, 0.999, 1.0, -1.0};
  const std::vector<std::string> labels{"quad 233", "quad 243", "quad 244", "quad 245", "quad 1", "quad 2"};
  const Chart chart = corner_chart(values, labels, {480, 420, "goblet_fold: corners at vertex 476"});
  const auto box_of = [](const ChartText& t) {
    const double width = 0.6 * t.size * static_cast<double>(t.text.size());
    const double x = t.anchor == ChartAnchor::center ? t.at.x - 0.5 * width : t.at.x;
    return ChartRect{x, t.at.y - t.size, width, 1.25 * t.size, {}};
  };
  const auto overlap = [](const ChartRect& a, const ChartRect& b) {
    return a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height && b.y < a.y + a.height;
  };
  std::vector<ChartRect> value_boxes, category_boxes;
  double title_baseline = 0.0;
  for (const ChartText& t : chart.texts) {
    if (t.text == "goblet_fold: corners at vertex 476") title_baseline = t.at.y;
    if (std::find(labels.begin(), labels.end(), t.text) != labels.end()) category_boxes.push_back(box_of(t));
    for (double v : values) {
      char text[16];
      std::snprintf(text, sizeof text, "%.3f", v);
      if (t.text == text) {
        value_boxes.push_back(box_of(t));
        break;
      }
    }
  }
  ASSERT_EQ(value_boxes.size(), values.size());
  ASSERT_EQ(category_boxes.size(), labels.size());
  ASSERT_GT(title_baseline, 0.0);
  for (const ChartRect& v : value_boxes) {
    for (const ChartRect& c : category_boxes) EXPECT_FALSE(overlap(v, c)) << v.x << ", " << v.y;
    EXPECT_GE(v.y, title_baseline + 6.0);
  }
  const std::vector<ChartRect> bars(chart.rects.begin(), chart.rects.begin() + static_cast<std::ptrdiff_t>(values.size()));
  std::size_t grid = 0;
  for (const ChartPolyline& line : chart.lines) {
    if (line.points.size() != 2 || line.points[0].y != line.points[1].y) continue;
    if (line.points[0].y == chart.plot.y + chart.plot.height) continue;  // the x axis
    const double y = line.points[0].y, x0 = std::min(line.points[0].x, line.points[1].x),
                 x1 = std::max(line.points[0].x, line.points[1].x);
    if (line.color.r != line.color.g || line.color.r < 200) continue;  // the grid's pale grey only
    ++grid;
    for (const std::vector<ChartRect>* boxes : {&bars, static_cast<const std::vector<ChartRect>*>(&value_boxes)})
      for (const ChartRect& b : *boxes)
        EXPECT_FALSE(y > b.y && y < b.y + b.height && x0 < b.x + b.width && b.x < x1)
            << "grid line at y " << y << " across a box at (" << b.x << ", " << b.y << ")";
  }
  EXPECT_GT(grid, 0u);
  bool keyed = false;
  for (std::size_t i = values.size(); i < chart.rects.size(); ++i)
    keyed = keyed || chart.rects[i].fill == to_rgba8(kInvertedColor);
  EXPECT_TRUE(keyed);
  EXPECT_TRUE(has_text(chart, "< 0: inverted"));
}

TEST(SortedBoundaryError, BarsFromTheZeroLineOnASymmetricAxis) {
  const std::vector<double> e{0.3, -0.1, std::nan(""), 0.0, -0.45, 0.2};
  const Chart chart = sorted_boundary_error_chart(e, {800, 400, "t"});
  // 5 finite values, the exact zero has no bar.
  ASSERT_EQ(chart.rects.size(), 4u);
  for (const ChartRect& r : chart.rects) EXPECT_TRUE(inside(chart.plot, r));
  // Symmetric axis [-0.6, 0.6] (steps of 0.2 over max |error| 0.45): zero in the middle of the plot.
  EXPECT_TRUE(has_text(chart, "-0.6"));
  EXPECT_TRUE(has_text(chart, "0.6"));
  EXPECT_TRUE(has_text(chart, "0"));
  const double y0 = chart.plot.y + 0.5 * chart.plot.height;
  // Sorted ascending: the most inside (-0.45) first, below the zero line, in blue.
  EXPECT_NEAR(chart.rects[0].y, y0, 1e-9);
  EXPECT_NEAR(chart.rects[0].height, 0.45 / 1.2 * chart.plot.height, 1e-9);
  EXPECT_GT(chart.rects[0].fill.b, chart.rects[0].fill.r);
  // The most outside (0.3) last, above the zero line, in red.
  const ChartRect& last = chart.rects.back();
  EXPECT_NEAR(last.y + last.height, y0, 1e-9);
  EXPECT_NEAR(last.height, 0.3 / 1.2 * chart.plot.height, 1e-9);
  EXPECT_GT(last.fill.r, last.fill.b);
  for (std::size_t i = 1; i < chart.rects.size(); ++i) EXPECT_GT(chart.rects[i].x, chart.rects[i - 1].x);
  // The zero line spans the plot.
  EXPECT_TRUE(std::any_of(chart.lines.begin(), chart.lines.end(), [&](const ChartPolyline& l) {
    return l.points.size() == 2 && std::abs(l.points[0].y - y0) < 1e-9 && std::abs(l.points[1].y - y0) < 1e-9 &&
           std::abs(l.points[1].x - l.points[0].x - chart.plot.width) < 1e-9;
  }));
}

TEST(SortedBoundaryError, TheNoiseFloorIsAGreyBandAboutZero) {
  const std::vector<double> e{0.3, -0.1, 0.0, -0.45, 0.2};
  const Chart plain = sorted_boundary_error_chart(e, {800, 400, "t"}, {"samples", "% of diagonal"});
  const Chart chart = sorted_boundary_error_chart(e, {800, 400, "t"}, {"samples", "% of diagonal", 0.06});
  ASSERT_EQ(chart.rects.size(), plain.rects.size() + 1);
  // Axis [-0.6, 0.6]: the band spans the plot's width, +-0.06 about the zero line, over the bars.
  const ChartRect& band = chart.rects.back();
  const double y0 = chart.plot.y + 0.5 * chart.plot.height;
  EXPECT_NEAR(band.x, chart.plot.x, 1e-9);
  EXPECT_NEAR(band.width, chart.plot.width, 1e-9);
  EXPECT_NEAR(band.y, y0 - 0.06 / 1.2 * chart.plot.height, 1e-9);
  EXPECT_NEAR(band.height, 0.12 / 1.2 * chart.plot.height, 1e-9);
  EXPECT_LT(band.fill.a, 255) << "translucent: the bars show through";
  EXPECT_TRUE(has_text(chart, "grey band about 0: on the surface, |error| \u2264 0.06 % of diagonal"));
}

TEST(SortedBoundaryError, ManyVerticesOneBarPerPixelColumn) {
  std::vector<double> e;
  for (int i = 0; i < 100000; ++i) e.push_back((i % 2 ? 1.0 : -1.0) * 1e-3 * (i % 97));
  const Chart chart = sorted_boundary_error_chart(e, {600, 300, ""});
  EXPECT_LE(chart.rects.size(), static_cast<std::size_t>(chart.plot.width));
  EXPECT_GT(chart.rects.size(), static_cast<std::size_t>(chart.plot.width) - 5);
  // The extremes reach the axis limit 0.1 (nice ceiling of 0.096).
  EXPECT_TRUE(has_text(chart, "0.1"));
  EXPECT_NEAR(chart.rects.front().height, 0.5 * chart.plot.height * 0.096 / 0.1, 1e-6);
}

TEST(SortedBoundaryError, FewOutliersAreClippedAndCounted) {
  std::vector<double> e;
  for (int i = 0; i < 199; ++i) e.push_back((i % 2 ? 1e-5 : -1e-5) * (1 + i % 5));  // |e| <= 5e-5
  e.push_back(-0.036);
  const Chart chart = sorted_boundary_error_chart(e, {800, 400, ""});
  EXPECT_TRUE(has_text(chart, "6e-05"));  // the axis follows the bulk (steps of 2e-05), not the outlier
  EXPECT_TRUE(has_text(chart, "1 vertex beyond the axis (clipped), max |error| 0.036"));
  // The outlier's bar ends at the bottom of the plot.
  EXPECT_NEAR(chart.rects.front().y + chart.rects.front().height, chart.plot.y + chart.plot.height, 1e-9);
  const Chart area = boundary_area_chart(e, std::vector<double>(e.size(), 1.0), 1e-9, {800, 500, ""});
  EXPECT_TRUE(has_text(area, "5e-05"));
}

TEST(BoundaryArea, StackedBarAndCumulativeCurves) {
  // Areas: outside 1+2 = 3, on 1, inside 4; total 8.
  const std::vector<double> e{0.1, 0.2, 0.0, -0.3, std::nan("")};
  const std::vector<double> a{1.0, 2.0, 1.0, 4.0, 5.0};
  const Chart chart = boundary_area_chart(e, a, 1e-9, {800, 500, "t"});
  // Stacked bar: the first three rects, outside | on | inside, widths in proportion.
  ASSERT_GE(chart.rects.size(), 3u);
  const double w = chart.rects[0].width + chart.rects[1].width + chart.rects[2].width;
  EXPECT_NEAR(chart.rects[0].width / w, 3.0 / 8.0, 1e-9);
  EXPECT_NEAR(chart.rects[1].width / w, 1.0 / 8.0, 1e-9);
  EXPECT_NEAR(chart.rects[2].width / w, 4.0 / 8.0, 1e-9);
  EXPECT_LT(chart.rects[0].x, chart.rects[2].x);
  EXPECT_GT(chart.rects[0].fill.r, chart.rects[0].fill.b);  // outside red
  EXPECT_GT(chart.rects[2].fill.b, chart.rects[2].fill.r);  // inside blue
  EXPECT_LT(chart.rects[0].y + chart.rects[0].height, chart.plot.y) << "the bar is above the curve panel";
  EXPECT_TRUE(has_text(chart, "outside (37.5%)"));
  EXPECT_TRUE(has_text(chart, "inside (50.0%)"));
  // Every colour of the bar has a legend entry: the grey "on" one too, with its share and tolerance.
  EXPECT_TRUE(has_text(chart, "on the surface (12.5%), |error| \u2264 1e-09: bar only"));
  EXPECT_EQ(std::count_if(chart.rects.begin(), chart.rects.end(),
                          [&](const ChartRect& r) { return r.fill == chart.rects[1].fill; }),
            2)
      << "the grey segment and its legend swatch";
  // y axis up to 50% (nice ceiling), x axis up to 0.3.
  EXPECT_TRUE(has_text(chart, "50"));
  EXPECT_TRUE(has_text(chart, "0.3"));
  // Two curves, each ending at its fraction on the right edge.
  std::vector<const ChartPolyline*> curves;
  for (const ChartPolyline& l : chart.lines)
    if (l.width > 2.0) curves.push_back(&l);
  ASSERT_EQ(curves.size(), 2u);
  auto y_of = [&](double percent) { return chart.plot.y + chart.plot.height * (1.0 - percent / 50.0); };
  EXPECT_NEAR(curves[0]->points.back().y, y_of(37.5), 1e-9);
  EXPECT_NEAR(curves[0]->points.back().x, chart.plot.x + chart.plot.width, 1e-9);
  EXPECT_NEAR(curves[1]->points.back().y, y_of(50.0), 1e-9);
  EXPECT_NEAR(curves[0]->points.front().y, y_of(0.0), 1e-9);
  // The outside curve steps at 0.1 (x = a third of the axis) to 12.5%.
  EXPECT_NEAR(curves[0]->points[2].x, chart.plot.x + chart.plot.width / 3.0, 1e-9);
  EXPECT_NEAR(curves[0]->points[2].y, y_of(12.5), 1e-9);
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

TEST(MethodDistribution, OneDotPerValueAtItsHeightAndAMedianBar) {
  const std::vector<std::string> methods = {"a", "b"};
  const std::vector<std::vector<double>> values = {{0.5, -0.25, std::nan("")}, {1.0, 0.0, 0.5, 0.25}};
  const Chart chart = method_distribution_chart(methods, values, {600, 400, "t"});
  ASSERT_EQ(chart.rects.size(), 6u);  // NaN left out
  const ChartRect& plot = chart.plot;
  auto y_of = [&](double q) { return plot.y + plot.height * (1.0 - q) / 2.0; };
  // Column a: the dots' centres at y(-0.25) and y(0.5), the inverted one blue-violet.
  int inverted = 0;
  for (const ChartRect& r : chart.rects) {
    const double cx = r.x + r.width / 2, cy = r.y + r.height / 2;
    EXPECT_GT(cx, plot.x);
    EXPECT_LT(cx, plot.x + plot.width);
    const bool in_a = cx < plot.x + plot.width / 2;
    const std::vector<double>& mine = values[in_a ? 0 : 1];
    EXPECT_TRUE(std::any_of(mine.begin(), mine.end(), [&](double q) { return std::abs(y_of(q) - cy) < 1e-9; }));
    inverted += r.fill.r == to_rgba8(kInvertedColor).r && r.fill.b == to_rgba8(kInvertedColor).b;
  }
  EXPECT_EQ(inverted, 1);
  // Median bars: a at 0.125 (of -0.25 and 0.5), b at 0.375 (of 0, 0.25, 0.5, 1).
  std::vector<double> bars;
  for (const ChartPolyline& l : chart.lines)
    if (l.points.size() == 2 && l.width == 2.0) bars.push_back(l.points[0].y);
  ASSERT_EQ(bars.size(), 2u);
  EXPECT_NEAR(bars[0], y_of(0.125), 1e-9);
  EXPECT_NEAR(bars[1], y_of(0.375), 1e-9);
  // Each column names its method and count.
  auto has_text = [&](const std::string& t) {
    return std::any_of(chart.texts.begin(), chart.texts.end(), [&](const ChartText& x) { return x.text == t; });
  };
  EXPECT_TRUE(has_text("a") && has_text("b") && has_text("2 meshes") && has_text("4 meshes"));
}

// Bars coloured and sorted by agreement (-direction * rho), not by the sign
// of rho: from the zero line to rho on [-1, 1]; a size with no direction
// grey, below a separator, tagged; the interval as a whisker and in the
// numbers column; a NaN rho named under the chart, not drawn.
TEST(MetricCorrelation, BarsColouredAndSortedByAgreement) {
  const double nan = std::nan("");
  // condition (lower is better) rho +0.5: agrees 0.5; scaled_jacobian
  // (higher is better) rho -0.3: agrees 0.3; edge_ratio (lower) rho -0.6:
  // disagrees -0.6; volume (size) rho -0.8; c constant.
  const std::vector<CorrelationBar> bars = {
      {"scaled_jacobian", -0.3, -0.4, -0.2, nan, 0.3, false}, {"volume", -0.8, -0.85, -0.75, nan, nan, true},
      {"edge_ratio", -0.6, -0.7, -0.5, nan, -0.6, false},     {"c", nan, nan, nan, nan, nan, false},
      {"condition", 0.5, 0.4, 0.6, nan, 0.5, false}};
  const Chart chart = metric_correlation_chart(bars, {900, 300, "t"}, 100);
  const ChartRect& plot = chart.plot;
  const auto x_of = [&](double v) { return plot.x + plot.width * (v + 1.0) / 2.0; };
  std::vector<ChartRect> drawn;  // the bars: inside the plot, taller than a grid line is wide
  for (const ChartRect& r : chart.rects)
    if (inside(plot, r) && r.width > 1.0 && r.height < 20.0) drawn.push_back(r);
  ASSERT_EQ(drawn.size(), 4u);
  const double expected[] = {0.5, -0.3, -0.6, -0.8};  // condition, scaled_jacobian, edge_ratio, volume
  const Rgba8 colour[] = {kAgreesColor, kAgreesColor, kDisagreesColor, kNoDirectionColor};
  for (int k = 0; k < 4; ++k) {
    const ChartRect& bar = drawn[static_cast<std::size_t>(k)];
    EXPECT_NEAR(std::min(bar.x, bar.x + bar.width), std::min(x_of(0.0), x_of(expected[k])), 1e-9) << k;
    EXPECT_NEAR(std::max(bar.x, bar.x + bar.width), std::max(x_of(0.0), x_of(expected[k])), 1e-9) << k;
    EXPECT_EQ(bar.fill, colour[k]) << k;
    if (k > 0) {
      EXPECT_GT(bar.y, drawn[static_cast<std::size_t>(k - 1)].y);
    }
  }
  // A separator slot between the directed rows and the size: 2 rows apart.
  EXPECT_NEAR(drawn[3].y - drawn[2].y, 40.0, 1e-9);
  EXPECT_TRUE(has_text(chart, "volume (size)") && has_text(chart, "condition") && has_text(chart, "no better direction:"));
  EXPECT_TRUE(has_text(chart, "0.500 [0.40, 0.60]") && has_text(chart, "-0.800 [-0.85, -0.75]"));
  EXPECT_TRUE(has_text(chart, "no \u03c1 (constant on this mesh): c"));
  EXPECT_TRUE(has_text(chart, "Spearman \u03c1 over the 100 hexes, metric vs error density (as in the cells figure)"));
  // The whisker of condition's interval: a horizontal line from 0.4 to 0.6.
  bool whisker = false;
  for (const ChartPolyline& l : chart.lines)
    whisker = whisker || (l.points.size() == 2 && std::abs(l.points[0].x - x_of(0.4)) < 1e-9 &&
                          std::abs(l.points[1].x - x_of(0.6)) < 1e-9 && l.points[0].y == l.points[1].y);
  EXPECT_TRUE(whisker);
}

// An interval that includes 0 reads "undecided" (an open pale bar), whatever
// the sign; a bound under 0.005 keeps 3 decimals; the count line is on every
// chart, shape and size-weighted metrics apart; the "why is not tested" line
// only where most shape metrics disagree; the key defines relative_size_squared
// as Verdict does (a relative size, not shape times size).
TEST(MetricCorrelation, IntervalThroughZeroIsUndecided) {
  const double nan = std::nan("");
  // stretch (higher is better) rho +0.05 [-0.07, 0.15]: disagrees by sign, undecided;
  // edge_ratio (lower is better) rho -0.12 [-0.23, -0.004]: disagrees;
  // shape_and_size (size-weighted, higher is better) rho -0.4: agrees.
  const std::vector<CorrelationBar> bars = {{"stretch", 0.05, -0.07, 0.15, nan, -0.05, false},
                                            {"edge_ratio", -0.12, -0.23, -0.004, nan, -0.12, false},
                                            {"shape_and_size", -0.4, -0.5, -0.3, nan, 0.4, true}};
  const Chart chart = metric_correlation_chart(bars, {900, 300, "t"}, 500);
  std::vector<ChartRect> drawn;
  for (const ChartRect& r : chart.rects)
    if (inside(chart.plot, r) && r.width > 1.0 && r.height < 20.0) drawn.push_back(r);
  ASSERT_EQ(drawn.size(), 3u);  // shape_and_size (0.4), stretch (-0.05), edge_ratio (-0.12)
  EXPECT_EQ(drawn[0].fill, kAgreesColor);
  EXPECT_EQ(drawn[1].fill, kUndecidedColor);
  EXPECT_EQ(drawn[2].fill, kDisagreesColor);
  // The open bar's outline: a closed polyline on stretch's rectangle.
  bool outlined = false;
  for (const ChartPolyline& l : chart.lines)
    outlined = outlined || (l.points.size() == 5 && l.color == kUndecidedEdgeColor &&
                            std::abs(l.points[0].x - drawn[1].x) < 1e-9 && std::abs(l.points[0].y - drawn[1].y) < 1e-9);
  EXPECT_TRUE(outlined);
  EXPECT_TRUE(has_text(chart, "-0.120 [-0.23, -0.004]"));
  EXPECT_TRUE(has_text(chart, "shape_and_size (size-weighted)") && has_text(chart, "stretch"));
  EXPECT_TRUE(has_text(chart, "undecided: the interval includes 0 (open bar)"));
  EXPECT_TRUE(has_text(chart, "shape metrics (2): 0 agree, 1 disagree, 1 undecided; size-weighted (1): 1 agree, "
                              "0 disagree, 0 undecided"));
  const auto has_prefix = [](const Chart& c, const std::string& prefix) {
    return std::any_of(c.texts.begin(), c.texts.end(), [&](const ChartText& t) { return t.text.starts_with(prefix); });
  };
  EXPECT_FALSE(has_prefix(chart, "Most shape metrics disagree"));
  // The key says which interval the verdicts rest on: one 95 % interval, or
  // simultaneous over the verdict family (Bonferroni, 1 - 0.05/20 = 99.75 %).
  EXPECT_TRUE(has_prefix(chart, "95% interval (Fisher z"));
  const Chart simultaneous = metric_correlation_chart(bars, {900, 300, "t"}, 500, 20);
  EXPECT_TRUE(has_text(simultaneous, "interval: simultaneous 95% over the 20 metrics with a direction (Bonferroni: "
                                     "each at 99.75%;"));
  EXPECT_TRUE(has_text(simultaneous, "Fisher z, Bonett\u2013Wright SE); agree / disagree / undecided rest on it;"));
  EXPECT_TRUE(has_text(simultaneous, "\u03c1 [simultaneous 95%]"));
  // Two decided disagreements and one undecided among shape metrics: most disagree.
  const std::vector<CorrelationBar> most = {{"skew", -0.3, -0.35, -0.25, nan, -0.3, false},
                                            {"taper", -0.2, -0.25, -0.15, nan, -0.2, false},
                                            {"shape", 0.01, -0.05, 0.07, nan, -0.01, false}};
  const Chart other = metric_correlation_chart(most, {900, 300, "t"});
  EXPECT_TRUE(has_text(other, "shape metrics (3): 0 agree, 2 disagree, 1 undecided"));
  EXPECT_TRUE(has_prefix(other, "Most shape metrics disagree"));
  // Only the verdicts it shows: no "agrees" entry without a blue row.
  EXPECT_FALSE(has_prefix(other, "agrees:"));
  EXPECT_TRUE(has_prefix(other, "disagrees:"));
  EXPECT_TRUE(has_prefix(other, "why is not tested here"));
  EXPECT_FALSE(has_prefix(other, "a position or grading effect"));
  // The same with partials within 0.05 of rho: the hex size explains none of it.
  std::vector<CorrelationBar> sized = most;
  sized[0].rho_given_size = -0.28;
  sized[1].rho_given_size = -0.22;
  const Chart size_free = metric_correlation_chart(sized, {900, 300, "t"});
  EXPECT_TRUE(has_prefix(size_free, "\u03c1 hardly changes given the hex size h_e, so size does not explain it"));
  EXPECT_TRUE(has_prefix(size_free, "Most shape metrics disagree: here the hexes they call worse tend to have"));
  EXPECT_TRUE(has_text(chart, "  relative_size_squared = min(\u03c4, 1/\u03c4)\u00b2, \u03c4 = its mean corner "
                              "determinant / the mean hex volume;"));
  EXPECT_TRUE(has_text(chart, "  shape_and_size, shear_and_size = shape, shear times relative_size_squared"));
}

// Read on the drawn image: each bar's pixels are its legend swatch's pixels
// (the key names the colour the eye sees), and the two key colours differ.
TEST(MetricCorrelation, BarColourIsItsLegendSwatchOnTheImage) {
  const double nan = std::nan("");
  const std::vector<CorrelationBar> bars = {{"skew", 0.7, 0.6, 0.8, nan, 0.7, false},
                                            {"shape", 0.6, 0.5, 0.7, nan, -0.6, false},
                                            {"dimension", 0.5, 0.4, 0.6, nan, nan, true}};
  const Chart chart = metric_correlation_chart(bars, {900, 300, "t"});
  const Image image = chart_image(chart);
  ASSERT_EQ(image.width, chart.width);
  const auto swatch_of = [&](const std::string& prefix) {
    for (const ChartText& t : chart.texts)
      if (t.text.starts_with(prefix))
        return test::pixel_at(image, static_cast<int>(t.at.x) - 13, static_cast<int>(t.at.y) - 4);
    ADD_FAILURE() << "no key " << prefix;
    return Rgba8{};
  };
  const Rgba8 agrees = swatch_of("agrees:"), disagrees = swatch_of("disagrees:"), size = swatch_of("no better direction (a size)");
  EXPECT_NE(agrees, disagrees);
  EXPECT_NE(agrees, size);
  std::vector<ChartRect> drawn;
  for (const ChartRect& r : chart.rects)
    if (inside(chart.plot, r) && r.width > 1.0 && r.height < 20.0) drawn.push_back(r);
  ASSERT_EQ(drawn.size(), 3u);
  const Rgba8 expected[] = {agrees, disagrees, size};  // skew, shape (disagrees), dimension
  for (int k = 0; k < 3; ++k) {
    const ChartRect& bar = drawn[static_cast<std::size_t>(k)];
    // Between the bar's top and the whisker (at the row's middle), away from the caps.
    const Rgba8 pixel = test::pixel_at(image, static_cast<int>(bar.x + 0.5 * bar.width), static_cast<int>(bar.y + 2.5));
    EXPECT_EQ(pixel, expected[k]) << k;
  }
}

// Every hex with 0 < SJ <= 1 and a positive density lands in one cell of
// the grid (the counts add up, whatever the number of hexes), at its
// log-log position; the others are counted in the key.
TEST(ErrorDensityScatter, EveryHexCountedInALogLogGrid) {
  std::vector<double> sj, density;
  for (int i = 0; i < 20000; ++i) {
    const double t = (i % 1000 + 0.5) / 1000.0;
    sj.push_back(0.05 + 0.95 * t);
    density.push_back(1e-3 / sj.back());
  }
  sj.push_back(-0.5);  // inverted: in the strip at the left
  density.push_back(1.0);
  sj.push_back(0.5);  // no density: left out
  density.push_back(std::nan(""));
  const Chart chart = error_density_scatter_chart(sj, density, {900, 560, "t"});
  const ChartRect& plot = chart.plot;
  std::size_t cells = 0;
  for (const ChartRect& r : chart.rects)
    if (inside(plot, r)) ++cells;
  EXPECT_GT(cells, 50u);    // a curve of cells, not one dot
  EXPECT_LT(cells, 2000u);  // not one rectangle per hex
  bool key = false;
  for (const ChartText& t : chart.texts)
    key = key || (t.text.starts_with("hexes per 4-pixel cell: 1 to ") &&
                  t.text.ends_with("; 20001 hexes, 1 with SJ \u2264 0 in the strip at left, 1 left out (no density)"));
  EXPECT_TRUE(key);
  // The inverted hex: a cell in the labelled strip left of the log plot, at
  // the top (density 1, the y axis's top decade); the first version dropped it.
  EXPECT_TRUE(has_text(chart, "SJ \u2264 0"));
  bool in_strip = false;
  for (const ChartRect& r : chart.rects)
    in_strip = in_strip || (r.x + r.width < plot.x && r.height <= 4.0 && r.y < plot.y + 5.0 && r.fill.r < 200);
  EXPECT_TRUE(in_strip);
  // Decades: x from 0.01 to 1, y from 1e-3 to 0.1.
  EXPECT_TRUE(has_text(chart, "0.01") && has_text(chart, "1") && has_text(chart, "1e-3") && has_text(chart, "0.1"));
  // The cell of SJ 1, density 1e-3 (x at the right end, y at the bottom).
  bool corner = false;
  for (const ChartRect& r : chart.rects)
    corner = corner || (inside(plot, r) && r.x + r.width > plot.x + plot.width - 5 && r.y + r.height > plot.y + plot.height - 5);
  EXPECT_TRUE(corner);
  // The median curve falls (density ~ 1 / SJ).
  const ChartPolyline* median = nullptr;
  for (const ChartPolyline& l : chart.lines)
    if (l.points.size() > 2) median = &l;
  ASSERT_NE(median, nullptr);
  EXPECT_GT(median->points.back().y, median->points.front().y);  // y down: the right end lower
}

}  // namespace
}  // namespace hq

namespace hq {
namespace HQ_TEST_UNIT {

// The renumbering against std::regex (what it replaced) on tricky text:
// ids inside longer words, a word without digits, '-' without digits, ids
// at both ends, and repeats.
std::string renumber_by_regex(const std::string& svg) {
  const std::regex ids(R"((surface|glyph|clip|image|pattern|source|mask)(\d+)(-\d+)?)");
  std::map<std::string, int> renumbered;
  std::string out;
  std::size_t last = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), ids); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    const auto [entry, inserted] = renumbered.try_emplace(m[1].str() + m[2].str(), static_cast<int>(renumbered.size()));
    out.append(svg, last, static_cast<std::size_t>(m.position(0)) - last);
    out += m[1].str() + std::to_string(entry->second) + m[3].str();
    last = static_cast<std::size_t>(m.position(0) + m.length(0));
  }
  out.append(svg, last, std::string::npos);
  return out;
}

TEST(ChartSvg, RenumberingEqualsTheRegexOne) {
  const std::string tricky =
      "glyph7-3 <use xlink:href=\"#glyph7-3\"/> subsurface12 surface surface- surface9- clip40 mask2-x "
      "image3-45 pattern0 source11 glyph7-4 surface12 glyph7 gly7 masks3 clip40-1clip41";
  EXPECT_EQ(renumber_cairo_ids(tricky), renumber_by_regex(tricky));
  EXPECT_EQ(renumber_cairo_ids(""), "");
  EXPECT_EQ(renumber_cairo_ids("surface1"), "surface0");
  const std::vector<double> values{-0.2, 0.1, 0.5, 0.5, 0.9, 1.0};
  const std::string svg = chart_svg(quality_histogram_chart(values, false, {300, 200, "glyph12 surface3"}));
  EXPECT_NE(svg.find("glyph0"), std::string::npos);
  EXPECT_EQ(svg, renumber_by_regex(svg)) << "a chart's ids are already renumbered: a second pass changes nothing";
}

}  // namespace
}  // namespace hq
