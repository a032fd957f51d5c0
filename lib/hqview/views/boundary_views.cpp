#include "hqview/views/boundary_views.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <span>

#include "hqview/core/number_format.h"
#include "hqview/image/colormap.h"
#include "hqview/views/inverted_callout.h"
#include "hqview/views/overview_views.h"

namespace hq {
namespace {

// Errors below 0.01% of the diagonal are noise: the scale never goes lower,
// so a boundary that fits reads as white, not as amplified noise.
constexpr double kMinScale = 1e-4;

Rgba8 error_rgba(double e, double scale) { return to_rgba8(diverging_color(e / scale)); }

std::string percent(double v) { return display_number(v, 3); }

// "+10.2 % (1.36)": a signed error in % of the diagonal and in model units.
std::string signed_percent_label(double e, double diagonal) {
  const double pct = diagonal > 0.0 ? 100.0 * e / diagonal : e;
  return (e > 0 ? "+" : "") + percent(pct) + " % (" + (e > 0 ? "+" : "") + percent(e) + ")";
}

// The outward normal of a triangle's plane, times twice its area.
Vec3 area_normal(const std::array<Vec3, 3>& c) { return cross(c[1] - c[0], c[2] - c[0]); }

// Patches as flat triangles (3 vertices each, normals from their planes), coloured by their error.
TriangleSet patch_triangles(const std::vector<BoundaryError::ErrorPatch>& patches, const Vec3& origin, double scale) {
  TriangleSet set;
  set.positions.reserve(3 * patches.size());
  set.colors.reserve(3 * patches.size());
  set.indices.reserve(3 * patches.size());
  for (const auto& p : patches) {
    const Rgba8 color = error_rgba(p.error, scale);
    for (const Vec3& c : p.corners) {
      set.indices.push_back(static_cast<std::uint32_t>(set.positions.size()));
      set.positions.push_back(to_vec3f(c - origin));
      set.colors.push_back(color);
    }
  }
  return set;
}

}  // namespace

// The marker's label: "max |error| +10.2 % (1.36)", right of the ring (left
// when it would leave the view; above or below it when neither side has
// room), on a pale box, inside the view.
void draw_worst_label(Image& figure, const PixelRect& view, double cx, double cy, double radius,
                      const std::string& label, const AnnotationStyle& style) {
  const int size = std::max(style.min_text_size, static_cast<int>(std::lround(20 * style.scale)));
  const PixelRect extent = text_extent(label, size, style);
  const int right = static_cast<int>(std::lround(cx + radius + 6));
  const int left = static_cast<int>(std::lround(cx - radius - 6)) - extent.width;
  int x = right, baseline = static_cast<int>(std::lround(cy + 0.35 * size));
  if (right + extent.width + 4 > view.x + view.width) x = left;
  if (x < view.x + 2) {  // fits neither side: above the ring, else below it
    x = static_cast<int>(std::lround(cx)) - extent.width / 2;
    baseline = static_cast<int>(std::lround(cy - radius - 6));
    if (baseline - size < view.y) baseline = static_cast<int>(std::lround(cy + radius + 6)) + size;
  }
  x = std::max(view.x + 2, std::min(x, view.x + view.width - extent.width - 2));
  // Inside the view (its top row first when the view is smaller than the text).
  const int y = std::max(view.y + size + 2, std::min(baseline, view.y + view.height - 4));
  fill_rect(figure, {x - 3, y - size - 1, extent.width + 6, size + 6}, {255, 255, 255, 230});
  draw_text(figure, x, y, label, size, style);
}

namespace {

// Whether a pixel shows data of the flat view: a dark casing, ring or text
// (its largest channel below 80) or a saturated colour (its channels over
// 30 apart); the page, the pale domain and its thin wireframe do not, even
// where several of its half-transparent edges overlap at a vertex.
bool is_data_pixel(const Image& image, int x, int y) {
  const std::size_t o = pixel_offset(image, x, y);
  const auto [lo, hi] = std::minmax({image.rgba[o], image.rgba[o + 1], image.rgba[o + 2]});
  return hi < 80 || hi - lo > 30;
}

}  // namespace

LabelPlace place_label_in_empty_space(const Image& figure, const PixelRect& view, double cx, double cy, double radius,
                                      int box_w, int box_h, bool far_ok) {
  // Summed-area table of data pixels over the view.
  const int w = view.width, h = view.height;
  std::vector<int> sum(static_cast<std::size_t>(w + 1) * (h + 1), 0);
  const auto at = [&](int x, int y) -> int& { return sum[static_cast<std::size_t>(y) * (w + 1) + x]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      at(x + 1, y + 1) = at(x, y + 1) + at(x + 1, y) - at(x, y) + (is_data_pixel(figure, view.x + x, view.y + y) ? 1 : 0);
  // Whether the leader from the ring's edge to (bx, by) (view pixels) stays
  // off the data: its first pixels beside the ring may touch the ringed
  // line, none after that.
  const double rx = cx - view.x, ry = cy - view.y;
  const auto leader_is_clear = [&](double bx, double by) {
    const double len = std::hypot(bx - rx, by - ry);
    for (double t = radius + 8; t < len; t += 1.0) {
      const int x = static_cast<int>(rx + (bx - rx) * t / len), y = static_cast<int>(ry + (by - ry) * t / len);
      if (x >= 0 && y >= 0 && x < w && y < h && is_data_pixel(figure, view.x + x, view.y + y)) return false;
    }
    return true;
  };
  const auto nearest = [&](double reach) {
    LabelPlace best;
    double best_d = INFINITY;
    for (int y = 0; y + box_h <= h; y += 8)
      for (int x = 0; x + box_w <= w; x += 8) {
        if (at(x + box_w, y + box_h) - at(x, y + box_h) - at(x + box_w, y) + at(x, y) > 0) continue;
        const double nx = std::clamp(rx, double(x), double(x + box_w));
        const double ny = std::clamp(ry, double(y), double(y + box_h));
        const double d = std::hypot(nx - rx, ny - ry);
        if (d < radius + 4 || d >= best_d || d > reach) continue;
        if (d > radius + 24 && !leader_is_clear(nx, ny)) continue;
        best_d = d;
        best = {true, view.x + x, view.y + y, d > radius + 24, view.x + nx, view.y + ny, d <= reach};
      }
    return best;
  };
  const LabelPlace near = nearest(radius + kLabelReach * std::min(w, h));
  if (near.found || !far_ok) return near;
  LabelPlace far = nearest(INFINITY);
  far.near = false;
  return far;
}

namespace {

// The flat view's marker label in empty space (place_label_in_empty_space):
// near its ring on one line, else on two (its polyline's note on the
// second), else the nearest place with a clear leader; a leader line when
// it is not beside the ring; draw_worst_label when no place is found.
void draw_label_in_empty_space(Image& figure, const PixelRect& view, double cx, double cy, double radius,
                               const std::string& label, const AnnotationStyle& style) {
  const int size = std::max(style.min_text_size, static_cast<int>(std::lround(20 * style.scale)));
  std::string text = label;
  const auto place_of = [&](const std::string& t, bool far_ok) {
    const PixelRect extent = text_extent(t, size, style);
    // The pale box and 4 px around.
    return place_label_in_empty_space(figure, view, cx, cy, radius, extent.width + 6 + 8,
                                      std::max(size, extent.height) + 6 + 8, far_ok);
  };
  LabelPlace place = place_of(text, false);
  if (const std::size_t comma = label.rfind(", "); !place.found && comma != std::string::npos) {
    const std::string two = label.substr(0, comma) + "\n" + label.substr(comma + 2);
    if (const LabelPlace p = place_of(two, false); p.found) place = p, text = two;
  }
  if (!place.found) place = place_of(text, true);
  if (!place.found) {
    draw_worst_label(figure, view, cx, cy, radius, label, style);
    return;
  }
  const PixelRect extent = text_extent(text, size, style);
  const int x = place.x + 7, baseline = place.y + 4 + size + 1;
  if (place.leader) {
    const double len = std::hypot(place.leader_x - cx, place.leader_y - cy);
    draw_line(figure, cx + (place.leader_x - cx) * radius / len, cy + (place.leader_y - cy) * radius / len,
              place.leader_x, place.leader_y, kWorstMarkerColor, std::max(1.5, 2.0 * style.scale));
  }
  fill_rect(figure, {x - 3, baseline - size - 1, extent.width + 6, std::max(size, extent.height) + 6},
            {255, 255, 255, 230});
  draw_text(figure, x, baseline, text, size, style);
}

// An error figure: the scene through the frame's camera, the shared colour
// bar with the marks' entries, a ring on each mark (the samples of largest
// |error|, or the planar figure's two extremes), then their labels (so no
// label lies on a later ring).
Image render_error_figure(Scene scene, const ErrorFigureFrame& frame, std::span<const WorstError> marks,
                          const BoundaryError& error, Renderer& renderer, const BoundaryViewOptions& options,
                          bool label_in_empty_space = false) {
  scene.background = options.background;
  Image figure = render_figure(renderer, scene, frame.camera, options.width, options.height, frame.layout,
                               options.title, frame.style);
  draw_color_bar(figure, frame.layout.legend, frame.bar, frame.style);
  struct Ring {
    double cx, cy;
    bool facing;
    const WorstError* mark;
  };
  std::vector<Ring> rings;
  const double radius = std::max(8.0, 22.0 * frame.style.scale), thickness = std::max(2.0, 4.0 * frame.style.scale);
  for (const WorstError& worst : marks) {
    if (!worst.found) continue;
    const double aspect = static_cast<double>(frame.layout.view.width) / frame.layout.view.height;
    const Vec3 ndc = project_to_ndc(frame.camera, aspect, worst.position);
    if (!std::isfinite(ndc.x) || std::abs(ndc.x) > 1.0 || std::abs(ndc.y) > 1.0) continue;
    const double cx = frame.layout.view.x + 0.5 * (ndc.x + 1.0) * frame.layout.view.width;
    const double cy = frame.layout.view.y + 0.5 * (1.0 - ndc.y) * frame.layout.view.height;
    // A planar figure (labels in empty space) has no far side: its marks'
    // normals follow the file's winding (an L-shaped Gmsh plate's inside
    // extreme read ", far side", dashed).
    const bool facing = label_in_empty_space || dot(worst.normal, frame.camera.eye - worst.position) >= 0.0;
    // Solid when the sample faces the camera, dashed when it lies on the far side.
    draw_marker_ring(figure, cx, cy, radius, thickness, !facing, kWorstMarkerColor);
    rings.push_back({cx, cy, facing, &worst});
  }
  for (const Ring& r : rings)
    (label_in_empty_space ? draw_label_in_empty_space : draw_worst_label)(
        figure, frame.layout.view, r.cx, r.cy, radius,
        r.mark->what + " " + signed_percent_label(r.mark->error, error.reference_bbox_diagonal) +
            (r.facing ? "" : ", far side") + r.mark->note,
        frame.style);
  return figure;
}

}  // namespace

double error_scale(const std::vector<double>& field) {
  std::vector<double> magnitudes;
  for (double e : field)
    if (std::isfinite(e)) magnitudes.push_back(std::abs(e));
  if (magnitudes.empty()) return 1.0;
  const auto at = magnitudes.begin() + static_cast<std::ptrdiff_t>(0.98 * static_cast<double>(magnitudes.size() - 1));
  std::nth_element(magnitudes.begin(), at, magnitudes.end());
  const double s = *at;
  return s > 0.0 ? s : 1.0;
}

double boundary_error_scale(const BoundaryError& error) {
  std::vector<std::pair<double, double>> magnitudes;  // (|error|, area)
  double total = 0.0;
  for (const auto* patches : {&error.mesh_patches, &error.reference_patches})
    for (const auto& p : *patches)
      if (std::isfinite(p.error) && p.area > 0.0) {
        magnitudes.push_back({std::abs(p.error), p.area});
        total += p.area;
      }
  if (magnitudes.empty()) return 1.0;
  std::sort(magnitudes.begin(), magnitudes.end());
  double cumulative = 0.0, s = magnitudes.back().first;
  for (const auto& [m, a] : magnitudes) {
    cumulative += a;
    if (cumulative >= 0.98 * total) {
      s = m;
      break;
    }
  }
  s = std::max(s, kMinScale * error.reference_bbox_diagonal);
  return s > 0.0 ? s : 1.0;
}

double nice_tick_step(double top) {
  if (!(top > 0.0) || !std::isfinite(top)) return 1.0;
  const double raw = 0.5 * top;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * power <= raw * (1.0 + 1e-9)) step = m * power;
  return step;
}

ColorBar error_color_bar(double scale, double diagonal, std::string_view mesh_word) {
  ColorBar bar;
  // D: the reference's axis-aligned box diagonal (its pose in the file sets it).
  bar.label = "signed error, + = " + std::string(mesh_word) + " outside\n% of D (model units)\nD = " + percent(diagonal) +
              ": the reference's\naxis-aligned box diagonal";
  const double top = diagonal > 0.0 ? 100.0 * scale / diagonal : scale;
  const double units_per_percent = top > 0.0 ? scale / top : 1.0;
  bar.min_value = -top;
  bar.max_value = top;
  for (int i = 0; i <= 32; ++i) bar.colors.push_back(diverging_color(-1.0 + i / 16.0));
  // The ends (the scale's exact half-range; beyond it the end colour), then
  // round ticks at multiples of nice_tick_step, none within 8 % of an end.
  bar.ticks.push_back({-top, "<= " + percent(-top) + " (" + percent(-scale) + ")"});
  const double step = nice_tick_step(top);
  const int n = static_cast<int>(std::floor(top / step + 1e-9));
  for (int i = -n; i <= n; ++i) {
    const double v = i * step;
    if (std::abs(v) > 0.92 * top) continue;
    bar.ticks.push_back({v, i == 0 ? std::string("0") : percent(v) + " (" + percent(v * units_per_percent) + ")"});
  }
  bar.ticks.push_back({top, ">= " + percent(top) + " (" + percent(scale) + ")"});
  return bar;
}

WorstError worst_error(const std::vector<BoundaryError::ErrorPatch>& patches, std::span<const Vec3> points,
                       std::span<const double> point_error, int sign) {
  // How bad an error is for this sign; -1 when it does not count.
  const auto badness = [sign](double e) {
    if (!std::isfinite(e)) return -1.0;
    if (sign == 0) return std::abs(e);
    return sign * e > 0.0 ? sign * e : -1.0;
  };
  WorstError w;
  double worst = -1.0;
  for (const auto& p : patches)
    if (badness(p.error) > worst) {
      worst = badness(p.error);
      w = {(p.corners[0] + p.corners[1] + p.corners[2]) / 3.0, area_normal(p.corners), p.error, true, {}};
    }
  std::size_t best_point = points.size();
  const std::size_t n = std::min(points.size(), point_error.size());
  for (std::size_t i = 0; i < n; ++i)
    if (badness(point_error[i]) > worst) {
      worst = badness(point_error[i]);
      w = {points[i], Vec3{}, point_error[i], true, {}};
      best_point = i;
    }
  if (best_point < points.size()) {  // a vertex: the summed normals of the patches around it
    for (const auto& p : patches)
      for (const Vec3& c : p.corners)
        if (c.x == w.position.x && c.y == w.position.y && c.z == w.position.z) w.normal = w.normal + area_normal(p.corners);
  }
  return w;
}

ErrorFigureFrame error_figure_frame(const std::vector<Vec3>& points, const BoundaryError& error, double scale,
                                   const WorstError& worst, const Vec3& view_direction,
                                   const BoundaryViewOptions& options, std::vector<ColorBarSwatch> swatches) {
  ErrorFigureFrame f;
  f.style = annotation_style_for(options.text_height > 0 ? options.text_height : options.height);
  f.style.background = options.background;
  f.bar = error_color_bar(scale, error.reference_bbox_diagonal, options.mesh_word);
  f.bar.swatches = std::move(swatches);
  if (worst.found)
    f.bar.swatches.push_back({to_color(kWorstMarkerColor),
                              "ring: " + worst.what + " " +
                                  signed_percent_label(worst.error, error.reference_bbox_diagonal) + worst.note,
                              SwatchShape::solid_ring});
  f.layout = figure_layout(options.width, options.height, !options.title.empty(), color_bar_width(f.bar, f.style),
                           f.style);
  const double aspect = static_cast<double>(f.layout.view.width) / f.layout.view.height;
  f.camera = fit_camera_to_points(points, view_direction, aspect,
                                  {.up = options.up, .is_perspective = !options.orthographic});
  return f;
}

WorstError worst_mesh_error(const HexMesh& mesh, const Topology& topology, const BoundaryError& error) {
  std::vector<Vec3> points;
  std::vector<double> values;
  for (Index v : topology.boundary_vertices)
    if (static_cast<std::size_t>(v) < error.vertex_error.size()) {
      points.push_back(mesh.points[static_cast<std::size_t>(v)]);
      values.push_back(error.vertex_error[static_cast<std::size_t>(v)]);
    }
  return worst_error(error.mesh_patches, points, values);
}

Scene build_boundary_error_scene(const HexMesh& mesh, const Topology& topology, const BoundaryError& error,
                                 double scale) {
  // The overview's boundary edges; the faces are the sampled patches.
  OverviewOptions overview;
  std::vector<double> dummy(mesh.points.size(), 1.0);
  Scene scene = build_quality_overview_scene(mesh, topology, dummy, overview);
  scene.triangles.at(0) = patch_triangles(error.mesh_patches, scene.origin, scale);
  for (Rgba8& c : scene.lines.at(0).colors) c.a = 60;
  return scene;
}

Image render_boundary_error_view(const HexMesh& mesh, const Topology& topology, const BoundaryError& error,
                                 const Vec3& view_direction, const BoundaryViewOptions& options, Renderer& renderer) {
  const double scale = boundary_error_scale(error);
  const std::vector<Vec3> points = boundary_points(mesh, topology);
  const WorstError worst = worst_mesh_error(mesh, topology, error);
  return render_error_figure(build_boundary_error_scene(mesh, topology, error, scale),
                             error_figure_frame(points, error, scale, worst, view_direction, options), {&worst, 1},
                             error, renderer, options);
}

Scene build_reference_error_scene(const BoundaryError& error, double scale) {
  Scene scene;
  scene.origin = 0.5 * (error.reference_bbox_min + error.reference_bbox_max);
  scene.triangles.push_back(patch_triangles(error.reference_patches, scene.origin, scale));
  return scene;
}

Image render_reference_error_view(const TriSurface& reference, const BoundaryError& error, const Vec3& view_direction,
                                  const BoundaryViewOptions& options, Renderer& renderer) {
  const double scale = boundary_error_scale(error);
  std::vector<Vec3> points;
  points.reserve(3 * error.reference_patches.size());
  for (const auto& p : error.reference_patches) points.insert(points.end(), p.corners.begin(), p.corners.end());
  const WorstError worst = worst_error(error.reference_patches, reference.points, error.reference_vertex_error);
  return render_error_figure(build_reference_error_scene(error, scale),
                             error_figure_frame(points, error, scale, worst, view_direction, options), {&worst, 1},
                             error, renderer, options);
}

Scene build_reference_overlay_scene(const HexMesh& mesh, const Topology& topology, const TriSurface& reference) {
  OverviewOptions overview;
  std::vector<double> dummy(mesh.points.size(), 1.0);
  Scene scene = build_quality_overview_scene(mesh, topology, dummy, overview);
  scene.triangles.at(0).scalars.clear();  // plain grey, not the quality map
  for (Rgba8& c : scene.triangles.at(0).colors) c = {214, 214, 218, 255};
  for (Rgba8& c : scene.lines.at(0).colors) c = {50, 50, 60, 150};
  TriangleSet surface;
  for (const Vec3& p : reference.points) {
    surface.positions.push_back(to_vec3f(p - scene.origin));
    surface.colors.push_back(kReferenceOverlayColor);
  }
  for (const auto& t : reference.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    for (Index v : t) surface.indices.push_back(static_cast<std::uint32_t>(v));
  }
  scene.translucent.push_back(std::move(surface));
  return scene;
}

Image render_reference_overlay(const HexMesh& mesh, const Topology& topology, const TriSurface& reference,
                               const Vec3& view_direction, const BoundaryViewOptions& options, Renderer& renderer) {
  AnnotationStyle style = annotation_style_for(options.height);
  style.background = options.background;
  const FigureLayout layout = figure_layout(options.width, options.height, !options.title.empty(), 0, style);
  Scene scene = build_reference_overlay_scene(mesh, topology, reference);
  scene.background = options.background;
  std::vector<Vec3> points = boundary_points(mesh, topology);
  points.insert(points.end(), reference.points.begin(), reference.points.end());
  const double aspect = static_cast<double>(layout.view.width) / layout.view.height;
  const Camera camera = fit_camera_to_points(points, view_direction, aspect, {.up = options.up});
  Image figure = render_figure(renderer, scene, camera, options.width, options.height, layout, options.title, style);
  return figure;
}

namespace {

// The sampled pieces of a planar polyline (flat triangles (a, midpoint, b))
// as line segments coloured by their errors (or all `casing`, when set),
// moved by `lift`.
LineSet patch_segments(const std::vector<BoundaryError::ErrorPatch>& patches, const Vec3& origin, const Vec3& lift,
                       double scale, float width, std::optional<Rgba8> casing = std::nullopt) {
  LineSet set;
  set.width = width;
  for (const auto& p : patches) {
    const Rgba8 color = casing ? *casing : error_rgba(p.error, scale);
    for (const Vec3& c : {p.corners[0], p.corners[2]}) {
      set.indices.push_back(static_cast<std::uint32_t>(set.positions.size()));
      set.positions.push_back(to_vec3f(c + lift - origin));
      set.colors.push_back(color);
    }
  }
  return set;
}

// `lines` as strokes in the plane (normal n) `radius` (model units) either
// side of each piece: a band across the piece (GL's wide lines are as wide
// as asked only along x or y: a diagonal one is 0.71 times as wide) and a
// disc at both ends (round caps and joins), in the piece's colours.
void append_round_strokes(const LineSet& lines, const Vec3& n, double radius, TriangleSet& strokes) {
  constexpr int kSides = 16;
  const auto push = [&](const Vec3f& c, const Vec3& d, Rgba8 color) {
    strokes.positions.push_back(
        {c.x + static_cast<float>(d.x), c.y + static_cast<float>(d.y), c.z + static_cast<float>(d.z)});
    strokes.colors.push_back(color);
    return static_cast<std::uint32_t>(strokes.positions.size() - 1);
  };
  for (std::size_t i = 0; i + 1 < lines.indices.size(); i += 2) {
    const Vec3f& a = lines.positions[lines.indices[i]];
    const Vec3f& b = lines.positions[lines.indices[i + 1]];
    const Vec3 side = cross(n, Vec3{b.x - a.x, b.y - a.y, b.z - a.z});
    if (!(norm(side) > 0.0)) continue;
    const Vec3 d = (radius / norm(side)) * side;
    const Rgba8 ca = lines.colors[lines.indices[i]], cb = lines.colors[lines.indices[i + 1]];
    const std::uint32_t q0 = push(a, -1.0 * d, ca), q1 = push(b, -1.0 * d, cb), q2 = push(b, d, cb), q3 = push(a, d, ca);
    strokes.indices.insert(strokes.indices.end(), {q0, q1, q2, q0, q2, q3});
  }
  Vec3 u = cross(n, std::abs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0});
  u = (radius / norm(u)) * u;
  const Vec3 v = (radius / norm(n)) * cross(n, (1.0 / radius) * u);
  for (std::size_t i = 0; i < lines.positions.size(); ++i) {
    const std::uint32_t centre = push(lines.positions[i], Vec3{}, lines.colors[i]);
    for (int k = 0; k < kSides; ++k) {
      const double t = 2.0 * M_PI * k / kSides;
      push(lines.positions[i], std::cos(t) * u + std::sin(t) * v, lines.colors[i]);
      strokes.indices.insert(strokes.indices.end(), {centre, centre + 1 + k, centre + 1 + (k + 1) % kSides});
    }
  }
}

}  // namespace

Scene build_planar_boundary_error_scene(const HexMesh& mesh, const Topology& topology, const TriSurface& reference,
                                        const BoundaryError& error, double scale, double pixel) {
  Scene scene;
  scene.origin = 0.5 * (error.reference_bbox_min + error.reference_bbox_max);
  const Vec3 step = (1e-3 * error.reference_bbox_diagonal) * error.plane_normal;  // towards the camera
  TriangleSet domain;
  for (const Vec3& p : reference.points) {
    domain.positions.push_back(to_vec3f(p - scene.origin));
    domain.normals.push_back(to_vec3f(error.plane_normal));
    domain.colors.push_back(kPlanarDomainColor);
  }
  for (const auto& t : reference.triangles)
    for (Index v : t) domain.indices.push_back(static_cast<std::uint32_t>(v));
  scene.triangles.push_back(std::move(domain));
  LineSet edges;
  for (const auto& e : topology.surface.edges)
    for (Index v : e) {
      edges.indices.push_back(static_cast<std::uint32_t>(edges.positions.size()));
      edges.positions.push_back(to_vec3f(mesh.points[static_cast<std::size_t>(v)] + step - scene.origin));
      edges.colors.push_back(kPlanarEdgeColor);
    }
  scene.lines.push_back(std::move(edges));
  double lift = 2.0;
  for (const auto& [patches, width] : {std::pair{&error.mesh_patches, kPlanarBoundaryWidth},
                                       std::pair{&error.reference_patches, kPlanarOutlineWidth}}) {
    scene.lines.push_back(
        patch_segments(*patches, scene.origin, lift * step, scale, width + kPlanarCasing, kPlanarCasingColor));
    scene.lines.push_back(patch_segments(*patches, scene.origin, (lift + 1.0) * step, scale, width));
    lift += 2.0;
  }
  if (pixel > 0.0) {
    TriangleSet strokes;
    strokes.is_lit = false;
    for (std::size_t k = 1; k < scene.lines.size(); ++k)
      append_round_strokes(scene.lines[k], error.plane_normal, 0.5 * scene.lines[k].width * pixel, strokes);
    scene.triangles.push_back(std::move(strokes));
  }
  return scene;
}

namespace {

// The worse of the mesh's (its boundary pieces and vertices) and the
// outline's by worst_error's sign (ties: the mesh's), noted with its polyline.
WorstError planar_worst(const HexMesh& mesh, const BoundaryError& error, int sign) {
  std::vector<Vec3> points;
  std::vector<double> values;
  for (std::size_t v = 0; v < error.vertex_error.size(); ++v)
    if (std::isfinite(error.vertex_error[v])) {
      points.push_back(mesh.points[v]);
      values.push_back(error.vertex_error[v]);
    }
  WorstError w = worst_error(error.mesh_patches, points, values, sign);
  w.note = ", mesh boundary";
  WorstError outline =
      worst_error(error.reference_patches, error.reference_outline.points, error.outline_vertex_error, sign);
  const auto badness = [sign](double e) { return sign == 0 ? std::abs(e) : sign * e; };
  if (outline.found && (!w.found || badness(outline.error) > badness(w.error))) {
    w = outline;
    w.note = ", reference outline";
  }
  return w;
}

}  // namespace

WorstError worst_planar_error(const HexMesh& mesh, const BoundaryError& error) { return planar_worst(mesh, error, 0); }

std::vector<WorstError> planar_extremes(const HexMesh& mesh, const BoundaryError& error) {
  std::vector<WorstError> marks;
  for (const int sign : {1, -1}) {
    WorstError w = planar_worst(mesh, error, sign);
    w.what = sign > 0 ? "max outside" : "max inside";
    // An extreme within the on-surface tolerance is the noise the length
    // shares count as "on" (a straight edge's +9e-08 on an untuned plate was
    // ringed as its max outside): no ring.
    if (w.found && sign * w.error > error.on_surface_tolerance) marks.push_back(std::move(w));
  }
  return marks;
}

PlanarErrorFigure planar_error_figure(const HexMesh& mesh, const BoundaryError& error,
                                      const BoundaryViewOptions& options) {
  const double scale = boundary_error_scale(error);
  std::vector<Vec3> points = error.reference_outline.points;
  for (const auto& p : error.mesh_patches) points.insert(points.end(), p.corners.begin(), p.corners.end());
  BoundaryViewOptions flat = options;
  flat.orthographic = true;
  // Each line as it is drawn: a white core (error 0) on its casing; the
  // edges over the domain (their colour blended as the figure blends it).
  const auto cased = [](float width) {
    return SwatchStroke{.width = width, .halo_width = width + kPlanarCasing, .halo = kPlanarCasingColor};
  };
  const double a = kPlanarEdgeColor.a / 255.0;
  const auto over_domain = [a](std::uint8_t edge, std::uint8_t domain) {
    return static_cast<std::uint8_t>(std::lround(a * edge + (1.0 - a) * domain));
  };
  const Rgba8 edge{over_domain(kPlanarEdgeColor.r, kPlanarDomainColor.r),
                   over_domain(kPlanarEdgeColor.g, kPlanarDomainColor.g),
                   over_domain(kPlanarEdgeColor.b, kPlanarDomainColor.b), 255};
  const Color white = to_color(Rgba8{255, 255, 255, 255});
  std::vector<ColorBarSwatch> swatches{
      {white, "thick: mesh boundary (core: its error)", SwatchShape::thick_line, cased(kPlanarBoundaryWidth)},
      {white, "thin: reference outline (its error)", SwatchShape::line, cased(kPlanarOutlineWidth)},
      {to_color(edge), "grey: mesh edges", SwatchShape::line, SwatchStroke{.width = 1.0}},
      {to_color(kPlanarDomainColor), "reference domain", SwatchShape::box}};
  PlanarErrorFigure f;
  f.marks = planar_extremes(mesh, error);
  // One legend line for both rings (their full values are by the rings):
  // a line each pushed the legend's last line below boundary.html's first
  // screen (the 47j review).
  std::string rings;
  for (const WorstError& w : f.marks)
    rings += (rings.empty() ? "" : ", ") + w.what + (w.error > 0 ? " +" : " ") +
             percent(error.reference_bbox_diagonal > 0 ? 100.0 * w.error / error.reference_bbox_diagonal : w.error) +
             " %";
  if (!rings.empty())
    swatches.push_back({to_color(kWorstMarkerColor), (f.marks.size() > 1 ? "rings: " : "ring: ") + rings,
                        SwatchShape::solid_ring});
  const Vec3 direction = -1.0 * error.plane_normal;
  const auto frame = [&](const BoundaryViewOptions& o) {
    ErrorFigureFrame e = error_figure_frame(points, error, scale, WorstError{}, direction, o, swatches);
    e.bar.max_bar_height = static_cast<int>(std::lround(options.height / 3.0));
    return e;
  };
  f.frame = frame(flat);
  f.options = flat;
  // The domain's box in the view; the height it needs with the margin beside it.
  const PixelRect& view = f.frame.layout.view;
  const double aspect = static_cast<double>(view.width) / view.height;
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (const Vec3& p : points) {
    const Vec3 ndc = project_to_ndc(f.frame.camera, aspect, p);
    x0 = std::min(x0, ndc.x), x1 = std::max(x1, ndc.x), y0 = std::min(y0, ndc.y), y1 = std::max(y1, ndc.y);
  }
  if (!(x1 > x0) || !(y1 > y0)) return f;
  // Room for a label line above and below the domain (draw_label_in_empty_space's box).
  const int label = std::max(f.frame.style.min_text_size, static_cast<int>(std::lround(20 * f.frame.style.scale))) + 14;
  const double needed = 0.5 * (y1 - y0) * view.height + (1.0 - 0.5 * (x1 - x0)) * view.width + 2 * label;
  const int legend = color_bar_height(f.frame.bar, f.frame.style, 1 << 20);
  const int height = std::max(options.height - static_cast<int>(std::floor(view.height - needed)),
                              f.frame.layout.legend.y + legend + static_cast<int>(std::lround(20 * f.frame.style.scale)));
  if (height >= options.height) return f;
  flat.height = height;
  flat.text_height = options.text_height > 0 ? options.text_height : options.height;
  f.frame = frame(flat);
  f.options = flat;
  return f;
}

Image render_planar_boundary_error_view(const HexMesh& mesh, const Topology& topology, const TriSurface& reference,
                                        const BoundaryError& error, const BoundaryViewOptions& options,
                                        Renderer& renderer) {
  const double scale = boundary_error_scale(error);
  const PlanarErrorFigure f = planar_error_figure(mesh, error, options);
  const double pixel = f.frame.camera.ortho_height / f.frame.layout.view.height;
  return render_error_figure(build_planar_boundary_error_scene(mesh, topology, reference, error, scale, pixel),
                             f.frame, f.marks, error, renderer, f.options, true);
}

Scene build_uv_error_scene(const TriSurface& reference, const UvAtlas& atlas, const std::vector<double>& point_error,
                           double scale) {
  Scene scene;
  scene.origin = {0.5, 0.5, 0.0};
  TriangleSet map;
  map.is_lit = false;
  const std::vector<double> corner = uv_corner_values(reference, point_error);
  const std::size_t n = std::min(atlas.uvs.size() / 3, reference.triangles.size());
  for (std::size_t t = 0; t < n; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const Uv& uv = atlas.uvs[3 * t + k];
      map.indices.push_back(static_cast<std::uint32_t>(map.positions.size()));
      map.positions.push_back({static_cast<float>(uv[0] - 0.5), static_cast<float>(uv[1] - 0.5), 0.0f});
      map.colors.push_back(error_rgba(corner[3 * t + k], scale));
    }
  // Chart outlines: an edge is inside a chart when two triangles of that chart share it.
  std::map<std::pair<Index, Index>, std::vector<std::size_t>> edge_uses;
  for (std::size_t t = 0; t < n; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const Index a = reference.triangles[t][k], b = reference.triangles[t][(k + 1) % 3];
      edge_uses[{std::min(a, b), std::max(a, b)}].push_back(3 * t + k);
    }
  LineSet outlines;
  outlines.width = 1.0f;
  for (const auto& [edge, uses] : edge_uses)
    for (std::size_t use : uses) {
      const std::size_t t = use / 3;
      bool inside = false;
      for (std::size_t other : uses)
        if (other != use && atlas.triangle_chart[other / 3] == atlas.triangle_chart[t]) inside = true;
      if (inside) continue;
      for (std::size_t k : {use % 3, (use % 3 + 1) % 3}) {
        const Uv& uv = atlas.uvs[3 * t + k];
        outlines.indices.push_back(static_cast<std::uint32_t>(outlines.positions.size()));
        outlines.positions.push_back({static_cast<float>(uv[0] - 0.5), static_cast<float>(uv[1] - 0.5), 0.0f});
        outlines.colors.push_back({50, 50, 56, 200});
      }
    }
  scene.triangles.push_back(std::move(map));
  scene.lines.push_back(std::move(outlines));
  return scene;
}

Camera uv_map_camera(double aspect) {
  Camera camera;
  camera.eye = {0.5, 0.5, 2.0};
  camera.target = {0.5, 0.5, 0.0};
  camera.up = {0.0, 1.0, 0.0};
  camera.is_perspective = false;
  camera.near_plane = 0.5;
  camera.far_plane = 4.0;
  camera.ortho_height = 1.06 * std::max(1.0, 1.0 / aspect);
  return camera;
}

Image render_uv_error_map(const TriSurface& reference, const UvAtlas& atlas, const BoundaryError& error,
                          const BoundaryViewOptions& options, Renderer& renderer) {
  AnnotationStyle style = annotation_style_for(options.height);
  style.background = options.background;
  const double scale = boundary_error_scale(error);
  const ColorBar bar = error_color_bar(scale, error.reference_bbox_diagonal, options.mesh_word);
  const FigureLayout layout =
      figure_layout(options.width, options.height, !options.title.empty(), color_bar_width(bar, style), style);
  Scene scene = build_uv_error_scene(reference, atlas, error.reference_vertex_error, scale);
  scene.background = options.background;
  const Camera camera = uv_map_camera(static_cast<double>(layout.view.width) / layout.view.height);
  Image figure = render_figure(renderer, scene, camera, options.width, options.height, layout, options.title, style);
  draw_color_bar(figure, layout.legend, bar, style);
  return figure;
}

}  // namespace hq
