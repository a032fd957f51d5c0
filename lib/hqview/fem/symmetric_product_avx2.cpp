// The four-column chunk loop of the symmetric product on AVX2: built with
// -mavx2 -mno-fma -ffp-contract=off (cmake/HqExactArithmetic.cmake), one
// 256-bit operation a four-double value; called by symmetric_product only
// where the CPU has AVX2. The same operations in the same order as the
// baseline build, so the same bits (symmetric_product.h).

#include "hqview/fem/symmetric_product.h"

namespace hq::detail {

std::array<double, 4> product_chunk_avx2(const CsrMatrix& a, bool narrow_columns, std::size_t first, std::size_t last,
                                         std::size_t head_end, const double* x, double* y, double* overflow,
                                         const double* w) {
  if (narrow_columns)
    return product_chunk<4>(a, NarrowColumns{a.column_steps.data()}, first, last, head_end, x, y, overflow, w);
  return product_chunk<4>(a, WideColumns{a.columns.data()}, first, last, head_end, x, y, overflow, w);
}

}  // namespace hq::detail
