// read_surface(): reference triangle surfaces. OBJ, OFF, STL and PLY go
// through OpenMesh (polygons triangulated as fans; OpenMesh merges the
// duplicate vertices of STL files); .mesh through read_medit_triangles.

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/core/error.h"
#include "hqview/core/sha256.h"
#include "hqview/core/types.h"
#include "hqview/io/medit_reader.h"
#include "hqview/io/mesh_file.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/io/mesh_source.h"

namespace hq {
namespace {

using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

// OpenMesh's readers share global state (the IOManager singleton, its
// reader instances, the omerr stream): one read at a time.
std::mutex& openmesh_mutex() {
  static std::mutex mutex;
  return mutex;
}

constexpr std::size_t kPrefixBytes = std::size_t{1} << 20;

// ASCII STL starts with "solid" and holds no NUL byte (in its first MiB).
bool is_ascii_stl(std::string_view bytes) {
  return bytes.starts_with("solid") && bytes.substr(0, kPrefixBytes).find('\0') == std::string_view::npos;
}

TriSurface read_with_openmesh(const SurfaceSource& source) {
  const std::string name = source.path.string();
  PolyMesh mesh;
  {
    const std::lock_guard lock(openmesh_mutex());
    // The library never prints: OpenMesh reports problems on omerr/omlog,
    // which would go to std::cerr.
    omerr().disable();
    omlog().disable();
    omout().disable();
    OpenMesh::IO::Options options;
    // OpenMesh reads the file by its path, not from source.bytes: its
    // readers check the content's format (can_u_read) only on files, and a
    // stream would take text that is no OFF at all for an empty surface.
    if (!OpenMesh::IO::read_mesh(mesh, name, options))
      throw InputError(name + ": cannot read surface (OpenMesh could not parse it)");
  }
  if (mesh.n_vertices() == 0 || mesh.n_faces() == 0) throw InputError(name + ": empty surface (no faces)");
  if (mesh.n_vertices() > static_cast<std::size_t>(kMaxIndexCount))
    throw InputError(name + ": " + std::to_string(mesh.n_vertices()) + " vertices exceed the limit of " +
                     std::to_string(kMaxIndexCount));

  TriSurface surface;
  surface.points.reserve(mesh.n_vertices());
  for (const auto vertex : mesh.vertices()) {
    const auto& p = mesh.point(vertex);
    const Vec3 point{p[0], p[1], p[2]};
    if (!is_finite(point))
      throw ParseError(name, 0, "non-finite coordinate (vertex " + std::to_string(vertex.idx()) + ")");
    surface.points.push_back(point);
  }
  surface.triangles.reserve(mesh.n_faces());
  std::vector<Index> corners;
  for (const auto face : mesh.faces()) {
    corners.clear();
    for (const auto vertex : mesh.fv_range(face)) corners.push_back(static_cast<Index>(vertex.idx()));
    for (std::size_t i = 1; i + 1 < corners.size(); ++i)
      surface.triangles.push_back({corners[0], corners[i], corners[i + 1]});
  }
  if (surface.triangles.size() > static_cast<std::size_t>(kMaxIndexCount))
    throw InputError(name + ": " + std::to_string(surface.triangles.size()) + " triangles exceed the limit of " +
                     std::to_string(kMaxIndexCount));
  return surface;
}

// The first MiB of a file (or all of it).
std::string read_prefix(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string prefix(kPrefixBytes, '\0');
  in.read(prefix.data(), static_cast<std::streamsize>(prefix.size()));
  prefix.resize(static_cast<std::size_t>(in.gcount()));
  return prefix;
}

// The element counts in the text header of an OFF ("OFF\nV F
// E") or PLY ("element vertex V") file, summed; 0 when none can be read.
std::uint64_t header_counts(std::string_view header, bool is_ply) {
  std::istringstream in{std::string(header)};
  std::string line;
  std::uint64_t total = 0;
  if (!is_ply) {
    std::getline(in, line);  // OFF keyword (counts may follow on the same line)
    const std::size_t off = line.find("OFF");
    std::istringstream rest(off == std::string::npos ? std::string() : line.substr(off + 3));
    std::uint64_t v = 0, f = 0;
    if (!(rest >> v >> f)) {
      while (std::getline(in, line) && (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#')) {
      }
      std::istringstream counts(line);
      if (!(counts >> v >> f)) return 0;
    }
    return v > UINT64_MAX - f ? UINT64_MAX : v + f;
  }
  while (std::getline(in, line) && line.rfind("end_header", 0) != 0) {
    std::istringstream words(line);
    std::string word, kind;
    std::uint64_t n = 0;
    if (words >> word >> kind >> n && word == "element") total = n > UINT64_MAX - total ? UINT64_MAX : total + n;
  }
  return total;
}

// Refuses, before OpenMesh reads the file (and allocates what its header
// claims, or reads gigabytes of zeros), a surface larger than the budget,
// binary data in a text format, a binary STL whose triangle count does not
// match its size, and OFF / PLY header counts the file cannot hold (each
// element takes at least one byte).
void check_surface_file(const std::filesystem::path& path, const std::string& ext, const ReadLimits& limits) {
  const std::string name = path.string();
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return;  // OpenMesh reports it
  if (limits.max_memory > 0 && size >= limits.max_memory)
    throw InputError(name + ": the file has " + std::to_string(size) + " bytes (" + format_memory_size(size) +
                     "), more than --max-memory (" + format_memory_size(limits.max_memory) + ")");
  const std::string prefix = read_prefix(path);
  const std::size_t nul = prefix.find('\0');
  const std::string_view first_line = std::string_view(prefix).substr(0, prefix.find('\n'));
  auto binary_data = [&](const char* format) {
    throw ParseError(
        name, 0,
        std::string("binary data, expected ") + format + " text (a NUL byte at offset " + std::to_string(nul) + ")");
  };
  if (ext == ".stl") {
    // Binary STL: an 80-byte header, a uint32 count, 50 bytes per triangle.
    if (is_ascii_stl(prefix)) return;
    std::uint64_t count = 0;
    for (int i = 3; i >= 0 && prefix.size() >= 84; --i) count = count << 8 | static_cast<unsigned char>(prefix[80 + i]);
    if (size < 84 || 84 + 50 * count != size)
      throw ParseError(name, 0,
                       "binary STL header claims " + std::to_string(count) + " triangles (" +
                           std::to_string(84 + 50 * count) + " bytes) but the file has " + std::to_string(size));
    return;
  }
  if (ext == ".obj" && nul != std::string::npos) binary_data("OBJ");
  if (ext == ".mesh" && nul != std::string::npos) binary_data("MEDIT (.mesh)");
  if (ext == ".off") {
    const bool is_binary = first_line.find("BINARY") != std::string_view::npos;
    if (nul != std::string::npos && (!is_binary || first_line.find("OFF") == std::string_view::npos))
      binary_data("OFF");
  }
  if (ext == ".ply") {
    const std::size_t end = prefix.find("end_header");
    if (!prefix.starts_with("ply") || (nul != std::string::npos && nul < end)) {
      if (nul != std::string::npos) binary_data("PLY header");
      return;  // OpenMesh reports it
    }
  }
  if (ext == ".off" || ext == ".ply") {
    const std::uint64_t claimed =
        header_counts(prefix.substr(0, std::min(prefix.size(), std::size_t{1} << 16)), ext == ".ply");
    if (claimed > size)
      throw ParseError(name, 0,
                       "the header claims " + std::to_string(claimed) + " vertices and faces but the file has " +
                           std::to_string(size) + " bytes");
  }
}

}  // namespace

SurfaceSource open_surface_source(const std::filesystem::path& path, const ReadLimits& limits) {
  const std::string ext = detail::lowercase_extension(path);
  if (ext != ".obj" && ext != ".off" && ext != ".stl" && ext != ".ply" && ext != ".mesh") {
    if (ext.empty()) throw InputError(path.string() + ": no file extension (expected .obj, .off, .stl, .ply or .mesh)");
    throw InputError(path.string() + ": unknown surface format '" + path.extension().string() +
                     "' (expected .obj, .off, .stl, .ply or .mesh)");
  }
  detail::check_readable_file(path);
  check_surface_file(path, ext, limits);  // before the file is read whole
  SurfaceSource source;
  source.path = path;
  source.format = ext == ".mesh" ? "medit" : ext.substr(1);
  source.bytes = read_file_bytes(path);
  source.sha256 = sha256_hex(source.bytes);
  return source;
}

TriSurface read_surface(const SurfaceSource& source) {
  if (source.format != "medit") return read_with_openmesh(source);
  if (const std::size_t nul = source.bytes.find('\0'); nul != std::string::npos)
    throw ParseError(source.path.string(), 0,
                     "binary data, expected MEDIT (.mesh) text (a NUL byte at offset " + std::to_string(nul) + ")");
  return read_medit_triangles(source.bytes, source.path.string());
}

TriSurface read_surface(const std::filesystem::path& path, const ReadLimits& limits) {
  return read_surface(open_surface_source(path, limits));
}

InputFile input_file(const SurfaceSource& source) { return {reported_path(source.path), source.format, source.sha256}; }

}  // namespace hq
