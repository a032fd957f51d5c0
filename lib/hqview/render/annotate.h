#pragma once
// Annotations drawn onto rendered images: titles, text and colour bars, and
// the figure layout that keeps them clear of the 3D view. Text is rendered
// with FreeType in DejaVu Sans (package fonts-dejavu-core).
// Sizes are given for a 1200-pixel-high figure and scaled with the height.

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/image/color.h"
#include "hqview/image/image.h"

namespace hq {

inline constexpr const char* kDefaultFontPath = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// A rectangle in image pixels, (x, y) its top-left corner.
struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
};

struct AnnotationStyle {
  std::string font_path = kDefaultFontPath;
  Rgba8 text_color{38, 38, 38, 255};
  Rgba8 background{255, 255, 255, 255};
  double scale = 1.0;      // 1 for a 1200-pixel-high figure
  int min_text_size = 11;  // pixels: scaled text never gets smaller (legible thumbnails)
};

// The style for a figure of the given height (scale = height / 1200,
// clamped to [0.4, 4]).
AnnotationStyle annotation_style_for(int figure_height);

// A width x height image filled with one colour.
Image make_image(int width, int height, Rgba8 fill);
// Fills the part of rect inside the image.
void fill_rect(Image& image, const PixelRect& rect, Rgba8 color);
// Blends a straight line from (x0, y0) to (x1, y1) (pixel coordinates, the
// top-left corner of pixel (0, 0) at (0, 0)) of the given width in pixels,
// anti-aliased, clipped to the image (leader lines of moved labels).
void draw_line(Image& image, double x0, double y0, double x1, double y1, Rgba8 color, double width);
// Copies src into dst with its top-left corner at (x, y), clipped to dst.
void paste(Image& dst, const Image& src, int x, int y);

enum class TextAnchor { left, center, right };

// Draws one or more lines ('\n') of text, the first baseline at y, anchored
// at x. size_px is the font size in pixels (already scaled).
// Throws RenderError when the font cannot be loaded.
void draw_text(Image& image, int x, int y, std::string_view text, int size_px, const AnnotationStyle& style,
               TextAnchor anchor = TextAnchor::left);
// Width and height in pixels of text set at size_px.
// Throws RenderError when the font cannot be loaded.
PixelRect text_extent(std::string_view text, int size_px, const AnnotationStyle& style);

// The largest size in [min_size, size_px] at which text is at most max_width
// pixels wide (min_size when even that is too wide).
int fitting_text_size(std::string_view text, int size_px, int min_size, int max_width, const AnnotationStyle& style);
// text itself when it is at most max_width pixels wide at size_px, else its
// longest prefix (whole UTF-8 characters) followed by "..." that is.
std::string ellipsize(std::string_view text, int size_px, int max_width, const AnnotationStyle& style);

struct ColorBarTick {
  double value = 0.0;
  std::string label;
};

// A discrete legend entry drawn below the bar (e.g. "inverted").
// A swatch's mark, as the figure draws the thing it names (kSwatchMarks
// describes each; draw_swatch draws them for the colour bar and the swatch
// legend alike): box, a filled square (a colour of the data); solid_ring /
// dashed_ring, a ring as the figure's markers (the overview's inverted-cell
// rings, issue 45e: each ring style its own entry); line / thick_line /
// dashed_line / thick_dashed_line, a horizontal segment as the figure draws
// edges (1, 2.5, 1 and 2.5 times the line width, the dashed in 4 dashes); arrow, a thick segment
// with a head (view A's overlap arrows); text: no mark, the label alone (a
// count the figure names but does not draw).
enum class SwatchShape { box, solid_ring, dashed_ring, line, thick_line, dashed_line, thick_dashed_line, arrow, text };
// How a shape is drawn in a swatch box of height h: its kind of mark, its
// stroke width as a fraction of h (rings and segments), whether it is
// dashed (every other of 12 arcs, 4 of 7 segment pieces).
struct SwatchMark {
  enum class Kind { fill, ring, segment, none };
  SwatchShape shape;
  Kind kind;
  double width = 0.0;
  bool dashed = false;
  bool head = false;  // an arrowhead at the segment's right end
};
inline constexpr SwatchMark kSwatchMarks[] = {
    {SwatchShape::box, SwatchMark::Kind::fill},
    {SwatchShape::solid_ring, SwatchMark::Kind::ring, 0.18},
    {SwatchShape::dashed_ring, SwatchMark::Kind::ring, 0.18, true},
    {SwatchShape::line, SwatchMark::Kind::segment, 0.08},
    {SwatchShape::thick_line, SwatchMark::Kind::segment, 0.2},
    {SwatchShape::dashed_line, SwatchMark::Kind::segment, 0.08, true},
    {SwatchShape::thick_dashed_line, SwatchMark::Kind::segment, 0.2, true},
    {SwatchShape::arrow, SwatchMark::Kind::segment, 0.14, false, true},
    {SwatchShape::text, SwatchMark::Kind::none},
};
const SwatchMark& swatch_mark(SwatchShape shape);
// A line as a figure draws it, for a swatch that shows it exactly (issue
// 48r: a generic thick dashed swatch did not look like the max hex's edges):
// its core width, a halo under it (halo_width 0: none), and its dashes
// (dash 0: solid), all in pixels, dashed as dashed_pieces lays them out.
struct SwatchStroke {
  double width = 0, halo_width = 0;
  Rgba8 halo{255, 255, 255, 255};
  double dash = 0, gap = 0;
};
// The pieces [t0, t1] of a dashed line `length` pixels long: as many dashes
// of stroke.dash pixels as dash-and-gap periods fit, each centred in its
// period (the gaps stretched to fit, half a gap at each end, so the line's
// ends are open); shorter than one period: one dash over its middle 60 %;
// one piece (solid) when stroke.dash is 0. Not open_ends (a legend swatch,
// about two periods wide): the same dashes from end to end, the gaps
// stretched, solid when fewer than two fit.
std::vector<std::array<double, 2>> dashed_pieces(double length, const SwatchStroke& stroke, bool open_ends = true);
struct ColorBarSwatch {
  Color color;
  std::string label;
  SwatchShape shape = SwatchShape::box;
  std::optional<SwatchStroke> stroke = std::nullopt;  // set: drawn as this stroke (a line across the box), not as shape's mark
  // A ring swatch's band inside its ring (as LegendLine::ring_band: view C's
  // worst vertex is ringed in a yellow band in a dark ring).
  std::optional<Rgba8> ring_band = std::nullopt;
};

// A vertical colour bar legend: a title (lines separated by '\n'), the bar
// from min_value (bottom) to max_value (top) coloured by evenly spaced
// samples, tick labels on its right, then swatches below.
struct ColorBar {
  std::string label;
  double min_value = 0.0, max_value = 1.0;
  std::vector<Color> colors;  // >= 1 samples, colors.front() at min_value
  std::vector<ColorBarTick> ticks;
  std::vector<ColorBarSwatch> swatches;
  // > 0: the bar at most this many pixels high and the legend drawn from
  // its area's top, not centred (the overview: its whole legend above the
  // report page's fold, issue 45).
  int max_bar_height = 0;
};

// The legend for vertex quality: quality map on [0, 1] with ticks every
// 0.25, an "inverted (< 0)" swatch, labelled
// "vertex quality (min corner scaled Jacobian)".
ColorBar quality_color_bar();

// Width in pixels a colour bar legend needs, margins included.
int color_bar_width(const ColorBar& bar, const AnnotationStyle& style);
// The style draw_color_bar uses in area: style itself when the legend fits,
// else one with smaller scale (and smaller minimum text size, down to 7
// pixels) so that the legend's width and height fit area (small figures,
// e.g. --size 320x240, where the legend panel is capped at half the width).
AnnotationStyle color_bar_style_for(const ColorBar& bar, const AnnotationStyle& style, const PixelRect& area);
// Pixel height of the legend drawn in an area of the given height.
int color_bar_height(const ColorBar& bar, const AnnotationStyle& style, int area_height);
// The ticks of bar whose labels draw_color_bar writes on a bar of
// bar_height pixels (top row max_value), each label label_height pixels
// tall centred on its tick: the ends (the ticks at min_value and
// max_value) first, then the others in order, each left out when its label
// would overlap or touch (1 px) one kept (the 47j review: the turned
// plate's ">= 0.832" and "0.75" labels were 2 px apart). Indices into
// bar.ticks, ascending.
std::vector<std::size_t> legible_ticks(const ColorBar& bar, int bar_height, int label_height);
// Draws the legend vertically centred in area, shrunk to fit it
// (color_bar_style_for); the tick labels legible_ticks keeps.
void draw_color_bar(Image& image, const PixelRect& area, const ColorBar& bar, const AnnotationStyle& style);

// Where a figure's parts go: the title band on top (empty rect when there is
// no title), the legend panel on the right (empty when legend_width = 0),
// the 3D view in the rest.
struct FigureLayout {
  PixelRect title, legend, view;
};
FigureLayout figure_layout(int width, int height, bool has_title, int legend_width, const AnnotationStyle& style);

// Draws a title left-aligned and vertically centred in area; a title too
// long for the area's width is set smaller (down to 9 pixels), then cut
// with "...".
void draw_title(Image& image, const PixelRect& area, std::string_view title, const AnnotationStyle& style);

// A line of a swatch legend: a swatch (its shape as the figure draws the
// thing named, kSwatchMarks) and its text, or text alone (a heading or a
// note); gap_halves half lines of space before it.
struct LegendLine {
  std::optional<Rgba8> swatch;
  std::string text;
  int gap_halves = 0;
  SwatchShape shape = SwatchShape::box;
  // A ring swatch's band inside its ring (view A's #0: a yellow band in a
  // dark ring), as wide as the ring.
  std::optional<Rgba8> ring_band = std::nullopt;
};
// Draws shape's mark (kSwatchMarks) in color in box; a fill gets an
// outline of outline px in the outline grey when outline > 0.
void draw_swatch(Image& image, const PixelRect& box, const Rgba8& color, SwatchShape shape, int outline = 0);
// Draws the lines from the top of area: 34-pixel pitch, 18-pixel swatches and
// 19-pixel text at the style's scale, all shrunk together when the lines
// would not fit the area's height; text too long for the width ends in
// "...". Swatches are drawn opaque (draw_swatch): a ring swatch is a circle
// outline with the background inside, so it differs by shape from any
// filled swatch of a similar colour; a line swatch a horizontal line across
// the swatch's width.
void draw_legend(Image& image, const PixelRect& area, std::span<const LegendLine> lines, const AnnotationStyle& style);

}  // namespace hq
