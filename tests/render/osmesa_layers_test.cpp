// The OSMesa backend's sphere impostors, arrows and translucent triangles,
// on tiny scenes with pixel assertions.
#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "hqview/image/png.h"
#include "support/fixtures.h"

#include "hqview/render/osmesa_renderer.h"
#include "hqview/render/scene_shapes.h"
#include "support/image_probe.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::pixel_at;

Renderer& renderer() {
  static const std::unique_ptr<Renderer> instance = make_osmesa_renderer();
  return *instance;
}

const Rgba8 kBlack{0, 0, 0, 255};

Camera front_camera(bool perspective) {
  Camera camera;
  camera.eye = {0, 0, 5};
  camera.target = {0, 0, 0};
  camera.up = {0, 1, 0};
  camera.near_plane = 1;
  camera.far_plane = 10;
  camera.is_perspective = perspective;
  camera.ortho_height = 4.0;
  camera.fov_y_degrees = 2.0 * std::atan(2.0 / 5.0) * 180.0 / M_PI;  // the z = 0 plane spans y in [-2, 2]
  return camera;
}

Scene sphere_scene(Vec3f centre, float radius, Rgba8 color) {
  Scene scene;
  scene.background = kBlack;
  SphereSet spheres;
  spheres.centers = {centre};
  spheres.radii = {radius};
  spheres.colors = {color};
  scene.spheres.push_back(spheres);
  return scene;
}

bool is_reddish(Rgba8 p) { return p.r > 60 && p.r > 2 * p.g && p.r > 2 * p.b; }

TEST(SphereImpostor, CoversItsDiscAndNothingElse) {
  for (bool perspective : {false, true}) {
    const Image image =
        renderer().render(sphere_scene({0, 0, 0}, 1.0f, {220, 30, 30, 255}), front_camera(perspective), 80, 80);
    // The sphere spans a disc of radius 20 pixels around the centre.
    EXPECT_TRUE(is_reddish(pixel_at(image, 40, 40))) << "centre, perspective " << perspective;
    EXPECT_TRUE(is_reddish(pixel_at(image, 40, 24))) << "inside the disc";
    EXPECT_EQ(pixel_at(image, 40, 14), kBlack) << "outside the disc";
    EXPECT_EQ(pixel_at(image, 24, 24), kBlack) << "the quad's corner is discarded";
    EXPECT_EQ(pixel_at(image, 2, 2), kBlack) << "background";
    // Lit from above: the upper part is brighter than the lower part.
    EXPECT_GT(pixel_at(image, 40, 30).r, pixel_at(image, 40, 54).r);
  }
}

TEST(SphereImpostor, WritesTheSpheresDepth) {
  // A green square at z = 0.5 in front of the sphere's centre but behind its
  // front cap (z = 1): the cap's centre wins, the sphere's rim loses.
  Scene scene = sphere_scene({0, 0, 0}, 1.0f, {220, 30, 30, 255});
  TriangleSet square;
  const Rgba8 green{20, 200, 20, 255};
  square.positions = {{-2, -2, 0.5f}, {2, -2, 0.5f}, {2, 2, 0.5f}, {-2, 2, 0.5f}};
  square.colors = {green, green, green, green};
  square.indices = {0, 1, 2, 0, 2, 3};
  square.is_lit = false;
  scene.triangles.push_back(square);
  const Image image = renderer().render(scene, front_camera(false), 80, 80);
  EXPECT_TRUE(is_reddish(pixel_at(image, 40, 40))) << "the sphere's cap is in front of the square";
  EXPECT_EQ(pixel_at(image, 40, 21), green) << "near the rim the sphere is behind the square";
  EXPECT_EQ(pixel_at(image, 5, 5), green);
}

bool is_greyish(Rgba8 p) { return p.r > 40 && std::abs(p.r - p.g) < 12 && std::abs(p.r - p.b) < 12; }

TEST(SphereImpostor, ASetOverOtherSpheresShowsInFrontOfCloserOnes) {
  // A grey sphere in front of (closer than) a red one and a blue one, the
  // red one also in front of the blue one. Without the flag the grey one
  // hides the red one's centre; with it, the red and blue spheres (the
  // flagged set, in the order red, blue) show over the grey one, and the
  // red one over the blue one (back to front within the set), while a
  // line in front of the red one still shows (depth is written).
  for (bool over : {false, true}) {
    Scene scene;
    scene.background = kBlack;
    SphereSet grey;
    grey.centers = {{0, 0, 2}};
    grey.radii = {0.8f};
    grey.colors = {{128, 128, 128, 255}};
    SphereSet ranked;
    ranked.over_other_spheres = over;
    ranked.centers = {{0, 0, 0}, {0.5f, 0, -1}};  // red first: the set's order is not the drawing order
    ranked.radii = {0.6f, 1.0f};
    ranked.colors = {{220, 30, 30, 255}, {30, 30, 220, 255}};
    scene.spheres = {grey, ranked};
    LineSet line;
    line.positions = {{-2, -0.25f, 3}, {2, -0.25f, 3}};
    line.colors = {{20, 200, 20, 255}, {20, 200, 20, 255}};
    line.indices = {0, 1};
    line.width = 3.0f;
    scene.lines.push_back(line);
    const Image image = renderer().render(scene, front_camera(false), 80, 80);
    if (over) {
      EXPECT_TRUE(is_reddish(pixel_at(image, 40, 40))) << "the red sphere over the grey one";
      EXPECT_TRUE(is_reddish(pixel_at(image, 47, 40))) << "red in front of blue within the set";
      EXPECT_GT(pixel_at(image, 40, 45).g, 150) << "the line in front still shows";
    } else {
      EXPECT_TRUE(is_greyish(pixel_at(image, 40, 40))) << "depth order: the grey sphere is closest";
    }
  }
}

TEST(SphereImpostor, FirstOnTopDrawsBySetOrderNotDepthAndCoversUnderLines) {
  // Issue 44's fifth round (warrior: the worst glyph half hidden by a nearer,
  // less severe one): a set with first_on_top draws its first sphere over
  // the others whatever their depth. Red (first) behind blue (second) and
  // overlapping it on screen: red shows at the overlap. A line in front of
  // both, flagged under_ranked_spheres, is covered by them; the same line
  // unflagged shows.
  for (bool first_on_top : {false, true}) {
    Scene scene;
    scene.background = kBlack;
    SphereSet ranked;
    ranked.over_other_spheres = true;
    ranked.first_on_top = first_on_top;
    ranked.centers = {{-0.3f, 0, -1}, {0.3f, 0, 1}};  // red farther, blue nearer
    ranked.radii = {0.6f, 0.6f};
    ranked.colors = {{220, 30, 30, 255}, {30, 30, 220, 255}};
    SphereSet grey;  // nearer than both, a plain set: the ranked ones cover it
    grey.centers = {{0.0f, 0.0f, 2.0f}};
    grey.radii = {0.3f};
    grey.colors = {{128, 128, 128, 255}};
    scene.spheres = {grey, ranked};
    for (bool under : {true, false}) {
      LineSet line;
      line.positions = {{-2, 0.3f, 3}, {2, 0.3f, 3}};
      line.colors = {{20, 200, 20, 255}, {20, 200, 20, 255}};
      line.indices = {0, 1};
      line.width = 3.0f;
      line.under_ranked_spheres = under;
      scene.lines = {line};
      const Image image = renderer().render(scene, front_camera(false), 80, 80);
      // (40, 40) is inside both discs.
      if (first_on_top) {
        EXPECT_TRUE(is_reddish(pixel_at(image, 40, 40))) << "the first sphere on top";
      } else {
        EXPECT_FALSE(is_reddish(pixel_at(image, 40, 40))) << "back to front: the nearer blue one on top";
      }
      // The line crosses the spheres at y = 0.3 (a pixel row above the centre).
      int green = 0;
      for (int x = 30; x <= 50; ++x)
        for (int y = 30; y <= 40; ++y) green += pixel_at(image, x, y).g > 150 ? 1 : 0;
      if (under) {
        EXPECT_EQ(green, 0) << "a line under the ranked spheres is covered";
      } else {
        EXPECT_GT(green, 10) << "a line in front shows";
      }
    }
  }
}

TEST(Arrow, PointsTheRightWay) {
  Scene scene;
  scene.background = kBlack;
  TriangleSet arrows;
  // Along +x, tip on the right; the cone is much wider than the shaft.
  append_arrow(arrows, {-1.5f, 0, 0}, {1.5f, 0, 0}, {0.08f, 0.4f, 0.8f, 16}, Rgba8{250, 250, 250, 255});
  scene.triangles.push_back(arrows);
  const Image image = renderer().render(scene, front_camera(false), 80, 80);
  auto column_height = [&](int x) {
    int n = 0;
    for (int y = 0; y < 80; ++y) n += pixel_at(image, x, y).g > 100;
    return n;
  };
  const int near_tail = column_height(20), near_head = column_height(56);
  EXPECT_GT(near_tail, 0) << "the shaft is drawn";
  EXPECT_GT(near_head, 3 * near_tail) << "the head is at the tip (+x, right)";
  EXPECT_EQ(column_height(75), 0) << "nothing beyond the tip";
}

TEST(Translucent, BlendsBackToFrontOverTheBackground) {
  Scene scene;
  scene.background = {255, 255, 255, 255};
  TriangleSet layers;
  auto add_square = [&](float z, Rgba8 color) {
    const auto base = static_cast<std::uint32_t>(layers.positions.size());
    layers.positions.insert(layers.positions.end(), {{-1, -1, z}, {1, -1, z}, {1, 1, z}, {-1, 1, z}});
    layers.colors.insert(layers.colors.end(), 4, color);
    layers.indices.insert(layers.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  };
  // Listed front first: the renderer must sort them.
  add_square(0.5f, {255, 0, 0, 128});
  add_square(-0.5f, {0, 0, 255, 128});
  layers.is_lit = false;
  scene.translucent.push_back(layers);
  const Image image = renderer().render(scene, front_camera(false), 40, 40);
  const Rgba8 p = pixel_at(image, 20, 20);
  // white, then blue at 50%, then red at 50%: red dominates, some blue, no green.
  EXPECT_GT(p.r, 170);
  EXPECT_GT(p.b, 40);
  EXPECT_LT(p.b, p.r);
  EXPECT_LT(p.g, 80);
  EXPECT_GT(p.g, 40);
  EXPECT_EQ(pixel_at(image, 1, 1), (Rgba8{255, 255, 255, 255})) << "background untouched";
}

TEST(SphereImpostor, OverTranslucentKeepsTheSpheresColourUnderAGlass) {
  // A red ranked sphere behind a translucent magenta square in front of
  // it (issue 44 part U, round 2: the intersecting cells' boxes turned #0
  // magenta). Without over_translucent the glass blends over it (blue
  // rises); with it the sphere's centre is red as without the glass, and
  // the glass still shows beside the sphere.
  for (bool keep : {false, true}) {
    Scene scene = sphere_scene({0, 0, 0}, 0.8f, {220, 30, 30, 255});
    scene.spheres[0].over_other_spheres = true;
    scene.spheres[0].over_translucent = keep;
    TriangleSet glass;
    glass.positions = {{-1.5f, -1.5f, 1.5f}, {1.5f, -1.5f, 1.5f}, {1.5f, 1.5f, 1.5f}, {-1.5f, 1.5f, 1.5f}};
    glass.colors.assign(4, Rgba8{210, 40, 200, 160});
    glass.indices = {0, 1, 2, 0, 2, 3};
    glass.is_lit = false;
    scene.translucent.push_back(glass);
    const Image image = renderer().render(scene, front_camera(false), 80, 80);
    const Rgba8 centre = pixel_at(image, 40, 40);
    if (keep) {
      EXPECT_TRUE(is_reddish(centre)) << int(centre.r) << ' ' << int(centre.g) << ' ' << int(centre.b);
      EXPECT_GT(pixel_at(image, 40, 66).b, 80) << "the glass beside the sphere";
    } else {
      EXPECT_FALSE(is_reddish(centre)) << "the glass blends over a sphere without the flag";
    }
  }
}

// All layers at once against a golden image (tests/render/golden/layers.png),
// with a tolerance for rasterizer differences between Mesa versions. Set
// HQVIEW_UPDATE_GOLDEN=1 to rewrite the golden image after a deliberate change.
TEST(Golden, AllLayersMatchTheGoldenImage) {
  Scene scene;
  scene.background = {255, 255, 255, 255};
  SphereSet spheres;
  spheres.centers = {{-0.8f, 0.3f, 0.0f}, {0.6f, -0.4f, 0.2f}};
  spheres.radii = {0.6f, 0.35f};
  spheres.colors = {{78, 121, 167, 255}, {242, 142, 43, 255}};
  scene.spheres.push_back(spheres);
  TriangleSet arrows;
  append_arrow(arrows, {1.6f, 1.2f, 0.0f}, {0.75f, -0.2f, 0.2f}, {0.04f, 0.12f, 0.3f, 16}, {140, 20, 120, 255});
  scene.triangles.push_back(arrows);
  LineSet lines;
  lines.positions = {{-1.8f, -1.2f, 0.0f}, {1.8f, -1.2f, 0.0f}, {1.8f, 1.2f, 0.0f}, {-1.8f, 1.2f, 0.0f}};
  lines.colors.assign(4, {60, 60, 70, 255});
  lines.indices = {0, 1, 1, 2, 2, 3, 3, 0};
  scene.lines.push_back(lines);
  TriangleSet glass;
  glass.positions = {{-0.2f, -1.0f, 0.5f}, {1.2f, -1.0f, 0.5f}, {1.2f, 0.4f, 0.5f}, {-0.2f, 0.4f, 0.5f}};
  glass.colors.assign(4, {214, 40, 190, 96});
  glass.indices = {0, 1, 2, 0, 2, 3};
  scene.translucent.push_back(glass);
  Camera camera = front_camera(true);
  camera.eye = {0.8, 1.0, 5.0};
  const Image image = renderer().render(scene, camera, 160, 120);

  const std::filesystem::path golden = test::source_dir() / "tests/render/golden/layers.png";
  if (std::getenv("HQVIEW_UPDATE_GOLDEN")) test::write_png_file(image, golden);
  OIIO::ImageBuf expected(golden.string());
  ASSERT_TRUE(expected.read()) << "missing golden image " << golden << " (HQVIEW_UPDATE_GOLDEN=1 writes it)";
  OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
  OIIO::ImageBuf actual(spec, const_cast<std::uint8_t*>(image.rgba.data()));
  const auto result = OIIO::ImageBufAlgo::compare(actual, expected, 0.1, 0.02);
  EXPECT_LT(result.meanerror, 0.01);
  EXPECT_LT(result.nfail, 40) << "pixels differing by more than 10%";
}

}  // namespace
}  // namespace hq
