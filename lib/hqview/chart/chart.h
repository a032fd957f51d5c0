#pragma once
// Charts: a pure description (rectangles, polylines, texts in pixel
// coordinates, y down) built by the chart builders below and tested without
// drawing, then drawn by Cairo into SVG (for the HTML page) or PNG (for
// Markdown) from the one drawing routine draw_chart().

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "hqview/image/color.h"
#include "hqview/image/image.h"

namespace hq {

struct ChartPoint {
  double x = 0.0, y = 0.0;
};

struct ChartRect {
  double x = 0.0, y = 0.0, width = 0.0, height = 0.0;
  Rgba8 fill;
};

struct ChartPolyline {
  std::vector<ChartPoint> points;
  Rgba8 color;
  double width = 1.0;
};

// A clickable region of a chart (chart B: a bar's column), standing for
// `key` (chart B: the bar's vertex id). Pixel coordinates like the rects.
struct ChartHotspot {
  ChartRect rect;
  std::int32_t key = -1;
};

enum class ChartAnchor { left, center, right };

struct ChartText {
  ChartPoint at;  // the baseline's anchor point
  std::string text;
  double size = 12.0;
  Rgba8 color{38, 38, 38, 255};
  ChartAnchor anchor = ChartAnchor::left;
  bool is_vertical = false;  // rotated 90 degrees counterclockwise (y axis titles)
};

// Drawn in this order: rects, lines, texts.
struct Chart {
  int width = 800, height = 500;
  Rgba8 background{255, 255, 255, 255};
  ChartRect plot;  // the plot area (axes frame), for tests and overlays
  std::vector<ChartRect> rects;
  std::vector<ChartPolyline> lines;
  std::vector<ChartText> texts;
  std::vector<ChartHotspot> hotspots;  // not drawn: for links over the image
};

struct ChartOptions {
  int width = 800, height = 500;
  std::string title;
};

// The histogram's axis titles: the x axis, and the cells counted (plural:
// the y axis, " (log scale)" added on a log chart).
struct HistogramAxes {
  std::string x_label = "scaled Jacobian (per hex)";
  std::string cells = "hexes";
};

// Histogram of per-cell scaled Jacobian: bins of width bin_width on [-1, 1],
// bars coloured by the quality map at the bin's centre (inverted bins in
// kInvertedColor); values >= 1e30 (degenerate) and NaN are left out. With
// log_scale the bar heights are log10(1 + count).
Chart quality_histogram_chart(std::span<const double> values, bool log_scale, const ChartOptions& options,
                              double bin_width = 0.05, const HistogramAxes& axes = {});

// Chart B, sorted vertex quality: the worst_n lowest values as bars (worst
// on the left, coloured by quality), and the whole ascending distribution as
// a curve over [0, 1] of the vertex rank on a second panel. NaN left out.
// Ties are ranked by vertex id; hotspots: one per bar (its whole column in
// the plot), key = the bar's vertex id.
Chart sorted_quality_chart(std::span<const double> vertex_quality, int worst_n, const ChartOptions& options);

// Chart E: the values of the corners at one vertex as bars, each labelled
// with its value (labels[i] under bar i).
Chart corner_chart(std::span<const double> values, std::span<const std::string> labels, const ChartOptions& options);

// With --reference: the signed error of every hex boundary vertex, sorted
// ascending (most inside on the left, most outside on the right), as bars
// from the zero line coloured by the diverging error map, on a y axis
// symmetric about 0 ([-A, A], A a nice ceiling of max |error|); the x axis is
// the fraction of boundary vertices. More vertices than plot pixels are drawn
// as one bar per pixel column (the extreme value of its ranks). NaN left out.
// labels.items names what is sorted (the x axis), labels.unit the values'
// unit (both axis titles say it when not empty).
struct ErrorChartLabels {
  std::string items = "boundary vertices";
  std::string unit;  // e.g. "% of diagonal"
  // Sorted chart: when > 0, |error| at or below it (the noise floor, in the
  // values' unit) is "on the surface": a translucent grey band about 0 over
  // the bars, edged by grey lines at +-on_band and named in a note.
  double on_band = 0;
  // Area chart: what the weights measure ("length" for a planar mesh's boundary polylines).
  std::string measure = "area";
  // Both charts' name for |error| within the noise floor.
  std::string on_word = "on the surface";
};
// weights, when not empty (one per value): the x axis is the fraction of
// their sum (e.g. of the boundary length), not of the count; each pixel
// column the extreme value of the ranks whose weight it covers.
Chart sorted_boundary_error_chart(std::span<const double> vertex_error, const ChartOptions& options,
                                  const ErrorChartLabels& labels = {}, std::span<const double> weights = {});

// With --reference: the boundary area outside / on / inside the reference as
// one stacked horizontal bar of percentages (top strip), and below it the
// cumulative area fraction (percent of the whole boundary area) against
// |error|, one curve for the outside part (ending at fraction_outside) and one
// for the inside part. error and area per vertex (NaN error or area <= 0 left
// out); tolerance: |error| at or below it is "on" the reference. The legend
// names all three colours of the bar: outside and inside (their curves) and
// the grey "on the surface" with its tolerance (no curve).
Chart boundary_area_chart(std::span<const double> vertex_error, std::span<const double> vertex_area, double tolerance,
                          const ChartOptions& options, const ErrorChartLabels& labels = {});

// Methods compared over a dataset: one column per method, one dot per mesh
// at its min scaled Jacobian (coloured by the quality map, inverted ones in
// kInvertedColor), a dark bar at the column's median; y on [-1, 1]; the
// method's name and its number of values under its column. values[i] holds
// method i's values (NaN left out).
Chart method_distribution_chart(std::span<const std::string> methods, std::span<const std::vector<double>> values,
                                const ChartOptions& options);

// --simulate: Spearman's rho over the hexes between the normalised error
// density and each metric (fem.poisson.correlation), one horizontal bar per
// metric from 0 to rho on [-1, 1], coloured by agreement (not by the sign):
// the metric-direction normalisation agreement = -direction * rho
// (metric_agreement, fem/metric_correlation.h) > 0 is blue ("agrees: the
// metric's worse side has the higher error"), < 0 orange ("disagrees"), and
// a metric with no better direction grey; a directed metric whose interval
// includes 0 (correlation_undecided) an open pale bar, "undecided", whatever
// its sign. Rows: the metrics with a direction
// by agreement, strongest agreement on top (strongest disagreement at the
// bottom of that group), then the ones without a direction by |rho|, under a
// separator line. A size metric (metric_is_size) gets " (size)" without a
// direction, " (size-weighted)" with one. Each row: a black whisker on a white
// casing for its interval (lo, hi; none where NaN): simultaneous 95 % over
// the `verdict_family` directed metrics (Bonferroni, each at 1 - 0.05 / m;
// the verdicts rest on it, the key says so; verdict_family <= 1: one 95 %
// interval), an open diamond at
// the partial rho given the hex size (none where NaN), and in a column right
// of the plot "rho [lo, hi]" (bounds to 2 decimals, 3 under 0.005) and the
// partial. Under the key, on every chart, the count line: agree / disagree /
// undecided of the shape metrics and of the size-weighted ones apart, and
// when most shape metrics disagree a line saying that the chart does not test
// why (the partial rho shows what the hex size explains). Metrics whose rho
// is NaN (constant on the mesh) are named under the chart; the key names
// every colour and mark. count > 0: the number of hexes, in the axis title.
struct CorrelationBar {
  std::string metric;
  double rho = 0;
  double lo = 0, hi = 0;     // its interval (simultaneous over the verdict family); NaN: none
  double rho_given_size = 0;  // NaN: none
  double agreement = 0;       // -direction * rho; NaN: no better direction
  bool is_size = false;
};
inline constexpr Rgba8 kAgreesColor{49, 104, 170, 255};
inline constexpr Rgba8 kDisagreesColor{205, 96, 40, 255};
inline constexpr Rgba8 kNoDirectionColor{150, 150, 156, 255};
// A directed metric whose 95 % interval includes 0: an open (outlined) pale bar.
inline constexpr Rgba8 kUndecidedColor{236, 234, 228, 255};
inline constexpr Rgba8 kUndecidedEdgeColor{96, 96, 104, 255};
// Whether a bar's interval includes 0 (lo <= 0 <= hi): its sign is undecided.
// False without an interval.
inline bool correlation_undecided(const CorrelationBar& bar) { return bar.lo <= 0 && bar.hi >= 0; }
Chart metric_correlation_chart(std::span<const CorrelationBar> bars, const ChartOptions& options,
                               std::int64_t count = 0, int verdict_family = 0);

// --simulate: per hex the normalised error density against the scaled
// Jacobian, both on log axes (whole decades; x up to 1). Every hex with
// 0 < SJ <= 1 and a positive density is counted into a grid of 4-pixel
// cells shaded by log count (so a mesh of millions of hexes draws the same
// few thousand rectangles, the same for any thread count), with the median
// density of 16 log-SJ bins as a curve. Hexes with SJ <= 0 (inverted
// corners; a log axis has no place for them) are counted by density into a
// pale violet strip at the left labelled "SJ <= 0" with their number
// ("none" when there are none); hexes without a density are counted in the key.
Chart error_density_scatter_chart(std::span<const double> scaled_jacobian, std::span<const double> error_density,
                                  const ChartOptions& options);

// The chart as an SVG document / as a PNG-ready image (both from draw_chart).
// Throws RenderError when Cairo fails.
std::string chart_svg(const Chart& chart);

// Cairo's SVG ids (surface|glyph|clip|image|pattern|source|mask followed by
// digits, optionally '-' and digits) renumbered from 0 in order of first
// appearance of word and number: chart_svg's last step.
std::string renumber_cairo_ids(const std::string& svg);
Image chart_image(const Chart& chart);

}  // namespace hq
