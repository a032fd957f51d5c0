// make_refined INPUT LEVELS OUTPUT.mesh: writes INPUT (any mesh format
// HQView reads) refined LEVELS times 1->8 (bench_data.h, refine_1_to_8) as a
// MEDIT file, the input of scripts/bench's end-to-end stage (two levels of
// Dolphin_padded: 45,440 -> 2,908,160 hexes). Prints the counts on stdout.

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>

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

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: make_refined INPUT LEVELS OUTPUT.mesh\n");
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
    write_medit(mesh, argv[3]);
    std::printf("%zu vertices, %zu hexes\n", mesh.points.size(), mesh.hexes.size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_refined: %s\n", e.what());
    return 3;
  }
  return 0;
}
