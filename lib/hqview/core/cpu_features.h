#pragma once
// What the CPU running HQView can do, for the kernels that have a copy
// built for a wider instruction set (cmake/HqExactArithmetic.cmake: a file
// *_avx2.cpp, built on x86-64 only, where HQ_AVX2_KERNELS is defined).
// A caller runs such a copy only where both hold:
//
//   #if HQ_AVX2_KERNELS
//     if (has_avx2()) return kernel_avx2(...);
//   #endif
//     return kernel(...);

namespace hq {

// Whether the CPU has AVX2 (asked once); false off x86-64.
bool has_avx2();

}  // namespace hq
