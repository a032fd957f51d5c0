#include "hqview/core/cpu_features.h"

namespace hq {

bool has_avx2() {
#if defined(__x86_64__) || defined(_M_X64)
  static const bool yes = __builtin_cpu_supports("avx2");
  return yes;
#else
  return false;
#endif
}

}  // namespace hq
