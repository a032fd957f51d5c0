#pragma once
// Legacy VTK reader (.vtk, "# vtk DataFile Version X.Y", Kitware's "VTK File
// Formats" document), DATASET UNSTRUCTURED_GRID only, ASCII or BINARY
// (big-endian), file versions 1.0 to 5.1:
//   <= 4.2: CELLS n size, then per cell its point count and point ids;
//   5.x:    CELLS nOffsets nConnectivity, then OFFSETS <type> and
//           CONNECTIVITY <type> arrays (vtktypeint64, vtktypeint32, int, ...).
// POINTS may be float, double or any integer type. Sections may come in any
// order; FIELD and METADATA blocks are skipped; reading stops once POINTS,
// CELLS and CELL_TYPES are in (CELL_DATA, POINT_DATA, ... are not read).
//
// Cells: types 12 (VTK_HEXAHEDRON), 10 (tetra), 13 (wedge) and 14 (pyramid)
// are loaded as they are into their blocks (source_index: the 0-based cell
// id); type 11 (VTK_VOXEL) is reordered to hexahedron order (voxel corners
// 2<->3 and 6<->7). A cell of those types with another point count is an
// error ("cell 3 has type 10 (tetra) but 5 points, expected 4"), except that
// a cell with
// 8 points whose type has a fixed, different point count (e.g. 10, tetra) is
// loaded as a hexahedron with one warning naming the mislabelled cells, as
// HexaLab does; other cells are skipped with one warning counting them and
// listing their types. Points unused by any cell are kept.
//
// Throws ParseError "name:line: message" on malformed input (see
// read_medit for the list). Errors inside binary data are reported at the
// line of the section keyword, with the byte offset (from the start of the
// file) in the message.

#include <string>
#include <string_view>

#include "hqview/core/error.h"
#include "hqview/io/mesh_reader.h"

namespace hq {

// The hex mesh of a legacy VTK file's bytes. format = "vtk-legacy-ascii" or
// "vtk-legacy-binary"; warnings are prefixed with name.
// Throws ParseError for a file whose declared counts exceed limits (read_limits.h).
LoadedMesh read_vtk_legacy(std::string_view bytes, const std::string& name, const ReadLimits& limits = {});

}  // namespace hq
