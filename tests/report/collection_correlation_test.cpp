// Across a collection: duplicates found by geometry (the scale-invariant
// metrics), not by name, counted once; how far significance is out of reach
// with few meshes (min_p, critical_rho), by hand.
#include "hqview/report/collection_correlation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace hq {
namespace {

std::size_t slot(std::string_view key) {
  std::size_t k = 0;
  while (k < kNumHeadlineKeys && key != kHeadlineKeys[k]) ++k;
  return k;
}

// A mesh of 8 hexes whose scaled Jacobian min is sj, scaled by `scale`
// (the volume follows, the shape metrics do not), with errors l2 and h1.
BatchEntry mesh(const std::string& path, double sj, double scale, double l2, double h1) {
  BatchEntry e;
  e.path = path;
  e.status = BatchStatus::ok;
  e.headline[slot("mesh.num_vertices")] = 27;
  e.headline[slot("mesh.num_hexes")] = 8;
  e.headline[slot("fem.poisson.mean.l2_error")] = l2;
  e.headline[slot("fem.poisson.mean.h1_error")] = h1;
  e.metrics = {{"edge_ratio", 1.0, 1.1 + (1 - sj), 1.3 + (1 - sj)},
               {"fem_kappa", 3.0, 3.2 + (1 - sj), 3.9 + (1 - sj)},
               {"scaled_jacobian", sj, 0.5 * (1 + sj), 1.0},
               {"volume", 0.1 * scale * scale * scale, 0.125 * scale * scale * scale, 0.2 * scale * scale * scale}};
  return e;
}

TEST(CollectionCorrelation, DuplicatesByGeometryCountOnce) {
  std::vector<BatchEntry> entries;
  const double sj[] = {0.9, 0.8, 0.7, 0.6, 0.5, 0.4};
  for (int i = 0; i < 6; ++i)
    entries.push_back(mesh("m" + std::to_string(i) + ".mesh", sj[i], 1.0, 0.01 * (i + 1), 0.1 * (i + 1)));
  // A rotated, 3x scaled copy of m2 under another name: same shape metrics,
  // other volume, errors 10 % higher (the problem sits elsewhere on it).
  entries.push_back(mesh("z_rotated.mesh", 0.7, 3.0, 0.033, 0.33));
  // Not a duplicate: m4's shape with one metric off by 1e-6 relative.
  BatchEntry near = mesh("y_near.mesh", 0.5, 1.0, 0.02, 0.2);
  near.metrics[1].mean *= 1 + 1e-6;
  EXPECT_TRUE(same_mesh_geometry(entries[2], entries[6]));
  EXPECT_FALSE(same_mesh_geometry(entries[4], near));
  EXPECT_FALSE(same_mesh_geometry(entries[1], entries[2]));
  const CollectionCorrelation c = correlate_collection(entries);
  EXPECT_EQ(c.num_meshes, 6);
  ASSERT_EQ(c.duplicates.size(), 1u);
  EXPECT_EQ(c.duplicates[0].path, "z_rotated.mesh");
  EXPECT_EQ(c.duplicates[0].same_as, "m2.mesh");
  EXPECT_NEAR(c.duplicates[0].l2_difference, 0.003 / 0.033, 1e-12);
  EXPECT_NEAR(c.duplicates[0].h1_difference, 0.03 / 0.33, 1e-12);
  // Over the six distinct meshes the min SJ falls as the error rises: rho = -1,
  // exact p = 2/720 (the copy, counted twice, would have tied two ranks).
  for (const CollectionCorrelationRow& r : c.rows)
    if (r.metric == "scaled_jacobian" && r.stat == "worst") {
      EXPECT_EQ(r.num_meshes, 6);
      EXPECT_DOUBLE_EQ(r.rho_h1, -1.0);
      EXPECT_NEAR(r.p_h1, 2.0 / 720.0, 1e-15);
    }
  // By hand: 2/6!, and the smallest |rho| with exact p <= 0.05 over 6 ranks,
  // 31/35 (sum d^2 = 4: 1 - 24/210; counted in the test below).
  EXPECT_NEAR(c.min_p, 2.0 / 720.0, 1e-15);
  EXPECT_NEAR(c.critical_rho, 31.0 / 35.0, 1e-12);
  // Without the copy: the same rows (it was left out).
  std::vector<BatchEntry> distinct(entries.begin(), entries.begin() + 6);
  const CollectionCorrelation d = correlate_collection(distinct);
  ASSERT_EQ(d.rows.size(), c.rows.size());
  for (std::size_t i = 0; i < d.rows.size(); ++i) {
    EXPECT_EQ(d.rows[i].metric, c.rows[i].metric);
    if (std::isfinite(d.rows[i].rho_h1)) {
      EXPECT_EQ(d.rows[i].rho_h1, c.rows[i].rho_h1) << d.rows[i].metric;
    }
  }
}

// The critical |rho| from the permutation distribution, counted here: over
// n = 6 ranks, the fraction of the 720 orders with |rho| >= v.
TEST(CollectionCorrelation, CriticalRhoIsTheFivePercentPoint) {
  std::vector<int> order = {0, 1, 2, 3, 4, 5};
  std::vector<double> all;
  do {
    double d2 = 0;
    for (int i = 0; i < 6; ++i) d2 += (order[i] - i) * (order[i] - i);
    all.push_back(std::abs(1.0 - 6.0 * d2 / 210.0));
  } while (std::next_permutation(order.begin(), order.end()));
  const auto fraction = [&](double v) {
    return static_cast<double>(std::count_if(all.begin(), all.end(), [&](double a) { return a >= v - 1e-12; })) / 720.0;
  };
  EXPECT_LE(fraction(31.0 / 35.0), 0.05);  // critical: p <= 0.05 ...
  EXPECT_GT(fraction(29.0 / 35.0), 0.05);  // ... and the next value down is not
  std::vector<BatchEntry> entries;
  for (int i = 0; i < 6; ++i)
    entries.push_back(mesh("m" + std::to_string(i), 0.9 - 0.1 * i, 1.0, 0.01 * (i + 1), 0.1 * (i + 1)));
  EXPECT_NEAR(correlate_collection(entries).critical_rho, 31.0 / 35.0, 1e-12);
  // Four meshes: below the minimum, no statement.
  entries.resize(4);
  const CollectionCorrelation few = correlate_collection(entries);
  EXPECT_TRUE(std::isnan(few.min_p) && std::isnan(few.critical_rho));
}

}  // namespace
}  // namespace hq
