#include "hqview/render/annotate.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>

#include "hqview/core/error.h"
#include "hqview/core/message_text.h"
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

// A colour bar's: its max_bar_height caps the bar.
LegendMetrics legend_metrics(const ColorBar& bar, const AnnotationStyle& style, int available_height) {
  LegendMetrics m = legend_metrics(style, available_height);
  if (bar.max_bar_height > 0) m.bar_height = std::max(1, std::min(m.bar_height, bar.max_bar_height));
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

void draw_line(Image& image, double x0, double y0, double x1, double y1, Rgba8 color, double width) {
  const double half = 0.5 * std::max(width, 0.5);
  const int left = std::max(0, static_cast<int>(std::floor(std::min(x0, x1) - half - 1)));
  const int right = std::min(image.width - 1, static_cast<int>(std::ceil(std::max(x0, x1) + half + 1)));
  const int top = std::max(0, static_cast<int>(std::floor(std::min(y0, y1) - half - 1)));
  const int bottom = std::min(image.height - 1, static_cast<int>(std::ceil(std::max(y0, y1) + half + 1)));
  const double dx = x1 - x0, dy = y1 - y0, length2 = dx * dx + dy * dy;
  for (int y = top; y <= bottom; ++y)
    for (int x = left; x <= right; ++x) {
      // Distance from the pixel centre to the segment; coverage falls off
      // over one pixel at the line's edge.
      const double px = x + 0.5 - x0, py = y + 0.5 - y0;
      const double t = length2 > 0.0 ? std::clamp((px * dx + py * dy) / length2, 0.0, 1.0) : 0.0;
      const double distance = std::hypot(px - t * dx, py - t * dy);
      const double coverage = std::clamp(half + 0.5 - distance, 0.0, 1.0) * (color.a / 255.0);
      if (coverage <= 0.0) continue;
      std::uint8_t* p = image.rgba.data() + pixel_offset(image, x, y);
      const std::uint8_t channels[3] = {color.r, color.g, color.b};
      for (int c = 0; c < 3; ++c) p[c] = static_cast<std::uint8_t>(std::lround(p[c] + (channels[c] - p[c]) * coverage));
    }
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

namespace {

// FreeType, one library and one face per font file for the process, behind
// one lock (faces are not thread-safe; text is a sliver of a view's time).
class Fonts {
 public:
  ~Fonts() {
    for (auto& [path, face] : faces_) FT_Done_Face(face);
    if (library_ != nullptr) FT_Done_FreeType(library_);
  }
  std::mutex mutex;
  // The face of `path` at `size_px`; throws RenderError when it cannot be loaded.
  FT_Face face(const std::string& path, int size_px) {
    if (library_ == nullptr && FT_Init_FreeType(&library_) != 0) throw RenderError("cannot start FreeType");
    auto it = faces_.find(path);
    if (it == faces_.end()) {
      FT_Face f = nullptr;
      if (FT_New_Face(library_, path.c_str(), 0, &f) != 0)
        throw RenderError("cannot load font '" + path + "' (install fonts-dejavu-core)");
      it = faces_.emplace(path, f).first;
    }
    if (FT_Set_Pixel_Sizes(it->second, 0, static_cast<FT_UInt>(std::max(size_px, 1))) != 0)
      throw RenderError("cannot use font '" + path + "' at " + std::to_string(size_px) + " px");
    return it->second;
  }

 private:
  FT_Library library_ = nullptr;
  std::map<std::string, FT_Face> faces_;
};

Fonts& fonts() {
  static Fonts f;
  return f;
}

// The next code point of UTF-8 text at i (advanced); U+FFFD for a bad byte.
char32_t next_code_point(std::string_view s, std::size_t& i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i++);
  if (c < 0x80) return c;
  const int extra = c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : c >= 0xC0 ? 1 : -1;
  if (extra < 0 || i + static_cast<std::size_t>(extra) > s.size()) return 0xFFFD;
  char32_t cp = c & (0x3F >> extra);
  for (int k = 0; k < extra; ++k) {
    if ((byte(i) & 0xC0) != 0x80) return 0xFFFD;
    cp = (cp << 6) | (byte(i++) & 0x3F);
  }
  return cp;
}

// One line laid out: each glyph's pen position (pixels from the line's
// start, kerned) and the line's advance width and ink box (y up from the
// baseline: top > 0 above it). Calls visit(glyph slot, pen x) when given.
struct LineExtent {
  int advance = 0;
  int ink_top = 0, ink_bottom = 0;
};

template <class Visit>
LineExtent lay_out(FT_Face face, std::string_view line, Visit&& visit) {
  LineExtent e;
  long pen = 0;  // 26.6 fixed point
  FT_UInt previous = 0;
  bool any_ink = false;
  // Input text (a mesh name in a title) is drawn as a message: bytes that
  // are not UTF-8 and control characters as \xHH, measured as drawn.
  const std::string shown = message_text(line);
  for (std::size_t i = 0; i < shown.size();) {
    const FT_UInt glyph = FT_Get_Char_Index(face, next_code_point(shown, i));
    if (previous != 0 && glyph != 0 && FT_HAS_KERNING(face)) {
      FT_Vector k{};
      if (FT_Get_Kerning(face, previous, glyph, FT_KERNING_DEFAULT, &k) == 0) pen += k.x;
    }
    if (FT_Load_Glyph(face, glyph, FT_LOAD_RENDER) != 0) continue;
    const FT_GlyphSlot slot = face->glyph;
    const int x = static_cast<int>((pen + 32) >> 6);
    if (slot->bitmap.rows > 0) {
      const int top = slot->bitmap_top, bottom = slot->bitmap_top - static_cast<int>(slot->bitmap.rows);
      e.ink_top = any_ink ? std::max(e.ink_top, top) : top;
      e.ink_bottom = any_ink ? std::min(e.ink_bottom, bottom) : bottom;
      any_ink = true;
    }
    visit(slot, x);
    pen += slot->advance.x;
    previous = glyph;
  }
  e.advance = static_cast<int>((pen + 32) >> 6);
  return e;
}

// Blends a glyph's coverage in `color` over the image ("over": straight
// alpha), its pen at (x, baseline).
void blend_glyph(Image& image, const FT_GlyphSlot slot, int x, int baseline, const Color& color) {
  const FT_Bitmap& b = slot->bitmap;
  for (unsigned row = 0; row < b.rows; ++row) {
    const int py = baseline - slot->bitmap_top + static_cast<int>(row);
    if (py < 0 || py >= image.height) continue;
    for (unsigned col = 0; col < b.width; ++col) {
      const int px = x + slot->bitmap_left + static_cast<int>(col);
      if (px < 0 || px >= image.width) continue;
      const float a = color.a * static_cast<float>(b.buffer[static_cast<std::ptrdiff_t>(row) * b.pitch + col]) / 255.0f;
      if (a <= 0.0f) continue;
      std::uint8_t* p = image.rgba.data() + pixel_offset(image, px, py);
      const float rgb[3] = {color.r, color.g, color.b};
      const float dst_a = static_cast<float>(p[3]) / 255.0f;
      const float out_a = a + dst_a * (1.0f - a);
      for (int k = 0; k < 3; ++k) {
        const float d = static_cast<float>(p[k]) / 255.0f;
        const float v = out_a > 0.0f ? (rgb[k] * a + d * dst_a * (1.0f - a)) / out_a : 0.0f;
        p[k] = static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
      }
      p[3] = static_cast<std::uint8_t>(std::lround(std::clamp(out_a, 0.0f, 1.0f) * 255.0f));
    }
  }
}

}  // namespace

void draw_text(Image& image, int x, int y, std::string_view text, int size_px, const AnnotationStyle& style,
               TextAnchor anchor) {
  if (image.width <= 0 || image.height <= 0 || text.empty()) return;
  const Color c = to_color(style.text_color);
  const int line_height = static_cast<int>(std::lround(size_px * kLineSpacing));
  Fonts& f = fonts();
  const std::lock_guard lock(f.mutex);
  FT_Face face = f.face(style.font_path, size_px);
  int baseline = y;
  for (std::string_view line : split_lines(text)) {
    if (!line.empty()) {
      const int width = lay_out(face, line, [](FT_GlyphSlot, int) {}).advance;
      const int start = anchor == TextAnchor::left ? x : anchor == TextAnchor::center ? x - width / 2 : x - width;
      lay_out(face, line, [&](FT_GlyphSlot slot, int pen) { blend_glyph(image, slot, start + pen, baseline, c); });
    }
    baseline += line_height;
  }
}

PixelRect text_extent(std::string_view text, int size_px, const AnnotationStyle& style) {
  int width = 0, height = 0;
  const std::vector<std::string_view> lines = split_lines(text);
  Fonts& f = fonts();
  const std::lock_guard lock(f.mutex);
  FT_Face face = f.face(style.font_path, size_px);
  for (std::string_view line : lines) {
    if (line.empty()) continue;
    const LineExtent e = lay_out(face, line, [](FT_GlyphSlot, int) {});
    width = std::max(width, e.advance);
    height = std::max(height, e.ink_top - e.ink_bottom);
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
  const LegendMetrics m = legend_metrics(bar, style, area_height);
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

const SwatchMark& swatch_mark(SwatchShape shape) {
  for (const SwatchMark& m : kSwatchMarks)
    if (m.shape == shape) return m;
  return kSwatchMarks[0];
}

std::vector<std::array<double, 2>> dashed_pieces(double length, const SwatchStroke& stroke, bool open_ends) {
  if (!(stroke.dash > 0) || !(length > 0)) return {{0.0, 1.0}};
  if (!open_ends) {  // a swatch: dashes from end to end, at least two
    const int count = static_cast<int>(std::floor((length + stroke.gap) / (stroke.dash + stroke.gap)));
    if (count < 2) return {{0.0, 1.0}};
    const double dash = stroke.dash / length, gap = (1.0 - count * dash) / (count - 1);
    std::vector<std::array<double, 2>> pieces;
    for (int i = 0; i < count; ++i) pieces.push_back({i * (dash + gap), i * (dash + gap) + dash});
    return pieces;
  }
  // Issue 48c: a half gap at each end, so the dashes of edges meeting at a
  // corner do not merge into a chevron; an edge shorter than a dash and a
  // gap one dash in its middle, its ends open (it was drawn solid, or as two
  // dashes: small hexes' outlines read as scribbles or corner brackets).
  const int count = static_cast<int>(std::floor(length / (stroke.dash + stroke.gap)));
  if (count < 1) return {{0.2, 0.8}};
  const double slot = 1.0 / count, dash = stroke.dash / length;
  std::vector<std::array<double, 2>> pieces;
  for (int i = 0; i < count; ++i) pieces.push_back({(i + 0.5) * slot - 0.5 * dash, (i + 0.5) * slot + 0.5 * dash});
  return pieces;
}

namespace {

// A stroke swatch: the halo's pieces, then the core's, across the box.
void draw_stroke_swatch(Image& image, const PixelRect& box, const Rgba8& color, const SwatchStroke& stroke) {
  const double x0 = box.x + 1.0, x1 = box.x + box.width - 1.0, cy = box.y + 0.5 * box.height;
  const std::vector<std::array<double, 2>> pieces = dashed_pieces(x1 - x0, stroke, false);
  for (const auto& [rgba, width] : {std::pair{stroke.halo, stroke.halo_width}, std::pair{color, stroke.width}})
    if (width > 0)
      for (const auto& [t0, t1] : pieces) draw_line(image, x0 + t0 * (x1 - x0), cy, x0 + t1 * (x1 - x0), cy, rgba, width);
}

}  // namespace

void draw_swatch(Image& image, const PixelRect& box, const Rgba8& color, SwatchShape shape, int outline) {
  const SwatchMark& mark = swatch_mark(shape);
  const double width = std::max(1.5, mark.width * box.height);
  const double cx = box.x + 0.5 * box.width, cy = box.y + 0.5 * box.height;
  switch (mark.kind) {
    case SwatchMark::Kind::fill:
      fill_rect(image, box, color);
      if (outline > 0) outline_rect(image, box, outline, kOutlineColor);
      return;
    case SwatchMark::Kind::segment: {
      // Across the box (the head's length short of its right end): 4 dashes
      // and 3 gaps when dashed.
      const double x0 = box.x + 1.0, head = mark.head ? 0.4 * box.height : 0.0;
      const double x1 = box.x + box.width - 1.0 - head;
      for (int d = 0; d < 7; d += mark.dashed ? 2 : 7)
        draw_line(image, x0 + (mark.dashed ? d / 7.0 : 0.0) * (x1 - x0), cy,
                  x0 + (mark.dashed ? (d + 1) / 7.0 : 1.0) * (x1 - x0), cy, color, width);
      if (mark.head)
        for (const double side : {-1.0, 1.0})
          draw_line(image, x1 + head, cy, x1 - 0.2 * head, cy + side * head, color, width);
      return;
    }
    case SwatchMark::Kind::ring: {
      // As the figure draws it: 12 arcs of 30 degrees, every other one
      // left out when dashed.
      const double r = 0.5 * (std::min(box.width, box.height) - width);
      constexpr int kArcs = 12, kSteps = 4;
      for (int a = 0; a < kArcs; ++a) {
        if (mark.dashed && a % 2 == 1) continue;
        for (int k = 0; k < kSteps; ++k) {
          const double t0 = 2.0 * M_PI * (a * kSteps + k) / (kArcs * kSteps);
          const double t1 = 2.0 * M_PI * (a * kSteps + k + 1) / (kArcs * kSteps);
          draw_line(image, cx + r * std::cos(t0), cy + r * std::sin(t0), cx + r * std::cos(t1), cy + r * std::sin(t1),
                    color, width);
        }
      }
      return;
    }
    case SwatchMark::Kind::none: return;
  }
}

namespace {

// draw_swatch, and for a ring with a band (view A's and C's worst: a yellow
// band in a dark ring) the band inside the ring, as the figure draws it: the
// ring's stroke is mark.width * the box's height wide, the band as wide
// again within it.
void draw_banded_swatch(Image& image, const PixelRect& box, const Rgba8& color, SwatchShape shape,
                        const std::optional<Rgba8>& band, int outline = 0) {
  if (band && swatch_mark(shape).kind == SwatchMark::Kind::ring) {
    const int inset = static_cast<int>(std::lround(swatch_mark(shape).width * box.height));
    draw_swatch(image, {box.x + inset, box.y + inset, box.width - 2 * inset, box.height - 2 * inset}, *band, shape);
  }
  draw_swatch(image, box, color, shape, outline);
}

}  // namespace

std::vector<std::size_t> legible_ticks(const ColorBar& bar, int bar_height, int label_height) {
  const double range = bar.max_value - bar.min_value;
  std::vector<std::pair<std::size_t, int>> order;  // (tick, its row), the ends first
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < bar.ticks.size(); ++i) {
      const double u = range != 0.0 ? (bar.ticks[i].value - bar.min_value) / range : 0.0;
      if (!(u >= 0.0 && u <= 1.0)) continue;
      if ((u == 0.0 || u == 1.0) != (pass == 0)) continue;
      order.push_back({i, static_cast<int>(std::lround((1.0 - u) * (bar_height - 1)))});
    }
  std::vector<int> rows;
  std::vector<std::size_t> kept;
  for (const auto& [i, y] : order) {
    if (std::any_of(rows.begin(), rows.end(), [&](int r) { return std::abs(r - y) < label_height + 1; })) continue;
    rows.push_back(y);
    kept.push_back(i);
  }
  std::sort(kept.begin(), kept.end());
  return kept;
}

void draw_color_bar(Image& image, const PixelRect& area, const ColorBar& bar, const AnnotationStyle& given_style) {
  const AnnotationStyle style = color_bar_style_for(bar, given_style, area);
  const LegendMetrics m = legend_metrics(bar, style, area.height);
  const int label_lines = bar.label.empty() ? 0 : static_cast<int>(split_lines(bar.label).size());
  const int label_block = label_lines * m.line_height;
  const int total = color_bar_height(bar, style, area.height);
  const int top = area.y + (bar.max_bar_height > 0 ? 0 : std::max(0, (area.height - total) / 2));
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
  // A label's height: a line of tick text at its spacing (brackets and
  // descenders too; digits alone left the turned plate's labels touching).
  const int label_height = static_cast<int>(std::lround(m.tick_size * kLineSpacing));
  for (std::size_t i : legible_ticks(bar, bar_rect.height, label_height)) {
    const ColorBarTick& tick = bar.ticks[i];
    const double u = range != 0.0 ? (tick.value - bar.min_value) / range : 0.0;
    const int y = bar_rect.y + static_cast<int>(std::lround((1.0 - u) * (bar_rect.height - 1)));
    fill_rect(image, {tick_x, y - outline / 2, m.tick_length, outline}, kOutlineColor);
    draw_text(image, tick_x + m.tick_length + m.tick_gap, y + baseline_shift, tick.label, m.tick_size, style);
  }

  int swatch_y = bar_rect.y + bar_rect.height + outline + m.swatch_gap;
  for (const ColorBarSwatch& swatch : bar.swatches) {
    if (swatch.stroke)
      draw_stroke_swatch(image, {x, swatch_y, m.bar_width, m.swatch_height}, to_rgba8(swatch.color), *swatch.stroke);
    else
      draw_banded_swatch(image, {x, swatch_y, m.bar_width, m.swatch_height}, to_rgba8(swatch.color), swatch.shape,
                         swatch.ring_band, outline);
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
  // Several lines (issue 48e: a long title shrunk on one line to below the
  // legend's text): one size for all, the largest at which each fits and
  // the block fills at most 90 % of the band.
  std::vector<std::string_view> lines = split_lines(title);
  int size = std::max(14, scaled(kTitleSize, style));
  if (lines.size() == 1 && text_extent(title, fitting_text_size(title, size, 9, max_width, style), style).width > max_width) {
    // Too long for one line even at the smallest size: two lines, broken at
    // the space that leaves the longer line shortest (the 45e review: an
    // 800 x 400 compare view's title was cut at "...; mirror i...", the one
    // word it had to say).
    const std::string_view whole = lines[0];
    std::size_t cut = std::string_view::npos;
    int longer = std::numeric_limits<int>::max();
    for (std::size_t i = whole.find(' '); i != std::string_view::npos; i = whole.find(' ', i + 1)) {
      const int w = std::max(text_extent(whole.substr(0, i), 9, style).width, text_extent(whole.substr(i + 1), 9, style).width);
      if (w < longer) longer = w, cut = i;
    }
    if (cut != std::string_view::npos) lines = {whole.substr(0, cut), whole.substr(cut + 1)};
  }
  const int n = static_cast<int>(lines.size());
  if (n > 1) size = std::max(9, std::min(size, static_cast<int>(0.9 * area.height / (n * kLineSpacing))));
  int fitted = size;
  for (std::string_view line : lines) fitted = std::min(fitted, fitting_text_size(line, size, 9, max_width, style));
  const int line_height = static_cast<int>(std::lround(fitted * kLineSpacing));
  // Baseline so that the block (cap height 0.73 em on the last line) is centred in the band.
  int baseline = area.y + area.height / 2 + static_cast<int>(std::lround(0.365 * fitted)) - (n - 1) * line_height / 2;
  for (std::string_view line : lines) {
    draw_text(image, area.x + inset, baseline, ellipsize(line, fitted, max_width, style), fitted, style);
    baseline += line_height;
  }
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
      draw_banded_swatch(image, {x, y - swatch, swatch, swatch}, color, line.shape, line.ring_band);
      const int text_x = x + swatch + swatch / 2;
      draw_text(image, text_x, y - 2, ellipsize(line.text, text_size, right - text_x, style), text_size, style);
    } else {
      draw_text(image, x, y, ellipsize(line.text, text_size, right - x, style), text_size, style);
    }
    y += pitch;
  }
}

}  // namespace hq
