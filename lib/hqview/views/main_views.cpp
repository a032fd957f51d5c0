#include "hqview/views/main_views.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <numeric>

#include "hqview/core/error.h"
#include "hqview/core/number_format.h"
#include "hqview/image/colormap.h"
#include "hqview/render/annotate.h"
#include "hqview/render/scene_shapes.h"
#include "hqview/views/overview_views.h"

namespace hq {
namespace {

Vec3 forward_of(const Camera& camera) { return normalized(camera.target - camera.eye); }

// Model units per output pixel at distance depth in front of the camera.
double units_per_pixel(const Camera& camera, double depth, int view_height) {
  const double height =
      camera.is_perspective ? 2.0 * depth * std::tan(0.5 * camera.fov_y_degrees * M_PI / 180.0) : camera.ortho_height;
  return height / std::max(1, view_height);
}

// A line set of the given edges, vertices renumbered compactly; colour per edge.
LineSet edge_lines(const HexMesh& mesh, const Vec3& origin, const std::vector<Edge>& edges,
                   const std::vector<Rgba8>& edge_colors, float width) {
  LineSet lines;
  lines.width = width;
  lines.positions.reserve(2 * edges.size());
  lines.colors.reserve(2 * edges.size());
  lines.indices.reserve(2 * edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (Index v : edges[i]) {
      lines.indices.push_back(static_cast<std::uint32_t>(lines.positions.size()));
      lines.positions.push_back(to_vec3f(mesh.points[static_cast<std::size_t>(v)] - origin));
      lines.colors.push_back(edge_colors[i]);
    }
  return lines;
}

// Median on-screen length of a line set's segments, in pixels.
double median_edge_pixels(const LineSet& lines, const Vec3& origin, const Camera& camera, int width, int height) {
  if (lines.indices.empty()) return 0.0;
  const Mat4 to_ndc =
      projection_matrix(camera, static_cast<double>(width) / height) * view_matrix(camera) * translation_matrix(origin);
  std::vector<double> lengths;
  // A sample is enough for a median: every 7th segment of large sets.
  const std::size_t step = lines.indices.size() > 20000 ? 14 : 2;
  for (std::size_t i = 0; i + 1 < lines.indices.size(); i += step) {
    const Vec3f& a = lines.positions[lines.indices[i]];
    const Vec3f& b = lines.positions[lines.indices[i + 1]];
    const Vec3 pa = transform_point(to_ndc, {a.x, a.y, a.z}), pb = transform_point(to_ndc, {b.x, b.y, b.z});
    lengths.push_back(std::hypot(0.5 * (pa.x - pb.x) * width, 0.5 * (pa.y - pb.y) * height));
  }
  const auto middle = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), middle, lengths.end());
  return *middle;
}

}  // namespace

std::string viewpoint_name(const Vec3& d, const Vec3& up) {
  const double elevation = view_elevation_degrees(d, up);
  if (elevation > 89.5) return "straight above";
  if (elevation < -89.5) return "straight below";
  const long azimuth = std::lround(view_azimuth_degrees(d, up));
  return "azimuth " + std::to_string(azimuth < 0 ? azimuth + 360 : azimuth) + ", elevation " +
         std::to_string(std::lround(elevation)) + " deg";
}

double glyph_coverage(std::span<const Vec3> centers, std::span<const double> radii, const Camera& camera,
                      double aspect) {
  const int gw = std::max(8, static_cast<int>(std::lround(std::sqrt(40000.0 * aspect))));
  const int gh = std::max(8, static_cast<int>(std::lround(40000.0 / gw)));
  std::vector<char> covered(static_cast<std::size_t>(gw) * static_cast<std::size_t>(gh), 0);
  const Vec3 forward = forward_of(camera);
  const Mat4 projection = projection_matrix(camera, aspect);
  const Mat4 to_ndc = projection * view_matrix(camera);  // project_to_ndc's, made once
  for (std::size_t i = 0; i < centers.size(); ++i) {
    const double depth = dot(centers[i] - camera.eye, forward);
    if (camera.is_perspective && depth <= 0.0) continue;
    const Vec3 ndc = transform_point(to_ndc, centers[i]);
    if (!std::isfinite(ndc.x) || !std::isfinite(ndc.y)) continue;
    const double scale = camera.is_perspective ? 1.0 / depth : 2.0 / camera.ortho_height;
    const double rx = radii[i] * (camera.is_perspective ? projection(0, 0) * scale : scale / aspect);
    const double ry = radii[i] * (camera.is_perspective ? projection(1, 1) * scale : scale);
    // NDC to grid cells.
    const double cx = 0.5 * (ndc.x + 1.0) * gw, cy = 0.5 * (ndc.y + 1.0) * gh;
    const double px = 0.5 * rx * gw, py = 0.5 * ry * gh;
    const int x0 = std::max(0, static_cast<int>(std::floor(cx - px))), x1 = std::min(gw - 1, static_cast<int>(cx + px));
    const int y0 = std::max(0, static_cast<int>(std::floor(cy - py))), y1 = std::min(gh - 1, static_cast<int>(cy + py));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double dx = (x + 0.5 - cx) / std::max(px, 1e-12), dy = (y + 0.5 - cy) / std::max(py, 1e-12);
        if (dx * dx + dy * dy <= 1.0) covered[static_cast<std::size_t>(y) * gw + x] = 1;
      }
  }
  const auto n = std::count(covered.begin(), covered.end(), 1);
  return static_cast<double>(n) / static_cast<double>(covered.size());
}

std::vector<Vec3> main_view_points(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs) {
  std::vector<Vec3> points = boundary_points(mesh, topology);
  for (const AggregatedGlyph& g : glyphs.clusters)
    for (int axis = 0; axis < 3; ++axis)
      for (double s : {-1.0, 1.0}) {
        Vec3 p = g.position;
        (axis == 0 ? p.x : axis == 1 ? p.y : p.z) += s * g.radius;
        points.push_back(p);
      }
  return points;
}

std::vector<Vec3> choose_main_viewpoints(std::span<const Vec3> points, const GlyphResult& glyphs, double aspect,
                                         int count, const Vec3& up, double fov_y_degrees) {
  std::vector<Vec3> centers;
  std::vector<double> radii;
  for (const AggregatedGlyph& g : glyphs.clusters) {
    centers.push_back(g.position);
    radii.push_back(g.radius);
  }
  return choose_viewpoints(points, centers, radii, aspect, count, up, fov_y_degrees);
}

namespace {

// Visible sphere area in model units (the covered fraction of the view's
// area) from each direction: independent of how tightly the view frames
// the mesh, so a view along a long mesh's axis does not win by zooming in.
std::vector<double> visible_sphere_areas(std::span<const Vec3> directions, std::span<const Vec3> points,
                                         std::span<const Vec3> centers, std::span<const double> radii,
                                         double aspect, const Vec3& up, double fov_y_degrees) {
  std::vector<double> score(directions.size());
  // One task a direction (each score on its own: the same for any thread count).
  tbb::parallel_for(std::size_t{0}, directions.size(), [&](std::size_t i) {
    const Camera camera = fit_camera_to_points(
        points, directions[i], aspect, {.up = up, .fov_y_degrees = fov_y_degrees, .is_perspective = false});
    score[i] = glyph_coverage(centers, radii, camera, aspect) * camera.ortho_height * camera.ortho_height * aspect;
  });
  return score;
}

// The azimuth difference of two directions, degrees in [0, 180].
double azimuth_gap(const Vec3& a, const Vec3& b, const Vec3& up) {
  const double gap = std::abs(view_azimuth_degrees(a, up) - view_azimuth_degrees(b, up));
  return gap > 180.0 ? 360.0 - gap : gap;
}

}  // namespace

std::vector<Vec3> choose_viewpoints(std::span<const Vec3> points, std::span<const Vec3> centers,
                                    std::span<const double> radii, double aspect, int count, const Vec3& up,
                                    double fov_y_degrees) {
  if (count <= 0) return {};
  std::vector<Vec3> candidates = upright_view_candidates(up);
  std::vector<double> score;
  if (!centers.empty()) {
    score = visible_sphere_areas(candidates, points, centers, radii, aspect, up, fov_y_degrees);
    // Views from below only when no upright view shows a sphere.
    if (*std::max_element(score.begin(), score.end()) <= 0.0) {
      candidates = below_view_candidates(up);
      score = visible_sphere_areas(candidates, points, centers, radii, aspect, up, fov_y_degrees);
    }
  }
  if (score.empty() || *std::max_element(score.begin(), score.end()) <= 0.0) {
    // Nothing to aim at: the three-quarter view and the one behind it.
    std::vector<Vec3> chosen{three_quarter_view(up), three_quarter_back_view(up)};
    chosen.resize(static_cast<std::size_t>(std::min(count, 2)));
    return chosen;
  }
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return score[a] > score[b]; });
  // Each further view looks from at least 90 degrees of azimuth away from
  // those chosen (the other side of the model), while such a view remains.
  std::vector<Vec3> chosen{candidates[order[0]]};
  std::vector<bool> taken(candidates.size(), false);
  taken[order[0]] = true;
  while (static_cast<int>(chosen.size()) < count) {
    std::size_t pick = candidates.size();
    for (std::size_t i : order) {
      if (taken[i]) continue;
      const bool apart = std::all_of(chosen.begin(), chosen.end(),
                                     [&](const Vec3& c) { return azimuth_gap(candidates[i], c, up) >= 90.0 - 1e-9; });
      if (apart) {
        pick = i;
        break;
      }
    }
    if (pick == candidates.size())  // none far enough: the best one left
      for (std::size_t i : order)
        if (!taken[i]) {
          pick = i;
          break;
        }
    if (pick == candidates.size()) break;
    taken[pick] = true;
    chosen.push_back(candidates[pick]);
  }
  return chosen;
}

std::vector<ScreenMarker> merge_markers_on_screen(std::span<const OverlapMarker> markers, const Camera& camera,
                                                  int view_height, double min_pixels) {
  std::vector<ScreenMarker> drawn;
  const Vec3 forward = forward_of(camera);
  const Vec3 right = normalized(cross(forward, camera.up));
  const Vec3 up = cross(right, forward);
  // Screen position in pixels (any origin: only differences matter).
  auto screen = [&](const Vec3& p) {
    const Vec3 q = p - camera.eye;
    const double unit = units_per_pixel(camera, std::max(dot(q, forward), 1e-12), view_height);
    return std::array<double, 2>{dot(q, right) / unit, dot(q, up) / unit};
  };
  // Anchors in a grid of min_pixels cells: a closer anchor is in one of the
  // 3x3 cells around a marker's cell.
  const double cell = std::max(min_pixels, 1e-9);
  auto cell_of = [&](double v) { return static_cast<std::int64_t>(std::floor(v / cell)); };
  std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::size_t>> grid;
  std::vector<std::array<double, 2>> anchors;
  for (const OverlapMarker& m : markers) {
    const std::array<double, 2> s = screen(m.position);
    std::size_t best = drawn.size();
    if (min_pixels > 0.0 && std::isfinite(s[0]) && std::isfinite(s[1])) {
      const std::int64_t cx = cell_of(s[0]), cy = cell_of(s[1]);
      for (std::int64_t dx = -1; dx <= 1; ++dx)
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          const auto it = grid.find({cx + dx, cy + dy});
          if (it == grid.end()) continue;
          for (std::size_t g : it->second)
            if (g < best && std::hypot(anchors[g][0] - s[0], anchors[g][1] - s[1]) < min_pixels) best = g;
        }
    }
    if (best == drawn.size()) {
      drawn.push_back({m.position, 0, 0, 0});
      anchors.push_back(s);
      if (std::isfinite(s[0]) && std::isfinite(s[1])) grid[{cell_of(s[0]), cell_of(s[1])}].push_back(best);
    }
    ScreenMarker& d = drawn[best];
    (m.kind == MarkerKind::coincident ? d.coincident : d.intersections) += std::max<Index>(m.count, 1);
    ++d.members;
  }
  return drawn;
}

std::vector<std::uint8_t> worst_cluster_vertices(const GlyphResult& glyphs, int per_cluster) {
  std::vector<std::uint8_t> marked(glyphs.vertex_cluster.size(), 0);
  std::vector<Index> members;
  for (std::size_t c = 0; c + 1 < glyphs.cluster_offsets.size(); ++c) {
    members.assign(glyphs.cluster_vertices.begin() + glyphs.cluster_offsets[c],
                   glyphs.cluster_vertices.begin() + glyphs.cluster_offsets[c + 1]);
    const auto keep = std::min<std::size_t>(members.size(), static_cast<std::size_t>(std::max(per_cluster, 0)));
    auto radius = [&](Index v) {
      const std::size_t i = static_cast<std::size_t>(v);
      return i < glyphs.vertex_radius.size() ? glyphs.vertex_radius[i] : 0.0;
    };
    std::partial_sort(members.begin(), members.begin() + static_cast<std::ptrdiff_t>(keep), members.end(),
                      [&](Index a, Index b) { return radius(a) != radius(b) ? radius(a) > radius(b) : a < b; });
    for (std::size_t i = 0; i < keep; ++i) marked[static_cast<std::size_t>(members[i])] = 1;
  }
  return marked;
}

Scene build_main_scene(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs,
                       const OverlapReport* overlap, const Camera& camera, int view_height,
                       const MainViewOptions& options) {
  if (glyphs.vertex_cluster.size() != mesh.points.size())
    throw Error("glyph result does not match the mesh (" + std::to_string(glyphs.vertex_cluster.size()) + " vs " +
                std::to_string(mesh.points.size()) + " vertices)");
  const Box3 box = boundary_bounding_box(mesh, topology);
  Scene scene;
  scene.origin = 0.5 * (box.lo + box.hi);
  scene.background = options.background;
  auto local = [&](const Vec3& p) { return to_vec3f(p - scene.origin); };

  // 1. Boundary wireframe.
  const std::vector<Edge> wire = boundary_edges(topology);
  scene.lines.push_back(
      edge_lines(mesh, scene.origin, wire, std::vector<Rgba8>(wire.size(), kWireframeColor), options.wire_width));

  // 2. Cluster edges: around each cluster's worst vertices only (a cluster
  // of thousands of vertices would paint over the model), in its colour.
  const std::int64_t top = glyphs.options.top_clusters;
  const std::vector<std::uint8_t> marked = worst_cluster_vertices(glyphs, options.cluster_edge_vertices);
  std::vector<Edge> cluster_edges;
  std::vector<Rgba8> cluster_colors;
  for (const Edge& e : topology.edges) {
    const bool ma = marked[static_cast<std::size_t>(e[0])] != 0, mb = marked[static_cast<std::size_t>(e[1])] != 0;
    if (!ma && !mb) continue;
    const Index ca = ma ? glyphs.vertex_cluster[static_cast<std::size_t>(e[0])] : kNoIndex;
    const Index cb = mb ? glyphs.vertex_cluster[static_cast<std::size_t>(e[1])] : kNoIndex;
    const Index c = ca == kNoIndex ? cb : (cb == kNoIndex ? ca : std::min(ca, cb));
    cluster_edges.push_back(e);
    cluster_colors.push_back(to_rgba8(cluster_color(c, top)));
  }
  scene.lines.push_back(edge_lines(mesh, scene.origin, cluster_edges, cluster_colors, options.cluster_edge_width));

  // 3. Intersecting cells: translucent faces and their edges.
  TriangleSet cells;
  std::vector<Edge> cell_edges;
  if (overlap && overlap->cell_intersecting.size() == mesh.hexes.size()) {
    for (std::size_t c = 0; c < mesh.hexes.size(); ++c) {
      if (!overlap->cell_intersecting[c]) continue;
      for (int f = 0; f < 6; ++f) {
        const Quad& quad = topology.faces[static_cast<std::size_t>(topology.hex_faces[6 * c + f])];
        const auto base = static_cast<std::uint32_t>(cells.positions.size());
        for (int i = 0; i < 4; ++i) {
          cells.positions.push_back(local(mesh.points[static_cast<std::size_t>(quad[i])]));
          cells.colors.push_back(kIntersectingCellColor);
          const Index a = quad[i], b = quad[(i + 1) % 4];
          cell_edges.push_back({std::min(a, b), std::max(a, b)});
        }
        cells.indices.insert(cells.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
      }
    }
    std::sort(cell_edges.begin(), cell_edges.end());
    cell_edges.erase(std::unique(cell_edges.begin(), cell_edges.end()), cell_edges.end());
  }
  scene.lines.push_back(
      edge_lines(mesh, scene.origin, cell_edges, std::vector<Rgba8>(cell_edges.size(), kIntersectionArrowColor), 1.5f));

  // 4. Aggregated glyphs.
  SphereSet spheres;
  for (const AggregatedGlyph& g : glyphs.clusters) {
    if (!(g.radius > 0.0)) continue;
    spheres.centers.push_back(local(g.position));
    spheres.radii.push_back(static_cast<float>(g.radius));
    spheres.colors.push_back(to_rgba8(cluster_color(g.id, top)));
  }
  scene.spheres.push_back(std::move(spheres));

  // 5. Arrows on overlap markers, merged where they crowd on screen.
  TriangleSet arrows;
  if (overlap) {
    const Vec3 forward = forward_of(camera);
    for (const ScreenMarker& marker : merge_markers_on_screen(overlap->markers, camera, view_height,
                                                              options.marker_merge_pixels * options.pixel_scale)) {
      const Index total = std::max<Index>(1, marker.count());
      const int n = std::clamp<int>(static_cast<int>(total), 1, std::max(1, options.max_arrows_per_marker));
      // Coincident arrows first: their share of n, at least one when any.
      int num_coincident = 0;
      if (marker.intersections == 0)
        num_coincident = n;
      else if (marker.coincident > 0)
        num_coincident = std::clamp(
            static_cast<int>(std::lround(static_cast<double>(n) * static_cast<double>(marker.coincident) / total)), 1,
            std::max(1, n - 1));
      const double depth = std::max(dot(marker.position - camera.eye, forward), 1e-12);
      const double unit = units_per_pixel(camera, depth, view_height) * options.pixel_scale;
      const ArrowShape shape{static_cast<float>(2.2 * unit), static_cast<float>(6.5 * unit),
                             static_cast<float>(20.0 * unit), 16};
      int k = 0;
      for (const Vec3& d : arrow_directions(camera, n, options.arrow_start_degrees)) {
        const Rgba8 color = k++ < num_coincident ? kCoincidentArrowColor : kIntersectionArrowColor;
        const Vec3 tip = marker.position - 3.0 * unit * d;
        const Vec3 tail = tip - options.arrow_pixels * unit * d;
        append_arrow(arrows, local(tail), local(tip), shape, color);
      }
    }
  }
  scene.overlay.push_back(std::move(arrows));
  scene.translucent.push_back(std::move(cells));
  return scene;
}

namespace {

FigureLayout main_layout(const MainViewOptions& options, const AnnotationStyle& style) {
  const int legend_width = static_cast<int>(std::lround(340 * style.scale));
  return figure_layout(options.width, options.height, !options.title.empty(), legend_width, style);
}

}  // namespace

double main_view_aspect(const MainViewOptions& options) {
  const FigureLayout layout = main_layout(options, annotation_style_for(options.height));
  return static_cast<double>(std::max(1, layout.view.width)) / std::max(1, layout.view.height);
}

namespace {

// Rank labels next to the worst clusters' glyphs.
void draw_rank_labels(Image& figure, const GlyphResult& glyphs, const Camera& camera, const FigureLayout& layout,
                      const AnnotationStyle& style) {
  const double aspect = static_cast<double>(layout.view.width) / static_cast<double>(layout.view.height);
  const int label_size = std::max(11, static_cast<int>(std::lround(20 * style.scale)));
  const std::size_t num_labels = std::min<std::size_t>(
      glyphs.clusters.size(), static_cast<std::size_t>(labelled_cluster_count(glyphs.options.top_clusters)));
  std::vector<PixelRect> placed;  // labels never overlap: a later (better-ranked first) one is skipped
  for (std::size_t i = 0; i < num_labels; ++i) {
    const AggregatedGlyph& g = glyphs.clusters[i];
    const Vec3 ndc = project_to_ndc(camera, aspect, g.position);
    if (!std::isfinite(ndc.x) || std::abs(ndc.x) > 1.0 || std::abs(ndc.y) > 1.0) continue;
    const double depth = dot(g.position - camera.eye, forward_of(camera));
    const double r_px = g.radius / units_per_pixel(camera, depth, layout.view.height);
    const int x =
        layout.view.x + static_cast<int>(std::lround(0.5 * (ndc.x + 1.0) * layout.view.width + 0.75 * r_px + 3));
    const int y = layout.view.y + static_cast<int>(std::lround(0.5 * (1.0 - ndc.y) * layout.view.height - 0.75 * r_px));
    const std::string label = "#" + std::to_string(g.id);
    const PixelRect extent = text_extent(label, label_size, style);
    const PixelRect box{x - 2, y - extent.height - 2, extent.width + 4, extent.height + 4};
    const bool overlaps = std::any_of(placed.begin(), placed.end(), [&](const PixelRect& r) {
      return box.x < r.x + r.width && r.x < box.x + box.width && box.y < r.y + r.height && r.y < box.y + box.height;
    });
    if (overlaps) continue;
    placed.push_back(box);
    draw_text(figure, x, y, label, label_size, style);
  }
}

// Counts on merged (or over-full) overlap markers, right of the marker
// below the first arrow (which starts at 45 degrees, up and right).
void draw_marker_counts(Image& figure, const OverlapReport& overlap, const Camera& camera, const FigureLayout& layout,
                        const AnnotationStyle& style, const MainViewOptions& scaled) {
  const double aspect = static_cast<double>(layout.view.width) / static_cast<double>(layout.view.height);
  const int count_size = std::max(10, static_cast<int>(std::lround(18 * style.scale)));
  AnnotationStyle count_style = style;
  for (const ScreenMarker& marker : merge_markers_on_screen(overlap.markers, camera, layout.view.height,
                                                            scaled.marker_merge_pixels * scaled.pixel_scale)) {
    if (marker.members < 2 && marker.count() <= scaled.max_arrows_per_marker) continue;
    count_style.text_color = marker.intersections > 0 ? kIntersectionArrowColor : kCoincidentArrowColor;
    const Vec3 ndc = project_to_ndc(camera, aspect, marker.position);
    if (!std::isfinite(ndc.x) || std::abs(ndc.x) > 1.0 || std::abs(ndc.y) > 1.0) continue;
    const int x = layout.view.x + static_cast<int>(std::lround(0.5 * (ndc.x + 1.0) * layout.view.width + 6));
    const int y = layout.view.y + static_cast<int>(std::lround(0.5 * (1.0 - ndc.y) * layout.view.height)) + count_size;
    // On a pale box: the label sits among arrow shafts and cells.
    const std::string label = "x" + std::to_string(marker.count());
    const PixelRect extent = text_extent(label, count_size, count_style);
    Rgba8 halo = scaled.background;
    halo.a = 255;
    fill_rect(figure, {x - 2, y - count_size - 1, extent.width + 4, count_size + 5}, halo);
    draw_text(figure, x, y, label, count_size, count_style);
  }
}

// Legend: what each colour means (draw_legend shrinks it to the panel).
void draw_main_legend(Image& figure, const GlyphResult& glyphs, const OverlapReport* overlap,
                      const FigureLayout& layout, const AnnotationStyle& style, const MainViewOptions& options) {
  const std::size_t listed = std::min<std::size_t>(
      glyphs.clusters.size(), static_cast<std::size_t>(labelled_cluster_count(glyphs.options.top_clusters)));
  std::vector<LegendLine> lines{{std::nullopt, "glyphs: worst clusters"}};
  for (std::size_t i = 0; i < listed; ++i) {
    const AggregatedGlyph& g = glyphs.clusters[i];
    lines.push_back({to_rgba8(cluster_color(g.id, glyphs.options.top_clusters)),
                     "#" + std::to_string(g.id) + "  " + std::to_string(g.size) + (g.size == 1 ? " vertex" : " vertices") +
                         ", min " + display_number(g.min_quality, 3)});
  }
  if (glyphs.clusters.size() > listed) {
    const std::size_t rest = glyphs.clusters.size() - listed;
    lines.push_back({to_rgba8(neutral_cluster_color()), std::to_string(rest) + (rest == 1 ? " other cluster" : " other clusters")});
  }
  if (glyphs.clusters.empty()) lines.push_back({options.background, "none (no vertex below threshold)"});
  lines.push_back({std::nullopt, "size = 1 - min quality", 1});
  const std::size_t coincident = overlap ? overlap->coincident_groups.size() : 0;
  const std::size_t intersecting = overlap ? static_cast<std::size_t>(overlap->num_intersecting_cells) : 0;
  const std::size_t intersections =
      overlap ? overlap->markers.size() - std::min(overlap->markers.size(), coincident) : 0;
  const std::string unchecked = overlap ? "" : " (not checked)";
  lines.push_back({kCoincidentArrowColor, "coincident vertices: " + std::to_string(coincident) + unchecked, 1});
  lines.push_back({kIntersectionArrowColor, "intersections: " + std::to_string(intersections) + unchecked});
  lines.push_back({kIntersectingCellColor, "intersecting cells: " + std::to_string(intersecting) + unchecked});
  lines.push_back({kWireframeColor, "boundary edges"});
  draw_legend(figure, layout.legend, lines, style);
}

}  // namespace

Image render_main_view(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs,
                       const OverlapReport* overlap, const Vec3& view_direction, const MainViewOptions& options,
                       Renderer& renderer) {
  if (options.width <= 0 || options.height <= 0)
    throw RenderError("main view size must be positive, got " + std::to_string(options.width) + "x" +
                      std::to_string(options.height));
  AnnotationStyle style = annotation_style_for(options.height);
  style.background = options.background;
  const FigureLayout layout = main_layout(options, style);
  const double aspect = static_cast<double>(layout.view.width) / static_cast<double>(layout.view.height);
  const std::vector<Vec3> points = main_view_points(mesh, topology, glyphs);
  const Camera camera = fit_camera_to_points(
      points, view_direction, aspect, {.up = options.up, .fov_y_degrees = options.fov_y_degrees, .is_perspective = false});

  MainViewOptions scaled = options;
  scaled.pixel_scale = style.scale;
  Scene scene = build_main_scene(mesh, topology, glyphs, overlap, camera, layout.view.height, scaled);
  // The wireframe fades when dense on screen, so glyphs and clusters stay readable.
  const double pixels = median_edge_pixels(scene.lines[0], scene.origin, camera, layout.view.width, layout.view.height);
  const double opacity = std::clamp(pixels / 10.0, 0.2, 0.85);
  for (Rgba8& c : scene.lines[0].colors) c.a = static_cast<std::uint8_t>(std::lround(255.0 * opacity));

  Image figure = render_figure(renderer, scene, camera, options.width, options.height, layout, options.title, style);

  draw_rank_labels(figure, glyphs, camera, layout, style);
  if (overlap) draw_marker_counts(figure, *overlap, camera, layout, style, scaled);
  draw_main_legend(figure, glyphs, overlap, layout, style, options);
  return figure;
}

}  // namespace hq
