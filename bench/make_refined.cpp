// make_refined INPUT LEVELS OUTPUT.mesh [--tets]: writes INPUT (any mesh
// format HQView reads) refined LEVELS times 1->8 (bench_data.h,
// refine_1_to_8) as a MEDIT file, the input of scripts/bench's end-to-end
// stage (two levels of Dolphin_padded: 45,440 -> 2,908,160 hexes). With
// --tets, each hex is written as 6 tetrahedra, conformingly (split_into_tets
// below). Prints the counts on stdout.

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "hqview/core/cell_kinds.h"

#include "bench_data.h"
#include "hqview/io/mesh_reader.h"

namespace {

// Writes `mesh` as MEDIT (1-based ids, reference 0), points with 9
// significant digits (the refined points are means of the input's).
void write_medit(const hq::HexMesh& mesh, const std::filesystem::path& path) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "wb"), std::fclose);
  if (!file) throw hq::Error(path.string() + ": cannot open for writing");
  std::FILE* f = file.get();
  std::fprintf(f, "MeshVersionFormatted 1\nDimension 3\nVertices %zu\n", mesh.points.size());
  for (const hq::Vec3& p : mesh.points) std::fprintf(f, "%.9g %.9g %.9g 0\n", p.x, p.y, p.z);
  std::fprintf(f, "Hexahedra %zu\n", mesh.hexes.size());
  char line[8 * 12 + 4];
  for (const hq::Hex& hex : mesh.hexes) {
    char* out = line;
    for (hq::Index id : hex) {
      out = std::to_chars(out, line + sizeof line, id + 1).ptr;
      *out++ = ' ';
    }
    *out++ = '0';
    *out++ = '\n';
    std::fwrite(line, 1, static_cast<std::size_t>(out - line), f);
  }
  std::fprintf(f, "End\n");
  if (std::fflush(f) != 0 || std::ferror(f)) throw hq::Error(path.string() + ": write failed");
}

// Each hex as 6 tetrahedra that fit their neighbours': every quad face is
// split along the diagonal through its smallest vertex id (the same choice
// from both hexes that share it), by coning the hex from its smallest vertex
// v over the two triangles of each of the 3 faces that do not contain v
// (the faces through v then get diagonals through v: their smallest too).
// Each tet (the face triangle reversed, then v) is positive in VTK order
// when the face is outward (core/cell_kinds.h) and the hex convex.
std::vector<std::array<hq::Index, 4>> split_into_tets(const hq::HexMesh& mesh) {
  using Table = hq::CellKindTable<hq::CellKind::hex>;
  std::vector<std::array<hq::Index, 4>> tets;
  tets.reserve(6 * mesh.hexes.size());
  for (const hq::Hex& h : mesh.hexes) {
    int low = 0;
    for (int i = 1; i < 8; ++i)
      if (h[static_cast<std::size_t>(i)] < h[static_cast<std::size_t>(low)]) low = i;
    for (const hq::CellFace& face : Table::faces) {
      std::array<hq::Index, 4> q;
      bool has_low = false;
      for (int i = 0; i < 4; ++i) {
        q[static_cast<std::size_t>(i)] = h[static_cast<std::size_t>(face.v[static_cast<std::size_t>(i)])];
        has_low = has_low || face.v[static_cast<std::size_t>(i)] == low;
      }
      if (has_low) continue;
      int m = 0;  // the face's smallest id: its diagonal runs from there
      for (int i = 1; i < 4; ++i)
        if (q[static_cast<std::size_t>(i)] < q[static_cast<std::size_t>(m)]) m = i;
      const auto at = [&](int i) { return q[static_cast<std::size_t>((m + i) % 4)]; };
      const hq::Index apex = h[static_cast<std::size_t>(low)];
      tets.push_back({at(0), at(2), at(1), apex});
      tets.push_back({at(0), at(3), at(2), apex});
    }
  }
  return tets;
}

// Writes the tets of split_into_tets(mesh) as MEDIT Tetrahedra.
void write_medit_tets(const hq::HexMesh& mesh, const std::filesystem::path& path) {
  const auto tets = split_into_tets(mesh);
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "wb"), std::fclose);
  if (!file) throw hq::Error(path.string() + ": cannot open for writing");
  std::FILE* f = file.get();
  std::fprintf(f, "MeshVersionFormatted 1\nDimension 3\nVertices %zu\n", mesh.points.size());
  for (const hq::Vec3& p : mesh.points) std::fprintf(f, "%.9g %.9g %.9g 0\n", p.x, p.y, p.z);
  std::fprintf(f, "Tetrahedra %zu\n", tets.size());
  for (const auto& t : tets) std::fprintf(f, "%d %d %d %d 0\n", t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1);
  std::fprintf(f, "End\n");
  if (std::fflush(f) != 0 || std::ferror(f)) throw hq::Error(path.string() + ": write failed");
}

}  // namespace

int main(int argc, char** argv) {
  const bool tets = argc == 5 && std::string(argv[4]) == "--tets";
  if (argc != 4 && !tets) {
    std::fprintf(stderr, "usage: make_refined INPUT LEVELS OUTPUT.mesh [--tets]\n");
    return 2;
  }
  const int levels = std::atoi(argv[2]);
  if (levels < 0 || levels > 3) {
    std::fprintf(stderr, "make_refined: LEVELS must be 0 to 3, got '%s'\n", argv[2]);
    return 2;
  }
  try {
    hq::HexMesh mesh = hq::read_hex_mesh(argv[1]).mesh;
    for (int i = 0; i < levels; ++i) mesh = hq::bench::refine_1_to_8(mesh);
    if (tets) {
      write_medit_tets(mesh, argv[3]);
      std::printf("%zu vertices, %zu tetrahedra (6 per hex of %zu)\n", mesh.points.size(), 6 * mesh.hexes.size(),
                  mesh.hexes.size());
    } else {
      write_medit(mesh, argv[3]);
      std::printf("%zu vertices, %zu hexes\n", mesh.points.size(), mesh.hexes.size());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_refined: %s\n", e.what());
    return 3;
  }
  return 0;
}
