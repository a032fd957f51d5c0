#pragma once
// Inputs of the benchmarks: the largest mesh of ../shared/data (or
// $HQVIEW_DATA), falling back to the project's own example.

#include <filesystem>
#include <string>

namespace hq::bench {

// Path of the benchmark mesh: Dolphin_padded.mesh when the shared data is
// present, else examples/ball.mesh.
std::filesystem::path largest_mesh();

}  // namespace hq::bench
