// read_surface(): reference triangle surfaces. OBJ, OFF, STL and PLY go
// through OpenMesh (polygons triangulated as fans; OpenMesh merges the
// duplicate vertices of STL files); .mesh through read_medit_triangles.

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <cmath>
#include <mutex>
#include <string>
#include <vector>

#include "hqview/core/error.h"
#include "hqview/core/types.h"
#include "hqview/io/medit_reader.h"
#include "hqview/io/mesh_file.h"
#include "hqview/io/mesh_reader.h"

namespace hq {
namespace {

using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

// OpenMesh's readers share global state (the IOManager singleton, its
// reader instances, the omerr stream): one read at a time.
std::mutex& openmesh_mutex() {
  static std::mutex mutex;
  return mutex;
}

TriSurface read_with_openmesh(const std::filesystem::path& path) {
  const std::string name = path.string();
  PolyMesh mesh;
  {
    const std::lock_guard lock(openmesh_mutex());
    // The library never prints: OpenMesh reports problems on omerr/omlog,
    // which would go to std::cerr.
    omerr().disable();
    omlog().disable();
    omout().disable();
    OpenMesh::IO::Options options;
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

}  // namespace

TriSurface read_surface(const std::filesystem::path& path) {
  const std::string ext = detail::lowercase_extension(path);
  if (ext == ".mesh") return read_medit_triangles(read_file_bytes(path), path.string());
  if (ext != ".obj" && ext != ".off" && ext != ".stl" && ext != ".ply") {
    if (ext.empty()) throw InputError(path.string() + ": no file extension (expected .obj, .off, .stl, .ply or .mesh)");
    throw InputError(path.string() + ": unknown surface format '" + path.extension().string() +
                     "' (expected .obj, .off, .stl, .ply or .mesh)");
  }
  detail::check_readable_file(path);
  return read_with_openmesh(path);
}

}  // namespace hq
