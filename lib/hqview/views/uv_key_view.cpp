#include "hqview/views/uv_key_view.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "hqview/render/annotate.h"
#include "hqview/render/camera.h"
#include "hqview/render/label_layout.h"
#include "hqview/render/upright.h"
#include "hqview/views/inverted_callout.h"
#include "hqview/views/main_views.h"
#include "hqview/views/overview_views.h"

namespace hq {
namespace {

constexpr Rgba8 kOutline{60, 60, 68, 255};
constexpr Rgba8 kLabelBox{255, 255, 255, 230};

Vec3f to_f(const Vec3& p, const Vec3& origin) {
  return {static_cast<float>(p.x - origin.x), static_cast<float>(p.y - origin.y), static_cast<float>(p.z - origin.z)};
}

const Vec3& corner(const TriSurface& s, std::size_t t, std::size_t k) {
  return s.points[static_cast<std::size_t>(s.triangles[t][k])];
}

// An edge of triangle t (corners k, k+1) lies on its chart's border when no
// other triangle of the same chart shares it.
std::vector<std::array<std::size_t, 2>> chart_border_edges(const TriSurface& reference, const UvAtlas& atlas) {
  const std::size_t n = std::min(atlas.triangle_chart.size(), reference.triangles.size());
  std::vector<std::pair<std::array<Index, 3>, std::size_t>> uses;  // (min, max, chart), triangle*3+k
  for (std::size_t t = 0; t < n; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const Index a = reference.triangles[t][k], b = reference.triangles[t][(k + 1) % 3];
      uses.push_back({{std::min(a, b), std::max(a, b), atlas.triangle_chart[t]}, 3 * t + k});
    }
  std::sort(uses.begin(), uses.end());
  std::vector<std::array<std::size_t, 2>> border;
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].first == uses[i].first) ++j;
    if (j - i == 1) border.push_back({uses[i].second / 3, uses[i].second % 3});
    i = j;
  }
  return border;
}

// The reference, each chart tinted, its chart borders drawn.
Scene reference_scene(const TriSurface& reference, const UvAtlas& atlas, const Vec3& origin) {
  Scene scene;
  scene.origin = origin;
  TriangleSet tris;
  const std::size_t n = std::min(atlas.triangle_chart.size(), reference.triangles.size());
  for (std::size_t t = 0; t < n; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      tris.indices.push_back(static_cast<std::uint32_t>(tris.positions.size()));
      tris.positions.push_back(to_f(corner(reference, t, k), origin));
      tris.colors.push_back(chart_tint(atlas.triangle_chart[t]));
    }
  LineSet lines;
  lines.width = 1.5f;
  for (const auto& [t, k] : chart_border_edges(reference, atlas))
    for (std::size_t c : {k, (k + 1) % 3}) {
      lines.indices.push_back(static_cast<std::uint32_t>(lines.positions.size()));
      lines.positions.push_back(to_f(corner(reference, t, c), origin));
      lines.colors.push_back(kOutline);
    }
  scene.triangles.push_back(std::move(tris));
  scene.lines.push_back(std::move(lines));
  return scene;
}

// The atlas as the UV error map draws it (its scene: the same layout and
// chart outlines), each chart tinted instead of the error colours.
Scene atlas_scene(const TriSurface& reference, const UvAtlas& atlas) {
  Scene scene = build_uv_error_scene(reference, atlas, std::vector<double>(reference.points.size(), 0.0), 1.0);
  std::vector<Rgba8>& colors = scene.triangles.front().colors;
  for (std::size_t i = 0; i < colors.size(); ++i) colors[i] = chart_tint(atlas.triangle_chart[i / 3]);
  return scene;
}

// The pale box a number is written in, centred at (x, y).
PixelRect number_box(int x, int y, Index number, int size, const AnnotationStyle& style) {
  const PixelRect extent = text_extent(std::to_string(number), size, style);
  const int pad = std::max(2, size / 5);
  return {x - extent.width / 2 - pad, y - size / 2 - pad, extent.width + 2 * pad, size + 2 * pad};
}

bool inside(const PixelRect& box, const PixelRect& bounds) {
  return box.x >= bounds.x && box.y >= bounds.y && box.x + box.width <= bounds.x + bounds.width &&
         box.y + box.height <= bounds.y + bounds.height;
}

// A frame's numbers: leader lines first (a dark line on a pale halo, a dot
// at the anchor), then the boxes, so no line crosses a number.
void draw_numbers(Image& image, const std::vector<UvKeyNumber>& numbers, int size, const AnnotationStyle& style) {
  for (const UvKeyNumber& n : numbers) {
    if (!n.placed || !n.has_leader) continue;
    const double cx = n.box.x + 0.5 * n.box.width, cy = n.box.y + 0.5 * n.box.height;
    draw_line(image, n.anchor_x, n.anchor_y, cx, cy, kLabelBox, std::max(3.0, 4.0 * style.scale));
    draw_line(image, n.anchor_x, n.anchor_y, cx, cy, kOutline, std::max(1.0, 1.6 * style.scale));
    const int r = std::max(2, static_cast<int>(std::lround(3 * style.scale)));
    fill_rect(image, {n.anchor_x - r, n.anchor_y - r, 2 * r + 1, 2 * r + 1}, kOutline);
  }
  for (const UvKeyNumber& n : numbers) {
    if (!n.placed) continue;
    fill_rect(image, n.box, kLabelBox);
    draw_text(image, n.box.x + n.box.width / 2, n.box.y + n.box.height / 2 + size * 2 / 5,
              std::to_string(n.chart), size, style, TextAnchor::center);
  }
}

// A scene of reference_scene or atlas_scene recoloured for chart_ids: each
// triangle in its chart's id colour, unlit, no outlines.
void as_id_scene(Scene& scene, const UvAtlas& atlas) {
  TriangleSet& tris = scene.triangles.front();
  for (std::size_t i = 0; i < tris.colors.size(); ++i) tris.colors[i] = chart_id_color(atlas.triangle_chart[i / 3]);
  tris.scalars.clear();
  tris.is_lit = false;
  scene.lines.clear();
  scene.background = {255, 255, 255, 255};
}

// Numbers a frame (area of the figure) from its id frame: in a 3D frame a
// chart needs 20 pixels (at 1200 px height) to get a number there, in the
// atlas (which shows every chart) one.
void number_frame(Image& figure, const PixelRect& area, const Image& id_frame, int number_size,
                  const AnnotationStyle& style, bool is_atlas, std::vector<UvKeyFrame>* frames) {
  ChartIdImage ids = chart_ids(id_frame);
  const int min_pixels = is_atlas ? 1 : std::max(4, static_cast<int>(std::lround(20 * style.scale * style.scale)));
  const std::vector<UvKeyNumberAnchor> anchors = visible_chart_anchors(ids, area.x, area.y, min_pixels, is_atlas);
  std::vector<UvKeyNumber> numbers = place_uv_key_numbers(anchors, area, number_size, style);
  // A sliver in the atlas (no pixel 3 px from anything else: a 1-2 px
  // smudge beside a bigger chart) is ringed, so that its number's dot reads
  // as naming what is inside the ring, not the chart next to it.
  bool any_sliver = false;
  if (is_atlas)
    for (std::size_t i = 0; i < anchors.size() && i < numbers.size(); ++i)
      if (numbers[i].placed && anchors[i].room <= kSliverRoom) {
        draw_marker_ring(figure, anchors[i].x + 0.5, anchors[i].y + 0.5, std::max(6.0, 10.0 * style.scale),
                         std::max(1.5, 2.5 * style.scale), false, {90, 90, 90, 255});
        any_sliver = true;
      }
  draw_numbers(figure, numbers, number_size, style);
  if (any_sliver) {
    const int size = std::max(style.min_text_size, static_cast<int>(std::lround(16 * style.scale)));
    draw_text(figure, area.x + area.width / 2, area.y + area.height - size / 2, "ringed: a chart too thin to see here",
              size, style, TextAnchor::center);
  }
  if (frames) frames->push_back({area, std::move(ids), std::move(numbers)});
}

}  // namespace

Rgba8 chart_tint(Index chart) {
  const double hue = std::fmod(0.11 + 0.6180339887498949 * chart, 1.0) * 6.0;
  const double s = 0.38, v = 0.97;
  const int i = static_cast<int>(hue);
  const double f = hue - i, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  double r = v, g = t, b = p;
  switch (i % 6) {
    case 1: r = q, g = v, b = p; break;
    case 2: r = p, g = v, b = t; break;
    case 3: r = p, g = q, b = v; break;
    case 4: r = t, g = p, b = v; break;
    case 5: r = v, g = p, b = q; break;
    default: break;
  }
  const auto byte = [](double x) { return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(x, 0.0, 1.0))); };
  return {byte(r), byte(g), byte(b), 255};
}

std::vector<UvChartLabel> uv_chart_labels(const TriSurface& reference, const UvAtlas& atlas) {
  const std::size_t n = std::min(atlas.triangle_chart.size(), reference.triangles.size());
  struct Sum {
    double area = 0, uv_area = 0;
    Vec3 centroid{};
    std::array<double, 2> uv_centroid{};
  };
  std::vector<Sum> sums(static_cast<std::size_t>(atlas.num_charts));
  const auto uv_of = [&](std::size_t t, std::size_t k) { return atlas.uvs[3 * t + k]; };
  const auto uv_area = [&](std::size_t t) {
    const Uv a = uv_of(t, 0), b = uv_of(t, 1), c = uv_of(t, 2);
    return 0.5 * std::abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
  };
  for (std::size_t t = 0; t < n; ++t) {
    Sum& s = sums[static_cast<std::size_t>(atlas.triangle_chart[t])];
    const Vec3 &a = corner(reference, t, 0), &b = corner(reference, t, 1), &c = corner(reference, t, 2);
    const double area = 0.5 * norm(cross(b - a, c - a));
    s.area += area;
    s.centroid = s.centroid + (area / 3.0) * (a + b + c);
    const double w = uv_area(t);
    s.uv_area += w;
    for (std::size_t d = 0; d < 2; ++d) s.uv_centroid[d] += w / 3.0 * (uv_of(t, 0)[d] + uv_of(t, 1)[d] + uv_of(t, 2)[d]);
  }
  std::vector<UvChartLabel> anchors(sums.size());
  std::vector<double> best(sums.size(), INFINITY), best_uv(sums.size(), INFINITY);
  for (std::size_t c = 0; c < sums.size(); ++c) anchors[c].chart = static_cast<Index>(c);
  for (std::size_t t = 0; t < n; ++t) {
    const std::size_t c = static_cast<std::size_t>(atlas.triangle_chart[t]);
    const Sum& s = sums[c];
    if (!(s.area > 0)) continue;
    const Vec3 &a = corner(reference, t, 0), &b = corner(reference, t, 1), &q = corner(reference, t, 2);
    const Vec3 m = (a + b + q) / 3.0;
    const double d = squared_norm(m - s.centroid / s.area);
    if (d < best[c] && norm(cross(b - a, q - a)) > 0) {
      best[c] = d;
      anchors[c].triangle = static_cast<Index>(t);
      anchors[c].position = m;
      anchors[c].normal = normalized(cross(b - a, q - a));
    }
    if (s.uv_area > 0 && uv_area(t) > 0) {
      const std::array<double, 2> u{(uv_of(t, 0)[0] + uv_of(t, 1)[0] + uv_of(t, 2)[0]) / 3.0,
                                    (uv_of(t, 0)[1] + uv_of(t, 1)[1] + uv_of(t, 2)[1]) / 3.0};
      const double du = std::hypot(u[0] - s.uv_centroid[0] / s.uv_area, u[1] - s.uv_centroid[1] / s.uv_area);
      if (du < best_uv[c]) {
        best_uv[c] = du;
        anchors[c].uv = u;
        anchors[c].uv_triangle = static_cast<Index>(t);
      }
    }
  }
  std::erase_if(anchors, [](const UvChartLabel& a) { return a.triangle == kNoIndex || a.uv_triangle == kNoIndex; });
  return anchors;
}

Rgba8 chart_id_color(Index chart) {
  const auto code = static_cast<std::uint32_t>(chart) + 1u;  // 0: no chart
  return {static_cast<std::uint8_t>(code & 0xFFu), static_cast<std::uint8_t>((code >> 8) & 0xFFu),
          static_cast<std::uint8_t>((code >> 16) & 0x7Fu), 255};
}

ChartIdImage chart_ids(const Image& id_frame) {
  ChartIdImage out;
  out.width = id_frame.width;
  out.height = id_frame.height;
  const std::size_t n = static_cast<std::size_t>(out.width) * static_cast<std::size_t>(out.height);
  std::vector<std::uint32_t> code(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* p = &id_frame.rgba[4 * i];
    // The background (white) and any blend with it have the high bit of blue set or are not opaque.
    code[i] = p[2] >= 0x80 || p[3] != 255 ? 0u : std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16;
  }
  out.ids.assign(n, kNoIndex);
  for (int y = 1; y + 1 < out.height; ++y)
    for (int x = 1; x + 1 < out.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * out.width + x;
      const std::uint32_t c = code[i];
      if (c == 0 || code[i - 1] != c || code[i + 1] != c || code[i - out.width] != c || code[i + out.width] != c)
        continue;
      out.ids[i] = static_cast<Index>(c - 1);
    }
  return out;
}

std::vector<UvKeyNumberAnchor> visible_chart_anchors(const ChartIdImage& ids, int x0, int y0, int min_pixels,
                                                     bool islands) {
  const int w = ids.width, h = ids.height;
  // Chessboard distance to the nearest pixel of another id (kNoIndex and
  // outside the frame included): 1 on a chart's edge; two passes.
  constexpr int kFar = 1 << 29;
  std::vector<int> d(ids.ids.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Index c = ids.at(x, y);
      d[static_cast<std::size_t>(y) * w + x] = c == kNoIndex ? 0 : kFar;
    }
  auto relax = [&](int x, int y, int dx, int dy) {
    int& here = d[static_cast<std::size_t>(y) * w + x];
    if (here == 0) return;
    const int nx = x + dx, ny = y + dy;
    const int there = nx < 0 || ny < 0 || nx >= w || ny >= h || ids.at(nx, ny) != ids.at(x, y)
                          ? 0
                          : d[static_cast<std::size_t>(ny) * w + nx];
    here = std::min(here, there + 1);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (const auto& [dx, dy] : {std::pair{-1, -1}, std::pair{0, -1}, std::pair{1, -1}, std::pair{-1, 0}}) relax(x, y, dx, dy);
  for (int y = h - 1; y >= 0; --y)
    for (int x = w - 1; x >= 0; --x)
      for (const auto& [dx, dy] : {std::pair{1, 1}, std::pair{0, 1}, std::pair{-1, 1}, std::pair{1, 0}}) relax(x, y, dx, dy);
  struct Best {
    int count = 0, room = 0, x = 0, y = 0;
  };
  // Per island (4-connected pixels of one chart; with islands = false, per
  // chart) its size and its pixel of most room.
  std::vector<int> island(ids.ids.size(), -1);
  std::vector<Best> best;
  std::vector<Index> chart_of;
  std::vector<std::size_t> stack;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t at = static_cast<std::size_t>(y) * w + x;
      const Index c = ids.ids[at];
      if (c == kNoIndex || island[at] >= 0) continue;
      if (!islands) {  // one "island" per chart, numbered by the chart
        if (static_cast<std::size_t>(c) >= best.size()) best.resize(static_cast<std::size_t>(c) + 1), chart_of.resize(best.size());
        chart_of[static_cast<std::size_t>(c)] = c;
        island[at] = static_cast<int>(c);
        continue;
      }
      const int k = static_cast<int>(best.size());
      best.emplace_back();
      chart_of.push_back(c);
      island[at] = k;
      stack.assign(1, at);
      while (!stack.empty()) {
        const std::size_t p = stack.back();
        stack.pop_back();
        const int px = static_cast<int>(p % w), py = static_cast<int>(p / w);
        for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
          const int nx = px + dx, ny = py + dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          const std::size_t q = static_cast<std::size_t>(ny) * w + nx;
          if (island[q] < 0 && ids.ids[q] == c) island[q] = k, stack.push_back(q);
        }
      }
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t at = static_cast<std::size_t>(y) * w + x;
      if (ids.ids[at] == kNoIndex) continue;
      Best& b = best[static_cast<std::size_t>(island[at])];
      ++b.count;
      const int r = d[at];
      if (r > b.room) b = {b.count, r, x, y};
    }
  // A chart's total and its largest island.
  std::vector<int> total, largest;
  for (std::size_t k = 0; k < best.size(); ++k) {
    if (best[k].count == 0) continue;
    const auto c = static_cast<std::size_t>(chart_of[k]);
    if (c >= total.size()) total.resize(c + 1, 0), largest.resize(c + 1, -1);
    total[c] += best[k].count;
    if (largest[c] < 0 || best[k].count > best[static_cast<std::size_t>(largest[c])].count) largest[c] = static_cast<int>(k);
  }
  std::vector<UvKeyNumberAnchor> anchors;
  for (std::size_t c = 0; c < total.size(); ++c) {
    if (largest[c] < 0 || total[c] < min_pixels) continue;
    // The largest island first, then the others of at least kIslandFraction
    // of the chart (and min_pixels), in row order of their first pixel.
    const Best& b = best[static_cast<std::size_t>(largest[c])];
    anchors.push_back({static_cast<Index>(c), x0 + b.x, y0 + b.y, b.room});
    for (std::size_t k = 0; k < best.size(); ++k)
      if (static_cast<int>(k) != largest[c] && static_cast<std::size_t>(chart_of[k]) == c &&
          best[k].count >= std::max<double>(min_pixels, kIslandFraction * total[c]))
        anchors.push_back({static_cast<Index>(c), x0 + best[k].x, y0 + best[k].y, best[k].room});
  }
  if (!islands) return anchors;
  // Lobes: per chart, the parts of its pixels of at least R room (R =
  // kLobeRoom, or kLobeFraction of the chart's most room if more) that are
  // not 8-connected to each other: pieces joined to the rest by a neck
  // thinner than 2R. Each lobe without an anchor gets one at its roomiest
  // pixel (up to kMaxLobes per chart).
  std::vector<int> most(total.size(), 0);
  for (std::size_t at = 0; at < ids.ids.size(); ++at)
    if (ids.ids[at] != kNoIndex) most[static_cast<std::size_t>(ids.ids[at])] = std::max(most[static_cast<std::size_t>(ids.ids[at])], d[at]);
  auto reach = [&](Index c) { return std::max(kLobeRoom, static_cast<int>(kLobeFraction * most[static_cast<std::size_t>(c)])); };
  std::vector<int> lobe(ids.ids.size(), -1);
  std::vector<Best> lobes;
  std::vector<Index> lobe_chart;
  for (std::size_t start = 0; start < ids.ids.size(); ++start) {
    const Index c = ids.ids[start];
    if (c == kNoIndex || lobe[start] >= 0 || d[start] < reach(c)) continue;
    const int k = static_cast<int>(lobes.size());
    lobes.push_back({0, d[start], static_cast<int>(start % w), static_cast<int>(start / w)});
    lobe_chart.push_back(c);
    lobe[start] = k;
    stack.assign(1, start);
    while (!stack.empty()) {
      const std::size_t p = stack.back();
      stack.pop_back();
      ++lobes.back().count;
      const int px = static_cast<int>(p % w), py = static_cast<int>(p / w);
      if (d[p] > lobes.back().room) lobes.back() = {lobes.back().count, d[p], px, py};
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = px + dx, ny = py + dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          const std::size_t q = static_cast<std::size_t>(ny) * w + nx;
          if (lobe[q] < 0 && ids.ids[q] == c && d[q] >= reach(c)) lobe[q] = k, stack.push_back(q);
        }
    }
  }
  std::vector<int> extra(total.size(), 0);
  std::vector<char> has_anchor(lobes.size(), 0);
  for (const UvKeyNumberAnchor& a : anchors) {
    const int k = lobe[static_cast<std::size_t>(a.y - y0) * w + static_cast<std::size_t>(a.x - x0)];
    if (k >= 0) has_anchor[static_cast<std::size_t>(k)] = 1;
  }
  const std::size_t before = anchors.size();
  for (std::size_t k = 0; k < lobes.size(); ++k) {
    const auto c = static_cast<std::size_t>(lobe_chart[k]);
    if (has_anchor[k] || extra[c] == kMaxLobes) continue;
    ++extra[c];
    anchors.push_back({lobe_chart[k], x0 + lobes[k].x, y0 + lobes[k].y, lobes[k].room});
  }
  // In chart order, as without lobes.
  std::stable_sort(anchors.begin() + static_cast<std::ptrdiff_t>(before), anchors.end(),
                   [](const UvKeyNumberAnchor& x, const UvKeyNumberAnchor& y) { return x.chart < y.chart; });
  return anchors;
}

std::vector<UvKeyNumber> place_uv_key_numbers(const std::vector<UvKeyNumberAnchor>& anchors, const PixelRect& bounds,
                                              int text_size, const AnnotationStyle& style) {
  LabelLayoutOptions options;
  options.bounds = bounds;
  options.gap = 2.0 * style.scale;
  options.ring_step = 10.0 * style.scale;
  options.rings = static_cast<int>(std::ceil(std::max(bounds.width, bounds.height) / options.ring_step));
  options.leader_distance = 10.0 * style.scale;
  std::vector<UvKeyNumber> numbers;
  std::vector<PixelRect> taken;
  for (const UvKeyNumberAnchor& a : anchors) {
    UvKeyNumber n;
    n.chart = a.chart;
    n.anchor_x = a.x;
    n.anchor_y = a.y;
    const PixelRect centred = number_box(a.x, a.y, a.chart, text_size, style);
    // The centred box on the chart's own pixels (UvKeyNumberAnchor::room).
    const bool fits = 2LL * a.room > std::max(centred.width, centred.height) + 1LL;
    const bool free = fits && inside(centred, bounds) &&
                      std::none_of(taken.begin(), taken.end(), [&](const PixelRect& t) { return boxes_overlap(t, centred); });
    if (free) {
      n.placed = true;
      n.box = centred;
    } else {
      const LabelRequest request[] = {{ScreenDisc{double(a.x), double(a.y), 1.0}, centred.width, centred.height}};
      if (const std::optional<PlacedLabel> p = place_labels(request, {}, taken, options)[0]) {
        n.placed = true;
        n.box = p->box;
        // Off its anchor the box may cover other charts: a leader (and the
        // dot at the anchor) says which chart it names, however short.
        n.has_leader = true;
      }
    }
    if (n.placed) taken.push_back(n.box);
    numbers.push_back(n);
  }
  return numbers;
}

Image render_uv_key(const TriSurface& reference, const UvAtlas& atlas, const BoundaryViewOptions& options,
                    Renderer& renderer, std::vector<UvKeyFrame>* frames) {
  AnnotationStyle style = annotation_style_for(options.height);
  style.background = options.background;
  // Layout: the title on top; the left half two 3D views (front over back),
  // the right half the atlas square.
  const FigureLayout layout = figure_layout(options.width, options.height, !options.title.empty(), options.width / 2, style);
  Image figure = make_image(options.width, options.height, options.background);
  if (!options.title.empty()) draw_title(figure, layout.title, options.title, style);
  const int number_size = std::max(style.min_text_size, static_cast<int>(std::lround(22 * style.scale)));

  Box3 box;
  for (const auto& t : reference.triangles)
    for (Index v : t) box.add(reference.points[static_cast<std::size_t>(v)]);
  const Vec3 origin = 0.5 * (box.lo + box.hi);
  const Scene scene3d = reference_scene(reference, atlas, origin);
  Scene id3d = reference_scene(reference, atlas, origin);
  as_id_scene(id3d, atlas);
  if (frames) frames->clear();
  std::vector<Vec3> points(reference.points.begin(), reference.points.end());
  const int half = layout.view.height / 2;
  for (int row = 0; row < 2; ++row) {
    const PixelRect area{layout.view.x, layout.view.y + row * half, layout.view.width, half};
    const Vec3 direction = row == 0 ? three_quarter_view(options.up) : three_quarter_back_view(options.up);
    const Camera camera = fit_camera_to_points(points, direction, static_cast<double>(area.width) / area.height,
                                               {.up = options.up});
    paste(figure, renderer.render(scene3d, camera, area.width, area.height), area.x, area.y);
    number_frame(figure, area, renderer.render(id3d, camera, area.width, area.height), number_size, style, false,
                 frames);
    // Named by the eye (the three-quarter view of --up and its opposite), not
    // "front" / "back": the model's own front is unknown (the kitten's
    // "front" showed the back of its head).
    draw_text(figure, area.x + number_size / 2, area.y + number_size + 4,
              (row == 0 ? "" : "opposite side: ") + viewpoint_name(direction, options.up), number_size, style);
  }
  // The atlas, framed as the UV error map frames it.
  const PixelRect uv_area{layout.legend.x, layout.view.y, layout.legend.width, layout.view.height};
  const Camera camera = uv_map_camera(static_cast<double>(uv_area.width) / uv_area.height);
  Scene uv_scene = atlas_scene(reference, atlas);
  uv_scene.background = options.background;
  paste(figure, renderer.render(uv_scene, camera, uv_area.width, uv_area.height), uv_area.x, uv_area.y);
  Scene uv_ids = atlas_scene(reference, atlas);
  as_id_scene(uv_ids, atlas);
  number_frame(figure, uv_area, renderer.render(uv_ids, camera, uv_area.width, uv_area.height), number_size, style,
               true, frames);
  return figure;
}

}  // namespace hq
