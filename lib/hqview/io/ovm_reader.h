#pragma once
// OpenVolumeMesh ASCII reader (.ovm, "OVM ASCII"; OpenVolumeMesh's
// FileManager): Vertices (x y z), Edges (two vertex ids), Faces (valence,
// then half-edge ids: edge e has half-edges 2e from its first vertex and
// 2e+1 back), Polyhedra (valence, then half-face ids: face f has half-faces
// 2f as listed and 2f+1 reversed). Keywords are case-insensitive; property
// sections after Polyhedra are not read.
//
// Each polyhedron must be a hexahedron (6 quadrilateral half-faces), a
// tetrahedron (4 triangles), a wedge (2 triangles, 3 quadrilaterals) or a
// pyramid (1 quadrilateral, 4 triangles) whose half-faces close up as that
// cell's, outward; any other polyhedron is an error naming it. A tetrahedron,
// wedge or pyramid is rebuilt in VTK's order from its first triangle (tet,
// wedge) or its quadrilateral (pyramid), so its volume is positive when its
// half-faces point outward (source_index: the 0-based polyhedron id). A
// hexahedron's corners are rebuilt from the
// half-faces, whatever type of mesh wrote them: OpenVolumeMesh orients a
// cell's half-faces outward, so the first half-face, reversed, is the
// bottom 0-1-2-3 and each corner i+4 is the neighbour of corner i off the
// bottom face (VTK_HEXAHEDRON order; for a cell written by OVM's
// HexahedralMesh whose first face it created itself, exactly the documented
// [o0,o1,o2,o3,o4,o7,o6,o5]; otherwise the same hexahedron with its corners
// relabelled by a rotation, which changes no metric).
//
// Throws ParseError "name:line: message" on malformed input.

#include <string>
#include <string_view>

#include "hqview/core/error.h"
#include "hqview/io/mesh_reader.h"

namespace hq {

// True when bytes start (after blanks) with "OVM ASCII" or "OVM BINARY".
bool looks_like_ovm(std::string_view bytes);

// The hex mesh of an OVM ASCII file's bytes. format = "ovm-ascii".
// Throws ParseError for a file whose declared counts exceed limits (read_limits.h).
LoadedMesh read_ovm(std::string_view bytes, const std::string& name, const ReadLimits& limits = {});

}  // namespace hq
