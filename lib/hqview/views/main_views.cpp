#include "hqview/views/main_views.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <iterator>
#include <utility>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <numeric>
#include <set>

#include "hqview/core/error.h"
#include "hqview/core/number_format.h"
#include "hqview/core/text.h"
#include "hqview/image/colormap.h"
#include "hqview/mesh/boundary_polygons.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/render/annotate.h"
#include "hqview/render/scene_shapes.h"
#include "hqview/views/overview_views.h"
#include "hqview/views/overview_viewpoint.h"
#include "hqview/views/surface_views.h"

namespace hq {
namespace {

Vec3 forward_of(const Camera& camera) { return normalized(camera.target - camera.eye); }

// The id of #0's rings as an obstacle of its own label (no glyph's, no fan's).
constexpr std::int64_t kRingsObstacleId = -2;
// A surface mesh's inverted face (MainViewOptions::label_free_centres): no
// label box on it, any leader across it.
constexpr std::int64_t kFaceObstacleId = -3;

// Whether an id of main_view_id_image is a line's (any edge).
bool is_line_id(std::uint32_t id) { return id == kIdEdge || id == kIdClusterEdge; }

// Model units per output pixel at distance depth in front of the camera.
double units_per_pixel(const Camera& camera, double depth, int view_height) {
  const double height =
      camera.is_perspective ? 2.0 * depth * std::tan(0.5 * camera.fov_y_degrees * M_PI / 180.0) : camera.ortho_height;
  return height / std::max(1, view_height);
}

}  // namespace

namespace {

// The factors displayed_glyph_scale clamps 1 to: [lo, max(lo, hi)], lo
// the floor's, hi the cap's (none: [1, 1]).
struct GlyphScaleBounds {
  double lo = 1.0, hi = 1.0;
};

GlyphScaleBounds glyph_scale_bounds(const GlyphResult& glyphs, const Camera& camera, int view_height,
                                    double pixel_scale, double model_diagonal_pixels, const GlyphSizeLimits& limits) {
  if (glyphs.clusters.empty() || !(glyphs.clusters[0].radius > 0.0)) return {};
  const AggregatedGlyph& worst = glyphs.clusters[0];
  const double depth = std::max(dot(worst.position - camera.eye, forward_of(camera)), 1e-12);
  const double unit = units_per_pixel(camera, depth, view_height);
  const double pixels = worst.radius / unit;
  if (!(pixels > 0.0) || !std::isfinite(pixels)) return {};
  const double floor = limits.min_pixels * pixel_scale;
  // The cap: a mean edge length (the glyph unit rmax of ratio 1, under the
  // default unit) and a fraction of the model's on-screen diagonal.
  double cap = std::numeric_limits<double>::infinity();
  const double edge = glyphs.options.rmax_unit == RmaxUnit::kMeanEdgeLength && glyphs.options.rmax > 0.0
                          ? glyphs.rmax / glyphs.options.rmax
                          : glyphs.rmax;
  if (edge > 0.0 && std::isfinite(edge)) cap = std::min(cap, limits.max_edges * edge / unit);
  if (model_diagonal_pixels > 0.0) cap = std::min(cap, kWorstGlyphMaxDiagonal * model_diagonal_pixels);
  // #0's radius in pixels: clamp(pixels, floor, max(floor, cap)).
  return {floor / pixels, cap / pixels};
}

double scale_within(const GlyphScaleBounds& b) { return std::clamp(1.0, b.lo, std::max(b.lo, b.hi)); }

}  // namespace

double displayed_glyph_scale(const GlyphResult& glyphs, const Camera& camera, int view_height, double pixel_scale,
                             double model_diagonal_pixels, const GlyphSizeLimits& limits) {
  return scale_within(glyph_scale_bounds(glyphs, camera, view_height, pixel_scale, model_diagonal_pixels, limits));
}

GlyphSizeLimits glyph_size_limits(const MainViewOptions& options) {
  if (!options.surface_cell_quality) return {};
  return {kSurfaceInvertedGlyphMinPixels, kSurfaceInvertedGlyphMaxEdges};
}

namespace {

// The glyph scale a main view draws with: the mesh's (options.glyph_scale) or its own.
double view_glyph_scale(const GlyphResult& glyphs, const Camera& camera, int view_height,
                        const MainViewOptions& options) {
  return options.glyph_scale > 0.0
             ? options.glyph_scale
             : displayed_glyph_scale(glyphs, camera, view_height, options.pixel_scale, options.model_diagonal_pixels,
                                     glyph_size_limits(options));
}

}  // namespace

double model_diagonal_pixels(const HexMesh& mesh, const Topology& topology, const Camera& camera, int view_width,
                             int view_height) {
  const Box3 box = boundary_bounding_box(mesh, topology);
  const double aspect = static_cast<double>(view_width) / static_cast<double>(std::max(1, view_height));
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  for (int k = 0; k < 8; ++k) {
    const Vec3 p{(k & 1) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y, (k & 4) ? box.hi.z : box.lo.z};
    const Vec3 ndc = project_to_ndc(camera, aspect, p);
    const double x = 0.5 * ndc.x * view_width, y = 0.5 * ndc.y * view_height;
    lo[0] = std::min(lo[0], x), hi[0] = std::max(hi[0], x), lo[1] = std::min(lo[1], y), hi[1] = std::max(hi[1], y);
  }
  const double d = std::hypot(hi[0] - lo[0], hi[1] - lo[1]);
  return std::isfinite(d) ? d : 0.0;
}

namespace {

// glyph_tie_classes(glyphs.clusters): given, or computed into storage.
std::span<const Index> tie_classes_of(const GlyphResult& glyphs, std::span<const Index> given,
                                      std::vector<Index>& storage) {
  if (!given.empty() || glyphs.clusters.empty()) return given;
  storage = glyph_tie_classes(glyphs.clusters);
  return storage;
}

// The tie classes wearing a cluster colour (coloured_tie_classes).
Index coloured_classes_of(const GlyphResult& glyphs, std::span<const Index> tie_class) {
  return coloured_tie_classes(tie_class_sizes(tie_class),
                              static_cast<Index>(labelled_cluster_count(glyphs.options.top_clusters)));
}

// Whether view A draws a cluster's glyph grey (unlabelled; scene
// spheres[0]): its tie class is beyond the coloured ones.
bool is_grey_glyph(Index id, std::span<const Index> tie_class, Index coloured) {
  return tie_class[static_cast<std::size_t>(id)] >= coloured;
}

// A glyph's colour in view A: its tie class's (cluster_color by class).
Rgba8 glyph_color(Index id, std::span<const Index> tie_class, Index coloured, const GlyphResult& glyphs) {
  const Index c = tie_class[static_cast<std::size_t>(id)];
  return to_rgba8(cluster_color(c < coloured ? c : -1, glyphs.options.top_clusters));
}

}  // namespace

std::vector<double> displayed_glyph_radii(const GlyphResult& glyphs, double scale) {
  std::vector<double> radii;
  radii.reserve(glyphs.clusters.size());
  for (const AggregatedGlyph& g : glyphs.clusters) radii.push_back(g.radius * scale);
  return radii;
}

Rgba8 pale_grey_glyph_color() { return grey_glyph_color(kGreyGlyphPale); }

bool is_faded_grey_glyph(const AggregatedGlyph& g) { return !(g.min_quality < kUnfadedGlyphQuality); }

Rgba8 grey_glyph_color(float pale) {
  // The sphere shader's steps at the lit side (diffuse 0.8 with ambient
  // 0.25: shade 0.85), in linear RGB, then mixed towards white.
  const Color grey = neutral_cluster_color();
  auto channel = [pale](float v) {
    const double linear = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    const double lit = std::min(1.0, linear * 0.85) * (1.0 - pale) + pale;
    const double srgb = lit <= 0.0031308 ? 12.92 * lit : 1.055 * std::pow(lit, 1.0 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(srgb, 0.0, 1.0)));
  };
  return {channel(grey.r), channel(grey.g), channel(grey.b), 255};
}

GlyphsDrawn main_view_glyphs_drawn(const GlyphResult& glyphs, const Camera& camera, int view_height,
                                   std::span<const double> drawn_radii, std::span<const Index> ties) {
  GlyphsDrawn result;
  result.tie_class = ties.empty() ? glyph_tie_classes(glyphs.clusters) : std::vector<Index>(ties.begin(), ties.end());
  const std::size_t n = glyphs.clusters.size();
  result.drawn.assign(n, 0);
  const Index labelled = result.coloured_classes = coloured_classes_of(glyphs, result.tie_class);
  const Vec3 forward = forward_of(camera);
  const Vec3 right = normalized(cross(forward, camera.up));
  const Vec3 up = cross(right, forward);
  // Screen discs (pixels, image plane) of the glyphs drawn so far, in a
  // uniform grid of cell size = the largest drawn radius (#0's, up to
  // perspective): a disc overlapping another lies in its 3 x 3 cells.
  struct Disc {
    double x, y, r;
  };
  std::vector<Disc> discs(n, Disc{0.0, 0.0, 0.0});
  double largest = 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const AggregatedGlyph& g = glyphs.clusters[i];
    if (!(g.radius > 0.0) || i >= drawn_radii.size()) continue;
    const Vec3 d = g.position - camera.eye;
    const double unit = units_per_pixel(camera, std::max(dot(d, forward), 1e-12), view_height);
    discs[i] = {dot(d, right) / unit, dot(d, up) / unit, drawn_radii[i] / unit};
    if (std::isfinite(discs[i].r)) largest = std::max(largest, discs[i].r);
  }
  std::map<std::pair<long long, long long>, std::vector<std::size_t>> grid;
  auto cell_of = [&](double v) { return static_cast<long long>(std::floor(v / largest)); };
  std::vector<Index> first_of_class;
  for (std::size_t i = 0; i < n; ++i) {
    const AggregatedGlyph& g = glyphs.clusters[i];
    if (!(g.radius > 0.0) || i >= drawn_radii.size()) continue;
    const Disc& d = discs[i];
    if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.r)) continue;
    const Index c = result.tie_class[i];
    // A coloured class is a unit (issue 44 part U): none of its members
    // is left out (30 tied worst glyphs are 30, not 29).
    bool keep = c < labelled;
    if (!keep) {
      int covered = 0;
      const long long cx = cell_of(d.x), cy = cell_of(d.y);
      for (int k = 0; k < kThinSamples; ++k) {
        // Vogel's sunflower: evenly spread over the disc's area.
        const double radius = d.r * std::sqrt((k + 0.5) / kThinSamples);
        const double angle = k * 2.399963229728653;
        const double x = d.x + radius * std::cos(angle), y = d.y + radius * std::sin(angle);
        bool inside = false;
        for (long long gy = cy - 1; gy <= cy + 1 && !inside; ++gy)
          for (long long gx = cx - 1; gx <= cx + 1 && !inside; ++gx) {
            const auto it = grid.find({gx, gy});
            if (it == grid.end()) continue;
            for (std::size_t j : it->second)
              if (std::hypot(x - discs[j].x, y - discs[j].y) < discs[j].r) {
                inside = true;
                break;
              }
          }
        covered += inside ? 1 : 0;
      }
      keep = covered < kThinnedCoverage * kThinSamples;
    }
    if (!keep) {
      ++result.num_left_out;
      if (c < labelled) ++result.num_left_out_coloured;
      continue;
    }
    result.drawn[i] = 1;
    grid[{cell_of(d.x), cell_of(d.y)}].push_back(i);
  }
  return result;
}

Rgba8 cell_kind_edge_color(CellKind kind) {
  // Away from the quality map, the non-conforming brown (46q review Q-M6)
  // and every legend colour of view A (issue 44 part P; main_views.h).
  switch (kind) {
    case CellKind::tet: return {0, 0, 153, 255};      // dark blue
    case CellKind::wedge: return {102, 136, 0, 255};    // olive
    case CellKind::pyramid: return {187, 102, 136, 255};  // dusty rose
    default: return {34, 0, 51, 255};                 // hex: near-black aubergine
  }
}

std::vector<std::pair<Rgba8, std::string>> cell_kind_swatches(std::string_view cell_kinds) {
  std::vector<std::pair<Rgba8, std::string>> out;
  std::string_view rest = cell_kinds;
  if (rest.starts_with("cells: ")) rest.remove_prefix(7);
  while (!rest.empty()) {
    const std::size_t comma = rest.find(", ");
    const std::string_view item = rest.substr(0, comma);
    // "16 pyramid" or "16 pyramid (inside)": the word after the count.
    std::string_view name = item.substr(std::min(item.size(), item.find(' ') + 1));
    name = name.substr(0, name.find(' '));
    for (CellKind kind : kCellKinds)
      if (cell_kind_name(kind) == name) out.push_back({cell_kind_edge_color(kind), std::string(item)});
    rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 2);
  }
  return out;
}

namespace {

// The boundary edges' colours on a mesh of several kinds: each edge in the
// edge colour of the kinds of its boundary faces, the rarer kind winning
// (pyramid, wedge, tet, hex) so that the few pyramids among tets show.
std::vector<Rgba8> boundary_edge_kind_colors(const HexMesh& mesh, const Topology& topology,
                                             const std::vector<Edge>& edges) {
  constexpr std::array<int, 4> kRank = {0, 1, 2, 3};  // hex, tet, wedge, pyramid: higher wins
  std::vector<int> rank(edges.size(), 0);
  const std::array<Index, 5> start = volume_block_starts(mesh);
  for (const BoundaryPolygon& face : boundary_polygons(topology)) {
    int kind = 0;
    while (kind < 3 && face.cell >= start[static_cast<std::size_t>(kind) + 1]) ++kind;
    for (int i = 0; i < face.size; ++i) {
      const Index a = face.v[static_cast<std::size_t>(i)], b = face.v[static_cast<std::size_t>((i + 1) % face.size)];
      const Edge e{std::min(a, b), std::max(a, b)};
      const auto it = std::lower_bound(edges.begin(), edges.end(), e);
      if (it != edges.end() && *it == e) {
        int& r = rank[static_cast<std::size_t>(it - edges.begin())];
        r = std::max(r, kRank[static_cast<std::size_t>(kind)]);
      }
    }
  }
  std::vector<Rgba8> colors;
  colors.reserve(edges.size());
  for (int r : rank) colors.push_back(cell_kind_edge_color(static_cast<CellKind>(r)));
  return colors;
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

std::vector<std::uint8_t> view_signature(std::span<const Vec3> points, std::span<const Vec3> centers,
                                         std::span<const double> radii, const Vec3& direction, double aspect,
                                         const Vec3& up, double fov_y_degrees) {
  const Camera camera = fit_camera_to_points(points, direction, aspect,
                                             {.up = up, .fov_y_degrees = fov_y_degrees, .is_perspective = false});
  constexpr std::size_t kCells = static_cast<std::size_t>(kViewSignatureWidth) * kViewSignatureHeight;
  std::vector<std::uint8_t> mask(2 * kCells, 0);
  const Mat4 to_ndc = projection_matrix(camera, aspect) * view_matrix(camera);
  std::size_t half = 0;  // 0: the points' cells, kCells: the discs'
  auto mark = [&](double x, double y) {  // NDC
    const int gx = static_cast<int>(std::floor(0.5 * (x + 1.0) * kViewSignatureWidth));
    const int gy = static_cast<int>(std::floor(0.5 * (y + 1.0) * kViewSignatureHeight));
    if (gx >= 0 && gy >= 0 && gx < kViewSignatureWidth && gy < kViewSignatureHeight)
      mask[half + static_cast<std::size_t>(gy) * kViewSignatureWidth + static_cast<std::size_t>(gx)] = 1;
  };
  for (const Vec3& p : points) {
    const Vec3 ndc = transform_point(to_ndc, p);
    if (std::isfinite(ndc.x) && std::isfinite(ndc.y)) mark(ndc.x, ndc.y);
  }
  half = kCells;
  // The glyph discs (orthographic: radius 2 r / ortho_height in NDC y).
  for (std::size_t i = 0; i < centers.size() && i < radii.size(); ++i) {
    const Vec3 ndc = transform_point(to_ndc, centers[i]);
    if (!std::isfinite(ndc.x) || !std::isfinite(ndc.y)) continue;
    const double ry = 2.0 * radii[i] / camera.ortho_height, rx = ry / aspect;
    const int steps = 8;
    for (int a = -steps; a <= steps; ++a)
      for (int b = -steps; b <= steps; ++b)
        if (a * a + b * b <= steps * steps) mark(ndc.x + rx * a / steps, ndc.y + ry * b / steps);
  }
  return mask;
}

double view_signature_similarity(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) {
  constexpr std::size_t kCells = static_cast<std::size_t>(kViewSignatureWidth) * kViewSignatureHeight;
  if (a.size() != 2 * kCells || b.size() != 2 * kCells) return 0.0;
  // One half's intersection over union, b as it is or mirrored left to
  // right (the view from the other side of a plate seen face-on, whose
  // glyphs the wireframe does not hide).
  auto iou = [&](std::size_t half, bool mirrored) {
    std::size_t both = 0, either = 0;
    for (int y = 0; y < kViewSignatureHeight; ++y)
      for (int x = 0; x < kViewSignatureWidth; ++x) {
        const std::size_t row = half + static_cast<std::size_t>(y) * kViewSignatureWidth;
        const bool in_a = a[row + static_cast<std::size_t>(x)] != 0;
        const bool in_b = b[row + static_cast<std::size_t>(mirrored ? kViewSignatureWidth - 1 - x : x)] != 0;
        both += in_a && in_b;
        either += in_a || in_b;
      }
    return either == 0 ? 1.0 : static_cast<double>(both) / static_cast<double>(either);
  };
  return std::max(std::min(iou(0, false), iou(kCells, false)), std::min(iou(0, true), iou(kCells, true)));
}

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
  // A view that repeats a chosen one (a symmetric model: the twisted
  // cross from azimuth 30 and 210; issue 44 part U) is no further view:
  // view_signature_similarity >= kSameViewSimilarity.
  std::vector<Vec3> chosen{candidates[order[0]]};
  std::vector<std::vector<std::uint8_t>> signatures{
      view_signature(points, centers, radii, candidates[order[0]], aspect, up, fov_y_degrees)};
  std::vector<bool> taken(candidates.size(), false);
  taken[order[0]] = true;
  std::vector<std::vector<std::uint8_t>> signature_of(candidates.size());
  auto is_copy = [&](std::size_t i) {
    if (signature_of[i].empty())
      signature_of[i] = view_signature(points, centers, radii, candidates[i], aspect, up, fov_y_degrees);
    return std::any_of(signatures.begin(), signatures.end(), [&](const std::vector<std::uint8_t>& s) {
      return view_signature_similarity(s, signature_of[i]) >= kSameViewSimilarity;
    });
  };
  while (static_cast<int>(chosen.size()) < count) {
    std::size_t pick = candidates.size();
    for (std::size_t i : order) {
      if (taken[i]) continue;
      const bool apart = std::all_of(chosen.begin(), chosen.end(),
                                     [&](const Vec3& c) { return azimuth_gap(candidates[i], c, up) >= 90.0 - 1e-9; });
      if (apart && !is_copy(i)) {
        pick = i;
        break;
      }
    }
    if (pick == candidates.size())  // none far enough: the best one left that differs
      for (std::size_t i : order)
        if (!taken[i] && !is_copy(i)) {
          pick = i;
          break;
        }
    if (pick == candidates.size()) {
      // Every candidate repeats a chosen view: from high above instead.
      const Vec3 high = upright_view_direction(up, view_azimuth_degrees(chosen[0], up), kHighViewElevation);
      if (std::any_of(chosen.begin(), chosen.end(), [&](const Vec3& c) { return norm(c - high) < 1e-9; })) break;
      chosen.push_back(high);
      signatures.push_back(view_signature(points, centers, radii, high, aspect, up, fov_y_degrees));
      continue;
    }
    taken[pick] = true;
    chosen.push_back(candidates[pick]);
    signatures.push_back(signature_of[pick]);
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
            if (g < best && drawn[g].kind == m.kind && std::hypot(anchors[g][0] - s[0], anchors[g][1] - s[1]) < min_pixels)
              best = g;
        }
    }
    if (best == drawn.size()) {
      drawn.push_back({m.position, 0, 0, 0, m.kind});
      anchors.push_back(s);
      if (std::isfinite(s[0]) && std::isfinite(s[1])) grid[{cell_of(s[0]), cell_of(s[1])}].push_back(best);
    }
    ScreenMarker& d = drawn[best];
    (m.kind == MarkerKind::coincident ? d.coincident : d.intersections) += std::max<Index>(m.count, 1);
    ++d.members;
  }
  return drawn;
}

std::vector<ScreenMarker> group_markers_on_screen(std::span<const OverlapMarker> markers, const Camera& camera,
                                                  int view_height, double min_pixels, int max_groups) {
  double distance = std::max(min_pixels, 0.0);
  std::vector<ScreenMarker> groups = merge_markers_on_screen(markers, camera, view_height, distance);
  while (static_cast<int>(groups.size()) > std::max(1, max_groups) && distance < 1e7) {
    distance = distance > 0.0 ? 1.5 * distance : 1.0;
    groups = merge_markers_on_screen(markers, camera, view_height, distance);
  }
  return groups;
}

namespace {

// The image plane of a camera: right and up, unit vectors.
struct ImagePlane {
  Vec3 right, up, forward;
};
ImagePlane image_plane(const Camera& camera) {
  const Vec3 forward = forward_of(camera);
  const Vec3 right = normalized(cross(forward, camera.up));
  return {right, cross(right, forward), forward};
}

// One marker group's arrows, as drawn.
struct MarkerFan {
  ScreenMarker group;
  struct Arrow {
    Vec3 tail, tip;
    Rgba8 color;
  };
  std::vector<Arrow> arrows;
  double reach = 0;  // model units from the anchor to the farthest arrow tail (in the image plane)
  double unit = 0;   // model units per output pixel at the anchor
};

// The arrows of every marker group (build_main_scene's overlay[0] and the
// labels' fans). The coloured glyphs' discs (#0, #1, #2: in the image plane,
// plus the arrow head's half width) are kept clear, see build_main_scene
// (the 44c review: #1 and #2 lay under gmsh_box's fans).
std::vector<MarkerFan> marker_fans(const GlyphResult& glyphs, const OverlapReport& overlap, const Camera& camera,
                                   int view_height, const MainViewOptions& options) {
  const ImagePlane plane = image_plane(camera);
  const std::vector<double> shown =
      displayed_glyph_radii(glyphs, view_glyph_scale(glyphs, camera, view_height, options));
  std::vector<std::pair<Vec3, double>> kept_clear;  // centre, radius in model units
  std::vector<Index> storage;
  const std::span<const Index> ties = tie_classes_of(glyphs, {}, storage);
  const Index coloured = coloured_classes_of(glyphs, ties);
  for (const AggregatedGlyph& g : glyphs.clusters)  // #0 first
    if (g.radius > 0.0 && !is_grey_glyph(g.id, ties, coloured))
      kept_clear.push_back({g.position, shown[static_cast<std::size_t>(g.id)]});
  auto in_plane = [&](const Vec3& v) { return std::array<double, 2>{dot(v, plane.right), dot(v, plane.up)}; };
  std::vector<MarkerFan> fans;
  const std::vector<ScreenMarker> groups = group_markers_on_screen(
      overlap.markers, camera, view_height, options.marker_merge_pixels * options.pixel_scale, options.max_marker_groups);
  // Each group's centre on screen (pixels): a fan reaches at most half way
  // to the nearest other (the 44e review: inj_grid's x28 and x23 fans,
  // hubs 45 px apart, and stack60's chain of three interleaved their
  // arrows, so no arrow could be told to one fan).
  std::vector<std::array<double, 2>> hubs;
  for (const ScreenMarker& g : groups) {
    const Vec3 q = g.position - camera.eye;
    const double unit = units_per_pixel(camera, std::max(dot(q, plane.forward), 1e-12), view_height);
    hubs.push_back({dot(q, plane.right) / unit, dot(q, plane.up) / unit});
  }
  for (std::size_t gi = 0; gi < groups.size(); ++gi) {
    const ScreenMarker& marker = groups[gi];
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t o = 0; o < groups.size(); ++o)
      if (o != gi) nearest = std::min(nearest, std::hypot(hubs[o][0] - hubs[gi][0], hubs[o][1] - hubs[gi][1]));
    MarkerFan fan{marker, {}, 0.0, 0.0};
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
    const double depth = std::max(dot(marker.position - camera.eye, plane.forward), 1e-12);
    const double unit = units_per_pixel(camera, depth, view_height) * options.pixel_scale;
    fan.unit = unit;
    // (3 px: where an arrow's tip stops short of its hub; at least its
    // head and a stub of shaft, 26 px.)
    // (Not a fan on a coloured glyph: its arrows start at the glyph's rim.)
    const bool on_glyph = std::any_of(kept_clear.begin(), kept_clear.end(), [&](const auto& disc) {
      const std::array<double, 2> m = in_plane(marker.position - disc.first);
      return std::hypot(m[0], m[1]) < disc.second + 7.0 * unit;
    });
    const double half_way = on_glyph ? options.arrow_pixels : 0.5 * nearest / options.pixel_scale - 3.0;
    const double length =
        std::max(std::min(options.arrow_pixels, half_way), std::min(options.arrow_pixels, 26.0)) * unit;
    // The arrow on the ray marker − t d: its start t0 (3 pixels, or where
    // the ray leaves the discs holding the marker) and how long it may run
    // from there before it meets another disc (at most length).
    struct Ray {
      double t0, free;
    };
    auto ray_of = [&](const Vec3& d) {
      Ray ray{3.0 * unit, length};
      const std::array<double, 2> e = in_plane(d);
      for (const auto& [centre, radius] : kept_clear) {  // the discs holding the marker first
        const double clear = radius + 7.0 * unit;  // widened by an arrow head's half width
        const std::array<double, 2> m = in_plane(marker.position - centre);
        const double m2 = m[0] * m[0] + m[1] * m[1], me = m[0] * e[0] + m[1] * e[1];
        if (m2 < clear * clear) ray.t0 = std::max(ray.t0, me + std::sqrt(std::max(0.0, me * me - m2 + clear * clear)));
      }
      for (const auto& [centre, radius] : kept_clear) {
        const double clear = radius + 7.0 * unit;
        const std::array<double, 2> m = in_plane(marker.position - centre);
        const double m2 = m[0] * m[0] + m[1] * m[1], me = m[0] * e[0] + m[1] * e[1];
        const double disc = me * me - m2 + clear * clear;
        if (disc <= 0.0) continue;
        const double enter = me - std::sqrt(disc), leave = me + std::sqrt(disc);
        if (leave > ray.t0 && enter < ray.t0 + ray.free) ray.free = std::max(0.0, enter - ray.t0);
      }
      return ray;
    };
    // Every one of the n arrows is drawn, so that the fan's count can be
    // checked against its label (the 44d review: lshape's "x8" fan lost
    // the arrows that crossed #2 and showed 4). The evenly spread
    // directions when none meets a coloured glyph; else n of 72 directions
    // spread over those clear at full length, then the longest of the rest,
    // each shortened to stop at the glyph's halo.
    auto add_arrow = [&](const Vec3& d, const Ray& ray, double run, const Rgba8& color) {
      fan.arrows.push_back({marker.position - (ray.t0 + run) * d, marker.position - ray.t0 * d, color});
      fan.reach = std::max(fan.reach, ray.t0 + run);
    };
    auto color_of = [&](int k) { return k < num_coincident ? kCoincidentArrowColor : kIntersectionArrowColor; };
    const std::vector<Vec3> even = arrow_directions(camera, n, options.arrow_start_degrees);
    std::vector<Ray> rays;
    for (const Vec3& d : even) rays.push_back(ray_of(d));
    if (std::all_of(rays.begin(), rays.end(), [&](const Ray& r) { return r.free >= length; })) {
      for (std::size_t k = 0; k < even.size(); ++k) add_arrow(even[k], rays[k], length, color_of(static_cast<int>(k)));
    } else {
      constexpr int kCandidates = 72;
      const std::vector<Vec3> around = arrow_directions(camera, kCandidates, options.arrow_start_degrees);
      std::vector<Ray> ray(around.size());
      std::vector<std::size_t> clear, rest;
      for (std::size_t i = 0; i < around.size(); ++i) {
        ray[i] = ray_of(around[i]);
        (ray[i].free >= length ? clear : rest).push_back(i);
      }
      std::vector<std::size_t> chosen;
      const std::size_t from_clear = std::min(clear.size(), static_cast<std::size_t>(n));
      for (std::size_t k = 0; k < from_clear; ++k) chosen.push_back(clear[k * clear.size() / from_clear]);
      std::stable_sort(rest.begin(), rest.end(), [&](std::size_t a, std::size_t b) { return ray[a].free > ray[b].free; });
      const std::size_t from_rest = static_cast<std::size_t>(n) - from_clear;
      // (Of the rest every other one first, so that shortened arrows spread.)
      std::vector<std::size_t> spread;
      for (std::size_t i = 0; i < rest.size(); i += 2) spread.push_back(rest[i]);
      for (std::size_t i = 1; i < rest.size(); i += 2) spread.push_back(rest[i]);
      for (std::size_t k = 0; k < from_rest && k < spread.size(); ++k) chosen.push_back(spread[k]);
      std::sort(chosen.begin(), chosen.end());
      // A shortened arrow keeps at least its head and a stub of shaft.
      const double shortest = std::min(length, 26.0 * unit);
      for (std::size_t k = 0; k < chosen.size(); ++k) {
        const std::size_t i = chosen[k];
        add_arrow(around[i], ray[i], std::max(std::min(ray[i].free, length), shortest), color_of(static_cast<int>(k)));
      }
    }
    fans.push_back(std::move(fan));
  }
  return fans;
}

// Pixels (at 1200 px height) within which an intersecting cell's edge
// adds nothing beside one drawn (edges_apart_on_screen).
constexpr double kCellEdgesApartPixels = 5.0;

// The edges in order, less each one whose two ends lie within apart pixels
// of an edge kept before it (so all of it lies in that edge's band): the
// stacked copies of a cell (stack80_rot in the 44c/44d reviews: 80 cubes a
// pixel apart) drew their edges into one flat lilac slab of the edge
// colour that no legend swatch matched and that hid the cubes; one edge
// every few pixels shows them over the tint.
std::vector<Edge> edges_apart_on_screen(const HexMesh& mesh, std::span<const Edge> edges, const Camera& camera,
                                        int view_height, double apart) {
  if (!(apart > 0.0)) return {edges.begin(), edges.end()};
  const ImagePlane plane = image_plane(camera);
  using Point = std::array<double, 2>;
  auto screen = [&](Index v) {
    const Vec3 q = mesh.points[static_cast<std::size_t>(v)] - camera.eye;
    const double unit = units_per_pixel(camera, std::max(dot(q, plane.forward), 1e-12), view_height);
    return Point{dot(q, plane.right) / unit, dot(q, plane.up) / unit};
  };
  auto distance = [](const Point& p, const Point& a, const Point& b) {  // from p to the segment ab
    const double dx = b[0] - a[0], dy = b[1] - a[1], length2 = dx * dx + dy * dy;
    const double t = length2 > 0.0 ? std::clamp(((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2, 0.0, 1.0) : 0.0;
    return std::hypot(a[0] + t * dx - p[0], a[1] + t * dy - p[1]);
  };
  // The kept edges in each cell that their box, widened by apart, meets.
  const double cell = std::max(apart, 32.0);
  auto cell_of = [&](double v) { return static_cast<std::int64_t>(std::floor(v / cell)); };
  std::map<std::pair<std::int64_t, std::int64_t>, std::vector<std::size_t>> near_cell;
  std::vector<std::array<Point, 2>> kept_ends;
  std::vector<Edge> kept;
  for (const Edge& e : edges) {
    const Point a = screen(e[0]), b = screen(e[1]);
    if (!std::isfinite(a[0]) || !std::isfinite(a[1]) || !std::isfinite(b[0]) || !std::isfinite(b[1])) {
      kept.push_back(e);
      continue;
    }
    const auto it = near_cell.find({cell_of(a[0]), cell_of(a[1])});
    if (it != near_cell.end() && std::any_of(it->second.begin(), it->second.end(), [&](std::size_t k) {
          return distance(a, kept_ends[k][0], kept_ends[k][1]) < apart &&
                 distance(b, kept_ends[k][0], kept_ends[k][1]) < apart;
        }))
      continue;
    const std::int64_t x0 = cell_of(std::min(a[0], b[0]) - apart), x1 = cell_of(std::max(a[0], b[0]) + apart);
    const std::int64_t y0 = cell_of(std::min(a[1], b[1]) - apart), y1 = cell_of(std::max(a[1], b[1]) + apart);
    if ((x1 - x0 + 1) * (y1 - y0 + 1) <= 4096)  // (an edge across the whole view and far beyond: kept, alone)
      for (std::int64_t cx = x0; cx <= x1; ++cx)
        for (std::int64_t cy = y0; cy <= y1; ++cy) near_cell[{cx, cy}].push_back(kept.size());
    kept_ends.push_back({a, b});
    kept.push_back(e);
  }
  return kept;
}

}  // namespace

InvertedFaces inverted_boundary_faces(const Topology& topology, const MainViewOptions& options) {
  InvertedFaces result;
  if (!options.inverted_cells || !options.orientation_note.empty()) return result;
  const std::vector<std::uint8_t>& inverted = *options.inverted_cells;
  result.cells = static_cast<std::size_t>(std::count_if(inverted.begin(), inverted.end(), [](std::uint8_t c) { return c != 0; }));
  std::vector<BoundaryPolygon> faces;
  for (const BoundaryPolygon& face : boundary_polygons(topology)) {
    const auto c = static_cast<std::size_t>(face.cell);
    if (c < inverted.size() && inverted[c] != 0) faces.push_back(face);
  }
  result.faces = faces.size();
  const bool surface = options.surface_cell_quality != nullptr;
  result.over_limit = faces.size() > (surface ? kMaxInvertedOverlayFaces : kMaxInvertedOverlayVolumeFaces);
  if (result.over_limit) return result;
  // One depth rule (issue 44 part V): the see-through wireframe shows
  // every glyph, near or far, so every marked face is drawn too (round 2
  // of part U hid the far ones by ray casting while far glyphs showed:
  // 3 of gmsh_ring_dent's 5 dent faces were gone). A surface mesh is drawn
  // filled: the depth test hides its far side, faces and glyphs alike.
  result.drawn = std::move(faces);
  return result;
}

std::vector<std::uint8_t> worst_cluster_vertices(const GlyphResult& glyphs, int per_cluster,
                                                 std::span<const Index> given_ties) {
  std::vector<std::uint8_t> marked(glyphs.vertex_cluster.size(), 0);
  std::vector<Index> members;
  // The coloured clusters only: the grey ones' edges, hundreds with bounded
  // clusters, would veil the model (issue 44's fifth round). Every member
  // of a coloured tie class alike (issue 44 part U: edges at one of 28
  // equals singled it out), per_cluster shared among them.
  std::vector<Index> storage;
  const std::span<const Index> ties = tie_classes_of(glyphs, given_ties, storage);
  const std::vector<Index> sizes = tie_class_sizes(ties);
  const Index coloured_classes = coloured_classes_of(glyphs, ties);
  // (Clusters without an aggregated glyph: each a class of its own, the
  // first labelled_cluster_count(K) coloured.)
  const std::size_t clusters = glyphs.cluster_offsets.empty() ? 0 : glyphs.cluster_offsets.size() - 1;
  const auto labelled = static_cast<std::size_t>(labelled_cluster_count(glyphs.options.top_clusters));
  for (std::size_t c = 0; c < clusters; ++c) {
    const bool has_class = c < ties.size();
    if (has_class ? ties[c] >= coloured_classes : c >= labelled) break;
    members.assign(glyphs.cluster_vertices.begin() + glyphs.cluster_offsets[c],
                   glyphs.cluster_vertices.begin() + glyphs.cluster_offsets[c + 1]);
    const Index class_size = has_class ? std::max<Index>(1, sizes[static_cast<std::size_t>(ties[c])]) : 1;
    const Index share = per_cluster > 0 ? std::max<Index>(1, per_cluster / class_size) : 0;
    const auto keep = std::min<std::size_t>(members.size(), static_cast<std::size_t>(share));
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
                       const MainViewOptions& options, const InvertedFaces* inverted) {
  if (glyphs.vertex_cluster.size() != mesh.points.size())
    throw Error("glyph result does not match the mesh (" + std::to_string(glyphs.vertex_cluster.size()) + " vs " +
                std::to_string(mesh.points.size()) + " vertices)");
  const Box3 box = boundary_bounding_box(mesh, topology);
  Scene scene;
  scene.origin = 0.5 * (box.lo + box.hi);
  scene.background = options.background;
  auto local = [&](const Vec3& p) { return to_vec3f(p - scene.origin); };

  // 0. A surface mesh's faces, filled by quality (surface_views.h).
  if (options.surface_cell_quality) {
    scene.triangles.push_back(surface_fill_faces(mesh, topology, *options.surface_cell_quality, scene.origin,
                                                 options.surface_inverted_cells, options.surface_inverted_are_reversed));
    scene.triangles.back().is_lit = options.surface_fill_lit;
  }

  // 1. Boundary wireframe.
  // On a mesh of several kinds each edge in its faces' kind colour.
  // (Drawn once the intersecting cells' edges are known, step 3.)
  std::vector<Edge> wire = boundary_edges_all_kinds(topology);
  const bool surface = options.surface_cell_quality != nullptr;
  const std::size_t wire_lines = scene.lines.size();
  scene.lines.emplace_back();

  // 2. Cluster edges: around each cluster's worst vertices only (a cluster
  // of thousands of vertices would paint over the model), in its colour.
  const std::int64_t top = glyphs.options.top_clusters;
  std::vector<Index> tie_storage;
  const std::span<const Index> edge_ties = tie_classes_of(glyphs, options.glyph_ties, tie_storage);  // colours by tie class
  const Index edge_coloured = coloured_classes_of(glyphs, edge_ties);
  const std::vector<std::uint8_t> marked = worst_cluster_vertices(glyphs, options.cluster_edge_vertices, edge_ties);
  std::vector<Edge> cluster_edges;
  std::vector<Rgba8> cluster_colors;
  // An edge with a marked end, in the colour of its marked ends' lower rank
  // (every member of a tie class is marked alike: worst_cluster_vertices).
  auto add_cluster_edge = [&](const Edge& e) {
    const bool ma = marked[static_cast<std::size_t>(e[0])] != 0, mb = marked[static_cast<std::size_t>(e[1])] != 0;
    if (!ma && !mb) return;
    const Index ca = ma ? glyphs.vertex_cluster[static_cast<std::size_t>(e[0])] : kNoIndex;
    const Index cb = mb ? glyphs.vertex_cluster[static_cast<std::size_t>(e[1])] : kNoIndex;
    const Index c = ca == kNoIndex ? cb : (cb == kNoIndex ? ca : std::min(ca, cb));
    if (c == kNoIndex) return;  // marked ends in no cluster: no cluster colour
    cluster_edges.push_back(e);
    const Index slot = edge_ties[static_cast<std::size_t>(c)];
    cluster_colors.push_back(to_rgba8(cluster_color(slot < edge_coloured ? slot : -1, top)));
  };
  for (const Edge& e : topology.edges) add_cluster_edge(e);
  // The tets', wedges' and pyramids' edges too (topology.edges holds the
  // hexes' only): every kind's edges around the worst vertices.
  if (topology.across_kinds) {
    std::vector<Edge> other;
    const auto cells = static_cast<std::size_t>(num_volume_cells(mesh));
    for (std::size_t c = mesh.hexes.size(); c < cells; ++c)
      for_each_edge_of(volume_cell(mesh, static_cast<Index>(c)), [&](Index a, Index b) {
        if (marked[static_cast<std::size_t>(a)] || marked[static_cast<std::size_t>(b)])
          other.push_back({std::min(a, b), std::max(a, b)});
      });
    std::sort(other.begin(), other.end());
    other.erase(std::unique(other.begin(), other.end()), other.end());
    for (const Edge& e : other)
      if (!std::binary_search(topology.edges.begin(), topology.edges.end(), e)) add_cluster_edge(e);
  }
  scene.lines.push_back(edge_lines(mesh, scene.origin, cluster_edges, cluster_colors, options.cluster_edge_width));
  scene.lines.back().under_ranked_spheres = true;  // around the coloured glyphs, not over them

  // 3. Intersecting cells: translucent faces and their edges. Unlit and
  // one layer (TriangleSet::single_layer), each face once (a face two such
  // cells share too): every pixel of them is the tint blended once over what
  // is behind, on the background exactly the legend's swatch
  // (blend_over(kIntersectingCellColor, background); the 44p review: the
  // lit, stacked faces were up to CIEDE2000 44 from the swatch).
  TriangleSet cells;
  cells.is_lit = false;
  cells.single_layer = true;
  std::vector<Edge> cell_edges;
  std::set<std::array<Index, 4>> drawn_faces;  // sorted corners, -1 last for a triangle
  const auto add_face = [&](const Index* v, int size) {
    std::array<Index, 4> key{v[0], v[1], v[2], size == 4 ? v[3] : Index{-1}};
    for (int i = 1; i < size; ++i)  // (std::sort of 3 or 4 warned -Warray-bounds)
      for (int j = i; j > 0 && key[static_cast<std::size_t>(j - 1)] > key[static_cast<std::size_t>(j)]; --j)
        std::swap(key[static_cast<std::size_t>(j - 1)], key[static_cast<std::size_t>(j)]);
    if (!drawn_faces.insert(key).second) return;
    const auto base = static_cast<std::uint32_t>(cells.positions.size());
    for (int i = 0; i < size; ++i) {
      cells.positions.push_back(local(mesh.points[static_cast<std::size_t>(v[i])]));
      cells.colors.push_back(kIntersectingCellColor);
      const Index a = v[i], b = v[(i + 1) % size];
      cell_edges.push_back({std::min(a, b), std::max(a, b)});
    }
    cells.indices.insert(cells.indices.end(), {base, base + 1, base + 2});
    if (size == 4) cells.indices.insert(cells.indices.end(), {base, base + 2, base + 3});
  };
  const std::size_t num_checked_cells = overlap ? overlap->cell_intersecting.size() : 0;
  if (overlap && (num_checked_cells == mesh.hexes.size() ||
                  num_checked_cells == static_cast<std::size_t>(num_volume_cells(mesh)))) {
    for (std::size_t c = 0; c < mesh.hexes.size(); ++c) {
      if (!overlap->cell_intersecting[c]) continue;
      for (int f = 0; f < 6; ++f)
        add_face(topology.faces[static_cast<std::size_t>(topology.hex_faces[6 * c + f])].data(), 4);
    }
    // Tets, wedges and pyramids (when the overlap stage checked them), each
    // with its own faces (CellKindTable).
    for (std::size_t c = mesh.hexes.size(); c < num_checked_cells; ++c) {
      if (!overlap->cell_intersecting[c]) continue;
      for_each_face_of(volume_cell(mesh, static_cast<Index>(c)),
                       [&](const std::array<Index, 4>& v, int size) { add_face(v.data(), size); });
    }
  }
  // A surface mesh's intersecting faces (check_surface_overlap), the same way.
  if (overlap && overlap->is_surface) {
    const std::size_t nq = mesh.quads.size();
    for (std::size_t c = 0; c < num_checked_cells; ++c) {
      if (!overlap->cell_intersecting[c]) continue;
      add_face(c < nq ? mesh.quads[c].data() : mesh.triangles[c - nq].data(), c < nq ? 4 : 3);
    }
  }
  std::sort(cell_edges.begin(), cell_edges.end());
  cell_edges.erase(std::unique(cell_edges.begin(), cell_edges.end()), cell_edges.end());
  // The wireframe without the intersecting cells' edges: they are drawn in
  // the intersection colour (a stack's grey edges between its lilac ones
  // made the 44c review's slab).
  std::erase_if(wire, [&](const Edge& e) {
    return std::binary_search(cell_edges.begin(), cell_edges.end(), Edge{std::min(e[0], e[1]), std::max(e[0], e[1])});
  });
  scene.lines[wire_lines] = edge_lines(mesh, scene.origin, wire,
                                       topology.across_kinds ? boundary_edge_kind_colors(mesh, topology, wire)
                                       : surface             ? std::vector<Rgba8>(wire.size(), kSurfaceEdgeColor)
                                                             : std::vector<Rgba8>(wire.size(), kWireframeColor),
                                       options.wire_width);
  scene.lines[wire_lines].under_ranked_spheres = true;  // no veil over the coloured glyphs
  cell_edges = edges_apart_on_screen(mesh, cell_edges, camera, view_height, kCellEdgesApartPixels * options.pixel_scale);
  scene.lines.push_back(
      edge_lines(mesh, scene.origin, cell_edges, std::vector<Rgba8>(cell_edges.size(), kIntersectionArrowColor), 1.5f));
  // Under the ranked glyphs, as the wireframe (issue 44 part V: the lilac
  // edges of the cells injected round the dent took a quarter of #0).
  scene.lines.back().under_ranked_spheres = true;

  // 4. Aggregated glyphs: the grey ones, then the coloured (ranked) ones
  // over them, so that no grey glyph hides a ranked one.
  // Drawn at displayed_glyph_radii: #0 at least kWorstGlyphMinPixels, the
  // grey ones smaller.
  // Tied clusters wear their class's colour; glyphs piled up on screen are
  // left out (main_view_glyphs_drawn); the grey ones are pale.
  SphereSet spheres, ranked, unfaded;
  spheres.pale = kGreyGlyphPale;
  ranked.over_other_spheres = true;
  ranked.first_on_top = true;  // by rank: #0 on top of every other glyph
  // And over the intersecting cells' translucent faces (issue 44 part U,
  // round 2: they turned #0 magenta).
  ranked.over_translucent = true;
  const std::vector<double> shown =
      displayed_glyph_radii(glyphs, view_glyph_scale(glyphs, camera, view_height, options));
  const GlyphsDrawn drawn = main_view_glyphs_drawn(glyphs, camera, view_height, shown, edge_ties);
  for (const AggregatedGlyph& g : glyphs.clusters) {
    if (!(g.radius > 0.0) || !drawn.drawn[static_cast<std::size_t>(g.id)]) continue;
    const Rgba8 color = glyph_color(g.id, drawn.tie_class, drawn.coloured_classes, glyphs);
    SphereSet& set = !is_grey_glyph(g.id, drawn.tie_class, drawn.coloured_classes) ? ranked
                     : is_faded_grey_glyph(g)                                       ? spheres
                                                                                     : unfaded;
    set.centers.push_back(local(g.position));
    set.radii.push_back(static_cast<float>(shown[static_cast<std::size_t>(g.id)]));
    set.colors.push_back(is_far_side(g.id, options) ? far_side_color(color) : color);
  }
  // The grey ones over the intersecting cells' tint too (the 44c review: a
  // lilac-grey ball matched no legend line).
  spheres.over_translucent = unfaded.over_translucent = true;
  scene.spheres.push_back(std::move(spheres));
  scene.spheres.push_back(std::move(ranked));
  scene.spheres.push_back(std::move(unfaded));

  // 5. Arrows on overlap markers, grouped where they crowd on screen.
  TriangleSet arrows;
  if (overlap) {
    for (const MarkerFan& fan : marker_fans(glyphs, *overlap, camera, view_height, options)) {
      const double unit = fan.unit;
      const ArrowShape shape{static_cast<float>(2.2 * unit), static_cast<float>(6.5 * unit),
                             static_cast<float>(20.0 * unit), 16};
      for (const MarkerFan::Arrow& arrow : fan.arrows)
        append_arrow(arrows, local(arrow.tail), local(arrow.tip), shape, arrow.color);
    }
  }
  scene.overlay.push_back(std::move(arrows));
  scene.translucent.push_back(std::move(cells));

  // 5b. The boundary faces of inverted cells that show (issue 44 part U:
  // #0's glyph sits on the worst vertex, a corner of the inverted faces,
  // and hid them): opaque, unlit, in the inverted colour, with their edges,
  // moved towards the camera by kInvertedFaceLift of the model's diagonal
  // (they win over a surface mesh's fill and over coplanar folded faces),
  // depth-tested against the mesh's fill and the glyphs (part U round 2:
  // drawn over everything they turned #0 blue). Their outlines show over
  // the glyphs (main_view_outlines_over_glyphs).
  InvertedFaces computed;
  if (!inverted) computed = inverted_boundary_faces(topology, options);
  const std::vector<BoundaryPolygon>& inverted_faces = (inverted ? *inverted : computed).drawn;
  if (!inverted_faces.empty()) {
    TriangleSet faces;
    faces.is_lit = false;
    // They write depth (44v round 2 drew them without: the intersecting
    // cells' translucent tint, drawn after, turned them violet), so a grey
    // glyph behind them is covered, as any geometry behind them.
    LineSet outline;
    outline.width = std::max(1.5f, options.wire_width);
    const double lift = kInvertedFaceLift * norm(box.hi - box.lo);
    const Vec3 forward = forward_of(camera);
    auto lifted = [&](const Vec3& p) {
      const Vec3 towards = camera.is_perspective ? normalized(camera.eye - p) : -1.0 * forward;
      return local(p + lift * towards);
    };
    for (const BoundaryPolygon& face : inverted_faces) {
      const Rgba8 color = options.surface_cell_quality
                              ? surface_fill_color((*options.surface_cell_quality)[static_cast<std::size_t>(face.cell)])
                              : to_rgba8(kInvertedColor);
      const auto base = static_cast<std::uint32_t>(faces.positions.size());
      for (int i = 0; i < face.size; ++i) {
        const Vec3f q = lifted(mesh.points[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)])]);
        faces.positions.push_back(q);
        faces.colors.push_back(color);
        outline.positions.push_back(q);
        outline.colors.push_back(kWireframeColor);
        outline.indices.insert(outline.indices.end(),
                               {base + static_cast<std::uint32_t>(i), base + static_cast<std::uint32_t>((i + 1) % face.size)});
      }
      faces.indices.insert(faces.indices.end(), {base, base + 1, base + 2});
      if (face.size == 4) faces.indices.insert(faces.indices.end(), {base, base + 2, base + 3});
    }
    // A surface mesh's folded faces overlap their neighbours, whose
    // intersecting-cell lilac (the translucent layer, blended after every
    // opaque triangle) tinted them: drawn once more, opaque, after that lilac
    // (depth-tested, so a glyph in front still hides them; the ranked glyphs
    // are drawn over the translucent layer again). Issue 47 part F.
    if (options.surface_cell_quality && overlap) scene.translucent.push_back(faces);
    scene.triangles.push_back(std::move(faces));
    // Under the ranked glyphs (render_main_view draws the part a glyph
    // hides over it, outside its core).
    outline.under_ranked_spheres = true;
    scene.lines.push_back(std::move(outline));
  }

  // 6. On a mesh of several kinds, the pyramids' edges that are not boundary
  // edges, in the pyramid colour: pyramids join a hex block to tets, inside
  // the mesh as a rule, so these show where the hexes end and give the
  // legend's pyramid swatch its edges (46q review Q-M7).
  if (topology.across_kinds && !mesh.pyramids.empty() && mesh.pyramids.size() <= kMaxInteriorPyramids) {
    std::vector<Edge> inner;
    inner.reserve(8 * mesh.pyramids.size());
    for (const auto& p : mesh.pyramids)
      for (int i = 0; i < 4; ++i)
        for (const Edge e : {Edge{p[i], p[(i + 1) % 4]}, Edge{p[i], p[4]}})
          inner.push_back({std::min(e[0], e[1]), std::max(e[0], e[1])});
    std::sort(inner.begin(), inner.end());
    inner.erase(std::unique(inner.begin(), inner.end()), inner.end());
    std::vector<Edge> kept;
    std::set_difference(inner.begin(), inner.end(), wire.begin(), wire.end(), std::back_inserter(kept));
    if (!kept.empty()) {
      scene.lines.push_back(edge_lines(mesh, scene.origin, kept,
                                       std::vector<Rgba8>(kept.size(), cell_kind_edge_color(CellKind::pyramid)),
                                       options.wire_width));
      scene.lines.back().under_ranked_spheres = true;
    }
  }
  return scene;
}

IdImage main_view_id_image(Renderer& renderer, const Scene& scene, const GlyphResult& glyphs, const Camera& camera,
                           const PixelRect& view, bool with_markers, std::span<const Index> given_ties) {
  if (scene.spheres.size() != 3) throw RenderError("main_view_id_image needs view A's scene");
  Scene coded;
  coded.origin = scene.origin;
  coded.background = id_color(kIdBackground);
  for (const TriangleSet& set : scene.triangles) {
    TriangleSet flat = set;
    flat.scalars.clear();
    flat.colors.assign(set.positions.size(), id_color(kIdEdge));
    coded.triangles.push_back(std::move(flat));
  }
  // Lines: the segments drawn at least half opaque at both ends (the
  // clusters' coloured edges, build_main_scene step 2, apart).
  for (const LineSet& set : scene.lines) {
    LineSet opaque;
    opaque.width = set.width;
    opaque.under_ranked_spheres = set.under_ranked_spheres;
    opaque.positions = set.positions;
    opaque.colors.assign(set.positions.size(), id_color(coded.lines.size() == 1 ? kIdClusterEdge : kIdEdge));
    for (std::size_t i = 0; i + 1 < set.indices.size(); i += 2)
      if (set.colors[set.indices[i]].a >= 128 && set.colors[set.indices[i + 1]].a >= 128)
        opaque.indices.insert(opaque.indices.end(), {set.indices[i], set.indices[i + 1]});
    coded.lines.push_back(std::move(opaque));
  }
  // Spheres: in build_main_scene's order (grey ones, then coloured ones, by
  // rank), without the glyphs it left out (main_view_glyphs_drawn): a
  // glyph is the next sphere of its set when that sphere sits at its
  // position (a left-out glyph at the same position as the next drawn one
  // is covered by it: the id is the drawn one's either way).
  coded.spheres = scene.spheres;
  std::size_t next[3] = {0, 0, 0};
  std::vector<Index> storage;
  const std::span<const Index> ties = tie_classes_of(glyphs, given_ties, storage);
  const Index coloured = coloured_classes_of(glyphs, ties);
  for (const AggregatedGlyph& g : glyphs.clusters) {
    if (!(g.radius > 0.0)) continue;
    const std::size_t set = !is_grey_glyph(g.id, ties, coloured) ? 1 : is_faded_grey_glyph(g) ? 0 : 2;
    const SphereSet& drawn = coded.spheres[set];
    const Vec3f at = to_vec3f(g.position - scene.origin);
    if (next[set] >= drawn.centers.size() || !(drawn.centers[next[set]].x == at.x && drawn.centers[next[set]].y == at.y &&
                                               drawn.centers[next[set]].z == at.z))
      continue;
    coded.spheres[set].colors[next[set]++] = id_color(kIdGlyph + static_cast<std::uint32_t>(g.id));
  }
  if (next[0] != coded.spheres[0].colors.size() || next[1] != coded.spheres[1].colors.size() ||
      next[2] != coded.spheres[2].colors.size())
    throw RenderError("main_view_id_image: scene and glyphs differ");
  if (with_markers)
    for (const TriangleSet& set : scene.overlay) {
      TriangleSet flat = set;
      flat.scalars.clear();
      flat.colors.assign(set.positions.size(), id_color(kIdMarker));
      coded.overlay.push_back(std::move(flat));
    }
  IdImage ids = renderer.render_ids(coded, camera, view.width, view.height);
  ids.x0 = view.x;
  ids.y0 = view.y;
  return ids;
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

// Label sizes at the figure's scale.
int cluster_label_size(const AnnotationStyle& style) {
  return std::max(11, static_cast<int>(std::lround(20 * style.scale)));
}
int marker_label_size(const AnnotationStyle& style) {
  return std::max(10, static_cast<int>(std::lround(18 * style.scale)));
}

// A label's box: its text's extent with a 2-pixel margin, the baseline at
// box.y + 2 + size (draw_main_view_labels).
LabelRequest label_request(const std::string& text, int size, const ScreenDisc& anchor, const AnnotationStyle& style) {
  const PixelRect extent = text_extent(text, size, style);
  return {anchor, extent.width + 4, std::max(extent.height, size) + 5};
}

void draw_main_view_labels(Image& figure, const MainViewLabels& labels, const AnnotationStyle& style,
                           const MainViewOptions& options) {
  AnnotationStyle text_style = style;
  Rgba8 halo = options.background;
  halo.a = 255;
  // Leader lines first (on a pale halo, so they show over arrows, cells and
  // edges), then the labels: a leader never crosses a label's text.
  for (const MainViewLabel& label : labels.labels) {
    const PlacedLabel& p = label.placement;
    if (!p.has_leader) continue;
    // The halo from where the leader leaves its glyph's disc (issue 44
    // part V: a callout's leader starts inside the glyph, and a pale halo
    // over the glyph's rim made it look smaller).
    const double dx = p.leader_x1 - p.leader_x0, dy = p.leader_y1 - p.leader_y0;
    const double length = std::hypot(dx, dy);
    double t0 = 0.0;
    if (label.kind == MainViewLabel::Kind::cluster && length > 0.0) {
      // The leader's parameter where it leaves the anchor disc (plus 1 px
      // and the halo's half width), if it starts inside.
      const double fx = p.leader_x0 - label.anchor.x, fy = p.leader_y0 - label.anchor.y;
      const double r = label.anchor.radius + 1.0 + 0.5 * std::max(3.0, 4.5 * style.scale);
      const double b = (fx * dx + fy * dy) / length, c = fx * fx + fy * fy - r * r;
      if (c < 0.0) t0 = std::min(1.0, (-b + std::sqrt(b * b - c)) / length);
    }
    if (t0 < 1.0)
      draw_line(figure, p.leader_x0 + t0 * dx, p.leader_y0 + t0 * dy, p.leader_x1, p.leader_y1, halo,
                std::max(3.0, 4.5 * style.scale));
    draw_line(figure, p.leader_x0, p.leader_y0, p.leader_x1, p.leader_y1, label.color, std::max(1.0, 1.8 * style.scale));
  }
  for (const MainViewLabel& label : labels.labels) {
    const PlacedLabel& p = label.placement;
    const int size = label.kind == MainViewLabel::Kind::cluster ? cluster_label_size(style) : marker_label_size(style);
    // On a pale box: labels sit among arrow shafts and edges.
    fill_rect(figure, p.box, halo);
    text_style.text_color = label.color;
    draw_text(figure, p.box.x + 2, p.box.y + 1 + size, label.text, size, text_style);
  }
}

// The inverted ring's halo width (pixels): 10 at scale 1, so that the 3 px
// ring in its middle keeps a 3.5 px pale gap from the glyph (with a 1 px
// gap a blue ring on a blue glyph read as its rim: issue 44's fifth round).
double inverted_halo_width(const AnnotationStyle& style) { return std::max(8.0, 10.0 * style.scale); }

// The radius (pixels) of the inverted ring around a glyph of radius pixels:
// its halo begins 0.5 px outside the glyph, so the ring never covers the
// glyph's rim (it did by 1 px: bunny_in's inverted #0 then looked 1 px
// smaller than #1, a worse cluster drawn smaller).
double inverted_ring_radius(double radius, const AnnotationStyle& style) {
  return radius + 0.5 + 0.5 * inverted_halo_width(style);
}

// The radius (pixels) of #0's dark ring around its glyph of radius pixels:
// outside the inverted ring (draw_inverted_glyph_rings) when #0 has one.
double worst_ring_radius(double radius, bool is_inverted, const AnnotationStyle& style) {
  return is_inverted ? inverted_ring_radius(radius, style) + 0.5 * inverted_halo_width(style) + 2.0 * style.scale
                     : radius + 1.5 + 0.5 * std::max(4.0, 5.0 * style.scale);
}

}  // namespace

bool is_far_side(Index cluster, const MainViewOptions& options) {
  const auto k = static_cast<std::size_t>(cluster);
  return k < options.far_side_glyphs.size() && options.far_side_glyphs[k] != 0;
}

Rgba8 far_side_color(Rgba8 c) {
  auto pale = [](std::uint8_t v) { return static_cast<std::uint8_t>(std::lround(v + kFarSideGlyphPale * (255 - v))); };
  return {pale(c.r), pale(c.g), pale(c.b), c.a};
}

bool has_inverted_ring(const AggregatedGlyph& g, const MainViewOptions& options) {
  return g.min_quality < 0.0 && !options.surface_cell_quality;
}

double worst_rings_extent(double radius, bool is_inverted, const AnnotationStyle& style) {
  return worst_ring_radius(radius, is_inverted, style) + 0.5 * std::max(4.0, 5.0 * style.scale);
}

namespace {

// A ring around cluster #0's glyph on screen (dark on a pale halo, a few
// pixels outside its silhouette), so the worst place is found first even
// where its glyph is small. The halo hugs the glyph from 0.5 px outside
// its rim (issue 44 part P, round 3): a light outline between #0's glyph
// and the wireframe or a dark neighbour (an inverted #0's halo is
// the inverted ring's, which begins there too).
// A tied #0's class: no stretch inside another glyph of the class (others),
// so that no ring crosses a worst glyph.
// A glyph on the far side of a surface (is_far_side) wears the ring paled as
// its glyph is (far_side_color): a ring as strong as #0's in sight drew the
// eye to a glyph with nothing to see behind it (the 47d review's gbell).
void draw_worst_glyph_ring(Image& figure, const ScreenDisc& worst, bool is_inverted, const AnnotationStyle& style,
                           const MainViewOptions& options, std::span<const ScreenDisc> others = {}) {
  if (!(worst.radius > 0.0)) return;
  Rgba8 halo = options.background;
  halo.a = 255;
  const double radius = worst_ring_radius(worst.radius, is_inverted, style);
  const double halo_width = std::max(4.0, 5.0 * style.scale);
  const double outer = radius + 0.5 * halo_width;
  const double inner = is_inverted ? radius - 0.5 * halo_width : worst.radius + 0.5;
  const double ring_width = std::max(1.5, 2.2 * style.scale);
  // The pale halo, the yellow band from the halo's inner edge to the dark
  // ring (kWorstBandColor), the dark ring.
  struct Pass {
    double r, width;
    Rgba8 color;
  };
  const double band_outer = radius - 0.5 * ring_width;
  const bool pale = is_far_side(static_cast<Index>(worst.id), options);
  const Pass passes[] = {{0.5 * (inner + outer), outer - inner, halo},
                         {0.5 * (inner + band_outer), band_outer - inner, pale ? far_side_color(kWorstBandColor) : kWorstBandColor},
                         {radius, ring_width, pale ? far_side_color(style.text_color) : style.text_color}};
  constexpr int kSegments = 96;
  for (const Pass& pass : passes)
    for (int i = 0; i < kSegments; ++i) {
      const double a0 = 2.0 * M_PI * i / kSegments, a1 = 2.0 * M_PI * (i + 1) / kSegments;
      const double am = 0.5 * (a0 + a1);
      const double mx = worst.x + pass.r * std::cos(am), my = worst.y + pass.r * std::sin(am);
      if (std::any_of(others.begin(), others.end(), [&](const ScreenDisc& o) {
            return o.id != worst.id && std::hypot(mx - o.x, my - o.y) < o.radius + 0.5 * pass.width;
          }))
        continue;
      draw_line(figure, worst.x + pass.r * std::cos(a0), worst.y + pass.r * std::sin(a0),
                worst.x + pass.r * std::cos(a1), worst.y + pass.r * std::sin(a1), pass.color, pass.width);
    }
}

// A ring in the inverted colour just outside each glyph of a cluster with an
// inverted vertex (on a pale halo), so inverted clusters differ from merely
// poor ones at a glance; cluster #0's dark ring goes outside it.
// A ring's stretch inside a coloured glyph ranked before its own is left
// out (that glyph is drawn over it: a grey glyph's ring over a coloured
// one read as the grey glyph in front). The glyphs of ids below
// banded_below (#0's class) have their halo in the yellow band
// (draw_worst_glyph_ring).
void draw_inverted_glyph_rings(Image& figure, const std::vector<ScreenDisc>& inverted,
                               const std::vector<ScreenDisc>& coloured, std::int64_t banded_below,
                               const AnnotationStyle& style, const MainViewOptions& options) {
  Rgba8 background = options.background;
  background.a = 255;
  const Rgba8 color = to_rgba8(kInvertedColor);
  for (const ScreenDisc& d : inverted) {
    // #0's halo is its yellow band (draw_worst_glyph_ring), up to its dark ring.
    const Rgba8 halo = d.id >= 0 && d.id < banded_below ? kWorstBandColor : background;
    const double radius = inverted_ring_radius(d.radius, style);
    const int segments = std::clamp(static_cast<int>(radius), 24, 96);
    for (int pass = 0; pass < 2; ++pass)
      for (int i = 0; i < segments; ++i) {
        const double a0 = 2.0 * M_PI * i / segments, a1 = 2.0 * M_PI * (i + 1) / segments;
        const double am = 0.5 * (a0 + a1), mx = d.x + radius * std::cos(am), my = d.y + radius * std::sin(am);
        if (std::any_of(coloured.begin(), coloured.end(), [&](const ScreenDisc& c) {
              return c.id < d.id && std::hypot(mx - c.x, my - c.y) < c.radius;
            }))
          continue;
        draw_line(figure, d.x + radius * std::cos(a0), d.y + radius * std::sin(a0), d.x + radius * std::cos(a1),
                  d.y + radius * std::sin(a1), pass == 0 ? halo : color,
                  pass == 0 ? inverted_halo_width(style) : std::max(2.0, 3.0 * style.scale));
      }
  }
}

}  // namespace

std::string mostly_inverted_note(const QualityField& quality) {
  const std::size_t cells = quality.cell_scaled_jacobian.size();
  std::size_t inverted = 0;
  for (std::size_t c = 0; c < cells; ++c) inverted += cell_is_inverted(quality, c);
  if (cells == 0 || 2 * inverted <= cells) return {};
  return "inverted: " + std::to_string(inverted) + " of " + std::to_string(cells) + " cells";
}

std::vector<LegendLine> main_legend_lines(const GlyphResult& glyphs, const OverlapReport* overlap,
                                          const AnnotationStyle& style, const MainViewOptions& options,
                                          double glyph_scale, std::span<const Index> hidden, Index left_out,
                                          std::span<const Index> unlabelled, double worst_pixels,
                                          std::span<const Rgba8> outlines_over_glyphs, bool cluster_edges_seen) {
  // One line per coloured tie class (glyph_tie_classes): "#k (n)  min q",
  // or for a tie "#k-#m  N tied at q".
  std::vector<Index> storage;
  const std::span<const Index> ties = tie_classes_of(glyphs, options.glyph_ties, storage);
  const std::vector<Index> tie_sizes = tie_class_sizes(ties);
  const Index labelled = coloured_classes_of(glyphs, ties);
  std::size_t listed = 0;  // clusters in coloured classes
  while (listed < ties.size() && ties[listed] < labelled) ++listed;
  const bool worst_is_tied = !tie_sizes.empty() && tie_sizes[0] > 1;
  // A tie among the coloured classes (the "tied" lines are said only then).
  bool coloured_tie = false;
  for (Index c = 0; c < labelled && static_cast<std::size_t>(c) < tie_sizes.size(); ++c)
    coloured_tie = coloured_tie || tie_sizes[static_cast<std::size_t>(c)] > 1;
  std::vector<LegendLine> lines;
  // Mostly inverted: the glyphs mark the orientation, not a local defect.
  if (!options.orientation_note.empty()) {
    lines.push_back({to_rgba8(kInvertedColor), options.orientation_note, 0});
    lines.push_back({std::nullopt, "  mirrored? reversed nodes?"});
  }
  lines.push_back({std::nullopt, "glyphs: worst clusters", options.orientation_note.empty() ? 0 : 1});
  for (std::size_t i = 0; i < listed; ++i) {
    if (i > 0 && ties[i - 1] == ties[i]) continue;
    const AggregatedGlyph& g = glyphs.clusters[i];
    const Index tied = tie_sizes[static_cast<std::size_t>(ties[i])];
    const std::string is_hidden =
        std::find(hidden.begin(), hidden.end(), g.id) != hidden.end()                 ? ", hidden"
        : std::find(unlabelled.begin(), unlabelled.end(), g.id) != unlabelled.end() ? ", no room"
                                                                                       : "";
    // As the label reads, then the key number (short: a long line is cut).
    if (tied > 1)
      lines.push_back({to_rgba8(cluster_color(ties[i], glyphs.options.top_clusters)),
                       "#" + std::to_string(g.id) + "-#" + std::to_string(g.id + tied - 1) + "  " +
                           std::to_string(tied) + " tied at " + display_number(g.min_quality, 3) + is_hidden});
    else
      lines.push_back({to_rgba8(cluster_color(ties[i], glyphs.options.top_clusters)),
                       "#" + std::to_string(g.id) + " (" + std::to_string(g.size) + ")  min " +
                           display_number(g.min_quality, 3) + is_hidden});
  }
  if (glyphs.clusters.size() > listed) {
    // The grey ones' range of min quality (they may be as bad as a
    // coloured one only when ties ran past the palette).
    // Inverted or about 0 (degenerate) ones unfaded (issue 44 part U), a
    // line of their own; the rest pale.
    std::size_t strong = listed;
    while (strong < glyphs.clusters.size() && !is_faded_grey_glyph(glyphs.clusters[strong])) ++strong;
    auto others = [&](std::size_t from, std::size_t to, Rgba8 swatch, const std::string& what) {
      if (to <= from) return;
      const std::size_t rest = to - from;
      const double lo = glyphs.clusters[from].min_quality, hi = glyphs.clusters[to - 1].min_quality;
      lines.push_back({swatch, std::to_string(rest) + (rest == 1 ? " other" : " others") + what + ": " +
                                   display_number(lo, 2) + (rest == 1 ? "" : " to " + display_number(hi, 2))});
    };
    others(listed, strong, grey_glyph_color(0.0f), "");
    others(strong, glyphs.clusters.size(), pale_grey_glyph_color(), "");
  }
  if (coloured_tie)
    lines.push_back({std::nullopt, "tied: min within " + display_number(kGlyphTieTolerance, 2)});
  if (left_out > 0)
    lines.push_back({std::nullopt, std::to_string(left_out) + " not drawn: >" +
                                       std::to_string(static_cast<int>(kThinnedCoverage * 100)) + "% covered"});
  if (glyphs.clusters.empty())
    lines.push_back({options.background, "none: no quality below " + display_number(1.0 - glyphs.options.threshold, 3)});
  // The size key (issue 44 part U, round 2: "drawn x0.73: #0 42 px" said
  // neither radius nor what the factor was): the rule, #0's drawn radius
  // on screen (worst_pixels, when known; else the floor's), and in words
  // why every glyph is drawn larger (the kWorstGlyphMinPixels floor) or
  // smaller (the kWorstGlyphMaxEdges / kWorstGlyphMaxDiagonal cap) than
  // its radius in model units.
  lines.push_back({std::nullopt, "glyph radius \u221d 1 - min quality", 1});
  if (glyphs.options.size_rule == GlyphSizeRule::kPaper)
    lines.push_back({std::nullopt, "  + 0.1 per 10 vertices (paper)"});
  if (!glyphs.clusters.empty() && glyphs.clusters[0].radius > 0.0 && (glyph_scale != 1.0 || worst_pixels > 0.0)) {
    const GlyphSizeLimits limits = glyph_size_limits(options);
    const double px = worst_pixels > 0.0 ? worst_pixels : limits.min_pixels * style.scale;
    lines.push_back({std::nullopt, "#0 radius " + std::to_string(std::lround(px)) + " px"});
    if (glyph_scale < 1.0) {
      lines.push_back({std::nullopt, "  all shrunk x" + display_number(glyph_scale, 2) + ": #0 at most"});
      lines.push_back({std::nullopt, limits.max_edges != kWorstGlyphMaxEdges
                                         ? "  " + display_number(limits.max_edges, 2) + " mean edge and 3% of"
                                         : "  1 mean edge, 3% of model size"});
      if (limits.max_edges != kWorstGlyphMaxEdges)
        lines.push_back({std::nullopt, "  model size, so faces show"});
    } else if (glyph_scale > 1.0) {
      lines.push_back({std::nullopt, "  all enlarged x" + display_number(glyph_scale, 2) + ": #0 at"});
      lines.push_back({std::nullopt, "  least " + std::to_string(static_cast<int>(limits.min_pixels)) +
                                         " px (at 1600 x 1200)"});
    }

  }
  if (!glyphs.clusters.empty()) {
    lines.push_back({std::nullopt, "label #k (n): rank k, n vertices"});
    if (coloured_tie) {
      lines.push_back({std::nullopt, "  #k-#m tied (n): ranks k to m"});
      lines.push_back({std::nullopt, "  equal, n vertices together"});
    }
  }
  // The coloured edge lines that scene step 2 draws around each cluster's
  // worst vertices: their colour is the cluster's, their meaning said here.
  // A line swatch in #0's colour; the count is the vertices the lines
  // really surround: those build_main_scene step 2 marks
  // (worst_cluster_vertices: every member of a coloured tie class alike),
  // counted, not the cap nor one member's (star_twisted: "#0's 7 vertices"
  // under edges at 30 tied glyphs).
  if (!glyphs.clusters.empty() && options.cluster_edge_vertices > 0) {
    const std::vector<std::uint8_t> marked = worst_cluster_vertices(glyphs, options.cluster_edge_vertices, ties);
    const auto surrounded = static_cast<std::size_t>(std::count(marked.begin(), marked.end(), std::uint8_t{1}));
    std::size_t members = 0, classes = 0;
    for (std::size_t i = 0; i < listed; ++i) {
      members += static_cast<std::size_t>(std::max<Index>(glyphs.clusters[i].size, 0));
      classes += i == 0 || ties[i - 1] != ties[i] ? 1 : 0;
    }
    const bool capped = surrounded < members;
    const std::string n = std::to_string(surrounded);
    const std::string worst = worst_is_tied ? "#0-#" + std::to_string(tie_sizes[0] - 1) : "#0";
    // No swatch when no pixel of them shows (all under the glyphs).
    const std::optional<Rgba8> swatch =
        cluster_edges_seen ? std::optional(to_rgba8(cluster_color(0, glyphs.options.top_clusters))) : std::nullopt;
    if (classes == 1)
      lines.push_back({swatch,
                       "edges at " + worst + "'s " + n + (capped ? " worst" : "") +
                           (surrounded == 1 ? " vertex" : " vertices"),
                       0, SwatchShape::thick_line});
    else if (classes > 1) {
      lines.push_back({swatch, "edges at " + n + (capped ? " worst vertices" : " glyph vertices"), 0,
                       SwatchShape::thick_line});
      lines.push_back({std::nullopt, "  (each in its cluster's colour)"});
    }
    if (classes > 0 && !cluster_edges_seen) lines.push_back({std::nullopt, "  (all under the glyphs)"});
  }
  // The rings as the view draws them (draw_worst_glyph_ring,
  // draw_inverted_glyph_rings): ring swatches, unlike the square ones.
  if (!glyphs.clusters.empty() && glyphs.clusters[0].radius > 0.0)
    lines.push_back({style.text_color,
                     worst_is_tied ? "ring: worst clusters #0-#" + std::to_string(tie_sizes[0] - 1)
                                   : std::string("ring: worst cluster #0"),
                     0, SwatchShape::solid_ring, kWorstBandColor});
  // Ringed glyphs on the far side wear it pale (draw_worst_glyph_ring).
  if (!glyphs.clusters.empty() && glyphs.clusters[0].radius > 0.0) {
    const std::size_t ringed = worst_is_tied ? static_cast<std::size_t>(tie_sizes[0]) : 1;
    std::string far;
    for (std::size_t k = 0; k < ringed && k < glyphs.clusters.size(); ++k)
      if (is_far_side(static_cast<Index>(k), options)) far += (far.empty() ? "#" : ", #") + std::to_string(k);
    if (!far.empty())
      lines.push_back({far_side_color(style.text_color), "pale ring: " + far + " on the far side", 0,
                       SwatchShape::solid_ring, far_side_color(kWorstBandColor)});
  }
  if (!glyphs.clusters.empty() && has_inverted_ring(glyphs.clusters[0], options))
    lines.push_back({to_rgba8(kInvertedColor), "ring: inverted (min < 0)", 0, SwatchShape::solid_ring});
  // A surface mesh's coloured glyphs seen through it, in the first such one's pale colour.
  {
    std::vector<Index> storage;
    const std::span<const Index> ties = tie_classes_of(glyphs, options.glyph_ties, storage);
    const Index coloured = coloured_classes_of(glyphs, ties);
    for (const AggregatedGlyph& g : glyphs.clusters)
      if (!is_grey_glyph(g.id, ties, coloured) && is_far_side(g.id, options)) {
        lines.push_back({far_side_color(glyph_color(g.id, ties, coloured, glyphs)), "pale: glyph on the far side", 0});
        break;
      }
  }
  // Findings and places by kind, as the markers count them: the "xN"
  // labels of the marker groups add up to the two findings counts.
  std::size_t findings[2] = {0, 0};
  if (overlap)
    for (const OverlapMarker& m : overlap->markers) {
      const int kind = m.kind == MarkerKind::coincident ? 0 : 1;
      findings[kind] += static_cast<std::size_t>(std::max<Index>(m.count, 1));
    }
  const std::size_t intersecting = overlap ? static_cast<std::size_t>(overlap->num_intersecting_cells) : 0;
  // One word for one count (issue 45): "hexes" on a pure-hex mesh, as its
  // page's cards, overlap table and overview say; "cells" on a hybrid one.
  const std::string cells_word = plural(options.cell_noun);
  // The inverted cells and which of their boundary faces the view draws
  // (issue 44 part U, round 2: a legend said nothing of dolphin_rot's 759
  // faces left out). A surface mesh's fill lines count them.
  if (options.inverted_cell_count > 0 && !options.surface_cell_quality) {
    const std::size_t faces = options.inverted_face_count, drawn = options.inverted_overlay_faces;
    // A swatch only when faces are drawn (nothing else wears it).
    lines.push_back({drawn > 0 && faces <= kMaxInvertedOverlayVolumeFaces ? std::optional(to_rgba8(kInvertedColor))
                                                                          : std::nullopt,
                     "inverted " + cells_word + ": " + std::to_string(options.inverted_cell_count), 1});
    if (faces == 0)
      lines.push_back({std::nullopt, "  none on the boundary"});
    else if (faces > kMaxInvertedOverlayVolumeFaces) {
      lines.push_back({std::nullopt, "  their " + std::to_string(faces) + " boundary faces"});
      lines.push_back({std::nullopt, "  not drawn (more than " + std::to_string(kMaxInvertedOverlayVolumeFaces) + ")"});
    } else {
      // One depth rule (issue 44 part V): drawn near and far, as the glyphs.
      lines.push_back({std::nullopt, "  " + std::string(drawn == faces ? "all " : "") + std::to_string(drawn) +
                                         " boundary faces drawn"});
      lines.push_back({std::nullopt, "  (see-through, as glyphs)"});
    }
  }
  // The outlines drawn over the glyphs that hide such faces: a line swatch
  // per colour drawn (44p review: a mark without a legend entry).
  for (const Rgba8& color : outlines_over_glyphs)
    lines.push_back({color, "outline: face behind a glyph", 0, SwatchShape::line});
  // An unrun check has no number and no swatch (nothing of its colours is
  // drawn): "0" would read as "checked, none found".
  if (overlap) {
    // The findings as the view marks them, with arrows; the cells as their
    // translucent faces look on the background (44p review: pairs and
    // cells shared one swatch).
    // A swatch only for what is drawn: none for a count of 0.
    const auto swatch = [](std::size_t count, const Rgba8& color) {
      return count > 0 ? std::optional(color) : std::nullopt;
    };
    lines.push_back({swatch(findings[0], kCoincidentArrowColor), "coincident vertices: " + std::to_string(findings[0]),
                     1, SwatchShape::arrow});
    lines.push_back({swatch(findings[1], kIntersectionArrowColor), "intersecting pairs: " + std::to_string(findings[1]),
                     0, SwatchShape::arrow});
    // A surface mesh's page, overview and overlap table say "intersecting
    // faces": one word for one count (issue 47 part F).
    lines.push_back({swatch(intersecting, blend_over(kIntersectingCellColor, options.background)),
                     "intersecting " + (options.surface_cell_quality ? std::string("faces") : cells_word) + ": " +
                         std::to_string(intersecting)});
    if (intersecting > 0) lines.push_back({kIntersectionArrowColor, "  their edges", 0, SwatchShape::thick_line});
  } else if (options.surface_cell_quality) {
    lines.push_back({std::nullopt, "overlap: not checked", 1});
    lines.push_back({std::nullopt, "  on surface meshes"});
  } else {
    lines.push_back({std::nullopt, "overlap: not checked", 1});
  }
  if (overlap && !overlap->markers.empty()) {
    lines.push_back({std::nullopt, "label xN: N of its colour's kind"});
    // More findings than a fan's arrows: a fan can be capped (its label
    // then says "(M shown)").
    const int cap = std::max(1, options.max_arrows_per_marker);
    Index findings = 0;
    for (const OverlapMarker& m : overlap->markers) findings += m.count;
    if (findings > cap) lines.push_back({std::nullopt, "  at most " + std::to_string(cap) + " arrows a label"});
  }
  if (options.surface_cell_quality) {
    const std::vector<LegendLine> fill =
        surface_fill_legend_lines(*options.surface_cell_quality, options.surface_inverted_cells,
                                  options.surface_inverted_are_reversed);
    lines.insert(lines.end(), fill.begin(), fill.end());
  }
  // On a mesh of several kinds the boundary edges are in their kinds'
  // colours (no edge is kWireframeColor).
  if (options.cell_kinds.empty())
    lines.push_back({options.surface_cell_quality ? kSurfaceEdgeColor : kWireframeColor,
                     options.surface_cell_quality ? "edges" : "boundary edges", 0, SwatchShape::line});
  // "cells: 64 hex, 484 tet, 16 pyramid" as a heading and one line per kind
  // (one line would be cut in the legend's width).
  // Each with its boundary edges' colour.
  if (!options.cell_kinds.empty()) {
    lines.push_back({std::nullopt, "edge colour by cell kind", 1});
    for (const auto& [color, text] : cell_kind_swatches(options.cell_kinds))
      lines.push_back({color, text, 0, SwatchShape::line});
  }
  return lines;
}

namespace {

// The visible part of a glyph in an id image (layout_main_view_labels).
struct VisibleGlyph {
  std::size_t pixels = 0;  // pixels showing the glyph
  ScreenDisc leader_from;  // where a leader to it starts (inside its visible pixels)
  bool is_mostly_hidden = false;
};

// lines_hide: edge lines over the glyph count as hiding it (else as part
// of it: the leader's start then slides past them, slide_leader_start).
VisibleGlyph visible_glyph(const IdImage& ids, std::uint32_t id, const ScreenDisc& disc, bool lines_hide) {
  VisibleGlyph result;
  // The disc's box and a 2-pixel margin (beyond the id image: background).
  const int left = static_cast<int>(std::floor(disc.x - disc.radius)) - 2;
  const int top = static_cast<int>(std::floor(disc.y - disc.radius)) - 2;
  const int w = static_cast<int>(std::ceil(disc.x + disc.radius)) + 3 - left;
  const int h = static_cast<int>(std::ceil(disc.y + disc.radius)) + 3 - top;
  if (w <= 0 || h <= 0 || static_cast<double>(w) * h > 4.0e7) return result;
  // own: pixels showing the glyph, or an edge line over it (a line of 1-3
  // px crossing a glyph does not hide it: the leader's start slides past it,
  // slide_leader_start); others: the rest of the box.
  std::vector<std::uint8_t> own(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  std::vector<std::array<int, 2>> others;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const std::uint32_t at = ids.at(left + u, top + v, kIdBackground);
      const bool is_on_disc = std::hypot(left + u + 0.5 - disc.x, top + v + 0.5 - disc.y) < disc.radius - 0.5;
      const bool is_own = at == id || (!lines_hide && is_line_id(at) && is_on_disc);
      own[static_cast<std::size_t>(v) * static_cast<std::size_t>(w) + static_cast<std::size_t>(u)] = is_own ? 1 : 0;
      if (at == id) ++result.pixels;
      if (!is_own) others.push_back({left + u, top + v});
    }
  if (result.pixels == 0) return result;
  // Distance from (x, y) to the centre of the nearest pixel not showing the
  // glyph: a disc of that radius less 1 px about (x, y) covers only pixels
  // that show it or a line over it (a point of it is within 0.71 px of its
  // pixel's centre).
  auto clearance = [&](double x, double y) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& p : others) best = std::min(best, std::hypot(p[0] + 0.5 - x, p[1] + 0.5 - y));
    return best;
  };
  const auto id_at = [&](double x, double y) { return ids.at(static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y))); };
  if (id_at(disc.x, disc.y) == id || (!lines_hide && is_line_id(id_at(disc.x, disc.y)))) {
    const double d = clearance(disc.x, disc.y);
    if (d >= 0.5 * disc.radius) {
      result.leader_from = {disc.x, disc.y, std::max(0.0, d - 1.0), disc.id};
      return result;
    }
  }
  // Mostly hidden: about the visible pixel farthest from the other glyphs
  // and #0's rings, at least a pixel inside its silhouette where it can
  // (the 44m brief, 44l review M5: a sliver's middle 3 px from #0's ring
  // read as pointing at #0; its edge beside the background does not), then
  // farthest from anything else (a 3-4 chamfer distance; ties: nearest the
  // glyph's centre, then the first in rows).
  constexpr int kFar = 1 << 28;
  // The chamfer distance from the pixels `is_seed` picks (own pixels never).
  const auto chamfer = [&](auto&& is_seed) {
    std::vector<int> dist(own.size());
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) {
        const std::size_t k = static_cast<std::size_t>(v) * static_cast<std::size_t>(w) + static_cast<std::size_t>(u);
        dist[k] = own[k] || !is_seed(ids.at(left + u, top + v, kIdBackground)) ? kFar : 0;
      }
    auto at = [&](int u, int v) -> int& { return dist[static_cast<std::size_t>(v) * static_cast<std::size_t>(w) + static_cast<std::size_t>(u)]; };
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < w; ++u) {
        int& d = at(u, v);
        if (d == 0) continue;
        if (u > 0) d = std::min(d, at(u - 1, v) + 3);
        if (v > 0) {
          d = std::min(d, at(u, v - 1) + 3);
          if (u > 0) d = std::min(d, at(u - 1, v - 1) + 4);
          if (u + 1 < w) d = std::min(d, at(u + 1, v - 1) + 4);
        }
      }
    for (int v = h - 1; v >= 0; --v)
      for (int u = w - 1; u >= 0; --u) {
        int& d = at(u, v);
        if (d == 0) continue;
        if (u + 1 < w) d = std::min(d, at(u + 1, v) + 3);
        if (v + 1 < h) {
          d = std::min(d, at(u, v + 1) + 3);
          if (u + 1 < w) d = std::min(d, at(u + 1, v + 1) + 4);
          if (u > 0) d = std::min(d, at(u - 1, v + 1) + 4);
        }
      }
    return dist;
  };
  const std::vector<int> dist = chamfer([](std::uint32_t) { return true; });
  const std::vector<int> from_glyphs =
      chamfer([](std::uint32_t at) { return at >= kIdGlyph || at == kIdAnnotation || at == kIdMarker; });
  // 6: a pixel off the silhouette's edge pixels (3 or 4), if any is.
  int inside = 0;
  for (std::size_t k = 0; k < own.size(); ++k)
    if (own[k]) inside = std::max(inside, std::min(dist[k], 6));
  int best_u = -1, best_v = -1;
  std::size_t best = 0;
  double best_centre = 0.0;
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const std::size_t k = static_cast<std::size_t>(v) * static_cast<std::size_t>(w) + static_cast<std::size_t>(u);
      if (!own[k] || dist[k] < inside) continue;
      const double centre = std::hypot(left + u + 0.5 - disc.x, top + v + 0.5 - disc.y);
      const auto key = std::pair{from_glyphs[k], dist[k]}, best_key = std::pair{from_glyphs[best], dist[best]};
      if (best_u < 0 || key > best_key || (key == best_key && centre < best_centre)) {
        best_u = u;
        best_v = v;
        best = k;
        best_centre = centre;
      }
    }
  const double x = left + best_u + 0.5, y = top + best_v + 0.5;
  result.leader_from = {x, y, std::max(0.0, clearance(x, y) - 1.0), disc.id};
  result.is_mostly_hidden = true;
  return result;
}

void mark_drawn(IdImage& ids, const MainViewLabels& labels, const GlyphResult& glyphs, AnnotationStyle style,
                MainViewOptions scaled, bool is_labels);

// Moves a leader's start along the leader towards its leader_from centre,
// in 0.25 px steps, until it lies on a pixel showing glyph id (past an edge
// line over the glyph); when the leader runs along such a line, to the
// centre of the nearest pixel showing it within 4 px; else false.
bool slide_leader_start(PlacedLabel& p, const ScreenDisc& from, const IdImage& ids, std::uint32_t id) {
  if (!p.has_leader) return true;
  const double x0 = p.leader_x0, y0 = p.leader_y0;
  const double dx = from.x - p.leader_x0, dy = from.y - p.leader_y0;
  const double length = std::hypot(dx, dy);
  const int steps = static_cast<int>(std::floor(length / 0.25));
  for (int i = 0; i <= steps; ++i) {
    const double t = length > 0.0 ? 0.25 * i / length : 0.0;
    const double x = p.leader_x0 + t * dx, y = p.leader_y0 + t * dy;
    if (ids.at(static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y))) == id) {
      p.leader_x0 = x;
      p.leader_y0 = y;
      return true;
    }
  }
  double best = 4.0;
  bool found = false;
  for (int v = static_cast<int>(std::floor(y0)) - 4; v <= static_cast<int>(std::floor(y0)) + 4; ++v)
    for (int u = static_cast<int>(std::floor(x0)) - 4; u <= static_cast<int>(std::floor(x0)) + 4; ++u) {
      const double d = std::hypot(u + 0.5 - x0, v + 0.5 - y0);
      if (d <= best && ids.at(u, v) == id) {
        best = d;
        p.leader_x0 = u + 0.5;
        p.leader_y0 = v + 0.5;
        found = true;
      }
    }
  return found;
}

// Ids of the arrow fans' discs among the glyphs' (ranks) in place_labels.
constexpr std::int64_t kFanIdBase = std::int64_t{1} << 40;
// Ids of the fans' arrow shafts (fan_arrow_discs): no label's own.
constexpr std::int64_t kArrowIdBase = std::int64_t{1} << 41;

// A fan's arrows as chains of discs along them, pixels (the 44d review:
// the "#2 (4)" leader lay on the bottom arrow of #2's x8 fan, the x8
// leader on its right one): the heads under the fan's id (fan_id, its own
// label's leader leaves the fan between them), the shafts under
// kArrowIdBase + the fan's index, 5 px wider than the shaft, so that no
// leader runs along an arrow or within a halo's width of one.
void add_fan_arrow_discs(std::vector<ScreenDisc>& discs, const std::array<double, 2>& tip,
                         const std::array<double, 2>& tail, double pixels_per_unit_scale, std::int64_t fan_id,
                         std::int64_t index) {
  const double dx = tail[0] - tip[0], dy = tail[1] - tip[1];
  const double length = std::hypot(dx, dy);
  if (!(length > 0.0)) return;
  const double head = std::min(length, 20.0 * pixels_per_unit_scale);
  const int steps = static_cast<int>(std::ceil(length / 2.0));
  for (int i = 0; i <= steps; ++i) {
    const double s = length * i / steps;
    const bool is_head = s < head;
    const double radius = is_head ? 6.5 * pixels_per_unit_scale * s / head + 1.0 : (2.2 + 5.0) * pixels_per_unit_scale;
    discs.push_back({tip[0] + dx * s / length, tip[1] + dy * s / length, radius,
                     is_head ? fan_id : kArrowIdBase + index});
  }
}

// The longest leader a label gets, as a share of the view's diagonal
// (issue 44 part V round 2: callout leaders of 540-700 px at 1600 x 1200).
constexpr double kMaxLeaderShare = 1.0 / 3.0;

// View A's labels are placed in up to this many orders (layout_main_view_labels).
constexpr int kMainLayoutRounds = 4;

double leader_length(const PlacedLabel& p) {
  return p.has_leader ? std::hypot(p.leader_x1 - p.leader_x0, p.leader_y1 - p.leader_y0) : 0.0;
}

// Whether p's leader runs over an obstacle disc (glyph, #0's rings, fan)
// other than the label's own (its glyph, its tie class's, its fan) and
// those holding the leader's start, unless it heads into them
// (leader_over_disc; the 44l review: near leaders over bunny's, a turned
// dolphin's and warrior's glyphs, "#3 behind #1" through #1).
bool leader_over_others(const MainViewLabel& l, const PlacedLabel& p, std::span<const ScreenDisc> obstacles) {
  const bool is_cluster = l.kind == MainViewLabel::Kind::cluster;
  const std::int64_t own_end = std::max<std::int64_t>(l.cluster + 1, l.protect_end);
  return p.has_leader && std::any_of(obstacles.begin(), obstacles.end(), [&](const ScreenDisc& d) {
           const bool own = d.id == kFaceObstacleId ||
                            (is_cluster ? (d.id >= l.cluster && d.id < own_end) || (l.cluster == 0 && d.id == kRingsObstacleId)
                                        : d.id == l.anchor.id);
           return !own && leader_over_disc(p, ScreenDisc{d.x, d.y, d.radius - 0.5, d.id});
         });
}

// A layout's faults, worst first: its clusters with no room, then its
// labels whose leader crosses other glyphs (leader_over_others).
std::pair<std::size_t, std::size_t> layout_faults(const MainViewLabels& labels, std::span<const ScreenDisc> obstacles) {
  std::size_t over = 0;
  for (const MainViewLabel& l : labels.labels) over += leader_over_others(l, l.placement, obstacles) ? 1 : 0;
  return {labels.unlabelled_clusters.size(), over};
}

// The labels that found no place near their anchor, or only one with a
// leader longer than max_leader (deferred; such a label's placement is that
// place, its fallback), in the margin callout columns (place_callout_columns,
// issue 44 part V): a cluster's leader starts inside its glyph's visible
// pixels (leader_from), a marker's at its anchor's edge; the slots avoid the
// labels placed, the glyph discs, #0's rings and the fans, and (with an id
// image) the model's pixels where they can. The labels placed near their
// glyphs stay where they are (round 2: round 1 moved those in a callout
// leader's way into the callouts too, #0's short leader became 700 px).
// A callout is kept only if its leader crosses no coloured glyph (ids below
// coloured_ids) but its own tie class's, no placed label's box or leader,
// and is at most max_leader long (and, for a label with a fallback, better
// than the fallback: off the glyphs its leader crosses, or shorter); else
// the fallback, else a marker label at its
// anchor's right, clamped to the view (the counts add up), a cluster label
// left out (omitted_clusters).
void place_main_view_callouts(MainViewLabels& result, std::vector<MainViewLabel> deferred,
                              std::span<const ScreenDisc> obstacles, const IdImage& seen, const AnnotationStyle& style,
                              const LabelLayoutOptions& options, Index coloured_ids, double max_leader) {
  auto cost = [&](const PixelRect& box) {
    // 0.15 px of leader per model pixel hidden: empty margin first.
    double covered = 0.0;
    for (int y = box.y; y < box.y + box.height; ++y)
      for (int x = box.x; x < box.x + box.width; ++x) covered += seen.at(x, y, kIdBackground) != kIdBackground ? 1.0 : 0.0;
    return 0.15 * covered;
  };
  // The near labels and the fallbacks: callouts keep clear of them all.
  std::vector<PlacedLabel> kept;
  for (const MainViewLabel& l : result.labels) kept.push_back(l.placement);
  for (const MainViewLabel& l : deferred)
    if (l.placement.box.width > 0) kept.push_back(l.placement);
  std::vector<PlacedLabel> placed;
  std::vector<PixelRect> taken;
  for (const PlacedLabel& k : kept) taken.push_back(k.box);
  // Their leaders and boxes as chains of small discs that a callout leader
  // avoids where it can, as it does the glyphs (ids below protect, a
  // crossing costing 10^6 in place_callout_columns), so that the checks
  // below pass.
  // Every glyph is protected (the 44l review: a near label whose leader
  // crossed a grey glyph comes here, and its callout should not); a
  // callout over a coloured one is refused below.
  std::vector<ScreenDisc> avoid(obstacles.begin(), obstacles.end());
  const std::int64_t kept_id = kFanIdBase - 1, protect = kFanIdBase;
  // The arrows' shafts too (fan_arrow_discs: no leader along an arrow).
  for (ScreenDisc& d : avoid)
    if (d.id >= kArrowIdBase) d.id = kept_id;
  for (const PlacedLabel& k : kept) {
    if (k.has_leader) {
      const double length = leader_length(k);
      const int n = std::max(1, static_cast<int>(std::ceil(length / 3.0)));
      for (int i = 0; i <= n; ++i) {
        const double t = static_cast<double>(i) / n;
        avoid.push_back({k.leader_x0 + t * (k.leader_x1 - k.leader_x0), k.leader_y0 + t * (k.leader_y1 - k.leader_y0), 1.5,
                         kept_id});
      }
    }
    const double r = 0.5 * k.box.height;
    for (double x = k.box.x + r; x <= k.box.x + k.box.width - r + 0.5 * r; x += r)
      avoid.push_back({std::min(x, k.box.x + k.box.width - r), k.box.y + r, r, kept_id});
  }
  for (int round = 0; round < 8 && !deferred.empty(); ++round) {
    std::vector<CalloutLabel> requests;
    for (const MainViewLabel& l : deferred) {
      const int size = l.kind == MainViewLabel::Kind::cluster ? cluster_label_size(style) : marker_label_size(style);
      const LabelRequest r = label_request(l.text, size, l.anchor, style);
      // Its leader crosses no coloured glyph (but its own), label or leader
      // where the columns allow.
      requests.push_back({l.leader_from.value_or(l.anchor), r.width, r.height, protect});
    }
    placed = place_callout_columns(requests, avoid, taken, options.bounds, options.gap,
                                   seen.empty() ? std::function<double(const PixelRect&)>{} : cost);
    if (placed.empty()) break;
    // A cluster's leader ends on its glyph's pixels (past a line over it),
    // else it starts again from the pixels no line covers.
    bool is_again = false;
    for (std::size_t i = 0; i < deferred.size(); ++i) {
      MainViewLabel& l = deferred[i];
      if (l.kind != MainViewLabel::Kind::cluster || !l.leader_from || seen.empty()) continue;
      const auto own = kIdGlyph + static_cast<std::uint32_t>(l.anchor.id);
      if (slide_leader_start(placed[i], *l.leader_from, seen, own)) continue;
      const VisibleGlyph strict = visible_glyph(seen, own, l.anchor, true);
      if (strict.pixels == 0 || (strict.leader_from.x == l.leader_from->x && strict.leader_from.y == l.leader_from->y))
        continue;
      l.leader_from = strict.leader_from;
      is_again = true;
    }
    if (!is_again) break;
  }
  auto crosses_coloured = [&](const MainViewLabel& l, const PlacedLabel& p) {
    const std::int64_t own_end = std::max<std::int64_t>(l.cluster + 1, l.protect_end);
    return std::any_of(result.coloured_glyphs.begin(), result.coloured_glyphs.end(), [&](const ScreenDisc& d) {
      const bool own = l.kind == MainViewLabel::Kind::cluster && d.id >= l.cluster && d.id < own_end;
      return !own && d.id < coloured_ids && leader_meets_disc(p, ScreenDisc{d.x, d.y, d.radius - 0.5, d.id});
    });
  };
  for (std::size_t i = 0; i < deferred.size(); ++i) {
    MainViewLabel& label = deferred[i];
    const bool has_fallback = label.placement.box.width > 0;
    if (i < placed.size()) {
      const PlacedLabel& p = placed[i];
      // Better than the fallback: off the glyphs that the fallback's leader
      // crosses, or shorter and over no glyph the fallback keeps off.
      const bool is_over = leader_over_others(label, p, obstacles);
      const bool is_fallback_over = has_fallback && leader_over_others(label, label.placement, obstacles);
      const bool is_shorter = has_fallback && leader_length(p) < leader_length(label.placement);
      const bool is_better = !has_fallback || (!is_over && (is_fallback_over || is_shorter)) ||
                             (is_over && is_fallback_over && is_shorter);
      bool ok = leader_length(p) <= max_leader && !crosses_coloured(label, p) && is_better;
      for (std::size_t k = 0; ok && k < kept.size(); ++k) {
        const PlacedLabel& near = kept[k];
        if (has_fallback && near.box.x == label.placement.box.x && near.box.y == label.placement.box.y) continue;
        ok = !leaders_cross(p, near) && !leader_meets_box(p, near.box) && !leader_meets_box(near, p.box);
      }
      if (ok) {
        label.placement = p;
        label.always_leader = true;
        label.is_callout = true;
        result.labels.push_back(label);
        continue;
      }
    }
    if (has_fallback) {
      result.labels.push_back(label);
      continue;
    }
    if (label.kind == MainViewLabel::Kind::cluster) {
      ++result.omitted_clusters;
      result.unlabelled_clusters.push_back(label.cluster);
      continue;
    }
    // No free place in the whole view: at the anchor's right, clamped to the view.
    const LabelRequest request = label_request(label.text, marker_label_size(style), label.anchor, style);
    PixelRect box{static_cast<int>(std::lround(label.anchor.x + label.anchor.radius)),
                  static_cast<int>(std::lround(label.anchor.y)), request.width, request.height};
    box.x = std::clamp(box.x, options.bounds.x, options.bounds.x + options.bounds.width - box.width);
    box.y = std::clamp(box.y, options.bounds.y, options.bounds.y + options.bounds.height - box.height);
    label.placement = PlacedLabel{box};
    if (disc_box_gap(label.anchor, box) > options.leader_distance) label.placement = with_leader(label.anchor, box);
    result.labels.push_back(label);
  }
}

}  // namespace

MainViewLabels layout_main_view_labels(const GlyphResult& glyphs, const OverlapReport* overlap, const Camera& camera,
                                       const FigureLayout& layout, const AnnotationStyle& style,
                                       const MainViewOptions& scaled, const IdImage* ids) {
  const double aspect = static_cast<double>(layout.view.width) / static_cast<double>(std::max(1, layout.view.height));
  const ImagePlane plane = image_plane(camera);
  // Figure pixels of a model point, and model units per pixel there.
  auto screen_of = [&](const Vec3& p, double radius) {
    const Vec3 ndc = project_to_ndc(camera, aspect, p);
    const double depth = dot(p - camera.eye, plane.forward);
    return ScreenDisc{layout.view.x + 0.5 * (ndc.x + 1.0) * layout.view.width,
                      layout.view.y + 0.5 * (1.0 - ndc.y) * layout.view.height,
                      radius / units_per_pixel(camera, depth, layout.view.height)};
  };
  auto on_screen = [&](const ScreenDisc& d) {
    return std::isfinite(d.x) && std::isfinite(d.y) && d.x >= layout.view.x &&
           d.x <= layout.view.x + layout.view.width && d.y >= layout.view.y &&
           d.y <= layout.view.y + layout.view.height;
  };
  MainViewLabels result;
  result.camera = camera;
  result.view = layout.view;
  result.glyph_scale = view_glyph_scale(glyphs, camera, layout.view.height, scaled);
  const std::vector<double> shown = displayed_glyph_radii(glyphs, result.glyph_scale);
  const GlyphsDrawn drawn = main_view_glyphs_drawn(glyphs, camera, layout.view.height, shown, scaled.glyph_ties);
  const std::vector<Index> tie_sizes = tie_class_sizes(drawn.tie_class);
  result.left_out_glyphs = drawn.num_left_out;
  result.worst_is_tied = !tie_sizes.empty() && tie_sizes[0] > 1;
  // Obstacles: the glyphs (the 1,000 largest on screen: under the severity
  // rule the first 1,000 ranks; bounded clusters are many, bunny_in 467)
  // and the arrow fans.
  constexpr std::size_t kGlyphObstacles = 1000;
  std::vector<std::pair<double, ScreenDisc>> glyph_discs;
  for (const AggregatedGlyph& g : glyphs.clusters) {
    if (!(g.radius > 0.0) || !drawn.drawn[static_cast<std::size_t>(g.id)]) continue;
    ScreenDisc d = screen_of(g.position, shown[static_cast<std::size_t>(g.id)]);
    d.id = g.id;
    if (on_screen(d) && d.radius >= 1.0) glyph_discs.push_back({d.radius, d});
    if (on_screen(d) && has_inverted_ring(g, scaled)) result.inverted_glyphs.push_back(d);
    if (on_screen(d) && !is_grey_glyph(g.id, drawn.tie_class, drawn.coloured_classes)) result.coloured_glyphs.push_back(d);
    if (on_screen(d) && result.worst_is_tied && drawn.tie_class[static_cast<std::size_t>(g.id)] == 0)
      result.worst_class_glyphs.push_back(d);
  }
  std::stable_sort(glyph_discs.begin(), glyph_discs.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  if (glyph_discs.size() > kGlyphObstacles) glyph_discs.resize(kGlyphObstacles);
  if (!glyphs.clusters.empty() && glyphs.clusters[0].radius > 0.0)
    result.worst_glyph = screen_of(glyphs.clusters[0].position, shown[0]);
  result.worst_glyph.id = 0;
  // What the labels see: the id image with the rings drawn over it.
  IdImage seen;
  if (ids && !ids->empty()) {
    seen = *ids;
    mark_drawn(seen, result, glyphs, style, scaled, false);
  }
  std::vector<ScreenDisc> fans, arrows;
  std::vector<MainViewLabel> markers;
  if (overlap) {
    for (const MarkerFan& fan : marker_fans(glyphs, *overlap, camera, layout.view.height, scaled)) {
      ScreenDisc disc = screen_of(fan.group.position, fan.reach + 6.5 * fan.unit);
      disc.id = kFanIdBase + static_cast<std::int64_t>(fans.size());
      const double scale = screen_of(fan.group.position, fan.unit).radius;  // pixels of one arrow unit
      for (const MarkerFan::Arrow& arrow : fan.arrows) {
        const ScreenDisc tip = screen_of(arrow.tip, 0.0), tail = screen_of(arrow.tail, 0.0);
        add_fan_arrow_discs(arrows, {tip.x, tip.y}, {tail.x, tail.y}, scale, disc.id,
                            static_cast<std::int64_t>(fans.size()));
      }
      fans.push_back(disc);
      MainViewLabel label;
      label.kind = MainViewLabel::Kind::marker;
      label.count = fan.group.count();
      label.text = "x" + std::to_string(label.count);
      // A fan draws at most max_arrows_per_marker arrows: the label says
      // how many when fewer than its count (the 44e review: "x2725" showed
      // 12 arrows and nothing said so).
      if (static_cast<Index>(fan.arrows.size()) < label.count)
        label.text += " (" + std::to_string(fan.arrows.size()) + " shown)";
      label.color = fan.group.kind == MarkerKind::intersection ? kIntersectionArrowColor : kCoincidentArrowColor;
      // Anchored where its arrows point; its own fan is an obstacle, so
      // the label sits next to the fan with a leader line to its centre.
      label.anchor = ScreenDisc{disc.x, disc.y, 3.0 * style.scale, disc.id};
      // A fan centred on #0's glyph: its leader starts at #0's rings, not
      // at the fan's centre (the 44r/44p reviews: gmsh_box's "x15" leader
      // ran across #0's glyph; nothing covers it).
      if (!result.worst_is_tied && result.worst_glyph.radius > 0.0) {
        const double rings =
            worst_rings_extent(result.worst_glyph.radius, has_inverted_ring(glyphs.clusters[0], scaled), style);
        if (std::hypot(disc.x - result.worst_glyph.x, disc.y - result.worst_glyph.y) < rings)
          label.leader_from = ScreenDisc{result.worst_glyph.x, result.worst_glyph.y, rings, disc.id};
      }
      // The same on #1's and #2's glyphs and their inverted rings (the 44c
      // review: gmsh_box's "x15" leader started on #1's centre).
      for (const ScreenDisc& g : result.coloured_glyphs) {
        if (g.id == 0 || (result.worst_is_tied && drawn.tie_class[static_cast<std::size_t>(g.id)] == 0)) continue;
        const double outer = has_inverted_ring(glyphs.clusters[static_cast<std::size_t>(g.id)], scaled)
                                 ? inverted_ring_radius(g.radius, style) + 0.5 * inverted_halo_width(style)
                                 : g.radius + 1.5 * style.scale;
        const double off = std::hypot(disc.x - g.x, disc.y - g.y);
        if (label.leader_from || off >= outer) continue;
        // On its fan's side of the glyph, where its arrows meet (the 44e
        // review: hand_inj_rot's "x13" left #1's far rim 6 px from "#1 (10)"'s
        // leader, a second label of #1); from anywhere on the rim when the
        // fan sits on the glyph's centre.
        label.leader_from = off > 0.25 * g.radius ? ScreenDisc{g.x + (disc.x - g.x) / off * outer,
                                                               g.y + (disc.y - g.y) / off * outer, 0.0, disc.id}
                                                  : ScreenDisc{g.x, g.y, outer, disc.id};
      }
      markers.push_back(label);
    }
    std::stable_sort(markers.begin(), markers.end(),
                     [](const MainViewLabel& a, const MainViewLabel& b) { return a.count > b.count; });
  }
  std::vector<MainViewLabel> clusters;
  // One label per coloured tie class, on its first (labelled) member; a
  // tie's label reads "#k (n) +m tied".
  const Index labelled_classes = drawn.coloured_classes;
  for (std::size_t i = 0; i < glyphs.clusters.size() && drawn.tie_class[i] < labelled_classes; ++i) {
    if (i > 0 && drawn.tie_class[i - 1] == drawn.tie_class[i]) continue;
    const Index tied = tie_sizes[static_cast<std::size_t>(drawn.tie_class[i])];
    // On a surface mesh a tie's label sits on its first member in sight
    // (the 47r review: "#0-#1 tied" named the glyph behind the bell, not
    // the one in front); else on its first member.
    std::size_t anchor = i;
    for (std::size_t k = i; k < i + static_cast<std::size_t>(tied) && k < glyphs.clusters.size(); ++k)
      if (!is_far_side(static_cast<Index>(k), scaled) && drawn.drawn[k] &&
          on_screen(screen_of(glyphs.clusters[k].position, shown[k]))) {
        anchor = k;
        break;
      }
    const AggregatedGlyph& g = glyphs.clusters[anchor];
    ScreenDisc disc = screen_of(g.position, shown[anchor]);
    disc.id = g.id;
    if (!on_screen(disc)) continue;
    MainViewLabel label;
    label.kind = MainViewLabel::Kind::cluster;
    label.cluster = glyphs.clusters[i].id;
    // A tie as a unit: "#0-#29 tied (210)", the class's vertices.
    Index vertices = 0;
    for (Index k = 0; k < tied; ++k) vertices += glyphs.clusters[i + static_cast<std::size_t>(k)].size;
    const Index first = label.cluster;
    label.text = tied > 1 ? "#" + std::to_string(first) + "-#" + std::to_string(first + tied - 1) + " tied (" +
                                std::to_string(vertices) + ")"
                          : "#" + std::to_string(first) + " (" + std::to_string(g.size) + ")";
    if (is_far_side(g.id, scaled)) label.text += ", far side";
    label.protect_end = tied > 1 ? first + tied : first;
    label.color = style.text_color;
    label.anchor = disc;
    if (!seen.empty()) {
      const VisibleGlyph visible = visible_glyph(seen, kIdGlyph + static_cast<std::uint32_t>(g.id), disc, false);
      if (visible.pixels == 0) {
        result.hidden_clusters.push_back(first);
        continue;
      }
      label.leader_from = visible.leader_from;
      label.always_leader = visible.is_mostly_hidden;
      // Mostly hidden behind another glyph (the 44g review: a leader ending
      // on a sliver named nothing one could check): the label says which.
      if (visible.is_mostly_hidden) {
        const std::uint32_t front = seen.at(static_cast<int>(std::floor(disc.x)), static_cast<int>(std::floor(disc.y)));
        if (front >= kIdGlyph && front != kIdGlyph + static_cast<std::uint32_t>(g.id))
          label.text += " behind #" + std::to_string(front - kIdGlyph);
      }
    }
    clusters.push_back(label);
  }
  // Order: cluster #0, the marker groups, the other clusters.
  std::vector<MainViewLabel> order;
  std::size_t first_other = 0;
  if (!clusters.empty() && clusters[0].cluster == 0) {
    order.push_back(clusters[0]);
    first_other = 1;
  }
  order.insert(order.end(), markers.begin(), markers.end());
  order.insert(order.end(), clusters.begin() + static_cast<std::ptrdiff_t>(first_other), clusters.end());

  LabelLayoutOptions options;
  options.bounds = layout.view;
  options.gap = 4.0 * style.scale;
  options.ring_step = 14.0 * style.scale;
  options.rings = static_cast<int>(std::ceil(std::max(layout.view.width, layout.view.height) / options.ring_step));
  options.leader_distance = 10.0 * style.scale;
  // A clear leader's halo (render_main_view) keeps off the other glyphs.
  options.leader_clearance = 0.5 * std::max(3.0, 4.5 * style.scale);
  std::vector<ScreenDisc> all_obstacles;
  for (const auto& g : glyph_discs) all_obstacles.push_back(g.second);
  if (result.worst_glyph.radius > 0.0) {
    all_obstacles.push_back(result.worst_glyph);
    // #0's rings too: no other label or leader crosses them.
    ScreenDisc rings = result.worst_glyph;
    rings.radius = worst_rings_extent(rings.radius, has_inverted_ring(glyphs.clusters[0], scaled), style);
    all_obstacles.push_back(rings);
    // And no label box (#0's own too, issue 44 part U: on a glyph capped
    // small its label box covered much of the rings) comes within #0's
    // radius of the rings: #0's neighbourhood, its worst cells, stays in
    // sight (the 44l review: gmsh_ring_dent's "#0" sat over the funnel);
    // #0's leader crosses it: a disc under an id of no glyph.
    if (!result.worst_is_tied) {
      rings.id = kRingsObstacleId;
      rings.radius += result.worst_glyph.radius;
      all_obstacles.push_back(rings);
    }
  }
  // A tied #0's class: each member's band and ring.
  for (ScreenDisc d : result.worst_class_glyphs) {
    d.radius = worst_rings_extent(d.radius, has_inverted_ring(glyphs.clusters[0], scaled), style);
    all_obstacles.push_back(d);
  }
  all_obstacles.insert(all_obstacles.end(), fans.begin(), fans.end());
  all_obstacles.insert(all_obstacles.end(), arrows.begin(), arrows.end());
  for (std::size_t i = 0; i < scaled.label_free_centres.size(); ++i) {
    ScreenDisc face = screen_of(scaled.label_free_centres[i], scaled.label_free_radii[i]);
    face.id = kFaceObstacleId;
    if (on_screen(face)) all_obstacles.push_back(face);
  }
  std::vector<ScreenDisc> worst_only;
  if (result.worst_glyph.radius > 0.0) worst_only.push_back(result.worst_glyph);
  // #0's own label may sit in its neighbourhood (the 44m brief, 44l review
  // M3: kept out, it went next to other clusters' glyphs or over #0's red
  // edges).
  std::vector<ScreenDisc> worst_label_obstacles;
  std::copy_if(all_obstacles.begin(), all_obstacles.end(), std::back_inserter(worst_label_obstacles),
               [](const ScreenDisc& d) { return d.id != kRingsObstacleId; });
  // The coloured glyphs' ranks: 0 to coloured_ids - 1 (ranked classes first).
  Index coloured_ids = 0;
  for (Index t : drawn.tie_class) coloured_ids += t < drawn.coloured_classes ? 1 : 0;
  const double max_leader =
      kMaxLeaderShare * std::hypot(static_cast<double>(layout.view.width), static_cast<double>(layout.view.height));
  // One greedy placement of the labels in `order`, onto result's copy.
  const MainViewLabels unplaced = result;
  const DiscIndex all_index(all_obstacles), worst_label_index(worst_label_obstacles), worst_only_index(worst_only);
  const auto lay_out = [&](std::vector<MainViewLabel> order) {
    MainViewLabels result = unplaced;
    LabelPlacer placer({}, options);
    // Labels with no place near their glyph, or only one with an overlong
    // leader: the callout columns below.
    std::vector<MainViewLabel> deferred;
    for (MainViewLabel& label : order) {
      const bool is_cluster = label.kind == MainViewLabel::Kind::cluster;
      const int size = is_cluster ? cluster_label_size(style) : marker_label_size(style);
      LabelRequest request = label_request(label.text, size, label.anchor, style);
      request.leader_from = label.leader_from;
      request.always_leader = label.always_leader;
      // No leader crosses a glyph ranked before its own (a marker's: #0).
      // A tie's label: nor any glyph of its class (issue 44 part U).
      request.protect_below = is_cluster ? label.protect_end : 1;
      request.strict_leaders = true;
      // Near its glyph wherever the placer finds a place, as before the
      // callouts (issue 44 part V round 2: a label with a clear near place
      // keeps it; round 1 sent labels with no clear place within 90 px to the
      // callouts, and moved bunny's, kitten's and Dolphin_padded's fine
      // labels), unless its leader runs longer than kMaxLeaderShare of the
      // view's diagonal: then a callout, if one is nearer.
      const DiscIndex& obstacles = is_cluster && label.cluster == 0 ? worst_label_index : all_index;
      std::optional<PlacedLabel> placed = placer.place(request, obstacles);
      if (!placed && !is_cluster) placed = placer.place(request, worst_only_index);
      // So is one whose leader crosses other glyphs (the 44l review): a
      // callout may pass them by.
      if (placed && placed->has_leader &&
          (leader_length(*placed) > max_leader || leader_over_others(label, *placed, all_obstacles))) {
        label.placement = *placed;  // the fallback if no callout is nearer
        placer.add(*placed);        // (kept free for it)
        deferred.push_back(label);
        continue;
      }
      if (!placed) {
        deferred.push_back(label);
        continue;
      }
      if (is_cluster && label.leader_from && !seen.empty()) {
        const auto own = kIdGlyph + static_cast<std::uint32_t>(label.anchor.id);
        if (!slide_leader_start(*placed, *label.leader_from, seen, own)) {
          // The leader runs along a line over the glyph: placed again from
          // the glyph's pixels that no line covers.
          const VisibleGlyph strict = visible_glyph(seen, own, label.anchor, true);
          label.leader_from = request.leader_from = strict.leader_from;
          label.always_leader = request.always_leader = strict.is_mostly_hidden;
          placed = placer.place(request, obstacles);
          if (!placed) {
            deferred.push_back(label);
            continue;
          }
        }
      }
      label.placement = *placed;
      placer.add(*placed);
      result.labels.push_back(label);
    }
    place_main_view_callouts(result, deferred, all_obstacles, seen, style, options, coloured_ids, max_leader);
    return result;
  };
  // Up to kMainLayoutRounds rounds (the 44l review: a turned dolphin's #4,
  // behind #0, was fenced in by the leaders placed before it and found "no
  // room"): the clusters with no room so far, or whose leader crossed other
  // glyphs, go right after #0 and the marker groups; the round with the
  // fewest faults (layout_faults) is kept (the first on a tie).
  MainViewLabels best = lay_out(order);
  std::vector<Index> promoted;
  const std::pair<std::size_t, std::size_t> none{0, 0};
  for (int round = 1; round < kMainLayoutRounds && layout_faults(best, all_obstacles) != none; ++round) {
    std::vector<Index> faulty = best.unlabelled_clusters;
    for (const MainViewLabel& l : best.labels)
      if (l.kind == MainViewLabel::Kind::cluster && leader_over_others(l, l.placement, all_obstacles))
        faulty.push_back(l.cluster);
    bool more = false;
    for (Index c : faulty)
      if (c != 0 && std::find(promoted.begin(), promoted.end(), c) == promoted.end()) {
        promoted.push_back(c);
        more = true;
      }
    if (!more) break;
    const auto is_promoted = [&](const MainViewLabel& l) {
      return l.kind == MainViewLabel::Kind::cluster && l.cluster != 0 &&
             std::find(promoted.begin(), promoted.end(), l.cluster) != promoted.end();
    };
    std::vector<MainViewLabel> again(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(first_other + markers.size()));
    std::copy_if(order.begin() + static_cast<std::ptrdiff_t>(again.size()), order.end(), std::back_inserter(again), is_promoted);
    std::copy_if(order.begin() + static_cast<std::ptrdiff_t>(first_other + markers.size()), order.end(),
                 std::back_inserter(again), [&](const MainViewLabel& l) { return !is_promoted(l); });
    MainViewLabels next = lay_out(std::move(again));
    if (layout_faults(next, all_obstacles) < layout_faults(best, all_obstacles)) best = std::move(next);
  }
  best.ids = std::move(seen);
  return best;
}

namespace {

// The style, layout, camera and scaled options of one main view figure.
struct MainViewFrame {
  AnnotationStyle style;
  FigureLayout layout;
  Camera camera;
  MainViewOptions scaled;
  InvertedFaces inverted;  // inverted_boundary_faces (with_inverted; else none)
};

MainViewFrame main_view_frame(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs,
                              const Vec3& view_direction, const MainViewOptions& options, bool with_inverted = true) {
  FigureFrame3d f = figure_frame_3d(
      "main view", options.width, options.height, options.background,
      [&](const AnnotationStyle& style) { return main_layout(options, style); }, main_view_points(mesh, topology, glyphs),
      view_direction, options.up, options.fov_y_degrees);
  MainViewFrame frame;
  frame.style = f.style;
  frame.layout = f.layout;
  frame.camera = f.camera;
  frame.scaled = options;
  frame.scaled.pixel_scale = frame.style.scale;
  if (with_inverted) {
    frame.inverted = inverted_boundary_faces(topology, options);
    frame.scaled.inverted_overlay_faces = frame.inverted.drawn.size();
    frame.scaled.inverted_cell_count = frame.inverted.cells;
    frame.scaled.inverted_face_count = frame.inverted.faces;
    if (options.surface_cell_quality && frame.inverted.drawn.size() <= kMaxLabelFreeFaces)
      for (const BoundaryPolygon& face : frame.inverted.drawn) {
        auto p = [&](int i) { return mesh.points[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i % face.size)])]; };
        Vec3 centre;
        for (int i = 0; i < face.size; ++i) centre = centre + (1.0 / face.size) * p(i);
        double radius = std::numeric_limits<double>::infinity();
        for (int i = 0; i < face.size; ++i) radius = std::min(radius, norm(0.5 * (p(i) + p(i + 1)) - centre));
        frame.scaled.label_free_centres.push_back(centre);
        frame.scaled.label_free_radii.push_back(radius);
      }
  }
  frame.scaled.model_diagonal_pixels =
      model_diagonal_pixels(mesh, topology, frame.camera, frame.layout.view.width, frame.layout.view.height);
  if (options.surface_cell_quality && !glyphs.clusters.empty()) {
    const std::vector<BoundaryPolygon> faces = boundary_polygons(topology);
    const FaceDepthGrid grid(mesh, faces, frame.camera,
                             static_cast<double>(frame.layout.view.width) / std::max(1, frame.layout.view.height));
    frame.scaled.far_side_glyphs.assign(glyphs.clusters.size(), 0);
    for (std::size_t k = 0; k < glyphs.clusters.size(); ++k)
      frame.scaled.far_side_glyphs[k] = grid.in_sight(glyphs.clusters[k].position) ? 0 : 1;
  }
  return frame;
}

}  // namespace

namespace {

// View A's scene as render_main_view draws it: the wireframe fades when
// dense on screen, so glyphs and clusters stay readable.
Scene main_view_scene(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs,
                      const OverlapReport* overlap, const MainViewFrame& f) {
  Scene scene =
      build_main_scene(mesh, topology, glyphs, overlap, f.camera, f.layout.view.height, f.scaled, &f.inverted);
  const double pixels =
      median_edge_pixels(scene.lines[0], scene.origin, f.camera, f.layout.view.width, f.layout.view.height);
  const double opacity = std::clamp(pixels / 10.0, 0.2, 0.85);
  for (Rgba8& c : scene.lines[0].colors) c.a = static_cast<std::uint8_t>(std::lround(255.0 * opacity));
  return scene;
}

// The rings render_main_view draws around the glyphs.
void draw_glyph_rings(Image& figure, const MainViewLabels& labels, const GlyphResult& glyphs,
                      const AnnotationStyle& style, const MainViewOptions& scaled) {
  // #0's class (ids 0 to n - 1) wears the band.
  std::int64_t banded_below = labels.worst_is_tied ? 0 : 1;
  for (const ScreenDisc& d : labels.worst_class_glyphs) banded_below = std::max(banded_below, d.id + 1);
  draw_inverted_glyph_rings(figure, labels.inverted_glyphs, labels.coloured_glyphs, banded_below, style, scaled);
  const bool is_inverted = !glyphs.clusters.empty() && has_inverted_ring(glyphs.clusters[0], scaled);
  if (!labels.worst_is_tied) draw_worst_glyph_ring(figure, labels.worst_glyph, is_inverted, style, scaled);
  for (const ScreenDisc& d : labels.worst_class_glyphs)
    draw_worst_glyph_ring(figure, d, is_inverted, style, scaled, labels.worst_class_glyphs);
}

// Marks kIdAnnotation where the rings (and with is_labels the leader lines
// and label boxes) are drawn: the same drawing in white on black, a pixel
// at least half white is covered.
void mark_drawn(IdImage& ids, const MainViewLabels& labels, const GlyphResult& glyphs, AnnotationStyle style,
                MainViewOptions scaled, bool is_labels) {
  const Rgba8 white{255, 255, 255, 255};
  style.text_color = white;
  scaled.background = white;
  MainViewLabels white_labels;
  if (is_labels) white_labels.labels = labels.labels;
  for (MainViewLabel& l : white_labels.labels) l.color = white;
  white_labels.worst_glyph = labels.worst_glyph;
  white_labels.worst_is_tied = labels.worst_is_tied;
  white_labels.worst_class_glyphs = labels.worst_class_glyphs;
  white_labels.inverted_glyphs = labels.inverted_glyphs;
  white_labels.coloured_glyphs = labels.coloured_glyphs;
  Image mask = make_image(std::max(1, ids.x0 + ids.width), std::max(1, ids.y0 + ids.height), Rgba8{0, 0, 0, 255});
  draw_glyph_rings(mask, white_labels, glyphs, style, scaled);
  draw_main_view_labels(mask, white_labels, style, scaled);
  for (int y = 0; y < ids.height; ++y)
    for (int x = 0; x < ids.width; ++x) {
      const int fx = x + ids.x0, fy = y + ids.y0;
      if (fx < 0 || fy < 0 || fx >= mask.width || fy >= mask.height) continue;
      if (mask.rgba[pixel_offset(mask, fx, fy)] >= 128)
        ids.ids[static_cast<std::size_t>(y) * static_cast<std::size_t>(ids.width) + static_cast<std::size_t>(x)] =
            kIdAnnotation;
    }
}

// A segment in model coordinates and its colour.
struct ColouredSegment {
  Vec3 a, b;
  Rgba8 color;
};

// The parts of segments that a glyph hides (ids: main_view_id_image shows
// a glyph there), as runs in figure pixels, but not within
// kInvertedOutlineCore of a coloured glyph's radius from its centre (the
// vertex it marks keeps its colour) nor anywhere on #0's disc (worst; the
// 44p review: they crossed #0's glyph).
// rings: discs (the glyph rings' extents) inside which segments are drawn
// too, glyph or not.
std::vector<OutlineRun> segment_runs_over_glyphs(std::span<const ColouredSegment> segments, const Camera& camera,
                                                 const PixelRect& view, const IdImage& ids,
                                                 std::span<const ScreenDisc> coloured, const ScreenDisc& worst,
                                                 std::span<const ScreenDisc> rings) {
  std::vector<OutlineRun> runs;
  if (ids.empty()) return runs;
  const double aspect = static_cast<double>(view.width) / static_cast<double>(std::max(1, view.height));
  auto pixel = [&](const Vec3& p) {
    const Vec3 ndc = project_to_ndc(camera, aspect, p);
    return std::array<double, 2>{view.x + 0.5 * (ndc.x + 1.0) * view.width, view.y + 0.5 * (1.0 - ndc.y) * view.height};
  };
  auto wanted = [&](double x, double y) {
    if (ids.at(static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y)), kIdBackground) < kIdGlyph &&
        std::none_of(rings.begin(), rings.end(),
                     [&](const ScreenDisc& d) { return std::hypot(x - d.x, y - d.y) < d.radius; }))
      return false;
    if (worst.radius > 0.0 && std::hypot(x - worst.x, y - worst.y) < worst.radius + 1.0) return false;
    return std::none_of(coloured.begin(), coloured.end(), [&](const ScreenDisc& d) {
      return std::hypot(x - d.x, y - d.y) < kInvertedOutlineCore * d.radius;
    });
  };
  // Runs of wanted points every 0.5 px, each one segment.
  for (const ColouredSegment& s : segments) {
    const auto a = pixel(s.a), b = pixel(s.b);
    const double length = std::hypot(b[0] - a[0], b[1] - a[1]);
    // (Far off the figure, or not finite: nothing to draw, and no pixel
    // coordinate cast out of int's range.)
    const auto is_near = [](const std::array<double, 2>& p) { return std::abs(p[0]) < 1e6 && std::abs(p[1]) < 1e6; };
    if (!std::isfinite(length) || length > 1e5 || !is_near(a) || !is_near(b)) continue;
    const int steps = std::max(1, static_cast<int>(std::ceil(2.0 * length)));
    int run = -1;
    for (int i = 0; i <= steps + 1; ++i) {
      const double t = std::min(1.0, static_cast<double>(i) / steps);
      const bool in = i <= steps && wanted(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]));
      if (in && run < 0) run = i;
      if (!in && run >= 0) {
        const double t0 = static_cast<double>(run) / steps, t1 = std::min(1.0, static_cast<double>(i - 1) / steps);
        runs.push_back({a[0] + t0 * (b[0] - a[0]), a[1] + t0 * (b[1] - a[1]), a[0] + t1 * (b[0] - a[0]),
                        a[1] + t1 * (b[1] - a[1]), s.color});
        run = -1;
      }
    }
  }
  return runs;
}

}  // namespace

std::vector<OutlineRun> main_view_outlines_over_glyphs(const HexMesh& mesh, const Topology& topology,
                                                       const GlyphResult& glyphs, const MainViewLabels& labels,
                                                       const MainViewOptions& options,
                                                       const AnnotationStyle& style,
                                                       std::span<const BoundaryPolygon> inverted_faces) {
  std::vector<ScreenDisc> rings;
  for (ScreenDisc d : labels.inverted_glyphs) {
    d.radius = inverted_ring_radius(d.radius, style) + 0.5 * inverted_halo_width(style);
    rings.push_back(d);
  }
  ScreenDisc worst;
  if (!labels.worst_is_tied && labels.worst_glyph.radius > 0.0) {
    worst = labels.worst_glyph;
    ScreenDisc d = labels.worst_glyph;
    d.radius = worst_rings_extent(d.radius, !glyphs.clusters.empty() && has_inverted_ring(glyphs.clusters[0], options), style);
    rings.push_back(d);
  }
  std::vector<ColouredSegment> outlines;
  // A surface mesh's glyph seen through it: the faces on the far side (its
  // own, as a rule) are not outlined over it (the 47r review: blue strokes
  // over a far glyph read as faces in front).
  std::optional<FaceDepthGrid> grid;
  if (std::any_of(options.far_side_glyphs.begin(), options.far_side_glyphs.end(), [](char c) { return c != 0; }))
    grid.emplace(mesh, boundary_polygons(topology), labels.camera,
                 static_cast<double>(labels.view.width) / std::max(1, labels.view.height));
  for (const BoundaryPolygon& face : inverted_faces) {
    bool in_sight = !grid;
    for (int k = 0; k < face.size && !in_sight; ++k) in_sight = grid->in_sight(grid->corner_sample(face, k));
    if (!in_sight) continue;
    const Rgba8 color = options.surface_cell_quality
                            ? surface_fill_color((*options.surface_cell_quality)[static_cast<std::size_t>(face.cell)])
                            : to_rgba8(kInvertedColor);
    for (int k = 0; k < face.size; ++k)
      outlines.push_back({mesh.points[static_cast<std::size_t>(face.v[static_cast<std::size_t>(k)])],
                          mesh.points[static_cast<std::size_t>(face.v[static_cast<std::size_t>((k + 1) % face.size)])],
                          color});
  }
  return segment_runs_over_glyphs(outlines, labels.camera, labels.view, labels.ids, labels.coloured_glyphs, worst,
                                  rings);
}

std::vector<Rgba8> outline_colors(std::span<const OutlineRun> runs) {
  std::vector<Rgba8> colors;
  for (const OutlineRun& r : runs)
    if (std::find(colors.begin(), colors.end(), r.color) == colors.end()) colors.push_back(r.color);
  return colors;
}

namespace {

// Draws the runs (main_view_outlines_over_glyphs) kInvertedOutlineWidth px
// wide (times the scale, at least 2 px: a thinner antialiased line has no
// pixel of the face's own colour), after the glyphs' rings (their pale
// halos hid the rest of a small face).
void draw_outline_runs(Image& figure, std::span<const OutlineRun> runs, const AnnotationStyle& style) {
  const double width = std::max(2.0, kInvertedOutlineWidth * style.scale);
  for (const OutlineRun& r : runs) draw_line(figure, r.x0, r.y0, r.x1, r.y1, r.color, width);
}

}  // namespace

void mark_main_view_annotations(IdImage& ids, const MainViewLabels& labels, const GlyphResult& glyphs,
                                const MainViewOptions& options) {
  AnnotationStyle style = annotation_style_for(options.height);
  MainViewOptions scaled = options;
  scaled.pixel_scale = style.scale;
  mark_drawn(ids, labels, glyphs, style, scaled, true);
}

double mesh_glyph_scale(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs,
                        std::span<const Vec3> directions, const MainViewOptions& options) {
  GlyphScaleBounds all{1.0, std::numeric_limits<double>::infinity()};
  bool any = false;
  for (const Vec3& direction : directions) {
    const MainViewFrame f = main_view_frame(mesh, topology, glyphs, direction, options, false);
    const GlyphScaleBounds b = glyph_scale_bounds(glyphs, f.camera, f.layout.view.height, f.scaled.pixel_scale,
                                                  f.scaled.model_diagonal_pixels, glyph_size_limits(options));
    all.lo = any ? std::max(all.lo, b.lo) : b.lo;
    all.hi = std::min(all.hi, b.hi);
    any = true;
  }
  return any ? scale_within(all) : 1.0;
}

bool cluster_edges_in_sight(const MainViewLabels& labels, const AnnotationStyle& style) {
  const IdImage& ids = labels.ids;
  if (ids.empty()) return true;
  for (int y = 0; y < ids.height; ++y)
    for (int x = 0; x < ids.width; ++x) {
      if (ids.ids[static_cast<std::size_t>(y) * static_cast<std::size_t>(ids.width) + static_cast<std::size_t>(x)] !=
          kIdClusterEdge)
        continue;
      const int fx = x + ids.x0, fy = y + ids.y0;
      // (The inverted rings and their halos are drawn over the disc
      // their outer edge bounds; the id image marks only the halos.)
      const auto under_ring = [&](const ScreenDisc& d) {
        return std::hypot(fx + 0.5 - d.x, fy + 0.5 - d.y) <
               inverted_ring_radius(d.radius, style) + 0.5 * inverted_halo_width(style);
      };
      if (std::none_of(labels.labels.begin(), labels.labels.end(),
                       [&](const MainViewLabel& l) {
                         const PixelRect& b = l.placement.box;
                         return fx >= b.x && fx < b.x + b.width && fy >= b.y && fy < b.y + b.height;
                       }) &&
          std::none_of(labels.inverted_glyphs.begin(), labels.inverted_glyphs.end(), under_ring))
        return true;
    }
  return false;
}

MainViewPlan plan_main_view(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs,
                            const OverlapReport* overlap, const Vec3& view_direction, const MainViewOptions& given,
                            Renderer* renderer) {
  MainViewPlan plan;
  MainViewOptions options = given;
  std::vector<Index> ties;  // when not given: computed once for this view, not kept
  options.glyph_ties = tie_classes_of(glyphs, given.glyph_ties, ties);
  const MainViewFrame frame = main_view_frame(mesh, topology, glyphs, view_direction, options);
  plan.style = frame.style;
  plan.layout = frame.layout;
  plan.scaled = frame.scaled;
  plan.scene = main_view_scene(mesh, topology, glyphs, overlap, frame);
  // Labels placed on what is visible (each points at its own glyph's pixels).
  IdImage ids;
  if (renderer)
    ids = main_view_id_image(*renderer, plan.scene, glyphs, frame.camera, plan.layout.view, true, options.glyph_ties);
  plan.labels = layout_main_view_labels(glyphs, overlap, frame.camera, plan.layout, plan.style, plan.scaled,
                                        ids.empty() ? nullptr : &ids);
  plan.outlines =
      main_view_outlines_over_glyphs(mesh, topology, glyphs, plan.labels, plan.scaled, plan.style,
                                     frame.inverted.drawn);
  plan.legend = main_legend_lines(glyphs, overlap, plan.style, plan.scaled, plan.labels.glyph_scale,
                                  plan.labels.hidden_clusters, plan.labels.left_out_glyphs,
                                  plan.labels.unlabelled_clusters, plan.labels.worst_glyph.radius,
                                  outline_colors(plan.outlines), cluster_edges_in_sight(plan.labels, plan.style));
  plan.scaled.glyph_ties = given.glyph_ties;  // the caller's (ties ends here)
  return plan;
}

MainViewLabels main_view_labels(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs,
                                const OverlapReport* overlap, const Vec3& view_direction,
                                const MainViewOptions& options, Scene* scene, Renderer* renderer) {
  MainViewPlan plan = plan_main_view(mesh, topology, glyphs, overlap, view_direction, options, renderer);
  if (scene) *scene = std::move(plan.scene);
  return std::move(plan.labels);
}

Image render_main_view(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs,
                       const OverlapReport* overlap, const Vec3& view_direction, const MainViewOptions& given,
                       Renderer& renderer) {
  const MainViewPlan plan = plan_main_view(mesh, topology, glyphs, overlap, view_direction, given, &renderer);
  Image figure = render_figure(renderer, plan.scene, plan.labels.camera, given.width, given.height, plan.layout,
                               given.title, plan.style);
  // The rings, the outlines over the glyphs, the labels (in this order:
  // each over the one before), the legend.
  draw_glyph_rings(figure, plan.labels, glyphs, plan.style, plan.scaled);
  draw_outline_runs(figure, plan.outlines, plan.style);
  draw_main_view_labels(figure, plan.labels, plan.style, plan.scaled);
  draw_legend(figure, plan.layout.legend, plan.legend, plan.style);
  return figure;
}

}  // namespace hq
