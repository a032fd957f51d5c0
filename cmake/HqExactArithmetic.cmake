# Code whose results are promised bit for bit (the Verdict kernels of the
# quality module, the FEM product's fixed sums) is built without
# contracting a * b + c into a fused multiply-add, which rounds once instead
# of twice: GCC and Clang contract by default wherever the target has FMA
# (aarch64 always; x86-64 with -mfma).
#
# Some of that code also has a copy built for AVX2 (a file *_avx2.cpp with
# -mavx2 -mno-fma: wider vectors, the same operations), run only where the
# CPU has AVX2 (hq::has_avx2(), core/cpu_features.h). Such copies are
# built on x86-64 only; HQ_AVX2_KERNELS=1 then says to the targets built
# through hq_exact_arithmetic that they exist, so that their calls to them
# are compiled (a target without it runs the baseline build: the same bits).
include(CheckCXXCompilerFlag)
check_cxx_compiler_flag("-ffp-contract=off" HQ_HAS_FP_CONTRACT_OFF)
check_cxx_compiler_flag("-mavx2 -mno-fma -ffp-contract=off" HQ_HAS_AVX2_FLAGS)
if(HQ_HAS_AVX2_FLAGS AND CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64|amd64)$")
  set(HQ_AVX2_KERNELS ON)
else()
  set(HQ_AVX2_KERNELS OFF)
endif()

# hq_exact_arithmetic(<target> [AVX2 <files>...]): <target> built without
# contraction and told of the AVX2 copies; those of its own, <files>, added
# to it where they can be built.
function(hq_exact_arithmetic target)
  cmake_parse_arguments(ARG "" "" "AVX2" ${ARGN})
  if(HQ_HAS_FP_CONTRACT_OFF)
    target_compile_options(${target} PRIVATE -ffp-contract=off)
  endif()
  if(HQ_AVX2_KERNELS)
    target_compile_definitions(${target} PRIVATE HQ_AVX2_KERNELS=1)
    if(ARG_AVX2)
      target_sources(${target} PRIVATE ${ARG_AVX2})
      set_source_files_properties(${ARG_AVX2} PROPERTIES COMPILE_OPTIONS "-mavx2;-mno-fma")
    endif()
  endif()
endfunction()
