#pragma once
// Reading hex meshes and reference surfaces. Each format has a reader from
// an in-memory text/bytes buffer with a name (used in error messages), and
// read_hex_mesh() / read_surface() open a file and dispatch on its extension,
// checked against the content.
//
// Every reader throws ParseError ("name:line: what is wrong") on malformed
// input and never allocates from a count before checking that the remaining
// input could hold that many entries.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/mesh/hex_mesh.h"

namespace hq {

struct LoadedMesh {
  HexMesh mesh;
  std::string format;                 // "medit", "vtk-legacy-ascii", "vtk-legacy-binary", ...
  std::vector<std::string> warnings;  // e.g. "12 non-hexahedral cells skipped"
};

// Reads a whole file into memory. Throws InputError when it cannot be opened
// or is not a regular file.
std::string read_file_bytes(const std::filesystem::path& path);

// A hex mesh file by its extension (.mesh, .vtk); throws InputError for an
// unknown extension and ParseError for a malformed file.
LoadedMesh read_hex_mesh(const std::filesystem::path& path);

// A reference triangle surface (.obj .off .stl .ply via OpenMesh, polygons
// triangulated; .mesh via its Triangles section).
TriSurface read_surface(const std::filesystem::path& path);

}  // namespace hq
