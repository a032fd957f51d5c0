#include "hqview/render/annotate.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "hqview/core/error.h"
#include "hqview/core/text.h"
#include "hqview/image/colormap.h"

namespace hq {
namespace {

// Sizes at scale 1 (a 1200-pixel-high figure), in pixels.
constexpr double kTitleSize = 34.0;
constexpr double kTitleBand = 78.0;
constexpr double kTitleInset = 36.0;
constexpr double kLegendLabelSize = 21.0;
constexpr double kTickLabelSize = 20.0;
constexpr double kLineSpacing = 1.3;  // baseline to baseline, in font sizes
constexpr double kLegendInset = 20.0;
constexpr double kLegendRightMargin = 36.0;
constexpr double kBarWidth = 34.0;
constexpr double kBarMaxHeight = 560.0;
constexpr double kTickLength = 7.0;
constexpr double kTickGap = 7.0;
constexpr double kLabelGap = 22.0;
constexpr double kSwatchGap = 26.0;
constexpr double kSwatchHeight = 26.0;
constexpr double kSwatchPitch = 38.0;

const Rgba8 kOutlineColor{96, 96, 96, 255};

int scaled(double size, const AnnotationStyle& style) {
  return std::max(1, static_cast<int>(std::lround(size * style.scale)));
}

// Text stays legible in thumbnails: never below style.min_text_size pixels.
int scaled_text(double size, const AnnotationStyle& style) {
  return std::max(style.min_text_size, scaled(size, style));
}

std::vector<std::string_view> split_lines(std::string_view text) { return split(text, '\n'); }

void outline_rect(Image& image, const PixelRect& r, int thickness, Rgba8 color) {
  fill_rect(image, {r.x - thickness, r.y - thickness, r.width + 2 * thickness, thickness}, color);
  fill_rect(image, {r.x - thickness, r.y + r.height, r.width + 2 * thickness, thickness}, color);
  fill_rect(image, {r.x - thickness, r.y, thickness, r.height}, color);
  fill_rect(image, {r.x + r.width, r.y, thickness, r.height}, color);
}

Color lerp(const Color& p, const Color& q, float f) {
  return {p.r + (q.r - p.r) * f, p.g + (q.g - p.g) * f, p.b + (q.b - p.b) * f, p.a + (q.a - p.a) * f};
}

// Colour of the bar at fraction u in [0, 1] from its bottom.
Color bar_color(const ColorBar& bar, double u) {
  if (bar.colors.empty()) return kUndefinedColor;
  if (bar.colors.size() == 1) return bar.colors.front();
  const double x = std::clamp(u, 0.0, 1.0) * static_cast<double>(bar.colors.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), bar.colors.size() - 2);
  return lerp(bar.colors[i], bar.colors[i + 1], static_cast<float>(x - static_cast<double>(i)));
}

struct LegendMetrics {
  int label_size, tick_size, line_height, bar_width, bar_height, tick_length, tick_gap, label_gap, swatch_gap,
      swatch_height, swatch_pitch, inset;
};

LegendMetrics legend_metrics(const AnnotationStyle& style, int available_height) {
  LegendMetrics m{};
  m.label_size = scaled_text(kLegendLabelSize, style);
  m.tick_size = scaled_text(kTickLabelSize, style);
  m.line_height = static_cast<int>(std::lround(m.label_size * kLineSpacing));
  m.bar_width = scaled(kBarWidth, style);
  m.bar_height = std::max(1, std::min(scaled(kBarMaxHeight, style), available_height * 11 / 20));
  m.tick_length = scaled(kTickLength, style);
  m.tick_gap = scaled(kTickGap, style);
  m.label_gap = scaled(kLabelGap, style);
  m.swatch_gap = scaled(kSwatchGap, style);
  m.swatch_height = scaled(kSwatchHeight, style);
  m.swatch_pitch = scaled(kSwatchPitch, style);
  m.inset = scaled(kLegendInset, style);
  return m;
}

}  // namespace

AnnotationStyle annotation_style_for(int figure_height) {
  AnnotationStyle style;
  style.scale = std::clamp(static_cast<double>(figure_height) / 1200.0, 0.4, 4.0);
  return style;
}

Image make_image(int width, int height, Rgba8 fill) {
  Image image{std::max(0, width), std::max(0, height), {}};
  image.rgba.resize(4 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    image.rgba[i] = fill.r;
    image.rgba[i + 1] = fill.g;
    image.rgba[i + 2] = fill.b;
    image.rgba[i + 3] = fill.a;
  }
  return image;
}

void fill_rect(Image& image, const PixelRect& rect, Rgba8 color) {
  const int x0 = std::max(rect.x, 0), x1 = std::min(rect.x + rect.width, image.width);
  const int y0 = std::max(rect.y, 0), y1 = std::min(rect.y + rect.height, image.height);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      std::uint8_t* p = image.rgba.data() + pixel_offset(image, x, y);
      p[0] = color.r;
      p[1] = color.g;
      p[2] = color.b;
      p[3] = color.a;
    }
}

void paste(Image& dst, const Image& src, int x, int y) {
  const int x0 = std::max(x, 0), x1 = std::min(x + src.width, dst.width);
  if (x1 <= x0) return;
  const std::size_t row_bytes = 4 * static_cast<std::size_t>(x1 - x0);
  for (int row = std::max(y, 0); row < std::min(y + src.height, dst.height); ++row)
    std::memcpy(dst.rgba.data() + pixel_offset(dst, x0, row), src.rgba.data() + pixel_offset(src, x0 - x, row - y),
                row_bytes);
}

void draw_text(Image& image, int x, int y, std::string_view text, int size_px, const AnnotationStyle& style,
               TextAnchor anchor) {
  if (image.width <= 0 || image.height <= 0 || text.empty()) return;
  OIIO::ImageBuf buffer(OIIO::ImageSpec(image.width, image.height, 4, OIIO::TypeDesc::UINT8), image.rgba.data());
  const Color c = to_color(style.text_color);
  const float color[4] = {c.r, c.g, c.b, c.a};
  const auto align = anchor == TextAnchor::left     ? OIIO::ImageBufAlgo::TextAlignX::Left
                     : anchor == TextAnchor::center ? OIIO::ImageBufAlgo::TextAlignX::Center
                                                    : OIIO::ImageBufAlgo::TextAlignX::Right;
  const int line_height = static_cast<int>(std::lround(size_px * kLineSpacing));
  int baseline = y;
  for (std::string_view line : split_lines(text)) {
    if (!line.empty() && !OIIO::ImageBufAlgo::render_text(buffer, x, baseline, line, size_px, style.font_path, color,
                                                          align, OIIO::ImageBufAlgo::TextAlignY::Baseline, 0, {}, 1))
      throw RenderError("cannot draw text with font '" + style.font_path +
                        "' (install fonts-dejavu-core): " + buffer.geterror());
    baseline += line_height;
  }
}

PixelRect text_extent(std::string_view text, int size_px, const AnnotationStyle& style) {
  int width = 0, height = 0;
  const std::vector<std::string_view> lines = split_lines(text);
  for (std::string_view line : lines) {
    if (line.empty()) continue;
    const OIIO::ROI roi = OIIO::ImageBufAlgo::text_size(line, size_px, style.font_path);
    if (!roi.defined()) throw RenderError("cannot load font '" + style.font_path + "' (install fonts-dejavu-core)");
    width = std::max(width, roi.width());
    height = std::max(height, roi.height());
  }
  if (lines.size() > 1)
    height += static_cast<int>(std::lround(size_px * kLineSpacing)) * static_cast<int>(lines.size() - 1);
  return {0, 0, width, height};
}

ColorBar quality_color_bar() {
  ColorBar bar;
  bar.label = "vertex quality\n(min corner scaled Jacobian)";
  bar.min_value = 0.0;
  bar.max_value = 1.0;
  constexpr int kSamples = 256;
  for (int i = 0; i < kSamples; ++i) bar.colors.push_back(sample_quality_map(i / double(kSamples - 1)));
  bar.ticks = {{0.0, "0"}, {0.25, "0.25"}, {0.5, "0.5"}, {0.75, "0.75"}, {1.0, "1"}};
  bar.swatches = {{kInvertedColor, "inverted (< 0)"}};
  return bar;
}

int fitting_text_size(std::string_view text, int size_px, int min_size, int max_width, const AnnotationStyle& style) {
  int size = std::max(size_px, min_size);
  while (size > min_size) {
    const int width = text_extent(text, size, style).width;
    if (width <= max_width) break;
    // Text width is about proportional to the size: jump close, then step.
    size = std::clamp(static_cast<int>(std::floor(size * static_cast<double>(max_width) / width)), min_size, size - 1);
  }
  return size;
}

std::string ellipsize(std::string_view text, int size_px, int max_width, const AnnotationStyle& style) {
  if (text_extent(text, size_px, style).width <= max_width) return std::string(text);
  // Longest prefix, by bisection over character boundaries (not inside a
  // UTF-8 sequence: continuation bytes are 10xxxxxx).
  std::vector<std::size_t> cuts;
  for (std::size_t i = 0; i < text.size(); ++i)
    if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) cuts.push_back(i);
  // The prefix of k characters is text[0, cuts[k]), k < cuts.size().
  auto shortened = [&](std::size_t k) {
    std::string_view prefix = text.substr(0, cuts[k]);
    while (!prefix.empty() && prefix.back() == ' ') prefix.remove_suffix(1);
    return std::string(prefix) + "...";
  };
  std::size_t lo = 0, hi = cuts.empty() ? 0 : cuts.size() - 1;
  while (lo < hi) {
    const std::size_t mid = (lo + hi + 1) / 2;
    if (text_extent(shortened(mid), size_px, style).width <= max_width)
      lo = mid;
    else
      hi = mid - 1;
  }
  return cuts.empty() ? std::string("...") : shortened(lo);
}

int color_bar_width(const ColorBar& bar, const AnnotationStyle& style) {
  const LegendMetrics m = legend_metrics(style, 0);
  int content = text_extent(bar.label, m.label_size, style).width;
  int tick_labels = 0;
  for (const ColorBarTick& tick : bar.ticks)
    tick_labels = std::max(tick_labels, text_extent(tick.label, m.tick_size, style).width);
  content = std::max(content, m.bar_width + m.tick_length + m.tick_gap + tick_labels);
  for (const ColorBarSwatch& swatch : bar.swatches)
    content = std::max(content,
                       m.bar_width + m.tick_gap + m.tick_length + text_extent(swatch.label, m.tick_size, style).width);
  return m.inset + content + scaled(kLegendRightMargin, style);
}

int color_bar_height(const ColorBar& bar, const AnnotationStyle& style, int area_height) {
  const LegendMetrics m = legend_metrics(style, area_height);
  const int label_lines = bar.label.empty() ? 0 : static_cast<int>(split_lines(bar.label).size());
  const int swatch_block =
      bar.swatches.empty() ? 0 : m.swatch_gap + static_cast<int>(bar.swatches.size()) * m.swatch_pitch;
  return label_lines * m.line_height + (label_lines ? m.label_gap : 0) + m.bar_height + swatch_block;
}

AnnotationStyle color_bar_style_for(const ColorBar& bar, const AnnotationStyle& style, const PixelRect& area) {
  AnnotationStyle fitted = style;
  for (int step = 0; step < 12; ++step) {
    if (color_bar_width(bar, fitted) <= area.width && color_bar_height(bar, fitted, area.height) <= area.height) break;
    fitted.scale *= 0.9;
    fitted.min_text_size = std::max(7, fitted.min_text_size - 1);
  }
  return fitted;
}

void draw_color_bar(Image& image, const PixelRect& area, const ColorBar& bar, const AnnotationStyle& given_style) {
  const AnnotationStyle style = color_bar_style_for(bar, given_style, area);
  const LegendMetrics m = legend_metrics(style, area.height);
  const int label_lines = bar.label.empty() ? 0 : static_cast<int>(split_lines(bar.label).size());
  const int label_block = label_lines * m.line_height;
  const int total = color_bar_height(bar, style, area.height);
  const int top = area.y + std::max(0, (area.height - total) / 2);
  const int x = area.x + m.inset;
  const int outline = std::max(1, scaled(1.0, style));

  if (label_lines) draw_text(image, x, top + m.label_size, bar.label, m.label_size, style);

  const PixelRect bar_rect{x, top + label_block + (label_lines ? m.label_gap : 0), m.bar_width, m.bar_height};
  for (int row = 0; row < bar_rect.height; ++row) {
    // Top row exactly max_value, bottom row exactly min_value.
    const double u = bar_rect.height > 1 ? 1.0 - static_cast<double>(row) / (bar_rect.height - 1) : 0.5;
    fill_rect(image, {bar_rect.x, bar_rect.y + row, bar_rect.width, 1}, to_rgba8(bar_color(bar, u)));
  }
  outline_rect(image, bar_rect, outline, kOutlineColor);

  const double range = bar.max_value - bar.min_value;
  const int tick_x = bar_rect.x + bar_rect.width + outline;
  // Tick labels centred on their tick: the baseline sits about 0.36 em
  // below it for DejaVu Sans digits (cap height 0.73 em).
  const int baseline_shift = static_cast<int>(std::lround(0.36 * m.tick_size));
  for (const ColorBarTick& tick : bar.ticks) {
    const double u = range != 0.0 ? (tick.value - bar.min_value) / range : 0.0;
    if (!(u >= 0.0 && u <= 1.0)) continue;
    const int y = bar_rect.y + static_cast<int>(std::lround((1.0 - u) * (bar_rect.height - 1)));
    fill_rect(image, {tick_x, y - outline / 2, m.tick_length, outline}, kOutlineColor);
    draw_text(image, tick_x + m.tick_length + m.tick_gap, y + baseline_shift, tick.label, m.tick_size, style);
  }

  int swatch_y = bar_rect.y + bar_rect.height + outline + m.swatch_gap;
  for (const ColorBarSwatch& swatch : bar.swatches) {
    const PixelRect box{x, swatch_y, m.bar_width, m.swatch_height};
    fill_rect(image, box, to_rgba8(swatch.color));
    outline_rect(image, box, outline, kOutlineColor);
    draw_text(image, tick_x + m.tick_length + m.tick_gap, swatch_y + m.swatch_height / 2 + baseline_shift, swatch.label,
              m.tick_size, style);
    swatch_y += m.swatch_pitch;
  }
}

FigureLayout figure_layout(int width, int height, bool has_title, int legend_width, const AnnotationStyle& style) {
  FigureLayout layout;
  const int title_height = has_title ? std::min(scaled(kTitleBand, style), height / 4) : 0;
  const int legend = std::clamp(legend_width, 0, width / 2);
  if (has_title) layout.title = {0, 0, width, title_height};
  if (legend > 0) layout.legend = {width - legend, title_height, legend, height - title_height};
  layout.view = {0, title_height, width - legend, height - title_height};
  return layout;
}

void draw_title(Image& image, const PixelRect& area, std::string_view title, const AnnotationStyle& style) {
  if (title.empty() || area.height <= 0) return;
  const int inset = scaled(kTitleInset, style);
  const int max_width = std::max(1, area.width - 2 * inset);
  const int size = fitting_text_size(title, std::max(14, scaled(kTitleSize, style)), 9, max_width, style);
  // Baseline so that the cap height (0.73 em) is centred in the band.
  const int baseline = area.y + area.height / 2 + static_cast<int>(std::lround(0.365 * size));
  draw_text(image, area.x + inset, baseline, ellipsize(title, size, max_width, style), size, style);
}

void draw_legend(Image& image, const PixelRect& area, std::span<const LegendLine> lines, const AnnotationStyle& style) {
  double height_in_lines = 0.0;
  for (const LegendLine& line : lines) height_in_lines += 1.0 + 0.5 * line.gap_halves;
  const int top = static_cast<int>(std::lround(40 * style.scale));
  const double fit = std::min(1.0, (area.height - top) / (std::max(1.0, height_in_lines) * 34 * style.scale));
  const int pitch = std::max(1, static_cast<int>(std::lround(34 * style.scale * fit)));
  const int swatch = std::max(1, static_cast<int>(std::lround(18 * style.scale * fit)));
  const int text_size =
      std::max(fit < 1.0 ? 7 : 10, std::min(static_cast<int>(std::lround(19 * style.scale)), pitch * 3 / 4));
  const int x = area.x + static_cast<int>(std::lround(16 * style.scale));
  const int right = area.x + area.width - static_cast<int>(std::lround(8 * style.scale));
  int y = area.y + top;
  for (const LegendLine& line : lines) {
    y += pitch * line.gap_halves / 2;
    if (y > area.y + area.height) return;
    if (line.swatch) {
      Rgba8 color = *line.swatch;
      color.a = 255;
      fill_rect(image, {x, y - swatch, swatch, swatch}, color);
      const int text_x = x + swatch + swatch / 2;
      draw_text(image, text_x, y - 2, ellipsize(line.text, text_size, right - text_x, style), text_size, style);
    } else {
      draw_text(image, x, y, ellipsize(line.text, text_size, right - x, style), text_size, style);
    }
    y += pitch;
  }
}

}  // namespace hq
