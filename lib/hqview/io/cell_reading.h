#pragma once
// What every mesh reader shares to put a file's volume cells into a Mesh's
// blocks (mesh/mesh.h): appending a cell of a kind with its source index,
// the corner permutation of the formats that list a wedge the other way
// round, the check for repeated corners, and the words of the messages
// ("2 tetrahedra, 1 wedge").
//
// Wedge orders (docs/formats.md): VTK (legacy, VTU), MEDIT and OVM's
// reconstruction use VTK_WEDGE's order (the right-hand normal of the first
// triangle points away from the second); Gmsh (prism, type 6), Exodus
// (WEDGE6) and Abaqus (C3D6) point it towards the second, as Verdict does.
// Those three are read through kWedgeFlippedToVtk.

#include <array>
#include <cstdint>
#include <string>

#include "hqview/core/cell_kinds.h"
#include "hqview/core/types.h"
#include "hqview/mesh/mesh.h"

namespace hq::detail {

// A wedge in Gmsh/Exodus/Abaqus/Verdict order -> VTK order:
// vtk_corner[i] = file_corner[kWedgeFlippedToVtk[i]] (its own inverse).
inline constexpr std::array<int, 6> kWedgeFlippedToVtk = {0, 2, 1, 3, 5, 4};

// Appends one cell, its corners already in VTK order, and its source index.
template <CellKind K>
void append_cell(Mesh& mesh, const CellCorners<K>& corners, std::int64_t source_index) {
  cell_block<K>(mesh).push_back(corners);
  mesh.source_index[static_cast<std::size_t>(K)].push_back(source_index);
}

// Appends one volume cell of `kind` from the num_corners(kind) ids at
// `corners`, in the file's order; `to_vtk` (nullptr: none) permutes them:
// vtk_corner[i] = corners[to_vtk[i]].
void append_cell(Mesh& mesh, CellKind kind, const Index* corners, const int* to_vtk, std::int64_t source_index);

// The position j of the first id among ids[0..n) equal to an earlier one, -1
// when all are distinct.
int first_repeated(const Index* ids, int n);

// The word for a kind's cells, singular or plural: "hexahedron",
// "tetrahedra", "wedges", "pyramid", ...
std::string cell_kind_noun(CellKind kind, std::int64_t count);

// "2 tetrahedra, 1 wedge, 3 pyramids": the non-empty volume blocks other
// than hexahedra, "" when there are none.
std::string non_hex_volume_counts(const Mesh& mesh);

// The number of volume cells (hexahedra, tetrahedra, wedges, pyramids).
std::int64_t num_volume_cells(const Mesh& mesh);

}  // namespace hq::detail
