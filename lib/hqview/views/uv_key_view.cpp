#include "hqview/views/uv_key_view.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "hqview/render/annotate.h"
#include "hqview/render/camera.h"
#include "hqview/render/label_layout.h"
#include "hqview/render/upright.h"
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

// Per chart, where its number goes in a 3D view along `direction`: the
// chart's triangle facing the eye (normal within 70 degrees of it) nearest
// the area centroid of the chart's facing triangles; none when less than 2 %
// of the chart faces the eye. (Not an occlusion test: a number may sit on a
// part hidden behind another.)
std::vector<std::pair<Index, Vec3>> facing_anchors(const TriSurface& reference, const UvAtlas& atlas,
                                                   const Vec3& direction) {
  const std::size_t n = std::min(atlas.triangle_chart.size(), reference.triangles.size());
  const Vec3 to_eye = normalized(-direction);
  const std::size_t charts = static_cast<std::size_t>(atlas.num_charts);
  std::vector<double> area(charts, 0.0), facing(charts, 0.0);
  std::vector<Vec3> sum(charts);
  for (std::size_t t = 0; t < n; ++t) {
    const std::size_t c = static_cast<std::size_t>(atlas.triangle_chart[t]);
    const Vec3 &a = corner(reference, t, 0), &b = corner(reference, t, 1), &q = corner(reference, t, 2);
    const Vec3 normal = cross(b - a, q - a);
    const double w = 0.5 * norm(normal);
    area[c] += w;
    if (dot(normalized(normal), to_eye) < 0.34) continue;
    facing[c] += w;
    sum[c] = sum[c] + (w / 3.0) * (a + b + q);
  }
  std::vector<double> best(charts, INFINITY);
  std::vector<std::pair<Index, Vec3>> anchors(charts, {kNoIndex, Vec3{}});
  for (std::size_t t = 0; t < n; ++t) {
    const std::size_t c = static_cast<std::size_t>(atlas.triangle_chart[t]);
    if (!(facing[c] > 0.02 * area[c])) continue;
    const Vec3 &a = corner(reference, t, 0), &b = corner(reference, t, 1), &q = corner(reference, t, 2);
    if (dot(normalized(cross(b - a, q - a)), to_eye) < 0.34) continue;
    const Vec3 m = (a + b + q) / 3.0;
    const double d = squared_norm(m - sum[c] / facing[c]);
    if (d < best[c]) {
      best[c] = d;
      anchors[c] = {static_cast<Index>(c), m};
    }
  }
  std::erase_if(anchors, [](const auto& a) { return a.first == kNoIndex; });
  return anchors;
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

// Pixel of a world point in an image area drawn with `camera`.
std::array<int, 2> to_pixel(const Camera& camera, const PixelRect& area, const Vec3& p) {
  const Vec3 ndc = project_to_ndc(camera, static_cast<double>(area.width) / area.height, p);
  return {area.x + static_cast<int>(std::lround((ndc.x + 1.0) * 0.5 * area.width)),
          area.y + static_cast<int>(std::lround((1.0 - ndc.y) * 0.5 * area.height))};
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
    UvKeyNumber n{a.chart, a.x, a.y};
    const PixelRect centred = number_box(a.x, a.y, a.chart, text_size, style);
    const bool free = inside(centred, bounds) && std::none_of(taken.begin(), taken.end(), [&](const PixelRect& t) {
                        return boxes_overlap(t, centred);
                      });
    if (free) {
      n.placed = true;
      n.box = centred;
    } else {
      const LabelRequest request[] = {{ScreenDisc{double(a.x), double(a.y), 1.0}, centred.width, centred.height}};
      if (const std::optional<PlacedLabel> p = place_labels(request, {}, taken, options)[0]) {
        n.placed = true;
        n.box = p->box;
        n.has_leader = disc_box_gap(request[0].anchor, p->box) > options.leader_distance;
      }
    }
    if (n.placed) taken.push_back(n.box);
    numbers.push_back(n);
  }
  return numbers;
}

Image render_uv_key(const TriSurface& reference, const UvAtlas& atlas, const BoundaryViewOptions& options,
                    Renderer& renderer) {
  AnnotationStyle style = annotation_style_for(options.height);
  style.background = options.background;
  // Layout: the title on top; the left half two 3D views (front over back),
  // the right half the atlas square.
  const FigureLayout layout = figure_layout(options.width, options.height, !options.title.empty(), options.width / 2, style);
  Image figure = make_image(options.width, options.height, options.background);
  if (!options.title.empty()) draw_title(figure, layout.title, options.title, style);
  const int number_size = std::max(style.min_text_size, static_cast<int>(std::lround(22 * style.scale)));
  const std::vector<UvChartLabel> anchors = uv_chart_labels(reference, atlas);

  Box3 box;
  for (const auto& t : reference.triangles)
    for (Index v : t) box.add(reference.points[static_cast<std::size_t>(v)]);
  const Vec3 origin = 0.5 * (box.lo + box.hi);
  const Scene scene3d = reference_scene(reference, atlas, origin);
  std::vector<Vec3> points(reference.points.begin(), reference.points.end());
  const int half = layout.view.height / 2;
  for (int row = 0; row < 2; ++row) {
    const PixelRect area{layout.view.x, layout.view.y + row * half, layout.view.width, half};
    const Vec3 direction = row == 0 ? three_quarter_view(options.up) : three_quarter_back_view(options.up);
    const Camera camera = fit_camera_to_points(points, direction, static_cast<double>(area.width) / area.height,
                                               {.up = options.up});
    paste(figure, renderer.render(scene3d, camera, area.width, area.height), area.x, area.y);
    std::vector<UvKeyNumberAnchor> frame;
    for (const auto& [chart, position] : facing_anchors(reference, atlas, direction)) {
      const auto [x, y] = to_pixel(camera, area, position);
      frame.push_back({chart, x, y});
    }
    draw_numbers(figure, place_uv_key_numbers(frame, area, number_size, style), number_size, style);
    draw_text(figure, area.x + number_size / 2, area.y + number_size + 4, row == 0 ? "front" : "back",
              number_size, style);
  }
  // The atlas, framed as the UV error map frames it.
  const PixelRect uv_area{layout.legend.x, layout.view.y, layout.legend.width, layout.view.height};
  const Camera camera = uv_map_camera(static_cast<double>(uv_area.width) / uv_area.height);
  Scene uv_scene = atlas_scene(reference, atlas);
  uv_scene.background = options.background;
  paste(figure, renderer.render(uv_scene, camera, uv_area.width, uv_area.height), uv_area.x, uv_area.y);
  std::vector<UvKeyNumberAnchor> frame;
  for (const UvChartLabel& a : anchors) {
    const auto [x, y] = to_pixel(camera, uv_area, {a.uv[0], a.uv[1], 0.0});
    frame.push_back({a.chart, x, y});
  }
  draw_numbers(figure, place_uv_key_numbers(frame, uv_area, number_size, style), number_size, style);
  return figure;
}

}  // namespace hq
