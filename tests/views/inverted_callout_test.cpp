// The rings of the inverted cells on the overview (inverted_callout.h): a
// grid with inverted hexes deep inside (no blue on the boundary) gets a
// dashed ring, drawn where those hexes project, and a label saying they are
// inside; a dent on a face in sight gets a solid ring. Rendered with OSMesa
// and judged on the figure's pixels, the projection computed here.
#include "hqview/views/inverted_callout.h"

#include <gtest/gtest.h>

#include <memory>

#include "hqview/mesh/topology.h"
#include "hqview/quality/quality_field.h"
#include "hqview/render/osmesa_renderer.h"
#include "hqview/render/upright.h"
#include "hqview/views/overview_views.h"
#include "support/fixtures.h"
#include "support/image_probe.h"

namespace hq {
namespace {

struct Case {
  HexMesh mesh;
  Topology topology;
  QualityField quality;
  std::vector<Index> inverted;
};

Case make_case(HexMesh mesh) {
  Case c{std::move(mesh), {}, {}, {}};
  c.topology = build_topology(c.mesh);
  c.quality = compute_quality(c.mesh, c.topology);
  for (std::size_t h = 0; h < c.mesh.hexes.size(); ++h)
    if (c.quality.cell_scaled_jacobian[h] <= 0.0) c.inverted.push_back(static_cast<Index>(h));
  return c;
}

// The overview's view rectangle and camera, as render_quality_overview makes
// them (its legend has the ring's entry).
struct Frame {
  PixelRect view;
  Camera camera;
};
Frame overview_frame(const Case& c, const OverviewOptions& o) {
  const AnnotationStyle style = annotation_style_for(o.height);
  ColorBar bar = overview_color_bar(c.topology, c.quality.vertex_quality);
  bar.swatches.push_back({to_color(kCalloutColor), "ring: inverted hexes"});
  const FigureLayout layout = figure_layout(o.width, o.height, !o.title.empty(), color_bar_width(bar, style), style);
  const double aspect = static_cast<double>(layout.view.width) / layout.view.height;
  return {layout.view, fit_camera_to_points(boundary_points(c.mesh, c.topology), three_quarter_view(o.up), aspect,
                                            {.up = o.up})};
}

// The mean screen position of the inverted hexes' centres.
std::pair<double, double> projected_centre(const Case& c, const Frame& f) {
  const double aspect = static_cast<double>(f.view.width) / f.view.height;
  double x = 0, y = 0;
  for (Index h : c.inverted) {
    Vec3 centre;
    for (Index v : c.mesh.hexes[static_cast<std::size_t>(h)]) centre = centre + 0.125 * c.mesh.points[static_cast<std::size_t>(v)];
    const Vec3 ndc = project_to_ndc(f.camera, aspect, centre);
    x += f.view.x + 0.5 * (ndc.x + 1.0) * f.view.width;
    y += f.view.y + 0.5 * (1.0 - ndc.y) * f.view.height;
  }
  return {x / c.inverted.size(), y / c.inverted.size()};
}

// Pixels of the ring colour in the view within `within` pixels of (x, y).
test::ColorPixels ring_pixels(const Image& image, const PixelRect& view, double x, double y, double within) {
  return test::pixels_of_color(image, view, kCalloutColor, x, y, within);
}

TEST(InvertedCallout, RingsInvertedHexesDeepInsideWhereTheyProject) {
  // A 9^3 grid; interior vertex (6, 2, 6) pushed 1.7 cells along -x past
  // its neighbour: the hexes around it invert, none touches the boundary.
  HexMesh mesh = test::box_grid(9, 9, 9);
  for (Vec3& p : mesh.points)
    if (p.x == 6.0 && p.y == 2.0 && p.z == 6.0) p.x -= 1.7;
  const Case c = make_case(std::move(mesh));
  ASSERT_FALSE(c.inverted.empty());
  for (std::size_t v = 0; v < c.mesh.points.size(); ++v) {
    const Vec3& p = c.mesh.points[v];
    if (p.x == 0 || p.y == 0 || p.z == 0 || p.x == 9 || p.y == 9 || p.z == 9) {
      ASSERT_GE(c.quality.vertex_quality[v], 0.0) << "a boundary vertex is inverted: the case is not 'inside'";
    }
  }
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  OverviewOptions o;
  o.width = 800;
  o.height = 600;
  o.inverted_cells = c.inverted;
  const Image image = render_quality_overview(c.mesh, c.topology, c.quality.vertex_quality, o, *renderer);
  const Frame f = overview_frame(c, o);
  const auto [x, y] = projected_centre(c, f);

  // The callout: one group, not on the boundary, nothing in sight.
  const std::vector<InvertedCallout> callouts = inverted_callouts(
      c.mesh, c.topology, c.inverted, c.quality.vertex_quality, f.camera, f.view, 13.0, *renderer);
  ASSERT_EQ(callouts.size(), 1u);
  EXPECT_EQ(callouts[0].num_cells, static_cast<int>(c.inverted.size()));
  EXPECT_FALSE(callouts[0].on_boundary);
  EXPECT_EQ(callouts[0].visible_pixels, 0);
  EXPECT_EQ(inverted_callout_label(callouts[0], "hex", 1e6),
            std::to_string(c.inverted.size()) + " inverted hexes, inside");

  // The ring's pixels in the figure: a ring (dashed, half its circumference)
  // of radius >= 13 px around the projected hexes.
  const test::ColorPixels ring = ring_pixels(image, f.view, x, y, 0.45 * f.view.height);
  EXPECT_GT(ring.count, 40);
  EXPECT_NEAR(ring.cx, x, 4.0);
  EXPECT_NEAR(ring.cy, y, 4.0);
  // Without cells there is no ring at all.
  o.inverted_cells.clear();
  const Image plain = render_quality_overview(c.mesh, c.topology, c.quality.vertex_quality, o, *renderer);
  EXPECT_EQ(ring_pixels(plain, f.view, x, y, 1e9).count, 0);
}

TEST(InvertedCallout, ADentInSightGetsASolidRing) {
  // Vertex (3, 0, 2) of the -y face (in the three-quarter view of +z)
  // pushed 1.6 cells inwards: the hexes behind it are inverted at that
  // boundary corner, painted blue where the eye sees.
  HexMesh mesh = test::box_grid(6, 6, 4);
  for (Vec3& p : mesh.points)
    if (p.x == 3.0 && p.y == 0.0 && p.z == 2.0) p.y += 1.6;
  const Case c = make_case(std::move(mesh));
  ASSERT_FALSE(c.inverted.empty());
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  OverviewOptions o;
  o.width = 800;
  o.height = 600;
  const Frame f = overview_frame(c, o);
  const std::vector<InvertedCallout> callouts = inverted_callouts(
      c.mesh, c.topology, c.inverted, c.quality.vertex_quality, f.camera, f.view, 13.0, *renderer);
  ASSERT_EQ(callouts.size(), 1u);
  EXPECT_TRUE(callouts[0].on_boundary);
  EXPECT_GT(callouts[0].visible_pixels, 20);
  EXPECT_TRUE(callout_in_sight(callouts[0]));
  // Seen from the back (the +y side), the dent is hidden.
  const Camera back = fit_camera_to_points(boundary_points(c.mesh, c.topology), Vec3{0, -1, -0.5},
                                           static_cast<double>(f.view.width) / f.view.height);
  const std::vector<InvertedCallout> hidden = inverted_callouts(
      c.mesh, c.topology, c.inverted, c.quality.vertex_quality, back, f.view, 13.0, *renderer);
  ASSERT_EQ(hidden.size(), 1u);
  EXPECT_EQ(hidden[0].visible_pixels, 0);
  EXPECT_NE(inverted_callout_label(hidden[0], "hex", 1e6).find(", hidden"), std::string::npos);
  // The figure: a solid ring (more pixels than a dashed one of the same radius) around the projected hexes.
  o.inverted_cells = c.inverted;
  const Image image = render_quality_overview(c.mesh, c.topology, c.quality.vertex_quality, o, *renderer);
  const auto [x, y] = projected_centre(c, f);
  const test::ColorPixels ring = ring_pixels(image, f.view, x, y, callouts[0].radius + 3.0);
  EXPECT_GT(ring.count, static_cast<int>(2 * 3.14159 * callouts[0].radius * 0.8));
  EXPECT_NEAR(ring.cx, x, 4.0);
  EXPECT_NEAR(ring.cy, y, 4.0);
}

}  // namespace
}  // namespace hq
