// View fem_error_density: the colour scale, the cells it draws, and on a
// rendered box with an injected bad region that the region's pixels carry
// the high end of the map (measured on the image by projecting its faces).
#include "hqview/views/error_density_views.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "hqview/fem/fem_element_field.h"
#include "hqview/fem/poisson_check.h"
#include "hqview/image/colormap.h"
#include "hqview/render/osmesa_renderer.h"
#include "support/fixtures.h"
#include "support/image_probe.h"

namespace hq {
namespace {

// Redness r / (b + 1): the diffuse shading scales a face's r, g, b alike, so
// this ratio keeps where on the map (pale blue-grey low, red high) a pixel is.
double redness(Rgba8 c) { return c.r / (c.b + 1.0); }
double redness(Color c) { return redness(to_rgba8(c)); }

TEST(ErrorDensityView, LogScaleHighIsTheMapsRedEnd) {
  const std::vector<double> d = {1e-3, 1e-2, 0.1, std::nan(""), -1.0, 0.05};
  const ErrorDensityScale s = error_density_scale(d);
  EXPECT_DOUBLE_EQ(s.hi, 0.1);
  EXPECT_DOUBLE_EQ(s.lo, 1e-3);
  EXPECT_EQ(to_rgba8(error_density_color(0.1, s)), to_rgba8(sample_quality_map(0.0)));
  EXPECT_EQ(to_rgba8(error_density_color(1e-3, s)), to_rgba8(sample_quality_map(1.0)));
  EXPECT_EQ(to_rgba8(error_density_color(1e-2, s)), to_rgba8(sample_quality_map(0.5)));  // log: the middle
  EXPECT_EQ(to_rgba8(error_density_color(std::nan(""), s)), to_rgba8(kUndefinedColor));
  const ColorBar bar = error_density_color_bar(s);
  EXPECT_DOUBLE_EQ(bar.min_value, -3.0);
  EXPECT_DOUBLE_EQ(bar.max_value, -1.0);
  ASSERT_EQ(bar.ticks.size(), 3u);  // 0.001, 0.01, 0.1 (max)
  EXPECT_EQ(bar.ticks[1].label, "0.01");
}

TEST(ErrorDensityView, CellsUnderTheThresholdAndTheDensest) {
  const std::vector<double> sj = {0.9, 0.3, 0.95, 0.8, 1e30};
  const std::vector<double> d = {0.1, 0.2, 0.9, 0.3, 0.1};
  ErrorDensityViewOptions o;
  o.quality_threshold = 0.5;
  o.densest_fraction = 0.01;  // one hex: #2
  EXPECT_EQ(error_density_cells(sj, d, o), (std::vector<Index>{1, 2, 4}));
}

// A 10^3 unit box whose interior vertices with z >= 0.6 and x, y in
// [0.3, 0.7] moved by up to 0.45 h: the hexes using them (the top layer's
// among them, with faces on the top) are the bad region.
TEST(ErrorDensityView, TheBadRegionCarriesTheHighEndOfTheMap) {
  const int n = 10;
  HexMesh mesh = test::grid(n);
  std::vector<char> moved(mesh.points.size(), 0);
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    Vec3& p = mesh.points[v];
    const bool interior = p.x > 0 && p.x < n && p.y > 0 && p.y < n && p.z > 0 && p.z < n;
    p = p / static_cast<double>(n);
    if (interior && p.z >= 0.6 - 1e-9 && p.x >= 0.3 - 1e-9 && p.x <= 0.7 + 1e-9 && p.y >= 0.3 - 1e-9 &&
        p.y <= 0.7 + 1e-9) {
      for (int a = 0; a < 3; ++a) {
        const double t = std::sin(12.9898 * static_cast<double>(v) + 78.233 * a) * 43758.5453;
        p[a] += 0.45 * 2 * (t - std::floor(t) - 0.5) / n;
      }
      moved[v] = 1;
    }
  }
  const Topology topology = build_topology(mesh);
  const PoissonCheck check = run_poisson_check(mesh, topology, compute_fem_elements(mesh));
  ASSERT_TRUE(check.skipped.empty()) << check.skipped;
  const std::vector<double>& density = check.cell_error_density;
  ErrorDensityViewOptions options;
  options.width = 800;
  options.height = 600;
  const std::unique_ptr<Renderer> renderer = make_osmesa_renderer();
  const Vec3 direction = choose_error_density_viewpoint(mesh, topology, density, options);
  Camera camera;
  PixelRect view;
  const Image image =
      render_error_density_boundary(mesh, topology, density, direction, options, *renderer, &camera, &view);
  const Mat4 to_ndc =
      projection_matrix(camera, static_cast<double>(view.width) / view.height) * view_matrix(camera);
  const ErrorDensityScale scale = error_density_scale(density);
  std::vector<double> region, rest;
  for (Index face : topology.boundary_faces) {
    const Quad& q = topology.faces[static_cast<std::size_t>(face)];
    Vec3 c;
    for (Index v : q) c = c + mesh.points[static_cast<std::size_t>(v)] / 4.0;
    const Vec3 outward = c - Vec3{0.5, 0.5, 0.5};
    // Only faces turned to the camera (a box: nothing hides them).
    const Vec3 normal = std::abs(outward.z) > 0.499 ? Vec3{0, 0, outward.z} : std::abs(outward.x) > 0.499 ? Vec3{outward.x, 0, 0} : Vec3{0, outward.y, 0};
    if (dot(normal, camera.target - camera.eye) >= 0) continue;
    const Vec3 ndc = transform_point(to_ndc, c);
    const int x = view.x + static_cast<int>(std::lround((ndc.x + 1) / 2 * view.width));
    const int y = view.y + static_cast<int>(std::lround((1 - ndc.y) / 2 * view.height));
    const Index h = topology.face_hexes[static_cast<std::size_t>(topology.face_hex_offsets[static_cast<std::size_t>(face)])];
    bool bad = false;
    for (Index v : mesh.hexes[static_cast<std::size_t>(h)]) bad = bad || moved[static_cast<std::size_t>(v)];
    (bad ? region : rest).push_back(redness(test::pixel_at(image, x, y)));
  }
  ASSERT_GE(region.size(), 9u);
  ASSERT_GE(rest.size(), 100u);
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  // The region's pixels sit in the upper half of the map (redder than its
  // middle, t = 0.5) and redder than the rest's.
  EXPECT_GT(median(region), redness(sample_quality_map(0.5))) << median(region) << " vs " << median(rest);
  EXPECT_GT(median(region), 1.25 * median(rest)) << median(region) << " vs " << median(rest);
  (void)scale;
}

}  // namespace
}  // namespace hq
