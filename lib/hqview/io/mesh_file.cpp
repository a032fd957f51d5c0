#include "hqview/io/mesh_file.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <memory>
#include <optional>
#include <string_view>
#include <system_error>

#include "hqview/core/error.h"
#include "hqview/core/sha256.h"
#include "hqview/io/abaqus_reader.h"
#include "hqview/io/cell_reading.h"
#include "hqview/io/exodus_reader.h"
#include "hqview/io/gmsh_reader.h"
#include "hqview/io/medit_reader.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/io/mesh_source.h"
#include "hqview/io/ovm_reader.h"
#include "hqview/io/polygon_reader.h"
#include "hqview/io/read_limits.h"
#include "hqview/io/text_scanner.h"
#include "hqview/io/vtk_legacy_reader.h"
#include "hqview/io/vtu_reader.h"

namespace hq {
namespace detail {
namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

std::string errno_text(int error) { return std::error_code(error, std::generic_category()).message(); }

// Checks the file type before opening: opening a fifo would block.
FilePtr open_regular_file(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw InputError(path.string() + ": not a regular file");
  errno = 0;
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) throw InputError(path.string() + ": cannot open: " + errno_text(errno != 0 ? errno : ENOENT));
  return file;
}

}  // namespace

std::string lowercase_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c); });
  return ext;
}

void check_readable_file(const std::filesystem::path& path) { open_regular_file(path); }

}  // namespace detail

std::string read_file_bytes(const std::filesystem::path& path) {
  const detail::FilePtr file = detail::open_regular_file(path);
  std::string bytes;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) bytes.reserve(static_cast<std::size_t>(size));
  char buffer[1 << 16];
  while (true) {
    const std::size_t n = std::fread(buffer, 1, sizeof buffer, file.get());
    bytes.append(buffer, n);
    if (n < sizeof buffer) break;
  }
  if (std::ferror(file.get())) throw InputError(path.string() + ": read error: " + detail::errno_text(errno));
  return bytes;
}

namespace {

bool looks_like_vtk(std::string_view bytes) { return detail::istarts_with(bytes, "# vtk DataFile"); }

// MeshVersionFormatted after blanks and # comment lines.
bool looks_like_medit(std::string_view bytes) {
  return detail::istarts_with(detail::after_blanks_and_comments(bytes), "MeshVersionFormatted");
}

// OBJ has no signature: only its extension names it.
bool looks_like_obj(std::string_view) { return false; }

// netCDF classic / 64-bit offset / HDF5 (netCDF-4) signatures: Exodus II.
bool looks_like_exodus(std::string_view bytes) {
  return bytes.starts_with(std::string_view("CDF\x01", 4)) || bytes.starts_with(std::string_view("CDF\x02", 4)) ||
         bytes.starts_with(std::string_view("CDF\x05", 4)) || bytes.starts_with("\x89HDF\r\n\x1a\n");
}

using Reader = LoadedMesh (*)(std::string_view, const std::string&, const ReadLimits&);

struct MeshFormat {
  std::string_view name;         // for read_hex_mesh_as (and a future --format)
  std::string_view description;  // for messages
  std::string_view extensions[2];
  bool (*looks_like)(std::string_view);
  Reader read;
  bool is_text_only;  // no binary variant: a NUL byte anywhere is binary data
  bool is_polygon;    // a polygon (surface) format: not picked from a directory of hex meshes
};

// Detection order matters only for content that two formats could claim:
// none of these signatures overlap, except that Abaqus's (a line starting
// with '*') is checked after the others (OFF's and PLY's first words are
// never an Abaqus keyword). OBJ, OFF and PLY are surface
// (polygon) meshes (polygon_reader.h).
constexpr MeshFormat kFormats[] = {
    {"mesh", "MEDIT (.mesh)", {".mesh", ""}, looks_like_medit, read_medit, true, false},
    {"vtk", "legacy VTK", {".vtk", ""}, looks_like_vtk, read_vtk_legacy, false, false},
    {"vtu", "VTK XML", {".vtu", ""}, looks_like_vtu, read_vtu, false, false},
    {"msh", "Gmsh", {".msh", ""}, looks_like_gmsh, read_gmsh, false, false},
    {"ovm", "OpenVolumeMesh", {".ovm", ""}, looks_like_ovm, read_ovm, false, false},  // refuses OVM BINARY itself
    {"exodus", "Exodus II (netCDF)", {".e", ".exo"}, looks_like_exodus, read_exodus, false, false},
    {"inp", "Abaqus", {".inp", ""}, looks_like_abaqus, read_abaqus, true, false},
    {"obj", "OBJ (Wavefront)", {".obj", ""}, looks_like_obj, read_obj, true, true},
    {"off", "OFF", {".off", ""}, looks_like_off, read_off, false, true},  // refuses OFF BINARY itself
    {"ply", "PLY", {".ply", ""}, looks_like_ply, read_ply, false, true},
};

constexpr std::string_view kExpected =
    "expected .mesh, .vtk, .vtu, .msh, .ovm, .inp, .e or .exo, or a surface .obj, .off or .ply";

const MeshFormat* format_by_extension(const std::string& ext) {
  if (ext.empty()) return nullptr;
  for (const MeshFormat& format : kFormats)
    for (const std::string_view e : format.extensions)
      if (e == ext) return &format;
  return nullptr;
}

const MeshFormat* format_by_name(std::string_view name) {
  for (const MeshFormat& format : kFormats)
    if (format.name == name) return &format;
  return nullptr;
}

const MeshFormat* format_by_content(std::string_view bytes) {
  for (const MeshFormat& format : kFormats)
    if (format.looks_like(bytes)) return &format;
  return nullptr;
}

// Throws InputError unless path has a hex mesh extension.
const MeshFormat& format_of_path(const std::filesystem::path& path) {
  const std::string ext = detail::lowercase_extension(path);
  if (const MeshFormat* format = format_by_extension(ext)) return *format;
  if (ext.empty()) throw InputError(path.string() + ": no file extension (" + std::string(kExpected) + ")");
  throw InputError(path.string() + ": unknown mesh format '" + path.extension().string() + "' (" +
                   std::string(kExpected) + ")");
}

const MeshFormat& format_of_name(std::string_view name) {
  if (const MeshFormat* format = format_by_name(name)) return *format;
  throw ValueError("unknown mesh format '" + std::string(name) + "' (expected " + mesh_format_names() + ")");
}

// The bytes looked at before a file is read whole.
constexpr std::size_t kPrefixBytes = std::size_t{1} << 20;

// Binary data is refused from the file's first MiB, before the rest is read:
// a NUL byte where no format's signature is (every binary format HQView
// reads starts with one), or anywhere in a text-only format. This is what
// makes a 2 GB file of zeros fail at once instead of being read whole.
void check_not_binary(const MeshFormat& format, std::string_view prefix, const std::string& name) {
  prefix = prefix.substr(0, kPrefixBytes);
  const std::size_t nul = prefix.find('\0');
  if (nul == std::string_view::npos) return;
  if (format.is_text_only)
    throw ParseError(name, 0,
                     "binary data, expected " + std::string(format.description) + " text (a NUL byte at offset " +
                         std::to_string(nul) + ")");
  if (format_by_content(prefix) == nullptr)
    throw ParseError(name, 0,
                     "binary data, expected " + std::string(format.description) + " content (a NUL byte at offset " +
                         std::to_string(nul) + " and no mesh format's signature)");
}

// Refuses content that is recognisably another format than the extension says.
void check_content_matches(const MeshFormat& format, const std::filesystem::path& path, std::string_view bytes) {
  const MeshFormat* content = format_by_content(bytes);
  if (content != nullptr && content != &format)
    throw ParseError(path.string(), 0,
                     "a " + detail::lowercase_extension(path) + " file with " + std::string(content->description) +
                         " content (expected the extension " + std::string(content->extensions[0]) + ")");
}

// Every reader's mesh passes here: its coordinates must be analysable, and
// a mesh without any cell (a volume cell, or a surface mesh's quadrilateral
// or triangle) is refused.
LoadedMesh checked(LoadedMesh loaded, const std::string& name) {
  check_coordinate_magnitudes(loaded.mesh, name);
  if (num_cells(loaded.mesh) == 0) throw ParseError(name, 0, "no hexahedra");
  return loaded;
}

LoadedMesh read_as(const MeshFormat& format, const std::filesystem::path& path, std::string_view bytes,
                   const ReadLimits& limits) {
  check_content_matches(format, path, bytes);
  check_not_binary(format, bytes, path.string());
  return checked(format.read(bytes, path.string(), limits), path.string());
}

// The bytes of a mesh file: its size checked against the budget and its
// first MiB against binary garbage before the rest is read.
std::string read_mesh_bytes(const MeshFormat& format, const std::filesystem::path& path, const ReadLimits& limits) {
  const detail::FilePtr file = detail::open_regular_file(path);
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  // The bytes alone must fit; the counts the file declares are checked by its reader.
  if (!ec && limits.max_memory > 0 && size >= limits.max_memory)
    throw InputError(path.string() + ": the file has " + std::to_string(size) + " bytes (" + format_memory_size(size) +
                     "), more than --max-memory (" + format_memory_size(limits.max_memory) + ")");
  std::string bytes;
  if (!ec) bytes.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(size, kPrefixBytes)));
  bool is_prefix_checked = false;
  char buffer[1 << 16];
  while (true) {
    const std::size_t n = std::fread(buffer, 1, sizeof buffer, file.get());
    bytes.append(buffer, n);
    if (!is_prefix_checked && (bytes.size() >= kPrefixBytes || n < sizeof buffer)) {
      check_not_binary(format, bytes, path.string());
      is_prefix_checked = true;
      if (!ec && size > bytes.size()) bytes.reserve(static_cast<std::size_t>(size));
    }
    if (n < sizeof buffer) break;
  }
  if (std::ferror(file.get())) throw InputError(path.string() + ": read error: " + detail::errno_text(errno));
  return bytes;
}

}  // namespace

bool has_hex_mesh_extension(const std::filesystem::path& path) {
  const MeshFormat* format = format_by_extension(detail::lowercase_extension(path));
  return format != nullptr && !format->is_polygon;
}

bool has_polygon_mesh_extension(const std::filesystem::path& path) {
  const MeshFormat* format = format_by_extension(detail::lowercase_extension(path));
  return format != nullptr && format->is_polygon;
}

std::string mesh_format_names() {
  std::string names;
  for (const MeshFormat& format : kFormats) names += (names.empty() ? "" : ", ") + std::string(format.name);
  return names;
}

std::string detect_mesh_format(std::string_view bytes) {
  const MeshFormat* format = format_by_content(bytes);
  return format == nullptr ? std::string() : std::string(format->name);
}

bool has_exodus_support() { return exodus_available(); }

bool has_zlib_support() {
#ifdef HQ_HAVE_ZLIB
  return true;
#else
  return false;
#endif
}

LoadedMesh read_hex_mesh(const std::filesystem::path& path, const ReadLimits& limits) {
  const MeshFormat& format = format_of_path(path);
  return read_as(format, path, read_mesh_bytes(format, path, limits), limits);
}

LoadedMesh read_hex_mesh(const std::filesystem::path& path, std::string_view bytes, const ReadLimits& limits) {
  return read_as(format_of_path(path), path, bytes, limits);
}

LoadedMesh read_hex_mesh_as(const std::filesystem::path& path, std::string_view format, const ReadLimits& limits) {
  if (format.empty()) return read_hex_mesh(path, limits);
  const MeshFormat& chosen = format_of_name(format);
  return checked(chosen.read(read_mesh_bytes(chosen, path, limits), path.string(), limits), path.string());
}

LoadedMesh read_hex_mesh_as(const std::filesystem::path& path, std::string_view bytes, std::string_view format,
                            const ReadLimits& limits) {
  if (format.empty()) return read_hex_mesh(path, bytes, limits);
  const MeshFormat& chosen = format_of_name(format);
  check_not_binary(chosen, bytes, path.string());
  return checked(chosen.read(bytes, path.string(), limits), path.string());
}

std::string reported_path(const std::filesystem::path& path) {
  return path.is_absolute() ? path.filename().string() : path.lexically_normal().string();
}

MeshSource open_mesh_source(const std::filesystem::path& path, std::string_view format, const ReadLimits& limits) {
  const MeshFormat& chosen = format.empty() ? format_of_path(path) : format_of_name(format);
  MeshSource source;
  source.path = path;
  source.format = std::string(chosen.name);
  source.is_format_given = !format.empty();
  source.bytes = read_mesh_bytes(chosen, path, limits);  // size and binary checks, once
  return source;
}

LoadedMesh read_hex_mesh(MeshSource& source, const ReadLimits& limits) {
  const MeshFormat& format = format_of_name(source.format);
  if (!source.is_format_given) check_content_matches(format, source.path, source.bytes);
  // The hash (about a third of the parse's time) is taken while the
  // single-threaded parser runs.
  std::optional<LoadedMesh> loaded;
  tbb::parallel_invoke(
      [&] { loaded = checked(format.read(source.bytes, source.path.string(), limits), source.path.string()); },
      [&] { source.sha256 = sha256_hex(source.bytes); });
  return std::move(*loaded);
}

InputFile input_file(const MeshSource& source, const LoadedMesh& loaded) {
  return {reported_path(source.path), loaded.format, source.sha256};
}

}  // namespace hq
