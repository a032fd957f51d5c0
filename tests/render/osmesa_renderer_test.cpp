// The OSMesa backend, headless. Images are written next to the test binary
// (HQ_RENDER_TEST_OUTPUT_DIR) for people to look at.
#include "hqview/render/osmesa_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <utility>

#include "hqview/core/error.h"
#include "hqview/image/colormap.h"
#include "hqview/image/png.h"
#include "hqview/render/annotate.h"
#include "hqview/views/overview_views.h"
#include "support/fixtures.h"
#include "support/image_probe.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::count_differing;
using test::kWhite;
using test::pixel_at;

std::filesystem::path output_path(const std::string& name) {
  return std::filesystem::path(HQ_RENDER_TEST_OUTPUT_DIR) / name;
}

// One renderer for the whole suite: contexts are cheap but not free.
Renderer& renderer() {
  static const std::unique_ptr<Renderer> instance = make_osmesa_renderer();
  return *instance;
}

// A made-up but plausible field: quality falls from 1 towards the grid's
// highest corner (the one facing the default camera), which is inverted.
std::vector<double> falling_quality(const HexMesh& mesh) {
  Vec3 top;
  for (const Vec3& p : mesh.points) top = {std::max(top.x, p.x), std::max(top.y, p.y), std::max(top.z, p.z)};
  std::vector<double> quality;
  for (const Vec3& p : mesh.points) quality.push_back(1.0 - 0.95 * std::exp(-squared_norm(p - top) / 3.0));
  quality.back() = -0.3;
  return quality;
}

Scene one_triangle(Rgba8 color) {
  Scene scene;
  scene.background = {0, 0, 0, 255};
  TriangleSet set;
  set.positions = {{-1, 0.2f, 0}, {1, 0.2f, 0}, {0, 1, 0}};  // upper half of the view
  set.colors = {color, color, color};
  set.indices = {0, 1, 2};
  set.is_lit = false;
  scene.triangles.push_back(set);
  return scene;
}

Camera front_camera() {
  Camera camera;
  camera.eye = {0, 0, 3};
  camera.target = {0, 0, 0};
  camera.up = {0, 1, 0};
  camera.near_plane = 1;
  camera.far_plane = 5;
  camera.is_perspective = false;
  camera.ortho_height = 2.2;
  return camera;
}

TEST(OsmesaRenderer, RowsAreTopDownAndColoursExact) {
  const Rgba8 red{230, 20, 10, 255};
  const Image image = renderer().render(one_triangle(red), front_camera(), 64, 48);
  ASSERT_EQ(image.width, 64);
  ASSERT_EQ(image.height, 48);
  ASSERT_EQ(image.rgba.size(), 64u * 48u * 4u);
  EXPECT_EQ(pixel_at(image, 32, 12), red) << "the triangle is in the top half";
  EXPECT_EQ(pixel_at(image, 32, 40), (Rgba8{0, 0, 0, 255}));
  EXPECT_EQ(pixel_at(image, 2, 2), (Rgba8{0, 0, 0, 255}));
}

// Lit shading against the definitions: sRGB to linear, times ambient plus
// diffuse, back to sRGB, rounded to 8 bits. 256 quads in one set, each in its
// own colour (so the shader linearises per fragment), facing the camera.
TEST(OsmesaRenderer, ShadingFollowsTheSrgbCurves) {
  auto to_linear = [](double c) { return c >= 0.04045 ? std::pow((c + 0.055) / 1.055, 2.4) : c / 12.92; };
  auto to_srgb = [](double c) { return c >= 0.0031308 ? 1.055 * std::pow(c, 1.0 / 2.4) - 0.055 : 12.92 * c; };
  // The renderer's headlight, (0, 0.35, 0.94) normalised, on a normal (0, 0, 1).
  const double shade = 0.25 + 0.75 * 0.94 / std::sqrt(0.35 * 0.35 + 0.94 * 0.94);
  auto expected = [&](std::uint8_t byte) {
    return static_cast<int>(std::lround(255.0 * to_srgb(to_linear(byte / 255.0) * shade)));
  };
  // Cell (i, j) of a 16x16 grid over [-1, 1]^2; at 176x176 pixels
  // (ortho height 2.2) a cell is 10 pixels wide, its centre pixel 13 + 10 i.
  Scene scene;
  scene.background = {0, 0, 0, 255};
  TriangleSet set;
  auto color_of = [](int k) {
    return Rgba8{static_cast<std::uint8_t>(k), static_cast<std::uint8_t>(255 - k),
                 static_cast<std::uint8_t>((37 * k + 11) % 256), 255};
  };
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) {
      const float x0 = -1.0f + 0.125f * static_cast<float>(i), y1 = 1.0f - 0.125f * static_cast<float>(j);
      const auto base = static_cast<std::uint32_t>(set.positions.size());
      set.positions.insert(set.positions.end(), {{x0, y1 - 0.125f, 0}, {x0 + 0.125f, y1 - 0.125f, 0},
                                                 {x0 + 0.125f, y1, 0}, {x0, y1, 0}});
      set.normals.insert(set.normals.end(), 4, Vec3f{0, 0, 1});
      set.colors.insert(set.colors.end(), 4, color_of(16 * j + i));
      set.indices.insert(set.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  scene.triangles.push_back(set);
  const Image image = renderer().render(scene, front_camera(), 176, 176);
  int off_by_one = 0;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) {
      const Rgba8 c = color_of(16 * j + i), p = pixel_at(image, 13 + 10 * i, 13 + 10 * j);
      const std::array<std::pair<std::uint8_t, std::uint8_t>, 3> channels{{{c.r, p.r}, {c.g, p.g}, {c.b, p.b}}};
      for (const auto& [in, out] : channels) {
        const int want = expected(in);
        EXPECT_LE(std::abs(out - want), 1) << "cell " << i << "," << j << ": input " << int(in) << " gives " << int(out)
                                           << ", the curves give " << want;
        off_by_one += out != want;
      }
    }
  // The shader's curves are within 0.001/255 of the exact ones: a value
  // moves only where the exact one lies that close to a rounding boundary.
  EXPECT_LE(off_by_one, 8) << "of 768 channel values";
}

TEST(OsmesaRenderer, SizeChangesAndManyFrames) {
  for (int size : {17, 200, 33, 200}) {
    const Image image = renderer().render(one_triangle({0, 200, 0, 255}), front_camera(), size, size + 3);
    EXPECT_EQ(image.width, size);
    EXPECT_EQ(image.height, size + 3);
    EXPECT_GT(count_differing(image, {0, 0, size, size + 3}, {0, 0, 0, 255}), size);
  }
}

TEST(OsmesaRenderer, LinesShowOnTopOfCoincidentTriangles) {
  Scene scene = one_triangle({200, 200, 200, 255});
  LineSet line;
  line.positions = {{-0.5f, 0.4f, 0}, {0.5f, 0.4f, 0}};
  line.colors = {{0, 0, 255, 255}, {0, 0, 255, 255}};
  line.indices = {0, 1};
  line.width = 2.0f;
  scene.lines.push_back(line);
  const Image image = renderer().render(scene, front_camera(), 100, 100);
  // y = 0.4 in a 2.2-high view: row (1.1 - 0.4) / 2.2 * 100 = 31.8.
  bool found = false;
  for (int y = 28; y < 36; ++y) found |= pixel_at(image, 50, y) == Rgba8{0, 0, 255, 255};
  EXPECT_TRUE(found);
}

TEST(OsmesaRenderer, OverlayShowsOverCloserGeometryAndHidesOnlyItself) {
  // An opaque grey triangle in front (z = 0.5, nearer the eye at z = 3); the
  // overlay's red triangle behind it (z = -0.5) and, over the left half, a
  // green one between them (z = 0): the overlay wins over the grey one, and
  // within the overlay the nearer green one wins.
  Scene scene = one_triangle({200, 200, 200, 255});
  for (Vec3f& p : scene.triangles[0].positions) p.z = 0.5f;
  TriangleSet red = one_triangle({230, 20, 10, 255}).triangles[0];
  for (Vec3f& p : red.positions) p.z = -0.5f;
  TriangleSet green;
  green.positions = {{-1, 0.2f, 0}, {0, 0.2f, 0}, {-0.5f, 1, 0}};
  green.colors.assign(3, {0, 200, 0, 255});
  green.indices = {0, 1, 2};
  green.is_lit = false;
  scene.overlay = {red, green};
  const Image image = renderer().render(scene, front_camera(), 100, 100);
  // Rows: y = 0.4 is row (1.1 - 0.4) / 2.2 * 100 = 32; x = 0.3 is column 64.
  EXPECT_EQ(pixel_at(image, 64, 32), (Rgba8{230, 20, 10, 255}));
  // x = -0.5 is column 27: inside green (x in [-0.9, -0.1] at y = 0.4).
  EXPECT_EQ(pixel_at(image, 27, 32), (Rgba8{0, 200, 0, 255}));
  EXPECT_EQ(pixel_at(image, 50, 80), (Rgba8{0, 0, 0, 255})) << "background below the triangles";
}

// render_ids (issue 44's id image): two spheres, the nearer (id 7, z = 0.5)
// over the left part of the farther (id 600000, z = 0), a line in front
// (id 2) and an overlay triangle (id 3) behind everything: each pixel holds
// the id seen there exactly (no lighting, blending or filtering mixes two
// ids), the translucent set is left out and the background keeps its id.
TEST(OsmesaRenderer, IdImagesHoldTheVisibleIdExactly) {
  Scene scene;
  scene.background = id_color(0);
  SphereSet spheres;
  spheres.centers = {{0.3f, 0, 0}, {-0.3f, 0, 0.5f}};
  spheres.radii = {0.6f, 0.4f};
  spheres.colors = {id_color(600000), id_color(7)};
  scene.spheres.push_back(spheres);
  LineSet line;
  line.positions = {{-1, -0.8f, 0.9f}, {1, -0.8f, 0.9f}};
  line.colors = {id_color(2), id_color(2)};
  line.indices = {0, 1};
  line.width = 3.0f;
  scene.lines.push_back(line);
  TriangleSet glass = one_triangle({9, 9, 9, 40}).triangles[0];
  for (Vec3f& p : glass.positions) p.z = 1.0f;
  scene.translucent.push_back(glass);
  TriangleSet overlay;
  overlay.positions = {{0.8f, 0.8f, -1}, {1, 0.8f, -1}, {0.9f, 1, -1}};
  overlay.colors.assign(3, id_color(3));
  overlay.indices = {0, 1, 2};
  scene.overlay.push_back(overlay);
  const IdImage ids = renderer().render_ids(scene, front_camera(), 110, 110);
  ASSERT_EQ(ids.width, 110);
  ASSERT_EQ(ids.height, 110);
  // x = -0.3 is column 40, x = 0.6 column 85, y = 0 row 55, y = -0.8 row 95,
  // (0.9, 0.9) pixel (100, 10) (50 px per model unit).
  EXPECT_EQ(ids.at(40, 55), 7u);
  EXPECT_EQ(ids.at(85, 55), 600000u);
  EXPECT_EQ(ids.at(55, 95), 2u);
  EXPECT_EQ(ids.at(100, 12), 3u);
  EXPECT_EQ(ids.at(5, 5), 0u);
  // Every pixel is one of the ids drawn: none is a blend.
  for (std::uint32_t id : ids.ids) EXPECT_TRUE(id == 0 || id == 2 || id == 3 || id == 7 || id == 600000) << id;
  // The near sphere's pixels form its disc (radius 20 px) less nothing.
  const auto near = static_cast<int>(std::count(ids.ids.begin(), ids.ids.end(), 7u));
  EXPECT_NEAR(near, M_PI * 20 * 20, 40);
  // The image render of the same scene is unchanged by an id render.
  const Image before = renderer().render(scene, front_camera(), 110, 110);
  (void)renderer().render_ids(scene, front_camera(), 110, 110);
  EXPECT_EQ(before.rgba, renderer().render(scene, front_camera(), 110, 110).rgba);
}

TEST(OsmesaRenderer, RejectsBadInput) {
  EXPECT_THROW(renderer().render(Scene{}, front_camera(), 0, 10), RenderError);
  Scene scene = one_triangle({1, 2, 3, 255});
  scene.triangles[0].indices = {0, 1, 3};
  EXPECT_THROW(renderer().render(scene, front_camera(), 10, 10), RenderError);
  scene = one_triangle({1, 2, 3, 255});
  scene.triangles[0].colors.pop_back();
  EXPECT_THROW(renderer().render(scene, front_camera(), 10, 10), RenderError);
}

TEST(QualityOverview, Grid3RendersAFigure) {
  const HexMesh mesh = test::grid(3);
  const Topology topology = build_topology(mesh);
  const std::vector<double> quality = falling_quality(mesh);
  OverviewOptions options;
  options.title = "grid(3): vertex quality";
  const Image image = render_quality_overview(mesh, topology, quality, options, renderer());
  test::write_png_file(image, output_path("overview_grid3.png"));

  ASSERT_EQ(image.width, 1600);
  ASSERT_EQ(image.height, 1200);
  ASSERT_EQ(image.rgba.size(), 1600u * 1200u * 4u);

  const FigureLayout layout = quality_overview_frame(mesh, topology, quality, options).layout;
  // The mesh fills the middle of the view; its centre pixel is not background.
  const int cx = layout.view.x + layout.view.width / 2, cy = layout.view.y + layout.view.height / 2;
  EXPECT_NE(pixel_at(image, cx, cy), kWhite);
  const int mesh_pixels = count_differing(image, layout.view, kWhite);
  EXPECT_GT(mesh_pixels, layout.view.width * layout.view.height / 5);
  EXPECT_LT(mesh_pixels, layout.view.width * layout.view.height * 9 / 10) << "the mesh is framed with a margin";
  // Shading: the three visible sides of the grid differ in brightness, and
  // the striking end of the map shows where the quality is low.
  int reds = 0;
  for (int y = layout.view.y; y < layout.view.y + layout.view.height; y += 2)
    for (int x = layout.view.x; x < layout.view.x + layout.view.width; x += 2) {
      const Rgba8 c = pixel_at(image, x, y);
      reds += c.r > 120 && c.g < 90 && c.b < 90;
    }
  EXPECT_GT(reds, 50);
  // The legend: a bar and text in the right panel; the title band has text.
  // (The bar at most 0.18 of the figure's height since the 45t review, so
  // that index.html shows the whole legend at page load: 18,538 pixels.)
  EXPECT_GT(count_differing(image, layout.legend, kWhite), 15000);
  EXPECT_GT(count_differing(image, layout.title, kWhite), 500);
  // Nothing of the 3D view leaks into the legend's border column.
  EXPECT_EQ(count_differing(image, {1600 - 4, 0, 4, 1200}, kWhite), 0);

  // Deterministic, byte for byte.
  const Image again = render_quality_overview(mesh, topology, quality, options, renderer());
  EXPECT_TRUE(again.rgba == image.rgba);
}

TEST(QualityOverview, SmallFigureStillLaysOut) {
  const HexMesh mesh = test::grid(2);
  const Topology topology = build_topology(mesh);
  OverviewOptions options;
  options.width = 480;
  options.height = 360;
  const Image image = render_quality_overview(mesh, topology, falling_quality(mesh), options, renderer());
  test::write_png_file(image, output_path("overview_grid2_small.png"));
  EXPECT_EQ(image.width, 480);
  EXPECT_EQ(image.height, 360);
  EXPECT_NE(pixel_at(image, 150, 200), kWhite);
}

}  // namespace
}  // namespace hq
