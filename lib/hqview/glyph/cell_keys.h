#pragma once
// Grid cells of the glyph clustering (glyph_clusters.cpp, bounded_clusters.cpp):
// integer cell coordinates, clamped to [0, kMaxCellCoord] (clamping only
// merges far cells), packed 21 bits per axis into a 63-bit key.

#include <array>
#include <cstdint>

namespace hq::glyph_cells {

inline constexpr int kAxisBits = 21;
inline constexpr std::int64_t kMaxCellCoord = (std::int64_t{1} << 20) - 1;

// The cell coordinate of u (a position in cell units from the grid's
// origin): floor(u) clamped; NaN and negatives give 0.
inline std::int64_t cell_coord(double u) {
  if (!(u > 0.0)) return 0;  // also NaN
  if (u >= static_cast<double>(kMaxCellCoord)) return kMaxCellCoord;
  return static_cast<std::int64_t>(u);
}

inline std::uint64_t cell_key(std::int64_t x, std::int64_t y, std::int64_t z) {
  return static_cast<std::uint64_t>(x) | (static_cast<std::uint64_t>(y) << kAxisBits) |
         (static_cast<std::uint64_t>(z) << (2 * kAxisBits));
}

inline std::array<std::int64_t, 3> cell_coords(std::uint64_t key) {
  constexpr std::uint64_t mask = (std::uint64_t{1} << kAxisBits) - 1;
  return {static_cast<std::int64_t>(key & mask), static_cast<std::int64_t>((key >> kAxisBits) & mask),
          static_cast<std::int64_t>(key >> (2 * kAxisBits))};
}

}  // namespace hq::glyph_cells
