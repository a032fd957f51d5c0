#include "hqview/views/error_density_views.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "hqview/core/box3.h"
#include "hqview/core/error.h"
#include "hqview/core/hex_topology.h"
#include "hqview/image/colormap.h"
#include "hqview/quality/hex_metrics.h"
#include "hqview/render/upright.h"
#include "hqview/views/main_views.h"
#include "hqview/views/overview_views.h"

namespace hq {
namespace {

constexpr Rgba8 kVeilColor{176, 182, 194, 56};       // the translucent boundary of the cells figure
constexpr Rgba8 kBoundaryEdgeColor{40, 40, 46, 70};  // faint boundary edges over the colours
constexpr Rgba8 kCellEdgeColor{30, 30, 36, 255};     // edges of the drawn cells
constexpr double kFovY = 30.0;

const Vec3& point(const HexMesh& mesh, Index v) { return mesh.points[static_cast<std::size_t>(v)]; }

bool is_positive(double d) { return std::isfinite(d) && d > 0; }

Index face_hex(const Topology& topology, Index face) {
  return topology.face_hexes[static_cast<std::size_t>(topology.face_hex_offsets[static_cast<std::size_t>(face)])];
}

void check_sizes(const HexMesh& mesh, std::span<const double> field, const char* what) {
  if (field.size() != mesh.hexes.size())
    throw Error(std::string(what) + " has " + std::to_string(field.size()) + " values for " +
                std::to_string(mesh.hexes.size()) + " hexes");
}

// The hexes in the densest `fraction` (at least one), ascending ids.
std::vector<Index> densest_hexes(std::span<const double> density, double fraction) {
  std::vector<Index> order;
  for (std::size_t h = 0; h < density.size(); ++h)
    if (is_positive(density[h])) order.push_back(static_cast<Index>(h));
  if (order.empty()) return order;
  const auto keep = std::max<std::size_t>(1, static_cast<std::size_t>(fraction * static_cast<double>(order.size())));
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) {
    return density[static_cast<std::size_t>(a)] > density[static_cast<std::size_t>(b)];
  });
  order.resize(std::min(keep, order.size()));
  std::sort(order.begin(), order.end());
  return order;
}

Vec3 hex_center(const HexMesh& mesh, Index h) {
  Vec3 c;
  for (Index v : mesh.hexes[static_cast<std::size_t>(h)]) c = c + point(mesh, v) / 8.0;
  return c;
}

struct Figure {
  AnnotationStyle style;
  ColorBar bar;
  FigureLayout layout;
  Camera camera;
  Scene scene;
};

Figure begin_figure(const HexMesh& mesh, const Topology& topology, const ErrorDensityScale& scale,
                    const Vec3& view_direction, const ErrorDensityViewOptions& options) {
  if (options.width <= 0 || options.height <= 0)
    throw RenderError("error density view size must be positive, got " + std::to_string(options.width) + "x" +
                      std::to_string(options.height));
  Figure f;
  f.style = annotation_style_for(options.height);
  f.style.background = options.background;
  f.bar = error_density_color_bar(scale);
  f.layout = figure_layout(options.width, options.height, !options.title.empty(), color_bar_width(f.bar, f.style),
                           f.style);
  const double aspect = static_cast<double>(f.layout.view.width) / std::max(1, f.layout.view.height);
  f.camera = fit_camera_to_points(boundary_points(mesh, topology), view_direction, aspect,
                                  {.up = options.up, .fov_y_degrees = kFovY, .is_perspective = false});
  const Box3 box = boundary_bounding_box(mesh, topology);
  f.scene.origin = 0.5 * (box.lo + box.hi);
  f.scene.background = options.background;
  return f;
}

Image finish_figure(Figure& f, const ErrorDensityViewOptions& options, Renderer& renderer, Camera* camera,
                    PixelRect* view) {
  Image figure = render_figure(renderer, f.scene, f.camera, options.width, options.height, f.layout, options.title,
                               f.style);
  draw_color_bar(figure, f.layout.legend, f.bar, f.style);
  if (camera) *camera = f.camera;
  if (view) *view = f.layout.view;
  return figure;
}

// Quads as two flat triangles each, one colour per quad.
void add_quad(TriangleSet& set, const HexMesh& mesh, const Vec3& origin, const std::array<Index, 4>& q, Rgba8 color) {
  const auto base = static_cast<std::uint32_t>(set.positions.size());
  for (Index v : q) {
    set.positions.push_back(to_vec3f(point(mesh, v) - origin));
    set.colors.push_back(color);
  }
  for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) set.indices.push_back(base + i);
}

LineSet boundary_edge_lines(const HexMesh& mesh, const Topology& topology, const Vec3& origin, Rgba8 color,
                            float width) {
  LineSet lines;
  lines.width = width;
  for (const Edge& e : boundary_edges(topology))
    for (Index v : e) {
      lines.indices.push_back(static_cast<std::uint32_t>(lines.positions.size()));
      lines.positions.push_back(to_vec3f(point(mesh, v) - origin));
      lines.colors.push_back(color);
    }
  return lines;
}

}  // namespace

ErrorDensityScale error_density_scale(std::span<const double> density) {
  std::vector<double> values;
  for (double d : density)
    if (is_positive(d)) values.push_back(d);
  ErrorDensityScale s;
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  s.hi = values.back();
  s.lo = std::max(values[static_cast<std::size_t>(0.01 * static_cast<double>(values.size() - 1))], s.hi * 1e-4);
  if (!(s.hi > s.lo)) s.lo = s.hi / 10.0;
  return s;
}

Color error_density_color(double density, const ErrorDensityScale& scale) {
  if (!is_positive(density)) return kUndefinedColor;
  const double t = (std::log10(density) - std::log10(scale.lo)) / (std::log10(scale.hi) - std::log10(scale.lo));
  return sample_quality_map(1.0 - std::clamp(t, 0.0, 1.0));
}

ColorBar error_density_color_bar(const ErrorDensityScale& scale) {
  ColorBar bar;
  bar.label = "FEM error density\n(H1 error / a-priori\nh\u00b2|D\u00b2u|\u00b2, no unit; log)";
  bar.min_value = std::log10(scale.lo);
  bar.max_value = std::log10(scale.hi);
  for (int i = 0; i <= 32; ++i)
    bar.colors.push_back(error_density_color(std::pow(10.0, bar.min_value + (bar.max_value - bar.min_value) * i / 32.0),
                                             scale));
  const auto label = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2g", v);
    return std::string(text);
  };
  bar.ticks.push_back({bar.min_value, label(scale.lo)});
  const double span = bar.max_value - bar.min_value;
  for (int k = static_cast<int>(std::ceil(bar.min_value)); k <= static_cast<int>(std::floor(bar.max_value)); ++k)
    // Decades not crowding an end's label.
    if (k - bar.min_value > 0.08 * span && bar.max_value - k > 0.08 * span)
      bar.ticks.push_back({static_cast<double>(k), label(std::pow(10.0, k))});
  bar.ticks.push_back({bar.max_value, label(scale.hi) + " (max)"});
  bar.swatches = {{kUndefinedColor, "undefined"}};
  return bar;
}

std::vector<Index> error_density_cells(std::span<const double> cell_scaled_jacobian, std::span<const double> density,
                                       const ErrorDensityViewOptions& options) {
  std::vector<char> chosen(density.size(), 0);
  for (std::size_t h = 0; h < density.size() && h < cell_scaled_jacobian.size(); ++h) {
    const double s = cell_scaled_jacobian[h];
    if (s < options.quality_threshold || is_verdict_sentinel(s)) chosen[h] = 1;
  }
  for (Index h : densest_hexes(density, options.densest_fraction)) chosen[static_cast<std::size_t>(h)] = 1;
  std::vector<Index> cells;
  for (std::size_t h = 0; h < chosen.size(); ++h)
    if (chosen[h]) cells.push_back(static_cast<Index>(h));
  return cells;
}

Vec3 choose_error_density_viewpoint(const HexMesh& mesh, const Topology& topology, std::span<const double> density,
                                    const ErrorDensityViewOptions& options) {
  std::vector<Vec3> centers;
  std::vector<double> radii;
  for (Index h : densest_hexes(density, options.densest_fraction)) {
    centers.push_back(hex_center(mesh, h));
    const Hex& hex = mesh.hexes[static_cast<std::size_t>(h)];
    radii.push_back(0.5 * norm(point(mesh, hex[6]) - point(mesh, hex[0])));
  }
  const FigureLayout layout = figure_layout(options.width, options.height, !options.title.empty(),
                                            color_bar_width(error_density_color_bar({}), annotation_style_for(options.height)),
                                            annotation_style_for(options.height));
  const double aspect = static_cast<double>(layout.view.width) / std::max(1, layout.view.height);
  return choose_viewpoints(boundary_points(mesh, topology), centers, radii, aspect, 1, options.up, kFovY).front();
}

Image render_error_density_boundary(const HexMesh& mesh, const Topology& topology, std::span<const double> density,
                                    const Vec3& view_direction, const ErrorDensityViewOptions& options,
                                    Renderer& renderer, Camera* camera, PixelRect* view) {
  check_sizes(mesh, density, "error density");
  const ErrorDensityScale scale = error_density_scale(density);
  Figure f = begin_figure(mesh, topology, scale, view_direction, options);
  TriangleSet faces;
  for (Index face : topology.boundary_faces)
    add_quad(faces, mesh, f.scene.origin, topology.faces[static_cast<std::size_t>(face)],
             to_rgba8(error_density_color(density[static_cast<std::size_t>(face_hex(topology, face))], scale)));
  f.scene.triangles.push_back(std::move(faces));
  f.scene.lines.push_back(boundary_edge_lines(mesh, topology, f.scene.origin, kBoundaryEdgeColor,
                                              static_cast<float>(std::max(1.0, f.style.scale))));
  return finish_figure(f, options, renderer, camera, view);
}

Image render_error_density_cells(const HexMesh& mesh, const Topology& topology, std::span<const double> density,
                                 std::span<const double> cell_scaled_jacobian, const Vec3& view_direction,
                                 const ErrorDensityViewOptions& options, Renderer& renderer, Camera* camera,
                                 PixelRect* view) {
  check_sizes(mesh, density, "error density");
  check_sizes(mesh, cell_scaled_jacobian, "cell scaled Jacobian");
  const ErrorDensityScale scale = error_density_scale(density);
  Figure f = begin_figure(mesh, topology, scale, view_direction, options);
  TriangleSet veil;
  for (Index face : topology.boundary_faces)
    add_quad(veil, mesh, f.scene.origin, topology.faces[static_cast<std::size_t>(face)], kVeilColor);
  f.scene.translucent.push_back(std::move(veil));
  TriangleSet cells;
  LineSet edges;
  edges.width = static_cast<float>(std::max(1.0, f.style.scale));
  for (Index h : error_density_cells(cell_scaled_jacobian, density, options)) {
    const Hex& hex = mesh.hexes[static_cast<std::size_t>(h)];
    const Rgba8 color = to_rgba8(error_density_color(density[static_cast<std::size_t>(h)], scale));
    for (const auto& face : kHexFaces)
      add_quad(cells, mesh, f.scene.origin, {hex[face[0]], hex[face[1]], hex[face[2]], hex[face[3]]}, color);
    for (const auto& e : kHexEdges)
      for (int c : e) {
        edges.indices.push_back(static_cast<std::uint32_t>(edges.positions.size()));
        edges.positions.push_back(to_vec3f(point(mesh, hex[c]) - f.scene.origin));
        edges.colors.push_back(kCellEdgeColor);
      }
  }
  f.scene.triangles.push_back(std::move(cells));
  f.scene.lines.push_back(std::move(edges));
  return finish_figure(f, options, renderer, camera, view);
}

}  // namespace hq
