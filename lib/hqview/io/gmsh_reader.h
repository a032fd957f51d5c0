#pragma once
// Gmsh mesh reader (.msh; Gmsh reference manual, "MSH file format"):
// versions 2.2 (also 2.0 and 2.1) and 4.1, ASCII and binary (either byte
// order, detected from the format section's integer 1).
//
// Nodes keep their file order; node tags may be any non-negative integers,
// in any order, with gaps. Elements of types 5 (8-node hexahedron), 4
// (tetrahedron) and 7 (pyramid), whose corner orders are VTK's, and 6
// (prism, permuted to VTK_WEDGE's order) are loaded (source_index: the
// element tag); other element types are
// skipped with one warning counting them and listing their types. Sections
// other than $MeshFormat, $Nodes and $Elements ($PhysicalNames, $Entities,
// $NodeData, ...) are skipped up to their $End line; reading stops once
// $Nodes and $Elements are in. Nodes unused by any element are kept.
//
// Throws ParseError "name:line: message" on malformed input: unknown
// versions, bad counts (checked against the remaining bytes before any
// allocation), undefined or repeated node tags, ... Errors in binary data
// are reported at the line of their section keyword with the byte offset.

#include <string>
#include <string_view>

#include "hqview/core/error.h"
#include "hqview/io/mesh_reader.h"

namespace hq {

// True when bytes start (after blanks) with "$MeshFormat".
bool looks_like_gmsh(std::string_view bytes);

// The hex mesh of a .msh file's bytes. format = "gmsh-2.2-ascii",
// "gmsh-4.1-binary", ...; warnings are prefixed with name.
// Throws ParseError for a file whose declared counts exceed limits (read_limits.h).
LoadedMesh read_gmsh(std::string_view bytes, const std::string& name, const ReadLimits& limits = {});

}  // namespace hq
