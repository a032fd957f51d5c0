#pragma once
// VTK XML UnstructuredGrid reader (.vtu; Kitware's "VTK File Formats",
// XML section). <VTKFile type="UnstructuredGrid"> with byte_order
// LittleEndian or BigEndian, header_type UInt32 (default) or UInt64, no
// compressor or vtkZLibDataCompressor (when built with zlib). Every Piece is
// read; their points are concatenated in file order.
//
// DataArray formats: "ascii", "binary" (base64 of the byte-count header and
// the data, or of the compression header and the compressed blocks; header
// and data may be base64-encoded together or separately) and "appended"
// (offset into <AppendedData encoding="raw|base64">, whose content starts
// after its '_'). Types Int8 ... UInt64, Float32, Float64.
//
// Cells: types 12 (VTK_HEXAHEDRON), 10, 13 and 14 as they are, type 11
// (VTK_VOXEL) reordered to hexahedron order (source_index: the 0-based cell
// id over all pieces); one of these with another point count is an error;
// other cells are skipped with one warning counting them and listing their
// types. Points unused by any cell are kept.
//
// Throws ParseError "name:line: message" on malformed input; errors in
// binary data are reported at the line of their DataArray with the byte
// offset in the message. Counts are checked against the bytes that could
// hold them before anything is allocated (compressed data: against zlib's
// largest possible expansion).

#include <string>
#include <string_view>

#include "hqview/core/error.h"
#include "hqview/io/mesh_reader.h"

namespace hq {

// True when bytes look like a VTK XML file (an XML declaration or comment,
// then <VTKFile).
bool looks_like_vtu(std::string_view bytes);

// The hex mesh of a .vtu file's bytes. format = "vtu-ascii", "vtu-binary" or
// "vtu-appended" (by the format of the points); warnings are prefixed with name.
// Throws ParseError for a file whose declared counts exceed limits (read_limits.h).
LoadedMesh read_vtu(std::string_view bytes, const std::string& name, const ReadLimits& limits = {});

}  // namespace hq
