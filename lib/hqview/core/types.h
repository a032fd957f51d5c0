#pragma once
// Index: the one integer type for vertex, cell and face ids. Counts beyond
// int32 are rejected at load time (ARCHITECTURE.md, "Core data").

#include <cstdint>
#include <limits>

namespace hq {

using Index = std::int32_t;
inline constexpr Index kNoIndex = -1;
inline constexpr std::int64_t kMaxIndexCount = std::numeric_limits<Index>::max();

}  // namespace hq
