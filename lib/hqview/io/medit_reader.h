#pragma once
// MEDIT .mesh ASCII reader (the INRIA Gamma "MeshVersionFormatted" format as
// written by real hex-meshing datasets; libMeshb's keyword list).
//
// Accepted: MeshVersionFormatted 1-4, Dimension 3, counts on the keyword line
// or the next one ("Vertices 425" / "Vertices\n425"), `#` comments, keywords
// in any case, "Hexahedra" and the old spelling "Hexaedra", an optional End.
// Vertices are "x y z ref" lines; Hexahedra "v1 .. v8 ref" with 1-based ids
// in VTK_HEXAHEDRON order (returned 0-based); Tetrahedra and Pyramids in
// VTK's order, Prisms in P. L. George's (first triangle facing the second,
// permuted to VTK_WEDGE's); source_index: the 1-based entry of the section.
// Every other known section (Triangles, Quadrilaterals, non-standard Quads,
// Edges, Corners, Ridges, Required*, Normals, Tangents, NormalAt*, ...)
// is checked entry by entry and skipped; an unknown keyword followed by a
// count is skipped one line per entry, with a warning.
//
// Each entry must sit on one line (true of every writer we know): this is
// what lets "expected 8 vertex ids and a reference, got 8 values" name the
// right line instead of silently shifting every later entry.
//
// Throws ParseError "name:line: message" for any malformed input: bad or
// missing keywords, negative counts, counts above kMaxIndexCount or larger
// than the rest of the text could hold (checked before allocating), short or
// long entry lines, non-numbers, NaN/Inf coordinates, vertex ids out of
// range, a vertex repeated within one element, no Vertices section, no
// volume cells (line 0: "name: no volume cells (...)"). When a cell section
// comes before Vertices, its ids are range-checked at the end and reported at
// its keyword's line.

#include <string>
#include <string_view>

#include "hqview/core/error.h"
#include "hqview/io/mesh_reader.h"

namespace hq {

// The mesh of a .mesh text (every volume block). format = "medit". Warnings
// (prefixed with name) for unknown sections.
// Throws ParseError for a file whose declared counts exceed limits (read_limits.h).
LoadedMesh read_medit(std::string_view text, const std::string& name, const ReadLimits& limits = {});

// The Vertices and Triangles of a .mesh text (a reference surface); all
// other sections, Hexahedra included, are skipped. Throws ParseError as
// read_medit, with "no triangles" for a text without any.
TriSurface read_medit_triangles(std::string_view text, const std::string& name);

}  // namespace hq
