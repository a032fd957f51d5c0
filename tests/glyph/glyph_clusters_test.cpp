// cluster_glyphs() against an all-pairs reference written here: random point
// sets with random radii (wide, narrow, bimodal; exact ties at ri + rj;
// coincident points), every real mesh of ../shared/data, and every thread
// count. bound_glyph_clusters() (the default clusters since issue 44's
// fifth round) against a reference written from its definition, a chain
// computed by hand, and its properties (extent, connectivity, a refinement
// of the components).

#include "hqview/glyph/glyph_clusters.h"
#include "hqview/glyph/bounded_clusters.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numeric>
#include <queue>
#include <random>

#include "hqview/core/error.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/mesh/topology.h"
#include "hqview/quality/quality_field.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

// The definition, pair by pair: |pi − pj| < ri + rj with the squared distance
// ((dx² + dy²) + dz²) against (ri + rj)², glyphs where the radius is finite
// and > 0; components numbered by their smallest point id.
std::vector<Index> all_pairs_clusters(std::span<const Vec3> p, std::span<const double> r) {
  const std::size_t n = p.size();
  std::vector<Index> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](Index x) {
    while (parent[static_cast<std::size_t>(x)] != x)
      x = parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    return x;
  };
  auto has_glyph = [&](std::size_t i) { return std::isfinite(r[i]) && r[i] > 0.0; };
  for (std::size_t i = 0; i < n; ++i) {
    if (!has_glyph(i)) continue;
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!has_glyph(j)) continue;
      const double dx = p[i].x - p[j].x, dy = p[i].y - p[j].y, dz = p[i].z - p[j].z;
      const double s = r[i] + r[j];
      if (dx * dx + dy * dy + dz * dz < s * s) {
        const Index a = find(static_cast<Index>(i)), b = find(static_cast<Index>(j));
        parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
      }
    }
  }
  std::vector<Index> label(n, kNoIndex), cluster_of_root(n, kNoIndex);
  Index next = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!has_glyph(i)) continue;
    const auto root = static_cast<std::size_t>(find(static_cast<Index>(i)));
    if (cluster_of_root[root] == kNoIndex) cluster_of_root[root] = next++;
    label[i] = cluster_of_root[root];
  }
  return label;
}

// The bounded clusters by their definition (bounded_clusters.h), without
// components or a grid: glyphs in turn by radius (largest first, then the
// smallest id) seed a cluster of the glyphs not taken yet that lie strictly
// within reach · r_seed of the seed and are reached from it through
// overlapping pairs of such glyphs. Numbered by smallest member.
std::vector<Index> bounded_reference(std::span<const Vec3> p, std::span<const double> r, double reach) {
  const std::size_t n = p.size();
  auto has_glyph = [&](std::size_t i) { return std::isfinite(r[i]) && r[i] > 0.0; };
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < n; ++i)
    if (has_glyph(i)) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return r[a] > r[b]; });
  std::vector<Index> seed_of(n, kNoIndex);
  for (std::size_t s : order) {
    if (seed_of[s] != kNoIndex) continue;
    const double ball = reach * r[s];
    std::vector<std::size_t> candidates;
    for (std::size_t i = 0; i < n; ++i) {
      if (i == s || !has_glyph(i) || seed_of[i] != kNoIndex) continue;
      const double dx = p[i].x - p[s].x, dy = p[i].y - p[s].y, dz = p[i].z - p[s].z;
      if (dx * dx + dy * dy + dz * dz < ball * ball) candidates.push_back(i);
    }
    std::queue<std::size_t> queue;
    queue.push(s);
    seed_of[s] = static_cast<Index>(s);
    while (!queue.empty()) {
      const std::size_t g = queue.front();
      queue.pop();
      for (std::size_t c : candidates)
        if (seed_of[c] == kNoIndex && glyphs_overlap(p[g], r[g], p[c], r[c])) {
          seed_of[c] = static_cast<Index>(s);
          queue.push(c);
        }
    }
  }
  // Renumber by smallest member.
  std::vector<Index> label(n, kNoIndex), number(n, kNoIndex);
  Index next = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (seed_of[i] == kNoIndex) continue;
    const auto s = static_cast<std::size_t>(seed_of[i]);
    if (number[s] == kNoIndex) number[s] = next++;
    label[i] = number[s];
  }
  return label;
}

// The CSR part must agree with point_cluster.
void expect_consistent(const GlyphClusters& c, std::size_t num_points) {
  ASSERT_EQ(c.point_cluster.size(), num_points);
  ASSERT_FALSE(c.offsets.empty());
  EXPECT_EQ(c.offsets.front(), 0);
  EXPECT_EQ(static_cast<std::size_t>(c.offsets.back()), c.members.size());
  for (Index k = 0; k < c.num_clusters(); ++k) {
    ASSERT_LT(c.offsets[k], c.offsets[k + 1]) << "empty cluster " << k;
    for (Index m = c.offsets[k]; m < c.offsets[k + 1]; ++m) {
      EXPECT_EQ(c.point_cluster[static_cast<std::size_t>(c.members[m])], k);
      if (m > c.offsets[k]) {
        EXPECT_LT(c.members[m - 1], c.members[m]);
      }
    }
    if (k > 0) {
      EXPECT_LT(c.members[c.offsets[k - 1]], c.members[c.offsets[k]]) << "numbered by smallest member";
    }
  }
  const auto with_glyph =
      std::count_if(c.point_cluster.begin(), c.point_cluster.end(), [](Index x) { return x != kNoIndex; });
  EXPECT_EQ(static_cast<std::size_t>(with_glyph), c.members.size());
}

void expect_matches_all_pairs(std::span<const Vec3> p, std::span<const double> r, const std::string& what) {
  const GlyphClusters c = cluster_glyphs(p, r);
  expect_consistent(c, p.size());
  const std::vector<Index> expected = all_pairs_clusters(p, r);
  ASSERT_EQ(c.point_cluster.size(), expected.size());
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < expected.size(); ++i)
    if (c.point_cluster[i] != expected[i] && mismatches++ < 5) {
      ADD_FAILURE() << what << ": point " << i << " in cluster " << c.point_cluster[i] << ", all-pairs says "
                    << expected[i];
    }
  EXPECT_EQ(mismatches, 0u) << what;
}

// bound_glyph_clusters against the reference, and its properties: every
// member within reach · r of its cluster's largest glyph, each cluster
// inside one component (a refinement), the components' glyphs all kept.
void expect_bounded_matches_reference(std::span<const Vec3> p, std::span<const double> r, const std::string& what,
                                      double reach = kClusterReach) {
  const GlyphClusters components = cluster_glyphs(p, r);
  const GlyphClusters c = bound_glyph_clusters(components, p, r, reach);
  expect_consistent(c, p.size());
  const std::vector<Index> expected = bounded_reference(p, r, reach);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < expected.size(); ++i)
    if (c.point_cluster[i] != expected[i] && mismatches++ < 5) {
      ADD_FAILURE() << what << ": point " << i << " in bounded cluster " << c.point_cluster[i]
                    << ", the reference says " << expected[i];
    }
  EXPECT_EQ(mismatches, 0u) << what;
  for (Index k = 0; k < c.num_clusters(); ++k) {
    const std::span<const Index> m(c.members.data() + c.offsets[k], static_cast<std::size_t>(c.offsets[k + 1] - c.offsets[k]));
    std::size_t seed = static_cast<std::size_t>(m[0]);
    for (Index v : m)
      if (r[static_cast<std::size_t>(v)] > r[seed]) seed = static_cast<std::size_t>(v);
    for (Index v : m) {
      const Vec3 d = p[static_cast<std::size_t>(v)] - p[seed];
      EXPECT_LT(std::sqrt(squared_norm(d)), reach * r[seed] * (1 + 1e-12) + 1e-300) << what << ": cluster " << k;
      EXPECT_EQ(components.point_cluster[static_cast<std::size_t>(v)], components.point_cluster[seed]) << what;
    }
  }
}

enum class RadiusLaw { kUniform, kNarrow, kLogUniform, kBimodal, kWithHoles };

struct RandomSet {
  std::vector<Vec3> points;
  std::vector<double> radii;
};

RandomSet random_set(std::uint64_t seed, int n, RadiusLaw law, double box) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> coord(0.0, box), unit(0.0, 1.0);
  RandomSet s;
  for (int i = 0; i < n; ++i) {
    s.points.push_back({coord(rng), coord(rng), coord(rng)});
    const double u = unit(rng);
    double r = 0;
    switch (law) {
      case RadiusLaw::kUniform:
        r = 2.0 * u;
        break;
      case RadiusLaw::kNarrow:
        r = 0.5 + 0.1 * u;
        break;
      case RadiusLaw::kLogUniform:
        r = std::pow(10.0, -3.0 + 3.5 * u);
        break;
      case RadiusLaw::kBimodal:
        r = unit(rng) < 0.02 ? 3.0 + 3.0 * u : 0.05 + 0.3 * u;
        break;
      case RadiusLaw::kWithHoles: {
        const double pick = unit(rng);
        r = pick < 0.2    ? 0.0
            : pick < 0.25 ? -1.0
            : pick < 0.3  ? std::numeric_limits<double>::quiet_NaN()
            : pick < 0.32 ? std::numeric_limits<double>::infinity()
                          : u;
        break;
      }
    }
    s.radii.push_back(r);
  }
  return s;
}

TEST(GlyphClusters, RandomSetsMatchAllPairs) {
  const RadiusLaw laws[] = {RadiusLaw::kUniform, RadiusLaw::kNarrow, RadiusLaw::kLogUniform, RadiusLaw::kBimodal,
                            RadiusLaw::kWithHoles};
  std::uint64_t seed = 1;
  for (RadiusLaw law : laws)
    for (int n : {1, 2, 7, 60, 500, 3000})
      for (double box : {3.0, 20.0, 60.0}) {
        const RandomSet s = random_set(seed, n, law, box);
        expect_matches_all_pairs(s.points, s.radii,
                                 "seed " + std::to_string(seed) + " law " + std::to_string(static_cast<int>(law)) +
                                     " n " + std::to_string(n) + " box " + std::to_string(box));
        ++seed;
      }
}

TEST(GlyphClusters, BoundedRandomSetsMatchTheReference) {
  const RadiusLaw laws[] = {RadiusLaw::kUniform, RadiusLaw::kNarrow, RadiusLaw::kLogUniform, RadiusLaw::kBimodal,
                            RadiusLaw::kWithHoles};
  std::uint64_t seed = 1001;
  for (RadiusLaw law : laws)
    for (int n : {1, 2, 7, 60, 500, 2000})
      for (double box : {3.0, 12.0, 40.0}) {
        const RandomSet s = random_set(seed, n, law, box);
        const std::string what = "seed " + std::to_string(seed) + " law " + std::to_string(static_cast<int>(law)) +
                                 " n " + std::to_string(n) + " box " + std::to_string(box);
        expect_bounded_matches_reference(s.points, s.radii, what);
        if (n == 500) expect_bounded_matches_reference(s.points, s.radii, what + " reach 3.5", 3.5);
        ++seed;
      }
  // Integer lattices with radii in eighths: exact ties at the ball's edge
  // (reach · r) and at ri + rj, and coincident points.
  for (std::uint64_t lattice = 1; lattice <= 15; ++lattice) {
    std::mt19937_64 rng(lattice);
    const int n = 50 + static_cast<int>(rng() % 800), side = 3 + static_cast<int>(rng() % 10);
    std::vector<Vec3> points;
    std::vector<double> radii;
    for (int i = 0; i < n; ++i) {
      points.push_back({double(rng() % side), double(rng() % side), double(rng() % side)});
      radii.push_back(static_cast<double>(rng() % 9) / 8.0);
    }
    expect_bounded_matches_reference(points, radii, "lattice " + std::to_string(lattice));
  }
}

TEST(GlyphClusters, BoundedChainComputedByHand) {
  // Ten equal glyphs (r = 1) on a line, 1.5 apart: one component (1.5 < 2),
  // the chain issue 44's review saw across bunny_in. Seeds by smallest id:
  // point 0's ball (radius 2) holds point 1 (1.5) but not point 2 (3), so
  // the clusters are {0, 1}, {2, 3}, ..., {8, 9}.
  std::vector<Vec3> points;
  std::vector<double> radii(10, 1.0);
  for (int i = 0; i < 10; ++i) points.push_back({1.5 * i, 0, 0});
  const GlyphClusters components = cluster_glyphs(points, radii);
  EXPECT_EQ(components.num_clusters(), 1);
  const GlyphClusters c = bound_glyph_clusters(components, points, radii);
  EXPECT_EQ(c.point_cluster, (std::vector<Index>{0, 0, 1, 1, 2, 2, 3, 3, 4, 4}));
  // A worse glyph (r = 2) at point 5 seeds first: its ball (radius 4) holds
  // points 3, 4, 6, 7 (3 and 7 at 3.0, 2 and 8 at 4.5); it reaches 4 and 6
  // directly (1.5 < 3), 3 and 7 through them. Then {0, 1}, {2}, {8, 9}.
  radii[5] = 2.0;
  const GlyphClusters worse = bound_glyph_clusters(cluster_glyphs(points, radii), points, radii);
  EXPECT_EQ(worse.point_cluster, (std::vector<Index>{0, 0, 1, 2, 2, 2, 2, 2, 3, 3}));
  // A glyph inside the ball that the seed reaches only through a glyph
  // outside it stays out. Seed 0 (r 1) at the origin, ball radius 2;
  // 1 (r 0.6) at (1.5, 0) overlaps it (1.5 < 1.6); 2 (r 0.7) at (2.4, 0.8)
  // is outside the ball (2.53) and overlaps 1 (1.204 < 1.3); 3 (r 0.45) at
  // (1.4, 1.3) is inside the ball (1.91) but overlaps neither 0 (1.91 >
  // 1.45) nor 1 (1.3 > 1.05), only 2 (1.118 < 1.15). One component; the
  // clusters {0, 1} and, seeded by 2 (ball 1.4), {2, 3}.
  const std::vector<Vec3> hook{{0, 0, 0}, {1.5, 0, 0}, {2.4, 0.8, 0}, {1.4, 1.3, 0}};
  const std::vector<double> hook_r{1.0, 0.6, 0.7, 0.45};
  EXPECT_EQ(cluster_glyphs(hook, hook_r).num_clusters(), 1);
  const GlyphClusters h = bound_glyph_clusters(cluster_glyphs(hook, hook_r), hook, hook_r);
  EXPECT_EQ(h.point_cluster, (std::vector<Index>{0, 0, 1, 1}));
  expect_bounded_matches_reference(hook, hook_r, "hook");
  EXPECT_THROW(bound_glyph_clusters(components, points, radii, 0.0), Error);
  EXPECT_THROW(bound_glyph_clusters(components, points, std::vector<double>(3, 1.0)), Error);
}

TEST(GlyphClusters, BoundedIdenticalForEveryThreadCount) {
  const RandomSet s = random_set(4242, 20000, RadiusLaw::kNarrow, 20.0);
  tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 8);
  const GlyphClusters components = cluster_glyphs(s.points, s.radii);
  GlyphClusters reference;
  tbb::task_arena(1).execute([&] { reference = bound_glyph_clusters(components, s.points, s.radii); });
  EXPECT_GT(reference.num_clusters(), components.num_clusters());
  for (int threads : {2, 4, 8}) {
    GlyphClusters c;
    tbb::task_arena(threads).execute([&] { c = bound_glyph_clusters(components, s.points, s.radii); });
    EXPECT_EQ(c.point_cluster, reference.point_cluster) << threads;
    EXPECT_EQ(c.members, reference.members) << threads;
  }
}

TEST(GlyphClusters, ExactTiesDoNotOverlap) {
  // A lattice of spacing 1 with radii 1/4 and 3/4 (exact in binary): every
  // pair of lattice neighbours touches exactly (distance = ri + rj) unless
  // both radii are 3/4. Diagonal neighbours (√2) overlap when both are 3/4.
  std::vector<Vec3> points;
  std::vector<double> radii;
  std::mt19937_64 rng(42);
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        points.push_back({double(x), double(y), double(z)});
        radii.push_back((rng() % 3 == 0) ? 0.75 : 0.25);
      }
  expect_matches_all_pairs(points, radii, "lattice 1/4, 3/4");

  // Radii exactly 1/2 everywhere: neighbours touch, nobody overlaps.
  std::vector<double> halves(points.size(), 0.5);
  const GlyphClusters touching = cluster_glyphs(points, halves);
  EXPECT_EQ(touching.num_clusters(), static_cast<Index>(points.size()));
  // The next double above 1/2: every lattice neighbour pair overlaps, one cluster.
  std::vector<double> above(points.size(), std::nextafter(0.5, 1.0));
  EXPECT_EQ(cluster_glyphs(points, above).num_clusters(), 1);
  expect_matches_all_pairs(points, above, "lattice just above 1/2");

  // Shifted off the origin and scaled by a power of two: still exact ties.
  std::vector<Vec3> shifted;
  for (const Vec3& p : points) shifted.push_back(Vec3{1024.0, -512.0, 3.0} + 0.125 * p);
  std::vector<double> eighths(points.size(), 0.0625);
  EXPECT_EQ(cluster_glyphs(shifted, eighths).num_clusters(), static_cast<Index>(points.size()));
  expect_matches_all_pairs(shifted, eighths, "scaled lattice");
}

TEST(GlyphClusters, RandomLatticeSetsWithTiesAndCoincidentPoints) {
  // Integer coordinates and radii in eighths: all arithmetic is exact, so
  // many pairs sit exactly at |pi − pj| = ri + rj (touching, not merged), many
  // points coincide, and a few large radii take the large-glyph search.
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    std::mt19937_64 rng(seed);
    const int n = 50 + static_cast<int>(rng() % 1500);
    const int side = 4 + static_cast<int>(rng() % 16);
    std::vector<Vec3> points;
    std::vector<double> radii;
    for (int i = 0; i < n; ++i) {
      points.push_back({double(rng() % side), double(rng() % side), double(rng() % side)});
      const int eighths = rng() % 50 == 0 ? 8 + static_cast<int>(rng() % 40) : static_cast<int>(rng() % 9);
      radii.push_back(eighths / 8.0);  // 0: no glyph
    }
    expect_matches_all_pairs(points, radii, "lattice seed " + std::to_string(seed));
  }
}

TEST(GlyphClusters, TiesInsideTheLargeGlyphSearch) {
  // Two large glyphs (radius 4) among small ones: around the first, six
  // partners on the axes at distance exactly 4 + 1/2 with radius 1/2 touch;
  // around the second, the same partners with a radius one rounding step
  // larger (4 + r = the next double after 4.5) overlap.
  const double touching = 0.5, overlapping = std::nextafter(4.5, 5.0) - 4.0;
  ASSERT_EQ(4.0 + overlapping, std::nextafter(4.5, 5.0));
  std::vector<Vec3> points{{0, 0, 0}, {50, 0, 0}};
  std::vector<double> radii{4.0, 4.0};
  for (int centre = 0; centre < 2; ++centre)
    for (const Vec3 d :
         {Vec3{4.5, 0, 0}, Vec3{-4.5, 0, 0}, Vec3{0, 4.5, 0}, Vec3{0, -4.5, 0}, Vec3{0, 0, 4.5}, Vec3{0, 0, -4.5}}) {
      points.push_back(points[static_cast<std::size_t>(centre)] + d);
      radii.push_back(centre == 0 ? touching : overlapping);
    }
  // Enough small glyphs for the large ones to be above the 99th percentile.
  for (int i = 0; i < 300; ++i) {
    points.push_back({20.0 + i, 20.0, 20.0});
    radii.push_back(0.25);
  }
  expect_matches_all_pairs(points, radii, "large glyph ties");
  const GlyphClusters c = cluster_glyphs(points, radii);
  for (std::size_t i = 2; i < 8; ++i) EXPECT_NE(c.point_cluster[i], c.point_cluster[0]) << "point " << i;
  for (std::size_t i = 8; i < 14; ++i) EXPECT_EQ(c.point_cluster[i], c.point_cluster[1]) << "point " << i;
}

TEST(GlyphClusters, LargeGlyphsOfEqualRadius) {
  // Large glyphs of one radius that overlap only each other (each pair of
  // large glyphs is tested by one of the two, so equal radii need a rule).
  std::vector<Vec3> points;
  std::vector<double> radii;
  for (int i = 0; i < 400; ++i) {
    points.push_back({double(i), 100.0, 0.0});
    radii.push_back(0.125);
  }
  for (const Vec3 p : {Vec3{0, 0, 0}, Vec3{5, 0, 0}, Vec3{20, 0, 0}, Vec3{20, 0, 7.75}, Vec3{50, 50, 50}}) {
    points.push_back(p);
    radii.push_back(4.0);
  }
  expect_matches_all_pairs(points, radii, "equal large radii");
  const GlyphClusters c = cluster_glyphs(points, radii);
  EXPECT_EQ(c.point_cluster[400], c.point_cluster[401]);
  EXPECT_EQ(c.point_cluster[402], c.point_cluster[403]);
  EXPECT_NE(c.point_cluster[401], c.point_cluster[402]);
  EXPECT_EQ(c.num_clusters(), 400 + 3);
}

TEST(GlyphClusters, CoincidentPointsOverlap) {
  std::vector<Vec3> points{{1, 2, 3}, {1, 2, 3}, {1, 2, 3}, {5, 5, 5}, {5, 5, 5}, {9, 9, 9}};
  std::vector<double> radii{1e-12, 1e-12, 0.0, 1e-150, 1e-150, 1.0};
  const GlyphClusters c = cluster_glyphs(points, radii);
  EXPECT_EQ(c.point_cluster, (std::vector<Index>{0, 0, kNoIndex, 1, 1, 2}));
  EXPECT_EQ(c.num_clusters(), 3);
  expect_matches_all_pairs(points, radii, "coincident");
  // Many glyphs at one point: one cluster.
  std::vector<Vec3> same(200, Vec3{0.5, 0.5, 0.5});
  std::vector<double> tiny(200, 1e-9);
  EXPECT_EQ(cluster_glyphs(same, tiny).num_clusters(), 1);
}

TEST(GlyphClusters, EmptyAndNoGlyphs) {
  EXPECT_EQ(cluster_glyphs({}, {}).num_clusters(), 0);
  std::vector<Vec3> points(4);
  std::vector<double> radii(4, 0.0);
  const GlyphClusters c = cluster_glyphs(points, radii);
  EXPECT_EQ(c.num_clusters(), 0);
  EXPECT_EQ(c.point_cluster, std::vector<Index>(4, kNoIndex));
  EXPECT_THROW(cluster_glyphs(points, std::vector<double>(3, 1.0)), Error);
}

TEST(GlyphClusters, FarApartAndHugeCoordinates) {
  // Extents far beyond 2^20 cells: the grid coarsens, the result stays exact.
  std::vector<Vec3> points{{0, 0, 0}, {1e-3, 0, 0}, {1e12, 0, 0}, {1e12 + 1e-3, 0, 0}, {-1e12, 5e11, 0}};
  std::vector<double> radii{1e-3, 1e-3, 1e-3, 1e-4, 1.0};
  expect_matches_all_pairs(points, radii, "far apart");
  EXPECT_EQ(cluster_glyphs(points, radii).num_clusters(), 3);
}

TEST(GlyphClusters, PropertyInvarianceUnderTranslationByPowerOfTwoScale) {
  // Scaling by 2^k and translating by a multiple of a large power of two keep
  // every comparison exact, so the clusters must not change.
  const RandomSet s = random_set(777, 2000, RadiusLaw::kUniform, 25.0);
  const GlyphClusters base = cluster_glyphs(s.points, s.radii);
  std::vector<Vec3> moved;
  std::vector<double> scaled;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    moved.push_back(0.25 * s.points[i]);
    scaled.push_back(0.25 * s.radii[i]);
  }
  EXPECT_EQ(cluster_glyphs(moved, scaled).point_cluster, base.point_cluster);
}

TEST(GlyphClusters, IdenticalForEveryThreadCount) {
  for (RadiusLaw law : {RadiusLaw::kUniform, RadiusLaw::kBimodal, RadiusLaw::kLogUniform}) {
    const RandomSet s = random_set(99 + static_cast<int>(law), 60000, law, 60.0);
    // Allow more threads than cores, so that 4 and 8 really run concurrently.
    tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 8);
    GlyphClusters reference;
    tbb::task_arena one(1);
    one.execute([&] { reference = cluster_glyphs(s.points, s.radii); });
    for (int threads : {2, 3, 4, 8}) {
      tbb::task_arena arena(threads);
      for (int repeat = 0; repeat < 3; ++repeat) {
        GlyphClusters c;
        arena.execute([&] { c = cluster_glyphs(s.points, s.radii); });
        EXPECT_EQ(c.point_cluster, reference.point_cluster) << threads << " threads";
        EXPECT_EQ(c.offsets, reference.offsets) << threads << " threads";
        EXPECT_EQ(c.members, reference.members) << threads << " threads";
      }
    }
  }
}

// Every hex mesh of ../shared/data, with the glyph radii of a few settings.
TEST(GlyphClusters, RealMeshesMatchAllPairs) {
  const auto data = test::shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data (or $HQVIEW_DATA) not found";
  const std::vector<std::filesystem::path> files = test::shared_hex_meshes(*data);
  ASSERT_GE(files.size(), 11u);
  // The all-pairs reference is quadratic: up to this many glyphs (~1.3e9 pairs).
  constexpr std::size_t kMaxGlyphs = 50000;
  int compared = 0;
  for (const auto& file : files) {
    const HexMesh mesh = read_hex_mesh(file).mesh;
    const Topology topo = build_topology(mesh);
    const QualityField q = compute_quality(mesh, topo);
    const double mean_edge = test::mean_edge_length(mesh, topo);
    struct Setting {
      double threshold, rmax;
    };
    for (const Setting s : {Setting{0.0, 1.0}, Setting{0.5, 1.0}, Setting{0.2, 2.0}, Setting{0.5, 0.3}}) {
      std::vector<double> radii(mesh.points.size(), 0.0);
      std::size_t glyphs = 0;
      for (std::size_t v = 0; v < radii.size(); ++v) {
        const double c = 1.0 - q.vertex_quality[v];
        if (c > s.threshold) radii[v] = c * s.rmax * mean_edge, ++glyphs;
      }
      if (glyphs > kMaxGlyphs) continue;
      if (s.threshold == 0.5 && s.rmax == 1.0)  // the default setting
        expect_bounded_matches_reference(mesh.points, radii, file.filename().string() + " bounded");
      expect_matches_all_pairs(
          mesh.points, radii,
          file.filename().string() + " threshold " + std::to_string(s.threshold) + " rmax " + std::to_string(s.rmax));
      ++compared;
    }
  }
  EXPECT_GE(compared, 40);
}

}  // namespace
}  // namespace hq
