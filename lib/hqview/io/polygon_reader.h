#pragma once
// HQView's own reader of polygon meshes: OBJ, OFF and PLY, the formats quad
// remeshers (QuadriFlow, Instant Meshes, QuadWild) write. Triangles go into
// the mesh's triangle block and quadrilaterals into its quad block (corners
// in the file's order); nothing is triangulated.
//
//   OBJ: `v x y z [w | r g b]` (what follows x y z is ignored), `f` with
//        `v`, `v/vt`, `v//vn` or `v/vt/vn` corners, 1-based, negative ids
//        counting back from the last vertex read so far (-1 = the last), a
//        `\` at a line's end continuing it; `vt`, `vn`, `vp`, `l`, `p`, `o`,
//        `g`, `s`, `usemtl`, `mtllib` and unknown statements are skipped.
//        A positive id may name a vertex defined later in the file.
//   OFF: the keyword (`OFF`, with the Geomview prefixes `ST`, `C`, `N`),
//        then `V F E` (on the keyword's line or the next), one vertex per
//        line (x y z, then normals, colours or texture coordinates, which
//        are ignored), one face per line (`n i1 .. in`, then at most 4
//        colour values). `#` comments. 0-based ids. `4OFF`, `nOFF` and
//        `OFF BINARY` are refused with a message.
//   PLY: `format ascii`, `binary_little_endian` or `binary_big_endian` 1.0;
//        element `vertex` with properties x, y, z of any numeric type,
//        element `face` with a list property `vertex_indices` (or
//        `vertex_index`) of integers; every other element and property is
//        read past (sized by its type) and ignored. 0-based ids.
//
// Faces: a face of 3 vertices is a triangle, of 4 a quad; a polygon of more
// than 4 vertices is skipped, counted in a warning, and its edges are listed
// in LoadedMesh::hole_edges (they are holes left by the skipped face, not
// the surface's boundary). A face whose vertex ids repeat is skipped with a
// warning that counts it. Edges on more than two faces (non-manifold) are
// counted and the first few listed in a warning; their faces are kept (a
// halfedge structure cannot hold them: OpenMesh adds the faces it cannot
// attach with copies of their vertices, or drops them, and the edge is lost;
// that is why this reader exists; reference surfaces still go through
// OpenMesh). Coordinates are kept as the file's doubles (OpenMesh's
// PolyMesh rounds them to float).
//
// source_index: OBJ the 1-based number of the face among the file's `f`
// statements, OFF and PLY the 0-based face id.
//
// Throws ParseError "name:line: what is wrong" (binary PLY: "name: ... at
// byte N") on malformed input: an id out of range or zero, a face of fewer
// than 3 vertices, a truncated file, a NaN or Inf coordinate, counts that
// the rest of the file cannot hold or that exceed limits (checked before
// anything is allocated from them).

#include <string>
#include <string_view>

#include "hqview/core/error.h"
#include "hqview/io/mesh_reader.h"

namespace hq {

// True when the first token (after blanks and # comments) is an OFF keyword
// (`OFF`, `COFF`, `NOFF`, `STOFF`, `4OFF`, `nOFF`, ...).
bool looks_like_off(std::string_view bytes);

// True when bytes start with the line "ply".
bool looks_like_ply(std::string_view bytes);

// The surface mesh of an OBJ file's bytes. format = "obj".
LoadedMesh read_obj(std::string_view bytes, const std::string& name, const ReadLimits& limits = {});

// The surface mesh of an OFF file's bytes. format = "off".
LoadedMesh read_off(std::string_view bytes, const std::string& name, const ReadLimits& limits = {});

// The surface mesh of a PLY file's bytes. format = "ply-ascii",
// "ply-binary-little-endian" or "ply-binary-big-endian".
LoadedMesh read_ply(std::string_view bytes, const std::string& name, const ReadLimits& limits = {});

}  // namespace hq
