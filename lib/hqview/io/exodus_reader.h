#pragma once
// Exodus II reader (.e, .exo; Sandia's "EXODUS II: A Finite Element Data
// Model", SAND92-2137) through the netCDF library (libnetcdf-dev), when it
// is available at build time; exodus_available() tells. The file is opened
// from memory (nc_open_mem): classic, 64-bit offset and netCDF-4 files.
//
// Read: the node coordinates (coord, or coordx / coordy / coordz; a
// missing z is 0) in file order, and every element block whose elem_type
// starts with "HEX" and has 8 nodes per element (connectN, 1-based node
// indices; HEX8 corner order is VTK_HEXAHEDRON's), and TET*, WEDGE* (permuted
// to VTK's order) and PYR* blocks of 4, 6 and 5 nodes (source_index: the
// 1-based element id over the blocks). Other blocks are skipped
// with one warning counting their elements and listing their types. Node
// and element number maps are not used: ids are file positions.
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
