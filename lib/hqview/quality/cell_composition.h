#pragma once
// What a volume mesh is made of: cells and Verdict volume per kind (hex,
// tet, wedge, pyramid) and the hex fractions the headline reports.

#include <array>
#include <cstdint>
#include <optional>

#include "hqview/mesh/mesh.h"

namespace hq {

inline constexpr int kNumVolumeKinds = 4;  // hex, tet, wedge, pyramid: CellKind values 0..3

struct CellComposition {
  std::array<std::int64_t, kNumVolumeKinds> count{};
  // Sum of |Verdict's volume| of the cells of the kind (model units cubed;
  // an inverted or tangled cell still takes up space, so it counts positive).
  std::array<double, kNumVolumeKinds> volume{};
  // A surface mesh's cells (no volume cell; mesh.h is_surface_mesh).
  std::int64_t num_quads = 0, num_triangles = 0;
  std::int64_t num_cells = 0;  // every cell, volume or surface
  // hexes / all volume cells; none without a cell.
  std::optional<double> hex_fraction;
  // hex volume / the volume of every cell; none when that total is not > 0.
  std::optional<double> hex_volume_fraction;
};

// Parallel over cells; the volumes summed in cell order (the same bytes for
// any thread count).
CellComposition compute_cell_composition(const Mesh& mesh);

}  // namespace hq
