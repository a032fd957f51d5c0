// Across a collection: duplicates found by geometry (the scale-invariant
// metrics), not by name, counted once; how far significance is out of reach
// with few meshes (min_p, critical_rho), by hand.
#include "hqview/report/collection_correlation.h"

#include "hqview/report/batch_index.h"
#include "hqview/fem/moment_length.h"
#include "hqview/core/box3.h"
#include "support/fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace hq {
namespace HQ_TEST_UNIT {

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
  // A mesh left out for inverted hexes whose errors sit within the noise of
  // m3's (0.2 % in L2, 0.5 % in H1): counting it would add one tie in L2
  // and one in H1 (issue 48h round 2: the ties ran over it).
  BatchEntry folded = mesh("f_folded.mesh", 0.95, 1.0, 0.03157, 0.402);
  folded.metrics.push_back({"h_over_l", 0.9, 0.9, 0.9});
  folded.headline[slot("quality.num_inverted")] = 3;
  entries.push_back(folded);
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

// The cell texts of the index.html table row whose first cell is `first`.
std::vector<std::string> table_row(const std::string& html, const std::string& first) {
  std::vector<std::string> cells;
  const auto row = html.find("<td class=\"text\">" + first + "</td>");
  if (row == std::string::npos) return cells;
  const auto end = html.find("</tr>", row);
  for (auto at = html.find("<td", row); at < end; at = html.find("<td", at + 1)) {
    const auto open = html.find('>', at) + 1;
    cells.push_back(html.substr(open, html.find("</td>", open) - open));
  }
  return cells;
}

// One Benjamini-Hochberg family for the table and the sentence above it:
// mean volume / L^3 = (h/L)^3 restates h_over_l (same ranks) and is not a
// second hypothesis. Five meshes, by hand: h/L falls as the errors rise (rho
// -1, p = 2/5! = 1/60), and so does min volume / L^3; the shape metrics
// (ranks of sj 3,5,1,4,2) have rho -0.3. Family: edge_ratio, fem_kappa,
// scaled_jacobian (worst, mean), volume (min), h_over_l = 8 rows (num_hexes
// is constant: null); 2 of them at p = 1/60, so q = (1/60) 8 / 2 = 1/15 (with
// the restated row counted it would be (1/60) 9 / 3 = 0.05). The sentence's
// q is the table's.
TEST(CollectionCorrelation, RestatedBaselineIsNotASecondHypothesis) {
  std::vector<BatchEntry> entries;
  const double sj[] = {0.7, 0.9, 0.5, 0.8, 0.6};
  for (int i = 0; i < 5; ++i) {
    const double unit = 1.0 + i, d = 1.0 + 0.2 * i;
    BatchEntry e = mesh("m" + std::to_string(i) + ".mesh", sj[i], unit, 0.01 * (i + 1), 0.1 * (i + 1));
    e.metrics.push_back({"h_over_l", 0.5 / d, 0.5 / d, 0.5 / d});
    entries.push_back(e);
  }
  // A sixth mesh with inverted hexes: left out (its check ran on a map that folds).
  BatchEntry folded = mesh("f_folded.mesh", 0.95, 1.0, 0.5, 5.0);
  folded.metrics.push_back({"h_over_l", 0.9, 0.9, 0.9});
  folded.headline[slot("quality.num_inverted")] = 18;
  entries.push_back(folded);
  const CollectionCorrelation c = correlate_collection(entries);
  EXPECT_EQ(c.num_meshes, 5);
  EXPECT_EQ(c.inverted, std::vector<std::string>{"f_folded.mesh"});
  EXPECT_EQ(c.num_hypotheses_h1, 8);
  EXPECT_EQ(c.num_hypotheses_l2, 8);
  const auto row = [&](const std::string& metric, const std::string& stat) {
    return *std::find_if(c.rows.begin(), c.rows.end(), [&](const CollectionCorrelationRow& r) {
      return r.metric == metric && r.stat == stat;
    });
  };
  const CollectionCorrelationRow h = row("h_over_l", "value"), restated = row("volume", "mean");
  EXPECT_EQ(restated.restates, "h_over_l");
  EXPECT_TRUE(row("volume", "min").restates.empty());
  EXPECT_DOUBLE_EQ(h.rho_h1, -1.0);
  EXPECT_DOUBLE_EQ(restated.rho_h1, -1.0);
  EXPECT_NEAR(h.p_h1, 1.0 / 60.0, 1e-15);
  EXPECT_NEAR(h.q_h1, 1.0 / 15.0, 1e-15);
  EXPECT_NEAR(row("volume", "min").q_h1, 1.0 / 15.0, 1e-15);
  EXPECT_EQ(restated.q_h1, h.q_h1);
  EXPECT_EQ(restated.q_l2, h.q_l2);
  EXPECT_NEAR(row("scaled_jacobian", "worst").rho_h1, -0.3, 1e-12);
  const std::string html = batch_index_html(entries, "test", nullptr);
  const auto power = html.find("The Benjamini\u2013Hochberg family: the 8 rows");
  ASSERT_NE(power, std::string::npos) << html;
  const std::string sentence = "Here, H1: 2 rows at the smallest p, 0.0167 (volume (min), h_over_l): q = ";
  const auto at = html.find(sentence, power);
  ASSERT_NE(at, std::string::npos) << html.substr(power, 900);
  const std::string sentence_q = html.substr(at + sentence.size(), html.find(';', at) - at - sentence.size());
  const std::vector<std::string> cells = table_row(html, "h_over_l");
  ASSERT_GE(cells.size(), 9u);
  EXPECT_EQ(cells[8], sentence_q);  // q(H1) in the table = q in the sentence
  EXPECT_EQ(sentence_q, "0.0667");
  EXPECT_NE(html.find("mean (restates h_over_l)<"), std::string::npos);
  // h/L ranks the errors exactly: nothing left for a metric given h/L.
  EXPECT_TRUE(std::isnan(row("scaled_jacobian", "worst").rho_h1_given_h));
  EXPECT_TRUE(std::isnan(h.rho_h1_given_h));
  EXPECT_NE(html.find("h/L alone ranks these meshes\u2019 errors (\u03c1 = -1.000 with L2, -1.000 with H1)"),
            std::string::npos);
  EXPECT_NE(html.find("one swap of neighbouring ranks moves \u03c1 by 12/(n(n\u00b2\u22121)) = 0.1."),
            std::string::npos);
  EXPECT_NE(html.find("left out: 18 inverted hexes"), std::string::npos);
}

// L for h/L (fem.poisson.mesh_length): the diagonal of the box with the
// mesh's second moments of volume. By hand: a 2 x 3 x 4 box of unit hexes has
// L = sqrt(4 + 9 + 16) exactly (its bounding-box diagonal); a copy turned
// about a skew axis, mirrored, scaled by 2.5 and moved 1e3 away keeps L (x 2.5)
// to 1e-12 relative, though its bounding-box diagonal changes by percents;
// the same with interior vertices moved and the box bent (no box).
TEST(CollectionCorrelation, MeshLengthIsPlacementFree) {
  HexMesh box = test::box_grid(2, 3, 4);
  EXPECT_NEAR(moment_length(volume_moments(box)), std::sqrt(29.0), 1e-12 * std::sqrt(29.0));
  EXPECT_NEAR(moment_length(volume_moments(test::unit_cube())), std::sqrt(3.0), 1e-14);
  // Interior vertices moved (a fixed pattern): not a box any more.
  HexMesh bent = test::box_grid(4, 3, 5);
  for (std::size_t v = 0; v < bent.points.size(); ++v) {
    Vec3& p = bent.points[v];
    if (p.x > 0 && p.x < 4 && p.y > 0 && p.y < 3 && p.z > 0 && p.z < 5)
      for (int a = 0; a < 3; ++a) {
        const double t = std::sin(12.9898 * static_cast<double>(v) + 78.233 * a) * 43758.5453;
        p[a] += 0.3 * (t - std::floor(t) - 0.5);
      }
    p.z += 0.2 * p.x * p.x;  // and bent: its sides curve
  }
  // A rotation about the unit axis (1, 2, 3)/sqrt 14 by 0.7 rad (Rodrigues), a
  // mirror in x; a mesh turned inside out (the mirror alone) has no length.
  const Vec3 k = (1.0 / std::sqrt(14.0)) * Vec3{1, 2, 3};
  const double c = std::cos(0.7), s = std::sin(0.7);
  const auto turn = [&](const HexMesh& m, double scale) {
    HexMesh out = m;
    for (Vec3& p : out.points) {
      const Vec3 r = c * p + s * cross(k, p) + (1 - c) * dot(k, p) * k;
      p = scale * Vec3{-r.x, r.y, r.z} + Vec3{1e3, -2e3, 5e2};
    }
    // The mirror turns every hex inside out: its top and bottom swapped back.
    for (Hex& h : out.hexes) h = {h[4], h[5], h[6], h[7], h[0], h[1], h[2], h[3]};
    return out;
  };
  const auto diagonal = [](const HexMesh& m) {
    Box3 b;
    for (const Vec3& p : m.points) b.add(p);
    return b.diagonal();
  };
  for (const HexMesh* m : {&box, &bent}) {
    const HexMesh turned = turn(*m, 2.5);
    const double l = moment_length(volume_moments(*m)), lt = moment_length(volume_moments(turned));
    EXPECT_NEAR(lt, 2.5 * l, 1e-12 * lt);
    // The bounding-box diagonal is not placement-free (what L replaces).
    EXPECT_GT(std::abs(diagonal(turned) / 2.5 - diagonal(*m)), 0.02 * diagonal(*m));
  }
  HexMesh inside_out = box;
  for (Vec3& p : inside_out.points) p.x = -p.x;
  EXPECT_TRUE(std::isnan(moment_length(volume_moments(inside_out))));
  // h/L from report.json: the mesh length, not the bounding-box diagonal.
  ReportDocument report;
  report["fem"]["poisson"]["skipped"] = nullptr;
  report["fem"]["poisson"]["mesh_length"] = 4.0;
  report["fem"]["poisson"]["normalization"]["diagonal"] = 5.0;
  report["quality"]["metrics"]["volume"] = {{"min", 1.0}, {"mean", 8.0}, {"max", 9.0}};
  const std::vector<MeshMetricRange> summaries = metric_summaries_from_report(report);
  const auto h = std::find_if(summaries.begin(), summaries.end(), [](const MeshMetricRange& m) { return m.metric == "h_over_l"; });
  ASSERT_NE(h, summaries.end());
  EXPECT_DOUBLE_EQ(h->mean, 0.5);  // cbrt(8) / 4
}

}  // namespace
}  // namespace hq
