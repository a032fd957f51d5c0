// The mesh-wide metric field: per-hex kernels, the mean volume, subsets, and
// the same bytes for any thread count.

#include "hqview/quality/hex_metric_field.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <random>

#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

HexMesh perturbed_grid(int n, unsigned seed) {
  HexMesh mesh = test::grid(n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (Vec3& p : mesh.points) p = p + Vec3{u(rng), u(rng), u(rng)};
  return mesh;
}

TEST(HexMetricField, EqualsTheKernelsWithTheMeanVolume) {
  const HexMesh mesh = perturbed_grid(6, 1);
  const HexMetricField field = compute_hex_metrics(mesh);
  EXPECT_EQ(field.computed, all_hex_metrics());
  double sum = 0;
  for (Index h = 0; h < mesh.num_hexes(); ++h) sum += hex_volume(hex_corners(mesh, h));
  EXPECT_EQ(field.average_volume, sum / mesh.num_hexes());
  for (Index h = 0; h < mesh.num_hexes(); ++h)
    for (int m = 0; m < kNumHexMetrics; ++m)
      EXPECT_EQ(field.values[static_cast<std::size_t>(m)][static_cast<std::size_t>(h)],
                hex_metric(static_cast<HexMetric>(m), hex_corners(mesh, h), field.average_volume))
          << hex_metric_name(static_cast<HexMetric>(m)) << " hex " << h;
}

TEST(HexMetricField, SubsetComputesOnlyWhatIsAskedPlusScaledJacobian) {
  HexMetricSet which;
  insert(which, HexMetric::oddy);
  const HexMetricField field = compute_hex_metrics(test::grid(2), which);
  for (int m = 0; m < kNumHexMetrics; ++m) {
    const auto metric = static_cast<HexMetric>(m);
    const bool expected = metric == HexMetric::oddy || metric == HexMetric::scaled_jacobian;
    EXPECT_EQ(contains(field.computed, metric), expected) << hex_metric_name(metric);
    EXPECT_EQ(field.of(metric).size(), expected ? 8u : 0u) << hex_metric_name(metric);
  }
  EXPECT_EQ(field.average_volume, 0.0);
}

TEST(HexMetricField, SameValuesForOneAndTwoThreads) {
  const HexMesh mesh = perturbed_grid(20, 2);
  HexMetricField one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = compute_hex_metrics(mesh);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = compute_hex_metrics(mesh);
  }
  EXPECT_EQ(one.average_volume, two.average_volume);
  for (int m = 0; m < kNumHexMetrics; ++m)
    EXPECT_EQ(one.values[static_cast<std::size_t>(m)], two.values[static_cast<std::size_t>(m)]);
}

}  // namespace
}  // namespace hq
