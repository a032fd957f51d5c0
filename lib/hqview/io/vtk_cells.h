#pragma once
// What the two VTK readers (legacy .vtk, XML .vtu) and the VTU writer share:
// VTK's volume cell type ids, the types read and their point counts, corner
// orders (vtkCellType.h), and the
// sign extension of packed binary integers.

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "hqview/core/cell_kinds.h"

namespace hq::vtk {

inline constexpr int kTetra = 10;
inline constexpr int kVoxel = 11;
inline constexpr int kHexahedron = 12;
inline constexpr int kWedge = 13;
inline constexpr int kPyramid = 14;

// The volume cell types read (vtkCellType.h) and the kind each is read as:
// the linear ones (a voxel as a hexahedron), and the higher-order ones by
// their corner points, which every one of them lists first, in its linear
// kind's VTK order (VTK's "Higher-order cells" notes; vtkCellQuality reads
// them so too): quadratic tetra 24 (10 points), quadratic hexahedron 25
// (20), quadratic wedge 26 (15), quadratic pyramid 27 (13), triquadratic
// hexahedron 29 (27), quadratic linear wedge 31 (12), biquadratic quadratic
// wedge 32 (18), biquadratic quadratic hexahedron 33 (24), triquadratic
// pyramid 37 (19, VTK 9.1+), and the Lagrange (71-74) and Bezier (78-81)
// tetrahedron, hexahedron, wedge and pyramid of any order. Gmsh (4.8)
// writes its 14-node second-order pyramid as a VTK_PYRAMID of 14 points (VTK
// has no such type): read by its corners too.
struct VolumeType {
  int type;
  CellKind kind;
  int num_points;  // 0: Lagrange or Bezier, the count follows the order (lagrange_point_count_ok)
  const char* name;
};
inline constexpr VolumeType kVolumeTypes[] = {
    {kTetra, CellKind::tet, 4, "tetra"},
    {kVoxel, CellKind::hex, 8, "voxel"},
    {kHexahedron, CellKind::hex, 8, "hexahedron"},
    {kWedge, CellKind::wedge, 6, "wedge"},
    {kPyramid, CellKind::pyramid, 5, "pyramid"},
    {24, CellKind::tet, 10, "quadratic tetra"},
    {25, CellKind::hex, 20, "quadratic hexahedron"},
    {26, CellKind::wedge, 15, "quadratic wedge"},
    {27, CellKind::pyramid, 13, "quadratic pyramid"},
    {29, CellKind::hex, 27, "triquadratic hexahedron"},
    {31, CellKind::wedge, 12, "quadratic linear wedge"},
    {32, CellKind::wedge, 18, "biquadratic quadratic wedge"},
    {33, CellKind::hex, 24, "biquadratic quadratic hexahedron"},
    {37, CellKind::pyramid, 19, "triquadratic pyramid"},
    {71, CellKind::tet, 0, "Lagrange tetrahedron"},
    {72, CellKind::hex, 0, "Lagrange hexahedron"},
    {73, CellKind::wedge, 0, "Lagrange wedge"},
    {74, CellKind::pyramid, 0, "Lagrange pyramid"},
    {78, CellKind::tet, 0, "Bezier tetrahedron"},
    {79, CellKind::hex, 0, "Bezier hexahedron"},
    {80, CellKind::wedge, 0, "Bezier wedge"},
    {81, CellKind::pyramid, 0, "Bezier pyramid"},
};

// The entry of a volume type read; nullptr for every other type.
// The dimension of VTK's cell types of dimension 0-2, -1 for the others:
// vertices (1, 2), lines (3, 4, 21, 35, 68, 75), triangles, polygons,
// pixels and quads (5-9, 22, 23, 28, 30, 34, 36, 69, 70, 76, 77), linear to
// Lagrange and Bezier. Below the mesh's dimension a file skips them as notes.
inline int type_dimension(std::int64_t type) {
  switch (type) {
    case 1: case 2:
      return 0;
    case 3: case 4: case 21: case 35: case 68: case 75:
      return 1;
    case 5: case 6: case 7: case 8: case 9: case 22: case 23: case 28: case 30: case 34: case 36:
    case 69: case 70: case 76: case 77:
      return 2;
    default:
      return -1;
  }
}

inline const VolumeType* find_volume_type(std::int64_t type) {
  for (const VolumeType& entry : kVolumeTypes)
    if (entry.type == type) return &entry;
  return nullptr;
}

// The cell kind a volume VTK type is read as; none for every other type.
inline std::optional<CellKind> volume_kind(std::int64_t type) {
  const VolumeType* entry = find_volume_type(type);
  return entry != nullptr ? std::optional<CellKind>(entry->kind) : std::nullopt;
}

// Gmsh's second-order pyramid as it writes it: VTK_PYRAMID, 14 points.
inline constexpr int kGmshPyramidPoints = 14;

// The name a higher-order cell of a type with n points is counted under in
// the reader's warning: its type, "14 (14 points, as Gmsh writes a
// second-order pyramid)" for Gmsh's pyramid.
inline std::string higher_order_name(std::int64_t type, std::int64_t n) {
  return type == kPyramid && n == kGmshPyramidPoints
             ? std::to_string(type) + " (14 points, as Gmsh writes a second-order pyramid)"
             : std::to_string(type);
}

// Whether a Lagrange or Bezier cell of `kind` can have n points, for orders
// 1 to 20: tetrahedron (p+1)(p+2)(p+3)/6 or VTK's 15-point quadratic one;
// hexahedron (p+1)(q+1)(r+1), its orders maybe different per direction
// (HigherOrderDegrees); wedge (p+1)(p+2)/2 (q+1), or VTK's 21-point one;
// pyramid (p+1)(p+2)(2p+3)/6.
inline bool lagrange_point_count_ok(CellKind kind, std::int64_t n) {
  constexpr std::int64_t kMaxOrder = 20;
  const auto is_order_plus_one = [&](std::int64_t m) { return m >= 2 && m <= kMaxOrder + 1; };
  switch (kind) {
    case CellKind::tet:
      if (n == 15) return true;
      for (std::int64_t p = 1; p <= kMaxOrder; ++p)
        if (n == (p + 1) * (p + 2) * (p + 3) / 6) return true;
      return false;
    case CellKind::pyramid:
      for (std::int64_t p = 1; p <= kMaxOrder; ++p)
        if (n == (p + 1) * (p + 2) * (2 * p + 3) / 6) return true;
      return false;
    case CellKind::wedge:
      if (n == 21) return true;
      for (std::int64_t p = 1; p <= kMaxOrder; ++p) {
        const std::int64_t triangle = (p + 1) * (p + 2) / 2;
        if (n % triangle == 0 && is_order_plus_one(n / triangle)) return true;
      }
      return false;
    default:  // a product of three factors in [2, 21]
      for (std::int64_t a = 2; a <= kMaxOrder + 1; ++a) {
        if (n % a != 0) continue;
        const std::int64_t rest = n / a;
        for (std::int64_t b = 2; b <= kMaxOrder + 1; ++b)
          if (rest % b == 0 && is_order_plus_one(rest / b)) return true;
      }
      return false;
  }
}

// Whether a cell of a read volume type can have n points.
inline bool point_count_ok(const VolumeType& entry, std::int64_t n) {
  if (entry.type == kPyramid && n == kGmshPyramidPoints) return true;
  return entry.num_points > 0 ? n == entry.num_points : lagrange_point_count_ok(entry.kind, n);
}

// The point counts a read volume type can have, for messages: "20", or "4,
// 10, 15, 20, 35, ... (a Lagrange tetrahedron's)".
inline std::string expected_point_counts(const VolumeType& entry) {
  if (entry.num_points > 0) return std::to_string(entry.num_points);
  std::string text;
  int shown = 0;
  for (std::int64_t n = 1; shown < 5; ++n)
    if (lagrange_point_count_ok(entry.kind, n)) {
      text += std::to_string(n) + ", ";
      ++shown;
    }
  return text + "... (a " + std::string(entry.name) + "'s)";
}

// The surface cell types read (a file with no volume cell is a surface mesh;
// io/cell_reading.h keep_dimension): triangle 5, quad 9, pixel 8 (corners
// x fastest, reordered like a voxel), polygon 7 with 3 or 4 points (more:
// left out, counted by its type), and the quadratic triangle 22 (6 points),
// quadratic quad 23 (8), biquadratic quad 28 (9) and biquadratic triangle 34
// (7) by their corners, listed first.
inline constexpr int kTriangle = 5;
inline constexpr int kPolygon = 7;
inline constexpr int kPixel = 8;
inline constexpr int kQuad = 9;
struct SurfaceType {
  int type;
  CellKind kind;
  int num_points;  // 0: polygon (3 or 4 points)
};
inline constexpr SurfaceType kSurfaceTypes[] = {
    {kTriangle, CellKind::triangle, 3}, {kPixel, CellKind::quad, 4}, {kQuad, CellKind::quad, 4},
    {22, CellKind::triangle, 6},        {23, CellKind::quad, 8},     {28, CellKind::quad, 9},
    {34, CellKind::triangle, 7},        {kPolygon, CellKind::quad, 0},
};

// The kind a surface cell of `type` with n points is read as; none when the
// type is not a surface type read, or for a polygon of other than 3 or 4
// points. Sets `point_count_wrong` when the type is read but cannot have n
// points.
inline std::optional<CellKind> surface_kind(std::int64_t type, std::int64_t n, bool& point_count_wrong) {
  point_count_wrong = false;
  for (const SurfaceType& entry : kSurfaceTypes) {
    if (entry.type != type) continue;
    if (entry.num_points == 0) {
      if (n == 3) return CellKind::triangle;
      if (n == 4) return CellKind::quad;
      return std::nullopt;
    }
    if (n != entry.num_points) {
      point_count_wrong = true;
      return std::nullopt;
    }
    return entry.kind;
  }
  return std::nullopt;
}

// Whether `type` is a surface type (of any point count).
inline bool is_surface_type(std::int64_t type) {
  for (const SurfaceType& entry : kSurfaceTypes)
    if (entry.type == type) return true;
  return false;
}

// Pixel corner order (x fastest, then y) to quad order.
inline constexpr std::array<int, 4> kPixelToQuad = {0, 1, 3, 2};

// Voxel corner order (x fastest, then y, then z) to hexahedron order.
inline constexpr std::array<int, 8> kVoxelToHex = {0, 1, 3, 2, 4, 5, 7, 6};

// The low `size` bytes of bits (1 to 8) as a two's-complement integer.
inline std::int64_t sign_extend(std::uint64_t bits, int size) {
  const int shift = 64 - 8 * size;
  return static_cast<std::int64_t>(bits << shift) >> shift;
}

}  // namespace hq::vtk
