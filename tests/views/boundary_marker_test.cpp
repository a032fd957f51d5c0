// The boundary views' marker of the largest |error| (boundary_error and
// reference_error): on the sample that gives the sampled maximum of
// report.json, and drawn where that sample projects. Renders with OSMesa.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "hqview/boundary/boundary_error.h"
#include "hqview/mesh/topology.h"
#include "hqview/render/osmesa_renderer.h"
#include "hqview/views/boundary_views.h"
#include "hqview/views/overview_views.h"
#include "support/image_probe.h"
#include "support/surface_fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

double wavy_radius(const Vec3& u) { return 1.0 + 0.05 * u.z; }

struct Ball {
  HexMesh mesh = test::hex_ball(4, wavy_radius);
  Topology topo = build_topology(mesh);
  TriSurface sphere = test::icosphere(4);  // chord sag about 5e-3
  BoundaryError error = compute_boundary_error(mesh, topo, sphere);
};

const Ball& ball() {
  static const Ball b;
  return b;
}

TEST(WorstErrorMarker, SitsOnTheSampleOfTheSampledMaximum) {
  const Ball& b = ball();
  const double tol = 1e-12 * b.error.reference_bbox_diagonal;
  const WorstError m = worst_mesh_error(b.mesh, b.topo, b.error);
  ASSERT_TRUE(m.found);
  // report.json's boundary_error.hausdorff_sampled.mesh_to_reference.
  EXPECT_NEAR(std::abs(m.error), b.error.sampled_mesh_to_reference.max, tol);
  // Independently: the sphere is at distance |r - 1| of a point at radius r (within the chord sag).
  EXPECT_NEAR(std::abs(norm(m.position) - 1.0), std::abs(m.error), 6e-3);
  EXPECT_GT(dot(m.normal, m.position), 0.0) << "the outward normal of the hex boundary there";

  const WorstError r = worst_error(b.error.reference_patches, b.sphere.points, b.error.reference_vertex_error);
  ASSERT_TRUE(r.found);
  EXPECT_NEAR(std::abs(r.error), b.error.sampled_reference_to_mesh.max, tol);
  EXPECT_NEAR(norm(r.position), 1.0, 6e-3) << "a point of the reference sphere";
  EXPECT_GT(dot(r.normal, r.position), 0.0);

  // Ties and non-finite values: the first of the largest, NaN skipped.
  const std::array<Vec3, 3> c{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}};
  const std::vector<BoundaryError::ErrorPatch> patches{{c, 0.5, 1.0}, {c, -0.7, 1.0}, {c, NAN, 1.0}};
  const std::vector<Vec3> points{{0, 0, 0}, {5, 5, 5}};
  const WorstError t = worst_error(patches, points, std::vector<double>{NAN, 0.7});
  EXPECT_EQ(t.error, -0.7);
  EXPECT_EQ(t.position.x, 1.0 / 3.0);
  EXPECT_FALSE(worst_error({}, {}, {}).found);
}

// Pixels of the ring colour inside the 3D view, and their centre.
test::ColorPixels ring_pixels(const Image& image, const PixelRect& view) {
  return test::pixels_of_color(image, view, kWorstMarkerColor);
}

TEST(WorstErrorMarker, RingDrawnAroundTheProjectedSample) {
  const Ball& b = ball();
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  BoundaryViewOptions o;
  o.width = 640;
  o.height = 480;
  o.title = "ball";
  for (bool mesh_side : {true, false}) {
    const WorstError m = mesh_side ? worst_mesh_error(b.mesh, b.topo, b.error)
                                   : worst_error(b.error.reference_patches, b.sphere.points,
                                                 b.error.reference_vertex_error);
    // Looking at the sample from outside, a little from the side.
    const Vec3 direction = -1.0 * m.position + Vec3{0.3, 0.2, 0.1};
    const Image image = mesh_side ? render_boundary_error_view(b.mesh, b.topo, b.error, direction, o, *renderer)
                                  : render_reference_error_view(b.sphere, b.error, direction, o, *renderer);
    std::vector<Vec3> points;
    if (mesh_side)
      points = boundary_points(b.mesh, b.topo);
    else
      for (const auto& p : b.error.reference_patches) points.insert(points.end(), p.corners.begin(), p.corners.end());
    const ErrorFigureFrame f = error_figure_frame(points, b.error, boundary_error_scale(b.error), m, direction, o);
    const double aspect = static_cast<double>(f.layout.view.width) / f.layout.view.height;
    const Vec3 ndc = project_to_ndc(f.camera, aspect, m.position);
    const double px = f.layout.view.x + 0.5 * (ndc.x + 1.0) * f.layout.view.width;
    const double py = f.layout.view.y + 0.5 * (1.0 - ndc.y) * f.layout.view.height;
    const test::ColorPixels ring = ring_pixels(image, f.layout.view);
    // A solid ring of radius >= 8 px and core >= 1 px: at least 2 pi 8 pixels.
    EXPECT_GT(ring.count, 50) << (mesh_side ? "mesh" : "reference");
    EXPECT_NEAR(ring.cx, px, 1.5) << (mesh_side ? "mesh" : "reference");
    EXPECT_NEAR(ring.cy, py, 1.5) << (mesh_side ? "mesh" : "reference");
    ASSERT_FALSE(f.bar.swatches.empty());
    EXPECT_NE(f.bar.swatches.back().label.find("max |error|"), std::string::npos) << "the marker's legend entry";
  }
}

}  // namespace
}  // namespace hq
