#pragma once
// Exodus II reader (.e, .exo; Sandia's "EXODUS II: A Finite Element Data
// Model", SAND92-2137) through the netCDF library (libnetcdf-dev), when it
// is available at build time; exodus_available() tells. The file is opened
// from memory (nc_open_mem): classic, 64-bit offset and netCDF-4 files.
//
// Read: the node coordinates (coord, or coordx / coordy / coordz; a
// missing z is 0) in file order, and every element block whose elem_type
// starts with "HEX", "TET", "WEDGE" or "PYR" with a node count Exodus
// defines for it (HEX8 ... HEX27, TETRA4 ... TETRA15, WEDGE6 ... WEDGE21,
// PYRAMID5 ... PYRAMID19; connectN, 1-based node indices), by its corners,
// listed first (HEX8 corner order is VTK_HEXAHEDRON's; wedges permuted to
// VTK's order), with one warning naming the higher-order types. A HEX
// element with repeated corners in a collapse pattern is read as the
// wedge, pyramid or tetrahedron it collapses to (cell_reading.h). Other
// blocks are skipped with one warning counting their elements and listing
// their types. source_index: the element's entry in elem_num_map (the
// user's element id) when the file has one, else its 1-based number over
// the blocks. The node number map is not used: node ids are file positions.
//
// Throws ParseError "name: message" (no line numbers in a binary file) for
// a file netCDF cannot open or that lacks Exodus dimensions or variables,
// out-of-range node indices, NaN/Inf coordinates; without netCDF, an
// InputError saying that this build cannot read Exodus II.

#include <string>
#include <string_view>

#include "hqview/core/error.h"
#include "hqview/io/mesh_reader.h"

namespace hq {

// True when this build reads Exodus II files.
bool exodus_available();

// The hex mesh of an Exodus II file's bytes. format = "exodus".
// Throws ParseError for a file whose declared counts exceed limits (read_limits.h).
LoadedMesh read_exodus(std::string_view bytes, const std::string& name, const ReadLimits& limits = {});

}  // namespace hq
