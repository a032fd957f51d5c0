#include "hqview/views/detail_views.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <span>

#include "hqview/core/box3.h"
#include "hqview/glyph/glyph_ties.h"
#include "hqview/core/error.h"
#include "hqview/core/quality_text.h"
#include "hqview/image/colormap.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/quality/cell_corner_jacobian.h"
#include "hqview/quality/quality_field.h"
#include "hqview/render/annotate.h"
#include "hqview/render/label_layout.h"
#include "hqview/render/upright.h"
#include "hqview/views/main_views.h"
#include "hqview/views/surface_views.h"

namespace hq {
namespace {

// Glyphs of a cluster overlap by definition; at full size they hide the
// cells they sit on, so view C draws them at half their radius, and at most
// this fraction of the mean edge length of the cluster's cells (an inverted
// vertex's half-size glyph is still about one edge in radius: a cluster of
// them would be one blob hiding every cell).
constexpr double kClusterGlyphScale = 0.5;
constexpr double kClusterGlyphMaxEdgeFraction = 0.35;
constexpr double kClusterGlyphMinEdgeFraction = 0.08;
// View C of a planar surface mesh: how far its inverted faces are lifted
// over the others (and its edges twice that), in frame diagonals.
constexpr double kPlanarLift = 0.002;
constexpr Rgba8 kNeighbourEdgeColor{150, 152, 160, 255};
constexpr Rgba8 kRegionFaceColor{190, 196, 210, 60};
// View D's discs' rims (a dark outline, kLocalRimScale of each disc).
constexpr Rgba8 kLocalRimColor{40, 40, 46, 255};
// View C of a surface mesh: its cluster's edges lifted towards the eye by
// this many times the largest glyph's radius (surface_cluster_marks).
constexpr double kClusterEdgeLift = 1.05;
// View C's inset (ClusterInset): drawn when the cluster's shortest edge is
// under kInsetBelowPixels on screen (at scale 1), kInsetShare of the view's
// width and height, zoomed so that edge is kInsetEdgePixels long; its frame
// and the box in the view in kInsetColor.
constexpr double kInsetBelowPixels = 16.0;
constexpr double kInsetShare = 0.42;
constexpr double kInsetEdgePixels = 48.0;
constexpr Rgba8 kInsetColor{20, 20, 24, 255};
// View D's inset: each disc at most kInsetDiscPixels in radius, the
// vertex's dot kInsetDotPixels (at scale 1).
constexpr double kInsetDiscPixels = 10.0;
constexpr double kInsetDotPixels = 5.0;
constexpr double kInsetRoomShare = 0.8;  // of the way from a disc's anchor to its face's nearest edge
constexpr double kInsetMinZoom = 3.0, kInsetMaxZoom = 40.0;
constexpr double kInsetSliverRatio = 0.2;  // a face whose shortest edge is under this share of its longest

Vec3 centre_of(const std::vector<Vec3>& points) {
  if (points.empty()) return {};
  const Box3 box = bounding_box(points);
  return 0.5 * (box.lo + box.hi);
}

// Calls f(corner ids, size) for each face of cell c (any kind, id over all
// blocks): a volume cell's faces (for_each_face_of), a surface cell itself
// (a surface mesh's quad or triangle is its own face).
template <class F>
void for_each_drawn_face(const HexMesh& mesh, Index c, F&& f) {
  const CellRef cell = any_cell(mesh, c);
  if (cell_kind_dimension(cell.kind) == 3) return for_each_face_of(cell, f);
  std::array<Index, 4> v{kNoIndex, kNoIndex, kNoIndex, kNoIndex};
  std::copy_n(cell.corners.begin(), cell.num_corners, v.begin());
  f(v, cell.num_corners);
}

// Unique edges of the given cells (from their faces), in one colour, in
// ascending (a, b) order: the edges as 64-bit keys a * 2^32 + b, sorted.
LineSet cell_edges(const HexMesh& mesh, const Topology& topology, const std::vector<Index>& cells, const Vec3& origin,
                   Rgba8 color, float width) {
  std::vector<std::uint64_t> keys;
  keys.reserve(24 * cells.size());
  for (Index c : cells)
    for (int f = 0; f < 6 && c < mesh.num_hexes(); ++f) {
      const Quad& q = topology.faces[static_cast<std::size_t>(topology.hex_faces[6 * static_cast<std::size_t>(c) + f])];
      for (int i = 0; i < 4; ++i) {
        const auto a = static_cast<std::uint32_t>(std::min(q[i], q[(i + 1) % 4]));
        const auto b = static_cast<std::uint32_t>(std::max(q[i], q[(i + 1) % 4]));
        keys.push_back(std::uint64_t{a} << 32 | b);
      }
    }
  // Cells of other kinds (ids past the hexes: view D's one ring): their
  // faces' edges from CellKindTable.
  const Index num_hexes = mesh.num_hexes();
  for (Index c : cells) {
    if (c < num_hexes) continue;
    for_each_drawn_face(mesh, c, [&](const std::array<Index, 4>& v, int size) {
      for (int i = 0; i < size; ++i) {
        const Index x = v[static_cast<std::size_t>(i)], y = v[static_cast<std::size_t>((i + 1) % size)];
        keys.push_back(std::uint64_t{static_cast<std::uint32_t>(std::min(x, y))} << 32 |
                       static_cast<std::uint32_t>(std::max(x, y)));
      }
    });
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  LineSet lines;
  lines.width = width;
  lines.indices.reserve(2 * keys.size());
  lines.positions.reserve(2 * keys.size());
  lines.colors.assign(2 * keys.size(), color);
  for (const std::uint64_t key : keys)
    for (const std::uint64_t v : {key >> 32, key & 0xFFFFFFFFu}) {
      lines.indices.push_back(static_cast<std::uint32_t>(lines.positions.size()));
      lines.positions.push_back(to_vec3f(mesh.points[static_cast<std::size_t>(v)] - origin));
    }
  return lines;
}

// Faces of the cells used once among them (the region's outer surface), pale,
// in ascending face order: each face's uses counted (up to 2) in a table
// of all faces, then the table read in order. With cell_quality (a surface
// mesh's cell scaled Jacobians, by cell id), each face in
// quality_color(its cell's value) instead, opaque.
// Whether the quad v (a surface cell's face) is filled along its diagonal
// 1-3: when corner 1 or 3 is reflex (turns against the quad's Newell area),
// the diagonal 0-2 runs outside the quad and one of its triangles spills
// over the quad's edge, a fill with no edge line (47g review #1, a planar
// fold). A bow-tie keeps 0-2 (no diagonal is inside it).
bool splits_at_1_3(const HexMesh& mesh, const std::array<Index, 4>& v) {
  const auto p = [&](int i) { return mesh.points[static_cast<std::size_t>(v[static_cast<std::size_t>(i % 4)])]; };
  Vec3 area{};
  for (int i = 0; i < 4; ++i) area = area + cross(p(i), p(i + 1));
  const auto turns_with = [&](int a, int b, int c) { return dot(cross(p(b) - p(a), p(c) - p(a)), area) > 0.0; };
  return !(turns_with(0, 1, 2) && turns_with(0, 2, 3)) && turns_with(1, 2, 3) && turns_with(1, 3, 0);
}

TriangleSet outer_faces(const HexMesh& mesh, const Topology& topology, const std::vector<Index>& cells,
                        const Vec3& origin, Rgba8 color, std::span<const double> cell_quality = {}) {
  std::vector<std::uint8_t> uses(topology.faces.size(), 0);
  std::size_t first = uses.size(), last = 0;  // the range of faces used
  for (Index c : cells)
    for (int f = 0; f < 6 && c < mesh.num_hexes(); ++f) {
      const auto face = static_cast<std::size_t>(topology.hex_faces[6 * static_cast<std::size_t>(c) + f]);
      uses[face] = static_cast<std::uint8_t>(std::min(2, uses[face] + 1));
      first = std::min(first, face);
      last = std::max(last, face + 1);
    }
  TriangleSet set;
  for (std::size_t face = first; face < last; ++face) {
    if (uses[face] != 1) continue;
    const Quad& q = topology.faces[face];
    const auto base = static_cast<std::uint32_t>(set.positions.size());
    for (Index v : q) {
      set.positions.push_back(to_vec3f(mesh.points[static_cast<std::size_t>(v)] - origin));
      set.colors.push_back(color);
    }
    set.indices.insert(set.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  }
  // Cells of other kinds: every face (a face shared with a hex is drawn
  // twice: pale and translucent, that is fine). A surface mesh's faces
  // (filled by cell_quality, no hex faces before them) each shaded by one
  // normal, its Newell normal: a non-planar quad's two triangles flat-shaded
  // apart read as an extra edge (47g review #11).
  const bool one_normal_a_face = !cell_quality.empty() && set.positions.empty();
  for (Index c : cells) {
    if (c < mesh.num_hexes()) continue;
    const Rgba8 fill = static_cast<std::size_t>(c) < cell_quality.size()
                           ? to_rgba8(quality_color(cell_quality[static_cast<std::size_t>(c)]))
                           : color;
    for_each_drawn_face(mesh, c, [&](const std::array<Index, 4>& v, int size) {
      const auto base = static_cast<std::uint32_t>(set.positions.size());
      Vec3 newell{};
      for (int i = 0; i < size; ++i)
        newell = newell + cross(mesh.points[static_cast<std::size_t>(v[static_cast<std::size_t>(i)])],
                                mesh.points[static_cast<std::size_t>(v[static_cast<std::size_t>((i + 1) % size)])]);
      const Vec3f normal = to_vec3f(norm(newell) > 0.0 ? normalized(newell) : Vec3{0.0, 0.0, 1.0});
      for (int i = 0; i < size; ++i) {
        set.positions.push_back(to_vec3f(mesh.points[static_cast<std::size_t>(v[static_cast<std::size_t>(i)])] - origin));
        set.colors.push_back(fill);
        if (one_normal_a_face) set.normals.push_back(normal);
      }
      if (size == 3) set.indices.insert(set.indices.end(), {base, base + 1, base + 2});
      else if (splits_at_1_3(mesh, v))  // a concave quad: 0-2 runs outside it
        set.indices.insert(set.indices.end(), {base + 1, base + 2, base + 3, base + 1, base + 3, base});
      else
        set.indices.insert(set.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    });
  }
  return set;
}

// A set of ids below a fixed bound, marked in a table of that size and
// read back ascending: the distinct members without sorting the repeats.
class IdSet {
 public:
  explicit IdSet(std::size_t universe) : seen_(universe, 0) {}
  // Whether id was new.
  bool add(Index id) {
    const auto i = static_cast<std::size_t>(id);
    if (seen_[i]) return false;
    seen_[i] = 1;
    first_ = std::min(first_, i);
    last_ = std::max(last_, i + 1);
    return true;
  }
  std::vector<Index> ascending() const {
    std::vector<Index> out;
    for (std::size_t i = first_; i < last_; ++i)
      if (seen_[i]) out.push_back(static_cast<Index>(i));
    return out;
  }

 private:
  std::vector<char> seen_;
  std::size_t first_ = std::numeric_limits<std::size_t>::max(), last_ = 0;
};

// The points of the cells' distinct vertices: what their bounding box and a
// camera framing them need (a vertex shared by eight cells counts once).
std::vector<Vec3> cell_points(const HexMesh& mesh, const std::vector<Index>& cells) {
  IdSet vertices(mesh.points.size());
  std::vector<Vec3> points;
  for (Index c : cells) {
    const CellRef cell = any_cell(mesh, c);
    for (int i = 0; i < cell.num_corners; ++i) {
      const Index v = cell.corners[static_cast<std::size_t>(i)];
      if (vertices.add(v)) points.push_back(mesh.points[static_cast<std::size_t>(v)]);
    }
  }
  return points;
}

struct Figure {
  AnnotationStyle style;
  FigureLayout layout;
  double aspect = 1.0;
};

// The detail views' legend: the quality colour bar, its title ending with
// the kinds of the cells drawn (`kinds`, cell_kinds_legend) when not empty.
// The ring's edge colour of each kind in view D: cell_kind_edge_color (view A's).
Rgba8 ring_edge_color(CellKind kind) { return cell_kind_edge_color(kind); }

// kind_swatches: one swatch per kind named in `kinds`' last line, in its ring edge
// colour (view D, whose ring edges are coloured by kind).
// corner_discs: view D's heading (each disc one cell corner's value, not
// the vertex's min: 46t review).
// extra: the figure's own marks (view C's edges, fills and ring; view D's
// fills and dot), after the others.
ColorBar detail_color_bar(const std::string& kinds, bool kind_swatches = false, bool corner_discs = false,
                          std::span<const ColorBarSwatch> extra = {}) {
  ColorBar bar = quality_color_bar();
  if (corner_discs) bar.label = kLocalBarHeading;
  if (!kinds.empty()) bar.label += "\n" + kinds;
  if (kind_swatches)
    for (const auto& [color, text] : cell_kind_swatches(std::string_view(kinds).substr(kinds.rfind('\n') + 1))) {
      const std::string name = text.substr(text.find(' ') + 1);
      CellKind kind = CellKind::hex;
      for (CellKind k : kCellKinds)
        if (cell_kind_name(k) == name) kind = k;
      bar.swatches.push_back({to_color(ring_edge_color(kind)), name + " edges"});
    }
  bar.swatches.insert(bar.swatches.end(), extra.begin(), extra.end());
  return bar;
}

Figure detail_figure(const DetailViewOptions& options, const std::string& kinds = {}, bool kind_swatches = false,
                     bool corner_discs = false, std::span<const ColorBarSwatch> extra = {}) {
  Figure f;
  f.style = annotation_style_for(options.height);
  f.style.background = options.background;
  f.layout = figure_layout(options.width, options.height, !options.title.empty(),
                           color_bar_width(detail_color_bar(kinds, kind_swatches, corner_discs, extra), f.style), f.style);
  f.aspect = static_cast<double>(std::max(1, f.layout.view.width)) / std::max(1, f.layout.view.height);
  return f;
}

Image compose(const DetailViewOptions& options, const Figure& f, const Image& view, const std::string& kinds = {},
              bool kind_swatches = false, std::span<const ColorBarSwatch> extra = {}) {
  Image figure = make_image(options.width, options.height, options.background);
  paste(figure, view, f.layout.view.x, f.layout.view.y);
  draw_title(figure, f.layout.title, options.title, f.style);
  draw_color_bar(figure, f.layout.legend, detail_color_bar(kinds, kind_swatches, false, extra), f.style);
  return figure;
}

bool has_non_hex_cells(const HexMesh& mesh) {
  return !mesh.tets.empty() || !mesh.wedges.empty() || !mesh.pyramids.empty();
}

}  // namespace

namespace {

// vertex -> the tets, wedges and pyramids using it (cell ids over all
// blocks, ascending), as CSR; empty for a mesh of hexes only.
struct NonHexIncidence {
  std::vector<Index> offsets, cells;
  std::span<const Index> of(Index v) const {
    if (offsets.empty()) return {};
    return {cells.data() + offsets[static_cast<std::size_t>(v)], cells.data() + offsets[static_cast<std::size_t>(v) + 1]};
  }
};

NonHexIncidence non_hex_incidence(const HexMesh& mesh) {
  NonHexIncidence out;
  const Index first = mesh.num_hexes(), end = static_cast<Index>(num_cells(mesh));
  if (first == end) return out;
  out.offsets.assign(mesh.points.size() + 1, 0);
  for (Index c = first; c < end; ++c) {
    const CellRef cell = any_cell(mesh, c);
    for (int i = 0; i < cell.num_corners; ++i) ++out.offsets[static_cast<std::size_t>(cell.corners[static_cast<std::size_t>(i)]) + 1];
  }
  for (std::size_t v = 0; v < mesh.points.size(); ++v) out.offsets[v + 1] += out.offsets[v];
  out.cells.resize(static_cast<std::size_t>(out.offsets.back()));
  std::vector<Index> next(out.offsets.begin(), out.offsets.end() - 1);
  for (Index c = first; c < end; ++c) {
    const CellRef cell = any_cell(mesh, c);
    for (int i = 0; i < cell.num_corners; ++i)
      out.cells[static_cast<std::size_t>(next[static_cast<std::size_t>(cell.corners[static_cast<std::size_t>(i)])]++)] = c;
  }
  return out;
}

// The cells using the given vertices, every kind, ascending.
ClusterRegion region_of(const HexMesh& mesh, const Topology& topology, const NonHexIncidence& others,
                        std::span<const Index> vertices) {
  IdSet cells(static_cast<std::size_t>(num_cells(mesh)));
  for (Index v : vertices) {
    for (Index h : topology.hexes_of(v)) cells.add(h);
    for (Index c : others.of(v)) cells.add(c);
  }
  return {cells.ascending()};
}

std::span<const Index> cluster_members(const GlyphResult& glyphs, Index cluster) {
  if (cluster < 0 || static_cast<std::size_t>(cluster) + 1 >= glyphs.cluster_offsets.size()) return {};
  return {glyphs.cluster_vertices.data() + glyphs.cluster_offsets[static_cast<std::size_t>(cluster)],
          glyphs.cluster_vertices.data() + glyphs.cluster_offsets[static_cast<std::size_t>(cluster) + 1]};
}

}  // namespace

ClusterRegion cluster_region(const Topology& topology, const GlyphResult& glyphs, Index cluster) {
  ClusterRegion region;
  if (cluster < 0 || static_cast<std::size_t>(cluster) + 1 >= glyphs.cluster_offsets.size()) return region;
  IdSet cells(topology.hex_faces.size() / 6);
  for (Index v : cluster_members(glyphs, cluster))
    for (Index h : topology.hexes_of(v)) cells.add(h);
  region.cells = cells.ascending();
  return region;
}

ClusterRegion cluster_region(const HexMesh& mesh, const Topology& topology, const GlyphResult& glyphs, Index cluster) {
  return region_of(mesh, topology, non_hex_incidence(mesh), cluster_members(glyphs, cluster));
}

namespace {

// Neighbours: the cells (every kind) sharing a vertex with a cluster cell
// (the cells among them), ascending.
std::vector<Index> neighbour_cells(const HexMesh& mesh, const Topology& topology, const std::vector<Index>& cells) {
  const NonHexIncidence others = non_hex_incidence(mesh);
  IdSet vertices(mesh.points.size());
  std::vector<Index> distinct;
  for (Index c : cells) {
    const CellRef cell = any_cell(mesh, c);
    for (int i = 0; i < cell.num_corners; ++i)
      if (vertices.add(cell.corners[static_cast<std::size_t>(i)])) distinct.push_back(cell.corners[static_cast<std::size_t>(i)]);
  }
  return region_of(mesh, topology, others, distinct).cells;
}

// The shortest nonzero and the summed length of a line set's segments
// (each segment its own two positions, as cell_edges makes them).
std::pair<double, double> edge_lengths(const LineSet& lines) {
  double sum = 0.0, shortest = HUGE_VAL;
  for (std::size_t i = 0; i + 1 < lines.positions.size(); i += 2) {
    const Vec3f& a = lines.positions[i];
    const Vec3f& b = lines.positions[i + 1];
    const double length = std::hypot(double(a.x) - b.x, double(a.y) - b.y, double(a.z) - b.z);
    sum += length;
    if (length > 0.0) shortest = std::min(shortest, length);
  }
  return {shortest, sum};
}
double shortest_edge(const LineSet& lines) { return edge_lengths(lines).first; }

// A cluster's colour in view A (by tie class: glyph_colour_slots; by rank
// when the clusters are not listed): its edges' in view C.
Rgba8 cluster_edge_color(const GlyphResult& glyphs, Index cluster) {
  const std::vector<Index> slots =
      glyph_colour_slots(glyphs.clusters, static_cast<Index>(labelled_cluster_count(glyphs.options.top_clusters)));
  const Index slot = static_cast<std::size_t>(cluster) < slots.size() ? slots[static_cast<std::size_t>(cluster)] : cluster;
  return to_rgba8(cluster_color(slot, glyphs.options.top_clusters));
}

// View C's scene for the cluster's cells and the points of their distinct
// vertices (cell_points), both made once by the caller. With cell_quality
// (a surface mesh) the cluster's faces are filled by it (triangles[0]) and
// only the neighbours' faces are pale.
Scene cluster_scene(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                    const GlyphResult& glyphs, Index cluster, const std::vector<Index>& cells,
                    const std::vector<Vec3>& cell_vertex_points, std::span<const double> cell_quality = {}) {
  const std::vector<Index> neighbours = neighbour_cells(mesh, topology, cells);
  std::vector<Index> only_neighbours;
  std::set_difference(neighbours.begin(), neighbours.end(), cells.begin(), cells.end(),
                      std::back_inserter(only_neighbours));

  Scene scene;
  scene.origin = centre_of(cell_vertex_points);
  scene.lines.push_back(cell_edges(mesh, topology, only_neighbours, scene.origin, kNeighbourEdgeColor, 1.0f));
  scene.lines.push_back(cell_edges(mesh, topology, cells, scene.origin, cluster_edge_color(glyphs, cluster), 2.0f));
  const LineSet& own = scene.lines.back();
  const auto [shortest, edge_sum] = edge_lengths(own);
  // On a surface mesh the faces are the subject: a glyph keeps within the
  // shortest edge's fraction (a sliver's glyph hid the sliver), but not
  // below kClusterGlyphMinEdgeFraction of the mean edge (a dot).
  const double mean_edge = edge_sum / static_cast<double>(std::max<std::size_t>(1, own.positions.size() / 2));
  const double max_radius =
      own.positions.empty()  ? HUGE_VAL
      : cell_quality.empty() ? kClusterGlyphMaxEdgeFraction * mean_edge
                             : std::max(kClusterGlyphMaxEdgeFraction * shortest, kClusterGlyphMinEdgeFraction * mean_edge);
  // Size is severity, as in view A: every glyph scaled by one factor (their
  // radii keep their ratios, 1 - quality), the largest at most max_radius
  // (each capped alone, a fold's inverted glyphs were all one size: 47g
  // review #3).
  const std::span<const Index> members = cluster_members(glyphs, cluster);
  double largest = 0.0;
  for (Index v : members) largest = std::max(largest, glyphs.vertex_radius[static_cast<std::size_t>(v)]);
  const double factor = largest > 0.0 ? std::min(kClusterGlyphScale, max_radius / largest) : kClusterGlyphScale;
  // The worst member first (lowest quality, ties the smallest id): the one
  // cluster_shot rings.
  std::vector<Index> drawn;
  for (Index v : members)
    if (glyphs.vertex_radius[static_cast<std::size_t>(v)] > 0.0) drawn.push_back(v);
  const auto worst = std::min_element(drawn.begin(), drawn.end(), [&](Index a, Index b) {
    return vertex_quality[static_cast<std::size_t>(a)] < vertex_quality[static_cast<std::size_t>(b)];
  });
  if (worst != drawn.end()) std::rotate(drawn.begin(), worst, worst + 1);
  SphereSet spheres;
  for (Index member : drawn) {
    const auto v = static_cast<std::size_t>(member);
    spheres.centers.push_back(to_vec3f(mesh.points[v] - scene.origin));
    spheres.radii.push_back(static_cast<float>(factor * glyphs.vertex_radius[v]));
    spheres.colors.push_back(to_rgba8(quality_color(vertex_quality[v])));
  }
  scene.spheres.push_back(std::move(spheres));
  if (!cell_quality.empty()) {
    // The inverted faces in a set of their own (triangles[1]), which
    // cluster_shot lifts over the others on a plane.
    std::vector<Index> inverted, rest;
    for (Index c : cells)
      (static_cast<std::size_t>(c) < cell_quality.size() && cell_quality[static_cast<std::size_t>(c)] < 0.0 ? inverted
                                                                                                          : rest)
          .push_back(c);
    // Lit as view A's face fill (kSurfaceFillAmbient): a face's shade stays
    // near its colour on the bar (47g review #5: a quarter's ambient darkened
    // a khaki face off the bar).
    for (const std::vector<Index>* set : {&rest, &inverted}) {
      scene.triangles.push_back(outer_faces(mesh, topology, *set, scene.origin, kRegionFaceColor, cell_quality));
      scene.triangles.back().ambient = kSurfaceFillAmbient;
    }
  }
  scene.translucent.push_back(
      outer_faces(mesh, topology, cell_quality.empty() ? neighbours : only_neighbours, scene.origin, kRegionFaceColor));
  return scene;
}

}  // namespace

Scene build_cluster_scene(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                          const GlyphResult& glyphs, Index cluster) {
  const ClusterRegion region = cluster_region(mesh, topology, glyphs, cluster);
  return cluster_scene(mesh, topology, vertex_quality, glyphs, cluster, region.cells, cell_points(mesh, region.cells));
}

namespace {

// An annulus from radius r0 to r1 about c (relative to the scene's origin)
// in the plane facing the camera (screen axes right and up), unlit.
void append_annulus(TriangleSet& set, const Vec3& c, double r0, double r1, const ScreenAxes& axes, Rgba8 color) {
  constexpr int kSegments = 64;
  const auto base = static_cast<std::uint32_t>(set.positions.size());
  for (int k = 0; k < kSegments; ++k) {
    const double a = 2.0 * 3.14159265358979323846 * k / kSegments;
    const Vec3 u = std::cos(a) * axes.right + std::sin(a) * axes.up;
    set.positions.push_back(to_vec3f(c + r0 * u));
    set.positions.push_back(to_vec3f(c + r1 * u));
    set.colors.insert(set.colors.end(), 2, color);
  }
  for (std::uint32_t k = 0; k < kSegments; ++k) {
    const std::uint32_t i = base + 2 * k, j = base + 2 * ((k + 1) % kSegments);
    set.indices.insert(set.indices.end(), {i, i + 1, j + 1, i, j + 1, j});
  }
}

// An inset (DetailInset, no scene yet) for a view seen by `camera` in
// `view`, zoomed `zoom` times on `at`, in the corner of the view whose rect
// holds neither `at` nor any of `keep_clear` (screen rects) and the fewest
// of `points` on screen (none when every corner is taken).
std::optional<DetailInset> place_inset(const Camera& camera, const PixelRect& view, const Vec3& at, double zoom,
                                       std::span<const Vec3> points, std::span<const PixelRect> keep_clear) {
  const double pixels_per_unit = view.height / camera.ortho_height;
  DetailInset inset;
  inset.rect = {0, 0, static_cast<int>(kInsetShare * view.width), static_cast<int>(kInsetShare * view.height)};
  inset.zoom = zoom;
  inset.camera = camera;
  // Moved across the view only, so every point keeps its depth between the
  // view's near and far planes (47i review #1: moved along it too, to `at`'s
  // depth, a tilted planar ring, whose depths span a sliver of [near, far],
  // fell behind the far plane and the inset came out blank white).
  const Vec3 ahead = normalized(camera.target - camera.eye);
  const Vec3 across = (at - camera.target) - dot(at - camera.target, ahead) * ahead;
  inset.camera.eye = camera.eye + across;
  inset.camera.target = camera.target + across;
  inset.camera.ortho_height = inset.rect.height / (pixels_per_unit * inset.zoom);
  const double aspect = static_cast<double>(view.width) / view.height;
  const auto screen = [&](const Vec3& q) {
    const Vec3 ndc = project_to_ndc(camera, aspect, q);
    return std::array<double, 2>{view.x + 0.5 * (ndc.x + 1.0) * view.width, view.y + 0.5 * (1.0 - ndc.y) * view.height};
  };
  const auto [ax, ay] = screen(at);
  std::size_t fewest = std::numeric_limits<std::size_t>::max();
  for (int corner = 0; corner < 4; ++corner) {
    const int x = corner % 2 == 0 ? view.x : view.x + view.width - inset.rect.width;
    const int y = corner < 2 ? view.y : view.y + view.height - inset.rect.height;
    const PixelRect rect{x, y, inset.rect.width, inset.rect.height};
    const auto holds = [&](double px, double py) {
      return px >= x && px <= x + rect.width && py >= y && py <= y + rect.height;
    };
    if (holds(ax, ay) || std::any_of(keep_clear.begin(), keep_clear.end(),
                                     [&](const PixelRect& r) { return boxes_overlap(r, rect); }))
      continue;
    std::size_t n = 0;
    for (const Vec3& q : points) {
      const auto [px, py] = screen(q);
      n += holds(px, py);
    }
    if (n < fewest) fewest = n, inset.rect.x = x, inset.rect.y = y;
  }
  if (fewest == std::numeric_limits<std::size_t>::max()) return std::nullopt;
  // The area it shows, boxed in the view.
  const int box_w = static_cast<int>(std::lround(inset.rect.width / inset.zoom)),
            box_h = static_cast<int>(std::lround(inset.rect.height / inset.zoom));
  inset.box = {static_cast<int>(std::lround(ax)) - box_w / 2, static_cast<int>(std::lround(ay)) - box_h / 2, box_w, box_h};
  // Inside the view (47i review #1: about a vertex near the view's bottom it
  // ran off the picture), the inset moved with it: it shows what the box holds.
  const int dx = std::clamp(inset.box.x, view.x, std::max(view.x, view.x + view.width - box_w)) - inset.box.x,
            dy = std::clamp(inset.box.y, view.y, std::max(view.y, view.y + view.height - box_h)) - inset.box.y;
  inset.box.x += dx, inset.box.y += dy;
  const auto [right, up] = screen_axes(camera);
  const Vec3 move = (dx / pixels_per_unit) * right - (dy / pixels_per_unit) * up;
  inset.camera.eye = inset.camera.eye + move;
  inset.camera.target = inset.camera.target + move;
  return inset;
}

// A frame about a rect in kInsetColor (an inset's, or the area it shows).
void frame_rect(Image& figure, const PixelRect& p, const AnnotationStyle& style) {
  const double w = std::max(2.0, 2.0 * style.scale);
  draw_line(figure, p.x, p.y, p.x + p.width, p.y, kInsetColor, w);
  draw_line(figure, p.x + p.width, p.y, p.x + p.width, p.y + p.height, kInsetColor, w);
  draw_line(figure, p.x + p.width, p.y + p.height, p.x, p.y + p.height, kInsetColor, w);
  draw_line(figure, p.x, p.y + p.height, p.x, p.y, kInsetColor, w);
}

// Draws the inset over the figure: its scene framed in its rect, labelled
// `inset: xN at <at_what>` (the area it shows boxed first: frame_rect of
// inset.box, under any labels).
void draw_inset(Image& figure, const DetailInset& inset, Renderer& renderer, const AnnotationStyle& style,
                Rgba8 background, const char* at_what) {
  const Image view = renderer.render(inset.scene, inset.camera, inset.rect.width, inset.rect.height);
  paste(figure, view, inset.rect.x, inset.rect.y);
  frame_rect(figure, inset.rect, style);
  AnnotationStyle label = style;
  label.text_color = kInsetColor;
  const int size = std::max(11, static_cast<int>(std::lround(20 * style.scale)));
  char text[64];
  std::snprintf(text, sizeof text, "inset: x%.0f at %s", inset.zoom, at_what);
  const PixelRect extent = text_extent(text, size, style);
  fill_rect(figure, {inset.rect.x + 4, inset.rect.y + 4, extent.width + 8, size + 8}, background);
  draw_text(figure, inset.rect.x + 8, inset.rect.y + 4 + size, text, size, label);
}

// The ring about the first glyph of `spheres` (the worst vertex's) as view
// A rings its worst: a pale halo, the yellow band (kWorstBandColor), a dark
// ring, a pale halo, in pixels of a view `height` pixels high.
TriangleSet worst_ring(const SphereSet& spheres, const Camera& camera, int height, const AnnotationStyle& style) {
  TriangleSet marks;
  marks.is_lit = false;
  const double pixel = camera.ortho_height / std::max(1, height), s = style.scale;
  const Vec3 c{spheres.centers.at(0).x, spheres.centers[0].y, spheres.centers[0].z};
  const double r = spheres.radii[0], a = r + 0.5 * pixel, b = r + 1.5 * s * pixel, d = r + 5.0 * s * pixel,
               e = r + 7.5 * s * pixel, g = r + 9.0 * s * pixel;
  const ScreenAxes axes = screen_axes(camera);
  append_annulus(marks, c, a, b, axes, style.background);
  append_annulus(marks, c, b, d, axes, kWorstBandColor);
  append_annulus(marks, c, d, e, axes, style.text_color);
  append_annulus(marks, c, e, g, axes, style.background);
  return marks;
}

// View C of a surface mesh, once its camera is set (47g review #3, #4, #6,
// #8): the cluster's edges lifted towards the eye by the largest glyph's
// radius, so they are drawn over the glyphs (the vertex where a fold's edges
// meet stays in sight) and over a folded surface crossing itself (a fill
// boundary with no line); the worst vertex's glyph (the sphere set's first)
// ringed as view A rings its worst (a pale halo, kWorstBandColor, a dark
// ring); and a legend entry for each of these marks and for the neighbours.
void surface_cluster_marks(ClusterShot& shot, const Figure& f, const std::vector<Vec3>& points, double shortest) {
  const SphereSet& spheres = shot.scene.spheres.at(0);
  const double largest = spheres.radii.empty() ? 0.0 : *std::max_element(spheres.radii.begin(), spheres.radii.end());
  const Vec3 look = normalized(shot.camera.target - shot.camera.eye);
  const double lift = kClusterEdgeLift * largest;
  for (Vec3f& p : shot.scene.lines.at(1).positions) p = to_vec3f(Vec3{p.x, p.y, p.z} - lift * look);
  // The eye backs off by as much (the camera framed the glyphs' extremes:
  // the lifted edges lay before its near plane, clipped).
  shot.camera.eye = shot.camera.eye - lift * look;
  shot.camera.far_plane += lift;
  if (!spheres.centers.empty())
    shot.scene.overlay.push_back(worst_ring(spheres, shot.camera, f.layout.view.height, f.style));
  // A cluster of slivers (its shortest edge a few pixels): an inset zoomed
  // on the worst vertex, its shortest edge kInsetEdgePixels long there (47g
  // review #5: Dolphin_padded's strip of slivers was a 60-150 px band, its
  // three glyphs one blob).
  const double pixels_per_unit = f.layout.view.height / shot.camera.ortho_height;
  if (spheres.centers.empty() || !(shortest > 0.0) ||
      shortest * pixels_per_unit >= kInsetBelowPixels * f.style.scale)
    return;
  const Vec3 worst = shot.scene.origin + Vec3{spheres.centers[0].x, spheres.centers[0].y, spheres.centers[0].z};
  std::optional<DetailInset> inset = place_inset(shot.camera, f.layout.view, worst,
                                                 kInsetEdgePixels * f.style.scale / (shortest * pixels_per_unit), points, {});
  if (!inset) return;
  // Its glyphs at most 0.35 of the shortest edge (no floor: there the
  // sliver is the subject), its ring in its own pixels.
  inset->scene = shot.scene;
  const double glyph_scale = std::min(1.0, kClusterGlyphMaxEdgeFraction * shortest / largest);
  for (float& r : inset->scene.spheres.at(0).radii) r = static_cast<float>(r * glyph_scale);
  inset->scene.overlay = {worst_ring(inset->scene.spheres[0], inset->camera, inset->rect.height, f.style)};
  shot.inset = std::move(inset);
  shot.swatches.push_back({to_color(kInsetColor), "box: zoomed in the inset", SwatchShape::line});
}

// View C's legend entries on a surface mesh, one per mark (47g review #8):
// the cluster's edges in its colour, the worst vertex's ring, the
// neighbours' pale faces (kRegionFaceColor over the background) and edges.
std::vector<ColorBarSwatch> surface_cluster_swatches(const GlyphResult& glyphs, Index cluster,
                                                     const AnnotationStyle& style) {
  const Rgba8 pale = blend_over(kRegionFaceColor, style.background);
  return {{to_color(cluster_edge_color(glyphs, cluster)), "the cluster's edges", SwatchShape::thick_line},
          {to_color(style.text_color), "ring: its worst vertex", SwatchShape::solid_ring, std::nullopt, kWorstBandColor},
          {to_color(pale), "neighbour faces", SwatchShape::box},
          {to_color(kNeighbourEdgeColor), "neighbour edges", SwatchShape::line}};
}

}  // namespace

ClusterShot cluster_shot(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                         const GlyphResult& glyphs, Index cluster, const DetailViewOptions& options) {
  const ClusterRegion region = cluster_region(mesh, topology, glyphs, cluster);
  ClusterShot shot;
  if (has_non_hex_cells(mesh)) shot.cell_kinds = cell_kinds_legend(mesh, region.cells);
  if (!options.cell_quality.empty())
    shot.cell_kinds = std::string(kClusterFaceFillLegend) + "\n" + kClusterSphereLegend + "\n" +
                      cell_kinds_legend(mesh, region.cells);
  if (!options.cell_quality.empty())
    shot.swatches = surface_cluster_swatches(glyphs, cluster, annotation_style_for(options.height));
  const Figure f = detail_figure(options, shot.cell_kinds, false, false, shot.swatches);
  // The camera frames the cells' vertices and the extremes of every glyph.
  std::vector<Vec3> points = cell_points(mesh, region.cells);
  shot.scene = cluster_scene(mesh, topology, vertex_quality, glyphs, cluster, region.cells, points, options.cell_quality);
  std::vector<Vec3> centers;
  std::vector<double> radii;
  const SphereSet& s = shot.scene.spheres[0];
  for (std::size_t i = 0; i < s.centers.size(); ++i) {
    const Vec3 c = shot.scene.origin + Vec3{s.centers[i].x, s.centers[i].y, s.centers[i].z};
    centers.push_back(c);
    radii.push_back(s.radii[i]);
    for (int axis = 0; axis < 3; ++axis)
      for (double sign : {-1.0, 1.0}) {
        Vec3 p = c;
        (axis == 0 ? p.x : axis == 1 ? p.y : p.z) += sign * s.radii[i];
        points.push_back(p);
      }
  }
  // A planar surface along its normal; a curved one as view D sees its
  // ring (its faces in depth, none edge-on, upright); cells from where the
  // glyphs show most.
  const std::vector<Vec3> direction =
      options.view_direction ? std::vector<Vec3>{*options.view_direction}
      : !options.cell_quality.empty()
          ? std::vector<Vec3>{choose_local_viewpoint(local_face_areas(mesh, region.cells, kNoIndex), points, centers,
                                                     radii, f.aspect, options.up)}
          : choose_viewpoints(points, centers, radii, f.aspect, 1, options.up);
  shot.camera = fit_camera_to_points(points, direction.at(0), f.aspect, {.up = options.up, .is_perspective = false});
  // A plane hides nothing: where a fold stacks faces, the inverted ones
  // lie over the others, and every edge over the faces (kPlanarLift of the
  // frame's diagonal towards the eye, twice that for the edges).
  if (options.view_direction && shot.scene.triangles.size() == 2) {
    const Box3 box = bounding_box(points);
    const Vec3 towards_eye = (-kPlanarLift * norm(box.hi - box.lo)) * normalized(*options.view_direction);
    const auto lift = [](std::vector<Vec3f>& positions, const Vec3& by) {
      for (Vec3f& p : positions) p = to_vec3f(Vec3{p.x, p.y, p.z} + by);
    };
    lift(shot.scene.triangles[1].positions, towards_eye);
    for (LineSet& lines : shot.scene.lines) lift(lines.positions, 2.0 * towards_eye);
  }
  if (!options.cell_quality.empty()) surface_cluster_marks(shot, f, points, shortest_edge(shot.scene.lines.at(1)));
  return shot;
}

Image render_cluster_shot(const ClusterShot& shot, const DetailViewOptions& options, Renderer& renderer) {
  const Figure f = detail_figure(options, shot.cell_kinds, false, false, shot.swatches);
  Image figure = compose(options, f, renderer.render(shot.scene, shot.camera, f.layout.view.width, f.layout.view.height),
                         shot.cell_kinds, false, shot.swatches);
  if (shot.inset) {
    frame_rect(figure, shot.inset->box, f.style);
    draw_inset(figure, *shot.inset, renderer, f.style, options.background, "the worst vertex");
  }
  return figure;
}

Image render_cluster_view(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                          const GlyphResult& glyphs, Index cluster, const DetailViewOptions& options,
                          Renderer& renderer) {
  return render_cluster_shot(cluster_shot(mesh, topology, vertex_quality, glyphs, cluster, options), options, renderer);
}

namespace {

// The corner scaled Jacobians of a non-hex volume cell (the quality
// kernels' per-corner functions, cell_corner_jacobian.h), NaN where a corner
// has no value (the pyramid's apex). A surface cell's are read from
// corner_values (QualityField's layout): signed against the plane or its
// neighbours' orientation, which its own corners cannot tell.
std::array<double, 8> non_hex_corner_values(const HexMesh& mesh, const CellRef& cell,
                                            std::span<const double> corner_values) {
  std::array<double, 8> out;
  out.fill(std::nan(""));
  if (cell_kind_dimension(cell.kind) == 2) {
    std::size_t first = 0, per_cell = 0;
    for_each_cell_kind([&](auto kind) {
      if (kind() < cell.kind) first += kCornerValuesPerCell<kind()> * cell_block<kind()>(mesh).size();
      if (kind() == cell.kind) per_cell = kCornerValuesPerCell<kind()>;
    });
    first += per_cell * cell.index;
    for (std::size_t i = 0; i < per_cell && first + i < corner_values.size(); ++i) out[i] = corner_values[first + i];
    return out;
  }
  const auto at = [&](int i) { return mesh.points[static_cast<std::size_t>(cell.corners[static_cast<std::size_t>(i)])]; };
  const auto copy = [&](const auto& values) {
    for (std::size_t i = 0; i < values.value.size(); ++i) out[i] = values.value[i];
  };
  if (cell.kind == CellKind::tet) copy(tet_corner_scaled_jacobians({at(0), at(1), at(2), at(3)}));
  else if (cell.kind == CellKind::wedge) copy(wedge_corner_scaled_jacobians({at(0), at(1), at(2), at(3), at(4), at(5)}));
  else if (cell.kind == CellKind::pyramid) copy(pyramid_corner_scaled_jacobians({at(0), at(1), at(2), at(3), at(4)}));
  return out;
}

}  // namespace

std::vector<Index> non_hex_cells_of(const HexMesh& mesh, Index v) {
  std::vector<Index> cells;
  const std::array<Index, 5> start = volume_block_starts(mesh);
  const auto scan = [&](const auto& block, Index first) {
    for (std::size_t i = 0; i < block.size(); ++i)
      if (std::find(block[i].begin(), block[i].end(), v) != block[i].end()) cells.push_back(first + static_cast<Index>(i));
  };
  scan(mesh.tets, start[1]);
  scan(mesh.wedges, start[2]);
  scan(mesh.pyramids, start[3]);
  scan(mesh.quads, start[4]);
  scan(mesh.triangles, start[4] + static_cast<Index>(mesh.quads.size()));
  return cells;
}

std::vector<VertexCorner> vertex_corners(const HexMesh& mesh, const Topology& topology,
                                         std::span<const double> corner_values, Index v) {
  std::vector<VertexCorner> corners;
  if (v < 0 || static_cast<std::size_t>(v) + 1 >= topology.vertex_hex_offsets.size()) return corners;
  // By hex, then corner: the vertex's hexes are ascending.
  for (Index h : topology.hexes_of(v)) {
    const Hex& hex = mesh.hexes[static_cast<std::size_t>(h)];
    for (int i = 0; i < 8; ++i)
      if (hex[i] == v)
        corners.push_back({h, i, corner_values[8 * static_cast<std::size_t>(h) + static_cast<std::size_t>(i)]});
  }
  // Then the tets, wedges and pyramids, or a surface mesh's quads and
  // triangles (ascending cell id); a pyramid's apex has no corner value and
  // no entry.
  for (Index id : non_hex_cells_of(mesh, v)) {
    const CellRef cell = any_cell(mesh, id);
    const std::array<double, 8> values = non_hex_corner_values(mesh, cell, corner_values);
    for (int i = 0; i < cell.num_corners; ++i)
      if (cell.corners[static_cast<std::size_t>(i)] == v && !std::isnan(values[static_cast<std::size_t>(i)]))
        corners.push_back({id, i, values[static_cast<std::size_t>(i)], cell.kind});
  }
  return corners;
}

std::string cell_kinds_legend(const HexMesh& mesh, std::span<const Index> cells) {
  std::array<std::int64_t, kNumCellKinds> count{};
  const Index num_hexes = mesh.num_hexes();
  for (Index c : cells) ++count[static_cast<std::size_t>(c < num_hexes ? CellKind::hex : any_cell(mesh, c).kind)];
  return cell_kinds_text(count);
}

namespace {

Vec3 hex_centre(const HexMesh& mesh, Index h) {
  Vec3 c{};
  if (h < mesh.num_hexes()) {
    for (const Vec3& p : hex_corners(mesh, h)) c = c + p;
    return c / 8.0;
  }
  const CellRef cell = any_cell(mesh, h);
  for (int i = 0; i < cell.num_corners; ++i) c = c + mesh.points[static_cast<std::size_t>(cell.corners[static_cast<std::size_t>(i)])];
  return c / static_cast<double>(cell.num_corners);
}

double mean_edge_at(const HexMesh& mesh, const std::vector<VertexCorner>& corners, Index v) {
  double sum = 0.0;
  int n = 0;
  const Vec3& p = mesh.points[static_cast<std::size_t>(v)];
  for (const VertexCorner& c : corners) {
    sum += norm(hex_centre(mesh, c.hex) - p);
    ++n;
  }
  return n ? sum / n : 1.0;
}

// Where a surface cell's corner disc goes: inside its own face near its
// corner, along the bisector of the corner's two edges at kSurfaceDiscReach
// of the distance to the face's nearest other corner (a folded quad's far
// corner can be nearer than its edges' ends), halved until inside the face (even-odd, in the plane
// of its area vector: a folded quad's own region). 45% of the way to the
// face's centre put a folded quad's disc outside the face (47g review #2).
constexpr double kSurfaceDiscReach = 0.4;
constexpr int kSurfaceDiscHalvings = 6;

Vec3 surface_corner_anchor(const HexMesh& mesh, const VertexCorner& c) {
  const CellRef cell = any_cell(mesh, c.hex);
  const int n = cell.num_corners;
  const auto at = [&](int k) { return mesh.points[static_cast<std::size_t>(cell.corners[static_cast<std::size_t>((k + n) % n)])]; };
  const Vec3 p = at(c.local), a = at(c.local - 1) - p, b = at(c.local + 1) - p;
  const Vec3 to_centre = 0.45 * (hex_centre(mesh, c.hex) - p);
  const double la = norm(a), lb = norm(b);
  Vec3 area{};  // Newell
  for (int k = 0; k < n; ++k) area = area + cross(at(k), at(k + 1));
  Vec3 bisector = a / la + b / lb;
  const double lm = norm(bisector);
  if (!(la > 0.0) || !(lb > 0.0) || !(lm > 1e-9) || !(norm(area) > 0.0)) return p + to_centre;
  if (dot(cross(b, a), area) < 0.0) bisector = -1.0 * bisector;  // a reflex corner: its face beyond
  const Vec3 normal = normalized(area), u = normalized(a - dot(a, normal) * normal), w = cross(normal, u);
  const auto inside = [&](const Vec3& q) {
    bool in = false;
    const double x = dot(q - p, u), y = dot(q - p, w);
    for (int k = 0; k < n; ++k) {
      const double x0 = dot(at(k) - p, u), y0 = dot(at(k) - p, w), x1 = dot(at(k + 1) - p, u), y1 = dot(at(k + 1) - p, w);
      if ((y0 > y) != (y1 > y) && x < x0 + (y - y0) / (y1 - y0) * (x1 - x0)) in = !in;
    }
    return in;
  };
  double nearest = std::min(la, lb);
  for (int k = 2; k < n - 1; ++k) nearest = std::min(nearest, norm(at(c.local + k) - p));
  double reach = kSurfaceDiscReach * nearest / lm;
  for (int i = 0; i < kSurfaceDiscHalvings; ++i, reach *= 0.5)
    if (inside(p + reach * bisector)) return p + reach * bisector;
  return p + to_centre;
}

}  // namespace

double local_marker_radius(double scaled_jacobian, double size) {
  // Size is severity, as in view A: (1 − SJ), at least a quarter (a good
  // corner stays visible), at most 2 (SJ = −1); NaN as a quarter.
  const double c = 1.0 - scaled_jacobian;
  return 0.1 * size * (c >= 0.25 ? std::min(c, 2.0) : 0.25);
}

std::vector<Index> local_ring(const HexMesh& mesh, const Topology& topology, Index v) {
  std::vector<Index> ring;
  if (v < 0 || static_cast<std::size_t>(v) + 1 >= topology.vertex_hex_offsets.size()) return ring;
  const std::span<const Index> hexes = topology.hexes_of(v);
  ring.assign(hexes.begin(), hexes.end());
  if (mesh.hexes.size() == static_cast<std::size_t>(num_cells(mesh))) return ring;
  const std::vector<Index> others = non_hex_cells_of(mesh, v);
  ring.insert(ring.end(), others.begin(), others.end());
  return ring;
}

Scene build_local_scene(const HexMesh& mesh, const Topology& topology, std::span<const double> corner_values, Index v) {
  const std::vector<VertexCorner> corners = vertex_corners(mesh, topology, corner_values, v);
  const std::vector<Index> ring = local_ring(mesh, topology, v);
  Scene scene;
  const Vec3& p = mesh.points.at(static_cast<std::size_t>(v));
  scene.origin = p;
  // The ring's edges by kind (one set per kind present; a pure-hex ring is one set).
  std::array<std::vector<Index>, kNumCellKinds> by_kind;
  for (Index c : ring)
    by_kind[static_cast<std::size_t>(c < mesh.num_hexes() ? CellKind::hex : any_cell(mesh, c).kind)].push_back(c);
  for (std::size_t k = 0; k < by_kind.size(); ++k)
    if (k == 0 || !by_kind[k].empty())
      scene.lines.push_back(
          cell_edges(mesh, topology, by_kind[k], scene.origin, ring_edge_color(static_cast<CellKind>(k)), 1.5f));
  const double size = mean_edge_at(mesh, corners, v);
  SphereSet markers, centre;
  for (const VertexCorner& c : corners) {
    const Vec3 at = c.kind == CellKind::quad || c.kind == CellKind::triangle ? surface_corner_anchor(mesh, c)
                                                                             : p + 0.45 * (hex_centre(mesh, c.hex) - p);
    markers.centers.push_back(to_vec3f(at - scene.origin));
    markers.radii.push_back(static_cast<float>(local_marker_radius(c.value, size)));
    markers.colors.push_back(to_rgba8(quality_color(c.value)));
  }
  centre.centers.push_back({0.0f, 0.0f, 0.0f});
  centre.radii.push_back(static_cast<float>(0.04 * size));
  centre.colors.push_back({255, 255, 255, 255});
  scene.spheres.push_back(std::move(markers));
  scene.spheres.push_back(std::move(centre));
  // All faces of the ring (shared ones twice is fine: pale and translucent).
  TriangleSet faces = outer_faces(mesh, topology, ring, scene.origin, kRegionFaceColor);
  scene.translucent.push_back(std::move(faces));
  return scene;
}

std::vector<Vec3> local_face_areas(const HexMesh& mesh, std::span<const Index> cells, Index v) {
  std::vector<std::array<Index, 4>> seen;
  std::vector<Vec3> areas;
  for (Index c : cells)
    for_each_drawn_face(mesh, c, [&](const std::array<Index, 4>& f, int size) {
      if (v != kNoIndex && std::find(f.begin(), f.begin() + size, v) == f.begin() + size) return;
      // The face's corners sorted; a triangle's fourth slot kNoIndex (first
      // after sorting): one key per face whatever its corner order. All four
      // slots sorted, a fixed length: GCC 12 warned of an out-of-bounds
      // branch (-Warray-bounds) in std::sort over a variable length <= 4.
      std::array<Index, 4> key = f;
      if (size == 3) key[3] = kNoIndex;
      std::sort(key.begin(), key.end());
      if (std::find(seen.begin(), seen.end(), key) != seen.end()) return;
      seen.push_back(key);
      const auto p = [&](int i) { return mesh.points[static_cast<std::size_t>(f[static_cast<std::size_t>(i)])]; };
      Vec3 area = 0.5 * cross(p(1) - p(0), p(2) - p(0));
      if (size == 4) area = area + 0.5 * cross(p(2) - p(0), p(3) - p(0));
      areas.push_back(area);
    });
  return areas;
}

LocalViewScore local_view_score(std::span<const Vec3> face_areas, const Vec3& direction) {
  const Vec3 d = normalized(direction);
  LocalViewScore score{0.0, 90.0};
  for (const Vec3& a : face_areas) {
    const double length = norm(a);
    if (!(length > 0.0)) continue;  // a degenerate face has no plane
    const double along = std::abs(dot(a, d));
    score.projected_area += along;
    score.min_face_angle =
        std::min(score.min_face_angle, std::asin(std::min(1.0, along / length)) * 180.0 / 3.14159265358979323846);
  }
  return score;
}

Vec3 choose_local_viewpoint(std::span<const Vec3> face_areas, std::span<const Vec3> points,
                            std::span<const Vec3> centers, std::span<const double> radii, double aspect,
                            const Vec3& up) {
  std::vector<Vec3> candidates;
  std::vector<LocalViewScore> scores;
  for (double elevation : kLocalViewElevations)
    for (double azimuth = 0.0; azimuth < 360.0 - 1e-9; azimuth += kLocalViewAzimuthStep) {
      candidates.push_back(upright_view_direction(up, azimuth, elevation));
      scores.push_back(local_view_score(face_areas, candidates.back()));
    }
  double best_angle = 0.0;
  for (const LocalViewScore& s : scores) best_angle = std::max(best_angle, s.min_face_angle);
  const double min_angle = std::min(kLocalMinFaceAngle, 0.75 * best_angle);
  double best_area = 0.0;
  for (const LocalViewScore& s : scores)
    if (s.min_face_angle >= min_angle) best_area = std::max(best_area, s.projected_area);
  Vec3 chosen = candidates.front();
  double best_cover = -1.0;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (scores[i].min_face_angle < min_angle || scores[i].projected_area < kLocalAreaShare * best_area) continue;
    // The discs' visible area in model units (choose_viewpoints' measure).
    const Camera camera = fit_camera_to_points(points, candidates[i], aspect, {.up = up, .is_perspective = false});
    const double cover = glyph_coverage(centers, radii, camera, aspect) * camera.ortho_height * camera.ortho_height * aspect;
    if (cover > best_cover * (1.0 + 1e-9)) {
      best_cover = cover;
      chosen = candidates[i];
    }
  }
  return chosen;
}

namespace {

// View D's legend entries for its own marks (47g review #8): the faces at
// the vertex (kRegionFaceColor once over the background, and twice where a
// fold stacks two of them: a surface mesh only, a volume's cells stack
// many), the discs' rims and the vertex's dot.
std::vector<ColorBarSwatch> local_swatches(const DetailViewOptions& options) {
  std::vector<ColorBarSwatch> out;
  if (!options.cell_quality.empty()) {
    const Rgba8 once = blend_over(kRegionFaceColor, options.background), twice = blend_over(kRegionFaceColor, once);
    out = {{to_color(once), "faces at the vertex"}, {to_color(twice), "two faces stacked (a fold)"}};
  }
  out.push_back({to_color(kLocalRimColor), "disc rim (1.12 x its disc)", SwatchShape::solid_ring});
  out.push_back({Color{0.0, 0.0, 0.0}, "the vertex", SwatchShape::solid_ring});
  return out;
}

}  // namespace

// The corner markers (the scene's first sphere set) as flat discs facing the
// camera, each on a dark rim, over everything (Scene::overlay): behind the
// ring's translucent faces a sphere's colour washed out towards grey, so a
// marker's colour disagreed with its value. The discs are stacked by value
// (issue 46, 46q review Q-M1): each lies in the plane through the vertex
// facing the camera, kStackStep of the mean edge nearer the camera per rank,
// the worst corner on top; the vertex itself (the scene's second sphere
// set) is a dark disc above them all, so the view's subject is never hidden.
std::vector<std::size_t> local_stack_order(std::span<const double> values) {
  std::vector<std::size_t> order(values.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto key = [&](std::size_t i) { return std::isnan(values[i]) ? 2.0 : values[i]; };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) > key(b); });
  std::reverse(order.begin(), order.end());
  return order;
}

double covered_share(const ScreenDisc& disc, std::span<const ScreenDisc> over) {
  constexpr int kSteps = 8;
  int samples = 0, covered = 0;
  for (int a = -kSteps; a <= kSteps; ++a)
    for (int b = -kSteps; b <= kSteps; ++b) {
      const double u = static_cast<double>(a) / kSteps, w = static_cast<double>(b) / kSteps;
      if (u * u + w * w > 1.0) continue;
      ++samples;
      const double x = disc.x + u * disc.radius, y = disc.y + w * disc.radius;
      for (const ScreenDisc& o : over)
        if (std::hypot(x - o.x, y - o.y) <= o.radius) {
          ++covered;
          break;
        }
    }
  return samples > 0 ? static_cast<double>(covered) / samples : 0.0;
}

std::vector<std::array<double, 2>> local_spider_moves(std::span<const ScreenDisc> discs,
                                                      std::span<const std::size_t> top_down, const ScreenDisc& dot) {
  std::vector<std::array<double, 2>> moves(discs.size(), {0.0, 0.0});
  std::vector<ScreenDisc> over{dot};
  for (std::size_t i : top_down) {
    if (i >= discs.size()) continue;
    ScreenDisc d = discs[i];
    if (covered_share(d, over) > kLocalMaxCoveredShare) {
      // Away from the dot (or from what covers it most), the nearest free spot.
      double ax = d.x - dot.x, ay = d.y - dot.y;
      if (std::hypot(ax, ay) < 1e-6) {
        ax = 0.0, ay = -1.0;
        for (const ScreenDisc& o : over)
          if (std::hypot(d.x - o.x, d.y - o.y) > 1e-6 && std::hypot(d.x - o.x, d.y - o.y) < o.radius + d.radius) {
            ax = d.x - o.x, ay = d.y - o.y;
            break;
          }
      }
      const double base = std::atan2(ay, ax);
      double best_share = 2.0;
      ScreenDisc best = d;
      for (int step = 1; step <= 20 && best_share > kLocalMaxCoveredShare; ++step)
        for (double turn : {0.0, 30.0, -30.0, 60.0, -60.0, 90.0, -90.0}) {
          const double a = base + turn * 3.14159265358979323846 / 180.0, t = 0.2 * step * d.radius;
          ScreenDisc c = d;
          c.x += t * std::cos(a), c.y += t * std::sin(a);
          const double share = covered_share(c, over);
          if (share < best_share - 1e-12) best_share = share, best = c;
          if (share <= kLocalMaxCoveredShare) break;
        }
      moves[i] = {best.x - d.x, best.y - d.y};
      d = best;
    }
    over.push_back(d);
  }
  return moves;
}

Scene local_marker_discs(const Scene& scene, const Camera& camera, const std::vector<double>& values, double size) {
  Scene out = scene;
  if (out.spheres.empty()) return out;
  const SphereSet markers = out.spheres[0];
  out.spheres[0] = SphereSet{};
  SphereSet vertex;
  if (out.spheres.size() > 1) std::swap(vertex, out.spheres[1]);
  const Vec3 d = normalized(camera.target - camera.eye);
  const auto [right, up] = screen_axes(camera);
  constexpr int kSegments = 32;
  TriangleSet discs;
  discs.is_lit = false;
  const auto disc = [&](const Vec3& c, double r, Rgba8 color) {
    const auto base = static_cast<std::uint32_t>(discs.positions.size());
    discs.positions.push_back(to_vec3f(c));
    discs.colors.push_back(color);
    for (int k = 0; k < kSegments; ++k) {
      const double a = 2.0 * 3.14159265358979323846 * k / kSegments;
      discs.positions.push_back(to_vec3f(c + r * (std::cos(a) * right + std::sin(a) * up)));
      discs.colors.push_back(color);
    }
    for (std::uint32_t k = 0; k < kSegments; ++k)
      discs.indices.insert(discs.indices.end(), {base, base + 1 + k, base + 1 + (k + 1) % kSegments});
  };
  // Best first (lowest in the stack): local_stack_order reversed.
  std::vector<double> keys(markers.centers.size(), std::nan(""));
  std::copy_n(values.begin(), std::min(values.size(), keys.size()), keys.begin());
  std::vector<std::size_t> order = local_stack_order(keys);
  std::reverse(order.begin(), order.end());
  const double step = kLocalStackStep * size;
  // The plane through the vertex (the scene's origin) facing the camera.
  const auto in_plane = [&](const Vec3f& c, double rank) {
    const Vec3 q{c.x, c.y, c.z};
    return q - dot(q, d) * d - (rank * step) * d;
  };
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t i = order[k];
    const double r = markers.radii[i];
    disc(in_plane(markers.centers[i], 2.0 * static_cast<double>(k) + 1.0), kLocalRimScale * r, kLocalRimColor);  // its rim just under it
    disc(in_plane(markers.centers[i], 2.0 * static_cast<double>(k) + 2.0), r, markers.colors[i]);
  }
  // The vertex: its colour (white) inside a black ring, the legend's
  // "the vertex" (no kind's edge colour: the 46r review read the dark dot
  // as a hex edge's end).
  for (std::size_t i = 0; i < vertex.centers.size(); ++i) {
    const double top = 2.0 * static_cast<double>(order.size()) + 2.0;
    disc(in_plane(vertex.centers[i], top), kLocalDiscScale * vertex.radii[i], Rgba8{0, 0, 0, 255});
    disc(in_plane(vertex.centers[i], top + 1.0), 0.55 * kLocalDiscScale * vertex.radii[i], vertex.colors[i]);
  }
  out.overlay.push_back(std::move(discs));
  return out;
}

// Whether shot.labels[i] (placed as set) keeps clear of the labels in
// `kept`: no box over another, its leader (at most max_leader long)
// through no other box, no other corner's disc, the vertex's dot or another
// leader, and no other leader through its box (46t review: leaders ran
// under other labels' boxes and through other discs).
bool local_label_clear(const LocalShot& shot, std::size_t i, std::span<const std::size_t> kept,
                       std::span<const ScreenDisc> markers, const ScreenDisc& dot, double max_leader) {
  const LocalLabel& a = shot.labels[i];
  const auto leader_of = [](const LocalLabel& l) {
    PlacedLabel p;
    p.box = l.box, p.has_leader = l.has_leader;
    p.leader_x0 = l.leader_x0, p.leader_y0 = l.leader_y0, p.leader_x1 = l.leader_x1, p.leader_y1 = l.leader_y1;
    return p;
  };
  const PlacedLabel la = leader_of(a);
  if (a.has_leader) {
    if (std::hypot(a.leader_x1 - a.leader_x0, a.leader_y1 - a.leader_y0) > max_leader) return false;
    for (std::size_t j = 0; j < markers.size(); ++j)
      if (j != i && leader_meets_disc(la, markers[j])) return false;
    if (leader_meets_disc(la, dot)) return false;
  }
  for (std::size_t k : kept) {
    const LocalLabel& b = shot.labels[k];
    const PlacedLabel lb = leader_of(b);
    if (boxes_overlap(a.box, b.box)) return false;
    if (a.has_leader && leader_meets_box(la, b.box)) return false;
    if (b.has_leader && leader_meets_box(lb, a.box)) return false;
    if (a.has_leader && b.has_leader && leaders_cross(la, lb)) return false;
  }
  return true;
}

namespace {

const Vec3& p_of(const HexMesh& mesh, Index v) { return mesh.points.at(static_cast<std::size_t>(v)); }

// View D's inset on a surface mesh where a sliver's corner disc (its face's
// shortest edge under kInsetSliverRatio of its longest) as drawn is wider
// than its room in its face (from its anchor to the face's nearest edge;
// 47g review #6: Dolphin_padded's 0.090 disc covered its sliver): the ring's faces and edges zoomed on the vertex p,
// each corner's disc at its anchor inside its own face (build_local_scene's,
// not moved apart), at most kInsetDiscPixels in radius, its rim within
// kInsetRoomShare of the way to its face's nearest edge, in a corner of the
// view free of labels, discs and the table.
void local_inset(LocalShot& shot, const HexMesh& mesh, const Scene& scene, const std::vector<VertexCorner>& corners,
                 const std::vector<double>& values, const Vec3& p, double size, double scale) {
  // Each disc's room: from its anchor to its face's nearest edge.
  const SphereSet& anchors = scene.spheres.at(0);
  std::vector<double> room(std::min(anchors.centers.size(), corners.size()), HUGE_VAL);
  for (std::size_t i = 0; i < room.size(); ++i) {
    const Vec3 c = scene.origin + Vec3{anchors.centers[i].x, anchors.centers[i].y, anchors.centers[i].z};
    const CellRef cell = any_cell(mesh, corners[i].hex);
    for (int k = 0; k < cell.num_corners; ++k) {
      const Vec3& a = mesh.points[static_cast<std::size_t>(cell.corners[static_cast<std::size_t>(k)])];
      const Vec3& b =
          mesh.points[static_cast<std::size_t>(cell.corners[static_cast<std::size_t>((k + 1) % cell.num_corners)])];
      const double t = std::clamp(dot(c - a, b - a) / std::max(dot(b - a, b - a), 1e-300), 0.0, 1.0);
      room[i] = std::min(room[i], norm(c - (a + t * (b - a))));
    }
  }
  // Needed when a disc as the view draws it (with its rim) is wider than its
  // room; zoomed so every room holds a disc of kInsetDiscPixels (at least
  // kInsetMinZoom, at most kInsetMaxZoom times).
  const double tightest = room.empty() ? HUGE_VAL : *std::min_element(room.begin(), room.end());
  const double pixels_per_unit = shot.layout.view.height / shot.camera.ortho_height;
  bool crowded = false;
  for (std::size_t i = 0; i < room.size() && i < shot.labels.size(); ++i) {
    const CellRef cell = any_cell(mesh, corners[i].hex);
    double shortest = HUGE_VAL, longest = 0.0;
    for (int k = 0; k < cell.num_corners; ++k) {
      const double length =
          norm(mesh.points[static_cast<std::size_t>(cell.corners[static_cast<std::size_t>(k)])] -
               mesh.points[static_cast<std::size_t>(cell.corners[static_cast<std::size_t>((k + 1) % cell.num_corners)])]);
      shortest = std::min(shortest, length), longest = std::max(longest, length);
    }
    // A sliver's disc (a fold's large discs overlap their faces' edges by
    // design: view D moves them apart and labels them).
    crowded = crowded || (shortest < kInsetSliverRatio * longest && shot.labels[i].marker.radius > room[i] * pixels_per_unit);
  }
  if (!crowded || !(tightest > 0.0)) return;
  const double zoom = std::clamp(kInsetDiscPixels * kLocalRimScale * scale / (kInsetRoomShare * tightest * pixels_per_unit),
                                 kInsetMinZoom, kInsetMaxZoom);
  std::vector<PixelRect> taken;
  for (const LocalLabel& l : shot.labels) {
    if (l.placed) taken.push_back(l.box);
    const ScreenDisc& m = l.marker;
    taken.push_back({static_cast<int>(m.x - m.radius), static_cast<int>(m.y - m.radius),
                     static_cast<int>(2 * m.radius) + 1, static_cast<int>(2 * m.radius) + 1});
  }
  if (shot.table_box.width > 0) taken.push_back(shot.table_box);
  std::vector<Vec3> points;
  for (const Vec3f& q : scene.translucent.at(0).positions) points.push_back(scene.origin + Vec3{q.x, q.y, q.z});
  std::optional<DetailInset> inset = place_inset(shot.camera, shot.layout.view, p, zoom, points, taken);
  if (!inset) return;
  const double unit = inset->camera.ortho_height / inset->rect.height;  // model units per inset pixel
  Scene zoomed = scene;
  SphereSet& markers = zoomed.spheres.at(0);
  // Size still grows with 1 - SJ (half to all of kInsetDiscPixels, by each
  // marker's radius over the largest), each rim inside its face: at most
  // kInsetRoomShare of its room.
  const double largest = markers.radii.empty() ? 1.0 : *std::max_element(markers.radii.begin(), markers.radii.end());
  for (std::size_t i = 0; i < room.size(); ++i)
    markers.radii[i] = static_cast<float>(std::min(kInsetDiscPixels * scale * unit * (0.5 + 0.5 * markers.radii[i] / largest),
                                                   kInsetRoomShare * room[i] / kLocalRimScale));
  zoomed.spheres.at(1).radii.at(0) = static_cast<float>(kInsetDotPixels * scale * unit / kLocalDiscScale);
  inset->scene = local_marker_discs(zoomed, inset->camera, values, size);
  shot.inset = std::move(inset);
}

}  // namespace

LocalShot local_shot(const HexMesh& mesh, const Topology& topology, std::span<const double> corner_values, Index v,
                     const DetailViewOptions& options) {
  LocalShot shot;
  const std::vector<Index> ring = local_ring(mesh, topology, v);
  shot.kind_swatches = has_non_hex_cells(mesh);
  Scene scene = build_local_scene(mesh, topology, corner_values, v);
  const std::vector<VertexCorner> corners = vertex_corners(mesh, topology, corner_values, v);
  // Under the colour bar: the markers' size rule, the cells' kinds, and on
  // a mesh with non-hex cells the corner values' range (Verdict clamps
  // every kind's to [-1, 1]: an orthogonal tet corner reads 1, not sqrt 2).
  shot.legend = std::string(kLocalMarkerSizeLegend) +
                (shot.kind_swatches ? "\ncorners clamped to [-1, 1]\n" + cell_kinds_legend(mesh, ring)
                                    : std::string());
  const std::vector<ColorBarSwatch> swatches = local_swatches(options);
  const Figure f = detail_figure(options, shot.legend, shot.kind_swatches, true, swatches);
  shot.style = f.style;
  shot.layout = f.layout;
  // The discs at kLocalDiscScale of the markers' size: at full size a ring
  // of 20 cells was one blob of discs (46q review Q-M1).
  std::vector<double> values;
  for (const VertexCorner& c : corners) values.push_back(c.value);
  // The frame: the whole ring (46w review C3, M3: a closer frame cut the
  // ring's cells at its clipping planes and lost its silhouette); corners
  // with no room are listed in the table.
  const std::vector<Vec3> points = cell_points(mesh, ring);
  std::vector<Vec3> centers;
  std::vector<double> base_radii;
  for (std::size_t i = 0; i < scene.spheres[0].centers.size(); ++i) {
    const Vec3f& c = scene.spheres[0].centers[i];
    centers.push_back(scene.origin + Vec3{c.x, c.y, c.z});
    base_radii.push_back(scene.spheres[0].radii[i]);
  }
  shot.text_size = std::max(11, static_cast<int>(std::lround(22 * f.style.scale)));
  const int label_height = static_cast<int>(std::lround(1.15 * shot.text_size));
  shot.max_leader = kLocalMaxLeaderLabels * label_height;
  shot.table_text_size = std::max(10, static_cast<int>(std::lround(0.8 * shot.text_size)));
  std::vector<std::string> texts;
  for (const VertexCorner& c : corners)
    texts.push_back(quality_text(c.value) + "  " + std::string(cell_kind_name(c.kind)) + " " + std::to_string(c.hex));
  // Worst corner first: it gets the nearest free place and number 1.
  std::vector<std::size_t> order(corners.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return corners[a].value < corners[b].value; });

  std::vector<std::size_t> rank(corners.size());
  for (std::size_t k = 0; k < order.size(); ++k) rank[order[k]] = k;
  std::vector<std::size_t> priority = order;  // the numbers' placing order
  std::vector<bool> failed(corners.size(), false);  // no room for its number

  // Viewpoint: the corners' cells in depth (choose_local_viewpoint), the
  // discs apart (in the whole view: the same with or without the table).
  const std::vector<Vec3> direction = {options.view_direction
                                           ? *options.view_direction
                                           : choose_local_viewpoint(local_face_areas(mesh, ring, v), points, centers,
                                                                    base_radii, f.aspect, options.up)};
  // One layout in `view`: the camera, the discs on screen and the labels.
  const auto lay_out = [&](const PixelRect& view) {
    shot.labels.clear();
    shot.num_left_out = 0;
    shot.layout.view = view;
    const double aspect = static_cast<double>(std::max(1, view.width)) / std::max(1, view.height);
    shot.camera = fit_camera_to_points(points, direction.at(0), aspect, {.up = options.up, .is_perspective = false});
    const double pixels_per_unit = view.height / shot.camera.ortho_height;
    // Each disc at least kLocalMinDiscPixels in radius: a good corner's disc
    // (a quarter of the largest) was an 8-pixel dot on the pale faces (46r review).
    const double min_radius = kLocalMinDiscPixels * f.style.scale / pixels_per_unit;
    Scene drawn = scene;
    std::vector<double> radii(base_radii.size());
    for (std::size_t i = 0; i < radii.size(); ++i) {
      radii[i] = std::max(base_radii[i] * kLocalDiscScale, min_radius);
      drawn.spheres[0].radii[i] = static_cast<float>(radii[i]);
    }
    const auto to_screen = [&](const Vec3& p) {
      const Vec3 ndc = project_to_ndc(shot.camera, aspect, p);
      return std::pair{view.x + 0.5 * (ndc.x + 1.0) * view.width, view.y + 0.5 * (1.0 - ndc.y) * view.height};
    };
    const double dot_radius = kLocalDiscScale * scene.spheres.at(1).radii.at(0) * pixels_per_unit;
    std::vector<ScreenDisc> markers;
    for (std::size_t i = 0; i < centers.size(); ++i) {
      const auto [x, y] = to_screen(centers[i]);
      markers.push_back({x, y, kLocalRimScale * radii[i] * pixels_per_unit, static_cast<std::int64_t>(i)});
    }
    // Spider (46w review C1, M1): top down (the vertex's dot, then the worst
    // corner's disc ...), a disc mostly under those drawn over it is moved
    // on screen (in the plane facing the camera) out of them.
    {
      const auto [x, y] = to_screen(scene.origin);
      const std::vector<std::array<double, 2>> moves =
          local_spider_moves(markers, local_stack_order(values), ScreenDisc{x, y, dot_radius, -1});
      const auto [right, up] = screen_axes(shot.camera);
      for (std::size_t i = 0; i < markers.size(); ++i) {
        if (moves[i][0] == 0.0 && moves[i][1] == 0.0) continue;
        markers[i].x += moves[i][0], markers[i].y += moves[i][1];
        const Vec3 shift = (moves[i][0] / pixels_per_unit) * right - (moves[i][1] / pixels_per_unit) * up;
        Vec3f& c = drawn.spheres[0].centers[i];
        c = to_vec3f(Vec3{c.x, c.y, c.z} + shift);
      }
    }
    shot.scene = local_marker_discs(drawn, shot.camera, values, mean_edge_at(mesh, corners, v));
    // What no other label's leader or box may touch: each disc with its rim,
    // grown by the leaders' halo and a pixel (46t2 review: at 800 x 600 a
    // leader crossed a disc's rim, outside its fill).
    const double leader_width = local_leader_width(f.style.scale);
    std::vector<ScreenDisc> guards = markers;
    for (ScreenDisc& g : guards) g.radius += local_leader_clearance(leader_width);
    {
      const auto [x, y] = to_screen(scene.origin);
      shot.dot = {x, y, dot_radius, static_cast<std::int64_t>(markers.size())};
      shot.dot_clear_radius = std::max(dot_radius, kLocalDotClearLabels * label_height);
    }
    // Each disc has its id (its corner's index); the vertex's dot (with its
    // clear zone) is one more obstacle.
    std::vector<ScreenDisc> obstacles = guards;
    obstacles.push_back({shot.dot.x, shot.dot.y, shot.dot_clear_radius, shot.dot.id});
    for (std::size_t i = 0; i < centers.size(); ++i) {
      LocalLabel label;
      label.text = texts[i];  // the cell id ties each marker to its bar in chart E
      label.marker = markers[i];
      label.is_inverted = corners[i].value < 0;
      label.value = corners[i].value;
      label.rank = static_cast<int>(rank[i]) + 1;
      shot.labels.push_back(std::move(label));
    }
    LabelLayoutOptions layout;
    layout.bounds = view;
    layout.gap = 4.0 * f.style.scale;
    layout.ring_step = 12.0 * f.style.scale;
    layout.rings = static_cast<int>(std::ceil(shot.max_leader / layout.ring_step)) + 1;
    layout.leader_distance = 8.0 * f.style.scale;
    // A label beside its marker gets a short leader too: among a dozen
    // markers "next to" names none.
    const auto set_leader = [&](LocalLabel& label, const PlacedLabel& p) {
      label.box = p.box;
      label.has_leader = p.has_leader;
      label.leader_x0 = p.leader_x0, label.leader_y0 = p.leader_y0;
      label.leader_x1 = p.leader_x1, label.leader_y1 = p.leader_y1;
      if (p.has_leader) return;
      const ScreenDisc& m = label.marker;
      const double nx = std::clamp(m.x, double(label.box.x), double(label.box.x + label.box.width));
      const double ny = std::clamp(m.y, double(label.box.y), double(label.box.y + label.box.height));
      const double dx = nx - m.x, dy = ny - m.y, d = std::hypot(dx, dy);
      if (d > m.radius + 2.0) {
        label.has_leader = true;
        label.leader_x0 = m.x + dx / d * m.radius, label.leader_y0 = m.y + dy / d * m.radius;
        label.leader_x1 = nx, label.leader_y1 = ny;
      }
    };
    // Whether label i, as set, keeps clear of what is kept so far
    // (local_label_clear, its leader at most max_leader long) and of every
    // disc and the vertex's dot.
    std::vector<std::size_t> kept;
    const auto clear = [&](std::size_t i, double max_leader) {
      return local_label_clear(shot, i, kept, guards,
                               {shot.dot.x, shot.dot.y, dot_radius + local_leader_clearance(leader_width)}, max_leader);
    };
    // The placer's answer for corner i: its own disc as drawn (its label may
    // sit next to its rim), the others guarded.
    const auto place = [&](const LabelPlacer& placer, const LabelRequest& request, std::size_t i) {
      obstacles[i].radius = markers[i].radius;
      std::optional<PlacedLabel> p = placer.place(request, obstacles);
      obstacles[i].radius = guards[i].radius;
      return p;
    };
    // First the full labels (worst first; none on a dense ring): one whose
    // leader would be too long or cross another label's box, disc or
    // leader becomes a numbered callout.
    std::vector<std::size_t> callouts;
    if (corners.size() <= kLocalMaxFullLabels) {
      LabelPlacer placer({}, layout);
      for (std::size_t i : order) {
        const PixelRect extent = text_extent(texts[i], shot.text_size, f.style);
        LabelRequest request{markers[i], extent.width + 4, label_height};
        request.protect_below = static_cast<std::int64_t>(obstacles.size());
        request.strict_leaders = true;
        request.always_leader = true;  // so the placer checks the leader drawn
        const std::optional<PlacedLabel> p = place(placer, request, i);
        if (p) {
          set_leader(shot.labels[i], *p);
          if (clear(i, shot.max_leader)) {
            shot.labels[i].placed = true;
            kept.push_back(i);
            PlacedLabel as_set = *p;
            as_set.has_leader = shot.labels[i].has_leader;
            as_set.leader_x0 = shot.labels[i].leader_x0, as_set.leader_y0 = shot.labels[i].leader_y0;
            as_set.leader_x1 = shot.labels[i].leader_x1, as_set.leader_y1 = shot.labels[i].leader_y1;
            placer.add(as_set);
            continue;
          }
        }
        shot.labels[i].has_leader = false;
        callouts.push_back(i);
      }
    }
    // Any corner without room for its full label: every corner numbered by
    // its rank over the whole ring, so the table's "1 = worst" holds (46w
    // review C1: a numbered 0.932 was "1" beside two labelled 0.915).
    if (!callouts.empty() || corners.size() > kLocalMaxFullLabels) {
      for (LocalLabel& label : shot.labels) label.placed = false, label.has_leader = false;
      kept.clear();
      callouts = priority;
    }
    // Then the callouts: a number next to the disc, the same rules; its
    // value and cell in the table beside the view.
    LabelPlacer placer({}, layout);
    // A number with no room within the cap may take a leader up to
    // kLocalFarLeaderShare times as long (46w review M2: rather a long
    // leader to a bad corner than a bad corner left out).
    LabelLayoutOptions far_layout = layout;
    far_layout.rings = static_cast<int>(std::ceil(kLocalFarLeaderShare * shot.max_leader / layout.ring_step)) + 1;
    LabelPlacer far_placer({}, far_layout);
    for (std::size_t i : kept) {
      PlacedLabel p;
      const LocalLabel& l = shot.labels[i];
      p.box = l.box, p.has_leader = l.has_leader;
      p.leader_x0 = l.leader_x0, p.leader_y0 = l.leader_y0, p.leader_x1 = l.leader_x1, p.leader_y1 = l.leader_y1;
      placer.add(p);
      far_placer.add(p);
    }
    const double far_leader = kLocalFarLeaderShare * shot.max_leader;
    // In `priority` (worst first, or those with no room in an earlier
    // round first), each numbered by its rank; a corner with no room is
    // left out and counted, and every later one that has room is still
    // numbered (the vertex-158 review: one corner without room dropped all
    // the better ones after it, 21 of 36 unnumbered).
    std::fill(failed.begin(), failed.end(), false);
    for (std::size_t i : callouts) {
      LocalLabel& label = shot.labels[i];
      label.number = static_cast<int>(rank[i]) + 1;
      const PixelRect extent = text_extent(std::to_string(label.number), shot.text_size, f.style);
      LabelRequest request{markers[i], extent.width + 6, label_height};
      request.protect_below = static_cast<std::int64_t>(obstacles.size());
      request.strict_leaders = true;
      request.always_leader = true;  // so the placer checks the leader drawn
      std::optional<PlacedLabel> p = place(placer, request, i);
      // A disc inside the dot's clear zone (often the worst, stacked at
      // the vertex) may have its number's leader cross the zone (not an
      // obstacle protected from leaders), never the dot itself (clear).
      if (!p || (set_leader(label, *p), !clear(i, shot.max_leader))) {
        request.protect_below = static_cast<std::int64_t>(markers.size());
        p = place(placer, request, i);
      }
      if (!p || (set_leader(label, *p), !clear(i, shot.max_leader))) {
        request.protect_below = static_cast<std::int64_t>(obstacles.size());
        p = place(far_placer, request, i);
        // The far placer's first choice may break local_label_clear's
        // rules: up to kLocalRetries more, each with the places refused so
        // far taken (the 44m brief: at hex_tet's vertex 229 rank 2's only
        // choice was refused, while room was left beside its disc).
        std::optional<LabelPlacer> retry;  // far_placer's copy, made at the first refusal
        for (int k = 0; k < kLocalRetries && p && (set_leader(label, *p), !clear(i, far_leader)); ++k) {
          if (!retry) retry = far_placer;
          retry->add(PlacedLabel{p->box});
          p = place(*retry, request, i);
        }
      }
      if (p) {
        set_leader(label, *p);
        if (clear(i, far_leader)) {
          label.placed = true;
          kept.push_back(i);
          PlacedLabel as_set = *p;
          as_set.has_leader = label.has_leader;
          as_set.leader_x0 = label.leader_x0, as_set.leader_y0 = label.leader_y0;
          as_set.leader_x1 = label.leader_x1, as_set.leader_y1 = label.leader_y1;
          placer.add(as_set);
          far_placer.add(as_set);
          continue;
        }
      }
      label.has_leader = false;
      label.number = 0;
      failed[i] = true;
    }
    for (std::size_t i : callouts) shot.num_left_out += failed[i] ? 1 : 0;
    return callouts.size();
  };

  // The table of numbered corners: a column right of the view (the view
  // narrowed by it), made only when some corner is numbered.
  const auto lay_out_with_table = [&]() {
  shot.table_box = {};
  PixelRect view = f.layout.view;
  shot.layout = f.layout;
  if (lay_out(view) > 0) {
    int width = std::max(text_extent(kLocalTableHeading, shot.table_text_size, f.style).width,
                         text_extent(kLocalLeftOutHeading, shot.table_text_size, f.style).width);
    for (std::size_t i = 0; i < texts.size(); ++i)
      width = std::max(width, text_extent(std::to_string(i + 1) + "   " + texts[i], shot.table_text_size, f.style).width);
    const int line = static_cast<int>(std::lround(1.3 * shot.table_text_size));
    const int rows = std::max(1, view.height / line - 2);
    const int columns = static_cast<int>((texts.size() + rows - 1) / rows);
    const int margin = static_cast<int>(std::lround(12 * f.style.scale));
    const int table_width = columns * (width + margin) + margin;
    view.width -= std::min(table_width, view.width / 2);
    // In the narrowed view every label may fit in full: then no table.
    if (lay_out(view) > 0) shot.table_box = {view.x + view.width + margin, view.y, table_width - margin, view.height};
  }
  };
  // Up to kLocalLayoutRounds rounds: the corners with no room so far go
  // first; the round numbering the worse corners is kept (the first on a
  // tie): at the worst corner numbered in one round and left out in the
  // other, the round numbering it wins (the 44m brief: rounds kept for
  // leaving out fewest let ranks 35-38 take rank 2's room).
  const auto numbers_worse_first = [&](const LocalShot& a, const LocalShot& b) {
    for (std::size_t i : order)
      if (a.labels[i].placed != b.labels[i].placed) return a.labels[i].placed;
    return false;
  };
  lay_out_with_table();
  std::vector<bool> promoted(corners.size(), false);
  for (int round = 1; round < kLocalLayoutRounds && shot.num_left_out > 0; ++round) {
    bool more = false;
    for (std::size_t i = 0; i < corners.size(); ++i) more = more || (failed[i] && !promoted[i]);
    if (!more) break;
    for (std::size_t i = 0; i < corners.size(); ++i) promoted[i] = promoted[i] || failed[i];
    priority.clear();
    for (std::size_t i : order)
      if (promoted[i]) priority.push_back(i);
    for (std::size_t i : order)
      if (!promoted[i]) priority.push_back(i);
    LocalShot best = shot;
    lay_out_with_table();
    if (!numbers_worse_first(shot, best)) shot = std::move(best);
  }
  if (!options.cell_quality.empty()) local_inset(shot, mesh, scene, corners, values, p_of(mesh, v), mean_edge_at(mesh, corners, v), f.style.scale);
  return shot;
}

std::vector<LocalTableRow> local_table_rows(const LocalShot& shot) {
  std::vector<const LocalLabel*> numbered, left_out;
  for (const LocalLabel& label : shot.labels) {
    if (label.placed && label.number > 0) numbered.push_back(&label);
    if (!label.placed) left_out.push_back(&label);
  }
  std::sort(numbered.begin(), numbered.end(),
            [](const LocalLabel* a, const LocalLabel* b) { return a->number < b->number; });
  // NaN last.
  const auto key = [](const LocalLabel* l) { return std::isnan(l->value) ? HUGE_VAL : l->value; };
  std::stable_sort(left_out.begin(), left_out.end(),
                   [&](const LocalLabel* a, const LocalLabel* b) { return key(a) < key(b); });
  std::vector<LocalTableRow> rows;
  for (const LocalLabel* l : numbered) rows.push_back({std::to_string(l->number), l->text, false, l->is_inverted});
  if (!left_out.empty()) {
    rows.push_back({"", kLocalLeftOutHeading, true, false});
    for (const LocalLabel* l : left_out) rows.push_back({std::to_string(l->rank), l->text, false, l->is_inverted});
  }
  return rows;
}

Image render_local_shot(const LocalShot& shot, const DetailViewOptions& options, Renderer& renderer) {
  // A count of labels left out under the size rule (the kinds stay the
  // title's last line: detail_color_bar reads its swatches from it).
  std::string legend = shot.legend;
  if (shot.num_left_out > 0)
    legend.insert(std::string_view(kLocalMarkerSizeLegend).size(),
                  "\n" + std::to_string(shot.num_left_out) + (shot.num_left_out == 1 ? " corner" : " corners") +
                      " not numbered\n(listed at the table's end)");
  // The vertex's dot (a white disc on a black ring), the faces and the
  // discs' rims: their own legend entries.
  std::vector<ColorBarSwatch> swatches = local_swatches(options);
  if (shot.inset) swatches.push_back({to_color(kInsetColor), "box: zoomed in the inset", SwatchShape::line});
  const Figure f = detail_figure(options, shot.legend, shot.kind_swatches, true, swatches);
  const ColorBar bar = detail_color_bar(legend, shot.kind_swatches, true, swatches);
  Image figure = make_image(options.width, options.height, options.background);
  const PixelRect& view = shot.layout.view;  // narrowed by the table, if any
  paste(figure, renderer.render(shot.scene, shot.camera, view.width, view.height), view.x, view.y);
  draw_title(figure, f.layout.title, options.title, f.style);
  draw_color_bar(figure, f.layout.legend, bar, f.style);
  // All leaders (on a pale halo) under all boxes, then each label or
  // number on its box filled with the background (as view A's), so that no
  // cell edge runs through its text (46r review); no leader meets another
  // box (local_shot).
  if (shot.inset) frame_rect(figure, shot.inset->box, f.style);  // under the leaders and labels
  Rgba8 halo = options.background;
  halo.a = 200;
  const double width = local_leader_width(f.style.scale);
  const auto ink = [](const LocalLabel& label) {
    return label.is_inverted ? to_rgba8(kInvertedColor) : Rgba8{30, 30, 30, 255};
  };
  for (const LocalLabel& label : shot.labels)
    if (label.placed && label.has_leader)
      draw_line(figure, label.leader_x0, label.leader_y0, label.leader_x1, label.leader_y1, halo, kLocalHaloWidths * width);
  for (const LocalLabel& label : shot.labels)
    if (label.placed && label.has_leader)
      draw_line(figure, label.leader_x0, label.leader_y0, label.leader_x1, label.leader_y1, ink(label), width);
  AnnotationStyle label_style = f.style;
  for (const LocalLabel& label : shot.labels) {
    if (!label.placed) continue;
    fill_rect(figure, label.box, options.background);
    label_style.text_color = ink(label);
    const std::string text = label.number > 0 ? std::to_string(label.number) : label.text;
    draw_text(figure, label.box.x + (label.number > 0 ? 3 : 2),
              label.box.y + static_cast<int>(std::lround(0.85 * shot.text_size)), text, shot.text_size, label_style);
  }
  // The numbered corners' table (local_table_rows) in columns top to
  // bottom, its numbers right-aligned in their own column.
  if (shot.table_box.width > 0) {
    const std::vector<LocalTableRow> rows = local_table_rows(shot);
    const int line = static_cast<int>(std::lround(1.3 * shot.table_text_size));
    const int per_column = std::max(1, shot.table_box.height / line - 2);
    const int columns = std::max<int>(1, static_cast<int>((rows.size() + per_column - 1) / per_column));
    const int column_width = shot.table_box.width / columns;
    int key_width = 0;
    for (const LocalTableRow& row : rows)
      key_width = std::max(key_width, text_extent(row.key, shot.table_text_size, f.style).width);
    const int text_x = key_width + text_extent("  ", shot.table_text_size, f.style).width;
    const int top = shot.table_box.y + line;
    label_style.text_color = Rgba8{30, 30, 30, 255};
    draw_text(figure, shot.table_box.x, top, kLocalTableHeading, shot.table_text_size, label_style);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const LocalTableRow& row = rows[k];
      label_style.text_color = row.is_inverted ? to_rgba8(kInvertedColor) : Rgba8{30, 30, 30, 255};
      const int x = shot.table_box.x + static_cast<int>(k / per_column) * column_width;
      const int y = top + (static_cast<int>(k % per_column) + 1) * line + line / 2;
      if (row.is_heading) {
        draw_text(figure, x, y, row.text, shot.table_text_size, label_style);
        continue;
      }
      draw_text(figure, x + key_width - text_extent(row.key, shot.table_text_size, f.style).width, y, row.key,
                shot.table_text_size, label_style);
      draw_text(figure, x + text_x, y, row.text, shot.table_text_size, label_style);
    }
  }
  if (shot.inset) draw_inset(figure, *shot.inset, renderer, f.style, options.background, "the vertex");
  return figure;
}

Image render_local_view(const HexMesh& mesh, const Topology& topology, std::span<const double> corner_values, Index v,
                        const DetailViewOptions& options, Renderer& renderer) {
  return render_local_shot(local_shot(mesh, topology, corner_values, v, options), options, renderer);
}

}  // namespace hq
