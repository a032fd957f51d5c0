#pragma once
// What the two VTK readers (legacy .vtk, XML .vtu) and the VTU writer share:
// VTK's hexahedral cell type ids and corner orders (vtkCellType.h), and the
// sign extension of packed binary integers.

#include <array>
#include <cstdint>

namespace hq::vtk {

inline constexpr int kVoxel = 11;
inline constexpr int kHexahedron = 12;

// Voxel corner order (x fastest, then y, then z) to hexahedron order.
inline constexpr std::array<int, 8> kVoxelToHex = {0, 1, 3, 2, 4, 5, 7, 6};

// The low `size` bytes of bits (1 to 8) as a two's-complement integer.
inline std::int64_t sign_extend(std::uint64_t bits, int size) {
  const int shift = 64 - 8 * size;
  return static_cast<std::int64_t>(bits << shift) >> shift;
}

}  // namespace hq::vtk
