#pragma once
// Abaqus input deck reader (.inp; Abaqus Keywords Reference, *NODE and
// *ELEMENT). Lines starting with "**" are comments; keywords start with '*'
// and are case-insensitive, their parameters comma-separated
// ("*ELEMENT, TYPE=C3D8R, ELSET=solid").
//
// *NODE data lines: "id, x, y, z" (a missing y or z is 0, as in Abaqus).
// *ELEMENT, TYPE=C3D8|C3D8R|C3D8I|C3D8H|C3D8RH|C3D8IH data lines: "id, n1,
// ..., n8", continued on the next line when a line ends with a comma. The
// C3D8 corner order is VTK_HEXAHEDRON's; the tetrahedron (C3D4 ...), wedge
// (C3D6 ..., permuted to VTK's order) and pyramid (C3D5 ...) families are read
// too (docs/formats.md lists the names; source_index: the element label). Elements of other types are
// skipped with one warning counting them and listing their types; every
// other keyword's data lines are skipped. Node ids may be any positive
// integers, with gaps, in any order; nodes keep their file order (over all
// *NODE blocks). *INCLUDE is refused with a message.
//
// Throws ParseError "name:line: message" on malformed input.

#include <string>
#include <string_view>

#include "hqview/core/error.h"
#include "hqview/io/mesh_reader.h"

namespace hq {

// True when the first line that is neither blank nor a "**" comment starts
// with '*' followed by a letter.
bool looks_like_abaqus(std::string_view bytes);

// The hex mesh of an Abaqus .inp file's bytes. format = "abaqus"; warnings
// are prefixed with name.
// Throws ParseError for a file whose declared counts exceed limits (read_limits.h).
LoadedMesh read_abaqus(std::string_view bytes, const std::string& name, const ReadLimits& limits = {});

}  // namespace hq
