// Across a collection: duplicates found by geometry (the scale-invariant
// metrics), not by name, counted once; how far significance is out of reach
// with few meshes (min_p, critical_rho), by hand.
#include "hqview/report/collection_correlation.h"

#include "hqview/report/batch_index.h"

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

// Sizes across meshes in other units: the volume row is value / L^3 (L the
// bounding-box diagonal, cbrt(volume.mean) / h_over_l). Here the raw volumes
// grow with the error (each mesh in a larger unit) while the volumes in units
// of L fall: rho must be -1, not the units' +1. index.html names the row
// "volume / L³", pins the two baselines first, and turns a duplicate's error
// difference into ties among the counted meshes.
TEST(CollectionCorrelation, SizesInUnitsOfTheMeshLength) {
  std::vector<BatchEntry> entries;
  for (int i = 0; i < 6; ++i) {
    const double unit = 1.0 + i, d = 1.0 + 0.2 * i;  // L = unit * d; volume / L^3 = 0.1 / d^3
    BatchEntry e = mesh("m" + std::to_string(i) + ".mesh", 0.9 - 0.1 * i, unit, 0.01 * (i + 1), 0.1 * (i + 1));
    e.metrics.push_back({"h_over_l", 0.5 / d, 0.5 / d, 0.5 / d});  // cbrt(0.125 unit^3) / (unit d)
    entries.push_back(e);
  }
  CollectionCorrelation c = correlate_collection(entries);
  bool seen = false;
  for (const CollectionCorrelationRow& r : c.rows)
    if (r.metric == "volume") {
      seen = true;
      EXPECT_EQ(r.length_power, 3);
      EXPECT_EQ(r.num_meshes, 6);
      EXPECT_DOUBLE_EQ(r.rho_h1, -1.0) << r.stat;  // raw volumes would give +1
      EXPECT_DOUBLE_EQ(r.rho_l2, -1.0) << r.stat;
    } else if (r.metric == "scaled_jacobian") {
      EXPECT_EQ(r.length_power, 0);
    }
  EXPECT_TRUE(seen);
  EXPECT_EQ(size_length_power("dimension"), 1);
  EXPECT_EQ(size_length_power("fem_lambda_max"), 1);
  EXPECT_EQ(size_length_power("jacobian"), 3);
  EXPECT_EQ(size_length_power("fem_det_j_min"), 3);
  EXPECT_EQ(size_length_power("scaled_jacobian"), 0);
  // A 2x copy of m2 with errors 10 % (L2) and 2 % (H1) higher: m1 and m2
  // (0.02 vs 0.03 L2) differ by more; make m3's L2 5 % above m2's: one tie in L2.
  entries[3].headline[slot("fem.poisson.mean.l2_error")] = 0.0315;
  BatchEntry copy = mesh("z_copy.mesh", 0.7, 6.0, 0.033, 0.3 * 1.02);
  copy.metrics.push_back(entries[2].metrics.back());
  entries.push_back(copy);
  const std::string html = batch_index_html(entries, "test", nullptr);
  EXPECT_NE(html.find("volume / L\u00b3"), std::string::npos);
  EXPECT_NE(html.find("moved the L2 error by 9.1 % and the H1 error by 2 %: meshes whose errors differ by less are "
                      "ties. Here 1 pair of counted meshes is within that in L2 and 0 in H1"),
            std::string::npos)
      << html.substr(html.find("Placing"), 400);
  EXPECT_NE(html.find("left out: same counts and scale-invariant quality summaries as m2.mesh"), std::string::npos);
  // The baselines first: num_hexes (or h_over_l) before any metric row.
  const auto first_row = html.find("<td class=\"text\">", html.find("Which metrics rank these meshes"));
  ASSERT_NE(first_row, std::string::npos);
  const std::string cell = html.substr(first_row + 17, 9);
  EXPECT_TRUE(cell == "h_over_l<" || cell == "num_hexes") << cell;
  // The sizes after every metric with a better direction.
  EXPECT_LT(html.find(">scaled_jacobian<", first_row), html.find(">volume / L\u00b3<", first_row));
  EXPECT_LT(html.find(">edge_ratio<", first_row), html.find(">volume / L\u00b3<", first_row));
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
