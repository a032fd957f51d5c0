#include "hqview/views/inverted_callout.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "hqview/core/text.h"
#include "hqview/mesh/boundary_polygons.h"
#include "hqview/mesh/cell_faces.h"
#include "hqview/render/id_image.h"
#include "hqview/render/label_layout.h"
#include "hqview/render/scene.h"

namespace hq {
namespace {

constexpr std::uint32_t kIdNothing = 0;               // background
constexpr std::uint32_t kIdOccluder = kMaxId;         // boundary not painted inverted
constexpr double kPi = 3.14159265358979323846;
constexpr double kDashPixels = 14.0;  // a dashed ring's dash, along the ring
// The fraction of each period a dash takes: kDashPixels of the period, at most 0.6.
double dash_fraction(double n, double radius) { return std::min(0.6, kDashPixels * n / std::max(1.0, 2.0 * kPi * radius)); }

struct Projector {
  Mat4 to_ndc;
  PixelRect view;
  // Figure pixels of a model point.
  Vec3 operator()(const Vec3& p) const {
    const Vec3 ndc = transform_point(to_ndc, p);
    return {view.x + 0.5 * (ndc.x + 1.0) * view.width, view.y + 0.5 * (1.0 - ndc.y) * view.height, 0.0};
  }
};

// The id image's scene: every boundary face, flat, in kIdOccluder, except
// that a face with an inverted corner is split as the overview paints it:
// each triangle of its fan (corner, next corner, centre; a triangle face is
// its own fan) into the 3 parts nearest its vertices (each vertex and the
// midpoints of its two edges) and the middle; a part nearest an inverted
// vertex (the centre: when the corners' mean is < 0, its first inverted
// corner's) carries that vertex's slot + 1 (vertex_slot: its place among
// the inverted corners' vertices, -1 for the others), so that the pixels
// say which vertex's blue shows and with it which cells are in sight.
Scene id_scene(const HexMesh& mesh, const Topology& topology, std::span<const double> vertex_quality,
               const std::vector<int>& vertex_slot, const Vec3& origin) {
  Scene scene;
  scene.origin = origin;
  scene.background = id_color(kIdNothing);
  TriangleSet set;
  set.is_lit = false;
  auto add = [&](const Vec3& a, const Vec3& b, const Vec3& c, std::uint32_t id) {
    const auto base = static_cast<std::uint32_t>(set.positions.size());
    for (const Vec3* p : {&a, &b, &c}) {
      set.positions.push_back(to_vec3f(*p - origin));
      set.colors.push_back(id_color(id));
    }
    set.indices.insert(set.indices.end(), {base, base + 1, base + 2});
  };
  auto id_of_group = [](int g) { return g < 0 ? kIdOccluder : static_cast<std::uint32_t>(g + 1); };
  auto split = [&](const Vec3& a, const Vec3& b, const Vec3& c, int ga, int gb, int gc) {
    const Vec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
    add(a, ab, ca, id_of_group(ga));
    add(b, bc, ab, id_of_group(gb));
    add(c, ca, bc, id_of_group(gc));
    add(ab, bc, ca, kIdOccluder);
  };
  for (const BoundaryPolygon& face : boundary_polygons(topology)) {
    std::array<Vec3, 4> p;
    std::array<int, 4> g{-1, -1, -1, -1};
    int first = -1;
    for (int i = 0; i < face.size; ++i) {
      const auto v = static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)]);
      p[static_cast<std::size_t>(i)] = mesh.points[v];
      if (v < vertex_slot.size()) g[static_cast<std::size_t>(i)] = vertex_slot[v];
      if (first < 0) first = g[static_cast<std::size_t>(i)];
    }
    if (face.size == 3) {
      if (first < 0) add(p[0], p[1], p[2], kIdOccluder);
      else split(p[0], p[1], p[2], g[0], g[1], g[2]);
      continue;
    }
    if (first < 0) {
      add(p[0], p[1], p[2], kIdOccluder);
      add(p[0], p[2], p[3], kIdOccluder);
      continue;
    }
    double sum = 0.0;
    int finite = 0;
    for (int i = 0; i < 4; ++i) {
      const double q = vertex_quality[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)])];
      if (!std::isnan(q)) sum += q, ++finite;
    }
    const Vec3 centre = 0.25 * (p[0] + p[1] + p[2] + p[3]);
    const int gc = finite > 0 && sum / finite < 0.0 ? first : -1;
    for (std::size_t i = 0; i < 4; ++i) split(p[i], p[(i + 1) % 4], centre, g[i], g[(i + 1) % 4], gc);
  }
  scene.triangles.push_back(std::move(set));
  return scene;
}

// The area two discs share.
double disc_overlap_area(double x0, double y0, double r0, double x1, double y1, double r1) {
  const double d = std::hypot(x1 - x0, y1 - y0);
  if (d >= r0 + r1) return 0.0;
  if (d <= std::abs(r0 - r1)) return kPi * std::min(r0, r1) * std::min(r0, r1);
  const double a0 = std::acos(std::clamp((d * d + r0 * r0 - r1 * r1) / (2.0 * d * r0), -1.0, 1.0));
  const double a1 = std::acos(std::clamp((d * d + r1 * r1 - r0 * r0) / (2.0 * d * r1), -1.0, 1.0));
  return r0 * r0 * (a0 - std::sin(2.0 * a0) / 2.0) + r1 * r1 * (a1 - std::sin(2.0 * a1) / 2.0);
}

// "6 inverted hexes" (noun empty: "6 inverted").
std::string count_inverted(std::size_t n, const std::string& noun) {
  std::string label = std::to_string(n) + " inverted";
  if (!noun.empty()) label += " " + plural(noun, n);
  return label;
}


// 6. The blue in sight that each solid ring leaves outside (issue 45, the
// 45c/45d reviews: blue spread wider than the largest ring lay outside it,
// and the label's "32 in sight" did not say whether those cells were among
// them): each callout counts its cells in sight with a blue pixel beyond
// its (solid) ring's radius (num_seen_outside). ids: the id image of
// inverted_callouts' step 3a; group g's callout is rank[g] (none when past
// the callouts kept).
void count_blue_outside_rings(std::vector<InvertedCallout>& callouts, const IdImage& ids, const PixelRect& view,
                              const std::vector<int>& vertex_group, const std::vector<std::size_t>& rank,
                              const std::vector<int>& vertex_slot, const std::vector<std::size_t>& slot_vertex,
                              const std::vector<char>& slot_seen, const HexMesh& mesh, const std::vector<Index>& cells) {
  const auto callout_of_slot = [&](std::size_t slot) -> std::optional<std::size_t> {
    const int g = vertex_group[slot_vertex[slot]];
    if (g < 0 || static_cast<std::size_t>(g) >= rank.size() || rank[static_cast<std::size_t>(g)] >= callouts.size()) return std::nullopt;
    return rank[static_cast<std::size_t>(g)];
  };
  // Slots with a pixel beyond their callout's ring; then the cells in sight with such a corner.
  std::vector<char> slot_outside(slot_vertex.size(), 0);
  for (int v = 0; v < ids.height; ++v)
    for (int u = 0; u < ids.width; ++u) {
      const std::uint32_t id = ids.ids[static_cast<std::size_t>(v) * static_cast<std::size_t>(ids.width) + static_cast<std::size_t>(u)];
      if (id == kIdNothing || id == kIdOccluder || id > slot_vertex.size() || slot_outside[id - 1]) continue;
      const auto k = callout_of_slot(id - 1);
      if (!k) continue;
      const InvertedCallout& c = callouts[*k];
      slot_outside[id - 1] = std::hypot(view.x + ids.x0 + u + 0.5 - c.x, view.y + ids.y0 + v + 0.5 - c.y) > c.radius;
    }
  for (const Index cell : cells) {
    const CellRef ref = any_cell(mesh, cell);
    std::optional<std::size_t> k;
    bool outside = false;
    for (int i = 0; i < ref.num_corners; ++i) {
      const int slot = vertex_slot[static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(i)])];
      if (slot < 0 || !slot_seen[static_cast<std::size_t>(slot)]) continue;
      k = callout_of_slot(static_cast<std::size_t>(slot));
      outside = outside || slot_outside[static_cast<std::size_t>(slot)];
    }
    if (k && outside) ++callouts[*k].num_seen_outside;
  }
}

}  // namespace

std::vector<InvertedCallout> inverted_callouts(const HexMesh& mesh, const Topology& topology,
                                               std::span<const Index> inverted_cells,
                                               std::span<const double> vertex_quality, const Camera& camera,
                                               const PixelRect& view, double min_radius, Renderer& renderer) {
  if (inverted_cells.empty() || view.width <= 0 || view.height <= 0) return {};
  const double aspect = static_cast<double>(view.width) / view.height;
  const Projector project{projection_matrix(camera, aspect) * view_matrix(camera), view};
  // A surface mesh's cells (quads, triangles after the volume blocks) too:
  // its thumbnail rings them as a volume mesh's (issue 47 part F).
  const Index num_volume = num_volume_cells(mesh);
  const Index num_cells = num_volume + static_cast<Index>(mesh.quads.size() + mesh.triangles.size());

  // 1. The cells that project (finite) and their projected centres.
  std::vector<Index> cells;
  std::vector<Vec3> centres;  // projected
  for (Index c : inverted_cells) {
    if (c < 0 || c >= num_cells) continue;
    const CellRef ref = any_cell(mesh, c);
    Vec3 centre;
    for (int i = 0; i < ref.num_corners; ++i)
      centre = centre + mesh.points[static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(i)])];
    const Vec3 s = project((1.0 / ref.num_corners) * centre);
    if (!std::isfinite(s.x) || !std::isfinite(s.y)) continue;
    cells.push_back(c);
    centres.push_back(s);
  }
  if (cells.empty()) return {};

  // 2. Cells that share a vertex, transitively, form one group: connected
  // in 3D, whatever the camera (issue 45f: grouping by screen distance
  // merged two places far apart in depth into one ring, and a turned copy
  // or a smaller drawing grouped differently). Union-find over the cells.
  std::vector<int> parent(cells.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) {
    while (parent[static_cast<std::size_t>(i)] != i)
      i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    return i;
  };
  {
    std::unordered_map<Index, int> cell_of_vertex;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const CellRef ref = any_cell(mesh, cells[i]);
      for (int k = 0; k < ref.num_corners; ++k) {
        const auto [it, added] = cell_of_vertex.emplace(ref.corners[static_cast<std::size_t>(k)], static_cast<int>(i));
        if (added) continue;
        const int a = find(static_cast<int>(i)), b = find(it->second);
        if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
      }
    }
  }
  // Groups numbered in the order of their first cell.
  std::vector<int> group_of_root(cells.size(), -1);
  std::vector<int> cell_group(cells.size());
  int num_groups = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    int& g = group_of_root[static_cast<std::size_t>(find(static_cast<int>(i)))];
    if (g < 0) g = num_groups++;
    cell_group[i] = g;
  }

  // 3. Each group's ring: around the bounding box of its cells' projected
  // corners (centre: the box's; radius: half its diagonal, plus a margin),
  // so that it is as tight as a circle around them can be; its inverted
  // corners' vertices.
  std::vector<InvertedCallout> groups(static_cast<std::size_t>(num_groups));
  for (std::size_t i = 0; i < cells.size(); ++i) {
    InvertedCallout& g = groups[static_cast<std::size_t>(cell_group[i])];
    ++g.num_cells;
    g.cells.push_back(cells[i]);
  }
  struct Extent {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  };
  std::vector<Extent> extent(groups.size());
  std::vector<int> vertex_group(mesh.points.size(), -1);
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const auto g = static_cast<std::size_t>(cell_group[i]);
    const CellRef ref = any_cell(mesh, cells[i]);
    Extent& e = extent[g];
    e.x0 = std::min(e.x0, centres[i].x), e.x1 = std::max(e.x1, centres[i].x);
    e.y0 = std::min(e.y0, centres[i].y), e.y1 = std::max(e.y1, centres[i].y);
    for (int k = 0; k < ref.num_corners; ++k) {
      const auto v = static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(k)]);
      const Vec3 s = project(mesh.points[v]);
      if (std::isfinite(s.x) && std::isfinite(s.y))
        e.x0 = std::min(e.x0, s.x), e.x1 = std::max(e.x1, s.x), e.y0 = std::min(e.y0, s.y), e.y1 = std::max(e.y1, s.y);
      // A surface cell is its own boundary face: all its corners count (a
      // concave reversed face of a curved surface has a positive corner).
      const bool marks = cells[i] >= num_volume || (v < vertex_quality.size() && vertex_quality[v] < 0.0);
      if (marks && vertex_group[v] < 0) vertex_group[v] = static_cast<int>(g);
    }
  }
  auto grow = [](Extent& e, const Extent& f) {
    e.x0 = std::min(e.x0, f.x0), e.y0 = std::min(e.y0, f.y0), e.x1 = std::max(e.x1, f.x1), e.y1 = std::max(e.y1, f.y1);
  };
  const double max_radius = max_callout_radius(view, min_radius);
  auto ring_of = [&](const Extent& e, InvertedCallout& c) {
    c.x = 0.5 * (e.x0 + e.x1);
    c.y = 0.5 * (e.y0 + e.y1);
    c.radius = std::clamp(0.5 * std::hypot(e.x1 - e.x0, e.y1 - e.y0) + 0.2 * min_radius, min_radius, max_radius);
  };
  for (std::size_t g = 0; g < groups.size(); ++g) ring_of(extent[g], groups[g]);

  // 3a. On the boundary, and in sight: the id image (per 3D group, before
  // the merge, so that a merged ring knows which of its groups are hidden).
  for (const BoundaryPolygon& face : boundary_polygons(topology))
    for (int i = 0; i < face.size; ++i) {
      const int g = vertex_group[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)])];
      if (g >= 0) groups[static_cast<std::size_t>(g)].on_boundary = true;
    }
  // Kept for step 6: which pixels of blue each slot (marked vertex) paints.
  IdImage ids;
  std::vector<int> vertex_slot(vertex_group.size(), -1);
  std::vector<std::size_t> slot_vertex;
  std::vector<char> slot_seen;
  if (std::any_of(groups.begin(), groups.end(), [](const InvertedCallout& c) { return c.on_boundary; })) {
    // Each marked vertex its slot (ids up to kMaxId - 1; more: the rest draw as occluders).
    for (std::size_t v = 0; v < vertex_group.size(); ++v)
      if (vertex_group[v] >= 0 && slot_vertex.size() + 1 < kIdOccluder) {
        vertex_slot[v] = static_cast<int>(slot_vertex.size());
        slot_vertex.push_back(v);
      }
    ids = renderer.render_ids(id_scene(mesh, topology, vertex_quality, vertex_slot, camera.target), camera,
                              view.width, view.height);
    // Each group's visible pixels, and their box: the group's extent grows
    // to it, so that its solid ring encloses every blue pixel it names (a
    // face painted from an inverted corner reaches past the cells' corners).
    std::vector<Extent> seen(groups.size());
    slot_seen.assign(slot_vertex.size(), 0);
    for (int v = 0; v < ids.height; ++v)
      for (int u = 0; u < ids.width; ++u) {
        const std::uint32_t id = ids.ids[static_cast<std::size_t>(v) * static_cast<std::size_t>(ids.width) + static_cast<std::size_t>(u)];
        if (id == kIdNothing || id == kIdOccluder || id > slot_vertex.size()) continue;
        slot_seen[id - 1] = 1;
        const auto g = static_cast<std::size_t>(vertex_group[slot_vertex[id - 1]]);
        ++groups[g].visible_pixels;
        Extent& e = seen[g];
        const double x = view.x + ids.x0 + u, y = view.y + ids.y0 + v;
        e.x0 = std::min(e.x0, x), e.y0 = std::min(e.y0, y), e.x1 = std::max(e.x1, x + 1.0), e.y1 = std::max(e.y1, y + 1.0);
      }
    for (std::size_t g = 0; g < groups.size(); ++g) {
      if (groups[g].visible_pixels == 0) continue;
      const Extent& e = seen[g];
      InvertedCallout& c = groups[g];
      c.visible_x0 = e.x0, c.visible_y0 = e.y0, c.visible_x1 = e.x1, c.visible_y1 = e.y1;
      grow(extent[g], e);
      ring_of(extent[g], c);
    }
    // A cell is in sight when the blue of one of its corners shows (issue
    // 45, the 45r review: "37 in sight" counted every cell of a group with
    // any blue in sight, most of them inside).
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const CellRef ref = any_cell(mesh, cells[i]);
      for (int k = 0; k < ref.num_corners; ++k) {
        const int slot = vertex_slot[static_cast<std::size_t>(ref.corners[static_cast<std::size_t>(k)])];
        if (slot >= 0 && slot_seen[static_cast<std::size_t>(slot)] != 0) {
          ++groups[static_cast<std::size_t>(cell_group[i])].num_seen_cells;
          break;
        }
      }
    }
  }

  // 3b. Rings that overlap on screen (closer than kRingMergeGap x
  // min_radius apart, edge to edge) become one ring around both groups'
  // extents, repeatedly (issue 45g: the ball's three overlapping rings
  // left no leader a way out that crossed no other ring, and a reader could
  // not tell which ring a label named). The merged ring counts its groups.
  const std::vector<Extent> group_extent = extent;  // each 3D group's own, before the merge
  std::vector<int> merged(groups.size());
  std::iota(merged.begin(), merged.end(), 0);
  bool any_merged = false;
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t a = 0; a < groups.size() && !changed; ++a) {
      if (merged[a] != static_cast<int>(a)) continue;
      for (std::size_t b = a + 1; b < groups.size() && !changed; ++b) {
        if (merged[b] != static_cast<int>(b)) continue;
        const InvertedCallout &ga = groups[a], &gb = groups[b];
        if (std::hypot(ga.x - gb.x, ga.y - gb.y) >= ga.radius + gb.radius + kRingMergeGap * min_radius) continue;
        grow(extent[a], extent[b]);
        Extent& e = extent[a];
        for (int& m : merged)
          if (m == static_cast<int>(b)) m = static_cast<int>(a);
        ring_of(e, groups[a]);
        changed = any_merged = true;
      }
    }
  }
  if (any_merged) {
    // Renumber in the order of the first cell, the cells in the order given.
    std::vector<int> renumber(groups.size(), -1);
    std::vector<InvertedCallout> joined;
    std::vector<Extent> joined_extent;
    std::vector<int> groups_in(groups.size(), 0);
    for (std::size_t g = 0; g < groups.size(); ++g) ++groups_in[static_cast<std::size_t>(merged[g])];
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const auto root = static_cast<std::size_t>(merged[static_cast<std::size_t>(cell_group[i])]);
      if (renumber[root] < 0) {
        renumber[root] = static_cast<int>(joined.size());
        joined.emplace_back();
        joined.back().num_groups = groups_in[root];
        joined_extent.push_back(extent[root]);
        ring_of(extent[root], joined.back());
      }
      InvertedCallout& j = joined[static_cast<std::size_t>(renumber[root])];
      ++j.num_cells;
      j.cells.push_back(cells[i]);
      // A group out of sight keeps its cells apart (its inset draws them).
      if (!callout_in_sight(groups[static_cast<std::size_t>(cell_group[i])])) j.hidden_cells.push_back(cells[i]);
    }
    for (std::size_t g = 0; g < groups.size(); ++g) {
      InvertedCallout& j = joined[static_cast<std::size_t>(renumber[static_cast<std::size_t>(merged[g])])];
      if (groups[g].visible_pixels > 0) {
        const InvertedCallout& f = groups[g];
        const bool first = j.visible_pixels == 0;
        j.visible_x0 = first ? f.visible_x0 : std::min(j.visible_x0, f.visible_x0);
        j.visible_y0 = first ? f.visible_y0 : std::min(j.visible_y0, f.visible_y0);
        j.visible_x1 = first ? f.visible_x1 : std::max(j.visible_x1, f.visible_x1);
        j.visible_y1 = first ? f.visible_y1 : std::max(j.visible_y1, f.visible_y1);
      }
      j.visible_pixels += groups[g].visible_pixels;
      j.num_seen_cells += groups[g].num_seen_cells;
      j.on_boundary = j.on_boundary || groups[g].on_boundary;
      if (!callout_in_sight(groups[g])) {
        ++j.num_hidden_groups;
        j.hidden_on_boundary = j.hidden_on_boundary || groups[g].on_boundary;
      }
    }
    // A ring all of whose groups are hidden needs no list apart.
    for (InvertedCallout& j : joined)
      if (!callout_in_sight(j)) j.hidden_cells.clear(), j.num_hidden_groups = 0, j.hidden_on_boundary = false;
    // A ring with groups in sight and groups hidden is split by sight: a
    // solid ring around the extent of those in sight, a dashed one around
    // the extent of those hidden (the merge decided which label names them;
    // the rings say which are seen), unless the two would overlap by more
    // than kMaxSplitOverlap of the smaller: then one solid ring, its label
    // counting both.
    for (std::size_t k = 0; k < joined.size(); ++k) {
      InvertedCallout& j = joined[k];
      if (j.hidden_cells.empty()) continue;
      Extent seen, hidden;
      for (std::size_t g = 0; g < groups.size(); ++g)
        if (renumber[static_cast<std::size_t>(merged[g])] == static_cast<int>(k))
          grow(callout_in_sight(groups[g]) ? seen : hidden, group_extent[g]);
      InvertedCallout solid, dashed;
      ring_of(seen, solid);
      ring_of(hidden, dashed);
      const double smaller = std::min(solid.radius, dashed.radius);
      if (disc_overlap_area(solid.x, solid.y, solid.radius, dashed.x, dashed.y, dashed.radius) >
          kMaxSplitOverlap * kPi * smaller * smaller) {
        // One ring, then around the blue in sight when a ring holds it
        // (the 45r review: around all its groups' cells, centred on the
        // model, at its largest radius it cut through the blue); its inset
        // draws the hidden. Blue spread wider than the largest ring keeps
        // the ring around all the cells (centred on the blue it moved the
        // ring under an inset, and the model was drawn smaller to free it).
        InvertedCallout blue;
        ring_of({j.visible_x0, j.visible_y0, j.visible_x1, j.visible_y1}, blue);
        if (blue.radius >= max_radius) continue;
        // A ring counts only the hexes it surrounds (the 45e review: the
        // gmsh ring's far-side hexes lay 415 px from a ring of radius 345
        // that counted them): the ring on the blue keeps the hidden only
        // when it holds their ring's centre, else they keep their dashed one.
        if (std::hypot(dashed.x - blue.x, dashed.y - blue.y) <= blue.radius) {
          j.x = blue.x, j.y = blue.y, j.radius = blue.radius;
          continue;
        }
        solid = blue;
      }
      j.hidden_x = dashed.x, j.hidden_y = dashed.y, j.hidden_radius = dashed.radius;
      j.x = solid.x, j.y = solid.y, j.radius = solid.radius;
    }
    for (int& g : vertex_group)
      if (g >= 0) g = renumber[static_cast<std::size_t>(merged[static_cast<std::size_t>(g)])];
    groups = std::move(joined);
    extent = std::move(joined_extent);
    num_groups = static_cast<int>(groups.size());
  }

  // 5. The largest groups first (stable: ties keep the first cell's order);
  // rank: each group's place (vertex_group numbers them as before).
  std::vector<std::size_t> order(groups.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return groups[a].num_cells > groups[b].num_cells; });
  std::vector<InvertedCallout> sorted;
  std::vector<std::size_t> rank(groups.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    rank[order[k]] = k;
    sorted.push_back(std::move(groups[order[k]]));
  }
  groups = std::move(sorted);
  if (groups.size() > static_cast<std::size_t>(kMaxInvertedCallouts)) {
    int more = 0;
    for (std::size_t g = kMaxInvertedCallouts; g < groups.size(); ++g) more += groups[g].num_cells;
    groups.resize(kMaxInvertedCallouts);
    groups.back().num_more_cells = more;
  }
  if (!ids.empty()) count_blue_outside_rings(groups, ids, view, vertex_group, rank, vertex_slot, slot_vertex, slot_seen, mesh, cells);
  return groups;
}

std::string inverted_callout_label(const InvertedCallout& c, const std::string& noun, double view_area) {
  // The cells of its groups in sight, and of those the cells with blue in
  // sight at a corner (issue 45, the 45r review: "37 in sight" counted
  // whole groups).
  const std::size_t num_in_seen_groups = static_cast<std::size_t>(c.num_cells) - c.hidden_cells.size();
  const auto num_seen = static_cast<std::size_t>(c.num_seen_cells);
  // Blue in sight beyond the ring said with its count (the 45d review:
  // the reader could not tell whether it was among the "in sight").
  const std::string outside =
      c.num_seen_outside > 0 ? " (" + std::to_string(c.num_seen_outside) + (c.num_seen_outside == 1 ? " reaches" : " reach") + " outside the ring)"
                             : "";
  // The cells of the groups in sight whose blue does not show said too, so
  // that the parts add up to the count (the 45e review: cyl2's "92 inverted
  // hexes in 2 groups, 25 in sight" left 67 unsaid).
  const std::string seen_part = std::to_string(num_seen) + " in sight" + outside +
                                (num_in_seen_groups > num_seen ? ", " + std::to_string(num_in_seen_groups - num_seen) + " unseen beside them" : "");
  const bool all_seen = num_seen == num_in_seen_groups && outside.empty();
  if (c.hidden_radius > 0.0) {
    // A split ring's solid ring: its groups in sight only (the dashed ring
    // names the rest, inverted_hidden_label).
    std::string label = count_inverted(num_in_seen_groups, noun) + (all_seen ? " in sight" : ", " + seen_part);
    if (c.num_more_cells > 0) label += "; +" + std::to_string(c.num_more_cells) + " more";
    return label;
  }
  std::string label = count_inverted(static_cast<std::size_t>(c.num_cells), noun);
  if (c.num_groups > 1) label += " in " + std::to_string(c.num_groups) + " groups";
  if (!c.hidden_cells.empty()) {
    // One ring over groups in sight and hidden: how many of each, the cells
    // of the groups in sight whose blue does not show apart.
    label += ": " + seen_part + ", " + std::to_string(c.hidden_cells.size()) + (c.hidden_on_boundary ? " on the far side" : " inside");
    if (c.num_more_cells > 0) label += "; +" + std::to_string(c.num_more_cells) + " more";
    if (!c.inset.empty()) label += "; see inset " + c.inset;
    return label;
  }
  if (!c.on_boundary) label += ", inside";
  else if (c.visible_pixels == 0) label += ", far side";
  else if (!all_seen) label += ", " + seen_part;
  if (c.on_boundary && c.visible_pixels > 0 && static_cast<double>(c.visible_pixels) < kSmallInvertedFraction * view_area)
    label += " (small)";
  if (c.num_more_cells > 0) label += "; +" + std::to_string(c.num_more_cells) + " more";
  if (!c.inset.empty()) label += ": see inset " + c.inset;
  return label;
}

std::string inverted_hidden_label(const InvertedCallout& c, const std::string& noun) {
  std::string label = count_inverted(c.hidden_cells.size(), noun);
  if (c.num_hidden_groups > 1) label += " in " + std::to_string(c.num_hidden_groups) + " groups";
  label += c.hidden_on_boundary ? ", far side" : ", inside";
  if (!c.inset.empty()) label += ": see inset " + c.inset;
  return label;
}

std::vector<ScreenDisc> callout_discs(const InvertedCallout& c, double thickness) {
  std::vector<ScreenDisc> discs{{c.x, c.y, c.radius + thickness}};
  if (c.hidden_radius > 0.0) discs.push_back({c.hidden_x, c.hidden_y, c.hidden_radius + thickness});
  return discs;
}

void draw_callout_rings(Image& image, const InvertedCallout& c, double thickness, const PixelRect& clip) {
  draw_marker_ring(image, c.x, c.y, c.radius, thickness, !callout_in_sight(c), kCalloutColor, clip);
  if (c.hidden_radius > 0.0)
    draw_marker_ring(image, c.hidden_x, c.hidden_y, c.hidden_radius, thickness, true, kCalloutColor, clip);
}

void draw_marker_ring(Image& image, double cx, double cy, double radius, double thickness, bool dashed, Rgba8 color,
                      std::optional<PixelRect> clip) {
  const PixelRect within = clip.value_or(PixelRect{0, 0, image.width, image.height});
  const Rgba8 halo{255, 255, 255, 255};
  const int r = static_cast<int>(std::ceil(radius + 2 * thickness)) + 1;
  for (int y = static_cast<int>(cy) - r; y <= static_cast<int>(cy) + r; ++y)
    for (int x = static_cast<int>(cx) - r; x <= static_cast<int>(cx) + r; ++x) {
      if (x < std::max(0, within.x) || y < std::max(0, within.y) || x >= std::min(image.width, within.x + within.width) ||
          y >= std::min(image.height, within.y + within.height))
        continue;
      const double dx = x + 0.5 - cx, dy = y + 0.5 - cy, d = std::hypot(dx, dy);
      const double off = std::abs(d - radius);
      if (off > thickness) continue;
      const bool core = off <= 0.5 * thickness;
      // Dashes of about kDashPixels, at least 8 around, evenly spaced:
      // a large ring stays a ring (the 45e review: five short dashes
      // around a ball read as scratches).
      if (dashed) {
        const double turn = (std::atan2(dy, dx) + kPi) / (2.0 * kPi);  // [0, 1]
        const double n = std::max(8.0, std::round(2.0 * kPi * radius / (kDashPixels + std::max(6.0, 1.5 * thickness))));
        if (turn * n - std::floor(turn * n) >= dash_fraction(n, radius)) continue;
      }
      const Rgba8 c = core ? color : halo;
      std::copy_n(&c.r, 4, &image.rgba[pixel_offset(image, x, y)]);
    }
}

namespace {

// The words of text in lines of at most max_width pixels (a word longer
// than that on a line of its own); "see inset A" and a number with the word
// after it stay on one line.
std::vector<std::string> wrap_words(const std::string& text, int max_width, int text_size, const AnnotationStyle& style) {
  std::vector<std::string> words;
  for (std::size_t i = 0; i <= text.size();) {
    const std::size_t j = std::min(text.find(' ', i), text.size());
    std::string word = text.substr(i, j - i);
    // A count stays with the word after it ("29 unseen", the 45c review:
    // "29" ended one line, "unseen beside them" began the next).
    const bool glued = !words.empty() && (words.back() == "see" || words.back() == "see inset" ||
                                          std::all_of(words.back().begin(), words.back().end(),
                                                      [](char ch) { return ch == '+' || ch == '(' || (ch >= '0' && ch <= '9'); }));
    if (glued) words.back() += " " + word;
    else words.push_back(std::move(word));
    i = j + 1;
  }
  std::vector<std::string> lines;
  std::string line;
  for (const std::string& word : words) {
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && text_extent(longer, text_size, style).width > max_width) {
      lines.push_back(line);
      line = word;
    } else {
      line = longer;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

int line_pitch(int text_size) { return text_size + std::max(3, text_size / 5); }

}  // namespace

std::vector<InvertedRingLabel> place_callout_labels(const PixelRect& view, std::span<const InvertedCallout> callouts,
                                               const std::string& noun, double thickness, int text_size,
                                               const AnnotationStyle& style, std::span<const PixelRect> taken,
                                               std::span<const PixelRect> model, std::optional<PixelRect> bounds) {
  const double area = static_cast<double>(view.width) * view.height;
  std::vector<ScreenDisc> rings;
  std::vector<InvertedRingLabel> labels;
  for (std::size_t i = 0; i < callouts.size(); ++i) {
    const InvertedCallout& c = callouts[i];
    labels.push_back({inverted_callout_label(c, noun, area), i, false, {}, std::nullopt});
    rings.push_back({c.x, c.y, c.radius + thickness, static_cast<std::int64_t>(i)});
  }
  // The dashed rings of hidden groups after them, each with its own label:
  // no label covers one, and only its callout's labels' leaders may cross
  // it (the same id).
  for (std::size_t i = 0; i < callouts.size(); ++i) {
    const std::vector<ScreenDisc> discs = callout_discs(callouts[i], thickness);
    for (std::size_t k = 1; k < discs.size(); ++k) {
      labels.push_back({inverted_hidden_label(callouts[i], noun), i, true, {}, std::nullopt});
      rings.push_back({discs[k].x, discs[k].y, discs[k].radius, static_cast<std::int64_t>(i)});
    }
  }
  LabelLayoutOptions layout;
  // 8 pixels off the figure's edge (the 45e review's m1: a label touched it).
  const PixelRect b = bounds.value_or(view);
  layout.bounds = {b.x + 8, b.y + 2, b.width - 16, b.height - 4};
  layout.gap = std::max(8.0, 0.6 * text_size);  // a leader long enough to see
  layout.ring_step = std::max(8.0, 0.8 * text_size);
  // Each label around its ring; when no place there is free (a long label
  // beside a large ring near the view's edge: the 8 positions around the
  // ring all leave the view), around the ring's disc moved sideways and up
  // or down by steps, the leader still from the ring itself (the moved disc
  // only shifts where the label is tried); then the same on 2, then 3
  // lines (issue 45g: rockarm's small ring between a large ring and the
  // view's top edge had no room for one line).
  // Off the model first (the 45c review: the hand's label covered its
  // wrist with free space at the right): every place tried with no box on
  // the model's rectangles (leaders may cross them), on up to 8 lines (the
  // 45e review: on 4 lines the hand's, the 270 degree ring's and the dented
  // bunny's labels found no free place and covered fingertips, the ring's
  // cut face and blue in sight, with free room narrower than 4 lines
  // need), then, when none is free, anywhere on up to 4.
  LabelPlacer free_placer(taken, layout, model), placer(taken, layout);
  const DiscIndex ring_index(rings);
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const ScreenDisc ring = rings[i];
    const int one_line = text_extent(labels[i].text, text_size, style).width;
    std::optional<PlacedLabel> p;
    for (int pass = model.empty() ? 1 : 0; !p && pass < 2; ++pass)
    for (int n = 1; !p && n <= (pass == 0 ? 8 : 4); ++n) {
      const LabelPlacer& where = pass == 0 ? free_placer : placer;
      const std::vector<std::string> lines =
          n == 1 ? std::vector<std::string>{labels[i].text} : wrap_words(labels[i].text, (one_line + n - 1) / n, text_size, style);
      if (n > 1 && static_cast<int>(lines.size()) == 1) continue;
      int width = 0;
      for (const std::string& l : lines) width = std::max(width, text_extent(l, text_size, style).width);
      LabelRequest request{ring, width + 8, static_cast<int>(lines.size()) * line_pitch(text_size) + 8 - (line_pitch(text_size) - text_size)};
      request.always_leader = true;  // a label beside two rings names one of them
      // No leader over another ring or leader (issue 45g: the ball's leaders
      // crossed rings and ended on the wrong one).
      request.protect_below = static_cast<std::int64_t>(rings.size());
      request.strict_leaders = true;
      p = where.place(request, ring_index);
      const double step = std::max(0.5 * ring.radius, 0.75 * text_size);
      for (int k = 1; !p && k <= 24; ++k)
        for (const auto& [sx, sy] : {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1},
                                     std::pair{-1, -1}, std::pair{1, -1}, std::pair{-1, 1}, std::pair{1, 1}}) {
          LabelRequest moved = request;
          moved.anchor.x += sx * k * step;
          moved.anchor.y += sy * k * step;
          moved.leader_from = ring;
          moved.anchor.radius = std::min(ring.radius, 0.5 * text_size);  // only where the box is tried from
          p = where.place(moved, ring_index);
          if (p) break;
        }
      if (p) labels[i].lines = lines;
    }
    if (p) placer.add(*p), free_placer.add(*p);
    labels[i].placed = p;
  }
  return labels;
}

void draw_inverted_callouts(Image& figure, const PixelRect& view, std::span<const InvertedCallout> callouts,
                            const std::string& noun, double thickness, int text_size, const AnnotationStyle& style,
                            std::span<const PixelRect> taken, bool draw_rings, std::span<const PixelRect> model,
                            std::optional<PixelRect> bounds) {
  for (const InvertedCallout& c : callouts)
    if (draw_rings) draw_callout_rings(figure, c, thickness, view);
  if (text_size <= 0) return;
  const Rgba8 line{70, 70, 70, 255};  // the labels' leaders and frames: not the ring's colour
  const std::vector<InvertedRingLabel> labels = place_callout_labels(view, callouts, noun, thickness, text_size, style, taken, model, bounds);
  for (const InvertedRingLabel& label : labels) {
    if (!label.placed) continue;
    const PlacedLabel& p = *label.placed;
    if (p.has_leader) {
      draw_line(figure, p.leader_x0, p.leader_y0, p.leader_x1, p.leader_y1, {255, 255, 255, 255}, thickness + 2.0);
      draw_line(figure, p.leader_x0, p.leader_y0, p.leader_x1, p.leader_y1, line, 0.5 * thickness + 0.5);
    }
    fill_rect(figure, p.box, {255, 255, 255, 255});
    fill_rect(figure, {p.box.x, p.box.y, p.box.width, 1}, line);
    fill_rect(figure, {p.box.x, p.box.y + p.box.height - 1, p.box.width, 1}, line);
    fill_rect(figure, {p.box.x, p.box.y, 1, p.box.height}, line);
    fill_rect(figure, {p.box.x + p.box.width - 1, p.box.y, 1, p.box.height}, line);
    for (std::size_t k = 0; k < label.lines.size(); ++k)
      draw_text(figure, p.box.x + 4,
                p.box.y + 4 + static_cast<int>(std::lround(0.8 * text_size)) + static_cast<int>(k) * line_pitch(text_size),
                label.lines[k], text_size, style);
  }
}

}  // namespace hq
