#include "hqview/views/boundary_views.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "hqview/core/number_format.h"
#include "hqview/image/colormap.h"
#include "hqview/views/overview_views.h"

namespace hq {
namespace {

// Errors below 0.01% of the diagonal are noise: the scale never goes lower,
// so a boundary that fits reads as white, not as amplified noise.
constexpr double kMinScale = 1e-4;

Rgba8 error_rgba(double e, double scale) { return to_rgba8(diverging_color(e / scale)); }

std::string percent(double v) { return display_number(v, 3); }

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

ColorBar error_color_bar(double scale, double diagonal) {
  ColorBar bar;
  bar.label = "signed error\n(% of diagonal)\n+ = hex outside";
  const double top = diagonal > 0.0 ? 100.0 * scale / diagonal : scale;
  bar.min_value = -top;
  bar.max_value = top;
  for (int i = 0; i <= 32; ++i) bar.colors.push_back(diverging_color(-1.0 + i / 16.0));
  for (double t : {-1.0, -0.5, 0.0, 0.5, 1.0})
    bar.ticks.push_back({t * top, (t == -1.0 ? "<= " : t == 1.0 ? ">= " : "") + percent(t * top)});
  return bar;
}

Scene build_boundary_error_scene(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_error,
                                 double scale) {
  // The overview's geometry (faces as 4-triangle fans, boundary edges), recoloured.
  OverviewOptions overview;
  std::vector<double> dummy(mesh.points.size(), 1.0);
  Scene scene = build_quality_overview_scene(mesh, topology, dummy, overview);
  TriangleSet& faces = scene.triangles.at(0);
  std::size_t k = 0;
  for (Index face : topology.boundary_faces) {
    const Quad& quad = topology.faces[static_cast<std::size_t>(face)];
    double sum = 0.0;
    int n = 0;
    for (int i = 0; i < 4; ++i) {
      const double e = vertex_error[static_cast<std::size_t>(quad[i])];
      faces.colors[k + static_cast<std::size_t>(i)] = error_rgba(e, scale);
      if (std::isfinite(e)) {
        sum += e;
        ++n;
      }
    }
    faces.colors[k + 4] = error_rgba(n ? sum / n : std::nan(""), scale);
    k += 5;
  }
  for (Rgba8& c : scene.lines.at(0).colors) c.a = 60;
  return scene;
}

Image render_boundary_error_view(const HexMesh& mesh, const Topology& topology, const BoundaryError& error,
                                 const Vec3& view_direction, const BoundaryViewOptions& options, Renderer& renderer) {
  AnnotationStyle style = annotation_style_for(options.height);
  style.background = options.background;
  const double scale = std::max(error_scale(error.vertex_error), kMinScale * error.reference_bbox_diagonal);
  const ColorBar bar = error_color_bar(scale, error.reference_bbox_diagonal);
  const FigureLayout layout =
      figure_layout(options.width, options.height, !options.title.empty(), color_bar_width(bar, style), style);
  Scene scene = build_boundary_error_scene(mesh, topology, error.vertex_error, scale);
  scene.background = options.background;
  const double aspect = static_cast<double>(layout.view.width) / layout.view.height;
  const Camera camera = fit_camera_to_points(boundary_points(mesh, topology), view_direction, aspect, {.up = options.up});
  Image figure = render_figure(renderer, scene, camera, options.width, options.height, layout, options.title, style);
  draw_color_bar(figure, layout.legend, bar, style);
  return figure;
}

Scene build_reference_overlay_scene(const HexMesh& mesh, const Topology& topology, const TriSurface& reference) {
  OverviewOptions overview;
  std::vector<double> dummy(mesh.points.size(), 1.0);
  Scene scene = build_quality_overview_scene(mesh, topology, dummy, overview);
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
  const double scale = std::max(error_scale(error.reference_vertex_error), kMinScale * error.reference_bbox_diagonal);
  const ColorBar bar = error_color_bar(scale, error.reference_bbox_diagonal);
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
