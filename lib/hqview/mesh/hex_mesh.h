#pragma once
// The plain data the whole pipeline works on (ARCHITECTURE.md, "Core data").

#include <array>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/core/vec3.h"

namespace hq {

using Hex = std::array<Index, 8>;

// A hexahedral mesh: points in model units, hexes as 8 0-based point ids in
// VTK_HEXAHEDRON order. Points not used by any hex are allowed (reported).
struct HexMesh {
  std::vector<Vec3> points;
  std::vector<Hex> hexes;

  Index num_vertices() const { return static_cast<Index>(points.size()); }
  Index num_hexes() const { return static_cast<Index>(hexes.size()); }
};

// A triangle surface (a reference for boundary error). Triangles are 3
// 0-based point ids.
struct TriSurface {
  std::vector<Vec3> points;
  std::vector<std::array<Index, 3>> triangles;
};

// The 8 corner positions of hex h.
inline std::array<Vec3, 8> hex_corners(const HexMesh& mesh, Index h) {
  std::array<Vec3, 8> p;
  const Hex& hex = mesh.hexes[static_cast<std::size_t>(h)];
  for (int i = 0; i < 8; ++i) p[i] = mesh.points[static_cast<std::size_t>(hex[i])];
  return p;
}

}  // namespace hq
