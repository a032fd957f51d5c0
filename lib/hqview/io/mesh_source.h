#pragma once
// One way into a hex mesh file: open it once (its bytes read with the size
// and binary checks, its format resolved, its hash taken), then read the mesh
// from that source. report.json's `input` and `compare.input` come from it.

#include <filesystem>
#include <string>
#include <string_view>

#include "hqview/io/mesh_reader.h"
#include "hqview/io/read_limits.h"

namespace hq {

// A file as report.json names it.
struct InputFile {
  std::string path;    // as given by the user (file name only when absolute)
  std::string format;  // the reader's format name ("medit", "vtk-legacy-ascii", ...)
  std::string sha256;  // of the file's bytes, lowercase hex
};

// The path as the user gave it (lexically normal), or only its file name
// when absolute, so that reports hold no machine-specific path.
std::string reported_path(const std::filesystem::path& path);

struct MeshSource {
  std::filesystem::path path;    // as given; names the file in messages
  std::string format;            // resolved: a name of mesh_format_names()
  bool is_format_given = false;  // --format: the content is not checked against the extension
  std::string bytes;
  std::string sha256;  // of bytes, lowercase hex (filled by read_hex_mesh)
};

// Opens a hex mesh file: format by `format` (a name of mesh_format_names())
// or, when empty, by the extension; the file's size checked against
// limits.max_memory and its first MiB against binary data before the rest
// is read. Throws InputError (cannot open, unknown extension, too large),
// ParseError (binary data), ValueError (an unknown format name).
MeshSource open_mesh_source(const std::filesystem::path& path, std::string_view format, const ReadLimits& limits);

// The mesh of an opened source, and source.sha256 (hashed while the reader
// runs). Unless the format was given, content that is recognisably another
// format than the extension says is refused (ParseError); then the format's
// reader runs (ParseError, InvalidMeshError).
LoadedMesh read_hex_mesh(MeshSource& source, const ReadLimits& limits);

// report.json's description of the source once its mesh is read.
InputFile input_file(const MeshSource& source, const LoadedMesh& loaded);

// A reference surface file, opened the same way: extension checked, size,
// binary data and header counts checked before it is read whole, bytes
// hashed once.
struct SurfaceSource {
  std::filesystem::path path;
  std::string format;  // "obj", "off", "stl", "ply" or "medit"
  std::string bytes;
  std::string sha256;
};

// Throws InputError / ParseError as read_surface() (mesh_reader.h).
SurfaceSource open_surface_source(const std::filesystem::path& path, const ReadLimits& limits);

// The triangles of an opened surface source (OpenMesh for OBJ, OFF, STL,
// PLY, from the bytes; the MEDIT reader's Triangles section).
TriSurface read_surface(const SurfaceSource& source);

InputFile input_file(const SurfaceSource& source);

}  // namespace hq
