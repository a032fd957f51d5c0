// The polygon reader (OBJ, OFF, PLY): triangles and quads into their blocks,
// polygons of more than 4 vertices skipped as holes, faces with repeated
// vertices skipped, non-manifold edges diagnosed and kept, and every bad
// input as "path:line: what is wrong".

#include "hqview/io/polygon_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "hqview/core/error.h"
#include "hqview/io/mesh_reader.h"
#include "io/error_text.h"
#include "io/temp_dir.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::error_text;
using test::TempDir;

// The test surface, as every format writes it: the unit cube's bottom face
// as 4 quads around the centre point 8 (a 2 x 2 grid, points 0..8 row by
// row), a triangle on top of the first quad's edge, and a pentagon.
//   6--7--8      z=0: points (x, y) = (i % 3, i / 3) / 2
//   |  |  |
//   3--4--5      point 9 = (0.25, -0.5, 0)
//   |  |  |
//   0--1--2
const std::vector<std::array<Index, 4>> kQuads = {{0, 1, 4, 3}, {1, 2, 5, 4}, {3, 4, 7, 6}, {4, 5, 8, 7}};
const std::array<Index, 3> kTriangle = {1, 0, 9};
const std::array<Index, 5> kPentagon = {2, 1, 9, 3, 6};  // a polygon: skipped, its edges holes

Vec3 point(int i) { return i == 9 ? Vec3{0.25, -0.5, 0} : Vec3{(i % 3) * 0.5, (i / 3) * 0.5, 0}; }

void expect_test_surface(const LoadedMesh& loaded, std::int64_t first_source) {
  ASSERT_EQ(loaded.mesh.points.size(), 10u);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(loaded.mesh.points[static_cast<std::size_t>(i)], point(i)) << i;
  EXPECT_EQ(loaded.mesh.quads, kQuads);
  ASSERT_EQ(loaded.mesh.triangles.size(), 1u);
  EXPECT_EQ(loaded.mesh.triangles[0], kTriangle);
  EXPECT_TRUE(loaded.mesh.hexes.empty());
  // Faces in the file: the 4 quads, the pentagon, the triangle.
  const auto& quad_sources = loaded.mesh.source_index[static_cast<std::size_t>(CellKind::quad)];
  const auto& triangle_sources = loaded.mesh.source_index[static_cast<std::size_t>(CellKind::triangle)];
  EXPECT_EQ(quad_sources,
            (std::vector<std::int64_t>{first_source, first_source + 1, first_source + 2, first_source + 3}));
  EXPECT_EQ(triangle_sources, (std::vector<std::int64_t>{first_source + 5}));
  const std::vector<std::array<Index, 2>> holes = {{1, 2}, {1, 9}, {2, 6}, {3, 6}, {3, 9}};
  EXPECT_EQ(loaded.hole_edges, holes);
}

std::string obj_text() {
  std::string s = "# written by hand\nmtllib m.mtl\no surface\n";
  for (int i = 0; i < 10; ++i) {
    const Vec3 p = point(i);
    s += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + (i == 3 ? " 1 0 0" : "") +
         "\n";
  }
  s += "vt 0 0\nvt 1 0\nvn 0 0 1\ng quads\ns off\nusemtl red\n";
  s += "f 1 2 5 4\n";
  s += "f 2/1 3/2 6/1 5/2\n";
  s += "f 4//1 5//1 \\\n 8//1 7//1\n";  // continued on the next line
  s += "f -6/1/1 -5/2/1 -2/1/1 -3/2/1 # negative: relative to the 10 vertices read\n";
  s += "f 3 2 10 4 7\nl 1 2\nf 2 1 10\n";
  return s;
}

std::string off_text() {
  std::string s = "COFF\n# comment\n10 6 0\n";
  for (int i = 0; i < 10; ++i) {
    const Vec3 p = point(i);
    s += std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + " 255 0 0 255\n";
  }
  s += "4 0 1 4 3\n4 1 2 5 4 0.5 0.5 0.5\n\n4 3 4 7 6 1\n4 4 5 8 7 0 1 0 1\n5 2 1 9 3 6\n3 1 0 9\n";
  return s;
}

// PLY in every encoding: a vertex element with x, y, z and extra
// properties, a face element with an extra list, and an edge element.
enum class Ply { ascii, little, big };

template <class T>
void put(std::string& s, T value, Ply ply) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if ((ply == Ply::big) == (std::endian::native == std::endian::little)) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

std::string ply_text(Ply ply) {
  std::string s = std::string("ply\nformat ") +
                  (ply == Ply::ascii    ? "ascii"
                   : ply == Ply::little ? "binary_little_endian"
                                        : "binary_big_endian") +
                  " 1.0\ncomment test\nelement vertex 10\nproperty float nx\nproperty double x\nproperty double y\n"
                  "property double z\nproperty uchar red\nelement face 6\nproperty list uchar float texcoord\n"
                  "property list uchar int vertex_indices\nproperty short flags\nelement edge 1\n"
                  "property int vertex1\nproperty int vertex2\nend_header\n";
  std::vector<std::vector<Index>> faces;
  for (const auto& q : kQuads) faces.push_back({q[0], q[1], q[2], q[3]});
  faces.push_back({kPentagon.begin(), kPentagon.end()});
  faces.push_back({kTriangle.begin(), kTriangle.end()});
  if (ply == Ply::ascii) {
    for (int i = 0; i < 10; ++i) {
      const Vec3 p = point(i);
      s += "0.5 " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + " 200\n";
    }
    for (const auto& f : faces) {
      s += "2 0.5 0.25 " + std::to_string(f.size());
      for (const Index v : f) s += " " + std::to_string(v);
      s += " 7\n";
    }
    return s + "0 1\n";
  }
  for (int i = 0; i < 10; ++i) {
    const Vec3 p = point(i);
    put(s, 0.5f, ply);
    for (const double c : {p.x, p.y, p.z}) put(s, c, ply);
    put(s, std::uint8_t{200}, ply);
  }
  for (const auto& f : faces) {
    put(s, std::uint8_t{2}, ply);
    put(s, 0.5f, ply);
    put(s, 0.25f, ply);
    put(s, static_cast<std::uint8_t>(f.size()), ply);
    for (const Index v : f) put(s, std::int32_t{v}, ply);
    put(s, std::int16_t{7}, ply);
  }
  put(s, std::int32_t{0}, ply);
  put(s, std::int32_t{1}, ply);
  return s;
}

const std::string kPolygonWarning =
    ": 1 polygon of more than 4 vertices skipped (face 5): their edges are holes in the surface, not its boundary";

TEST(PolygonReader, ObjCornersNegativeIdsContinuationsAndPolygons) {
  const LoadedMesh loaded = read_obj(obj_text(), "s.obj");
  EXPECT_EQ(loaded.format, "obj");
  expect_test_surface(loaded, 1);
  EXPECT_EQ(loaded.warnings, std::vector<std::string>{"s.obj" + kPolygonWarning});
}

TEST(PolygonReader, OffWithColours) {
  const LoadedMesh loaded = read_off(off_text(), "s.off");
  EXPECT_EQ(loaded.format, "off");
  expect_test_surface(loaded, 0);
  EXPECT_EQ(loaded.warnings,
            std::vector<std::string>{"s.off" + std::string(": 1 polygon of more than 4 vertices skipped (face 4): "
                                                           "their edges are holes in the surface, not its boundary")});
  // Counts on the keyword's line, no edge count, other prefixes.
  const LoadedMesh same = read_off("NOFF 3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n", "t.off");
  EXPECT_EQ(same.mesh.triangles.size(), 1u);
  EXPECT_EQ(same.mesh.points[1], (Vec3{1, 0, 0}));
}

TEST(PolygonReader, PlyAsciiAndBinaryBothByteOrders) {
  for (const Ply ply : {Ply::ascii, Ply::little, Ply::big}) {
    const LoadedMesh loaded = read_ply(ply_text(ply), "s.ply");
    EXPECT_EQ(loaded.format, ply == Ply::ascii    ? "ply-ascii"
                             : ply == Ply::little ? "ply-binary-little-endian"
                                                  : "ply-binary-big-endian");
    expect_test_surface(loaded, 0);
    EXPECT_EQ(loaded.warnings, std::vector<std::string>{
                                   "s.ply" + std::string(": 1 polygon of more than 4 vertices skipped (face 4): their "
                                                         "edges are holes in the surface, not its boundary")});
  }
}

// Four quads on one edge (a "book" of four pages on the edge 0-1): the edge
// is non-manifold. The reader keeps every face and says so; OpenMesh, a
// halfedge structure, cannot hold it, which is what this reader is for.
const std::string kBookOff =
    "OFF\n10 4 0\n"
    "0 0 0\n1 0 0\n1 1 0\n0 1 0\n1 0 1\n0 0 1\n1 -1 0\n0 -1 0\n1 0 -1\n0 0 -1\n"
    "4 0 1 2 3\n4 1 0 5 4\n4 0 1 6 7\n4 1 0 9 8\n";

TEST(PolygonReader, NonManifoldEdgesAreCountedListedAndKept) {
  const LoadedMesh loaded = read_off(kBookOff, "book.off");
  EXPECT_EQ(loaded.mesh.quads.size(), 4u);
  EXPECT_EQ(loaded.warnings, std::vector<std::string>{"book.off: 1 non-manifold edge (on more than two faces; the "
                                                      "faces are kept): vertices 0-1 (4 faces)"});
  // OBJ names the vertices as the file does, 1-based.
  const LoadedMesh obj = read_obj(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 0 1\nv 0 0 1\nv 1 -1 0\nv 0 -1 0\n"
      "f 1 2 3 4\nf 2 1 6 5\nf 1 2 7 8\n",
      "book.obj");
  EXPECT_EQ(obj.warnings, std::vector<std::string>{"book.obj: 1 non-manifold edge (on more than two faces; the faces "
                                                   "are kept): vertices 1-2 (3 faces)"});
  TempDir dir("polygon");
  const TriSurface openmesh = read_surface(dir.write("book.off", kBookOff));
  // OpenMesh cannot hold the edge: it adds the faces it cannot attach with
  // copies of their vertices (18 points for 10), so the edge is gone.
  EXPECT_GT(openmesh.points.size(), loaded.mesh.points.size());
}

TEST(PolygonReader, FacesWithARepeatedVertexAreSkipped) {
  const LoadedMesh loaded =
      read_off("OFF\n4 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 1 2\n3 0 1 2\n4 0 1 2 0\n", "r.off");
  EXPECT_EQ(loaded.mesh.triangles.size(), 1u);
  EXPECT_TRUE(loaded.mesh.quads.empty());
  EXPECT_EQ(loaded.warnings, std::vector<std::string>{"r.off: 2 faces with a repeated vertex skipped (faces 0, 2)"});
}

TEST(PolygonReader, ObjErrors) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  const auto error = [](const std::string& text) { return error_text<ParseError>([&] { read_obj(text, "m.obj"); }); };
  EXPECT_EQ(error(v + "f 1 2 3 9\n"), "m.obj:5: vertex id 9 out of range [1, 4] (face 1)");
  EXPECT_EQ(error(v + "f 1 2 3\nf 1 2 -5\n"), "m.obj:6: vertex id -5 out of range (only 4 vertices before this face)");
  EXPECT_EQ(error(v + "f 0 1 2\n"), "m.obj:5: expected a vertex id (v, v/vt, v//vn or v/vt/vn, non-zero), got '0'");
  EXPECT_EQ(error(v + "f 1 2\n"), "m.obj:5: a face needs at least 3 vertices, got 2");
  EXPECT_EQ(error(v + "f 1/2/3/4 2 3\n"),
            "m.obj:5: expected a vertex id (v, v/vt, v//vn or v/vt/vn, non-zero), got '1/2/3/4'");
  EXPECT_EQ(error(v + "f 1 2 \xff\xfe\n"),
            "m.obj:5: expected a vertex id (v, v/vt, v//vn or v/vt/vn, non-zero), got '\\xff\\xfe'");
  EXPECT_EQ(error("v 0 nan 0\n"), "m.obj:1: non-finite coordinate (vertex 1)");
  EXPECT_EQ(error("v 0 0\n"), "m.obj:1: expected 3 coordinates after 'v'");
  EXPECT_EQ(error("v 0 0 x\n"), "m.obj:1: expected a coordinate, got 'x'");
  // Forward references are resolved once every vertex is read.
  EXPECT_EQ(read_obj("f 1 2 3\n" + v, "m.obj").mesh.triangles.size(), 1u);
}

TEST(PolygonReader, OffErrors) {
  const auto error = [](const std::string& text) { return error_text<ParseError>([&] { read_off(text, "m.off"); }); };
  const std::string v = "0 0 0\n1 0 0\n1 1 0\n";
  EXPECT_EQ(error("OFF\n3 1 0\n" + v + "3 0 1 3\n"), "m.off:6: vertex id 3 out of range [0, 3) (face 0)");
  EXPECT_EQ(error("OFF\n3 1 0\n" + v + "4 0 1 2\n"), "m.off:6: expected 4 vertex ids, got 3 (face 0)");
  EXPECT_EQ(error("OFF\n3 1 0\n" + v + "2 0 1   \n"), "m.off:6: face 0 has 2 vertices (at least 3)");
  EXPECT_EQ(error("OFF\n3 1 0\n" + v + "3 0 1 2 1 2 3 4 5\n"),
            "m.off:6: 9 values for face 0 of 3 vertices (expected at most 4 colour values after its ids)");
  EXPECT_EQ(error("OFF\n3 2 0\n" + v + "3 0 1 2\n"),
            "m.off:2: 2 faces cannot fit in the 8 bytes left after the vertices");
  // Huge counts are refused before anything is allocated from them.
  EXPECT_EQ(error("OFF\n2000000000 1 0\n0 0 0\n"),
            "m.off:2: 2000000000 vertices cannot fit in the 7 bytes left in the file");
  EXPECT_EQ(error("OFF\n3 1 0\n0 0 0\n1 0 0\n# a long comment line\n"),
            "m.off:5: unexpected end of file, expected vertex 2 of 3");
  EXPECT_EQ(error("OFF BINARY\n"), "m.off:1: binary OFF files are not read (write ASCII OFF)");
  EXPECT_EQ(error("4OFF\n"), "m.off:1: '4OFF' files (4D or n-dimensional vertices) are not read");
  EXPECT_EQ(error("PFF\n"), "m.off:1: expected 'OFF', got 'PFF'");
  EXPECT_EQ(error("OFF\n-1 0 0\n"), "m.off:2: negative number of vertices (-1)");
}

TEST(PolygonReader, PlyErrors) {
  const auto error = [](const std::string& text) { return error_text<ParseError>([&] { read_ply(text, "m.ply"); }); };
  const std::string binary = ply_text(Ply::little);
  // One byte short: the counts fit (each face takes at least 4 bytes), the last value does not.
  EXPECT_EQ(error(binary.substr(0, binary.size() - 1)),
            "m.ply: truncated binary data in element 'edge' 0 of 1 at byte " + std::to_string(binary.size() - 4));
  std::string out_of_range = ply_text(Ply::ascii);
  out_of_range.replace(out_of_range.find("4 0 1 4 3"), 9, "4 0 1 4 30");
  EXPECT_EQ(error(out_of_range), "m.ply:28: vertex id 30 out of range [0, 10) (face 0)");
  std::string huge = ply_text(Ply::little);
  huge.replace(huge.find("element face 6"), 14, "element face 4000000000");
  EXPECT_EQ(error(huge), "m.ply:10: 4000000000 elements 'face' cannot fit in the 176 bytes left in the file");
  EXPECT_EQ(error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n"),
            "m.ply:3: element 'vertex' has no x, y and z properties");
  EXPECT_EQ(error("ply\nformat ascii 1.0\nelement face 1\nproperty int a\nend_header\n0\n"),
            "m.ply:3: element 'face' has no list property 'vertex_indices' (or 'vertex_index')");
  EXPECT_EQ(error("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\n"),
            "m.ply:4: unknown property type 'quad'");
  EXPECT_EQ(error("ply\nformat ascii 1.0\n"), "m.ply:2: unexpected end of file in the header, expected 'end_header'");
  EXPECT_EQ(error("ply\nformat binary 1.0\nend_header\n"), "m.ply:2: unknown PLY format 'binary'");
  EXPECT_EQ(error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                  "end_header\n0 inf 0\n"),
            "m.ply:8: non-finite coordinate (vertex 0)");
}

TEST(PolygonReader, FormatDetectionAndDispatch) {
  EXPECT_TRUE(looks_like_off("# c\nCOFF\n"));
  EXPECT_TRUE(looks_like_off("STCNOFF 1 2 3"));
  EXPECT_FALSE(looks_like_off("OFFSET 1"));
  EXPECT_FALSE(looks_like_off("CSTOFF"));  // prefixes out of order
  EXPECT_TRUE(looks_like_ply("ply\r\nformat ascii 1.0\n"));
  EXPECT_EQ(detect_mesh_format(off_text()), "off");
  EXPECT_EQ(detect_mesh_format(ply_text(Ply::big)), "ply");
  // A surface mesh's extension is not a hex mesh's: batch DIR leaves reference surfaces alone.
  for (const char* name : {"m.obj", "m.OFF", "m.ply"}) EXPECT_FALSE(has_hex_mesh_extension(name)) << name;
  EXPECT_EQ(error_text<ParseError>([] { read_hex_mesh("m.off", ply_text(Ply::ascii)); }),
            "m.off: a .off file with PLY content (expected the extension .ply)");
  EXPECT_EQ(error_text<ParseError>([] { read_hex_mesh("m.obj", std::string("v 0 0 0\n\0", 9)); }),
            "m.obj: binary data, expected OBJ (Wavefront) text (a NUL byte at offset 8)");
}

// Real surfaces: the reader gives OpenMesh's points and triangles (each
// triangle up to a rotation of its corners) on the shared triangle surfaces.
TEST(PolygonReader, RealSurfacesAsOpenMeshReadsThem) {
  const std::optional<std::filesystem::path> data = test::shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data (or $HQVIEW_DATA) not found";
  const auto canonical = [](std::array<Index, 3> t) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
  };
  for (const char* file : {"meshes/gao2016_sweeping/kitten.off", "meshes/livesu2016_skeleton/armadillo.obj"}) {
    const std::filesystem::path path = *data / file;
    const std::string bytes = read_file_bytes(path);
    const LoadedMesh ours = path.extension() == ".off" ? read_off(bytes, file) : read_obj(bytes, file);
    const TriSurface openmesh = read_surface(path);
    EXPECT_TRUE(ours.warnings.empty()) << file;
    EXPECT_TRUE(ours.mesh.quads.empty()) << file;
    // OpenMesh's PolyMesh holds float coordinates; this reader keeps the file's doubles.
    ASSERT_EQ(ours.mesh.points.size(), openmesh.points.size()) << file;
    for (std::size_t i = 0; i < openmesh.points.size(); ++i) {
      const Vec3& p = ours.mesh.points[i];
      const Vec3& q = openmesh.points[i];
      ASSERT_TRUE(static_cast<float>(p.x) == q.x && static_cast<float>(p.y) == q.y && static_cast<float>(p.z) == q.z)
          << file << " point " << i;
    }
    ASSERT_EQ(ours.mesh.triangles.size(), openmesh.triangles.size()) << file;
    for (std::size_t t = 0; t < openmesh.triangles.size(); ++t)
      ASSERT_EQ(canonical(ours.mesh.triangles[t]), canonical(openmesh.triangles[t])) << file << " triangle " << t;
  }
}

// An independent writer: Debian's python3-meshio writes a quad-dominant
// mesh (a perturbed grid of quads, every third one split in 2 triangles,
// coordinates with all their digits) as OBJ and as ASCII and binary PLY;
// the reader gives back every point bit for bit and every cell. meshio
// writes quads first, then triangles, each block in order.
TEST(PolygonReader, FilesWrittenByMeshio) {
  const std::string python = HQ_SYSTEM_PYTHON;
  if (python.empty() || std::system((python + " -c 'import meshio' 2>/dev/null").c_str()) != 0)
    GTEST_SKIP() << "python3-meshio not available";
  Mesh mesh;
  const int n = 6;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      mesh.points.push_back(
          {i + 0.3 * std::sin(1.7 * i * j + 0.1), j + 0.3 * std::cos(2.3 * i + j), 0.1 * std::sin(i + 3.1 * j)});
  const auto id = [](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::array<Index, 4> q = {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      if ((i + j) % 3 == 0) {
        mesh.triangles.push_back({q[0], q[1], q[2]});
        mesh.triangles.push_back({q[0], q[2], q[3]});
      } else {
        mesh.quads.push_back(q);
      }
    }
  TempDir dir("meshio_polygon");
  std::string dump = std::to_string(mesh.points.size()) + " " + std::to_string(mesh.quads.size()) + " " +
                     std::to_string(mesh.triangles.size()) + "\n";
  const auto shortest = [](double v) {
    char buffer[32];
    return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);
  };
  for (const Vec3& p : mesh.points) dump += shortest(p.x) + " " + shortest(p.y) + " " + shortest(p.z) + "\n";
  for (const auto& q : mesh.quads)
    dump += std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " " +
            std::to_string(q[3]) + "\n";
  for (const auto& t : mesh.triangles)
    dump += std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n";
  const std::string command =
      python + " " + HQ_MESHIO_POLYGON_SCRIPT + " " + dir.write("mesh.txt", dump).string() + " " + dir.path().string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  for (const char* file : {"mesh.obj", "mesh_ascii.ply", "mesh_binary.ply"}) {
    const std::filesystem::path path = dir.path() / file;
    const std::string bytes = read_file_bytes(path);
    const LoadedMesh loaded = path.extension() == ".obj" ? read_obj(bytes, file) : read_ply(bytes, file);
    EXPECT_EQ(loaded.mesh.points, mesh.points) << file;
    EXPECT_EQ(loaded.mesh.quads, mesh.quads) << file;
    EXPECT_EQ(loaded.mesh.triangles, mesh.triangles) << file;
    EXPECT_TRUE(loaded.warnings.empty()) << file;
  }
}

}  // namespace
}  // namespace hq
