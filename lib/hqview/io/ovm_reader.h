#pragma once
// OpenVolumeMesh ASCII reader (.ovm, "OVM ASCII"; OpenVolumeMesh's
// FileManager): Vertices (x y z), Edges (two vertex ids), Faces (valence,
// then half-edge ids: edge e has half-edges 2e from its first vertex and
// 2e+1 back), Polyhedra (valence, then half-face ids: face f has half-faces
// 2f as listed and 2f+1 reversed). Keywords are case-insensitive; property
// sections after Polyhedra are not read.
//
// Each polyhedron must be a hexahedron: 6 quadrilateral half-faces whose
// edges close up as a hexahedron's. Its corners are rebuilt from the
// half-faces, whatever type of mesh wrote them: OpenVolumeMesh orients a
// cell's half-faces outward, so the first half-face, reversed, is the
// bottom 0-1-2-3 and each corner i+4 is the neighbour of corner i off the
// bottom face (VTK_HEXAHEDRON order; for a cell written by OVM's
// HexahedralMesh whose first face it created itself, exactly the documented
// [o0,o1,o2,o3,o4,o7,o6,o5]; otherwise the same hexahedron with its corners
// relabelled by a rotation, which changes no metric). A polyhedron that is not a hexahedron is an
// error naming it.
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
