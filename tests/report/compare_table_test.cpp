// The side-by-side rows of --compare and diff (compare_table.h): a
// difference of rounding only (a relative 1e-12) reads 0 and is not worse;
// a real one keeps its sign and its "worse" flag in either direction.

#include "hqview/report/compare_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace hq {
namespace HQ_TEST_UNIT {

const CompareTableRow& row(const std::vector<CompareTableRow>& rows, const std::string& label) {
  for (const CompareTableRow& r : rows)
    if (r.label == label) return r;
  throw std::runtime_error("no row " + label);
}

CompareNumbers hex_mesh(double sj_min, double sj_mean, double sj_p05) {
  CompareNumbers n;
  n.num_vertices = 27;
  n.num_hexes = 8;
  n.num_cells = 8;
  n.hex_fraction = n.hex_volume_fraction = 1;
  n.sj_min = sj_min;
  n.sj_mean = sj_mean;
  n.sj_p05 = sj_p05;
  n.vertex_quality_min = sj_min;
  n.bbox_diagonal = std::sqrt(3.0);
  n.edge_length_mean = 0.5;
  return n;
}

TEST(CompareTable, RoundingIsNoDifferenceAndARealOneIsWorse) {
  const double mean = 0.8599752219208608;
  const CompareNumbers mine = hex_mesh(0.5, mean, 0.6);
  // One ulp below on the mean (a sum in another order), 1e-9 below on p05
  // (real, if small), 0.1 above on the min (better).
  const CompareNumbers theirs = hex_mesh(0.6, std::nextafter(mean, 0.0), 0.6 - 1e-9);
  const std::vector<CompareTableRow> rows = compare_rows(mine, theirs);
  EXPECT_EQ(row(rows, "mean scaled Jacobian").difference, "0");
  EXPECT_FALSE(row(rows, "mean scaled Jacobian").is_worse);
  EXPECT_EQ(row(rows, "p05 scaled Jacobian").difference, "-1e-09");
  EXPECT_TRUE(row(rows, "p05 scaled Jacobian").is_worse);
  EXPECT_EQ(row(rows, "min scaled Jacobian").difference, "+0.1");
  EXPECT_FALSE(row(rows, "min scaled Jacobian").is_worse);
  // The other way round: the min is now worse.
  EXPECT_TRUE(row(compare_rows(theirs, mine), "min scaled Jacobian").is_worse);
  EXPECT_EQ(row(compare_rows(theirs, mine), "mean scaled Jacobian").difference, "0");
}

}  // namespace
}  // namespace hq
