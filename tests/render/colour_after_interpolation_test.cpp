// Colour after interpolation (issue 44): the overview maps the interpolated
// vertex quality per fragment, so an unlit render shows in the interior of
// every face only colours of the map (within CIEDE2000 3) or the inverted
// colour, and the inverted colour inside the faces that have an inverted
// corner (checked at probes 15 % of the way from each visible inverted corner
// to its face's centre), and nowhere else. Face interiors come from an id render of the same faces (one flat
// colour per face): a pixel counts when its 3x3 neighbourhood is one face.
// The seam where the inverted region meets the map is a hard edge that the
// 2x2 supersampling averages: pixels next to an inverted pixel may be
// blends, and are counted (at most 3 % of the interior). Colours mapped at
// the vertices and blended (the old way) fail the same check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "hqview/image/colormap.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/mesh/topology.h"
#include "hqview/quality/quality_field.h"
#include "hqview/render/osmesa_renderer.h"
#include "hqview/render/upright.h"
#include "hqview/views/overview_views.h"
#include "support/colour_science.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

Renderer& renderer() {
  static const std::unique_ptr<Renderer> instance = make_osmesa_renderer();
  return *instance;
}

Rgba8 pixel(const Image& image, int x, int y) {
  const std::uint8_t* p = image.rgba.data() + pixel_offset(image, x, y);
  return {p[0], p[1], p[2], p[3]};
}

// A distinct colour per face id (never white, the background).
Rgba8 id_color(std::size_t face) {
  const std::size_t v = face + 1;
  return {static_cast<std::uint8_t>(v & 0xff), static_cast<std::uint8_t>((v >> 8) & 0xff),
          static_cast<std::uint8_t>(16 + ((v >> 16) & 0x3f)), 255};
}

struct Result {
  std::size_t interior = 0;  // face-interior pixels
  std::size_t off_map = 0;   // of them, not within 3 of the map or the inverted colour and not at a seam
  std::size_t seam = 0;      // of them, blends next to an inverted pixel
  // Probes: for each inverted corner of a boundary face, the point 15 % of
  // the way from it to the face's centre (its barycentric weight there is
  // 0.85 in both fan triangles: it must wear the inverted colour), where the
  // id render shows that face around it (not hidden, not at an edge).
  std::size_t probes = 0;
  std::size_t probes_inverted = 0;
  std::size_t inverted_pixels = 0;            // interior pixels in the inverted colour
  std::size_t inverted_pixels_elsewhere = 0;  // of them, on faces without an inverted corner
};

Result check(const HexMesh& mesh, const Topology& topology, const std::vector<double>& quality, bool per_vertex_only,
             const Vec3& view_direction, const Vec3& up) {
  OverviewOptions options;
  options.up = up;
  Scene scene = build_quality_overview_scene(mesh, topology, quality, options);
  scene.lines.clear();
  TriangleSet& faces = scene.triangles.at(0);
  faces.is_lit = false;
  if (per_vertex_only) faces.scalars.clear();  // the old way: colours mapped at the vertices, then blended
  Scene ids = scene;
  TriangleSet& id_faces = ids.triangles.at(0);
  id_faces.scalars.clear();
  for (std::size_t i = 0; i < id_faces.colors.size(); ++i) id_faces.colors[i] = id_color(i / 5);  // 5 vertices a face

  constexpr int kWidth = 900, kHeight = 700;
  const double aspect = static_cast<double>(kWidth) / kHeight;
  const Camera camera = fit_camera_to_points(boundary_points(mesh, topology), view_direction, aspect, {.up = up});
  const Image image = renderer().render(scene, camera, kWidth, kHeight);
  const Image id_image = renderer().render(ids, camera, kWidth, kHeight);

  // The map, densely, and the inverted colour, in CIELAB.
  std::vector<test::Lab> map;
  for (int i = 0; i <= 1000; ++i) map.push_back(test::lab_of(to_rgba8(sample_quality_map(i / 1000.0))));
  const test::Lab inverted = test::lab_of(to_rgba8(kInvertedColor));
  std::map<std::uint32_t, double> cache;  // packed colour -> distance to the map
  auto map_distance = [&](Rgba8 c) {
    const std::uint32_t key = (std::uint32_t{c.r} << 16) | (std::uint32_t{c.g} << 8) | c.b;
    const auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    const test::Lab lab = test::lab_of(c);
    double best = 1e9;
    for (const test::Lab& m : map) best = std::min(best, test::ciede2000(lab, m));
    return cache[key] = best;
  };
  auto is_inverted = [&](Rgba8 c) { return test::ciede2000(test::lab_of(c), inverted) <= 3.0; };

  std::vector<char> face_has_inverted_corner(topology.boundary_faces.size(), 0);
  for (std::size_t f = 0; f < topology.boundary_faces.size(); ++f)
    for (Index v : topology.faces[static_cast<std::size_t>(topology.boundary_faces[f])])
      if (quality[static_cast<std::size_t>(v)] < 0.0) face_has_inverted_corner[f] = 1;

  auto face_of = [](Rgba8 id) {
    return (std::size_t{id.r} | (std::size_t{id.g} << 8) | (std::size_t{id.b - 16u} << 16)) - 1;
  };
  auto is_inside_face = [&](int x, int y, Rgba8 id) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (pixel(id_image, x + dx, y + dy) != id) return false;
    return true;
  };

  Result r;
  for (int y = 1; y + 1 < kHeight; ++y)
    for (int x = 1; x + 1 < kWidth; ++x) {
      const Rgba8 id = pixel(id_image, x, y);
      if (id == Rgba8{255, 255, 255, 255}) continue;
      if (!is_inside_face(x, y, id)) continue;
      const std::size_t face = face_of(id);
      ++r.interior;
      const Rgba8 c = pixel(image, x, y);
      if (is_inverted(c)) {
        ++r.inverted_pixels;
        if (face >= face_has_inverted_corner.size() || !face_has_inverted_corner[face]) ++r.inverted_pixels_elsewhere;
        continue;
      }
      if (map_distance(c) <= 3.0) continue;
      bool next_to_inverted = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          next_to_inverted = next_to_inverted || is_inverted(pixel(image, x + dx, y + dy));
      ++(next_to_inverted ? r.seam : r.off_map);
    }
  for (std::size_t f = 0; f < topology.boundary_faces.size(); ++f) {
    const Quad& quad = topology.faces[static_cast<std::size_t>(topology.boundary_faces[f])];
    Vec3 centre;
    for (Index v : quad) centre = centre + 0.25 * mesh.points[static_cast<std::size_t>(v)];
    for (Index v : quad) {
      if (!(quality[static_cast<std::size_t>(v)] < 0.0)) continue;
      const Vec3& corner = mesh.points[static_cast<std::size_t>(v)];
      const Vec3 ndc = project_to_ndc(camera, aspect, corner + 0.15 * (centre - corner));
      const int x = static_cast<int>(std::floor(0.5 * (ndc.x + 1.0) * kWidth));
      const int y = static_cast<int>(std::floor(0.5 * (1.0 - ndc.y) * kHeight));
      if (x < 1 || y < 1 || x + 1 >= kWidth || y + 1 >= kHeight || !is_inside_face(x, y, id_color(f))) continue;
      ++r.probes;
      r.probes_inverted += is_inverted(pixel(image, x, y));
    }
  }
  return r;
}

// A 6 x 6 x 2 grid whose top centre vertex is pushed below the middle layer:
// the 4 top cells around it invert, and with them the boundary vertices of
// the dent.
HexMesh dented_grid() {
  HexMesh mesh = test::box_grid(6, 6, 2);
  mesh.points[static_cast<std::size_t>(3 + 7 * (3 + 7 * 2))].z = 0.5;
  return mesh;
}

// has_visible_inverted_corner: the view shows an inverted corner's
// neighbourhood (some probe), so the inverted colour must be there.
void expect_map_colours_only(const HexMesh& mesh, const Vec3& view_direction, const Vec3& up,
                             bool has_visible_inverted_corner) {
  const Topology topology = build_topology(mesh);
  const QualityField q = compute_quality(mesh, topology);
  std::size_t negative_boundary = 0;
  std::vector<char> on_boundary(mesh.points.size(), 0);
  for (Index f : topology.boundary_faces)
    for (Index v : topology.faces[static_cast<std::size_t>(f)]) on_boundary[static_cast<std::size_t>(v)] = 1;
  for (std::size_t v = 0; v < mesh.points.size(); ++v) negative_boundary += on_boundary[v] && q.vertex_quality[v] < 0.0;
  ASSERT_GT(negative_boundary, 0u);

  const Result r = check(mesh, topology, q.vertex_quality, false, view_direction, up);
  EXPECT_GT(r.interior, 20000u);
  EXPECT_EQ(r.off_map, 0u);
  EXPECT_LE(r.seam, r.interior * 3 / 100);
  if (has_visible_inverted_corner) {
    EXPECT_GT(r.probes, 0u);
    EXPECT_GT(r.inverted_pixels, 0u);
  }
  EXPECT_EQ(r.probes_inverted, r.probes);
  EXPECT_EQ(r.inverted_pixels_elsewhere, 0u);

  // Blending colours mapped at the vertices leaves the map inside faces.
  const Result old = check(mesh, topology, q.vertex_quality, true, view_direction, up);
  EXPECT_GT(old.off_map, 100u);
}

TEST(ColourAfterInterpolation, DentedGrid) {
  // From above (a little off the vertical): the dent's bottom is in view.
  expect_map_colours_only(dented_grid(), {0.2, 0.3, -1.0}, {0, 1, 0}, true);
  // The three-quarter view: the dent's bottom is behind its rim.
  expect_map_colours_only(dented_grid(), three_quarter_view({0, 0, 1}), {0, 0, 1}, false);
}

TEST(ColourAfterInterpolation, Rockarm) {
  const auto data = test::shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data (or $HQVIEW_DATA) not found";
  const HexMesh mesh = read_hex_mesh(*data / "meshes/dualsheet2019/rockarm.vtk").mesh;
  expect_map_colours_only(mesh, three_quarter_view({0, 0, 1}), {0, 0, 1}, true);
  expect_map_colours_only(mesh, -1.0 * three_quarter_view({0, 0, 1}), {0, 0, 1}, false);
}

}  // namespace
}  // namespace hq
