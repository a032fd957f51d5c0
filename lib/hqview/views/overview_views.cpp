#include "hqview/views/overview_views.h"

#include <algorithm>
#include <numbers>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "hqview/core/error.h"
#include "hqview/core/number_format.h"
#include "hqview/core/text.h"
#include "hqview/image/colormap.h"
#include "hqview/mesh/boundary_polygons.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/quality/quad_metrics.h"
#include "hqview/render/annotate.h"
#include "hqview/render/upright.h"
#include "hqview/views/boundary_views.h"
#include "hqview/views/inverted_callout.h"
#include "hqview/views/inverted_inset.h"
#include "hqview/views/overview_viewpoint.h"

namespace hq {
namespace {

Vec3 view_direction_of(const OverviewOptions& options) {
  return squared_norm(options.view_direction) > 0.0 ? options.view_direction : three_quarter_view(options.up);
}

const Vec3& point(const HexMesh& mesh, Index v) { return mesh.points[static_cast<std::size_t>(v)]; }

}  // namespace

FigureFrame3d figure_frame_3d(const std::string& what, int width, int height, Rgba8 background,
                              const std::function<FigureLayout(const AnnotationStyle&)>& make_layout,
                              std::span<const Vec3> points, const Vec3& view_direction, const Vec3& up,
                              double fov_y_degrees) {
  if (width <= 0 || height <= 0)
    throw RenderError(what + " size must be positive, got " + std::to_string(width) + "x" + std::to_string(height));
  FigureFrame3d f;
  f.style = annotation_style_for(height);
  f.style.background = background;
  f.layout = make_layout(f.style);
  const double aspect = static_cast<double>(f.layout.view.width) / std::max(1, f.layout.view.height);
  f.camera = fit_camera_to_points(points, view_direction, aspect,
                                  {.up = up, .fov_y_degrees = fov_y_degrees, .is_perspective = false});
  return f;
}

std::vector<Vec3> boundary_points(const HexMesh& mesh, const Topology& topology) {
  if (num_boundary_faces_all_kinds(topology) == 0) return mesh.points;
  std::vector<char> is_used(mesh.points.size(), 0);
  for (const BoundaryPolygon& face : boundary_polygons(topology))
    for (int i = 0; i < face.size; ++i) is_used[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)])] = 1;
  std::vector<Vec3> points;
  for (std::size_t v = 0; v < is_used.size(); ++v)
    if (is_used[v]) points.push_back(mesh.points[v]);
  return points;
}

Box3 boundary_bounding_box(const HexMesh& mesh, const Topology& topology) {
  Box3 box;
  if (num_boundary_faces_all_kinds(topology) != 0) {
    for (const BoundaryPolygon& face : boundary_polygons(topology))
      for (int i = 0; i < face.size; ++i) box.add(point(mesh, face.v[static_cast<std::size_t>(i)]));
  } else {
    box = bounding_box(mesh.points);
  }
  if (!(box.lo.x <= box.hi.x)) return Box3{Vec3{}, Vec3{}};
  return box;
}

Scene build_quality_overview_scene(const HexMesh& mesh, const Topology& topology,
                                   const std::vector<double>& vertex_quality, const OverviewOptions& options) {
  if (vertex_quality.size() != mesh.points.size())
    throw Error("vertex quality has " + std::to_string(vertex_quality.size()) + " values for " +
                std::to_string(mesh.points.size()) + " vertices");
  const Box3 box = boundary_bounding_box(mesh, topology);

  Scene scene;
  scene.origin = 0.5 * (box.lo + box.hi);
  scene.background = options.background;
  auto local = [&](const Vec3& p) { return to_vec3f(p - scene.origin); };
  auto color = [](double q) { return to_rgba8(quality_color(q)); };

  // Faces: 5 vertices (corners, then centre) and 4 triangles per quad, all
  // with the quad's normal so each quad is one flat facet.
  // Colour after interpolation: the corners' qualities are interpolated and
  // mapped per fragment (ScalarColorMap), so an inverted corner keeps the
  // inverted colour in its part of the face and no face shows a blend that
  // is in no legend; colors holds the same mapping per vertex (alpha, and
  // renderers without per-fragment maps).
  TriangleSet faces;
  faces.color_map = {quality_map_samples(), kInvertedColor, kUndefinedColor};
  const std::vector<BoundaryPolygon> polygons = boundary_polygons(topology);
  const std::size_t num_faces = polygons.size();
  faces.positions.reserve(5 * num_faces);
  faces.normals.reserve(5 * num_faces);
  faces.colors.reserve(5 * num_faces);
  faces.indices.reserve(12 * num_faces);
  const std::array<Index, 5> block_start = volume_block_starts(mesh);
  // The values a face's corners take: its cell's kind's (options.kind_quality) or vertex_quality.
  const auto quality_of_face = [&](const BoundaryPolygon& polygon) -> const std::vector<double>& {
    if (options.kind_quality == nullptr || polygon.cell == kNoIndex) return vertex_quality;
    std::size_t kind = 0;
    while (kind < 3 && polygon.cell >= block_start[kind + 1]) ++kind;
    const std::vector<double>& q = options.kind_quality->by_kind[kind];
    return q.size() == vertex_quality.size() ? q : vertex_quality;
  };
  // A curved surface's reversed faces (options.inverted_are_reversed): the
  // inverted colour stays on them (issue 47 part R: their corners' negative
  // vertex quality turned half of every neighbour blue, ~3x their area).
  // A face not reversed has a negative corner of its own only where it is
  // concave (a reflex corner: its signed corner area below 0, as the
  // quality measures it): there it keeps the value below 0, as the colour
  // bar's note says; its other corners below 0 (a neighbour's) take its
  // lowest corner at or above 0.
  std::vector<Index> reversed;
  if (options.inverted_are_reversed) {
    reversed = options.inverted_cells;
    std::sort(reversed.begin(), reversed.end());
  }
  for (const BoundaryPolygon& polygon : polygons) {
    const auto base = static_cast<std::uint32_t>(faces.positions.size());
    const std::vector<double>& face_quality = quality_of_face(polygon);
    std::array<double, 4> corner{};
    for (int i = 0; i < polygon.size; ++i)
      corner[static_cast<std::size_t>(i)] = face_quality[static_cast<std::size_t>(polygon.v[static_cast<std::size_t>(i)])];
    if (!reversed.empty() && !std::binary_search(reversed.begin(), reversed.end(), polygon.cell)) {
      double lowest = std::numeric_limits<double>::infinity();
      for (int i = 0; i < polygon.size; ++i)
        if (corner[static_cast<std::size_t>(i)] >= 0.0) lowest = std::min(lowest, corner[static_cast<std::size_t>(i)]);
      std::array<double, 4> own_area{0.0, 0.0, 0.0, 0.0};  // a triangle: no reflex corner
      if (polygon.size == 4)
        own_area = quad_signed_corner_areas({point(mesh, polygon.v[0]), point(mesh, polygon.v[1]),
                                             point(mesh, polygon.v[2]), point(mesh, polygon.v[3])});
      if (std::isfinite(lowest))
        for (std::size_t i = 0; i < corner.size(); ++i)
          if (corner[i] < 0.0 && !(own_area[i] < 0.0)) corner[i] = lowest;
    }
    if (polygon.size == 3) {
      // A triangle (of a tet, wedge or pyramid): its 3 corners, one flat
      // triangle; the per-fragment map gives it the same colours as a quad.
      Vec3 p[3];
      for (int i = 0; i < 3; ++i) p[i] = point(mesh, polygon.v[static_cast<std::size_t>(i)]);
      const Vec3f normal = to_vec3f(normalized(cross(p[1] - p[0], p[2] - p[0])));
      for (int i = 0; i < 3; ++i) {
        const double q = corner[static_cast<std::size_t>(i)];
        faces.positions.push_back(local(p[i]));
        faces.normals.push_back(normal);
        faces.colors.push_back(color(q));
        faces.scalars.push_back(static_cast<float>(q));
      }
      faces.indices.insert(faces.indices.end(), {base, base + 1, base + 2});
      continue;
    }
    const Quad& quad = polygon.v;
    Vec3 p[4];
    double quality_sum = 0.0;
    int finite = 0;
    for (int i = 0; i < 4; ++i) {
      p[i] = point(mesh, quad[i]);
      const double q = corner[static_cast<std::size_t>(i)];
      if (!std::isnan(q)) {
        quality_sum += q;
        ++finite;
      }
    }
    const Vec3 centre = 0.25 * (p[0] + p[1] + p[2] + p[3]);
    // The diagonals' cross product: the area-weighted normal of a non-planar
    // quad, outward for an outward-oriented face.
    const Vec3f normal = to_vec3f(normalized(cross(p[2] - p[0], p[3] - p[1])));
    for (int i = 0; i < 4; ++i) {
      const double q = corner[static_cast<std::size_t>(i)];
      faces.positions.push_back(local(p[i]));
      faces.normals.push_back(normal);
      faces.colors.push_back(color(q));
      faces.scalars.push_back(static_cast<float>(q));
    }
    // The centre carries the mean of the corners' qualities: it is inverted
    // (and so is the part of the face nearer to it) when that mean is < 0.
    // An inverted corner alone keeps the inverted colour where its
    // barycentric weight is above one half: an eighth of the face.
    faces.positions.push_back(local(centre));
    faces.normals.push_back(normal);
    faces.colors.push_back(color(finite ? quality_sum / finite : std::nan("")));
    faces.scalars.push_back(static_cast<float>(finite ? quality_sum / finite : std::nan("")));
    for (std::uint32_t i = 0; i < 4; ++i) {
      faces.indices.push_back(base + i);
      faces.indices.push_back(base + (i + 1) % 4);
      faces.indices.push_back(base + 4);
    }
  }
  scene.triangles.push_back(std::move(faces));

  // Boundary edges, each once, then the vertices they use renumbered
  // compactly in ascending id order.
  const std::vector<Edge> edges = boundary_edges_all_kinds(topology);

  LineSet lines;
  lines.width = options.edge_width;
  std::vector<Index> local_id(mesh.points.size(), kNoIndex);
  for (const Edge& e : edges)
    for (Index v : e) local_id[static_cast<std::size_t>(v)] = 0;
  for (std::size_t v = 0; v < local_id.size(); ++v) {
    if (local_id[v] == kNoIndex) continue;
    local_id[v] = static_cast<Index>(lines.positions.size());
    lines.positions.push_back(local(mesh.points[v]));
    lines.colors.push_back(options.edge_color);
  }
  lines.indices.reserve(2 * edges.size());
  for (const Edge& e : edges)
    for (Index v : e) lines.indices.push_back(static_cast<std::uint32_t>(local_id[static_cast<std::size_t>(v)]));
  scene.lines.push_back(std::move(lines));
  if (!topology.non_conforming_faces.empty()) scene.overlay.push_back(non_conforming_outlines(mesh, topology, scene.origin));
  return scene;
}

TriangleSet non_conforming_outlines(const HexMesh& mesh, const Topology& topology, const Vec3& origin) {
  TriangleSet set;
  set.is_lit = false;
  for (const NonConformingFace& nc : topology.non_conforming_faces) {
    Vec3 p[4], centre{};
    for (int i = 0; i < 4; ++i) centre = centre + (p[i] = point(mesh, nc.quad[static_cast<std::size_t>(i)]));
    centre = 0.25 * centre;
    // A frame: each corner and its point kNonConformingFrame of the way
    // towards the centre; 4 trapezoids of 2 triangles.
    const auto base = static_cast<std::uint32_t>(set.positions.size());
    for (int i = 0; i < 4; ++i) {
      set.positions.push_back(to_vec3f(p[i] - origin));
      set.positions.push_back(to_vec3f(p[i] + kNonConformingFrame * (centre - p[i]) - origin));
    }
    set.colors.assign(set.positions.size(), kNonConformingColor);
    for (std::uint32_t i = 0; i < 4; ++i) {
      const std::uint32_t o0 = base + 2 * i, i0 = o0 + 1, o1 = base + 2 * ((i + 1) % 4), i1 = o1 + 1;
      set.indices.insert(set.indices.end(), {o0, o1, i1, o0, i1, i0});
    }
    add_non_conforming_diagonal(mesh, nc, origin, kNonConformingColor, set);
  }
  return set;
}

void add_non_conforming_diagonal(const HexMesh& mesh, const NonConformingFace& nc, const Vec3& origin,
                                 const Rgba8& color, TriangleSet& set, double end_margin) {
  // The diagonal: the two quad corners both triangles use.
  std::array<Index, 2> ends{kNoIndex, kNoIndex};
  int n = 0;
  for (Index v : nc.triangles[0])
    if (n < 2 && std::find(nc.triangles[1].begin(), nc.triangles[1].end(), v) != nc.triangles[1].end()) ends[static_cast<std::size_t>(n++)] = v;
  if (n < 2) return;
  Vec3 p[4], centre{};
  for (int i = 0; i < 4; ++i) centre = centre + (p[i] = point(mesh, nc.quad[static_cast<std::size_t>(i)]));
  centre = 0.25 * centre;
  const Vec3 a0 = point(mesh, ends[0]), b0 = point(mesh, ends[1]);
  const Vec3 a = a0 + end_margin * (b0 - a0), b = b0 - end_margin * (b0 - a0);
  // In the face's plane, across the diagonal: half as wide as the frame is deep.
  const Vec3 normal = cross(p[2] - p[0], p[3] - p[1]);
  const Vec3 across = cross(normal, b - a);
  if (!(squared_norm(across) > 0.0)) return;
  double depth = 0.0;  // the frame's depth at the corners the diagonal leaves
  for (const Vec3& e : {a0, b0}) depth = std::max(depth, kNonConformingFrame * norm(centre - e));
  const Vec3 side = (0.25 * depth) * normalized(across);
  // kNonConformingDashes dashes with gaps as long, from corner to corner.
  const int pieces = 2 * kNonConformingDashes - 1;
  for (int k = 0; k < pieces; k += 2) {
    const Vec3 s = a + (static_cast<double>(k) / pieces) * (b - a), e = a + (static_cast<double>(k + 1) / pieces) * (b - a);
    const auto base = static_cast<std::uint32_t>(set.positions.size());
    for (const Vec3& q : {s - side, s + side, e + side, e - side}) {
      set.positions.push_back(to_vec3f(q - origin));
      set.colors.push_back(color);
    }
    set.indices.insert(set.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
}

ColorBar overview_color_bar(const Topology& topology, const std::vector<double>& vertex_quality) {
  ColorBar bar = quality_color_bar();
  // The legend names only what is drawn: "inverted (< 0)" when a drawn
  // vertex is below 0 (issue 47: it was listed on meshes with none), "no
  // value" when one has none (only a hybrid mesh's boundary vertices can:
  // used by non-hex cells alone until their corners are analysed).
  bool below = false, undefined = false;
  for (const BoundaryPolygon& face : boundary_polygons(topology))
    for (int i = 0; i < face.size; ++i) {
      const double q = vertex_quality[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)])];
      below = below || q < 0.0;
      undefined = undefined || std::isnan(q);
    }
  if (!below) bar.swatches.clear();
  if (undefined) bar.swatches.push_back({kUndefinedColor, "no value"});
  if (!topology.non_conforming_faces.empty())
    bar.swatches.push_back({to_color(kNonConformingColor),
                            "non-conforming (" + std::to_string(topology.non_conforming_faces.size()) + ", inside; dashed: split)"});
  return bar;
}

namespace {

// Edges fade out when the mesh is dense on screen, so that a fine boundary
// mesh reads as a surface with a grid texture, not as a black blob: full
// opacity once the median boundary edge spans kOpaqueEdgePixels on screen,
// linearly less below, never under kMinEdgeOpacity.
constexpr double kOpaqueEdgePixels = 8.0;
constexpr double kMinEdgeOpacity = 0.3;

double edge_opacity(const Scene& scene, const Camera& camera, int width, int height) {
  if (scene.lines.empty() || scene.lines[0].indices.empty()) return 1.0;
  const LineSet& lines = scene.lines[0];
  const Mat4 to_ndc = projection_matrix(camera, static_cast<double>(width) / height) * view_matrix(camera) *
                      translation_matrix(scene.origin);
  std::vector<Vec3> screen;
  screen.reserve(lines.positions.size());
  for (const Vec3f& p : lines.positions) {
    const Vec3 ndc = transform_point(to_ndc, {p.x, p.y, p.z});
    screen.push_back({0.5 * ndc.x * width, 0.5 * ndc.y * height, 0.0});
  }
  std::vector<double> lengths;
  lengths.reserve(lines.indices.size() / 2);
  for (std::size_t i = 0; i + 1 < lines.indices.size(); i += 2)
    lengths.push_back(norm(screen[lines.indices[i]] - screen[lines.indices[i + 1]]));
  const auto middle = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), middle, lengths.end());
  return std::clamp(*middle / kOpaqueEdgePixels, kMinEdgeOpacity, 1.0);
}

// The silhouette grid's columns (rows by the view's aspect).
constexpr int kFitGrid = 192;

// The boundary's silhouette from `camera` on a grid of gw x gh cells over a
// view of `aspect`: a cell is set when a boundary triangle covers its
// centre or a projected corner falls in it, then grown by one cell (so that
// a face crossing a cell's corner counts).
std::vector<char> silhouette_mask(const HexMesh& mesh, const Topology& topology, const Camera& camera, double aspect,
                                  int gw, int gh) {
  std::vector<char> mask(static_cast<std::size_t>(gw) * static_cast<std::size_t>(gh), 0);
  auto set = [&](int i, int j) {
    if (i >= 0 && i < gw && j >= 0 && j < gh) mask[static_cast<std::size_t>(j) * gw + i] = 1;
  };
  for (const BoundaryPolygon& face : boundary_polygons(topology)) {
    double gx[4], gy[4];
    bool finite = true;
    for (int k = 0; k < face.size; ++k) {
      const Vec3 ndc = project_to_ndc(camera, aspect, mesh.points[static_cast<std::size_t>(face.v[static_cast<std::size_t>(k)])]);
      gx[k] = 0.5 * (ndc.x + 1.0) * gw, gy[k] = 0.5 * (1.0 - ndc.y) * gh;
      finite = finite && std::isfinite(gx[k]) && std::isfinite(gy[k]);
    }
    if (!finite) continue;
    for (int k = 0; k < face.size; ++k) set(static_cast<int>(std::floor(gx[k])), static_cast<int>(std::floor(gy[k])));
    for (int t = 0; t < face.size - 2; ++t) {
      const int a = 0, b = t + 1, c = t + 2;
      const int i0 = std::max(0, static_cast<int>(std::floor(std::min({gx[a], gx[b], gx[c]}))));
      const int i1 = std::min(gw - 1, static_cast<int>(std::floor(std::max({gx[a], gx[b], gx[c]}))));
      const int j0 = std::max(0, static_cast<int>(std::floor(std::min({gy[a], gy[b], gy[c]}))));
      const int j1 = std::min(gh - 1, static_cast<int>(std::floor(std::max({gy[a], gy[b], gy[c]}))));
      const double area = (gx[b] - gx[a]) * (gy[c] - gy[a]) - (gy[b] - gy[a]) * (gx[c] - gx[a]);
      if (area == 0.0) continue;
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const double px = i + 0.5, py = j + 0.5;
          const double w0 = (gx[b] - gx[a]) * (py - gy[a]) - (gy[b] - gy[a]) * (px - gx[a]);
          const double w1 = (gx[c] - gx[b]) * (py - gy[b]) - (gy[c] - gy[b]) * (px - gx[b]);
          const double w2 = (gx[a] - gx[c]) * (py - gy[c]) - (gy[a] - gy[c]) * (px - gx[c]);
          if (area > 0.0 ? (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0) : (w0 <= 0.0 && w1 <= 0.0 && w2 <= 0.0)) set(i, j);
        }
    }
  }
  std::vector<char> grown = mask;
  for (int j = 0; j < gh; ++j)
    for (int i = 0; i < gw; ++i)
      if (mask[static_cast<std::size_t>(j) * gw + i])
        for (int dj = -1; dj <= 1; ++dj)
          for (int di = -1; di <= 1; ++di) {
            const int u = i + di, v = j + dj;
            if (u >= 0 && u < gw && v >= 0 && v < gh) grown[static_cast<std::size_t>(v) * gw + u] = 1;
          }
  return grown;
}

// The rectangles the model covers in `view` from `camera` (silhouette_mask
// on kFitGrid / 2 columns, each row's runs of set cells as one rectangle).
std::vector<PixelRect> model_rects(const HexMesh& mesh, const Topology& topology, const Camera& camera, const PixelRect& view) {
  const int gw = kFitGrid / 2, gh = std::max(1, static_cast<int>(std::lround(gw * static_cast<double>(view.height) / std::max(1, view.width))));
  const std::vector<char> mask = silhouette_mask(mesh, topology, camera, static_cast<double>(view.width) / std::max(1, view.height), gw, gh);
  const auto at = [&](int i, int n, int length) { return static_cast<int>(std::lround(static_cast<double>(i) * length / n)); };
  std::vector<PixelRect> rects;
  for (int j = 0; j < gh; ++j)
    for (int i = 0; i < gw;) {
      if (!mask[static_cast<std::size_t>(j) * gw + i]) {
        ++i;
        continue;
      }
      int k = i;
      while (k < gw && mask[static_cast<std::size_t>(j) * gw + k]) ++k;
      const int x0 = at(i, gw, view.width), x1 = at(k, gw, view.width), y0 = at(j, gh, view.height), y1 = at(j + 1, gh, view.height);
      rects.push_back({view.x + x0, view.y + y0, x1 - x0, y1 - y0});
      i = k;
    }
  return rects;
}

// The part of `view` scaled by t about its corner (ax, ay): 0 left/top, 1 right/bottom.
PixelRect scaled_view(const PixelRect& view, double t, int ax, int ay) {
  const int w = static_cast<int>(std::lround(t * view.width)), h = static_cast<int>(std::lround(t * view.height));
  return {view.x + ax * (view.width - w), view.y + ay * (view.height - h), w, h};
}

// The largest fraction t (1.00 down to 0.50 by 0.01) of `view`, scaled
// about its corner (ax, ay), into which the silhouette `mask` (of the model
// fitted to the whole view) can be drawn scaled by t without a set cell
// touching any of `slots` grown by `margin`; 0 when none.
double largest_free_scale(const std::vector<char>& mask, int gw, int gh, const PixelRect& view,
                          const std::vector<PixelRect>& slots, int margin, int ax = 0, int ay = 0) {
  for (int step = 0; step <= 50; ++step) {
    const double t = 1.0 - 0.01 * step;
    const double cw = t * view.width / gw, ch = t * view.height / gh;
    const double ox = view.x + ax * (1.0 - t) * view.width, oy = view.y + ay * (1.0 - t) * view.height;
    bool hit = false;
    for (int j = 0; j < gh && !hit; ++j)
      for (int i = 0; i < gw && !hit; ++i) {
        if (!mask[static_cast<std::size_t>(j) * gw + i]) continue;
        const double x0 = ox + i * cw, x1 = x0 + cw, y0 = oy + j * ch, y1 = y0 + ch;
        for (const PixelRect& s : slots)
          if (x1 > s.x - margin && x0 < s.x + s.width + margin && y1 > s.y - margin && y0 < s.y + s.height + margin) {
            hit = true;
            break;
          }
      }
    if (!hit) return t;
  }
  return 0.0;
}

// The intersecting cells' unique edges, over everything: a white halo,
// then kIntersectingEdgeColor (OverviewOptions::intersecting_cell_ids).
std::vector<LineSet> intersecting_cell_edges(const HexMesh& mesh, const OverviewOptions& options, const Vec3& origin,
                                             const AnnotationStyle& style) {
  std::vector<Edge> edges;
  const Index num_cells = num_volume_cells(mesh);
  const bool surface = num_cells == 0;
  const auto add = [&](const std::array<Index, 4>& v, int size) {
    for (int i = 0; i < size; ++i) {
      const Index a = v[static_cast<std::size_t>(i)], b = v[static_cast<std::size_t>((i + 1) % size)];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  };
  for (Index c : options.intersecting_cell_ids) {
    if (c < 0) continue;
    if (!surface) {
      if (c < num_cells) for_each_face_of(volume_cell(mesh, c), add);
    } else if (static_cast<std::size_t>(c) < mesh.quads.size()) {
      add(mesh.quads[static_cast<std::size_t>(c)], 4);
    } else if (static_cast<std::size_t>(c) - mesh.quads.size() < mesh.triangles.size()) {
      const auto& t = mesh.triangles[static_cast<std::size_t>(c) - mesh.quads.size()];
      add({t[0], t[1], t[2], kNoIndex}, 3);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const double base = style.scale / kOverviewTextScale;  // 1 at 1200 px of height
  // Beside inverted cells: thin and faded, no halo (issue 45, the 45r and
  // 45t reviews: 118 hexes' lattice on a halo drew the eye before the
  // inverted hexes' blue, the worst region).
  const bool faded = !options.inverted_cells.empty();
  LineSet halo, core;
  halo.width = static_cast<float>(std::max(3.0, 5.0 * base));
  core.width = static_cast<float>(faded ? std::max(1.0, 1.5 * base) : std::max(1.5, 2.5 * base));
  halo.in_overlay = core.in_overlay = true;
  const Rgba8 color = faded ? kFadedIntersectingEdgeColor : kIntersectingEdgeColor;
  for (const Edge& e : edges)
    for (Index v : e) {
      const Vec3f at = to_vec3f(mesh.points[static_cast<std::size_t>(v)] - origin);
      for (LineSet* set : {&halo, &core}) {
        if (faded && set == &halo) continue;
        set->indices.push_back(static_cast<std::uint32_t>(set->positions.size()));
        set->positions.push_back(at);
        set->colors.push_back(set == &halo ? Rgba8{255, 255, 255, 255} : color);
      }
    }
  if (faded) return {std::move(core)};
  return {std::move(halo), std::move(core)};
}

}  // namespace

Image render_figure(Renderer& renderer, const Scene& scene, const Camera& camera, int width, int height,
                    const FigureLayout& layout, const std::string& title, const AnnotationStyle& style) {
  Image figure = make_image(width, height, style.background);
  paste(figure, renderer.render(scene, camera, layout.view.width, layout.view.height), layout.view.x, layout.view.y);
  draw_title(figure, layout.title, title, style);
  return figure;
}

// The overview's legend, drawn from the legend panel's top
// (ColorBar::max_bar_height), ends above this fraction of the figure's
// height: with a Warnings section above panel A, index.html at 1400 x 1000
// still shows its last legend line at page load (the browser test: 0.6).
// The colour bar takes the height the rest of the legend leaves under that
// line (issue 45, the 45d review: capped at 0.18 it was 216 px with 600 px
// of the column empty), at least kOverviewBarFraction of the figure's.
constexpr double kOverviewLegendEnd = 0.57;
constexpr double kOverviewBarFraction = 0.18;
// An inset in the legend's column at least this fraction of its size in
// the view (narrower, its caption's lines are cut: rockarm's two insets).
constexpr double kColumnInsetShare = 0.9;

namespace {

// The bar's height cap (ColorBar::max_bar_height): what the rest of the
// legend (its label and swatches, drawn in the style draw_color_bar picks
// for `legend`) leaves above kOverviewLegendEnd of the figure's height, at
// least kOverviewBarFraction of it.
void fit_overview_bar(ColorBar& bar, const AnnotationStyle& style, const PixelRect& legend, int figure_height) {
  bar.max_bar_height = 1;
  const int rest = color_bar_height(bar, color_bar_style_for(bar, style, legend), legend.height) - 1;
  bar.max_bar_height = std::max(static_cast<int>(std::lround(kOverviewBarFraction * figure_height)),
                                static_cast<int>(kOverviewLegendEnd * figure_height) - legend.y - rest);
}

struct PixelBox {
  double x0, y0, x1, y1;
};

// The box of points projected by camera into view (figure pixels).
PixelBox projected_box(std::span<const Vec3> points, const Camera& camera, const PixelRect& view) {
  const double aspect = static_cast<double>(view.width) / std::max(1, view.height);
  PixelBox box{1e300, 1e300, -1e300, -1e300};
  for (const Vec3& p : points) {
    const Vec3 ndc = project_to_ndc(camera, aspect, p);
    if (!std::isfinite(ndc.x) || !std::isfinite(ndc.y)) continue;
    const double x = view.x + 0.5 * (ndc.x + 1.0) * view.width, y = view.y + 0.5 * (1.0 - ndc.y) * view.height;
    box.x0 = std::min(box.x0, x), box.x1 = std::max(box.x1, x), box.y0 = std::min(box.y0, y),
    box.y1 = std::max(box.y1, y);
  }
  return box;
}

// The callouts found for the model projected into box `from`, carried to
// the model refitted (the same eye direction) into box `to`: centres by
// the similarity that takes the one box onto the other (exact when the
// views' aspects agree, the fit's camera then the same), radii scaled but
// at least min_radius and at most max_callout_radius of the model's view
// `model` (inverted_callouts' floor and cap, pixels at every scale). No
// ring is larger than inverted_callouts would draw it there, but for
// groups it would merge at the smaller scale: a mapped ring under an inset
// is one there (plan_quality_overview skips that layout without rendering).
std::vector<InvertedCallout> mapped_callouts(std::span<const InvertedCallout> callouts, const PixelBox& from,
                                             const PixelBox& to, const PixelRect& model, double min_radius) {
  const double from_w = from.x1 - from.x0, from_h = from.y1 - from.y0;
  const double scale =
      from_w >= from_h ? (to.x1 - to.x0) / std::max(1e-9, from_w) : (to.y1 - to.y0) / std::max(1e-9, from_h);
  const auto x_of = [&](double x) { return 0.5 * (to.x0 + to.x1) + scale * (x - 0.5 * (from.x0 + from.x1)); };
  const auto y_of = [&](double y) { return 0.5 * (to.y0 + to.y1) + scale * (y - 0.5 * (from.y0 + from.y1)); };
  const double largest = max_callout_radius(model, min_radius);
  const auto radius_of = [&](double r) { return std::min(largest, std::max(min_radius, scale * r)); };
  std::vector<InvertedCallout> mapped(callouts.begin(), callouts.end());
  for (InvertedCallout& c : mapped) {
    c.x = x_of(c.x), c.y = y_of(c.y), c.radius = radius_of(c.radius);
    if (c.hidden_radius > 0.0)
      c.hidden_x = x_of(c.hidden_x), c.hidden_y = y_of(c.hidden_y), c.hidden_radius = radius_of(c.hidden_radius);
  }
  return mapped;
}

// Whether a ring of callouts (callout_discs) reaches into one of rects.
bool rings_under(std::span<const InvertedCallout> callouts, std::span<const PixelRect> rects, double thickness) {
  for (const InvertedCallout& c : callouts)
    for (const ScreenDisc& d : callout_discs(c, thickness))
      for (const PixelRect& rect : rects)
        if (box_meets_disc(rect, d)) return true;
  return false;
}

}  // namespace

Index least_quality_vertex(const HexMesh& mesh, const std::vector<double>& vertex_quality) {
  Index worst = kNoIndex;
  const auto consider = [&](Index v) {
    const auto i = static_cast<std::size_t>(v);
    if (i >= vertex_quality.size() || !std::isfinite(vertex_quality[i])) return;
    if (worst == kNoIndex || vertex_quality[i] < vertex_quality[static_cast<std::size_t>(worst)] ||
        (vertex_quality[i] == vertex_quality[static_cast<std::size_t>(worst)] && v < worst))
      worst = v;
  };
  for (const auto& q : mesh.quads)
    for (Index v : q) consider(v);
  for (const auto& t : mesh.triangles)
    for (Index v : t) consider(v);
  return worst;
}

OverviewFrame quality_overview_frame(const HexMesh& mesh, const Topology& topology,
                                    const std::vector<double>& vertex_quality, const OverviewOptions& options) {
  if (options.width <= 0 || options.height <= 0)
    throw RenderError("overview size must be positive, got " + std::to_string(options.width) + "x" +
                      std::to_string(options.height));
  OverviewFrame f;
  f.style = annotation_style_for(options.height);
  f.style.scale *= kOverviewTextScale;
  f.style.background = options.background;
  f.bar = overview_color_bar(topology, vertex_quality);
  // A short bar, the legend from the top: on index.html (the overview at
  // the column's width under the cards) its last swatch above the 1400 x
  // 1000 window's fold (issue 45, the 45t review: the ring entries were
  // below it at page load).
  if (options.kind_quality != nullptr && !options.kind_quality->empty()) f.bar.label = kKindCornerQualityLabel;
  // A curved surface's values below 0: the corners of its reversed faces
  // (measured against their neighbours' orientation) and the reflex corners
  // of concave faces, which are not inverted there; "inverted (< 0)" named
  // neither (issue 47p).
  if (options.inverted_are_reversed && !f.bar.swatches.empty() &&
      to_rgba8(f.bar.swatches.front().color) == to_rgba8(kInvertedColor)) {
    f.bar.swatches.front().label = kCurvedBelowZeroLabel;
    f.bar.swatches.insert(f.bar.swatches.begin() + 1, {Color{}, std::string(kCurvedBelowZeroNote), SwatchShape::text});
  }
  // Both ring entries size the legend; the figure keeps those it draws.
  if (!options.inverted_cells.empty()) {
    const std::string cells = plural(options.cell_noun);
    if (options.outline_inverted_faces) {
      f.bar.swatches.push_back({to_color(kInvertedOutlineColor),
                                "outlined: " + std::to_string(options.inverted_cells.size()) +
                                    (options.inverted_are_reversed ? " reversed " : " inverted ") +
                                    plural(options.cell_noun, options.inverted_cells.size()),
                                SwatchShape::thick_line});  // drawn as an outline, named by one (44p review)
      if (options.inverted_are_reversed)
        f.bar.swatches.push_back({Color{}, "(orientation flipped)", SwatchShape::text});
      // How many show from here (the 47r review counted 3 of 6 on a turned
      // bell): filled in once the camera is known; this text is as wide as
      // the widest it becomes.
      const std::string all = std::to_string(options.inverted_cells.size());
      f.bar.swatches.push_back({Color{}, all + " in sight, " + all + (options.outline_on_top ? " under an overlapping face" : " on the far side"),
                                SwatchShape::text});
    }
    f.bar.swatches.push_back({to_color(kCalloutColor), "solid ring: inverted " + cells + ", some in sight", SwatchShape::solid_ring});
    f.bar.swatches.push_back(
        {to_color(kCalloutColor), "dashed ring: inside or on the far side", SwatchShape::dashed_ring});
  }
  if (options.intersecting_cells > 0) {
    // Volume meshes: the edges drawn (issue 45 part G); a surface mesh's
    // faces: "intersecting faces", the word of its page and main view, drawn
    // there only (issue 47 part F).
    const bool drawn = !options.intersecting_cell_ids.empty();
    f.bar.swatches.push_back({to_color(drawn && !options.inverted_cells.empty() ? kFadedIntersectingSwatchColor : kIntersectingEdgeColor),
                              "intersecting " + (options.outline_inverted_faces ? std::string("faces") : plural(options.cell_noun)) + ": " +
                                  std::to_string(options.intersecting_cells) + (drawn ? " (edges," : ""),
                              drawn ? SwatchShape::thick_line : SwatchShape::text});
    if (drawn)
      f.bar.swatches.push_back({Color{}, "seen through the surface)", SwatchShape::text});
    else if (options.outline_inverted_faces)
      f.bar.swatches.push_back({Color{}, "drawn in the main view, not here", SwatchShape::text});
  }
  if (options.outline_on_top && options.inverted_cells.empty()) {
    f.worst_vertex = least_quality_vertex(mesh, vertex_quality);
    if (f.worst_vertex != kNoIndex)
      f.bar.swatches.push_back({to_color(kWorstMarkerColor),
                                "ring: min vertex quality " +
                                    display_number(vertex_quality[static_cast<std::size_t>(f.worst_vertex)], 3),
                                SwatchShape::solid_ring});
  }
  f.layout = figure_layout(options.width, options.height, !options.title.empty(), color_bar_width(f.bar, f.style), f.style);
  fit_overview_bar(f.bar, f.style, f.layout.legend, options.height);
  const double aspect = static_cast<double>(f.layout.view.width) / static_cast<double>(f.layout.view.height);
  f.camera = fit_camera_to_points(boundary_points(mesh, topology), view_direction_of(options), aspect, {.up = options.up});
  if (options.outline_on_top) {
    // A planar mesh seen along its normal: its top under the title, as far
    // from it as its side is from the view's edge, not centred (issue 47: a
    // wide plate's overview began below index.html's first screen, under
    // an empty band); the spare height goes below it.
    const PixelBox box = projected_box(boundary_points(mesh, topology), f.camera, f.layout.view);
    const double shift = box.y0 - (f.layout.view.y + std::max(0.0, box.x0 - f.layout.view.x));
    if (box.y1 > box.y0 && shift > 1.0) {
      const Vec3 forward = normalized(f.camera.target - f.camera.eye);
      const Vec3 screen_up = normalized(cross(cross(forward, f.camera.up), forward));
      const double per_pixel =
          (f.camera.is_perspective ? 2.0 * norm(f.camera.target - f.camera.eye) *
                                         std::tan(0.5 * f.camera.fov_y_degrees * std::numbers::pi / 180.0)
                                   : f.camera.ortho_height) /
          f.layout.view.height;
      const Vec3 move = (shift * per_pixel) * screen_up;
      f.camera.eye = f.camera.eye - move;
      f.camera.target = f.camera.target - move;
    }
  }
  if (!options.inverted_cells.empty() && options.outline_inverted_faces) {
    // A planar mesh (seen along its normal, outlines on top) has no far
    // side: a face is hidden only under an overlapping one (a fold).
    const auto all = static_cast<Index>(options.inverted_cells.size());
    if (options.outline_on_top) f.hidden_cells = cells_under_other_faces(mesh, topology, options.inverted_cells, f.camera);
    const Index hidden = options.outline_on_top ? static_cast<Index>(f.hidden_cells.size())
                                                : all - cells_in_sight(mesh, topology, options.inverted_cells, f.camera, aspect);
    const char* where = options.outline_on_top ? " under an overlapping face" : " on the far side";
    for (auto s = f.bar.swatches.begin(); s != f.bar.swatches.end(); ++s)
      if (s->label.find(" in sight, ") != std::string::npos) {
        s->label = hidden == 0 ? std::string("all in sight") : std::to_string(all - hidden) + " in sight, " + std::to_string(hidden) + where;
        // The hidden ones' outline, as drawn (render_quality_overview);
        // no wider than the line above it, so the layout stands.
        if (!f.hidden_cells.empty())
          f.bar.swatches.insert(s + 1, {to_color(kInvertedOutlineColor), "dashed: under an overlapping face",
                                        SwatchShape::dashed_line});
        break;
      }
  }
  f.label_size = std::max(f.style.min_text_size, static_cast<int>(std::lround(20.0 * f.style.scale)));
  return f;
}

OverviewPlan plan_quality_overview(const HexMesh& mesh, const Topology& topology,
                                   const std::vector<double>& vertex_quality, const OverviewOptions& options,
                                   Renderer& renderer) {
  OverviewPlan plan;
  plan.frame = quality_overview_frame(mesh, topology, vertex_quality, options);
  OverviewFrame& f = plan.frame;
  plan.full_view = f.layout.view;
  // A surface mesh's inverted faces are outlined whole, not ringed.
  if (options.inverted_cells.empty() || options.outline_inverted_faces) return plan;
  const double min_radius = std::max(10.0, 26.0 * f.style.scale);
  plan.callouts = inverted_callouts(mesh, topology, options.inverted_cells, vertex_quality, f.camera, f.layout.view,
                                    min_radius, renderer);
  const double full_area = static_cast<double>(plan.full_view.width) * plan.full_view.height;
  const auto wanted = std::count_if(plan.callouts.begin(), plan.callouts.end(),
                                    [&](const InvertedCallout& c) { return callout_wants_inset(c, full_area); });
  const int count = static_cast<int>(std::min<long>(wanted, kMaxInvertedInsets));
  if (count == 0) return plan;
  // Out of sight: cut-away insets draw the cells themselves, in a strip
  // beside the model (inverted_inset.h), the model fitted into the rest.
  const std::vector<Vec3> points = boundary_points(mesh, topology);
  const PixelRect view = f.layout.view;  // (f's is the chosen candidate's at the end)
  const double aspect = static_cast<double>(view.width) / view.height;
  const PixelBox silhouette = projected_box(points, f.camera, view);
  const double silhouette_w = silhouette.x1 > silhouette.x0 ? silhouette.x1 - silhouette.x0 : view.width;
  const double silhouette_h = silhouette.y1 > silhouette.y0 ? silhouette.y1 - silhouette.y0 : view.height;
  const int margin = std::max(4, static_cast<int>(std::lround(12 * f.style.scale)));
  const InsetStrip strip = inset_strip(view, silhouette_w, silhouette_h, count, margin);
  // The model larger where the strip leaves room (issue 45f round 2, the
  // 45f review: it was drawn 0.61-0.71 of its width with quadrants empty):
  // the silhouette as fitted to the whole view, scaled about the view's
  // top-left corner until it clears the slots of the column or of the row
  // (inset_strip with a silhouette that only fits the one or the other),
  // when that draws it larger than the strip's rest does.
  const int gw = kFitGrid, gh = std::max(1, static_cast<int>(std::lround(kFitGrid * static_cast<double>(view.height) / view.width)));
  const std::vector<char> mask = silhouette_mask(mesh, topology, f.camera, aspect, gw, gh);
  // Issue 45g (the 45f2 review: the bunny and the ball small in their
  // frames): the column's slots also at the bottom (the model scaled about
  // the view's bottom-left corner too), the row's also on the left (about
  // the top-right corner too). Each candidate's model scale; the largest
  // wins, ties the earlier.
  struct Candidate {
    double scale;
    InsetStrip strip;
  };
  std::vector<Candidate> candidates{
      {std::min(strip.model.width / silhouette_w, strip.model.height / silhouette_h) /
           std::min(view.width / silhouette_w, view.height / silhouette_h),
       strip}};
  struct Arrangement {
    bool column, flipped;
    int ax, ay;
  };
  constexpr Arrangement kArrangements[] = {{true, false, 0, 0}, {false, false, 0, 0}, {true, false, 0, 1},
                                           {true, true, 0, 0},  {true, true, 0, 1},   {false, false, 1, 0},
                                           {false, true, 0, 0}, {false, true, 1, 0}};
  for (const Arrangement& a : kArrangements) {
    InsetStrip side = a.column ? inset_strip(view, 1.0, 1e9, count, margin) : inset_strip(view, 1e9, 1.0, count, margin);
    if (a.flipped)  // mirrored across the view's middle, the order kept (A on top / on the left)
      for (PixelRect& r : side.slots) {
        if (a.column) r.y = view.y + view.height - (r.y - view.y) - r.height;
        else r.x = view.x + view.width - (r.x - view.x) - r.width;
      }
    if (a.flipped) std::reverse(side.slots.begin(), side.slots.end());
    const double t = largest_free_scale(mask, gw, gh, view, side.slots, margin, a.ax, a.ay);
    if (t > 0.0) candidates.push_back({t, {scaled_view(view, t, a.ax, a.ay), side.slots}});
  }
  // First, the insets in the legend's column under the legend, side by
  // side, when they fit there at kColumnInsetShare of their size or more,
  // the model in the whole view (issue 45, the 45d review: the cylinder's
  // inset A took the view's top right, the model drawn in its lower-left
  // quarter, and the column under the legend stayed empty).
  {
    const PixelRect& legend = f.layout.legend;
    const int top = legend.y + color_bar_height(f.bar, color_bar_style_for(f.bar, f.style, legend), legend.height) + 2 * margin;
    const int bottom = std::min(legend.y + legend.height, options.height) - margin;
    const int full_w = static_cast<int>(std::lround(kInsetWidthFraction * view.width));
    const int full_h = static_cast<int>(std::lround(kInsetHeightFraction * view.height));
    const int w = std::min(full_w, (legend.width - (count + 1) * margin) / count), h = std::min(full_h, bottom - top);
    if (w >= kColumnInsetShare * full_w && h >= kColumnInsetShare * full_h) {
      InsetStrip column{view, {}};
      for (int i = 0; i < count; ++i)
        column.slots.push_back({legend.x + legend.width - (count - i) * (w + margin), top, w, h});
      candidates.insert(candidates.begin(), {1.0, column});
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.scale > b.scale; });
  // The largest model whose rings pass under no inset (issue 45: kitten's
  // ring ran under inset A, which hid part of it): the silhouette clears
  // the slots, a ring (drawn around its cells with a margin) may not.
  // None such: the largest. The id image is rendered for the full view's
  // rings only; a candidate's are those mapped (mapped_callouts), and only
  // a candidate whose mapped rings clear its insets has its own rings
  // found (inverted_callouts) to confirm it.
  const double thickness = overview_ring_thickness(f.style);
  const auto fitted = [&](const PixelRect& model) {
    return fit_camera_to_points(points, view_direction_of(options),
                                static_cast<double>(model.width) / std::max(1, model.height), {.up = options.up});
  };
  // The plan with s's model and insets; whether its rings clear the insets.
  const auto place = [&](const InsetStrip& s, const Camera& camera) {
    plan.frame.layout.view = s.model;
    plan.frame.camera = camera;
    plan.callouts = inverted_callouts(mesh, topology, options.inverted_cells, vertex_quality, camera, s.model,
                                      min_radius, renderer);
    plan.insets = plan_inverted_insets(mesh, plan.callouts, s.slots, camera, f.label_size, full_area);
    return !rings_under_insets(plan.callouts, plan.insets, thickness);
  };
  const std::vector<InvertedCallout> full = std::move(plan.callouts);
  for (const Candidate& c : candidates) {
    const Camera camera = fitted(c.strip.model);
    const std::vector<InvertedCallout> mapped =
        mapped_callouts(full, silhouette, projected_box(points, camera, c.strip.model), c.strip.model, min_radius);
    const std::size_t num_insets = inset_callouts(mapped, c.strip.slots, f.label_size, full_area).size();
    if (rings_under(mapped, std::span(c.strip.slots).first(num_insets), thickness)) continue;
    if (place(c.strip, camera)) return plan;
  }
  place(candidates.front().strip, fitted(candidates.front().strip.model));
  return plan;
}

bool rings_under_insets(std::span<const InvertedCallout> callouts, std::span<const InvertedInset> insets, double thickness) {
  std::vector<PixelRect> rects;
  for (const InvertedInset& inset : insets) rects.push_back(inset.rect);
  return rings_under(callouts, rects, thickness);
}

std::array<LineSet, 4> inverted_face_outlines(const HexMesh& mesh, const OverviewOptions& options, const OverviewFrame& f,
                                              const Vec3& origin) {
  // Whole inverted faces, over the fill and the edges: a 4 px line on a
  // 7 px white halo, apart from the black edges and the blue fill. The
  // faces under an overlapping face (a planar fold: f.hidden_cells) dashed,
  // as wide and drawn after them, so the legend's "N under an overlapping
  // face" can be counted in the picture (the 47d review; the 47f review:
  // thinner dashes drawn first were 1-2 px specks beside the solid lines).
  const FigureLayout& layout = f.layout;
  const double base = f.style.scale / kOverviewTextScale;  // 1 at 1200 px of height
  std::array<LineSet, 4> sets;
  LineSet &halo = sets[0], &outline = sets[1], &hidden_halo = sets[2], &hidden_outline = sets[3];
  halo.width = hidden_halo.width = static_cast<float>(std::max(4.0, 7.0 * base));
  outline.width = hidden_outline.width = static_cast<float>(std::max(2.0, 4.0 * base));
  for (LineSet& set : sets) set.in_overlay = options.outline_on_top;
  const double aspect = static_cast<double>(layout.view.width) / std::max(1, layout.view.height);
  const double dash_pixels = std::max(6.0, 10.0 * base);
  const auto add_segment = [&](LineSet& h, LineSet& o, const Vec3& a, const Vec3& b) {
    for (LineSet* set : {&h, &o})
      for (const Vec3& p : {a, b}) {
        set->indices.push_back(static_cast<std::uint32_t>(set->positions.size()));
        set->positions.push_back(to_vec3f(p - origin));
        set->colors.push_back(set == &h ? Rgba8{255, 255, 255, 255} : kInvertedOutlineColor);
      }
  };
  const auto add_face = [&](const std::array<Index, 4>& v, int size, bool is_hidden) {
    for (int i = 0; i < size; ++i) {
      const Vec3& a = mesh.points[static_cast<std::size_t>(v[static_cast<std::size_t>(i)])];
      const Vec3& b = mesh.points[static_cast<std::size_t>(v[static_cast<std::size_t>((i + 1) % size)])];
      if (!is_hidden) {
        add_segment(halo, outline, a, b);
        continue;
      }
      // Dashes of about dash_pixels, gaps of 0.7 of that, whole periods.
      const Vec3 pa = project_to_ndc(f.camera, aspect, a), pb = project_to_ndc(f.camera, aspect, b);
      const double pixels = 0.5 * std::hypot((pb.x - pa.x) * layout.view.width, (pb.y - pa.y) * layout.view.height);
      const int dashes = std::max(1, static_cast<int>(pixels / (1.7 * dash_pixels)));
      for (int k = 0; k < dashes; ++k) {
        const double t0 = (k + 0.15) / dashes, t1 = (k + 0.15 + 1.0 / 1.7) / dashes;
        add_segment(hidden_halo, hidden_outline, a + t0 * (b - a), a + t1 * (b - a));
      }
    }
  };
  for (Index c : options.inverted_cells) {
    const auto i = static_cast<std::size_t>(c);
    const bool is_hidden = std::binary_search(f.hidden_cells.begin(), f.hidden_cells.end(), c);
    if (i < mesh.quads.size())
      add_face(mesh.quads[i], 4, is_hidden);
    else if (i - mesh.quads.size() < mesh.triangles.size()) {
      const auto& t = mesh.triangles[i - mesh.quads.size()];
      add_face({t[0], t[1], t[2], kNoIndex}, 3, is_hidden);
    }
  }
  return sets;
}

Image render_quality_overview(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                              const OverviewOptions& options, Renderer& renderer) {
  // The rings' groups (id images only) and the insets' pictures first, so
  // that the overview's own frame is the renderer's last (report.json
  // views[].cameras).
  OverviewPlan plan = plan_quality_overview(mesh, topology, vertex_quality, options, renderer);
  OverviewFrame& f = plan.frame;
  const AnnotationStyle& style = f.style;
  const FigureLayout& layout = f.layout;
  const double thickness = overview_ring_thickness(style);
  const int text_size = f.label_size;
  std::vector<InvertedCallout>& callouts = plan.callouts;
  const std::vector<InvertedInset>& insets = plan.insets;
  const std::vector<Image> pictures = render_inverted_insets(mesh, insets, vertex_quality, renderer);

  Scene scene = build_quality_overview_scene(mesh, topology, vertex_quality, options);
  const double opacity = edge_opacity(scene, f.camera, layout.view.width, layout.view.height);
  for (LineSet& lines : scene.lines)
    for (Rgba8& c : lines.colors) c.a = static_cast<std::uint8_t>(std::lround(c.a * opacity));
  if (options.outline_inverted_faces)
    for (LineSet& set : inverted_face_outlines(mesh, options, f, scene.origin))
      if (!set.positions.empty()) scene.lines.push_back(std::move(set));

  if (!options.intersecting_cell_ids.empty())
    for (LineSet& set : intersecting_cell_edges(mesh, options, scene.origin, style)) scene.lines.push_back(std::move(set));

  Image figure = render_figure(renderer, scene, f.camera, options.width, options.height, layout, options.title, style);
  if (options.inverted_cells.empty()) {
    draw_color_bar(figure, layout.legend, f.bar, style);
    if (f.worst_vertex != kNoIndex) {
      const auto w = static_cast<std::size_t>(f.worst_vertex);
      const double aspect = static_cast<double>(layout.view.width) / layout.view.height;
      const Vec3 ndc = project_to_ndc(f.camera, aspect, mesh.points[w]);
      const double cx = layout.view.x + 0.5 * (ndc.x + 1.0) * layout.view.width;
      const double cy = layout.view.y + 0.5 * (1.0 - ndc.y) * layout.view.height;
      const double radius = std::max(10.0, 26.0 * style.scale);
      draw_marker_ring(figure, cx, cy, radius, thickness, false, kWorstMarkerColor);
      draw_worst_label(figure, layout.view, cx, cy, radius, "min " + display_number(vertex_quality[w], 3), style);
    }
    return figure;
  }
  // The rings, the insets beside the model (a large ring may pass under
  // one), then the labels around them, anywhere in the whole view.
  for (const InvertedCallout& c : callouts) draw_callout_rings(figure, c, thickness, plan.full_view);
  draw_inverted_insets(figure, insets, pictures, callouts, options.cell_noun, text_size, style);
  // The legend keeps the ring styles drawn.
  const bool solid = std::any_of(callouts.begin(), callouts.end(), callout_in_sight);
  const bool dashed = std::any_of(callouts.begin(), callouts.end(),
                                  [](const InvertedCallout& c) { return !callout_in_sight(c) || c.hidden_radius > 0.0; });
  std::erase_if(f.bar.swatches, [&](const ColorBarSwatch& s) {
    return (s.shape == SwatchShape::solid_ring && !solid) || (s.shape == SwatchShape::dashed_ring && !dashed);
  });
  fit_overview_bar(f.bar, style, layout.legend, options.height);  // the bar taller by an entry dropped
  draw_color_bar(figure, layout.legend, f.bar, style);
  // The labels may also take the legend's column under the legend, beside
  // the insets (the 45e review: labels lay on the model, on a hand's
  // fingertips and a cylinder's wall, with that column empty).
  std::vector<PixelRect> taken{
      {layout.legend.x, layout.legend.y, layout.legend.width,
       color_bar_height(f.bar, color_bar_style_for(f.bar, style, layout.legend), layout.legend.height)}};
  for (const InvertedInset& inset : insets) taken.push_back(inset.rect);
  const PixelRect bounds{plan.full_view.x, plan.full_view.y, options.width - plan.full_view.x, plan.full_view.height};
  draw_inverted_callouts(figure, plan.full_view, callouts, options.cell_noun, thickness, text_size, style, taken, false,
                         model_rects(mesh, topology, f.camera, layout.view), bounds);
  return figure;
}

Image render_compare_overview(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                              const HexMesh& other, const Topology& other_topology,
                              const std::vector<double>& other_vertex_quality, const OverviewOptions& options,
                              Renderer& renderer) {
  AnnotationStyle style = annotation_style_for(options.height);
  style.background = options.background;
  ColorBar bar = overview_color_bar(topology, vertex_quality);
  for (const KindVertexQuality* kinds : {options.kind_quality, options.other_kind_quality})
    if (kinds != nullptr && !kinds->empty()) bar.label = kKindCornerQualityLabel;
  for (ColorBarSwatch& swatch : overview_color_bar(other_topology, other_vertex_quality).swatches)
    if (std::none_of(bar.swatches.begin(), bar.swatches.end(),
                     [&](const ColorBarSwatch& s) { return s.label == swatch.label; }))
      bar.swatches.push_back(std::move(swatch));
  const FigureLayout layout =
      figure_layout(options.width, options.height, !options.title.empty(), color_bar_width(bar, style), style);
  const int half = std::max(1, layout.view.width / 2);
  std::vector<Vec3> points = boundary_points(mesh, topology);
  const std::vector<Vec3> other_points = boundary_points(other, other_topology);
  points.insert(points.end(), other_points.begin(), other_points.end());
  const double aspect = static_cast<double>(half) / static_cast<double>(layout.view.height);
  const Camera camera = fit_camera_to_points(points, view_direction_of(options), aspect, {.up = options.up});
  Image figure = make_image(options.width, options.height, options.background);
  const HexMesh* meshes[] = {&mesh, &other};
  const Topology* topologies[] = {&topology, &other_topology};
  const std::vector<double>* qualities[] = {&vertex_quality, &other_vertex_quality};
  for (int k = 0; k < 2; ++k) {
    OverviewOptions own = options;
    own.kind_quality = k == 0 ? options.kind_quality : options.other_kind_quality;
    Scene scene = build_quality_overview_scene(*meshes[k], *topologies[k], *qualities[k], own);
    const double opacity = edge_opacity(scene, camera, half, layout.view.height);
    for (LineSet& lines : scene.lines)
      for (Rgba8& c : lines.colors) c.a = static_cast<std::uint8_t>(std::lround(c.a * opacity));
    paste(figure, renderer.render(scene, camera, half, layout.view.height), layout.view.x + k * half, layout.view.y);
  }
  draw_title(figure, layout.title, options.title, style);
  draw_color_bar(figure, layout.legend, bar, style);
  return figure;
}

}  // namespace hq
