// tet_metric_list_many's kernels on AVX2's 4 lanes: built with -mavx2
// -mno-fma -ffp-contract=off (CMakeLists.txt), called by tet_metrics.cpp
// only where the CPU has AVX2. The same values as the 2-lane and one-tet
// kernels, bit for bit (tet_metric_kernels.h).

#include "hqview/quality/tet_metric_kernels.h"

static_assert(hq::tet_kernels::kTetLanes == 4, "tet_metrics_avx2.cpp is built without AVX2");

namespace hq::detail {

void tet_metric_list_many_avx2(std::span<const TetMetric> metrics, std::span<const TetCorners> tets,
                               const TetSizeReference& reference, std::span<double* const> out) {
  tet_kernels::metric_list_lanes(metrics, tets, reference, out);
}

}  // namespace hq::detail
