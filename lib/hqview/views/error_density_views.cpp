#include "hqview/views/error_density_views.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include "hqview/core/box3.h"
#include "hqview/core/number_format.h"
#include "hqview/core/error.h"
#include "hqview/core/hex_topology.h"
#include "hqview/image/colormap.h"
#include "hqview/mesh/planarity.h"
#include "hqview/quality/hex_metrics.h"
#include "hqview/quality/statistics.h"
#include "hqview/render/upright.h"
#include "hqview/views/boundary_views.h"
#include "hqview/views/inverted_callout.h"
#include "hqview/views/main_views.h"
#include "hqview/views/overview_views.h"

namespace hq {
namespace {

// The translucent boundary of the cells figure: blue-green, off the map
// (whose low end is a pale blue-grey), so "not drawn" never reads as "low".
constexpr Rgba8 kVeilColor{64, 168, 156, 52};
constexpr Rgba8 kBoundaryEdgeColor{40, 40, 46, 70};  // faint boundary edges over the colours
constexpr Rgba8 kCellEdgeColor{110, 110, 116, 255};    // edges of the drawn cells
constexpr Rgba8 kLowCellEdgeColor{0, 0, 0, 255};        // ... of those with scaled Jacobian below the threshold
constexpr double kFovY = 30.0;
// The veil as it looks over white where the boundary is seen through: its
// front and back layers (kVeilColor twice), the legend's veil swatch and the
// casing of the cells it hides.
constexpr Rgba8 kVeilOverWhite{185, 223, 229, 255};

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

// The hexes in the densest `fraction` (at least one, at most max_count), ascending ids.
std::vector<Index> densest_hexes(std::span<const double> density, double fraction,
                                 std::size_t max_count = static_cast<std::size_t>(-1)) {
  std::vector<Index> order;
  for (std::size_t h = 0; h < density.size(); ++h)
    if (is_positive(density[h])) order.push_back(static_cast<Index>(h));
  if (order.empty()) return order;
  const auto keep = std::max<std::size_t>(
      1, std::min(max_count, static_cast<std::size_t>(fraction * static_cast<double>(order.size()))));
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
  std::vector<Vec3> model_points;  // the boundary's points (the label's margin)
  AnnotationStyle style;
  ColorBar bar;
  FigureLayout layout;
  Camera camera;
  Scene scene;
  std::string worst_note;  // appended to the max's label (the cells figure: its SJ)
  // A boundary max the boundary hides from this viewpoint (its own faces
  // not seen: max_hex_behind_boundary): drawn through, its ring dashed, its
  // label says so; the same test in both figures.
  bool worst_hidden = false;
  // With the max hidden: the densest hex within kNearMaxFraction of it that
  // is seen from here (kNoIndex: none), named in the max's label (issue
  // 48e: on warrior_rot a face of 9.4x in plain view sat inside the dashed
  // ring of the hidden 9.7x max, and nothing told them apart).
  Index nearest_seen = kNoIndex;
  double nearest_density = 0;
  ErrorDensityScale scale;
  bool max_undashed = false;  // the boundary figure's hidden max drawn solid: every edge shorter than a dash
  std::vector<Index> drawn_cells;  // the densest 1% (the cells figure's cells): the max's label beside its ring avoids them
  // The max's pixels in this figure (max_pixels_in_view; a seen max only):
  // how many show and their centroid (figure pixels), the ring's centre.
  std::size_t max_pixels = 0;
  double max_x = 0, max_y = 0;
  // A seen max too small for its outline (max_too_small_to_outline): no
  // magenta edges over it, the label gives its pixels.
  bool max_unoutlined = false;
};

Figure begin_figure(const HexMesh& mesh, const Topology& topology, const ErrorDensityScale& scale,
                    const Vec3& view_direction, const ErrorDensityViewOptions& options) {
  Figure f;
  f.scale = scale;
  f.model_points = boundary_points(mesh, topology);
  f.bar = error_density_color_bar(scale);
  FigureFrame3d frame = figure_frame_3d(
      "error density view", options.width, options.height, options.background,
      [&](const AnnotationStyle& style) {
        return figure_layout(options.width, options.height, !options.title.empty(), color_bar_width(f.bar, style),
                             style);
      },
      f.model_points, view_direction, options.up, kFovY);
  f.style = frame.style;
  f.layout = frame.layout;
  f.camera = frame.camera;
  const Box3 box = boundary_bounding_box(mesh, topology);
  f.scene.origin = 0.5 * (box.lo + box.hi);
  f.scene.background = options.background;
  return f;
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

// A segment a-b of model points.
void add_segment(LineSet& set, const Vec3& origin, const Vec3& a, const Vec3& b, Rgba8 color) {
  for (const Vec3& p : {a, b}) {
    set.indices.push_back(static_cast<std::uint32_t>(set.positions.size()));
    set.positions.push_back(to_vec3f(p - origin));
    set.colors.push_back(color);
  }
}

// The figure's dashes, a fixed length on screen (issue 48r: 4 dashes per
// edge broke short edges into dots): 10 px dashes and 6 px gaps at 1200 px
// height.
struct Dashes {
  double dash, gap;  // pixels
};
Dashes figure_dashes(const Figure& f) { return {10.0 * f.style.scale, 6.0 * f.style.scale}; }

// The length of a-b on f's screen in pixels.
double pixel_length(const Figure& f, const Vec3& a, const Vec3& b) {
  const PixelRect& view = f.layout.view;
  const double aspect = static_cast<double>(view.width) / std::max(1, view.height);
  const Vec3 p = project_to_ndc(f.camera, aspect, a), q = project_to_ndc(f.camera, aspect, b);
  const double length = std::hypot(0.5 * (p.x - q.x) * view.width, 0.5 * (p.y - q.y) * view.height);
  return std::isfinite(length) ? length : 0.0;
}

// The max hex's edges as f draws them (issue 48r: the legend's swatch is
// drawn from the same stroke, so they agree): a core on a halo, dashed
// (figure_dashes) when hidden.
SwatchStroke max_edge_stroke(const Figure& f, double core, double halo, Rgba8 halo_color, bool dashed) {
  const Dashes d = figure_dashes(f);
  return {core, halo, halo_color, dashed ? d.dash : 0.0, d.gap};
}

// a-b dashed as f draws it (dashed_pieces of figure_dashes: the dashes of a
// halo and its core drawn with the same call coincide).
void add_dashed(LineSet& set, const Figure& f, const Vec3& a, const Vec3& b, Rgba8 color) {
  const Dashes d = figure_dashes(f);
  for (const auto& [t0, t1] : dashed_pieces(pixel_length(f, a, b), {0, 0, {}, d.dash, d.gap}))
    add_segment(set, f.scene.origin, a + t0 * (b - a), a + t1 * (b - a), color);
}

// The boundary figure's outline of the max hex: white halo, dashed when hidden.
SwatchStroke boundary_max_stroke(const Figure& f) {
  return max_edge_stroke(f, std::max(2.0, 2.5 * f.style.scale), std::max(4.0, 5.0 * f.style.scale),
                         {255, 255, 255, 255}, f.worst_hidden && !f.max_undashed);
}

// The boundary figure's outline of the max hex, all 12 edges in
// kMaxHexEdgeColor on a white halo. Seen on the boundary: solid, depth-tested
// like the boundary's edges (so its back edges stay hidden behind its own
// faces). Hidden (interior, or its faces not seen from here): dashed and
// drawn through the surface (no depth test) with no fill, so the faces in
// front keep their colours and it reads as behind them (issue 48: its faces
// were painted opaque over the front faces, and its dashed edges were
// depth-tested against them, which hid two of its edges or more).
void add_max_outline(Figure& f, const HexMesh& mesh, const ErrorDensityWorst& worst) {
  if (worst.hex == kNoIndex || f.max_unoutlined) return;
  const Hex& hex = mesh.hexes[static_cast<std::size_t>(worst.hex)];
  const SwatchStroke stroke = boundary_max_stroke(f);
  LineSet halo, core;
  halo.width = static_cast<float>(stroke.halo_width);
  core.width = static_cast<float>(stroke.width);
  halo.over_all = core.over_all = f.worst_hidden;
  f.max_undashed = f.worst_hidden && std::all_of(kHexEdges.begin(), kHexEdges.end(), [&](const auto& e) {
    return pixel_length(f, point(mesh, hex[e[0]]), point(mesh, hex[e[1]])) < figure_dashes(f).dash;
  });
  const auto add = [&](LineSet& set, const Vec3& a, const Vec3& b, Rgba8 color) {
    if (f.worst_hidden && !f.max_undashed)
      add_dashed(set, f, a, b, color);
    else
      add_segment(set, f.scene.origin, a, b, color);
  };
  for (const auto& e : kHexEdges) {
    const Vec3 &a = point(mesh, hex[e[0]]), &b = point(mesh, hex[e[1]]);
    add(halo, a, b, Rgba8{255, 255, 255, 255});
    add(core, a, b, kMaxHexEdgeColor);
  }
  f.scene.lines.push_back(std::move(halo));
  f.scene.lines.push_back(std::move(core));
}

// Whether the boundary hides the max hex from f's camera: an interior one
// always; a boundary one by the test error_density_cells_behind_boundary
// makes for it alone (so both figures agree).
bool max_hex_behind_boundary(const Figure& f, const HexMesh& mesh, const Topology& topology,
                             const ErrorDensityWorst& worst, Renderer& renderer) {
  if (worst.hex == kNoIndex) return false;
  if (!worst.on_boundary) return true;
  const std::vector<Index> max_hex{worst.hex};
  return error_density_cells_behind_boundary(mesh, topology, max_hex, f.camera, renderer).front();
}

// A seen max's pixels in f's view (issue 48f: warrior_rot's max, called
// seen on the verdict's zoomed id image, is 10 x 7 px in the figure, and
// its outline and halo covered it): an id image at the view's size with
// f's camera, the max's faces `own` against the `others` (the boundary's
// other faces, or the cells figure's other cells); their count and
// centroid in figure pixels into f. Nothing when it is hidden.
void max_pixels_in_view(Figure& f, const HexMesh& mesh, std::span<const std::array<Index, 4>> own,
                        std::span<const std::array<Index, 4>> others, Renderer& renderer) {
  f.max_pixels = 0;
  if (f.worst_hidden || own.empty()) return;
  Scene scene;
  scene.origin = f.scene.origin;
  scene.background = id_color(0);
  TriangleSet mine, rest;
  mine.is_lit = rest.is_lit = false;
  for (const auto& q : own) add_quad(mine, mesh, scene.origin, q, id_color(2));
  for (const auto& q : others) add_quad(rest, mesh, scene.origin, q, id_color(1));
  scene.triangles.push_back(std::move(mine));
  scene.triangles.push_back(std::move(rest));
  const PixelRect& view = f.layout.view;
  const IdImage ids = renderer.render_ids(scene, f.camera, view.width, view.height);
  double sx = 0, sy = 0;
  for (int y = 0; y < ids.height; ++y)
    for (int x = 0; x < ids.width; ++x)
      if (ids.at(x + ids.x0, y + ids.y0) == 2) ++f.max_pixels, sx += x + 0.5, sy += y + 0.5;
  if (f.max_pixels == 0) return;
  f.max_x = view.x + sx / static_cast<double>(f.max_pixels);
  f.max_y = view.y + sy / static_cast<double>(f.max_pixels);
}

// Whether a seen max's outline, a halo of halo_width pixels along its
// edges, would cover more than half of its pixels in the figure: a face of
// P pixels, about sqrt(P) on a side, loses about 2 halo_width sqrt(P) of
// them (half of each halo inside), more than P / 2 below (4 halo_width)^2
// (issue 48f: warrior_rot's 54 px max face was all magenta and white).
bool max_too_small_to_outline(const Figure& f, double halo_width) {
  return !f.worst_hidden && f.max_pixels > 0 &&
         static_cast<double>(f.max_pixels) < (4.0 * halo_width) * (4.0 * halo_width);
}

// With the max hidden (f.worst_hidden), or seen but too small to outline
// (f.max_unoutlined; issue 48f: warrior_rot's max shows 7 px, its 9.4x
// neighbour some 60 px in the same ring): the densest boundary hex of density
// at least kNearMaxFraction of the max's (at most kNearMaxCandidates of
// them) that error_density_cells_behind_boundary sees, into f.nearest_seen.
constexpr double kNearMaxFraction = 0.9;
constexpr std::size_t kNearMaxCandidates = 32;
void find_nearest_seen(Figure& f, const HexMesh& mesh, const Topology& topology, std::span<const double> density,
                       const ErrorDensityWorst& worst, Renderer& renderer) {
  f.nearest_seen = kNoIndex;
  if ((!f.worst_hidden && !f.max_unoutlined) || worst.hex == kNoIndex) return;
  std::vector<Index> near;
  for (Index face : topology.boundary_faces) {
    const Index h = face_hex(topology, face);
    if (h != worst.hex && density[static_cast<std::size_t>(h)] >= kNearMaxFraction * worst.density) near.push_back(h);
  }
  std::sort(near.begin(), near.end(), [&](Index a, Index b) {
    const double da = density[static_cast<std::size_t>(a)], db = density[static_cast<std::size_t>(b)];
    return da != db ? da > db : a < b;
  });
  near.erase(std::unique(near.begin(), near.end()), near.end());
  near.resize(std::min(near.size(), kNearMaxCandidates));
  const std::vector<bool> hidden = error_density_cells_behind_boundary(mesh, topology, near, f.camera, renderer);
  for (std::size_t k = 0; k < near.size(); ++k)
    if (!hidden[k]) {
      f.nearest_seen = near[k];
      f.nearest_density = density[static_cast<std::size_t>(near[k])];
      return;
    }
}

// The ring's legend swatch: solid for a max seen on the boundary, dashed for
// one drawn through it (interior, or on a boundary side hidden from here).
ColorBarSwatch worst_ring_swatch(const ErrorDensityWorst& worst, bool hidden) {
  const Color ink{0.08, 0.08, 0.08};
  if (!worst.on_boundary) return {ink, "ring: max (dashed: interior)", SwatchShape::dashed_ring};
  if (hidden) return {ink, "ring: max (dashed: behind)", SwatchShape::dashed_ring};
  return {ink, "ring: max (visible)", SwatchShape::solid_ring};
}

// The legend's line for a seen max drawn without its outline
// (max_too_small_to_outline): only the ring marks it.
ColorBarSwatch too_small_to_outline_swatch() {
  return {Color{0.08, 0.08, 0.08}, "  (max too small to outline)", SwatchShape::text};
}

// The label of the ring at (cx, cy) in the free margin beside the model's
// projected box (x0, y0)-(x1, y1): right of it, left, above or below (the
// first that fits in the view, nearest the ring's height or column), with a
// leader line from the label to the ring; so the label's white box never
// covers a drawn cell; a margin more than kMaxLeader of the view's smaller
// side from the ring's edge is no candidate (issue 48e: a 450 px leader on
// bracket, 590 px on kitten_rot; issue 48f: 0.2 left 214 px on hand_mr and
// 193 px across slab_pi's faces), and the boxes right of, left of, below
// and above the ring are: of them the one that covers the fewest model
// pixels drawn so far (the `avoid` boxes, the densest 1% of the hexes,
// weigh a hundredfold), then the nearest. label may have several lines.
constexpr double kMaxLeader = 0.1;
struct PixelBox {
  double x0, y0, x1, y1;
};
void draw_worst_label_outside(Image& figure, const PixelRect& view, const PixelBox& model, double cx, double cy,
                              double radius, const std::string& label, const AnnotationStyle& style,
                              std::span<const PixelBox> avoid) {
  const int size = std::max(style.min_text_size, static_cast<int>(std::lround(20 * style.scale)));
  const PixelRect extent = text_extent(label, size, style);
  const double w = extent.width + 6.0, h = std::max<double>(size, extent.height) + 8.0, gap = 10.0 * style.scale;
  // A margin off the view's edges (issue 48c: labels at x = 5 px touched the image border).
  const double inset = 10.0 * style.scale;
  const double vx0 = view.x + inset, vy0 = view.y + 2.0, vx1 = view.x + view.width - inset, vy1 = view.y + view.height - 2.0;
  const auto clamp_x = [&](double x) { return std::clamp(x, vx0, std::max(vx0, vx1 - w)); };
  const auto clamp_y = [&](double y) { return std::clamp(y, vy0, std::max(vy0, vy1 - h)); };
  struct Box {
    double x, y;
  };
  // The distance from the ring's centre to a box.
  const auto distance = [&](const Box& b) {
    const double dx = std::max({b.x - cx, 0.0, cx - (b.x + w)}), dy = std::max({b.y - cy, 0.0, cy - (b.y + h)});
    return std::hypot(dx, dy);
  };
  std::vector<Box> margins;
  if (model.x1 + gap + w <= vx1) margins.push_back({model.x1 + gap, clamp_y(cy - 0.5 * h)});
  if (model.x0 - gap - w >= vx0) margins.push_back({model.x0 - gap - w, clamp_y(cy - 0.5 * h)});
  if (model.y0 - gap - h >= vy0) margins.push_back({clamp_x(cx - 0.5 * w), model.y0 - gap - h});
  if (model.y1 + gap + h <= vy1) margins.push_back({clamp_x(cx - 0.5 * w), model.y1 + gap});
  const double max_leader = radius + kMaxLeader * std::min(view.width, view.height);
  // The candidates: the margins within max_leader, and beside the ring.
  std::vector<Box> candidates;
  for (const Box& m : margins)
    if (distance(m) <= max_leader) candidates.push_back(m);
  if (cx + radius + gap + w <= vx1) candidates.push_back({cx + radius + gap, clamp_y(cy - 0.5 * h)});
  if (cx - radius - gap - w >= vx0) candidates.push_back({cx - radius - gap - w, clamp_y(cy - 0.5 * h)});
  if (cy + radius + gap + h <= vy1) candidates.push_back({clamp_x(cx - 0.5 * w), cy + radius + gap});
  if (cy - radius - gap - h >= vy0) candidates.push_back({clamp_x(cx - 0.5 * w), cy - radius - gap - h});
  if (candidates.empty()) candidates.push_back({clamp_x(cx + radius + gap), clamp_y(cy - 0.5 * h)});
  // What a box covers: the model's pixels drawn so far (not the
  // background), each of the avoided boxes' (the densest hexes) counted as
  // if a hundred times over: the least covered, then the nearest.
  const Rgba8 background = style.background;
  const auto covered = [&](const Box& b) {
    const int bx0 = std::max(0, static_cast<int>(b.x)), by0 = std::max(0, static_cast<int>(b.y));
    const int bx1 = std::min(figure.width, static_cast<int>(b.x + w)), by1 = std::min(figure.height, static_cast<int>(b.y + h));
    double n = 0;
    for (int y = by0; y < by1; y += 2)
      for (int x = bx0; x < bx1; x += 2)
      {
        const std::uint8_t* p = &figure.rgba[pixel_offset(figure, x, y)];
        n += p[0] != background.r || p[1] != background.g || p[2] != background.b;
      }
    for (const PixelBox& a : avoid)
      n += 100.0 * std::max(0.0, std::min(b.x + w, a.x1) - std::max(b.x, a.x0)) *
           std::max(0.0, std::min(b.y + h, a.y1) - std::max(b.y, a.y0)) / 4.0;
    return n;
  };
  std::vector<double> cost;
  for (const Box& c : candidates) cost.push_back(covered(c));
  std::size_t pick = 0;
  for (std::size_t i = 1; i < candidates.size(); ++i)
    if (cost[i] < cost[pick] || (cost[i] == cost[pick] && distance(candidates[i]) < distance(candidates[pick]))) pick = i;
  const Box best = candidates[pick];
  // The leader: from the box's nearest point to the ring's edge.
  const double px = std::clamp(cx, best.x, best.x + w), py = std::clamp(cy, best.y, best.y + h);
  const double length = std::hypot(px - cx, py - cy);
  if (length > radius + 2.0) {
    const double ux = (px - cx) / length, uy = (py - cy) / length;
    draw_line(figure, cx + ux * radius, cy + uy * radius, px, py, kWorstMarkerColor, std::max(1.5, 2.0 * style.scale));
  }
  const int x = static_cast<int>(std::lround(best.x)), y = static_cast<int>(std::lround(best.y));
  fill_rect(figure, {x, y, static_cast<int>(std::lround(w)), static_cast<int>(std::lround(h))}, {255, 255, 255, 230});
  draw_text(figure, x + 3, y + size + 1, label, size, style);
}

// The ring's radius in pixels: the hex's projected extent plus a small
// margin (the ring encloses it, not its neighbours), at least kMinRingRadius
// (a small max, a few pixels, shows inside a ring that reads as one, and
// its outline is not covered by the ring's stroke; issue 48: 10 pixels, the
// dashes of a dashed one merged into a blot over the hex), at most
// kMaxRingFraction of the view's smaller side (issue 48e: kitten_rot's max
// hex drew a 600 px ring over a quarter of the model, the title and the
// picture's edge; its magenta outline shows its extent); and its centre,
// the hex's, moved in as far as needed to keep the ring and its stroke
// inside the view (issue 48e: twist_inject's ring was cut by the picture's
// left edge, kitten_rot's ran over the title).
struct Ring {
  double cx = 0, cy = 0, radius = 0;
};
Ring fit_ring(const PixelRect& view, double cx, double cy, double extent, double stroke, double scale) {
  const double half = 0.5 * std::min(view.width, view.height);
  // The stroke's halo and the labels' margin (issue 48f: twist_inject's
  // ring was 4 px from the picture's edge, the labels 10 px or more).
  const double pad = stroke + 10.0 * scale;
  double radius = std::clamp(extent + 4.0 * scale, kMinRingRadius * scale,
                             std::max(kMinRingRadius * scale, kMaxRingFraction * 2.0 * half));
  // Shrunk towards the edge first (not below the minimum), then moved in.
  const double room = std::min({cx - view.x, view.x + view.width - cx, cy - view.y, view.y + view.height - cy}) - pad;
  radius = std::max(std::min(radius, room), std::min(kMinRingRadius * scale, half - pad));
  const double lo = radius + pad;
  cx = std::clamp(cx, view.x + lo, std::max(view.x + lo, view.x + view.width - lo));
  cy = std::clamp(cy, view.y + lo, std::max(view.y + lo, view.y + view.height - lo));
  return {cx, cy, radius};
}

// The max's density "0.45 (9.7x)": times the scale's reference.
std::string density_with_ratio(double d, const ErrorDensityScale& scale) {
  const double r = d / scale.lo;
  return display_number(d, 3) + " (" + display_number(r, r < 10 ? 2 : 3) + "\u00d7)";
}

// The ring about the densest hex (fit_ring), dashed when it is inside or
// hidden, and its label: "max 11.4 (9.7x), hex 24347 (interior)" outside
// the model (model_points: the boundary's points) with a leader, and with
// a hidden max the densest hex near it that is seen (find_nearest_seen).
// Returns the ring (radius 0: none).
Ring draw_worst_marker(Image& figure, const Figure& f, const HexMesh& mesh, const ErrorDensityWorst& worst,
                         const std::vector<Vec3>& model_points) {
  if (worst.hex == kNoIndex) return {};
  const PixelRect& view = f.layout.view;
  const double aspect = static_cast<double>(view.width) / std::max(1, view.height);
  const auto to_pixel = [&](const Vec3& p, double& x, double& y) {
    const Vec3 ndc = project_to_ndc(f.camera, aspect, p);
    x = view.x + 0.5 * (ndc.x + 1.0) * view.width;
    y = view.y + 0.5 * (1.0 - ndc.y) * view.height;
    return std::isfinite(ndc.x) && std::isfinite(ndc.y);
  };
  // Centred on a seen max's pixels (issue 48f: on kitten_rot the hex's
  // centre projected onto a corner of its face in sight, and the ring was
  // 41 % its colour), else on its centre.
  double cx = f.max_x, cy = f.max_y;
  if (f.max_pixels == 0 && !to_pixel(hex_center(mesh, worst.hex), cx, cy)) return {};
  double extent = 0;
  for (Index v : mesh.hexes[static_cast<std::size_t>(worst.hex)]) {
    double x = 0, y = 0;
    if (to_pixel(point(mesh, v), x, y)) extent = std::max(extent, std::hypot(x - cx, y - cy));
  }
  const double stroke = std::max(2.0, 3.0 * f.style.scale);
  const Ring ring = fit_ring(view, cx, cy, extent, stroke, f.style.scale);
  draw_marker_ring(figure, ring.cx, ring.cy, ring.radius, stroke, !worst.on_boundary || f.worst_hidden,
                   kWorstMarkerColor);
  // The model's projected box and the ring's (which can stick out of it: a
  // max at the silhouette): the label goes in the free margin beside them,
  // so its box never covers the ring (issue 48: it cut off the top of a
  // ring at the model's top edge).
  double x0 = ring.cx - ring.radius, y0 = ring.cy - ring.radius, x1 = ring.cx + ring.radius, y1 = ring.cy + ring.radius;
  for (const Vec3& p : model_points) {
    double x = 0, y = 0;
    if (!to_pixel(p, x, y)) continue;
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  }
  std::string label = "max " + density_with_ratio(worst.density, f.scale) + ", hex " + std::to_string(worst.hex) +
                      (!worst.on_boundary ? " (interior, seen through)"
                       : f.worst_hidden   ? " (on the boundary, hidden: seen through)"
                       : f.max_unoutlined ? " (on the boundary, visible: " + std::to_string(f.max_pixels) + " px)"
                                          : std::string(" (on the boundary)")) +
                      f.worst_note;
  if (f.nearest_seen != kNoIndex)
    label += std::string(f.worst_hidden ? "\nnearest visible: " : "\nalso in sight: ") + density_with_ratio(f.nearest_density, f.scale) + ", hex " +
             std::to_string(f.nearest_seen);
  std::vector<PixelBox> avoid;
  for (Index h : f.drawn_cells) {
    if (h == worst.hex) continue;
    PixelBox box{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                 -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (Index v : mesh.hexes[static_cast<std::size_t>(h)]) {
      double x = 0, y = 0;
      if (!to_pixel(point(mesh, v), x, y)) continue;
      box = {std::min(box.x0, x), std::min(box.y0, y), std::max(box.x1, x), std::max(box.y1, y)};
    }
    avoid.push_back(box);
  }
  draw_worst_label_outside(figure, view, {x0, y0, x1, y1}, ring.cx, ring.cy, ring.radius, label, f.style, avoid);
  return ring;
}

Image finish_figure(Figure& f, const HexMesh& mesh, const ErrorDensityWorst& worst,
                    const ErrorDensityViewOptions& options, Renderer& renderer, Camera* camera, PixelRect* view,
                    ErrorDensityFigureParts* parts) {
  Image figure = render_figure(renderer, f.scene, f.camera, options.width, options.height, f.layout, options.title,
                               f.style);
  draw_color_bar(figure, f.layout.legend, f.bar, f.style);
  const Ring ring = draw_worst_marker(figure, f, mesh, worst, f.model_points);
  if (camera) *camera = f.camera;
  if (view) *view = f.layout.view;
  if (parts) *parts = {f.scene, f.bar.swatches, ring.cx, ring.cy, ring.radius, f.worst_hidden, f.nearest_seen, f.max_pixels, !f.max_unoutlined};
  return figure;
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

// The points' extent along the unit axis a (max - min of their projections).
double extent_along(std::span<const Vec3> points, const Vec3& a) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Vec3& p : points) {
    lo = std::min(lo, dot(p, a));
    hi = std::max(hi, dot(p, a));
  }
  return points.empty() ? 0.0 : hi - lo;
}

// The camera of the hidden-cell verdict: camera's direction and up, the
// near and far planes enclosing the whole boundary (so every occluder is
// drawn), framing the cells' boundary faces (orthographic: the view moved
// across and narrowed to them; perspective: the whole boundary).
Camera verdict_camera(const HexMesh& mesh, const Topology& topology, std::span<const Index> cells,
                      const Camera& camera) {
  Camera verdict =
      fit_camera_to_points(boundary_points(mesh, topology), camera.target - camera.eye, 1.0,
                           {.up = camera.up, .fov_y_degrees = camera.fov_y_degrees, .is_perspective = camera.is_perspective});
  if (verdict.is_perspective) return verdict;
  std::vector<Index> sorted(cells.begin(), cells.end());
  std::sort(sorted.begin(), sorted.end());
  const ScreenAxes axes = screen_axes(verdict);
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (Index face : topology.boundary_faces) {
    if (!std::binary_search(sorted.begin(), sorted.end(), face_hex(topology, face))) continue;
    for (Index v : topology.faces[static_cast<std::size_t>(face)]) {
      const Vec3 d = point(mesh, v) - verdict.target;
      x0 = std::min(x0, dot(d, axes.right)), x1 = std::max(x1, dot(d, axes.right));
      y0 = std::min(y0, dot(d, axes.up)), y1 = std::max(y1, dot(d, axes.up));
    }
  }
  const double size = 1.1 * std::max(x1 - x0, y1 - y0);
  if (!(size > 0) || size >= verdict.ortho_height) return verdict;
  const Vec3 shift = 0.5 * (x0 + x1) * axes.right + 0.5 * (y0 + y1) * axes.up;
  verdict.eye = verdict.eye + shift;
  verdict.target = verdict.target + shift;
  verdict.ortho_height = size;
  return verdict;
}

}  // namespace

Vec3 away_from_edge_on(const Vec3& direction, std::span<const Vec3> points, const Vec3& focus) {
  // Issue 48r: an extruded plate was seen edge-on (a rectangle); 48c: at 30
  // degrees its profile was still squeezed to a strip. Within
  // edge_on_degrees of edge-on to the model's thinnest axis n, the view is
  // tilted to tilt_degrees from edge-on, towards the side of n the focus
  // (the max hex) lies on, keeping its azimuth about n.
  // Issue 48d: 45 and 60 degrees only for a plate (its extent along n below
  // kPlateFraction of its extent along its longest principal axis); on
  // other models 48r's 15 and 30: the plate's rule turned bunny_1_pr's camera
  // so that its max, in plain view at 30, went behind the ear, and no tilt
  // at all left it behind the ear too.
  constexpr double kPlateFraction = 0.5;
  // The model's thinnest axis n: its least-squares plane's normal.
  const LeastSquaresPlane plane = least_squares_plane(points);
  const Vec3 n = plane.normal;
  const bool plate = extent_along(points, n) < kPlateFraction * extent_along(points, plane.longest);
  const double edge_on_degrees = plate ? 45.0 : 15.0, tilt_degrees = plate ? 60.0 : 30.0;
  const Vec3 d = direction / norm(direction);
  if (std::abs(dot(d, n)) >= std::sin(edge_on_degrees * std::numbers::pi / 180.0)) return direction;
  Vec3 across = d - dot(d, n) * n;
  if (!(norm(across) > 1e-9)) return direction;
  across = across / norm(across);
  // The eye at -d: on the focus's side of n when d points against it.
  const double side = dot(focus - plane.centroid, n);
  const double sign = side > 0 ? -1.0 : side < 0 ? 1.0 : (dot(d, n) < 0 ? -1.0 : 1.0);
  const double tilt = tilt_degrees * std::numbers::pi / 180.0;
  return std::cos(tilt) * across + sign * std::sin(tilt) * n;
}

std::array<bool, 12> hex_edges_facing(const HexMesh& mesh, const Hex& hex, const Camera& camera) {
  Vec3 center{0, 0, 0};
  for (Index v : hex) center = center + 0.125 * point(mesh, v);
  std::array<bool, 6> facing{};
  for (std::size_t f = 0; f < kHexFaces.size(); ++f) {
    const Vec3 &a = point(mesh, hex[kHexFaces[f][0]]), &b = point(mesh, hex[kHexFaces[f][1]]),
               &c = point(mesh, hex[kHexFaces[f][2]]), &d = point(mesh, hex[kHexFaces[f][3]]);
    const Vec3 mid = 0.25 * (a + b + c + d);
    Vec3 normal = cross(c - a, d - b);
    if (dot(normal, mid - center) < 0) normal = -1.0 * normal;
    const Vec3 to_eye = camera.is_perspective ? camera.eye - mid : camera.eye - camera.target;
    facing[f] = dot(normal, to_eye) > 0;
  }
  std::array<bool, 12> front{};
  for (std::size_t e = 0; e < kHexEdges.size(); ++e)
    for (std::size_t f = 0; f < kHexFaces.size(); ++f) {
      int shared = 0;
      for (int i = 0; i < 4; ++i)
        shared += kHexFaces[f][static_cast<std::size_t>(i)] == kHexEdges[e][0] ||
                  kHexFaces[f][static_cast<std::size_t>(i)] == kHexEdges[e][1];
      front[e] = front[e] || (shared == 2 && facing[f]);
    }
  return front;
}

ErrorDensityScale error_density_scale(std::span<const double> density, double reference) {
  ErrorDensityScale s;
  s.max = s.median = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> positive;
  for (double d : density)
    if (is_positive(d)) positive.push_back(d);
  if (!positive.empty()) {
    // The max and percentile_of_sorted's median (the mean of the two middle
    // values for an even count) by selection: no full sort of every hex's
    // density, which runs per figure and again in the viewer.
    s.max = *std::max_element(positive.begin(), positive.end());
    const std::size_t lo = (positive.size() - 1) / 2;
    const auto middle = positive.begin() + static_cast<std::ptrdiff_t>(lo);
    std::nth_element(positive.begin(), middle, positive.end());
    s.median = *middle;
    if (positive.size() % 2 == 0) s.median += 0.5 * (*std::min_element(middle + 1, positive.end()) - *middle);
  }
  // Issue 48c: relative to a reference, the mesh's median unless given (48r's
  // p05-to-max range painted a mesh whose max is 2x its median red; 48's
  // fixed 0.01-10 put every mesh in one pale band): pale up to the
  // reference, red from kErrorDensitySpan times it, or from the max when
  // higher; a given reference keeps the top there too (every mesh one scale).
  s.given = is_positive(reference);
  const double ref = s.given ? reference : s.median;
  if (!is_positive(ref)) return s;
  s.lo = ref;
  s.hi = s.given || !(s.max > kErrorDensitySpan * ref) ? kErrorDensitySpan * ref : s.max;
  return s;
}

Color error_density_color(double density, const ErrorDensityScale& scale) {
  if (!is_positive(density)) return kUndefinedColor;
  const double t = (std::log10(density) - std::log10(scale.lo)) / (std::log10(scale.hi) - std::log10(scale.lo));
  return sample_quality_map(1.0 - std::clamp(t, 0.0, 1.0));
}

ColorBar error_density_color_bar(const ErrorDensityScale& scale) {
  ColorBar bar;
  const bool relative = is_positive(scale.median) || scale.given;
  bar.label = std::string("FEM error density\n|u\u2212u_h|\u00b2_H1(e) / (|e| h_e\u00b2 |D\u00b2u|\u00b2),\nh_e = |e|^(1/3); no unit; log;\n") +
              (!relative      ? "no positive density"
               : scale.given ? "\u00d7 the given reference: pale \u2264 1\u00d7,\nred \u2265 10\u00d7"
                             : "\u00d7 this mesh's median: pale \u2264 1\u00d7,\nred at 10\u00d7 (or the max, if higher)");
  bar.min_value = std::log10(scale.lo);
  bar.max_value = std::log10(scale.hi);
  for (int i = 0; i <= 32; ++i)
    bar.colors.push_back(error_density_color(std::pow(10.0, bar.min_value + (bar.max_value - bar.min_value) * i / 32.0),
                                             scale));
  const auto value = [](double v) { return display_number(v, 3); };
  const auto times = [](double r) { return display_number(r, r < 10 ? 2 : 3) + "\u00d7"; };
  bar.ticks.push_back({bar.min_value, "\u2264 " + value(scale.lo) +
                                          (!relative     ? std::string()
                                           : scale.given ? " (reference)"
                                                         : " (median)")});
  const double span = bar.max_value - bar.min_value;
  const bool has_max = is_positive(scale.max);
  // The max's tick: where it is, at the top when above a given scale's (none
  // below the bottom: the title gives it).
  const bool max_on_bar = has_max && std::log10(scale.max) > bar.min_value;
  const double max_at = max_on_bar ? std::min(std::log10(scale.max), bar.max_value) : bar.max_value;
  // Round multiples of the reference between (2x, 5x, 10x, 20x, ...; whole
  // decades over more than two), none crowding an end's label or the max's;
  // the top end always labelled (issue 48e: warrior_rot's max at 9x, 0.046
  // decades under it, dropped the 10x tick, and nothing gave the red end's
  // value): beside the max's tick when more than kTopApart of the span from
  // it, else in one label with it at the top.
  constexpr double kApart = 0.08, kTopApart = 0.04;
  const bool decades_only = span > 2.0 + 1e-9;
  const bool max_at_top = max_on_bar && max_at >= bar.max_value - 1e-12;  // the max is the top, or above it
  bool merged = false;
  for (int k = 0; k <= static_cast<int>(std::ceil(span)); ++k)
    for (double m : {1.0, 2.0, 5.0}) {
      if (decades_only && m != 1.0) continue;
      const double raw = bar.min_value + std::log10(m) + k;
      if (raw > bar.max_value + 1e-9) continue;
      const double at = std::min(raw, bar.max_value);  // 10x: the top exactly (the bar drops u > 1)
      const bool top = at >= bar.max_value - 1e-9;
      if (!(at - bar.min_value > kApart * span)) continue;
      std::string label = relative ? times(m * std::pow(10.0, k)) + " (" + value(m * std::pow(10.0, k) * scale.lo) + ")"
                                   : value(m * std::pow(10.0, k) * scale.lo);
      if (max_on_bar && std::abs(at - max_at) <= (top ? kTopApart : kApart) * span) {
        const bool above = std::log10(scale.max) > bar.max_value + 1e-12;  // clamped to the top
        if (!top || (max_at_top && !above)) continue;  // the max's own label gives the top's value
        merged = true;  // the max just under the top, or above it: one label
        label += std::string(above ? ", \u2191 mesh max " : ", mesh max ") + value(scale.max) +
                 (relative ? " (" + times(scale.max / scale.lo) + ")" : std::string());
      }
      bar.ticks.push_back({at, label});
    }
  if (max_on_bar && !merged)
    bar.ticks.push_back({max_at, (std::log10(scale.max) > bar.max_value + 1e-12 ? "\u2191 mesh max " : "mesh max ") +
                                     value(scale.max) + (relative ? " (" + times(scale.max / scale.lo) + ")" : std::string())});
  bar.swatches = {{kUndefinedColor, "undefined"}};
  return bar;
}

ErrorDensityWorst error_density_worst(const Topology& topology, std::span<const double> density) {
  ErrorDensityWorst w;
  w.boundary_max = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t h = 0; h < density.size(); ++h)
    if (is_positive(density[h]) && (w.hex == kNoIndex || density[h] > w.density)) {
      w.hex = static_cast<Index>(h);
      w.density = density[h];
    }
  for (Index face : topology.boundary_faces) {
    const Index h = face_hex(topology, face);
    if (static_cast<std::size_t>(h) >= density.size()) continue;
    const double d = density[static_cast<std::size_t>(h)];
    if (h == w.hex) w.on_boundary = true;
    if (is_positive(d) && !(d <= w.boundary_max)) w.boundary_max = d;
  }
  return w;
}

std::vector<Index> error_density_cells(std::span<const double> density, const ErrorDensityViewOptions& options) {
  return densest_hexes(density, options.densest_fraction, std::max<std::size_t>(1, options.max_cells));
}

Vec3 choose_error_density_viewpoint(const HexMesh& mesh, const Topology& topology, std::span<const double> density,
                                    const ErrorDensityViewOptions& options, Renderer* renderer) {
  constexpr std::size_t kViewCandidates = 3;
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
  const std::vector<Vec3> points = boundary_points(mesh, topology);
  const ErrorDensityWorst worst = error_density_worst(topology, density);
  const std::vector<Vec3> chosen =
      choose_viewpoints(points, centers, radii, aspect, renderer ? kViewCandidates : 1, options.up, kFovY);
  if (worst.hex == kNoIndex) return chosen.front();
  // Issue 48d: the first candidate (best for the densest 1%) whose max hex
  // is seen (error_density_cells_behind_boundary); the first when none is
  // (bunny_1_pr: the first hid its max behind the ear, the second shows it).
  const std::vector<Index> max_hex{worst.hex};
  for (const Vec3& candidate : chosen) {
    const Vec3 d = away_from_edge_on(candidate, points, hex_center(mesh, worst.hex));
    if (!renderer || !worst.on_boundary) return d;
    const Camera camera =
        fit_camera_to_points(points, d, 1.0, {.up = options.up, .fov_y_degrees = kFovY, .is_perspective = false});
    if (!error_density_cells_behind_boundary(mesh, topology, max_hex, camera, *renderer).front()) return d;
  }
  return away_from_edge_on(chosen.front(), points, hex_center(mesh, worst.hex));
}

Image render_error_density_boundary(const HexMesh& mesh, const Topology& topology, std::span<const double> density,
                                    const Vec3& view_direction, const ErrorDensityViewOptions& options,
                                    Renderer& renderer, Camera* camera, PixelRect* view,
                                    ErrorDensityFigureParts* parts) {
  check_sizes(mesh, density, "error density");
  const ErrorDensityScale scale = error_density_scale(density, options.reference);
  Figure f = begin_figure(mesh, topology, scale, view_direction, options);
  const ErrorDensityWorst worst = error_density_worst(topology, density);
  TriangleSet faces;
  faces.is_lit = false;  // the legend's colours exactly; the edges give the shape
  for (Index face : topology.boundary_faces)
    add_quad(faces, mesh, f.scene.origin, topology.faces[static_cast<std::size_t>(face)],
             to_rgba8(error_density_color(density[static_cast<std::size_t>(face_hex(topology, face))], scale)));
  f.scene.triangles.push_back(std::move(faces));
  f.scene.lines.push_back(boundary_edge_lines(mesh, topology, f.scene.origin, kBoundaryEdgeColor,
                                              static_cast<float>(std::max(1.0, f.style.scale))));
  // The legend names only what is drawn: "undefined" (the bar's one
  // swatch) when a face's hex has no density (issue 47: it was listed with none).
  if (std::all_of(topology.boundary_faces.begin(), topology.boundary_faces.end(), [&](Index face) {
        return is_positive(density[static_cast<std::size_t>(face_hex(topology, face))]);
      }))
    f.bar.swatches.clear();
  // A max the boundary hides from here (interior, or a boundary one whose
  // faces this side does not show: on the far side, behind a fold or
  // edge-on) shows through it, so the dashed ring circles the max itself,
  // not other hexes' faces (issue 48h round 2).
  f.worst_hidden = max_hex_behind_boundary(f, mesh, topology, worst, renderer);
  if (worst.hex != kNoIndex) {
    std::vector<std::array<Index, 4>> own, others;
    for (Index face : topology.boundary_faces)
      (face_hex(topology, face) == worst.hex ? own : others).push_back(topology.faces[static_cast<std::size_t>(face)]);
    max_pixels_in_view(f, mesh, own, others, renderer);
  }
  f.max_unoutlined = max_too_small_to_outline(f, boundary_max_stroke(f).halo_width);
  find_nearest_seen(f, mesh, topology, density, worst, renderer);
  add_max_outline(f, mesh, worst);
  f.drawn_cells = error_density_cells(density, options);  // the label keeps off the densest region
  // The ring and the outline as drawn (issue 48h: the ring was a black
  // box; issue 48: the outline had no entry).
  for (ColorBarSwatch swatch : error_density_boundary_swatches(worst, f.worst_hidden, f.max_undashed, !f.max_unoutlined)) {
    if (swatch.shape == SwatchShape::dashed_line || swatch.shape == SwatchShape::thick_line)
      swatch.stroke = boundary_max_stroke(f);
    f.bar.swatches.push_back(swatch);
  }
  return finish_figure(f, mesh, worst, options, renderer, camera, view, parts);
}

Image render_error_density_cells(const HexMesh& mesh, const Topology& topology, std::span<const double> density,
                                 std::span<const double> cell_scaled_jacobian, const Vec3& view_direction,
                                 const ErrorDensityViewOptions& options, Renderer& renderer, Camera* camera,
                                 PixelRect* view, ErrorDensityFigureParts* parts) {
  check_sizes(mesh, density, "error density");
  check_sizes(mesh, cell_scaled_jacobian, "cell scaled Jacobian");
  const ErrorDensityScale scale = error_density_scale(density, options.reference);
  Figure f = begin_figure(mesh, topology, scale, view_direction, options);
  const ErrorDensityWorst worst = error_density_worst(topology, density);
  const std::vector<Index> shown = error_density_cells(density, options);
  const std::vector<bool> hidden =
      error_density_cells_behind_boundary(mesh, topology, shown, f.camera, renderer);
  f.drawn_cells = shown;
  // The veil first (blended over the background only), then the cells and
  // their edges in the overlay layer over it: no veil is ever blended over a
  // cell and no face is shaded, so every face is exactly its colour-bar
  // colour; the cells the boundary hides get dashed edges, and the max
  // hex's edges, drawn last, are kMaxHexEdgeColor (no other mark uses it)
  // on a white halo.
  TriangleSet veil;  // lit: its shading gives the shape
  for (Index face : topology.boundary_faces)
    add_quad(veil, mesh, f.scene.origin, topology.faces[static_cast<std::size_t>(face)], kVeilColor);
  f.scene.translucent.push_back(std::move(veil));
  TriangleSet cells;
  cells.is_lit = false;
  // casing: a light outline under the edges of a cell the boundary hides,
  // drawn under every fill (seen only beside the cell). The max hex: its edges on the faces turned to the camera
  // solid, the others (its back) thin and dashed, all drawn over nearer
  // cells; a white halo, black when its SJ is below the threshold (the thick
  // black edge's meaning kept).
  LineSet low_edges, edges, casing, halo, halo_core, max_back, max_back_halo;
  edges.width = static_cast<float>(std::max(1.0, f.style.scale));
  low_edges.width = static_cast<float>(std::max(2.0, 2.5 * f.style.scale));
  casing.width = static_cast<float>(std::max(5.0, 6.0 * f.style.scale));
  const auto front_stroke = [&](bool low) {
    return max_edge_stroke(f, std::max(2.5, 3.0 * f.style.scale), std::max(6.0, 7.0 * f.style.scale),
                           low ? kLowCellEdgeColor : Rgba8{255, 255, 255, 255}, f.worst_hidden);
  };
  halo.width = static_cast<float>(front_stroke(false).halo_width);
  halo_core.width = static_cast<float>(front_stroke(false).width);
  max_back.width = static_cast<float>(std::max(1.5, 1.5 * f.style.scale));
  // Issue 48c: on a crimson fill the thin magenta back edges vanished; a
  // white halo lifts them off any fill.
  max_back_halo.width = static_cast<float>(std::max(3.5, 3.5 * f.style.scale));
  const double back_width = max_back.width, back_halo_width = max_back_halo.width;
  const Vec3& origin = f.scene.origin;
  // The max hidden by the same test as the boundary figure's (issue 48h
  // round 2: it was drawn solid, as if in front, where the boundary figure
  // said its faces are not seen): then its front edges are dashed too.
  f.worst_hidden = max_hex_behind_boundary(f, mesh, topology, worst, renderer);
  if (worst.hex != kNoIndex) {  // the max among the drawn cells, each drawn whole
    std::vector<std::array<Index, 4>> own, others;
    for (Index h : shown) {
      const Hex& hex = mesh.hexes[static_cast<std::size_t>(h)];
      for (const auto& face : kHexFaces)
        (h == worst.hex ? own : others).push_back({hex[face[0]], hex[face[1]], hex[face[2]], hex[face[3]]});
    }
    max_pixels_in_view(f, mesh, own, others, renderer);
  }
  f.max_unoutlined = max_too_small_to_outline(f, front_stroke(false).halo_width);
  find_nearest_seen(f, mesh, topology, density, worst, renderer);
  bool any_low = false, any_hidden = false, max_low = false;
  for (std::size_t k = 0; k < shown.size(); ++k) {
    const Index h = shown[k];
    const Hex& hex = mesh.hexes[static_cast<std::size_t>(h)];
    const Rgba8 color = to_rgba8(error_density_color(density[static_cast<std::size_t>(h)], scale));
    for (const auto& face : kHexFaces) {
      const std::array<Index, 4> q{hex[face[0]], hex[face[1]], hex[face[2]], hex[face[3]]};
      add_quad(cells, mesh, f.scene.origin, q, color);
    }
    const double sj = cell_scaled_jacobian[static_cast<std::size_t>(h)];
    const bool low = sj < options.quality_threshold || is_verdict_sentinel(sj);
    any_low = any_low || low;
    const bool behind = h == worst.hex ? f.worst_hidden : static_cast<bool>(hidden[k]);
    any_hidden = any_hidden || behind;
    LineSet& set = low ? low_edges : edges;
    const Rgba8 edge_color = low ? kLowCellEdgeColor : kCellEdgeColor;
    const std::array<bool, 12> front = h == worst.hex ? hex_edges_facing(mesh, hex, f.camera) : std::array<bool, 12>{};
    if (h == worst.hex) {
      max_low = low;
      f.worst_note = ", SJ " + display_number(sj, 2);
    }
    for (std::size_t e = 0; e < kHexEdges.size(); ++e) {
      const Vec3 &a = point(mesh, hex[kHexEdges[e][0]]), &b = point(mesh, hex[kHexEdges[e][1]]);
      if (!behind) {
        add_segment(set, origin, a, b, edge_color);
      } else {  // dashed on a veil-coloured casing
        add_segment(casing, origin, a, b, kVeilOverWhite);
        add_dashed(set, f, a, b, edge_color);
      }
      if (h != worst.hex || f.max_unoutlined) continue;
      if (front[e] && !behind) {  // the max's front edges: solid magenta on a halo
        add_segment(halo, origin, a, b, low ? kLowCellEdgeColor : Rgba8{255, 255, 255, 255});
        add_segment(halo_core, origin, a, b, kMaxHexEdgeColor);
      } else if (front[e]) {  // hidden: the same, dashed
        add_dashed(halo, f, a, b, low ? kLowCellEdgeColor : Rgba8{255, 255, 255, 255});
        add_dashed(halo_core, f, a, b, kMaxHexEdgeColor);
      } else {  // its back edges: thin, dashed, on a thin white halo
        add_dashed(max_back_halo, f, a, b, Rgba8{255, 255, 255, 255});
        add_dashed(max_back, f, a, b, kMaxHexEdgeColor);
      }
    }
  }
  f.scene.overlay.push_back(std::move(cells));
  // The casing under the fills (with the other lines, before the veil and
  // the overlay's cells: issue 48h round 2, it was painted over them in the
  // veil's colour): it shows only beside a cell, where it lifts the dashes
  // off the veil; every fill keeps its colour of the bar.
  edges.in_overlay = low_edges.in_overlay = halo.in_overlay = halo_core.in_overlay = max_back.in_overlay =
      max_back_halo.in_overlay = true;
  // The max's wireframe over nearer cells (its back thin and dashed first).
  max_back.over_all = max_back_halo.over_all = halo.over_all = halo_core.over_all = true;
  f.scene.lines.push_back(std::move(casing));
  f.scene.lines.push_back(std::move(edges));
  f.scene.lines.push_back(std::move(low_edges));
  f.scene.lines.push_back(std::move(max_back_halo));
  f.scene.lines.push_back(std::move(max_back));
  f.scene.lines.push_back(std::move(halo));
  f.scene.lines.push_back(std::move(halo_core));
  // The legend: only the marks the figure has (no "undefined": a drawn cell
  // has a density); short lines, so the bar keeps its size.
  f.bar.swatches =
      error_density_cells_swatches(worst, f.worst_hidden, {any_low, max_low, any_hidden, !f.max_unoutlined},
                                   options.quality_threshold);
  // The front and back edges' swatches: their stroke, halo and dashes as drawn.
  for (ColorBarSwatch& swatch : f.bar.swatches) {
    if (to_rgba8(swatch.color) != kMaxHexEdgeColor) continue;
    if (swatch.shape == SwatchShape::thick_dashed_line || swatch.shape == SwatchShape::thick_line)
      swatch.stroke = front_stroke(max_low);
    else if (swatch.shape == SwatchShape::dashed_line)
      swatch.stroke = max_edge_stroke(f, back_width, back_halo_width, {255, 255, 255, 255}, true);
  }
  return finish_figure(f, mesh, worst, options, renderer, camera, view, parts);
}

std::vector<ColorBarSwatch> error_density_boundary_swatches(const ErrorDensityWorst& worst, bool max_hidden,
                                                            bool max_undashed, bool max_outlined) {
  if (worst.hex == kNoIndex) return {};
  const Color magenta = to_color(kMaxHexEdgeColor);
  if (!max_hidden && !max_outlined) return {worst_ring_swatch(worst, false), too_small_to_outline_swatch()};
  // Issue 48e: what is drawn. A hidden max whose edges are all shorter than
  // a dash is drawn solid through the surface (a dashed outline that small
  // was a magenta blot, and the legend said "dashed outline"); a seen one
  // depth-tested, so only its edges in sight show.
  if (max_hidden && max_undashed)
    return {worst_ring_swatch(worst, true),
            {magenta, "max hex: outline (too small", SwatchShape::thick_line},
            {magenta, "  to dash; behind: seen through)", SwatchShape::text}};
  if (max_hidden)
    return {worst_ring_swatch(worst, true),
            {magenta, "max hex: dashed outline", SwatchShape::dashed_line},
            {magenta, "  (behind: seen through)", SwatchShape::text}};
  return {worst_ring_swatch(worst, false), {magenta, "max hex: its edges in sight", SwatchShape::thick_line}};
}

std::vector<ColorBarSwatch> error_density_cells_swatches(const ErrorDensityWorst& worst, bool max_hidden,
                                                         const ErrorDensityCellsMarks& marks,
                                                         double quality_threshold) {
  std::vector<ColorBarSwatch> swatches;
  const Color magenta = to_color(kMaxHexEdgeColor);
  if (worst.hex != kNoIndex && !max_hidden && !marks.max_outlined) {
    swatches.push_back(worst_ring_swatch(worst, false));
    swatches.push_back(too_small_to_outline_swatch());
  } else if (worst.hex != kNoIndex) {
    swatches.push_back(worst_ring_swatch(worst, max_hidden));
    // Front thick, back thin (issue 48: a hidden max's front and back
    // swatches were the same thin dashed line).
    swatches.push_back(
        max_hidden ? ColorBarSwatch{magenta, "max hex: front edges, dashed (hidden)", SwatchShape::thick_dashed_line}
                   : ColorBarSwatch{magenta, "max hex: its front edges", SwatchShape::thick_line});
    swatches.push_back({magenta, "max hex: back edges (thin)", SwatchShape::dashed_line});
    swatches.push_back({magenta, "  (drawn over nearer cells)", SwatchShape::text});
  }
  swatches.push_back({to_color(kVeilOverWhite), "boundary (veil)"});
  swatches.push_back({to_color(kCellEdgeColor), "edge of a drawn cell", SwatchShape::line});
  const std::string threshold = display_number(quality_threshold, 3);
  if (marks.any_low)
    swatches.push_back({to_color(kLowCellEdgeColor),
                        (marks.max_low ? "black edge or halo: SJ < " : "thick edge: SJ < ") + threshold,
                        SwatchShape::thick_line});
  if (marks.any_hidden) {
    swatches.push_back({to_color(kCellEdgeColor), "dashed: behind the boundary", SwatchShape::dashed_line});
    swatches.push_back({to_color(kCellEdgeColor), "  (seen through the veil)", SwatchShape::text});
  }
  return swatches;
}

std::vector<bool> error_density_cells_behind_boundary(const HexMesh& mesh, const Topology& topology,
                                                      std::span<const Index> cells, const Camera& camera,
                                                      Renderer& renderer) {
  std::vector<bool> hidden(cells.size(), false);
  if (cells.empty() || cells.size() + 2 > kMaxId) return hidden;
  const Box3 box = boundary_bounding_box(mesh, topology);
  const Vec3 origin = 0.5 * (box.lo + box.hi);
  // Decided on its own square id image of kVerdictPixels along the
  // camera's direction (issue 48d: at the figure's size a wider legend, a
  // slightly smaller view, turned warrior_rot's max from seen to hidden; the
  // verdict now depends on the direction only), framed on the cells' own
  // boundary faces (issue 48e: framed on the whole boundary, a 10 x 7 px
  // max face fell under 48d's 64 px floor and was called hidden though in
  // plain view; zoomed, the verdict is the fraction alone, whatever the
  // face's size in the figure).
  constexpr int kVerdictPixels = 1200;
  const Camera verdict = verdict_camera(mesh, topology, cells, camera);
  std::vector<Index> sorted(cells.begin(), cells.end());
  std::sort(sorted.begin(), sorted.end());
  // Each boundary face of the cells its own id, 2 + j (owner[j] its cell's
  // index in cells); every other boundary face id 1.
  TriangleSet own, other;
  own.is_lit = other.is_lit = false;
  std::vector<std::size_t> owner;
  std::vector<double> area;  // each own face's area (model units^2)
  for (Index face : topology.boundary_faces) {
    const Index h = face_hex(topology, face);
    const auto at = std::lower_bound(sorted.begin(), sorted.end(), h);
    if (at == sorted.end() || *at != h) {
      add_quad(other, mesh, origin, topology.faces[static_cast<std::size_t>(face)], id_color(1));
      continue;
    }
    if (owner.size() + 3 > kMaxId) return hidden;
    owner.push_back(static_cast<std::size_t>(std::find(cells.begin(), cells.end(), h) - cells.begin()));
    const std::array<Index, 4>& q = topology.faces[static_cast<std::size_t>(face)];
    area.push_back(0.5 * norm(cross(point(mesh, q[2]) - point(mesh, q[0]), point(mesh, q[3]) - point(mesh, q[1]))));
    add_quad(own, mesh, origin, topology.faces[static_cast<std::size_t>(face)],
             id_color(static_cast<std::uint32_t>(owner.size() + 1)));
  }
  Scene alone;
  alone.origin = origin;
  alone.background = id_color(0);
  alone.triangles.push_back(own);
  Scene with = alone;
  with.triangles.push_back(std::move(other));
  const IdImage a = renderer.render_ids(alone, verdict, kVerdictPixels, kVerdictPixels);
  const IdImage b = renderer.render_ids(with, verdict, kVerdictPixels, kVerdictPixels);
  if (a.empty() || b.empty() || a.ids.size() != b.ids.size()) return hidden;
  std::vector<std::size_t> seen_alone(owner.size(), 0), seen_with(owner.size(), 0);
  for (std::size_t i = 0; i < a.ids.size(); ++i) {
    if (a.ids[i] >= 2 && a.ids[i] - 2 < owner.size()) ++seen_alone[a.ids[i] - 2];
    if (b.ids[i] >= 2 && b.ids[i] - 2 < owner.size()) ++seen_with[b.ids[i] - 2];
  }
  // Seen: one of its boundary faces shows at least half of what it covers
  // drawn alone (issue 48e: the fraction only; 48d's 64 px floor made a
  // small face in plain view hidden), and drawn alone at least
  // kMinFacing of its area face-on (orthographic: the cosine of its angle
  // to the view; issue 48e: with the floor gone, armadillo's max face seen
  // edge-on, a 3 px sliver, was called seen) and kMinSeenPixels, face by
  // face (issue 48c: summed over the cell, a face turned away, drawn alone,
  // outweighed a face seen at a grazing angle, and a max at the silhouette
  // whose face is in plain view was called hidden). Hidden: none is (an
  // interior cell, one behind a fold or on the far side, or whose faces are
  // off screen or edge-on).
  constexpr std::size_t kMinSeenPixels = 16;
  constexpr double kMinFacing = 0.15;
  const double pixel = verdict.ortho_height / kVerdictPixels;
  std::fill(hidden.begin(), hidden.end(), true);
  for (std::size_t j = 0; j < owner.size(); ++j) {
    const bool facing = verdict.is_perspective ||
                        static_cast<double>(seen_alone[j]) * pixel * pixel >= kMinFacing * area[j];
    if (facing && seen_alone[j] >= kMinSeenPixels && 2 * seen_with[j] >= seen_alone[j]) hidden[owner[j]] = false;
  }
  return hidden;
}

}  // namespace hq
