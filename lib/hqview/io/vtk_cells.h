#pragma once
// What the two VTK readers (legacy .vtk, XML .vtu) and the VTU writer share:
// VTK's volume cell type ids and corner orders (vtkCellType.h), and the
// sign extension of packed binary integers.

#include <array>
#include <cstdint>
#include <optional>

#include "hqview/core/cell_kinds.h"

namespace hq::vtk {

inline constexpr int kTetra = 10;
inline constexpr int kVoxel = 11;
inline constexpr int kHexahedron = 12;
inline constexpr int kWedge = 13;
inline constexpr int kPyramid = 14;

// The cell kind a linear volume VTK type is read as (a voxel as a
// hexahedron), none for every other type.
inline std::optional<CellKind> volume_kind(std::int64_t type) {
  switch (type) {
    case kTetra:
      return CellKind::tet;
    case kVoxel:
    case kHexahedron:
      return CellKind::hex;
    case kWedge:
      return CellKind::wedge;
    case kPyramid:
      return CellKind::pyramid;
    default:
      return std::nullopt;
  }
}

// The type's name in messages: "tetra", "voxel", "hexahedron", "wedge", "pyramid".
inline const char* volume_type_name(std::int64_t type) {
  switch (type) {
    case kTetra:
      return "tetra";
    case kVoxel:
      return "voxel";
    case kWedge:
      return "wedge";
    case kPyramid:
      return "pyramid";
    default:
      return "hexahedron";
  }
}

// Voxel corner order (x fastest, then y, then z) to hexahedron order.
inline constexpr std::array<int, 8> kVoxelToHex = {0, 1, 3, 2, 4, 5, 7, 6};

// The low `size` bytes of bits (1 to 8) as a two's-complement integer.
inline std::int64_t sign_extend(std::uint64_t bits, int size) {
  const int shift = 64 - 8 * size;
  return static_cast<std::int64_t>(bits << shift) >> shift;
}

}  // namespace hq::vtk
