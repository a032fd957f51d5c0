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
// vtk_legacy_reader.h (read_vtk_legacy), vtu_reader.h (read_vtu),
// gmsh_reader.h (read_gmsh), abaqus_reader.h (read_abaqus), ovm_reader.h
// (read_ovm), exodus_reader.h (read_exodus, when built with netCDF).

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "hqview/core/error.h"
#include "hqview/io/read_limits.h"
#include "hqview/mesh/hex_mesh.h"

namespace hq {

// A mesh as read: every block a reader reads (hexahedra, tetrahedra, wedges,
// pyramids) with its source_index. read_hex_mesh() refuses a mesh without
// hexahedra and warns about the other volume cells, which the analysis does
// not read yet.
struct LoadedMesh {
  Mesh mesh;
  std::string format;                 // "medit", "vtk-legacy-ascii", "vtk-legacy-binary", ...
  std::vector<std::string> warnings;  // e.g. "name: 12 cells of unread types skipped (type 5)"
  // Polygon readers (polygon_reader.h): the edges of the polygons of more
  // than 4 vertices they skipped, each as (a, b) with a < b, ascending,
  // unique. Holes left by the reader, not the surface's boundary.
  std::vector<std::array<Index, 2>> hole_edges;
  // Information, not a warning: the cells of a lower dimension than the
  // mesh's that a reader skipped (a Gmsh or VTK file's points and lines, and
  // a volume mesh's boundary triangles and quads: the geometric entities'
  // and physical groups' elements Gmsh writes beside the cells), worded as
  // the warning. Skipped cells of the mesh's own dimension (or of a type
  // the reader does not know) stay warnings (a skipped polygon leaves a hole).
  std::vector<std::string> notes;
};

// The cells a reader left out because it does not read their type (not a
// hexahedron, tetrahedron, wedge or pyramid), counted by the format's type (a
// VTK/Gmsh number, an Abaqus or Exodus name), and the two texts every reader
// words the same way: "3 cells of types 5, 9" for its "no volume cells"
// error and "NAME: 3 cells of unread types skipped (types 5, 9)" for the
// warning. `noun` is the format's word: "cell" or "element".
struct SkippedCells {
  std::int64_t count = 0;
  std::size_t num_types = 0;
  std::string types;  // "10, 12", in the map's order

  template <class Type>
  explicit SkippedCells(const std::map<Type, std::int64_t>& by_type) : num_types(by_type.size()) {
    for (const auto& [type, n] : by_type) {
      count += n;
      if (!types.empty()) types += ", ";
      if constexpr (std::is_arithmetic_v<Type>)
        types += std::to_string(type);
      else
        types += type;
    }
  }
  std::string type_word() const { return num_types > 1 ? "types " : "type "; }
  std::string counted(const char* noun) const {
    return std::to_string(count) + " " + noun + (count > 1 ? "s" : "") + " of " + type_word() + types;
  }
  std::string warning(const std::string& file, const char* noun) const {
    return file + ": " + std::to_string(count) + " " + noun + (count > 1 ? "s" : "") + " of unread types skipped (" +
           type_word() + types + ")";
  }
  // The skipped types split by dimension_of(type) (0 points, 1 lines, 2
  // faces, -1 unknown): those below mesh_dimension (3 a volume mesh, 2 a
  // surface mesh) as one note, the rest as one warning, each worded as
  // warning() (LoadedMesh::notes).
  template <class Type, class Dimension>
  static void report(const std::map<Type, std::int64_t>& by_type, Dimension dimension_of, int mesh_dimension,
                     const std::string& file, const char* noun, std::vector<std::string>& notes,
                     std::vector<std::string>& warnings) {
    std::map<Type, std::int64_t> lower, other;
    for (const auto& [type, n] : by_type) {
      const int d = dimension_of(type);
      (d >= 0 && d < mesh_dimension ? lower : other)[type] += n;
    }
    if (!lower.empty()) notes.push_back(SkippedCells(lower).warning(file, noun));
    if (!other.empty()) warnings.push_back(SkippedCells(other).warning(file, noun));
  }
};

// Reads a whole file into memory. Throws InputError "path: cannot open:
// <reason>" when it cannot be opened, "path: not a regular file" for a
// directory, fifo or device (never blocks on a fifo).
std::string read_file_bytes(const std::filesystem::path& path);

// A mesh file by its extension, in any case: .mesh (MEDIT), .vtk
// (legacy VTK), .vtu (VTK XML), .msh (Gmsh), .ovm (OpenVolumeMesh), .inp
// (Abaqus), .e or .exo (Exodus II), and the surface (polygon) meshes .obj,
// .off, .ply (polygon_reader.h; reference surfaces of these extensions go
// through read_surface() instead). Throws InputError for an unknown
// extension ("path: unknown mesh format '.xyz' (expected .mesh, ...)") and
// ParseError for a malformed file or one whose content is recognisably
// another format than its extension says.
//
// Every volume cell is read into its block and analysed; a mesh without any
// volume cell is refused (ParseError "path: no hexahedra").
//
// limits (read_limits.h): the file's size and the counts it declares are
// checked against limits.max_memory before anything is allocated from them
// (ParseError / InputError "... which needs about X; --max-memory is Y").
// Binary data where no format's signature is (a NUL byte in the first MiB)
// is refused from that first MiB: "binary data, not a MEDIT (.mesh) file".
LoadedMesh read_hex_mesh(const std::filesystem::path& path, const ReadLimits& limits = {});

// The same from bytes already read (e.g. by read_file_bytes(), to hash them
// too): dispatches on path's extension and names path in messages.
LoadedMesh read_hex_mesh(const std::filesystem::path& path, std::string_view bytes, const ReadLimits& limits = {});

// With an explicit format (a name of mesh_format_names(); empty: by the
// extension, as above): the extension is ignored and the content is not
// checked against it. Throws ValueError for an unknown format name.
LoadedMesh read_hex_mesh_as(const std::filesystem::path& path, std::string_view format, const ReadLimits& limits = {});
LoadedMesh read_hex_mesh_as(const std::filesystem::path& path, std::string_view bytes, std::string_view format,
                            const ReadLimits& limits = {});

// True when path's extension (any case) is a volume mesh format
// read_hex_mesh() dispatches on: not .obj, .off or .ply, which a directory
// of hex meshes holds as reference surfaces (batch DIR picks hex meshes).
bool has_hex_mesh_extension(const std::filesystem::path& path);
// True when path's extension (any case) is a polygon (surface) format the
// polygon reader reads: .obj, .off or .ply.
bool has_polygon_mesh_extension(const std::filesystem::path& path);

// The format names --format accepts, comma-separated: "mesh, vtk, vtu, msh,
// ovm, exodus, inp, obj, off, ply".
std::string mesh_format_names();

// The format name whose signature the content has ("" when none does):
// MeshVersionFormatted, "# vtk DataFile", <VTKFile, $MeshFormat, OVM ASCII,
// a netCDF/HDF5 signature, an Abaqus keyword line, an OFF keyword, "ply".
std::string detect_mesh_format(std::string_view bytes);

// True when this build reads Exodus II files (built with netCDF).
bool has_exodus_support();

// True when this build reads zlib-compressed .vtu data (built with zlib).
bool has_zlib_support();

// A reference triangle surface (.obj .off .stl .ply via OpenMesh, polygons
// triangulated as fans, STL duplicate vertices merged; .mesh via its
// Triangles section). Throws InputError "path: ..." for an unknown
// extension, an unreadable file, a file OpenMesh cannot parse or a surface
// without faces; ParseError for a malformed .mesh or NaN/Inf coordinates.
//
// Before OpenMesh reads the file: a file larger than limits.max_memory, binary
// data in a text format (OBJ, ASCII OFF, a PLY header, .mesh), a binary STL
// whose size is not 84 + 50 x its triangle count, and OFF/PLY header counts
// above the file's byte count are refused (ParseError / InputError).
TriSurface read_surface(const std::filesystem::path& path, const ReadLimits& limits = {});

}  // namespace hq
