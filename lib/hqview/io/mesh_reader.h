#pragma once
// Reading hex meshes and reference surfaces. Each format has a reader from
// an in-memory text/bytes buffer with a name (used in error messages), and
// read_hex_mesh() / read_surface() open a file and dispatch on its extension,
// checked against the content.
//
// Every reader throws ParseError ("name:line: what is wrong") on malformed
// input and never allocates from a count before checking that the remaining
// input could hold that many entries.
//
// The in-memory readers: medit_reader.h (read_medit, read_medit_triangles),
// vtk_legacy_reader.h (read_vtk_legacy).

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/core/error.h"
#include "hqview/mesh/hex_mesh.h"

namespace hq {

struct LoadedMesh {
  HexMesh mesh;
  std::string format;                 // "medit", "vtk-legacy-ascii", "vtk-legacy-binary", ...
  std::vector<std::string> warnings;  // e.g. "12 non-hexahedral cells skipped"
};

// Reads a whole file into memory. Throws InputError "path: cannot open:
// <reason>" when it cannot be opened, "path: not a regular file" for a
// directory, fifo or device (never blocks on a fifo).
std::string read_file_bytes(const std::filesystem::path& path);

// A hex mesh file by its extension (.mesh, .vtk, in any case); throws
// InputError for an unknown extension ("path: unknown mesh format '.xyz'
// (expected .mesh or .vtk)") and ParseError for a malformed file or one
// whose content is another format than its extension says.
LoadedMesh read_hex_mesh(const std::filesystem::path& path);

// The same from bytes already read (e.g. by read_file_bytes(), to hash them
// too): dispatches on path's extension and names path in messages.
LoadedMesh read_hex_mesh(const std::filesystem::path& path, std::string_view bytes);

// A reference triangle surface (.obj .off .stl .ply via OpenMesh, polygons
// triangulated as fans, STL duplicate vertices merged; .mesh via its
// Triangles section). Throws InputError "path: ..." for an unknown
// extension, an unreadable file, a file OpenMesh cannot parse or a surface
// without faces; ParseError for a malformed .mesh or NaN/Inf coordinates.
TriSurface read_surface(const std::filesystem::path& path);

}  // namespace hq
