// View A's clutter control (issue 44): on a stack of 50 overlapping cubes
// (from tests/bad_inputs/medit_overlapping_stack.mesh) and on a grid with
// injected overlapping hexes around a dented (inverted) corner, from both
// chosen viewpoints:
// - the label boxes are pairwise disjoint and inside the view;
// - each label is within the leader distance of its anchor or has a leader
//   line from its anchor to its box;
// - there are at most max_marker_groups + 10 labels;
// - each marker label counts one kind and wears its colour: the labels of
//   coincident vertices add up to the coincident vertices (the vertices in
//   coincident groups), those of intersecting pairs to the pairs;
// - a leader line runs from the anchor disc's edge to the label's box;
// - each cluster label points at a visible part of its own glyph, in the
//   id image of what is drawn (main_view_id_image): its leader starts on a
//   pixel showing that glyph, or, without a leader, it is within 14 px of
//   one; a cluster left unlabelled as hidden shows no pixel;
// - the worst cluster's glyph keeps at least 3/4 of its disc once arrows,
//   rings, leaders and labels are drawn, and no other glyph nor arrow
//   shows inside it (id images; issue 44's fifth round: #0 is drawn on top);
// - no leader runs over a glyph ranked before its own label's (a marker
//   label's: #0), in the id image;
// - every glyph of the scene, projected here with the labels' camera: no
//   label box meets a glyph disc; a label without a leader is within 10
//   pixels of its own glyph and every other glyph disc is at least 10
//   pixels farther (it cannot read as naming another glyph: warrior's
//   "#5 (1)" under the #6 glyph, hand7's "#0 (6)" beside #6);
// - no two leader lines cross, no leader runs through another label's box
//   (the Dolphin fin's tangle).
// Also on the shared meshes whose labels were found wrong (warrior, hand7_1,
// Dolphin_padded) when ../shared/data is there.
#include <gtest/gtest.h>

#include <functional>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>

#include "hqview/core/box3.h"
#include "hqview/glyph/glyphs.h"
#include "hqview/image/colormap.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/mesh/topology.h"
#include "hqview/overlap/overlap.h"
#include "hqview/quality/quality_field.h"
#include "hqview/render/osmesa_renderer.h"
#include "hqview/render/scene_shapes.h"
#include "hqview/views/main_views.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

struct Case {
  HexMesh mesh;
  Topology topology;
  GlyphResult glyphs;
  OverlapReport overlap;
};

Case analyse(HexMesh mesh) {
  Case c;
  c.mesh = std::move(mesh);
  c.topology = build_topology(c.mesh);
  const QualityField quality = compute_quality(c.mesh, c.topology);
  c.glyphs =
      compute_glyphs(c.mesh.points, quality.vertex_quality, test::mean_edge_length(c.mesh, c.topology), GlyphOptions{});
  c.overlap = check_overlap(c.mesh, c.topology, OverlapOptions{});
  return c;
}

// Adds a sheared hex (scaled Jacobian 0.23 at every corner with height 0.3,
// 0.08 with 0.1: a poor cluster) of edge `size` whose first corner is at
// `base`.
void add_sheared_hex(HexMesh& mesh, const Vec3& base, double size, double height = 0.3) {
  const Vec3 a{size, 0, 0}, b{0, size, 0}, up{0.9 * size, 0.9 * size, height * size};
  const Vec3 corners[8] = {base, base + a, base + a + b, base + b, base + up, base + a + up, base + a + b + up, base + b + up};
  std::array<Index, 8> hex{};
  for (int k = 0; k < 8; ++k) {
    hex[static_cast<std::size_t>(k)] = static_cast<Index>(mesh.points.size());
    mesh.points.push_back(corners[k]);
  }
  mesh.hexes.push_back(hex);
}

// A 24 x 24 x 2 grid of unit hexes; its top centre vertex pushed below the
// middle layer (the 4 top cells around it invert); 60 hexes added, each a
// copy of a top cell shifted by (0.3, 0.3, 0.2) (it intersects its original
// and neighbours), 8 of them around the dent and the rest spread over the
// top; and a sheared hex floating above the dent.
// Appends a copy of cell (a hex of mesh, taken by value) moved by shift.
void add_shifted_copy(HexMesh& mesh, const std::array<Index, 8> cell, const Vec3& shift) {
  std::array<Index, 8> copy{};
  for (std::size_t k = 0; k < 8; ++k) {
    copy[k] = static_cast<Index>(mesh.points.size());
    mesh.points.push_back(mesh.points[static_cast<std::size_t>(cell[k])] + shift);
  }
  mesh.hexes.push_back(copy);
}

HexMesh injected_overlaps() {
  HexMesh mesh = test::box_grid(24, 24, 2);
  const auto point_id = [](int i, int j, int k) { return static_cast<Index>(i + 25 * (j + 25 * k)); };
  mesh.points[static_cast<std::size_t>(point_id(12, 12, 2))].z = 0.6;
  auto cell_id = [](int i, int j, int k) { return static_cast<std::size_t>(i + 24 * (j + 24 * k)); };
  std::vector<std::pair<int, int>> where{{11, 11}, {12, 11}, {11, 12}, {12, 12},
                                         {10, 12}, {13, 12}, {12, 10}, {12, 13}};
  for (int n = 0; n < 52; ++n) where.push_back({(n * 7) % 24, (n * 11 + 3) % 24});
  for (const auto& [i, j] : where) add_shifted_copy(mesh, mesh.hexes[cell_id(i, j, 1)], Vec3{0.3, 0.3, 0.2});
  // A sheared hex floating 4.5 above the dent (scaled Jacobian 0.23 at every
  // corner: a poor cluster of its own, too far from the dent's to join
  // it): from above, its glyphs lie in front of #0's.
  add_sheared_hex(mesh, Vec3{12.0, 12.0, 5.5}, 1.0);
  return mesh;
}

// The glyph discs of the scene on screen (figure pixels), projected with
// the labels' camera: the centre, and the radius as the distance to the
// projection of a point one radius away in the image plane.
std::vector<ScreenDisc> glyph_discs(const Scene& scene, const MainViewLabels& labels) {
  const Camera& camera = labels.camera;
  const PixelRect& view = labels.view;
  const double aspect = static_cast<double>(view.width) / view.height;
  const Vec3 forward = normalized(camera.target - camera.eye);
  const Vec3 side = normalized(cross(forward, camera.up));
  auto pixel = [&](const Vec3& p) {
    const Vec3 ndc = project_to_ndc(camera, aspect, p);
    return std::array<double, 2>{view.x + 0.5 * (ndc.x + 1.0) * view.width, view.y + 0.5 * (1.0 - ndc.y) * view.height};
  };
  std::vector<ScreenDisc> discs;
  for (const SphereSet& set : scene.spheres)
    for (std::size_t i = 0; i < set.centers.size(); ++i) {
      const Vec3 centre = scene.origin + Vec3{set.centers[i].x, set.centers[i].y, set.centers[i].z};
      const auto a = pixel(centre), b = pixel(centre + static_cast<double>(set.radii[i]) * side);
      discs.push_back({a[0], a[1], std::hypot(b[0] - a[0], b[1] - a[1])});
    }
  return discs;
}

// Pixels on the circle radius - 1.5 px inside a glyph's disc that show the
// background (the rings' pale halo is the background colour): a ring drawn
// over the glyph's rim makes the glyph look smaller than it is (bunny_in:
// the inverted #0 looked 1 px smaller than #1). Of 72 samples.
int background_inside_rim(const Image& image, const ScreenDisc& d, const Rgba8& background) {
  int count = 0;
  for (int i = 0; i < 72; ++i) {
    const double a = 2.0 * M_PI * i / 72, r = d.radius - 1.0;
    const int x = static_cast<int>(std::lround(d.x + r * std::cos(a))),
              y = static_cast<int>(std::lround(d.y + r * std::sin(a)));
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) continue;
    const std::uint8_t* p = image.rgba.data() + pixel_offset(image, x, y);
    count += std::hypot(p[0] - background.r, p[1] - background.g, p[2] - background.b) <= 12.0 ? 1 : 0;
  }
  return count;
}

// Glyph sizes in the scene (issue 44): the grey glyphs (spheres[0]) and the
// coloured ones (spheres[1]) are in rank order; their radii on screen never
// grow with the rank (a worse cluster is never drawn smaller), #0 is at
// least kWorstGlyphMinPixels (24 px at 1200 px height) and the largest, and
// no grey glyph is drawn bigger than the smallest coloured one (issue 44
// part T: the grey ones keep their severity radius, no longer 0.6 of it;
// they rank after every coloured tie class).
void expect_sizes_by_severity(const Scene& scene, const std::vector<ScreenDisc>& discs, const MainViewLabels& labels,
                              double scale = 1.0) {
  // Sets: the pale grey ones, the coloured ones, the unfaded grey ones
  // (min quality < kUnfadedGlyphQuality: ranked before the pale ones).
  ASSERT_EQ(scene.spheres.size(), 3u);
  const std::size_t pale = scene.spheres[0].centers.size(), coloured = scene.spheres[1].centers.size(),
                    unfaded = scene.spheres[2].centers.size();
  ASSERT_EQ(pale + coloured + unfaded, discs.size());
  const auto radius = [&](std::size_t i) { return discs[i].radius; };
  // In rank order: coloured, unfaded grey, pale grey.
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < coloured; ++i) order.push_back(pale + i);
  for (std::size_t i = 0; i < unfaded; ++i) order.push_back(pale + coloured + i);
  for (std::size_t i = 0; i < pale; ++i) order.push_back(i);
  for (std::size_t k = 1; k < order.size(); ++k)
    if (k != coloured) EXPECT_LE(radius(order[k]), radius(order[k - 1]) * (1 + 1e-9) + 1e-9) << "rank " << k;
  if (coloured == 0) return;
  const double worst = radius(pale);  // cluster #0
  EXPECT_GE(worst, 24.0 * scale - 0.01);
  EXPECT_NEAR(labels.worst_glyph.radius, worst, 0.01);
  for (std::size_t i = 0; i < discs.size(); ++i) EXPECT_LE(radius(i), worst * (1 + 1e-9)) << i;
  for (std::size_t k = coloured; k < order.size(); ++k)
    EXPECT_LE(radius(order[k]), radius(pale + coloured - 1) * (1 + 1e-6)) << "grey " << k << " bigger than a coloured glyph";
}

struct MainViewFrameForTest {
  Camera camera;
  PixelRect view;
};

// Labels whose glyph they do not point at, in the id image they were
// placed on (issue 44: warrior's "#1 (1)" leader ended on #6, which hid
// #1): a cluster label's leader must start on a pixel showing its own
// glyph; one without a leader must be within 14 px (gap 4 + leader distance
// 10) of such a pixel. ids: with the markers, as render_main_view draws.
std::vector<std::string> labels_off_their_glyph(const MainViewLabels& labels, const IdImage& ids) {
  std::vector<std::string> wrong;
  for (const MainViewLabel& l : labels.labels) {
    if (l.kind != MainViewLabel::Kind::cluster) continue;
    const std::uint32_t own = kIdGlyph + static_cast<std::uint32_t>(l.cluster);
    const PlacedLabel& p = l.placement;
    if (p.has_leader) {
      const std::uint32_t at = ids.at(static_cast<int>(std::floor(p.leader_x0)), static_cast<int>(std::floor(p.leader_y0)));
      if (at != own) wrong.push_back(l.text + " leader ends on id " + std::to_string(at));
      continue;
    }
    bool near = false;
    const PixelRect& b = p.box;
    for (int y = b.y - 15; y <= b.y + b.height + 15 && !near; ++y)
      for (int x = b.x - 15; x <= b.x + b.width + 15 && !near; ++x)
        near = ids.at(x, y) == own && disc_box_gap(ScreenDisc{x + 0.5, y + 0.5, 0.0}, b) <= 14.0;
    if (!near) wrong.push_back(l.text + " beside no visible pixel of its glyph");
  }
  return wrong;
}

// Cluster labels whose leader starts on another glyph (the reviewer's
// cases), "#k on #j" each.
std::vector<std::string> leaders_on_other_glyphs(const MainViewLabels& labels, const IdImage& ids) {
  std::vector<std::string> wrong;
  for (const MainViewLabel& l : labels.labels) {
    if (l.kind != MainViewLabel::Kind::cluster || !l.placement.has_leader) continue;
    const std::uint32_t at = ids.at(static_cast<int>(std::floor(l.placement.leader_x0)),
                                    static_cast<int>(std::floor(l.placement.leader_y0)));
    if (at >= kIdGlyph && at != kIdGlyph + static_cast<std::uint32_t>(l.cluster))
      wrong.push_back("#" + std::to_string(l.cluster) + " on #" + std::to_string(at - kIdGlyph));
  }
  return wrong;
}

std::size_t count_id(const IdImage& ids, std::uint32_t id) {
  return static_cast<std::size_t>(std::count(ids.ids.begin(), ids.ids.end(), id));
}

// Pixels inside the worst glyph's disc (less 1.5 px: its antialiased rim)
// that show another glyph or an arrow (issue 44's fifth round: warrior's
// #0 was half covered by #1, drawn back to front by depth; #0 is now drawn
// on top of every glyph, and no arrow crosses it).
std::size_t worst_disc_covered(const IdImage& ids, const ScreenDisc& worst) {
  std::size_t covered = 0;
  const double r = worst.radius - 1.5;
  for (int y = static_cast<int>(std::floor(worst.y - r)); y <= static_cast<int>(std::ceil(worst.y + r)); ++y)
    for (int x = static_cast<int>(std::floor(worst.x - r)); x <= static_cast<int>(std::ceil(worst.x + r)); ++x) {
      if (std::hypot(x + 0.5 - worst.x, y + 0.5 - worst.y) >= r) continue;
      const std::uint32_t at = ids.at(x, y);
      covered += (at > kIdGlyph || at == kIdMarker) ? 1 : 0;
    }
  return covered;
}

// The arrows and marker leaders inside a coloured glyph's disc (less 1.5 px,
// its antialiased rim), "arrow over #1" each: #0's rule (nothing crosses its
// glyph) for #1 and #2 too (the 44c review: gmsh_box's #1 and #2 lay under
// arrow fans, the "x15" leader started on #1's centre). Two arrow pixels
// are allowed per glyph.
std::vector<std::string> marks_over_coloured_glyphs(const MainViewLabels& labels) {
  std::vector<std::string> wrong;
  for (const ScreenDisc& d : labels.coloured_glyphs) {
    std::size_t arrow = 0;
    const double r = d.radius - 1.5;
    for (int y = static_cast<int>(std::floor(d.y - r)); y <= static_cast<int>(std::ceil(d.y + r)); ++y)
      for (int x = static_cast<int>(std::floor(d.x - r)); x <= static_cast<int>(std::ceil(d.x + r)); ++x)
        if (std::hypot(x + 0.5 - d.x, y + 0.5 - d.y) < r && labels.ids.at(x, y) == kIdMarker) ++arrow;
    if (arrow > 2) wrong.push_back(std::to_string(arrow) + " arrow pixels over #" + std::to_string(d.id));
    for (const MainViewLabel& l : labels.labels)
      if (l.kind == MainViewLabel::Kind::marker && l.placement.has_leader &&
          leader_meets_disc(l.placement, ScreenDisc{d.x, d.y, d.radius - 0.5, d.id}))
        wrong.push_back(l.text + " leader over #" + std::to_string(d.id));
  }
  return wrong;
}

// Leaders that run over a glyph ranked before their own (a marker label's:
// #0) in the id image, "#6 (1) over #0" each: the pixels along the leader,
// every 0.5 px, that show such a glyph (issue 44's fifth round: warrior's
// "#6 (1)" leader ran straight through #0 and #1). One pixel is allowed
// (the rim of a glyph the leader passes just outside of).
std::vector<std::string> leaders_over_higher_ranks(const MainViewLabels& labels, const IdImage& ids) {
  std::vector<std::string> wrong;
  for (const MainViewLabel& l : labels.labels) {
    const PlacedLabel& p = l.placement;
    if (!p.has_leader) continue;
    const std::uint32_t below = kIdGlyph + static_cast<std::uint32_t>(l.kind == MainViewLabel::Kind::cluster ? l.cluster : 1);
    const double length = std::hypot(p.leader_x1 - p.leader_x0, p.leader_y1 - p.leader_y0);
    std::vector<std::pair<int, int>> hits;
    std::uint32_t first = 0;
    for (int i = 0; i <= static_cast<int>(2.0 * length); ++i) {
      const double t = length > 0.0 ? 0.5 * i / length : 0.0;
      const int x = static_cast<int>(std::floor(p.leader_x0 + t * (p.leader_x1 - p.leader_x0)));
      const int y = static_cast<int>(std::floor(p.leader_y0 + t * (p.leader_y1 - p.leader_y0)));
      const std::uint32_t at = ids.at(x, y);
      if (at >= kIdGlyph && at < below && std::find(hits.begin(), hits.end(), std::make_pair(x, y)) == hits.end()) {
        if (hits.empty()) first = at;
        hits.push_back({x, y});
      }
    }
    // A marker group inside #0's disc: its leader cannot but start over #0.
    const bool starts_in_worst = std::hypot(p.leader_x0 - labels.worst_glyph.x, p.leader_y0 - labels.worst_glyph.y) <
                                 labels.worst_glyph.radius;
    if (hits.size() > 1 && !(first == kIdGlyph && starts_in_worst))
      wrong.push_back(l.text + " over #" + std::to_string(first - kIdGlyph));
  }
  return wrong;
}

// Labels placed near their glyph whose leader runs over another glyph's
// disc (less its 0.5 px rim), "#5 (3) over the glyph at x, y" each (the 44l
// review: bunny's, a turned dolphin's and warrior's leaders crossed
// glyphs), where a way out exists. A leader that starts inside a disc (a
// group's marker inside a glyph) does not count that disc.
std::vector<std::string> near_leaders_over_glyphs(const MainViewLabels& labels, std::span<const ScreenDisc> discs) {
  std::vector<std::string> wrong;
  for (const MainViewLabel& l : labels.labels) {
    const PlacedLabel& p = l.placement;
    if (l.is_callout || !p.has_leader) continue;
    const auto counts = [&](const ScreenDisc& d) {
      return d.radius >= 1.0 && std::hypot(p.leader_x0 - d.x, p.leader_y0 - d.y) >= d.radius &&
             !(std::abs(d.x - l.anchor.x) < 0.5 && std::abs(d.y - l.anchor.y) < 0.5);
    };
    // Only where a way out exists: some straight line of 150 px from the
    // leader's start, every 2 degrees, meets no other disc (a label behind
    // a pile-up has none).
    bool is_free = false;
    for (int k = 0; k < 180 && !is_free; ++k) {
      PlacedLabel ray = p;
      ray.leader_x1 = p.leader_x0 + 150.0 * std::cos(k * M_PI / 90.0);
      ray.leader_y1 = p.leader_y0 + 150.0 * std::sin(k * M_PI / 90.0);
      is_free = std::none_of(discs.begin(), discs.end(), [&](const ScreenDisc& d) {
        return counts(d) && leader_meets_disc(ray, ScreenDisc{d.x, d.y, d.radius - 0.5});
      });
    }
    if (!is_free) continue;
    for (const ScreenDisc& d : discs)
      if (counts(d) && leader_meets_disc(p, ScreenDisc{d.x, d.y, d.radius - 0.5}))
        wrong.push_back(l.text + " over the glyph at " + std::to_string(std::lround(d.x)) + ", " +
                        std::to_string(std::lround(d.y)));
  }
  return wrong;
}

// Every fan draws all its arrows (the 44d review: lshape's "x8" fan, kept
// off #2's glyph, showed 4): the scene's arrows (overlay 0, each arrow the
// same number of vertices, append_arrow) number the marker labels' counts,
// each capped at max_arrows_per_marker. "drew 9 arrows for 12" each.
std::vector<std::string> arrows_short_of_counts(const Scene& scene, const MainViewLabels& labels,
                                                const MainViewOptions& options) {
  TriangleSet one;
  append_arrow(one, Vec3f{0.0f, 0.0f, 0.0f}, Vec3f{1.0f, 0.0f, 0.0f}, ArrowShape{0.1f, 0.2f, 0.3f, 16}, Rgba8{});
  std::size_t expected = 0;
  for (const MainViewLabel& l : labels.labels)
    if (l.kind == MainViewLabel::Kind::marker)
      expected += static_cast<std::size_t>(std::min<Index>(l.count, options.max_arrows_per_marker));
  const std::size_t vertices = scene.overlay.empty() ? 0 : scene.overlay[0].positions.size();
  if (vertices == expected * one.positions.size()) return {};
  return {"drew " + std::to_string(vertices / one.positions.size()) + " arrows for " + std::to_string(expected)};
}

// Leaders and arrows stay separate marks (the 44d review: the "#2 (4)"
// leader lay on an arrow of #2's x8 fan, lshape's ran 6 px beside one):
// the arrow pixels (id image) within 3 px of a leader, sampled every
// 0.5 px, past the first 24 px of a marker label's leader (it leaves its
// own fan between the arrow heads, 20 px long); at most 2 a leader.
std::vector<std::string> leaders_along_arrows(const MainViewLabels& labels) {
  std::vector<std::string> wrong;
  for (const MainViewLabel& l : labels.labels) {
    const PlacedLabel& p = l.placement;
    if (!p.has_leader) continue;
    const double length = std::hypot(p.leader_x1 - p.leader_x0, p.leader_y1 - p.leader_y0);
    const double skip = l.kind == MainViewLabel::Kind::marker ? 24.0 * labels.ids.height / 1200.0 : 0.0;
    std::vector<std::pair<int, int>> hits;
    for (int i = 0; i <= static_cast<int>(2.0 * length); ++i) {
      const double s = 0.5 * i;
      if (s < skip) continue;
      const double x = p.leader_x0 + s / length * (p.leader_x1 - p.leader_x0);
      const double y = p.leader_y0 + s / length * (p.leader_y1 - p.leader_y0);
      for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) {
          const int px = static_cast<int>(std::floor(x)) + dx, py = static_cast<int>(std::floor(y)) + dy;
          if (std::hypot(px + 0.5 - x, py + 0.5 - y) <= 3.0 && labels.ids.at(px, py) == kIdMarker &&
              std::find(hits.begin(), hits.end(), std::make_pair(px, py)) == hits.end())
            hits.push_back({px, py});
        }
    }
    if (hits.size() > 2)
      wrong.push_back(l.text + (l.is_callout ? " (callout)" : "") + " leader within 3 px of " + std::to_string(hits.size()) + " arrow pixels, first at (" +
                      std::to_string(hits[0].first) + ", " + std::to_string(hits[0].second) + ")");
  }
  return wrong;
}

// The 44l review's rules, for meshes with room to spare: every coloured
// cluster that shows is labelled (none "no room"), and no near label's
// leader crosses another glyph where a way out exists
// (near_leaders_over_glyphs).
struct Strict {
  bool all_labelled = false;
  bool leaders_clear = false;
};
void expect_clear_views(const Case& c, const char* name, bool expect_findings = true,
                        std::optional<Vec3> extra_direction = std::nullopt, const MainViewOptions& options = {},
                        Strict strict = {}) {
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  Index findings[2] = {0, 0};  // coincident vertices, intersecting pairs
  for (const OverlapMarker& m : c.overlap.markers)
    findings[m.kind == MarkerKind::coincident ? 0 : 1] += std::max<Index>(m.count, 1);
  if (expect_findings) ASSERT_GT(findings[0] + findings[1], 0) << name;
  EXPECT_EQ(findings[0], c.overlap.num_coincident_vertices) << name;
  const std::vector<Vec3> points = main_view_points(c.mesh, c.topology, c.glyphs);
  const std::vector<Vec3> directions =
      choose_main_viewpoints(points, c.glyphs, main_view_aspect(options), 2, options.up, options.fov_y_degrees);
  ASSERT_EQ(directions.size(), 2u);
  const double scale = annotation_style_for(options.height).scale;  // 1 at a 1200-pixel-high figure
  std::vector<Vec3> all_directions = directions;
  if (extra_direction) all_directions.push_back(*extra_direction);
  for (const Vec3& direction : all_directions) {
    SCOPED_TRACE(std::string(name) + " from " + viewpoint_name(direction, options.up));
    Scene scene;
    const MainViewLabels labels =
        main_view_labels(c.mesh, c.topology, c.glyphs, &c.overlap, direction, options, &scene, renderer.get());
    ASSERT_FALSE(labels.labels.empty());
    ASSERT_FALSE(labels.ids.empty());
    // Each cluster label points at a visible part of its own glyph (the id
    // image of what is drawn); a cluster left out shows no pixel.
    for (const std::string& w : labels_off_their_glyph(labels, labels.ids)) ADD_FAILURE() << w;
    for (Index hidden : labels.hidden_clusters)
      EXPECT_EQ(count_id(labels.ids, kIdGlyph + static_cast<std::uint32_t>(hidden)), 0u) << "#" << hidden;
    // Every coloured tie class whose glyph shows has one label, pointing at
    // its glyph (labels_off_their_glyph above), or is listed `no room`.
    // Callouts (issue 44 part V round 2): a callout leader crosses no
    // coloured glyph but its own class's (round 1: dolphin_rot's x315 over
    // #2), no label placed near its glyph, and is at most a third of the
    // view's diagonal (round 1: 540-700 px at 1600 x 1200).
    {
      const double diagonal = std::hypot(static_cast<double>(labels.view.width), static_cast<double>(labels.view.height));
      for (const MainViewLabel& l : labels.labels) {
        if (!l.is_callout) continue;
        const PlacedLabel& p = l.placement;
        ASSERT_TRUE(p.has_leader) << l.text;
        EXPECT_LE(std::hypot(p.leader_x1 - p.leader_x0, p.leader_y1 - p.leader_y0), diagonal / 3.0) << l.text;
        for (const ScreenDisc& d : labels.coloured_glyphs) {
          const bool own = l.kind == MainViewLabel::Kind::cluster && d.id >= l.cluster &&
                           d.id < std::max<std::int64_t>(l.cluster + 1, l.protect_end);
          if (!own) EXPECT_FALSE(leader_meets_disc(p, ScreenDisc{d.x, d.y, d.radius - 0.5, d.id})) << l.text << " over #" << d.id;
        }
        for (const MainViewLabel& near : labels.labels) {
          if (near.is_callout) continue;
          EXPECT_FALSE(leader_meets_box(p, near.placement.box)) << l.text << " over " << near.text;
          EXPECT_FALSE(leaders_cross(p, near.placement)) << l.text << " and " << near.text;
        }
      }
    }
    {
      const std::vector<Index> ties = glyph_tie_classes(c.glyphs.clusters);
      const Index coloured = coloured_tie_classes(
          tie_class_sizes(ties), static_cast<Index>(labelled_cluster_count(c.glyphs.options.top_clusters)));
      for (std::size_t i = 0; i < ties.size() && ties[i] < coloured; ++i) {
        if ((i > 0 && ties[i - 1] == ties[i]) || count_id(labels.ids, kIdGlyph + static_cast<std::uint32_t>(i)) == 0)
          continue;
        const auto named = std::count_if(labels.labels.begin(), labels.labels.end(), [&](const MainViewLabel& l) {
          return l.kind == MainViewLabel::Kind::cluster && l.cluster == static_cast<Index>(i);
        });
        const bool no_room = std::find(labels.unlabelled_clusters.begin(), labels.unlabelled_clusters.end(),
                                       static_cast<Index>(i)) != labels.unlabelled_clusters.end();
        EXPECT_EQ(named, no_room ? 0 : 1) << "#" << i;
      }
    }
    // The worst cluster's glyph keeps at least 3/4 of its disc once the
    // arrows, rings, leaders and labels are drawn (before issue 44's fifth
    // round this compared with the pixels it showed without the markers,
    // which a glyph already hidden by another passed), and no other glyph
    // nor arrow shows inside its disc. (Weakened to 0.7 in a merge of part
    // U, #0 capped at 24-40 px; since part V a leader's halo begins outside
    // its glyph, and 3/4 holds again.)
    if (!c.glyphs.clusters.empty() && labels.worst_glyph.radius > 0.0) {
      IdImage drawn = labels.ids;
      mark_main_view_annotations(drawn, labels, c.glyphs, options);
      const double disc = M_PI * labels.worst_glyph.radius * labels.worst_glyph.radius;
      const std::size_t after = count_id(drawn, kIdGlyph);
      EXPECT_GE(static_cast<double>(after), 0.75 * disc) << "the worst glyph shows " << after << " pixels of a disc of " << disc << " (" << count_id(labels.ids, kIdGlyph) << " before the annotations)";
      EXPECT_LE(worst_disc_covered(labels.ids, labels.worst_glyph), 2u) << "another glyph or an arrow over #0";
    }
    for (const std::string& w : leaders_over_higher_ranks(labels, labels.ids)) ADD_FAILURE() << w;
    for (const std::string& w : marks_over_coloured_glyphs(labels)) ADD_FAILURE() << w;
    for (const std::string& w : arrows_short_of_counts(scene, labels, options)) ADD_FAILURE() << w;
    const std::vector<ScreenDisc> discs = glyph_discs(scene, labels);
    if (strict.all_labelled)
      for (Index c : labels.unlabelled_clusters) ADD_FAILURE() << "no room for #" << c;
    if (strict.leaders_clear)
      for (const std::string& w : near_leaders_over_glyphs(labels, discs)) ADD_FAILURE() << w;
    // Every on-screen cluster with an inverted vertex is ringed, no other.
    // (Of the glyphs drawn: main_view_glyphs_drawn leaves out piled-up ones.)
    const GlyphsDrawn drawn = main_view_glyphs_drawn(c.glyphs, labels.camera, labels.view.height,
                                                     displayed_glyph_radii(c.glyphs, labels.glyph_scale));
    std::size_t inverted = 0;
    for (const AggregatedGlyph& g : c.glyphs.clusters)
      inverted += g.min_quality < 0.0 && drawn.drawn[static_cast<std::size_t>(g.id)] ? 1 : 0;
    EXPECT_EQ(labels.inverted_glyphs.size(), inverted);
    EXPECT_EQ(discs.size(), c.glyphs.clusters.size() - static_cast<std::size_t>(labels.left_out_glyphs));
    expect_sizes_by_severity(scene, discs, labels, scale);
    for (const MainViewLabel& l : labels.labels) {
      const PixelRect& b = l.placement.box;
      const double own = disc_box_gap(l.anchor, b);
      for (const ScreenDisc& d : discs) {
        const bool is_own = l.kind == MainViewLabel::Kind::cluster && std::abs(d.x - l.anchor.x) < 0.5 &&
                            std::abs(d.y - l.anchor.y) < 0.5;
        // The 1,000 largest discs are obstacles: smaller ones than 1 pixel
        // and those beyond the 1,000th are not asserted on.
        if (d.radius < 1.0 || (discs.size() > 1000 && d.radius < 3.0)) continue;
        EXPECT_FALSE(box_meets_disc(b, ScreenDisc{d.x, d.y, d.radius - 0.5})) << l.text << " covers a glyph";
        if (!is_own && !l.placement.has_leader)
          EXPECT_GE(disc_box_gap(d, b), own + 10.0 * scale * 0.999) << l.text << " without a leader beside another glyph";
      }
      if (!l.placement.has_leader) EXPECT_LE(own, 10.0 * scale) << l.text;
      for (const MainViewLabel& other : labels.labels) {
        if (&other == &l) continue;
        EXPECT_FALSE(leaders_cross(l.placement, other.placement)) << l.text << " and " << other.text << " leaders cross";
        // Nor run side by side (the 44e review: "x13" 6 px beside "#1 (10)").
        EXPECT_FALSE(leaders_run_together(l.placement, other.placement))
            << l.text << " and " << other.text << " leaders run together";
        EXPECT_FALSE(leader_meets_box(l.placement, other.placement.box)) << l.text << "'s leader crosses " << other.text;
      }
    }
    EXPECT_LE(labels.labels.size(), static_cast<std::size_t>(options.max_marker_groups + 10));
    Index counted[2] = {0, 0};
    int markers = 0;
    bool capped = false;
    for (std::size_t i = 0; i < labels.labels.size(); ++i) {
      const MainViewLabel& l = labels.labels[i];
      if (l.kind == MainViewLabel::Kind::marker) {
        const bool is_pair = l.color == kIntersectionArrowColor;
        EXPECT_TRUE(is_pair || l.color == kCoincidentArrowColor) << l.text;
        counted[is_pair ? 1 : 0] += l.count;
        ++markers;
        // A capped fan's label says how many arrows it shows (the 44e
        // review: "x2725" over 12 arrows), and the legend says the cap.
        const Index cap = options.max_arrows_per_marker;
        EXPECT_EQ(l.text, "x" + std::to_string(l.count) +
                              (l.count > cap ? " (" + std::to_string(cap) + " shown)" : std::string()));
        capped = capped || l.count > cap;
        // Anchored at its group's position (a small disc), not at its fan's rim.
        EXPECT_LE(l.anchor.radius, 3.0 * scale) << l.text;
      }
      const PixelRect& b = l.placement.box;
      for (std::size_t j = 0; j < i; ++j)
        EXPECT_FALSE(boxes_overlap(b, labels.labels[j].placement.box)) << i << " " << j;
      EXPECT_TRUE(l.placement.has_leader || disc_box_gap(l.anchor, b) <= 10.0 * scale) << l.text;
      // Without a leader, no other label's anchor is nearer to the box than its own.
      if (!l.placement.has_leader)
        for (const MainViewLabel& other : labels.labels)
          if (&other != &l)
            EXPECT_GE(disc_box_gap(other.anchor, b), disc_box_gap(l.anchor, b)) << l.text << " reads as " << other.text;
      if (l.placement.has_leader) {
        const PlacedLabel& p = l.placement;
        // A marker's leader starts at its anchor disc's edge, or at #0's
        // rings' when its group sits inside them (issue 44 part C: the
        // leader from the group's centre crossed #0's glyph), and never
        // enters #0's glyph (a cluster's on its glyph's visible pixels:
        // checked above).
        if (l.kind == MainViewLabel::Kind::marker) {
          const ScreenDisc& from = l.leader_from.value_or(l.anchor);
          EXPECT_NEAR(std::hypot(p.leader_x0 - from.x, p.leader_y0 - from.y), from.radius, 1.0) << l.text;
          if (l.leader_from) {
            EXPECT_EQ(from.x, labels.worst_glyph.x);
            EXPECT_EQ(from.y, labels.worst_glyph.y);
          }
          for (double t = 0.0; t <= 1.0 && labels.worst_glyph.radius > 0.0; t += 0.02)
            EXPECT_GE(std::hypot(p.leader_x0 + t * (p.leader_x1 - p.leader_x0) - labels.worst_glyph.x,
                                 p.leader_y0 + t * (p.leader_y1 - p.leader_y0) - labels.worst_glyph.y),
                      labels.worst_glyph.radius)
                << l.text << " crosses #0's glyph";
        }
        EXPECT_TRUE(p.leader_x1 >= b.x - 0.5 && p.leader_x1 <= b.x + b.width + 0.5 && p.leader_y1 >= b.y - 0.5 &&
                    p.leader_y1 <= b.y + b.height + 0.5)
            << l.text;
        EXPECT_LE(disc_box_gap(ScreenDisc{p.leader_x1, p.leader_y1, 0.0}, b), 0.5) << l.text;
      }
      EXPECT_GE(b.x, 0);
      EXPECT_LE(b.x + b.width, options.width);
      if (labels.worst_glyph.radius > 0.0) {
        EXPECT_FALSE(box_meets_disc(b, labels.worst_glyph)) << l.text;
      }
    }
    if (capped) {
      const std::string cap_line = "  at most " + std::to_string(options.max_arrows_per_marker) + " arrows a label";
      bool said = false;
      for (const LegendLine& line : main_legend_lines(c.glyphs, &c.overlap, AnnotationStyle{}, options, 1.0))
        said = said || line.text == cap_line;
      EXPECT_TRUE(said) << "a capped fan and no legend line on the cap";
    }
    if (!expect_findings) continue;
    EXPECT_EQ(counted[0], findings[0]);
    EXPECT_EQ(counted[1], findings[1]);
    EXPECT_LE(markers, options.max_marker_groups);
    // Arrows are drawn (the worst glyph's pixels above are counted with them).
    EXPECT_GT(count_id(labels.ids, kIdMarker), 0u);
  }
}

TEST(MainViewLabels, OverlappingStack) {
  // The whole stack (1,500 cubes, each face a boundary face: 36,000
  // triangles over one another) exceeds the overlap stage's default pair
  // budget, which then reports nothing; and cubes shifted by 1e-4 along x
  // only touch along coplanar faces, which the cell test does not count as
  // intersecting. So: its first 50 cubes, cube i moved by i (0.013, 0.009,
  // 0.005), every corner strictly inside its neighbours.
  HexMesh mesh = read_hex_mesh(test::source_dir() / "tests/bad_inputs/medit_overlapping_stack.mesh").mesh;
  ASSERT_EQ(mesh.hexes.size(), 1500u);
  mesh.hexes.resize(50);
  for (std::size_t i = 0; i < 50; ++i)
    for (Index v : mesh.hexes[i]) {
      Vec3& p = mesh.points[static_cast<std::size_t>(v)];
      p = p + static_cast<double>(i) * Vec3{0.013, 0.009, 0.005};
    }
  // The stack's cubes are perfect: a badly sheared hex beside it makes a
  // worst cluster, and a milder one floating above that (its own poor
  // cluster, 2.3 of #0's radii up: beyond #0's cluster) lies, from nearly
  // straight above, in front of #0's glyph (drawn back to front by depth
  // before issue 44's fifth round, it covered #0).
  Box3 box;
  for (const Vec3& p : mesh.points) box.add(p);
  add_sheared_hex(mesh, box.hi + Vec3{2.0, 2.0, -1.0}, 1.0, 0.1);
  const Case first = analyse(mesh);
  ASSERT_FALSE(first.glyphs.clusters.empty());
  const AggregatedGlyph& worst = first.glyphs.clusters[0];
  add_sheared_hex(mesh, worst.position + Vec3{0, 0, 2.3 * worst.radius}, first.glyphs.rmax);
  const Case c = analyse(std::move(mesh));
  EXPECT_FALSE(c.overlap.is_over_budget);
  EXPECT_EQ(c.overlap.num_intersecting_cells, 50);
  EXPECT_EQ(c.glyphs.clusters[0].position, worst.position);
  expect_clear_views(c, "overlapping stack", true, Vec3{0.1, 0.15, -1.0});
}

// Leaders keep off the arrows where the fans leave room (a 10 x 10 x 2
// grid dented to an inverted #0, with shifted copies of 4 cells: one under
// #0, three apart; no two fans overlap): from both main views no leader
// runs within 3 px of an arrow (leaders_along_arrows) and every fan draws
// its count of arrows. (Where a coincident and an intersection fan overlap,
// injected_overlaps' corners, a leader out of one may still cross the
// other's arrows.)
TEST(MainViewLabels, LeadersKeepOffTheArrows) {
  HexMesh mesh = test::box_grid(10, 10, 2);
  mesh.points[static_cast<std::size_t>(5 + 11 * (5 + 11 * 2))].z = 0.6;
  for (const auto& [i, j] : {std::pair{5, 5}, std::pair{1, 2}, std::pair{7, 2}, std::pair{2, 7}})
    add_shifted_copy(mesh, mesh.hexes[static_cast<std::size_t>(i + 10 * (j + 10))], Vec3{0.3, 0.3, 0.2});
  const Case c = analyse(std::move(mesh));
  ASSERT_LT(c.glyphs.clusters.at(0).min_quality, 0.0);
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  const MainViewOptions options;
  const std::vector<Vec3> directions = choose_main_viewpoints(main_view_points(c.mesh, c.topology, c.glyphs), c.glyphs,
                                                              main_view_aspect(options), 2, options.up, options.fov_y_degrees);
  std::size_t marker_leaders = 0;
  for (const Vec3& direction : directions) {
    SCOPED_TRACE(viewpoint_name(direction, options.up));
    Scene scene;
    const MainViewLabels labels =
        main_view_labels(c.mesh, c.topology, c.glyphs, &c.overlap, direction, options, &scene, renderer.get());
    for (const MainViewLabel& l : labels.labels)
      marker_leaders += l.kind == MainViewLabel::Kind::marker && l.placement.has_leader ? 1 : 0;
    for (const std::string& w : arrows_short_of_counts(scene, labels, options)) ADD_FAILURE() << w;
    for (const std::string& w : leaders_along_arrows(labels)) ADD_FAILURE() << w;
  }
  EXPECT_GE(marker_leaders, 4u);
}

TEST(MainViewLabels, InjectedOverlapsAroundAnInvertedCorner) {
  const Case c = analyse(injected_overlaps());
  ASSERT_FALSE(c.glyphs.clusters.empty());
  EXPECT_LT(c.glyphs.clusters[0].min_quality, 0.0);  // the dent's cluster is the worst
  EXPECT_GT(c.overlap.num_intersecting_cells, 60);
  // Without grouping, the markers would need far more labels than the limit.
  EXPECT_GT(c.overlap.markers.size(), 60u);
  // Also from nearly straight above, where the shifted copies' glyphs on
  // top lie in front of the dent's #0 (drawn back to front by depth before
  // issue 44's fifth round, they covered it).
  expect_clear_views(c, "injected overlaps", true, Vec3{0.1, 0.15, -1.0});
}

// The injected overlaps with a shifted copy of the floating sheared hex
// (a marker fan centred on its cluster's coloured glyph, as gmsh_box's #1
// in the 44c review): from both views and from above, no arrow and no
// marker leader inside a coloured glyph's disc.
TEST(MainViewLabels, FansKeepOffEveryColouredGlyph) {
  HexMesh mesh = injected_overlaps();
  add_shifted_copy(mesh, mesh.hexes.back(), Vec3{0.25, 0.2, 0.1});
  const Case c = analyse(std::move(mesh));
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  const MainViewOptions options;
  const std::vector<Vec3> points = main_view_points(c.mesh, c.topology, c.glyphs);
  std::vector<Vec3> directions =
      choose_main_viewpoints(points, c.glyphs, main_view_aspect(options), 2, options.up, options.fov_y_degrees);
  directions.push_back(Vec3{0.1, 0.15, -1.0});
  std::size_t fans_on_coloured = 0;  // marker groups within 2 radii of a coloured glyph (not #0): the case is built
  for (const Vec3& direction : directions) {
    Scene scene;
    const MainViewLabels labels = main_view_labels(c.mesh, c.topology, c.glyphs, &c.overlap, direction, options,
                                                   &scene, renderer.get());
    for (const std::string& w : arrows_short_of_counts(scene, labels, options))
      ADD_FAILURE() << viewpoint_name(direction, options.up) << ": " << w;
    for (const MainViewLabel& l : labels.labels)
      if (l.kind == MainViewLabel::Kind::marker)
        for (const ScreenDisc& d : labels.coloured_glyphs)
          fans_on_coloured += d.id > 0 && std::hypot(l.anchor.x - d.x, l.anchor.y - d.y) < 2.0 * d.radius ? 1 : 0;
    for (const std::string& w : marks_over_coloured_glyphs(labels)) ADD_FAILURE() << viewpoint_name(direction, options.up) << ": " << w;
  }
  EXPECT_GT(fans_on_coloured, 0u);
}

// View A rings the glyph of a cluster with an inverted vertex in the
// inverted colour (issue 44: inverted clusters looked like poor ones). An
// 8 x 8 x 2 grid whose top centre vertex is pushed down to z = 0.6 (below
// the middle layer: inverted) or to z = 1.5 and 0.3 along x (poor, min
// quality in [0, 0.5), not inverted): with the deep
// dent at least half of the ring's circle, 3 px outside #0's disc, is
// within 40 (RGB distance) of the inverted colour; with the shallow one no
// pixel of the 3D area is.
TEST(MainViewLabels, InvertedClustersWearARing) {
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  const Rgba8 inverted = to_rgba8(kInvertedColor);
  auto near_inverted = [&](const Image& image, int x, int y) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) return false;
    const std::uint8_t* p = image.rgba.data() + pixel_offset(image, x, y);
    return std::hypot(p[0] - inverted.r, p[1] - inverted.g, p[2] - inverted.b) <= 40.0;
  };
  auto dented = [](double z, double shift) {
    HexMesh mesh = test::box_grid(8, 8, 2);
    Vec3& p = mesh.points[static_cast<std::size_t>(4 + 9 * (4 + 9 * 2))];
    p.z = z;
    p.x += shift;
    return analyse(std::move(mesh));
  };
  const MainViewOptions options;  // 1600 x 1200: annotation scale 1
  const Vec3 direction{1.0, -1.0, 1.5};
  const Case deep = dented(0.6, 0.0);
  ASSERT_LT(deep.glyphs.clusters.at(0).min_quality, 0.0);
  const MainViewLabels labels =
      main_view_labels(deep.mesh, deep.topology, deep.glyphs, nullptr, direction, options, nullptr);
  ASSERT_EQ(labels.inverted_glyphs.size(), 1u);
  const Image image = render_main_view(deep.mesh, deep.topology, deep.glyphs, nullptr, direction, options, *renderer);
  const ScreenDisc& worst = labels.inverted_glyphs[0];
  int on = 0;
  constexpr int kSamples = 72;
  for (int i = 0; i < kSamples; ++i) {
    // 3 to 5 px out: the ring's band (3.5 px from the glyph, 2-3 px wide).
    const double a = 2.0 * M_PI * i / kSamples;
    bool hit = false;
    for (double r : {worst.radius + 3.0, worst.radius + 5.0})
      for (int dy = -1; dy <= 1 && !hit; ++dy)
        for (int dx = -1; dx <= 1 && !hit; ++dx)
          hit = near_inverted(image, static_cast<int>(std::lround(worst.x + r * std::cos(a))) + dx,
                              static_cast<int>(std::lround(worst.y + r * std::sin(a))) + dy);
    on += hit ? 1 : 0;
  }
  EXPECT_GE(on, kSamples / 2);
  // The legend names both rings with ring swatches (#0's dark ring in the
  // text colour, the inverted one), unlike the filled near-black square of
  // the coincident vertices.
  const AnnotationStyle style;
  const std::vector<LegendLine> legend = main_legend_lines(deep.glyphs, nullptr, style, options, labels.glyph_scale);
  int rings = 0;
  for (const LegendLine& line : legend) {
    if (line.text == "ring: worst cluster #0") {
      EXPECT_EQ(line.shape, SwatchShape::solid_ring);
      EXPECT_EQ(line.swatch, style.text_color);
      ++rings;
    }
    if (line.text == "ring: inverted (min < 0)") {
      EXPECT_EQ(line.shape, SwatchShape::solid_ring);
      EXPECT_EQ(line.swatch, inverted);
      ++rings;
    }
    if (line.text.starts_with("coincident vertices")) EXPECT_NE(line.shape, SwatchShape::solid_ring);
  }
  EXPECT_EQ(rings, 2);
  // The clusters' coloured edge lines are named with a line swatch in #0's
  // colour and the vertices they surround: #0's size, or the cap when it
  // cuts (47c review: "edges of 48 worst" on a 4-vertex cluster).
  const auto edge_line = [&](const MainViewOptions& o) {
    std::vector<LegendLine> found;
    for (const LegendLine& line : main_legend_lines(deep.glyphs, nullptr, style, o, labels.glyph_scale))
      if (line.text.starts_with("edges at")) found.push_back(line);
    return found;
  };
  const Index size = deep.glyphs.clusters[0].size;
  ASSERT_GE(size, 2);
  ASSERT_LT(size, options.cluster_edge_vertices);
  const std::vector<LegendLine> named = edge_line(options);
  ASSERT_EQ(named.size(), 1u);
  EXPECT_EQ(named[0].text, "edges at #0's " + std::to_string(size) + " vertices");
  EXPECT_EQ(named[0].shape, SwatchShape::thick_line);
  EXPECT_EQ(named[0].swatch, to_rgba8(cluster_color(0, deep.glyphs.options.top_clusters)));
  MainViewOptions capped = options;
  capped.cluster_edge_vertices = 1;
  ASSERT_EQ(edge_line(capped).size(), 1u);
  EXPECT_EQ(edge_line(capped)[0].text, "edges at #0's 1 worst vertex");
  MainViewOptions no_edges = options;
  no_edges.cluster_edge_vertices = 0;
  EXPECT_TRUE(edge_line(no_edges).empty());
  // Overlap not run on this volume mesh: said, without a number.
  for (const LegendLine& line : legend) EXPECT_FALSE(line.text.starts_with("coincident vertices"));
  // The rings begin outside the glyph: its rim is not covered.
  EXPECT_EQ(background_inside_rim(image, worst, options.background), 0);
  const Case shallow = dented(1.5, 0.3);
  ASSERT_FALSE(shallow.glyphs.clusters.empty());
  ASSERT_GE(shallow.glyphs.clusters[0].min_quality, 0.0);
  const MainViewLabels shallow_labels =
      main_view_labels(shallow.mesh, shallow.topology, shallow.glyphs, nullptr, direction, options, nullptr);
  EXPECT_TRUE(shallow_labels.inverted_glyphs.empty());
  const Image shallow_image =
      render_main_view(shallow.mesh, shallow.topology, shallow.glyphs, nullptr, direction, options, *renderer);
  int stray = 0;
  for (int y = shallow_labels.view.y; y < shallow_labels.view.y + shallow_labels.view.height; ++y)
    for (int x = shallow_labels.view.x; x < shallow_labels.view.x + shallow_labels.view.width; ++x)
      stray += near_inverted(shallow_image, x, y) ? 1 : 0;
  EXPECT_EQ(stray, 0);
}

// The shared meshes on which the labels were found wrong (bunny_in: #1 was
// drawn 1 px bigger than #0); the overlap check finds nothing there (so no
// marker labels).
TEST(MainViewLabels, SharedMeshesWithCrowdedGlyphs) {
  const auto data = test::shared_data_dir();
  if (!data) GTEST_SKIP() << "no ../shared/data";
  for (const char* file : {"meshes/livesu2016_skeleton/warrior.mesh", "meshes/gao2016_sweeping/hand7_1.mesh",
                           "meshes/gao2016_sweeping/Dolphin_padded.mesh", "meshes/livesu2015_edgecone/bunny_in.mesh"}) {
    const Case c = analyse(read_hex_mesh(*data / file).mesh);
    ASSERT_GT(c.glyphs.clusters.size(), 5u) << file;
    expect_clear_views(c, file, false);
  }
}

// Pile-ups (issue 44 part V): Dolphin_padded turned about a skew axis and
// mirrored (its glyphs pile up at one end, dolphin_rot of the 44u review:
// labels 200 px from their glyph, leaders over rings; untouched, its #4
// found "no room"), at 1600 x 1200 and at 800 x 600: every coloured
// cluster that shows gets one label whose leader ends on its glyph, no
// two boxes overlap, no leaders cross (expect_clear_views); the labels
// that find no clear place nearby are in the callout columns, stacked in
// the order of their glyphs' y.
TEST(MainViewLabels, PileUpsGoToCalloutColumns) {
  const auto data = test::shared_data_dir();
  if (!data) GTEST_SKIP() << "no ../shared/data";
  HexMesh mesh = read_hex_mesh(*data / "meshes/gao2016_sweeping/Dolphin_padded.mesh").mesh;
  // Rodrigues' rotation by 2.2 rad about (0.3, 1, 0.2), then x mirrored
  // (each hex's corners reordered so that it stays positively oriented).
  const Vec3 k = normalized(Vec3{0.3, 1.0, 0.2});
  const double a = 2.2;
  for (Vec3& p : mesh.points) {
    p = std::cos(a) * p + std::sin(a) * cross(k, p) + (1.0 - std::cos(a)) * dot(k, p) * k;
    p.x = -p.x;
  }
  for (auto& h : mesh.hexes) {
    std::swap(h[1], h[3]);
    std::swap(h[5], h[7]);
  }
  const Case c = analyse(std::move(mesh));
  ASSERT_GT(c.glyphs.clusters.size(), 5u);
  expect_clear_views(c, "Dolphin_padded turned", false);
  MainViewOptions small;
  small.width = 800;
  small.height = 600;
  expect_clear_views(c, "Dolphin_padded turned, 800 x 600", false, std::nullopt, small);
}

// The 44l review's meshes, with room to spare: Dolphin_padded, bunny_1
// turned 90 degrees about y and warrior (leaders over glyphs; none now
// where a way out exists), besides expect_clear_views' rules: each of the
// labelled clusters (#0-#2 since 44r's three colours; the review's "no
// room" for #4 and #3 was of ranks no longer labelled) finds room. Not
// checked: Dolphin_padded's leaders over grey glyphs (its tail pile-up).
TEST(MainViewLabels, EveryClusterFindsRoomAndLeadersPassGlyphsBy) {
  const auto data = test::shared_data_dir();
  if (!data) GTEST_SKIP() << "no ../shared/data";
  HexMesh bunny = read_hex_mesh(*data / "meshes/gao2016_sweeping/bunny_1.mesh").mesh;
  for (Vec3& p : bunny.points) p = Vec3{p.z, p.y, -p.x};
  const Case dolphin = analyse(read_hex_mesh(*data / "meshes/gao2016_sweeping/Dolphin_padded.mesh").mesh);
  expect_clear_views(dolphin, "Dolphin_padded", false, std::nullopt, {}, {.all_labelled = true});
  for (const auto& [name, c] : {std::pair{"bunny_1 turned about y", analyse(std::move(bunny))},
                                std::pair{"warrior", analyse(read_hex_mesh(*data / "meshes/livesu2016_skeleton/warrior.mesh").mesh)}}) {
    ASSERT_GE(c.glyphs.clusters.size(), static_cast<std::size_t>(kLabelledClusterPaletteSize)) << name;
    expect_clear_views(c, name, false, std::nullopt, {}, {.all_labelled = true, .leaders_clear = true});
  }
}

// Whether leader p runs over disc d, by sampling (independent of
// label_layout's leader_over_disc): a point every 0.25 px along it inside
// the disc (its edge 0.5 px in) and more than 1 px nearer its centre than
// the leader's start (a leader heading out of a disc holding its start
// does not run over it).
bool sampled_over_disc(const PlacedLabel& p, const ScreenDisc& d) {
  const double length = std::hypot(p.leader_x1 - p.leader_x0, p.leader_y1 - p.leader_y0);
  const double start = std::hypot(p.leader_x0 - d.x, p.leader_y0 - d.y);
  const int steps = std::max(1, static_cast<int>(std::ceil(4.0 * length)));
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const double r = std::hypot(p.leader_x0 + t * (p.leader_x1 - p.leader_x0) - d.x,
                                p.leader_y0 + t * (p.leader_y1 - p.leader_y0) - d.y);
    if (r < d.radius - 0.5 && r < start - 1.0) return true;
  }
  return false;
}

// Dolphin_padded turned 90 degrees about x (the 44m brief, 44l review C2:
// in view 2 "#3 (15) behind #1" started on #1's disc, at the seam where #3
// shows, and its 320 px leader ran through all of #1 while the upper right
// was empty): no leader runs over the disc of a coloured glyph ranked
// before its own (a disc holding its start counts once the leader heads
// into it, leader_over_disc), besides expect_clear_views' rules.
TEST(MainViewLabels, TurnedDolphinLeadersPassHigherRanksBy) {
  const auto data = test::shared_data_dir();
  if (!data) GTEST_SKIP() << "no ../shared/data";
  HexMesh mesh = read_hex_mesh(*data / "meshes/gao2016_sweeping/Dolphin_padded.mesh").mesh;
  for (Vec3& p : mesh.points) p = Vec3{p.x, -p.z, p.y};
  const Case c = analyse(std::move(mesh));
  expect_clear_views(c, "Dolphin_padded turned about x", false);
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  const MainViewOptions options;
  const std::vector<Vec3> directions = choose_main_viewpoints(main_view_points(c.mesh, c.topology, c.glyphs), c.glyphs,
                                                              main_view_aspect(options), 2, options.up,
                                                              options.fov_y_degrees);
  int pairs = 0;  // (leader, higher-ranked glyph) pairs checked
  for (const Vec3& direction : directions) {
    const MainViewLabels labels =
        main_view_labels(c.mesh, c.topology, c.glyphs, &c.overlap, direction, options, nullptr, renderer.get());
    for (const MainViewLabel& l : labels.labels) {
      if (l.kind != MainViewLabel::Kind::cluster || !l.placement.has_leader) continue;
      for (const ScreenDisc& d : labels.coloured_glyphs)
        if (d.id < l.cluster) {
          ++pairs;
          EXPECT_FALSE(sampled_over_disc(l.placement, d)) << l.text << " over #" << d.id;
        }
    }
  }
  // Since issue 44 part R colours 3 clusters, the reviewer's "#3 behind #1"
  // is grey and unlabelled: the rule is held on the labelled leaders here,
  // and its case is built on purpose in
  // HiddenGlyphsLeadersLeaveTheWorseGlyphsAndRingsBy.
  EXPECT_GT(pairs, 0);
}

// The 2nd-pass review B #3: since 44r colours 3 clusters, the cases of the
// 44m rules ("#3 behind #1", "#4 behind #0") no longer arose on the shared
// meshes. Built on purpose: a 16 x 16 x 8 box of unit hexes, its vertex
// quality 1 but at 3 vertices (by hand), each a cluster of one (glyphs of
// 1.5 mean edges at ratio 1): #0 at the top face's centre (8, 8, 8), 0
// (radius 1.5); #1 at (9, 8, 0), 0.1 (1.35), and #2 at (7, 8, 4), 0.2
// (1.2), apart in 3D, 1 unit either side of #0 seen from nearly straight
// above (view A is orthographic; glyph scale 1): each centre behind #0's
// disc, the outer part of each glyph beside it, beyond #0's ring. Both labels say
// "behind #0", each has a leader, which starts at least 3 px off #0's
// rings (LeadersEndOffTheWorstRings' rule) and runs over no glyph ranked
// before its own (TurnedDolphinLeadersPassHigherRanksBy's rule: #1's
// over #0's; #2's over #0's and #1's; checked by sampling), and all three
// are labelled.
TEST(MainViewLabels, HiddenGlyphsLeadersLeaveTheWorseGlyphsAndRingsBy) {
  Case c;
  c.mesh = test::box_grid(16, 16, 8);
  c.topology = build_topology(c.mesh);
  std::vector<double> quality(c.mesh.points.size(), 1.0);
  const auto at = [&](const Vec3& p) {
    for (std::size_t v = 0; v < c.mesh.points.size(); ++v)
      if (norm(c.mesh.points[v] - p) < 1e-9) return v;
    ADD_FAILURE() << "no vertex at " << p.x << ", " << p.y << ", " << p.z;
    return std::size_t{0};
  };
  quality[at({8, 8, 8})] = 0.0;
  quality[at({9, 8, 0})] = 0.1;
  quality[at({7, 8, 4})] = 0.2;
  c.glyphs = compute_glyphs(c.mesh.points, quality, test::mean_edge_length(c.mesh, c.topology), {.rmax = 1.5});
  ASSERT_EQ(c.glyphs.clusters.size(), 3u);
  EXPECT_EQ(c.glyphs.clusters[1].position.x, 9.0);
  EXPECT_EQ(c.glyphs.clusters[2].position.x, 7.0);
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  MainViewOptions options;
  options.width = 800;
  options.height = 600;
  options.glyph_scale = 1.0;
  const MainViewLabels labels =
      main_view_labels(c.mesh, c.topology, c.glyphs, nullptr, Vec3{0.02, 0.01, -1.0}, options, nullptr, renderer.get());
  // The arrangement: #1's and #2's centres on #0's disc, their discs out of it.
  ASSERT_EQ(labels.coloured_glyphs.size(), 3u);
  const ScreenDisc& worst = labels.worst_glyph;
  for (const ScreenDisc& d : labels.coloured_glyphs) {
    if (d.id == 0) continue;
    const double apart = std::hypot(d.x - worst.x, d.y - worst.y);
    ASSERT_LT(apart, worst.radius) << "#" << d.id << " at " << apart << " px of #0 (radius " << worst.radius << ")";
    ASSERT_GT(apart + d.radius, worst.radius + 2.0) << "#" << d.id << " radius " << d.radius;
  }
  EXPECT_TRUE(labels.hidden_clusters.empty());
  EXPECT_TRUE(labels.unlabelled_clusters.empty());
  const AnnotationStyle style = annotation_style_for(options.height);
  const double rings = worst_rings_extent(worst.radius, false, style);
  int leaders = 0, pairs = 0;
  for (const MainViewLabel& l : labels.labels) {
    if (l.kind != MainViewLabel::Kind::cluster || l.cluster == 0) continue;
    EXPECT_EQ(l.text, "#" + std::to_string(l.cluster) + " (1) behind #0");
    ASSERT_TRUE(l.placement.has_leader) << l.text;
    ++leaders;
    EXPECT_GE(std::hypot(l.placement.leader_x0 - worst.x, l.placement.leader_y0 - worst.y), rings + 3.0 * style.scale)
        << l.text << " starts on #0's rings";
    for (const ScreenDisc& d : labels.coloured_glyphs)
      if (d.id < l.cluster) {
        ++pairs;
        EXPECT_FALSE(sampled_over_disc(l.placement, d)) << l.text << " runs over #" << d.id;
      }
  }
  EXPECT_EQ(leaders, 2);
  EXPECT_EQ(pairs, 3);
}

// Each of the two main views of each named mesh, its labels placed as view A
// places them (scoped by the mesh's name and the view's direction).
void for_each_main_view(std::vector<std::pair<std::string, Case>> meshes, const MainViewOptions& options,
                        Renderer& renderer, const std::function<void(const Case&, const MainViewLabels&)>& check) {
  for (const auto& [name, c] : meshes) {
    const std::vector<Vec3> directions = choose_main_viewpoints(main_view_points(c.mesh, c.topology, c.glyphs), c.glyphs,
                                                                main_view_aspect(options), 2, options.up,
                                                                options.fov_y_degrees);
    for (const Vec3& direction : directions) {
      SCOPED_TRACE(name + " from " + viewpoint_name(direction, options.up));
      check(c, main_view_labels(c.mesh, c.topology, c.glyphs, &c.overlap, direction, options, nullptr, &renderer));
    }
  }
}

// A leader ends on its own glyph's visible pixels a few pixels off #0's
// rings (the 44m brief, 44l review M5: "#4 (63) behind #0" ended within 3
// px of #0's ring on Dolphin_padded and turned 90 degrees about x, and read
// as pointing at #0): every other cluster's leader starts at least 3 px
// (at scale 1) outside the rings' extent.
TEST(MainViewLabels, LeadersEndOffTheWorstRings) {
  const auto data = test::shared_data_dir();
  if (!data) GTEST_SKIP() << "no ../shared/data";
  HexMesh mesh = read_hex_mesh(*data / "meshes/gao2016_sweeping/Dolphin_padded.mesh").mesh;
  HexMesh turned = mesh;
  for (Vec3& p : turned.points) p = Vec3{p.x, -p.z, p.y};
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  const MainViewOptions options;
  const AnnotationStyle style = annotation_style_for(options.height);
  int checked = 0;  // the leaders held to the rule
  for_each_main_view({{"Dolphin_padded", analyse(std::move(mesh))}, {"Dolphin_padded turned about x", analyse(std::move(turned))}},
                     options, *renderer, [&](const Case& c, const MainViewLabels& labels) {
      const ScreenDisc& w = labels.worst_glyph;
      const double rings = worst_rings_extent(w.radius, c.glyphs.clusters.at(0).min_quality < 0.0, style);
      for (const MainViewLabel& l : labels.labels) {
        if (l.kind != MainViewLabel::Kind::cluster || l.cluster == 0 || !l.placement.has_leader) continue;
        const double d = std::hypot(l.placement.leader_x0 - w.x, l.placement.leader_y0 - w.y);
        ++checked;
        EXPECT_GE(d, rings + 3.0 * style.scale) << l.text;
      }
  });
  // Since issue 44 part R colours 3 clusters, #4 (whose leader ended next to
  // #0 on these meshes) is grey and unlabelled: the rule is held on the
  // leaders there are here, and its case is built on purpose in
  // HiddenGlyphsLeadersLeaveTheWorseGlyphsAndRingsBy.
  EXPECT_GT(checked, 0);
}

// #0's own label is exempt from the rule keeping labels out of #0's
// neighbourhood (the 44m brief, 44l review M3: kept out, kitten_1 turned
// 30 degrees about z had `#0 (4)` 10 px from #3's glyph and 44 px from #0's
// ring): in both views of it and of bunny_1 turned 90 degrees about y, #0's
// label box is nearer #0's glyph than any other coloured glyph.
TEST(MainViewLabels, WorstLabelNearerItsGlyphThanAnyOther) {
  const auto data = test::shared_data_dir();
  if (!data) GTEST_SKIP() << "no ../shared/data";
  HexMesh bunny = read_hex_mesh(*data / "meshes/gao2016_sweeping/bunny_1.mesh").mesh;
  for (Vec3& p : bunny.points) p = Vec3{p.z, p.y, -p.x};
  HexMesh kitten = read_hex_mesh(*data / "meshes/gao2016_sweeping/kitten_1.mesh").mesh;
  const double a = M_PI / 6.0;
  for (Vec3& p : kitten.points) p = Vec3{std::cos(a) * p.x - std::sin(a) * p.y, std::sin(a) * p.x + std::cos(a) * p.y, p.z};
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  const MainViewOptions options;
  int checked = 0;
  for_each_main_view({{"bunny_1 turned about y", analyse(std::move(bunny))}, {"kitten_1 turned about z", analyse(std::move(kitten))}},
                     options, *renderer, [&](const Case&, const MainViewLabels& labels) {
      for (const MainViewLabel& l : labels.labels) {
        if (l.kind != MainViewLabel::Kind::cluster || l.cluster != 0) continue;
        ++checked;
        const double own = disc_box_gap(labels.worst_glyph, l.placement.box);
        for (const ScreenDisc& d : labels.coloured_glyphs)
          if (d.id != 0) EXPECT_LT(own, disc_box_gap(d, l.placement.box)) << l.text << " nearer #" << d.id;
      }
  });
  EXPECT_EQ(checked, 4);
}

// The placement without the id image (main before issue 44d) lets leaders
// end off their glyph on warrior and Dolphin_padded: on the background or an
// edge line just outside the glyph's silhouette, and on another glyph drawn
// in front of their own (the reviewer's Dolphin "#7 (10)" on #5, with the
// connected clusters and 8 colours of then; with the bounded clusters and 6
// colours others; with the 2 colours of issue 44 part P round 1, 2 labels a
// view and 3 leaders off their glyph; 5 colours since round 2): the check
// above catches it; with the id
// image nothing is left.
TEST(MainViewLabels, PlacementWithoutIdImageMisnamesGlyphs) {
  const auto data = test::shared_data_dir();
  if (!data) GTEST_SKIP() << "no ../shared/data";
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  std::size_t wrong_with = 0, wrong_without = 0;
  for (const char* file : {"meshes/livesu2016_skeleton/warrior.mesh", "meshes/gao2016_sweeping/Dolphin_padded.mesh"}) {
    const Case c = analyse(read_hex_mesh(*data / file).mesh);
    const MainViewOptions options;
    const std::vector<Vec3> directions = choose_main_viewpoints(main_view_points(c.mesh, c.topology, c.glyphs), c.glyphs,
                                                                main_view_aspect(options), 2, options.up,
                                                                options.fov_y_degrees);
    for (const Vec3& direction : directions) {
      const MainViewLabels with =
          main_view_labels(c.mesh, c.topology, c.glyphs, &c.overlap, direction, options, nullptr, renderer.get());
      const MainViewLabels without = main_view_labels(c.mesh, c.topology, c.glyphs, &c.overlap, direction, options);
      wrong_with += labels_off_their_glyph(with, with.ids).size();
      wrong_without += labels_off_their_glyph(without, with.ids).size();
      EXPECT_TRUE(leaders_on_other_glyphs(with, with.ids).empty());
    }
  }
  EXPECT_EQ(wrong_with, 0u);
  EXPECT_GE(wrong_without, 3u);
}

// bunny_in (the reviewer's case): in view A the inverted #0 (min -0.003)
// was drawn 1 px smaller than #1 (min 0.023), its rim under the rings'
// halo. Every glyph with a ring keeps its rim, and the drawn radii follow
// the ranks.
TEST(MainViewLabels, BunnyInWorstGlyphNotDrawnSmaller) {
  const auto data = test::shared_data_dir();
  if (!data) GTEST_SKIP() << "no ../shared/data";
  const Case c = analyse(read_hex_mesh(*data / "meshes/livesu2015_edgecone/bunny_in.mesh").mesh);
  ASSERT_LT(c.glyphs.clusters.at(0).min_quality, 0.0);
  ASSERT_GT(c.glyphs.clusters.at(1).min_quality, 0.0);
  const MainViewOptions options;
  const std::vector<Vec3> points = main_view_points(c.mesh, c.topology, c.glyphs);
  const std::vector<Vec3> directions =
      choose_main_viewpoints(points, c.glyphs, main_view_aspect(options), 1, options.up, options.fov_y_degrees);
  ASSERT_EQ(directions.size(), 1u);
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  Scene scene;
  const MainViewLabels labels =
      main_view_labels(c.mesh, c.topology, c.glyphs, &c.overlap, directions[0], options, &scene);
  expect_sizes_by_severity(scene, glyph_discs(scene, labels), labels);
  const Image image =
      render_main_view(c.mesh, c.topology, c.glyphs, &c.overlap, directions[0], options, *renderer);
  ASSERT_FALSE(labels.inverted_glyphs.empty());
  EXPECT_EQ(background_inside_rim(image, labels.worst_glyph, options.background), 0);
  for (const ScreenDisc& d : labels.inverted_glyphs)
    EXPECT_EQ(background_inside_rim(image, d, options.background), 0) << d.x << ", " << d.y;
}

// A labelled cluster whose glyph shows no pixel gets no label and its legend
// line says so: an 8 x 8 x 2 grid with two dents on top (its vertex (4, 4)
// pushed below the middle layer, (1, 1) pushed down and sideways: two
// clusters), its id image with cluster #1's pixels turned into edge pixels
// (as if lines hid all of it), laid out again.
TEST(MainViewLabels, AClusterWhoseGlyphShowsNoPixelGetsNoLabel) {
  HexMesh mesh = test::box_grid(8, 8, 2);
  mesh.points[static_cast<std::size_t>(4 + 9 * (4 + 9 * 2))].z = 0.6;
  Vec3& poor = mesh.points[static_cast<std::size_t>(1 + 9 * (1 + 9 * 2))];
  poor.z = 1.5;
  poor.x += 0.3;
  const Case c = analyse(std::move(mesh));
  ASSERT_GE(c.glyphs.clusters.size(), 2u);
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  const MainViewOptions options;
  const std::vector<Vec3> directions = choose_main_viewpoints(main_view_points(c.mesh, c.topology, c.glyphs), c.glyphs,
                                                              main_view_aspect(options), 1, options.up,
                                                              options.fov_y_degrees);
  const MainViewLabels labels =
      main_view_labels(c.mesh, c.topology, c.glyphs, &c.overlap, directions.at(0), options, nullptr, renderer.get());
  ASSERT_TRUE(labels.hidden_clusters.empty());
  Index hidden = kNoIndex;
  for (const MainViewLabel& l : labels.labels)
    if (l.kind == MainViewLabel::Kind::cluster && l.cluster > 0) hidden = l.cluster;
  ASSERT_NE(hidden, kNoIndex);
  IdImage ids = labels.ids;
  std::replace(ids.ids.begin(), ids.ids.end(), kIdGlyph + static_cast<std::uint32_t>(hidden), kIdEdge);
  AnnotationStyle style = annotation_style_for(options.height);
  style.background = options.background;
  const FigureLayout layout = figure_layout(options.width, options.height, !options.title.empty(),
                                            static_cast<int>(std::lround(340 * style.scale)), style);
  ASSERT_EQ(layout.view.x, labels.view.x);
  ASSERT_EQ(layout.view.width, labels.view.width);
  MainViewOptions scaled = options;
  scaled.pixel_scale = style.scale;
  const MainViewLabels again = layout_main_view_labels(c.glyphs, &c.overlap, labels.camera, layout, style, scaled, &ids);
  EXPECT_EQ(again.hidden_clusters, std::vector<Index>{hidden});
  for (const MainViewLabel& l : again.labels) EXPECT_FALSE(l.kind == MainViewLabel::Kind::cluster && l.cluster == hidden);
  EXPECT_EQ(again.labels.size() + 1, labels.labels.size());
  int said = 0;
  for (const LegendLine& line : main_legend_lines(c.glyphs, &c.overlap, style, options, again.glyph_scale,
                                                  again.hidden_clusters))
    if (line.text.starts_with("#" + std::to_string(hidden) + " ")) {
      EXPECT_TRUE(line.text.ends_with(", hidden")) << line.text;
      ++said;
    }
  EXPECT_EQ(said, 1);
}

}  // namespace
}  // namespace hq
