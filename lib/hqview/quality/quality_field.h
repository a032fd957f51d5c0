#pragma once
// Mesh-wide quality fields: per-corner and per-cell scaled Jacobians and the
// per-vertex quality Jm (the paper's one-ring rule: min corner scaled
// Jacobian over the corners of the incident hexes at that vertex).

#include <cstdint>
#include <span>
#include <vector>

#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"

namespace hq {

struct QualityField {
  // corner_scaled_jacobian[8*h + i]: corner i of hex h (kCornerFrames order).
  std::vector<double> corner_scaled_jacobian;
  // Bit i set: corner i of hex h has a zero-length frame edge (value 0).
  std::vector<std::uint8_t> corner_degenerate_mask;
  // Verdict's cell scaled Jacobian, kVerdictDegenerate (1e30) when degenerate.
  std::vector<double> cell_scaled_jacobian;
  // Per vertex: min over the vertex's incident corners; NaN for a vertex no
  // hex uses.
  std::vector<double> vertex_quality;
};

// The corner scaled Jacobians of every hex: out[8*h + i] and mask[h]
// (sizes 8*#hexes and #hexes). Parallel over hexes.
void compute_corner_scaled_jacobians(const HexMesh& mesh, std::span<double> out, std::span<std::uint8_t> mask);

// Computes every field above; parallel over hexes and vertices, identical
// results for any thread count (each entry is written by one task).
QualityField compute_quality(const HexMesh& mesh, const Topology& topo);

}  // namespace hq
