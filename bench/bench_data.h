#pragma once
// Inputs of the benchmarks: the largest mesh of ../shared/data (or
// $HQVIEW_DATA), falling back to the project's own example.

#include <filesystem>
#include <string>

#include "hqview/mesh/hex_mesh.h"

namespace hq::bench {

// Path of the benchmark mesh: Dolphin_padded.mesh when the shared data is
// present, else examples/ball.mesh.
std::filesystem::path largest_mesh();

// Each hex split into 8 (edge, face and cell midpoints as the means of
// their corners; shared points made once): 8x the hexes, same shape.
hq::HexMesh refine_1_to_8(const hq::HexMesh& coarse);

}  // namespace hq::bench
