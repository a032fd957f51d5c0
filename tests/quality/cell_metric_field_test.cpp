// The per-block metric field of tets, wedges, pyramids, quads and triangles
// on meshes built by hand (a unit cube split into 6 tets, 2 wedges or 6
// pyramids; a planar quad grid and its triangulation): every value equals
// the per-cell kernel with the block's mean size, the mean and the inverted
// counts are the hand-computed ones, and -j1 equals -j2 bit for bit.

#include "hqview/quality/cell_metric_field.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include "hqview/quality/pyramid_metrics.h"
#include "hqview/quality/quad_metrics.h"
#include "hqview/quality/tet_metrics.h"
#include "hqview/quality/triangle_metrics.h"
#include "hqview/quality/wedge_metrics.h"

namespace hq {
namespace HQ_TEST_UNIT {

// The unit cube's corners in VTK_HEXAHEDRON order, then its centre (8).
const std::vector<Vec3> kCube = {Vec3{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},      {0, 0, 1},
                                 {1, 0, 1},     {1, 1, 1}, {0, 1, 1}, {0.5, 0.5, 0.5}};

template <std::size_t N>
std::array<Vec3, N> corners(const std::vector<Vec3>& points, const std::array<Index, N>& cell) {
  std::array<Vec3, N> p;
  for (std::size_t i = 0; i < N; ++i) p[i] = points[static_cast<std::size_t>(cell[i])];
  return p;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(CellMetricField, CubeTetsEqualTheKernelsWithTheBlockMean) {
  // Kuhn's 6 tets along the diagonal 0-6 (each det 1, volume 1/6) and one
  // mirrored copy of the first.
  const std::vector<std::array<Index, 4>> tets = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6},
                                                  {0, 4, 5, 6}, {0, 5, 1, 6}, {0, 2, 1, 6}};
  const auto field = compute_tet_block_metrics(kCube, tets);
  EXPECT_EQ(field.kind, CellKind::tet);
  EXPECT_EQ(field.count, 7);
  EXPECT_NEAR(field.average_size, (6.0 / 6 - 1.0 / 6) / 7, 1e-16);
  EXPECT_EQ(field.num_inverted, 1);
  EXPECT_EQ(field.validity[6], CellValidity::inverted);
  ASSERT_EQ(field.names.size(), static_cast<std::size_t>(kNumTetMetrics));
  for (std::size_t c = 0; c < tets.size(); ++c) {
    const auto expected = tet_metrics(corners(kCube, tets[c]), field.average_size);
    for (int m = 0; m < kNumTetMetrics; ++m) {
      const double v = field.values[static_cast<std::size_t>(m)][c];
      EXPECT_TRUE(v == expected[m] || (std::isnan(v) && std::isnan(expected[m]))) << field.names[m];
    }
    const auto k = tet_corner_scaled_jacobians(corners(kCube, tets[c]));
    for (int i = 0; i < 4; ++i) EXPECT_EQ(field.corner_scaled_jacobian[c * 4 + i], k.value[i]);
  }
  EXPECT_NEAR((*field.of("volume"))[0], 1.0 / 6, 1e-16);
  EXPECT_EQ(field.of("hex_only_metric"), nullptr);
  // Relative size against the mean 5/42: min(r, 1/r)^2 with r = (1/6)/(5/42).
  const double r = (1.0 / 6) / ((6.0 / 6 - 1.0 / 6) / 7);
  EXPECT_NEAR((*field.of("relative_size_squared"))[0], 1 / (r * r), 1e-12);

  const auto summary = summarize_cell_block(field);
  ASSERT_EQ(summary.size(), static_cast<std::size_t>(kNumTetMetrics) + 1);
  EXPECT_EQ(summary.back().name, "corner_scaled_jacobian");
  EXPECT_EQ(summary.back().stats.count, 28);
  EXPECT_EQ(summary.back().stats.num_inverted, 4);  // the mirrored tet's 4 corners
  for (const auto& s : summary)
    if (s.name == "scaled_jacobian") {
      EXPECT_EQ(s.stats.count, 7);
      EXPECT_EQ(s.stats.num_inverted, 1);
      EXPECT_EQ(s.stats.histogram.edges.front(), -1.0);
    }
}

TEST(CellMetricField, CubeWedgesAndPyramids) {
  // Two wedges in VTK order (normal of the first triangle away from the second).
  const std::vector<std::array<Index, 6>> wedges = {{0, 2, 1, 4, 6, 5}, {0, 3, 2, 4, 7, 6}};
  const auto w = compute_wedge_block_metrics(kCube, wedges);
  EXPECT_EQ(w.num_inverted, 0);
  EXPECT_NEAR(w.average_size, 0.5, 1e-16);
  for (double v : *w.of("scaled_jacobian")) EXPECT_NEAR(v, std::sqrt(2.0 / 3.0), 1e-15);  // 2/sqrt(3) sin 45
  EXPECT_EQ(w.corners_per_cell, 6);
  // Six pyramids from the cube's faces to its centre, base counter-clockwise
  // seen from the apex; the last with its apex pushed through its base.
  std::vector<Vec3> points = kCube;
  points.push_back({0.5, 0.5, -0.5});  // 9: below the bottom face
  const std::vector<std::array<Index, 5>> pyramids = {{1, 2, 3, 0, 8}, {7, 6, 5, 4, 8}, {4, 5, 1, 0, 8},
                                                      {6, 7, 3, 2, 8}, {5, 6, 2, 1, 8}, {7, 4, 0, 3, 8},
                                                      {1, 2, 3, 0, 9}};
  const auto p = compute_pyramid_block_metrics(points, pyramids);
  EXPECT_EQ(p.num_inverted, 1);
  EXPECT_EQ(p.validity[6], CellValidity::inverted);
  double sum = 0;
  for (int c = 0; c < 6; ++c) sum += (*p.of("volume"))[static_cast<std::size_t>(c)];
  EXPECT_NEAR(sum, 1.0, 1e-15);
  EXPECT_EQ((*p.of("scaled_jacobian"))[6], 0.0);  // Verdict: 0, never negative
  EXPECT_EQ(p.corners_per_cell, 4);
  for (int i = 0; i < 4; ++i) EXPECT_LT(p.corner_scaled_jacobian[6 * 4 + static_cast<std::size_t>(i)], 0.0);
}

TEST(CellMetricField, PlanarQuadGridAndItsTriangles) {
  std::vector<Vec3> points;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) points.push_back({double(i), double(j), 0.0});
  auto id = [](int i, int j) { return static_cast<Index>(j * 4 + i); };
  std::vector<std::array<Index, 4>> quads;
  std::vector<std::array<Index, 3>> triangles;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  std::swap(quads[4][1], quads[4][3]);  // the centre quad reversed
  std::swap(triangles[0][1], triangles[0][2]);
  const Vec3 up{0, 0, 1};
  const auto own = compute_quad_block_metrics(points, quads);
  const auto planar = compute_quad_block_metrics(points, quads, up);
  EXPECT_EQ(own.num_inverted, 0);  // no orientation of its own
  EXPECT_EQ(planar.num_inverted, 1);
  EXPECT_EQ(planar.validity[4], CellValidity::inverted);
  EXPECT_NEAR(own.average_size, 1.0, 1e-16);
  EXPECT_EQ(*own.of("scaled_jacobian"), *planar.of("scaled_jacobian"));  // Verdict's value either way
  const auto t = compute_triangle_block_metrics(points, triangles, up);
  EXPECT_EQ(t.num_inverted, 1);
  EXPECT_NEAR(t.average_size, 0.5, 1e-16);
  EXPECT_EQ(compute_triangle_block_metrics(points, triangles).num_inverted, 0);
}

TEST(CellMetricField, SameBitsForAnyThreadCount) {
  // 5000 jittered tets (enough for several TBB tasks).
  std::mt19937 rng(4646);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  std::vector<Vec3> points;
  std::vector<std::array<Index, 4>> tets;
  for (int c = 0; c < 5000; ++c) {
    const Index b = static_cast<Index>(points.size());
    for (const Vec3& v : {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}})
      points.push_back(v + Vec3{u(rng) + c, u(rng), u(rng)});
    tets.push_back({b, b + 1, b + 2, b + 3});
  }
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    return compute_tet_block_metrics(points, tets);
  };
  const auto one = run(1), two = run(2);
  EXPECT_EQ(std::memcmp(&one.average_size, &two.average_size, sizeof(double)), 0);
  for (std::size_t m = 0; m < one.values.size(); ++m) EXPECT_TRUE(same_bits(one.values[m], two.values[m]));
  EXPECT_TRUE(same_bits(one.corner_scaled_jacobian, two.corner_scaled_jacobian));
  EXPECT_EQ(one.validity, two.validity);
}

// summarize_cell_block_metrics (one column at a time, corners given)
// against compute_*_block_metrics + summarize_cell_block: the same summaries
// bit for bit, the kept columns equal, the others empty; -j1 equals -j2.
template <CellKind K, std::size_t N, class Full>
void expect_streamed_equals_full(const std::vector<Vec3>& points, const std::vector<std::array<Index, N>>& cells,
                                 Full full_of) {
  const CellBlockMetricField full = full_of(points, cells);
  const auto expected = summarize_cell_block(full);
  // The cells' scaled Jacobian as the quality field computes it (a tet's:
  // tet_scaled_jacobian), given in the last two rounds: a tet block then
  // copies its scaled_jacobian column from it.
  std::vector<double> field_sj;
  if constexpr (K == CellKind::tet)
    for (const auto& c : cells)
      field_sj.push_back(tet_scaled_jacobian({points[static_cast<std::size_t>(c[0])], points[static_cast<std::size_t>(c[1])],
                                              points[static_cast<std::size_t>(c[2])], points[static_cast<std::size_t>(c[3])]}));
  // Choices of kept columns: a few, the factors of a product metric with it
  // (a tet's shape_and_size then read from shape and relative_size_squared,
  // as the cells.csv columns make it), none (the product computed).
  const std::vector<std::function<bool(std::string_view)>> keeps = {
      [](std::string_view name) { return name == "volume" || name == "scaled_jacobian"; },
      [](std::string_view name) {
        return name == "volume" || name == "shape" || name == "relative_size_squared" || name == "shape_and_size";
      },
      [](std::string_view) { return false; },
      [](std::string_view name) { return name == "volume" || name == "scaled_jacobian"; }};
  for (std::size_t k = 0; k < 2 * keeps.size(); ++k) {
    const auto& keep = keeps[k / 2];
    const int threads = 1 + static_cast<int>(k % 2);
    BlockCornerValues corners{full.corner_scaled_jacobian, full.corner_degenerate_mask, full.validity};
    if (k / 2 + 1 == keeps.size()) corners.cell_scaled_jacobian = field_sj;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    const SummarizedCellBlock got = summarize_cell_block_metrics<K>(points, cells, corners, keep);
    EXPECT_EQ(got.field.kind, K);
    EXPECT_EQ(got.field.count, full.count);
    EXPECT_EQ(std::memcmp(&got.field.average_size, &full.average_size, sizeof(double)), 0);
    EXPECT_EQ(got.field.num_inverted, full.num_inverted);
    EXPECT_EQ(got.field.num_flat, full.num_flat);
    EXPECT_EQ(got.field.names, full.names);
    ASSERT_EQ(got.summaries.size(), expected.size());
    for (std::size_t m = 0; m < expected.size(); ++m) {
      const Statistics &a = got.summaries[m].stats, &b = expected[m].stats;
      EXPECT_EQ(got.summaries[m].name, expected[m].name);
      EXPECT_EQ(a.count, b.count) << expected[m].name;
      EXPECT_EQ(a.num_degenerate, b.num_degenerate) << expected[m].name;
      EXPECT_EQ(a.num_inverted, b.num_inverted) << expected[m].name;
      for (const auto& [x, y] : {std::pair{a.min, b.min}, {a.max, b.max}, {a.mean, b.mean}, {a.std, b.std},
                                 {a.p01, b.p01}, {a.p50, b.p50}, {a.p99, b.p99}})
        EXPECT_EQ(std::memcmp(&x, &y, sizeof(double)), 0) << expected[m].name;
      EXPECT_EQ(a.histogram.counts, b.histogram.counts) << expected[m].name;
      EXPECT_EQ(a.histogram.edges, b.histogram.edges) << expected[m].name;
    }
    for (std::size_t m = 0; m < full.names.size(); ++m)
      if (keep(full.names[m]))
        EXPECT_TRUE(same_bits(got.field.values[m], full.values[m])) << full.names[m];
      else
        EXPECT_TRUE(got.field.values[m].empty()) << full.names[m];
  }
}

TEST(CellMetricField, GivenScaledJacobianIsCopiedNotComputed) {
  // A tet block given its cells' scaled Jacobian reads that column from it:
  // values that are not the kernel's show in the summary and the kept column.
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  const std::vector<std::array<Index, 4>> tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  const CellBlockMetricField full = compute_tet_block_metrics(points, tets);
  const std::vector<double> given = {0.25, 0.75};
  BlockCornerValues corners{full.corner_scaled_jacobian, full.corner_degenerate_mask, full.validity};
  corners.cell_scaled_jacobian = given;
  const SummarizedCellBlock got = summarize_cell_block_metrics<CellKind::tet>(
      points, tets, corners, [](std::string_view name) { return name == "scaled_jacobian"; });
  const auto m = static_cast<std::size_t>(TetMetric::scaled_jacobian);
  EXPECT_EQ(got.field.values[m], given);
  EXPECT_EQ(got.summaries[m].stats.min, 0.25);
  EXPECT_EQ(got.summaries[m].stats.max, 0.75);
  EXPECT_EQ(got.summaries[m].stats.mean, 0.5);
}

TEST(CellMetricField, SummarizedAsComputedEqualsTheWholeField) {
  // Jittered cubes, each split into Kuhn's 6 tets, 2 wedges and 6 pyramids
  // to its centre (one cube flattened: degenerate and inverted cells).
  std::mt19937 rng(4647);
  std::uniform_real_distribution<double> u(-0.15, 0.15);
  std::vector<Vec3> points;
  std::vector<std::array<Index, 4>> tets;
  std::vector<std::array<Index, 6>> wedges;
  std::vector<std::array<Index, 5>> pyramids;
  for (int c = 0; c < 400; ++c) {  // 2,400 tets: several TBB tasks
    const Index b = static_cast<Index>(points.size());
    for (const Vec3& v : kCube) points.push_back(c == 5 ? Vec3{v.x + c, v.y, 0.0} : v + Vec3{u(rng) + c, u(rng), u(rng)});
    const auto at = [&](Index i) { return b + i; };
    for (const auto& t : std::vector<std::array<Index, 4>>{{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6},
                                                           {0, 4, 5, 6}, {0, 5, 1, 6}})
      tets.push_back({at(t[0]), at(t[1]), at(t[2]), at(t[3])});
    wedges.push_back({at(0), at(2), at(1), at(4), at(6), at(5)});
    wedges.push_back({at(0), at(3), at(2), at(4), at(7), at(6)});
    pyramids.push_back({at(1), at(2), at(3), at(0), at(8)});
    pyramids.push_back({at(7), at(6), at(5), at(4), at(8)});
  }
  expect_streamed_equals_full<CellKind::tet>(points, tets, [](const auto& p, const auto& c) {
    return compute_tet_block_metrics(p, c);
  });
  expect_streamed_equals_full<CellKind::wedge>(points, wedges, [](const auto& p, const auto& c) {
    return compute_wedge_block_metrics(p, c);
  });
  expect_streamed_equals_full<CellKind::pyramid>(points, pyramids, [](const auto& p, const auto& c) {
    return compute_pyramid_block_metrics(p, c);
  });
}

}  // namespace
}  // namespace hq
