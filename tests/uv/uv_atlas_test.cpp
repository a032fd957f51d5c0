// The UV atlas never fails: property test over adversarial surfaces made
// here, and analytic cases (uv_atlas_real_data_test.cpp: every reference
// surface in ../shared/data).

#include "hqview/uv/uv_atlas.h"
#include "hqview/uv/uv_cut.h"
#include "hqview/uv/uv_lscm.h"
#include "hqview/uv/uv_metrics.h"
#include "hqview/uv/uv_pack.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <tuple>

#include "hqview/io/mesh_reader.h"
#include "support/fixtures.h"
#include "support/surface_fixtures.h"
#include "uv_atlas_checks.h"

namespace hq::test {
namespace HQ_TEST_UNIT {

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

// The corners of an n x n vertex grid's triangles (two per cell,
// counter-clockwise in (u, v)), each vertex at place(i, j).
template <class Place>
std::vector<Uv> grid_layout(int n, Place&& place) {
  std::vector<Uv> uvs;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const Uv a = place(i, j), b = place(i + 1, j), c = place(i, j + 1), d = place(i + 1, j + 1);
      uvs.insert(uvs.end(), {a, b, d, a, d, c});
    }
  return uvs;
}

bool all_counter_clockwise(const std::vector<Uv>& uvs) {
  const auto flipped = uv_flipped_triangles(uvs);
  return std::count(flipped.begin(), flipped.end(), 1) == 0;
}

TEST(UvValidation, TheBorderCertificateAgreesWithTheSearchOnGridDisks) {
  // A 9 x 9 grid, each vertex moved at random by up to a third of a cell,
  // then bent around the origin through 0.6 to 1.4 turns (radius falling
  // with the row, so the triangles stay counter-clockwise): below a turn
  // mostly one-to-one, above it the ends overlap. Among the layouts
  // without a flipped triangle (the certificate's premise), a certified
  // one never has an overlapping pair, and here (a disk whose border does
  // not merely touch itself) the certificate holds exactly when the search
  // finds no pair.
  std::mt19937 rng(20);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int certified = 0, refused = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const double jitter = 0.33 * std::abs(unit(rng)), turns = 1.0 + 0.4 * unit(rng);
    std::vector<Uv> moved(81);
    for (Uv& p : moved) p = {jitter * unit(rng), jitter * unit(rng)};
    const std::vector<Uv> uvs = grid_layout(9, [&](int i, int j) {
      const Uv m = moved[static_cast<std::size_t>(9 * j + i)];
      const double angle = 2.0 * std::numbers::pi * turns * (i + m[0]) / 8.0, radius = 2.0 - 0.1 * (j + m[1]);
      return Uv{radius * std::cos(angle), radius * std::sin(angle)};
    });
    if (!all_counter_clockwise(uvs)) continue;
    const bool certificate = uv_border_certifies_one_to_one(uvs);
    const bool none = uv_overlapping_pairs(uvs).empty();
    EXPECT_EQ(certificate, none) << "trial " << trial;
    EXPECT_EQ(uv_one_to_one(uvs), none) << "trial " << trial;
    (certificate ? certified : refused) += 1;
  }
  EXPECT_GT(certified, 50);
  EXPECT_GT(refused, 25);
}

TEST(UvValidation, TheBorderCertificateRefusesWindingsAndHolesAndTheSearchDecides) {
  // A grid strip bent around the origin through an angle: below a full
  // turn it is one-to-one (certified); past a full turn its ends overlap,
  // every triangle still counter-clockwise (refused; the search finds the
  // pairs).
  for (const double turns : {0.5, 0.9, 1.1, 1.6}) {
    const std::vector<Uv> uvs = grid_layout(24, [&](int i, int j) {
      const double angle = 2.0 * std::numbers::pi * turns * i / 23.0, radius = 1.0 - 0.02 * j;
      return Uv{radius * std::cos(angle), radius * std::sin(angle)};
    });
    ASSERT_TRUE(all_counter_clockwise(uvs)) << turns;
    EXPECT_EQ(uv_border_certifies_one_to_one(uvs), turns < 1.0) << turns;
    EXPECT_EQ(uv_overlapping_pairs(uvs).empty(), turns < 1.0) << turns;
    EXPECT_EQ(uv_one_to_one(uvs), turns < 1.0) << turns;
  }
  // A fan of 8 triangles around one vertex through two full turns (each
  // rim point a little further out): every triangle counter-clockwise, the
  // rim winds twice.
  std::vector<Uv> fan;
  for (int k = 0; k < 8; ++k) {
    const auto rim = [](int i) {
      const double angle = std::numbers::pi / 2 * i, radius = 1.0 + 0.1 * i;
      return Uv{radius * std::cos(angle), radius * std::sin(angle)};
    };
    fan.insert(fan.end(), {Uv{0, 0}, rim(k), rim(k + 1)});
  }
  ASSERT_TRUE(all_counter_clockwise(fan));
  EXPECT_FALSE(uv_border_certifies_one_to_one(fan));
  EXPECT_FALSE(uv_one_to_one(fan));
  // An annulus (a ring of 16 quads): one-to-one, but its border is two
  // loops, so the certificate proves nothing and the search decides.
  const std::vector<Uv> ring = grid_layout(17, [](int i, int j) {
    const double angle = 2.0 * std::numbers::pi * (i % 16) / 16.0, radius = 1.5 - 0.5 * std::min(j, 1);
    return Uv{radius * std::cos(angle), radius * std::sin(angle)};
  });
  std::vector<Uv> annulus(ring.begin(), ring.begin() + 6 * 16);  // the first row of cells
  ASSERT_TRUE(all_counter_clockwise(annulus));
  EXPECT_FALSE(uv_border_certifies_one_to_one(annulus));
  EXPECT_TRUE(uv_overlapping_pairs(annulus).empty());
  EXPECT_TRUE(uv_one_to_one(annulus));
  // Two triangles that touch at one corner: no pair overlaps, but the
  // border passes through that point twice; one triangle alone is
  // certified; a triangle twice over is refused.
  const std::vector<Uv> bowtie = {{0, 0}, {1, 0}, {0, 1}, {0, 0}, {-1, 0}, {0, -1}};
  EXPECT_FALSE(uv_border_certifies_one_to_one(bowtie));
  EXPECT_TRUE(uv_one_to_one(bowtie));
  EXPECT_TRUE(uv_border_certifies_one_to_one(std::vector<Uv>(bowtie.begin(), bowtie.begin() + 3)));
  const std::vector<Uv> twice = {{0, 0}, {1, 0}, {0, 1}, {0, 0}, {1, 0}, {0, 1}};
  EXPECT_FALSE(uv_border_certifies_one_to_one(twice));
  EXPECT_FALSE(uv_one_to_one(twice));
}

// Per triangle (UV area / 3D area) / (total UV area / total 3D area), recomputed here.
std::vector<double> area_ratios(const TriSurface& s, const UvAtlas& atlas) {
  double a3 = 0, a2 = 0;
  std::vector<double> r3, r2;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const auto& tri = s.triangles[t];
    const Vec3 &a = s.points[tri[0]], &b = s.points[tri[1]], &c = s.points[tri[2]];
    const Uv *p = &atlas.uvs[3 * t];
    r3.push_back(0.5 * norm(cross(b - a, c - a)));
    r2.push_back(0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0])));
    a3 += r3.back(), a2 += r2.back();
  }
  std::vector<double> out;
  for (std::size_t t = 0; t < r3.size(); ++t) out.push_back((r2[t] / r3[t]) / (a2 / a3));
  return out;
}

// An open cylinder (no caps), n around, m along.
TriSurface open_cylinder(int n, int m, double radius, double height) {
  TriSurface s;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * std::numbers::pi * i / n;
      s.points.push_back({radius * std::cos(a), radius * std::sin(a), height * j / m});
    }
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const Index a = j * n + i, b = j * n + (i + 1) % n, c = a + n, d = b + n;
      s.triangles.push_back({a, b, d});
      s.triangles.push_back({a, d, c});
    }
  return s;
}

TriSurface torus(int n, int m, double big, double small) {
  TriSurface s;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = 2.0 * std::numbers::pi * i / n, v = 2.0 * std::numbers::pi * j / m;
      s.points.push_back({(big + small * std::cos(v)) * std::cos(u), (big + small * std::cos(v)) * std::sin(u),
                          small * std::sin(v)});
    }
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const Index a = j * n + i, b = j * n + (i + 1) % n, c = ((j + 1) % m) * n + i, d = ((j + 1) % m) * n + (i + 1) % n;
      s.triangles.push_back({a, b, d});
      s.triangles.push_back({a, d, c});
    }
  return s;
}

TEST(UvValidation, PartByPartFindsThePairsOfOneSearch) {
  // 3,000 random small counter-clockwise triangles in the unit square, in
  // 40 parts (random, so parts overlap everywhere), then the same with
  // parts that are vertical strips (the packed-charts case): the pairs
  // equal those of one search over all triangles.
  std::mt19937 rng(16);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Uv> uvs;
  for (int t = 0; t < 3000; ++t) {
    const double x = unit(rng), y = unit(rng), r = 0.02 * unit(rng) + 1e-3;
    uvs.insert(uvs.end(), {Uv{x, y}, Uv{x + r, y}, Uv{x + 0.3 * r, y + r}});
  }
  const auto all = uv_overlapping_pairs(uvs);
  ASSERT_GT(all.size(), 100u);
  std::vector<Index> random_parts, strips;
  for (int t = 0; t < 3000; ++t) {
    random_parts.push_back(static_cast<Index>(rng() % 40));
    strips.push_back(static_cast<Index>(std::min(9.0, std::floor(10 * uvs[3 * static_cast<std::size_t>(t)][0]))));
  }
  EXPECT_EQ(uv_overlapping_pairs_by_part(uvs, random_parts), all);
  EXPECT_EQ(uv_overlapping_pairs_by_part(uvs, strips), all);
}

TEST(UvPack, AChartLyingAtAnAngleIsTurnedToItsSmallestBox) {
  // A unit square chart (two triangles) laid out at 30 degrees: kept so,
  // its box is (cos 30 + sin 30)^2 = 1.866 times its area; turned by -30
  // degrees it fills the unit square but for the gutter (a cell or two of
  // the 256 along a side).
  const double a = std::numbers::pi / 6, c = std::cos(a), s = std::sin(a);
  const auto at = [&](double x, double y) { return Uv{c * x - s * y, s * x + c * y}; };
  const std::vector<Uv> local = {at(0, 0), at(1, 0), at(1, 1), at(0, 0), at(1, 1), at(0, 1)};
  const std::vector<std::vector<Index>> charts = {{0, 1}};
  const auto fill = [&](bool tilt) {
    std::vector<Uv> packed;
    pack_charts(local, charts, packed, PackOptions{.tilt_to_smallest_box = tilt});
    EXPECT_EQ(uv_flipped_triangles(packed), std::vector<std::uint8_t>(2, 0));
    for (const Uv& p : packed) EXPECT_TRUE(p[0] >= 0 && p[0] <= 1 && p[1] >= 0 && p[1] <= 1);
    return uv_signed_area(&packed[0]) + uv_signed_area(&packed[3]);
  };
  const double kept = fill(false), tilted = fill(true);
  EXPECT_NEAR(kept, 1.0 / ((c + s) * (c + s)), 0.02);
  EXPECT_GT(tilted, 0.97);
  EXPECT_LE(tilted, 1.0);
}

// The hull's candidates hold every vertex of the convex hull of all corners
// (computed here by gift wrapping on exact small integers): random clouds,
// a disk's rim (every rim point a vertex), and a grid with collinear sides;
// most interior corners are left out.
TEST(UvPack, HullCandidatesKeepEveryHullVertex) {
  const auto hull_vertices = [](const std::vector<Uv>& points) {
    std::vector<Uv> hull;
    const auto cross = [](const Uv& o, const Uv& a, const Uv& b) {
      return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    };
    std::size_t start = 0;
    for (std::size_t i = 1; i < points.size(); ++i)
      if (points[i] < points[start]) start = i;
    std::size_t p = start;
    do {  // the next vertex: every point on its left (collinear: the farthest)
      hull.push_back(points[p]);
      std::size_t q = p == 0 ? 1 : 0;
      for (std::size_t r = 0; r < points.size(); ++r) {
        const double c = cross(points[p], points[q], points[r]);
        const auto d2 = [&](std::size_t k) {
          return (points[k][0] - points[p][0]) * (points[k][0] - points[p][0]) +
                 (points[k][1] - points[p][1]) * (points[k][1] - points[p][1]);
        };
        if (c < 0 || (c == 0 && d2(r) > d2(q))) q = r;
      }
      p = q;
    } while (p != start && hull.size() <= points.size());
    return hull;
  };
  std::mt19937 random(7);
  std::vector<std::vector<Uv>> clouds;
  for (int n : {70, 500, 4000}) {
    std::uniform_int_distribution<int> coordinate(-1000, 1000);
    std::vector<Uv> cloud;
    for (int i = 0; i < n; ++i) cloud.push_back({double(coordinate(random)), double(coordinate(random))});
    clouds.push_back(cloud);
  }
  std::vector<Uv> rim;  // a regular 96-gon and its centre, each point 6 times
  for (int i = 0; i < 96; ++i)
    for (int k = 0; k < 6; ++k)
      rim.push_back({std::round(1e6 * std::cos(2 * std::numbers::pi * i / 96)),
                     std::round(1e6 * std::sin(2 * std::numbers::pi * i / 96))});
  rim.push_back({0, 0});
  clouds.push_back(rim);
  std::vector<Uv> grid;
  for (int x = 0; x < 30; ++x)
    for (int y = 0; y < 20; ++y) grid.push_back({double(x), double(y)});
  clouds.push_back(grid);
  for (const std::vector<Uv>& cloud : clouds) {
    const std::vector<Uv> candidates = hull_candidates(cloud);
    for (const Uv& v : hull_vertices(cloud))
      EXPECT_NE(std::find(candidates.begin(), candidates.end(), v), candidates.end())
          << "hull vertex " << v[0] << " " << v[1] << " of a cloud of " << cloud.size();
    const bool mostly_inside = &cloud != &clouds[3];  // not the rim
    if (mostly_inside && cloud.size() >= 500) EXPECT_LT(candidates.size(), cloud.size() / 2) << cloud.size();
  }
}

// Packing with a shape cache gives the packing without it, bit for bit,
// when the charts come back the same, when one chart's layout moves (its
// cached shapes must not be reused) and when a chart is split in two.
TEST(UvPack, TheShapeCacheChangesNoPacking) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  // 30 charts, each a strip of 2k triangles of a perturbed grid row.
  std::vector<Uv> local;
  std::vector<std::vector<Index>> charts;
  for (int c = 0; c < 30; ++c) {
    std::vector<Index> chart;
    const int n = 2 + c % 7;
    for (int i = 0; i < n; ++i) {
      const double x = i + 0.1 * jitter(random), y = 2.0 * c;
      for (const Uv& p : {Uv{x, y}, Uv{x + 1, y}, Uv{x + 1, y + 1 + jitter(random)}, Uv{x, y}, Uv{x + 1, y + 1},
                          Uv{x, y + 1 + jitter(random)}})
        local.push_back(p);
      chart.push_back(static_cast<Index>(local.size() / 3 - 2));
      chart.push_back(static_cast<Index>(local.size() / 3 - 1));
    }
    charts.push_back(chart);
  }
  PackShapeCache cache;
  const auto both = [&](const char* what, std::size_t reused) {
    std::vector<Uv> plain, cached;
    pack_charts(local, charts, plain, PackOptions{.resolution = 64});
    pack_charts(local, charts, cached, PackOptions{.resolution = 64}, &cache);
    EXPECT_EQ(plain, cached) << what;
    EXPECT_EQ(cache.num_reused(), reused) << what;
  };
  both("first call", 0);
  both("the same charts again", 30);
  for (std::size_t k = 3 * static_cast<std::size_t>(charts[4][0]); k < 3 * static_cast<std::size_t>(charts[4].back() + 1); ++k)
    local[k] = {-local[k][1], local[k][0]};  // chart 4 laid out anew: turned, the same area
  both("one chart moved", 29);
  std::vector<Index> half(charts[6].begin() + 2, charts[6].end());
  charts[6].resize(2);
  charts.push_back(half);  // chart 6 halved
  both("one chart split", 29);  // chart 6 and its new half are new
}

TEST(UvAtlas, CubeCornersUnfoldWithoutAreaDistortion) {
  // Three faces around a corner are one cone of normals (54.7 degrees from
  // the diagonal): charts hold corners, not single faces.
  const TriSurface cube = triangulated_box({0, 0, 0}, {1, 1, 1}, 3);
  const UvAtlas atlas = build_uv_atlas(cube, UvOptions{.improve_with_lscm = true});
  expect_valid_atlas(cube, atlas, "cube");
  expect_disks(cube, atlas, "cube");
  EXPECT_LE(atlas.num_charts, 6);
  EXPECT_GE(atlas.area_fraction_area_ratio_within_2, 0.9);
}

TEST(UvAtlas, OpenCylinderUnrollsIsometrically) {
  const TriSurface s = open_cylinder(96, 24, 1.0, 2.0);
  const UvAtlas atlas = build_uv_atlas(s, UvOptions{.improve_with_lscm = true});
  expect_valid_atlas(s, atlas, "cylinder");
  expect_disks(s, atlas, "cylinder");
  // A developable surface: LSCM lays each chart out without distortion.
  for (double r : area_ratios(s, atlas)) EXPECT_NEAR(r, 1.0, 0.01);
  EXPECT_NEAR(atlas.area_ratio.p5, 1.0, 0.01);
  EXPECT_NEAR(atlas.area_ratio.p95, 1.0, 0.01);
  EXPECT_LT(atlas.conformal_distortion.p95, 1.01);
  // Unrolled whole: one chart, cut open along one seam.
  EXPECT_EQ(atlas.num_charts, 1);
}

// A flat half ring (radii 3 and 4: area 11.0 in an 8 x 4 box, fill 0.34)
// unfolds into one chart that leaves most of the square empty; halved for
// the packing, its pieces fill it better, and each keeps its part of the
// isometric layout (area ratio and conformal distortion 1 on every
// triangle). A flat L (8 x 8, arms 2 wide: fill 0.44) is tried too: its
// median cut falls inside one arm, its tightest-box cut at the corner
// gives a 2 x 8 and a 6 x 2 bar, which still need a square of side 8
// (the same 0.44), so neither packs better and it stays whole: never worse.
TEST(UvAtlas, AChartThatFillsItsBoxPoorlyIsHalvedWhenThatPacksBetter) {
  TriSurface ring;
  const int n = 48, m = 4;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= n; ++i) {
      const double a = std::numbers::pi * i / n, r = 3.0 + 1.0 * j / m;
      ring.points.push_back({r * std::cos(a), r * std::sin(a), 0.0});
    }
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const Index a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      ring.triangles.push_back({a, d, b});
      ring.triangles.push_back({a, c, d});
    }
  const TriSurface l = remove_triangles(triangulated_box({0, 0, 0}, {8, 8, 1}, 16), [](const Vec3& c) {
    return c.z > 1e-9 || (c.x > 2.0 && c.y > 2.0);
  });
  for (const auto& [surface, name] : {std::pair<const TriSurface*, const char*>{&ring, "half ring"}, {&l, "L"}}) {
    UvOptions whole{.improve_with_lscm = true};
    whole.pack_max_splits = 0;
    const UvAtlas one = build_uv_atlas(*surface, whole);
    const UvAtlas halved = build_uv_atlas(*surface, UvOptions{.improve_with_lscm = true});
    expect_valid_atlas(*surface, halved, name);
    expect_disks(*surface, halved, name);
    EXPECT_EQ(one.num_charts, 1) << name;
    EXPECT_LE(halved.num_charts, 8) << name;
    EXPECT_GE(halved.packing_efficiency, one.packing_efficiency - 1e-12) << name;
    EXPECT_NEAR(halved.area_ratio.min, 1.0, 1e-6) << name;
    EXPECT_NEAR(halved.area_ratio.max, 1.0, 1e-6) << name;
    EXPECT_NEAR(halved.conformal_distortion.max, 1.0, 1e-6) << name;
    if (surface == &ring) {
      EXPECT_GE(halved.num_charts, 2);
      EXPECT_GT(halved.packing_efficiency, one.packing_efficiency + 0.1)
          << one.packing_efficiency << " -> " << halved.packing_efficiency;
    }
  }
}

TEST(UvAtlas, SphereAndTorusAreCutIntoFewDisks) {
  const TriSurface sphere = icosphere(4);
  const UvAtlas a = build_uv_atlas(sphere, UvOptions{.improve_with_lscm = true});
  expect_valid_atlas(sphere, a, "sphere");
  expect_disks(sphere, a, "sphere");
  EXPECT_LE(a.num_charts, 2);
  EXPECT_GE(a.area_fraction_area_ratio_within_2, 0.9);
  const TriSurface ring = torus(96, 32, 2.0, 0.6);
  const UvAtlas b = build_uv_atlas(ring, UvOptions{.improve_with_lscm = true});
  expect_valid_atlas(ring, b, "torus");
  expect_disks(ring, b, "torus");
  EXPECT_GE(b.area_fraction_area_ratio_within_2, 0.9);
  // One disk: the last union is an annulus, cut open by disk_cut.
  EXPECT_EQ(b.num_charts, 1);
}

// Sum of the lengths of the edges `keys` of s.
double seam_length(const TriSurface& s, const std::vector<std::uint64_t>& keys) {
  double length = 0.0;
  for (std::uint64_t k : keys) length += norm(s.points[k >> 32] - s.points[k & 0xffffffffu]);
  return length;
}

std::vector<Index> all_triangles(const TriSurface& s) {
  std::vector<Index> tris(s.triangles.size());
  for (std::size_t t = 0; t < tris.size(); ++t) tris[t] = static_cast<Index>(t);
  return tris;
}

// Across each edge of each triangle: the triangle on its other side, or
// kNoIndex (3 per triangle).
std::vector<Index> triangle_neighbours(const TriSurface& s) {
  std::map<std::pair<Index, Index>, std::pair<Index, int>> first;
  std::vector<Index> out(3 * s.triangles.size(), kNoIndex);
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Index a = s.triangles[t][k], b = s.triangles[t][(k + 1) % 3];
      const auto key = std::minmax(a, b);
      if (const auto it = first.find(key); it != first.end()) {
        out[3 * t + k] = it->second.first;
        out[3 * static_cast<std::size_t>(it->second.first) + it->second.second] = static_cast<Index>(t);
      } else {
        first.emplace(key, std::pair{static_cast<Index>(t), k});
      }
    }
  return out;
}

TEST(UvCut, AZigzagCutThroughARowOfDiagonalsIsStraightened) {
  // A 10 x 10 grid of unit squares, each halved by its diagonal from (i, j)
  // to (i+1, j+1). Side 1: triangles whose centroid lies left of x = 4.5.
  // In column 4 the upper triangle (centroid x 4 1/3) is on side 1 and the
  // lower (4 2/3) on side 2: the cut runs up the 10 diagonals of column 4
  // and the 9 edges between the rows there, 10 sqrt 2 + 9 long (worked by
  // hand). Each upper triangle of column 4 but the top one borders the
  // other side across its diagonal and its top edge and moves; the cut
  // then runs up the line x = 4 for 9 rows and across the top diagonal:
  // 10 edges, 9 + sqrt 2 long.
  const int n = 10;
  TriSurface s;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) s.points.push_back({double(i), double(j), 0.0});
  const auto v = [&](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      s.triangles.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      s.triangles.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  const std::vector<Index> neighbour = triangle_neighbours(s);
  std::vector<std::uint8_t> side(s.triangles.size());
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    double x = 0.0;
    for (Index p : s.triangles[t]) x += s.points[p].x / 3.0;
    side[t] = x < 4.5 ? 1 : 2;
  }
  const auto cut = [&](const std::vector<std::uint8_t>& by) {
    std::vector<std::uint64_t> keys;
    for (std::size_t t = 0; t < s.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const Index m = neighbour[3 * t + k];
        if (m != kNoIndex && static_cast<std::size_t>(m) > t && by[m] != by[t]) {
          const auto [a, b] = std::minmax(s.triangles[t][k], s.triangles[t][(k + 1) % 3]);
          keys.push_back(std::uint64_t(a) << 32 | std::uint64_t(b));
        }
      }
    return keys;
  };
  ASSERT_EQ(cut(side).size(), 19u);
  EXPECT_NEAR(seam_length(s, cut(side)), 10 * std::sqrt(2.0) + 9, 1e-12);
  const std::vector<Index> tris = all_triangles(s);
  // Edges that are not glued do not count: nothing moves.
  std::vector<std::uint8_t> unglued = side;
  straighten_two_way_cut(tris, neighbour, unglued, [](Index, int, Index) { return false; });
  EXPECT_EQ(unglued, side);
  straighten_two_way_cut(tris, neighbour, side, [](Index, int, Index) { return true; });
  ASSERT_EQ(cut(side).size(), 10u);
  EXPECT_NEAR(seam_length(s, cut(side)), 9 + std::sqrt(2.0), 1e-12);
  EXPECT_EQ(std::count(side.begin(), side.end(), 1), 2 * 4 * n + 1);  // 4 columns and the top upper triangle
}

// The chart mesh is built face by face (Euler::add_face) without a soup
// check first: what is no disk polygon mesh is still refused, and the uvs
// are left as they were. Points of a unit square and one above it.
TEST(LscmChartLayout, RefusesChartsThatAreNoDiskMesh) {
  TriSurface s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}, {2, 0, 0}, {2, 1, 0}};
  const auto layout = [&](std::vector<std::array<Index, 3>> triangles) {
    s.triangles = std::move(triangles);
    std::vector<Uv> uv{{7, 7}};
    const bool ok = lscm_chart_layout(s, all_triangles(s), uv);
    if (!ok) EXPECT_EQ(uv, (std::vector<Uv>{{7, 7}})) << "untouched";
    return ok;
  };
  EXPECT_TRUE(layout({{0, 1, 2}, {0, 2, 3}})) << "a square";
  EXPECT_FALSE(layout({{0, 1, 2}, {0, 3, 2}})) << "two triangles turned against each other";
  EXPECT_FALSE(layout({{0, 1, 2}, {0, 2, 3}, {0, 2, 4}})) << "three triangles on one edge";
  EXPECT_FALSE(layout({{0, 1, 2}, {2, 5, 6}})) << "a bowtie: two pieces at one vertex";
  EXPECT_FALSE(layout({{0, 1, 1}, {0, 1, 2}})) << "a triangle repeating a vertex";
  EXPECT_FALSE(layout({{0, 1, 2}, {0, 1, 2}})) << "a triangle twice";
}

TEST(UvCut, AnOpenCylinderIsCutAlongOneShortestLineBetweenItsBorders) {
  // 48 around, 10 rings, height 2: the shortest path between the two
  // borders is one vertical line of 10 edges, length 2.
  const TriSurface s = open_cylinder(48, 10, 1.0, 2.0);
  const std::vector<Index> tris = all_triangles(s);
  const std::vector<std::uint64_t> cut = disk_cut(s, tris, {});
  ASSERT_EQ(cut.size(), 10u);
  EXPECT_NEAR(seam_length(s, cut), 2.0, 1e-12);
  for (std::uint64_t k : cut) EXPECT_EQ((k & 0xffffffffu) - (k >> 32), 48u);  // vertical: one ring apart
  std::vector<Uv> uv;
  EXPECT_TRUE(lscm_chart_layout(s, tris, uv, cut));
  EXPECT_FALSE(lscm_chart_layout(s, tris, uv, {}));  // uncut it is no disk
}

TEST(UvCut, AClosedTorusIsCutIntoOneDiskAlongTwoLoops) {
  const TriSurface s = torus(48, 16, 2.0, 0.6);
  const std::vector<Index> tris = all_triangles(s);
  const std::vector<std::uint64_t> cut = disk_cut(s, tris, {});
  std::vector<Uv> uv;
  ASSERT_TRUE(lscm_chart_layout(s, tris, uv, cut));
  // No longer than the meridian and the outer equator through the first
  // vertex (both polylines of the grid), which together cut it open; at
  // least the meridian, the shortest loop that is not contractible.
  const double meridian = 16 * 2 * 0.6 * std::sin(std::numbers::pi / 16);
  const double equator = 48 * 2 * 2.6 * std::sin(std::numbers::pi / 48);
  EXPECT_LE(seam_length(s, cut), meridian + equator + 1e-9);
  EXPECT_GE(seam_length(s, cut), meridian - 1e-9);
}

TEST(UvLscm, GoodEnoughKeepsTheLscmLayoutOrAsksForArapFromIt) {
  // Half an icosphere (a disk): with a callback that accepts, the arap
  // method returns exactly the LSCM layout; with one that refuses, exactly
  // the ARAP layout (LSCM then the iterations), which differs from LSCM.
  const TriSurface sphere = icosphere(3);
  std::vector<Index> half;
  for (Index t = 0; t < static_cast<Index>(sphere.triangles.size()); ++t) {
    const auto& tri = sphere.triangles[t];
    if (sphere.points[tri[0]].z + sphere.points[tri[1]].z + sphere.points[tri[2]].z > 0) half.push_back(t);
  }
  std::vector<Uv> lscm, arap, kept, refined;
  ASSERT_TRUE(lscm_chart_layout(sphere, half, lscm));
  ASSERT_TRUE(lscm_chart_layout(sphere, half, arap, {}, ChartLayout::arap));
  int asked = 0;
  ASSERT_TRUE(lscm_chart_layout(sphere, half, kept, {}, ChartLayout::arap, [&](std::span<const Uv> layout) {
    ++asked;
    EXPECT_TRUE(std::equal(layout.begin(), layout.end(), lscm.begin(), lscm.end()));
    return true;
  }));
  ASSERT_TRUE(lscm_chart_layout(sphere, half, refined, {}, ChartLayout::arap, [](std::span<const Uv>) { return false; }));
  EXPECT_EQ(asked, 1);
  EXPECT_EQ(kept, lscm);
  EXPECT_EQ(refined, arap);
  EXPECT_NE(arap, lscm);
  // Refusing LSCM's and ARAP's layouts, the callback is asked about the
  // ARAP iterates from the latest back; the first it accepts is returned.
  std::vector<std::vector<Uv>> seen;
  std::vector<Uv> earlier;
  ASSERT_TRUE(lscm_chart_layout(sphere, half, earlier, {}, ChartLayout::arap, [&](std::span<const Uv> layout) {
    seen.emplace_back(layout.begin(), layout.end());
    return seen.size() == 4;
  }));
  ASSERT_EQ(seen.size(), 4u);
  EXPECT_EQ(seen[0], lscm);
  EXPECT_EQ(seen[1], arap);
  EXPECT_EQ(earlier, seen[3]);
  EXPECT_NE(seen[2], arap);
  EXPECT_NE(seen[3], seen[2]);
  EXPECT_NE(seen[3], lscm);
  // Refusing everything: LSCM, ARAP and its 11 earlier iterates were asked.
  int refusals = 0;
  ASSERT_TRUE(lscm_chart_layout(sphere, half, refined, {}, ChartLayout::arap, [&](std::span<const Uv>) {
    ++refusals;
    return false;
  }));
  EXPECT_EQ(refusals, 2 + kArapIterations - 1);
  EXPECT_EQ(refined, arap);
}

TEST(UvCut, DisksSpheresAndPiecesAreLeftAsTheyAre) {
  // Half the cylinder is a disk already; a sphere would need a slit; two
  // pieces are no single chart.
  const TriSurface cylinder = open_cylinder(48, 10, 1.0, 2.0);
  std::vector<Index> half, pieces;
  for (Index t = 0; t < static_cast<Index>(cylinder.triangles.size()); ++t) {
    const Index i = t / 2 % 48, j = t / 2 / 48;
    if (i < 24) half.push_back(t);
    if (i < 10 && (j < 3 || j > 6)) pieces.push_back(t);
  }
  EXPECT_TRUE(disk_cut(cylinder, half, {}).empty());
  EXPECT_TRUE(disk_cut(cylinder, pieces, {}).empty());
  const TriSurface sphere = icosphere(3);
  EXPECT_TRUE(disk_cut(sphere, all_triangles(sphere), {}).empty());
  // A seam already cut across the cylinder leaves nothing to add.
  std::vector<std::uint64_t> line;
  for (std::uint64_t j = 0; j < 10; ++j) line.push_back((48 * j) << 32 | (48 * j + 48));
  EXPECT_TRUE(disk_cut(cylinder, all_triangles(cylinder), line).empty());
}

TEST(UvAtlas, TheMergeStopsWhenItsWorkBudgetIsSpent) {
  // The sphere needs many trial layouts to come down to two charts: with a
  // budget of one surface's worth the merge stops early, and the atlas is
  // valid all the same; with none it is the per-chart LSCM atlas.
  const TriSurface sphere = icosphere(4);
  const UvAtlas full = build_uv_atlas(sphere, UvOptions{.improve_with_lscm = true});
  const UvAtlas one = build_uv_atlas(sphere, UvOptions{.improve_with_lscm = true, .merge_work_surfaces = 1});
  const UvAtlas none = build_uv_atlas(sphere, UvOptions{.improve_with_lscm = true, .merge_work_surfaces = 0});
  const UvAtlas off = build_uv_atlas(sphere, UvOptions{.improve_with_lscm = true, .merge_by_layout = false});
  expect_valid_atlas(sphere, one, "sphere, budget 1");
  expect_disks(sphere, one, "sphere, budget 1");
  EXPECT_GT(one.num_charts, full.num_charts);
  EXPECT_LT(one.num_charts, none.num_charts);
  EXPECT_EQ(none.num_charts, off.num_charts);
  EXPECT_EQ(none.uvs, off.uvs);
}

TEST(UvAtlas, StatisticsAgreeWithARecount) {
  const TriSurface s = icosphere(3);
  const UvAtlas atlas = build_uv_atlas(s);
  const std::vector<double> r = area_ratios(s, atlas);
  double within = 0, total = 0, uv = 0;
  for (std::size_t t = 0; t < r.size(); ++t) {
    const auto& tri = s.triangles[t];
    const double a = 0.5 * norm(cross(s.points[tri[1]] - s.points[tri[0]], s.points[tri[2]] - s.points[tri[0]]));
    total += a;
    if (r[t] >= 0.5 && r[t] <= 2.0) within += a;
    const Uv* p = &atlas.uvs[3 * t];
    uv += 0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]));
  }
  EXPECT_NEAR(atlas.area_fraction_area_ratio_within_2, within / total, 1e-12);
  EXPECT_NEAR(atlas.packing_efficiency, uv, 1e-12);
  EXPECT_NEAR(atlas.area_ratio.min, *std::min_element(r.begin(), r.end()), 1e-9);
  EXPECT_NEAR(atlas.area_ratio.max, *std::max_element(r.begin(), r.end()), 1e-9);
  EXPECT_LE(atlas.area_fraction_largest_chart, atlas.area_fraction_top_4_charts);
  EXPECT_LE(atlas.area_fraction_top_4_charts, atlas.area_fraction_top_8_charts);
  EXPECT_LE(atlas.area_fraction_top_8_charts, 1.0 + 1e-12);
}

TEST(UvAtlas, ARightAngleMapHasConformalDistortionTwo) {
  // (x, y) -> (2x, y): sigma 2 and 1, area ratio 2.
  const Uv uv[3] = {{0, 0}, {2, 0}, {0, 1}};
  const TriangleDistortion d = triangle_distortion({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, uv);
  EXPECT_NEAR(d.conformal, 2.0, 1e-12);
  EXPECT_NEAR(d.area_ratio, 2.0, 1e-12);
  const Uv rotated[3] = {{0, 0}, {0, 1}, {-1, 0}};  // a quarter turn: no distortion
  const TriangleDistortion r = triangle_distortion({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, rotated);
  EXPECT_NEAR(r.conformal, 1.0, 1e-12);
  EXPECT_NEAR(r.area_ratio, 1.0, 1e-12);
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
#if defined(__SANITIZE_ADDRESS__)
  // The same surfaces go through the same steps (and LSCM's) in
  // LscmImprovementKeepsTheAtlasValid, which the sanitizer run keeps.
  GTEST_SKIP() << "under the sanitizers: covered by LscmImprovementKeepsTheAtlasValid";
#endif
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

}  // namespace
}  // namespace hq::test
