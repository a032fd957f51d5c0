// The UV atlas never fails: property test over adversarial surfaces made
// here and every reference surface in ../shared/data.

#include "hqview/uv/uv_atlas.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "hqview/io/mesh_reader.h"
#include "support/fixtures.h"
#include "support/surface_fixtures.h"

namespace hq::test {
namespace {

namespace fs = std::filesystem;

// Every triangle in exactly one chart, 0 flipped, 0 overlapping (exact), all
// UVs in [0,1]^2, and the atlas's own counts agree.
void expect_valid_atlas(const TriSurface& s, const UvAtlas& atlas, const std::string& name) {
  const std::size_t nt = s.triangles.size();
  ASSERT_EQ(atlas.uvs.size(), 3 * nt) << name;
  ASSERT_EQ(atlas.triangle_chart.size(), nt) << name;
  std::vector<int> chart_size(static_cast<std::size_t>(atlas.num_charts), 0);
  for (Index c : atlas.triangle_chart) {
    ASSERT_GE(c, 0) << name;
    ASSERT_LT(c, atlas.num_charts) << name;
    ++chart_size[c];
  }
  for (int n : chart_size) EXPECT_GT(n, 0) << name << ": empty chart";
  for (const Uv& p : atlas.uvs) {
    ASSERT_TRUE(p[0] >= 0.0 && p[0] <= 1.0 && p[1] >= 0.0 && p[1] <= 1.0) << name << ": " << p[0] << " " << p[1];
  }
  const auto flipped = uv_flipped_triangles(atlas.uvs);
  EXPECT_EQ(std::count(flipped.begin(), flipped.end(), 1), 0) << name;
  EXPECT_TRUE(uv_overlapping_pairs(atlas.uvs).empty()) << name;
  EXPECT_EQ(atlas.num_flipped, 0) << name;
  EXPECT_EQ(atlas.num_overlaps, 0) << name;
  EXPECT_GT(atlas.packing_efficiency, 0.0) << name;
  EXPECT_LE(atlas.packing_efficiency, 1.0) << name;
}

TEST(UvValidation, ExactOverlapAndTouching) {
  // Triangles 0 and 1 share an edge: they touch. 2 is a copy of 0; 3 crosses 0, 1 and 2.
  const std::vector<Uv> uvs = {{0, 0}, {1, 0}, {0, 1}, {1, 0},    {1, 1},   {0, 1},
                               {0, 0}, {1, 0}, {0, 1}, {0.2, -1}, {0.3, 2}, {0.1, 2}};
  const auto flipped = uv_flipped_triangles(uvs);
  EXPECT_EQ(flipped, (std::vector<std::uint8_t>{0, 0, 0, 0}));
  const auto pairs = uv_overlapping_pairs(uvs);
  EXPECT_EQ(pairs, (std::vector<std::array<Index, 2>>{{0, 2}, {0, 3}, {1, 3}, {2, 3}}));
  // Groups keep triangles apart.
  const std::vector<Index> group = {0, 0, 1, 2};
  EXPECT_TRUE(uv_overlapping_pairs(uvs, group).empty());
  // A clockwise and a degenerate triangle are flipped.
  const std::vector<Uv> bad = {{0, 0}, {0, 1}, {1, 0}, {0, 0}, {1, 1}, {2, 2}};
  EXPECT_EQ(uv_flipped_triangles(bad), (std::vector<std::uint8_t>{1, 1}));
}

TEST(UvAtlas, CubeHasSixCharts) {
  const TriSurface cube = triangulated_box({0, 0, 0}, {1, 1, 1}, 3);
  const UvAtlas atlas = build_uv_atlas(cube);
  expect_valid_atlas(cube, atlas, "cube");
  EXPECT_EQ(atlas.num_charts, 6);
  EXPECT_EQ(atlas.num_splits, 0);
  EXPECT_GT(atlas.packing_efficiency, 0.4);
}

// A ribbon winding twice around the z axis while rising: seen from +z it
// overlaps itself, so its one chart must be split.
TriSurface helical_ramp() {
  TriSurface s;
  const int steps = 200;
  for (int i = 0; i <= steps; ++i) {
    const double a = 4.0 * std::numbers::pi * i / steps;
    const double z = 0.05 * i / steps;
    s.points.push_back({std::cos(a), std::sin(a), z});
    s.points.push_back({2 * std::cos(a), 2 * std::sin(a), z});
  }
  for (Index i = 0; i < steps; ++i) {
    const Index a = 2 * i, b = 2 * i + 1, c = 2 * i + 2, d = 2 * i + 3;
    s.triangles.push_back({a, b, d});  // counter-clockwise seen from +z
    s.triangles.push_back({a, d, c});
  }
  return s;
}

std::vector<std::pair<std::string, TriSurface>> adversarial_surfaces() {
  std::vector<std::pair<std::string, TriSurface>> out;
  out.emplace_back("icosphere", icosphere(4));
  out.emplace_back("open sphere", remove_triangles(icosphere(4), [](const Vec3& c) { return c.z > 0.5; }));
  out.emplace_back("genus 3", genus3_slab());
  out.emplace_back("helical ramp", helical_ramp());
  {
    // A non-manifold fin: two extra triangles on one cube edge (4 triangles on it).
    TriSurface s = triangulated_box({0, 0, 0}, {1, 1, 1}, 2);
    const Index a = 0, b = s.triangles[0][1];
    s.points.push_back({2, 2, 0.5});
    s.points.push_back({-1, 3, 0.2});
    s.triangles.push_back({a, b, static_cast<Index>(s.points.size() - 2)});
    s.triangles.push_back({b, a, static_cast<Index>(s.points.size() - 1)});
    out.emplace_back("non-manifold fin", s);
  }
  {
    TriSurface s = icosphere(3);
    for (int i = 0; i < 20; ++i) s.triangles.push_back(s.triangles[static_cast<std::size_t>(7 * i)]);
    s.triangles.push_back({s.triangles[3][2], s.triangles[3][1], s.triangles[3][0]});  // reversed duplicate
    out.emplace_back("duplicate faces", s);
  }
  {
    TriSurface s = triangulated_box({0, 0, 0}, {1, 1, 1}, 3);
    const Index n = static_cast<Index>(s.points.size());
    s.points.push_back({0.5, 0.5, 2});
    s.points.push_back({1.5, 1.5, 2});
    s.points.push_back({1.0, 1.0, 2});  // collinear with the two above
    s.points.push_back({0.5, 0.5, 2});  // coincident with n
    s.triangles.push_back({n, n + 1, n + 2});
    s.triangles.push_back({n, n + 3, n + 1});
    s.triangles.push_back({n, n, n + 1});
    s.triangles.push_back({0, 0, 0});
    s.triangles.push_back({1, 2, 1});
    out.emplace_back("zero-area triangles", s);
  }
  out.emplace_back("several components", append(append(icosphere(2), icosphere(2, 0.5, {3, 0, 0})),
                                                append(genus3_slab(), triangulated_box({5, 5, 5}, {5.001, 6, 7}, 4))));
  {
    // Tiny and huge triangles together.
    TriSurface s = append(icosphere(2, 1e-6), icosphere(2, 1e4, {1, 1, 1}));
    out.emplace_back("mixed scales", s);
  }
  return out;
}

TEST(UvAtlas, AdversarialSurfacesGetAValidAtlas) {
  for (const auto& [name, surface] : adversarial_surfaces()) {
    const UvAtlas atlas = build_uv_atlas(surface);
    expect_valid_atlas(surface, atlas, name);
  }
}

TEST(UvAtlas, LscmImprovementKeepsTheAtlasValid) {
  UvOptions options;
  options.improve_with_lscm = true;
  for (const auto& [name, surface] : adversarial_surfaces()) {
    const UvAtlas atlas = build_uv_atlas(surface, options);
    expect_valid_atlas(surface, atlas, name + " (LSCM)");
  }
  const TriSurface sphere = icosphere(4);
  const UvAtlas atlas = build_uv_atlas(sphere, options);
  EXPECT_GT(atlas.num_lscm_charts, 0);
  EXPECT_EQ(build_uv_atlas(sphere).num_lscm_charts, 0);
}

TEST(UvAtlas, HelicalRampIsSplit) {
  const TriSurface s = helical_ramp();
  const UvAtlas atlas = build_uv_atlas(s);
  expect_valid_atlas(s, atlas, "helical ramp");
  EXPECT_GT(atlas.num_splits, 0);
  EXPECT_GE(atlas.num_charts, 2);
}

TEST(UvAtlas, Deterministic) {
  const TriSurface s = adversarial_surfaces().back().second;
  const UvAtlas a = build_uv_atlas(s), b = build_uv_atlas(s);
  EXPECT_EQ(a.uvs, b.uvs);
  EXPECT_EQ(a.triangle_chart, b.triangle_chart);
}

TEST(UvAtlas, EmptySurface) {
  const UvAtlas atlas = build_uv_atlas(TriSurface{});
  EXPECT_EQ(atlas.num_charts, 0);
  EXPECT_TRUE(atlas.uvs.empty());
}

TEST(UvAtlas, CornerValuesFollowTheTriangles) {
  const TriSurface s = triangulated_box({0, 0, 0}, {1, 1, 1}, 1);
  std::vector<double> field(s.points.size());
  for (std::size_t i = 0; i < field.size(); ++i) field[i] = double(i);
  const auto corners = uv_corner_values(s, field);
  ASSERT_EQ(corners.size(), 3 * s.triangles.size());
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(corners[3 * t + k], double(s.triangles[t][k]));
}

TEST(UvAtlas, EveryReferenceInSharedData) {
  const auto data = shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data absent (set HQVIEW_DATA to run these)";
  std::vector<fs::path> references;
  for (const auto& entry : fs::recursive_directory_iterator(*data / "meshes")) {
    const std::string ext = entry.path().extension().string();
    if (entry.is_regular_file() && (ext == ".off" || ext == ".obj" || ext == ".stl" || ext == ".ply"))
      references.push_back(entry.path());
  }
  std::sort(references.begin(), references.end());
  ASSERT_FALSE(references.empty());
  for (const fs::path& path : references) {
    const TriSurface s = read_surface(path);
    const UvAtlas atlas = build_uv_atlas(s);
    expect_valid_atlas(s, atlas, path.filename().string());
    UvOptions lscm;
    lscm.improve_with_lscm = true;
    const UvAtlas improved = build_uv_atlas(s, lscm);
    expect_valid_atlas(s, improved, path.filename().string() + " (LSCM)");
    EXPECT_GT(improved.num_lscm_charts, 0) << path.filename().string();
    RecordProperty(path.filename().string() + "_lscm_charts",
                   std::to_string(improved.num_lscm_charts) + "/" + std::to_string(improved.num_charts));
  }
}

}  // namespace
}  // namespace hq::test
