#pragma once
// The hex-only name of the mesh (mesh.h), kept for the stages that analyse
// hexahedra only (ARCHITECTURE.md, "Core data"), and the reference surface.

#include <array>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/core/vec3.h"
#include "hqview/mesh/mesh.h"

namespace hq {

// The stages that read only `hexes` name the mesh so; other blocks are
// ignored by them until the analysis covers every kind.
using HexMesh = Mesh;

// A triangle surface (a reference for boundary error). Triangles are 3
// 0-based point ids.
struct TriSurface {
  std::vector<Vec3> points;
  std::vector<std::array<Index, 3>> triangles;
};

}  // namespace hq
