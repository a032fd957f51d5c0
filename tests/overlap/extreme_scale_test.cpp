// Legitimate meshes at any scale are analysed, not refused (issue 22): each
// mesh of ../shared/data scaled by 1e-9 and by 1e9 and translated by 1e7
// gives the same scaled Jacobians and the same overlap result, certified
// where the original is; the work budget never fires on them (in exhaustive
// mode either). And a mesh whose boxes all overlap stops at the budget.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>

#include "hqview/io/mesh_reader.h"
#include "hqview/io/read_limits.h"
#include "hqview/mesh/mesh_summary.h"
#include "hqview/overlap/overlap.h"
#include "hqview/quality/quality_field.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

struct Transform {
  const char* name;
  std::function<Vec3(const Vec3&)> apply;
};

const Transform kTransforms[] = {
    {"scaled by 1e-9", [](const Vec3& p) { return 1e-9 * p; }},
    {"scaled by 1e9", [](const Vec3& p) { return 1e9 * p; }},
    {"translated by 1e7",
     [](const Vec3& p) {
       return p + Vec3{1e7, 1e7, 1e7};
     }},
};

void expect_same_overlap(const OverlapReport& a, const OverlapReport& b) {
  EXPECT_EQ(a.certified_clean, b.certified_clean);
  EXPECT_FALSE(b.is_over_budget);
  EXPECT_EQ(a.num_coincident_vertices, b.num_coincident_vertices);
  EXPECT_EQ(a.inverted_cells, b.inverted_cells);
  EXPECT_EQ(a.degenerate_cells, b.degenerate_cells);
  EXPECT_EQ(a.num_intersecting_cells, b.num_intersecting_cells);
  ASSERT_EQ(a.intersecting_pairs.size(), b.intersecting_pairs.size());
  for (std::size_t i = 0; i < a.intersecting_pairs.size(); ++i)
    EXPECT_EQ(a.intersecting_pairs[i].cells, b.intersecting_pairs[i].cells);
}

class ExtremeScale : public testing::TestWithParam<const char*> {};

TEST_P(ExtremeScale, SameJacobiansAndOverlap) {
  const auto dir = test::shared_data_dir();
  if (!dir) GTEST_SKIP() << "../shared/data not found (set HQVIEW_DATA)";
  const HexMesh mesh = read_hex_mesh(*dir / "meshes" / GetParam()).mesh;
  const Topology topo = build_topology(mesh);
  const QualityField quality = compute_quality(mesh, topo);
  const OverlapReport overlap = check_overlap(mesh, topo, OverlapOptions{});
  EXPECT_FALSE(overlap.is_over_budget);
  const MeshSummary summary = summarize_mesh(mesh, topo);
  for (const Transform& t : kTransforms) {
    SCOPED_TRACE(t.name);
    HexMesh moved = mesh;
    for (Vec3& p : moved.points) p = t.apply(p);
    EXPECT_NO_THROW(check_coordinate_magnitudes(moved, "moved"));
    const QualityField q = compute_quality(moved, topo);
    // Scaling by a power of ten rounds each coordinate once (relative 1e-16);
    // translating by 1e7 rounds it to a multiple of 2^-29 = 1.9e-9, which
    // moves a corner Jacobian by about that over the shortest edge.
    const double tolerance =
        std::string(t.name).starts_with("translated") ? 64 * std::ldexp(1.0, -29) / summary.edge_length_min : 1e-9;
    double worst = 0.0;
    for (std::size_t i = 0; i < quality.corner_scaled_jacobian.size(); ++i)
      worst = std::max(worst, std::abs(q.corner_scaled_jacobian[i] - quality.corner_scaled_jacobian[i]));
    EXPECT_LE(worst, tolerance);
    for (std::size_t h = 0; h < quality.cell_scaled_jacobian.size(); ++h)
      ASSERT_NEAR(q.cell_scaled_jacobian[h], quality.cell_scaled_jacobian[h], tolerance) << "hex " << h;
    expect_same_overlap(overlap, check_overlap(moved, topo, OverlapOptions{}));
  }
  // Exhaustive mode tests every pair of overlapping boxes: still within the budget.
  EXPECT_FALSE(check_overlap(mesh, topo, OverlapOptions{.mode = OverlapMode::exhaustive}).is_over_budget);
}

INSTANTIATE_TEST_SUITE_P(Meshes, ExtremeScale,
                         testing::Values("gao2016_sweeping/kitten_1.mesh", "gao2016_sweeping/hand7_1.mesh",
                                         "gao2016_sweeping/Dolphin_padded.mesh", "livesu2016_skeleton/armadillo.mesh",
                                         "livesu2016_skeleton/warrior.mesh", "livesu2015_edgecone/bunny_in.mesh",
                                         "li2012_srf/fandisk.mesh", "dualsheet2019/rockarm.vtk",
                                         "smf2019/hex_cube_coarse.vtk"),
                         [](const testing::TestParamInfo<const char*>& info) {
                           std::string name = std::filesystem::path(info.param).stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

TEST(OverlapBudget, StopsWhereEveryBoxOverlapsEveryOther) {
  // n unit cubes shifted by 1e-4 along the diagonal each: all n(n-1)/2 cell
  // boxes overlap, and the lowest corner of each later cube lies inside every
  // earlier one. With a small budget the cell stage stops, certifies nothing and
  // says how many pairs it did not test.
  HexMesh mesh;
  const int n = 60;
  for (int i = 0; i < n; ++i) {
    const HexMesh cube = test::unit_cube();
    const Index base = mesh.num_vertices();
    for (const Vec3& p : cube.points) mesh.points.push_back(p + 1e-4 * i * Vec3{1, 1, 1});
    Hex h = cube.hexes[0];
    for (Index& v : h) v += base;
    mesh.hexes.push_back(h);
  }
  const Topology topo = build_topology(mesh);
  OverlapOptions options{.mode = OverlapMode::exhaustive};
  const OverlapReport full = check_overlap(mesh, topo, options);
  EXPECT_FALSE(full.is_over_budget);
  EXPECT_EQ(full.num_candidate_pairs, n * (n - 1) / 2);
  EXPECT_EQ(full.num_intersecting_cells, n);

  options.min_pair_budget = 100;
  options.pairs_per_box = 1;
  const OverlapReport stopped = check_overlap(mesh, topo, options);
  EXPECT_TRUE(stopped.is_over_budget);
  EXPECT_FALSE(stopped.certified_clean);
  EXPECT_EQ(stopped.over_budget_stage, "boundary");  // 4 x 6 x 60 = 1440 fan triangles, overlapping in bulk
  EXPECT_EQ(stopped.pair_budget, 1440);
  EXPECT_GT(stopped.num_untested_pairs, 1440);
  EXPECT_TRUE(stopped.intersecting_pairs.empty());
  EXPECT_EQ(stopped.num_candidate_pairs, 0);
}

}  // namespace
}  // namespace hq
