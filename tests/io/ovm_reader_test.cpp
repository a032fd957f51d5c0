// read_ovm on inline strings. The fixtures are written here the way
// OpenVolumeMesh's HexahedralMesh builds cells (HexahedralMeshTopologyKernel
// ::add_cell: six half-faces XF, XB, YF, YB, ZF, ZB from the corners
// o0..o7, shared faces reused with the matching half-face) and its
// FileManager writes them; the reader must give back the hexes in
// VTK_HEXAHEDRON order ([o0,o1,o2,o3,o4,o7,o6,o5], ALGORITHMS.md §1).

#include "hqview/io/ovm_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "error_text.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/quality/corner_jacobian.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::error_text;

std::string shortest(double v) {
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);
}

struct OvmWriter {
  std::vector<Vec3> points;
  std::vector<std::array<int, 2>> edges;
  std::map<std::pair<int, int>, int> edge_of;  // (min, max) -> edge
  std::vector<std::vector<int>> faces;         // half-edge ids
  std::vector<std::vector<int>> face_vertices;
  std::vector<std::vector<int>> cells;  // half-face ids

  int halfedge(int a, int b) {
    const auto key = std::minmax(a, b);
    auto it = edge_of.find(key);
    if (it == edge_of.end()) {
      it = edge_of.emplace(key, static_cast<int>(edges.size())).first;
      edges.push_back({a, b});
    }
    return 2 * it->second + (edges[static_cast<std::size_t>(it->second)][0] == a ? 0 : 1);
  }
  static bool same_cycle(const std::vector<int>& a, const std::vector<int>& b) {
    for (int r = 0; r < 4; ++r)
      if (a[0] == b[r] && a[1] == b[(r + 1) % 4] && a[2] == b[(r + 2) % 4] && a[3] == b[(r + 3) % 4]) return true;
    return false;
  }
  std::map<std::array<int, 4>, int> face_of;  // sorted vertex ids -> face
  int halfface(const std::vector<int>& vs) {
    std::array<int, 4> key = {vs[0], vs[1], vs[2], vs[3]};
    std::sort(key.begin(), key.end());
    if (const auto it = face_of.find(key); it != face_of.end()) {
      const auto f = static_cast<std::size_t>(it->second);
      if (same_cycle(face_vertices[f], vs)) return static_cast<int>(2 * f);
      std::vector<int> reversed(vs.rbegin(), vs.rend());
      if (same_cycle(face_vertices[f], reversed)) return static_cast<int>(2 * f + 1);
    }
    face_of.emplace(key, static_cast<int>(faces.size()));
    std::vector<int> hes;
    for (std::size_t k = 0; k < vs.size(); ++k) hes.push_back(halfedge(vs[k], vs[(k + 1) % vs.size()]));
    faces.push_back(hes);
    face_vertices.push_back(vs);
    return static_cast<int>(2 * (faces.size() - 1));
  }
  // A hex given in VTK order.
  void add_hex(const Hex& h) {
    const int o[8] = {h[0], h[1], h[2], h[3], h[4], h[7], h[6], h[5]};
    cells.push_back({halfface({o[3], o[2], o[1], o[0]}), halfface({o[7], o[6], o[5], o[4]}),
                     halfface({o[1], o[2], o[6], o[7]}), halfface({o[4], o[5], o[3], o[0]}),
                     halfface({o[1], o[7], o[4], o[0]}), halfface({o[2], o[3], o[5], o[6]})});
  }
  std::string text() const {
    std::string s = "OVM ASCII\nVertices\n" + std::to_string(points.size()) + "\n";
    for (const Vec3& p : points) s += shortest(p.x) + " " + shortest(p.y) + " " + shortest(p.z) + "\n";
    s += "Edges\n" + std::to_string(edges.size()) + "\n";
    for (const auto& e : edges) s += std::to_string(e[0]) + " " + std::to_string(e[1]) + "\n";
    s += "Faces\n" + std::to_string(faces.size()) + "\n";
    for (const auto& f : faces) {
      s += std::to_string(f.size());
      for (const int he : f) s += " " + std::to_string(he);
      s += "\n";
    }
    s += "Polyhedra\n" + std::to_string(cells.size()) + "\n";
    for (const auto& c : cells) {
      s += std::to_string(c.size());
      for (const int hf : c) s += " " + std::to_string(hf);
      s += "\n";
    }
    return s;
  }
};

// Two unit cubes side by side along x (they share a face), in VTK order.
OvmWriter two_cubes() {
  OvmWriter w;
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 3; ++x) w.points.push_back({double(x), double(y), double(z)});
  const auto id = [](int x, int y, int z) { return x + 3 * y + 6 * z; };
  for (int x = 0; x < 2; ++x)
    w.add_hex({id(x, 0, 0), id(x + 1, 0, 0), id(x + 1, 1, 0), id(x, 1, 0), id(x, 0, 1), id(x + 1, 0, 1),
               id(x + 1, 1, 1), id(x, 1, 1)});
  return w;
}

TEST(OvmReader, HexesInVtkOrder) {
  const OvmWriter w = two_cubes();
  const LoadedMesh loaded = read_ovm(w.text(), "c.ovm");
  EXPECT_EQ(loaded.format, "ovm-ascii");
  ASSERT_EQ(loaded.mesh.points.size(), 12u);
  EXPECT_EQ(loaded.mesh.points[7].x, 1.0);
  ASSERT_EQ(loaded.mesh.hexes.size(), 2u);
  EXPECT_EQ(loaded.mesh.hexes[0], (Hex{0, 1, 4, 3, 6, 7, 10, 9}));
  EXPECT_EQ(loaded.mesh.hexes[1], (Hex{1, 2, 5, 4, 7, 8, 11, 10}));
}

// Cells whose half-faces come in another order (not from OVM's hex type):
// the same hexahedron, same orientation, corners relabelled.
TEST(OvmReader, AnyHalfFaceOrder) {
  OvmWriter w = two_cubes();
  std::rotate(w.cells[1].begin(), w.cells[1].begin() + 2, w.cells[1].end());
  const LoadedMesh loaded = read_ovm(w.text(), "c.ovm");
  ASSERT_EQ(loaded.mesh.hexes.size(), 2u);
  Hex sorted = loaded.mesh.hexes[1];
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (Hex{1, 2, 4, 5, 7, 8, 10, 11}));
  // Right-handed corner 0 frame (1, 3, 4): the orientation is kept.
  const auto& p = loaded.mesh.points;
  const Hex& h = loaded.mesh.hexes[1];
  const Vec3 o = p[static_cast<std::size_t>(h[0])];
  const auto d = [&](int i) {
    const Vec3 q = p[static_cast<std::size_t>(h[i])];
    return Vec3{q.x - o.x, q.y - o.y, q.z - o.z};
  };
  const Vec3 a = d(1), b = d(3), c = d(4);
  EXPECT_GT(a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x), 0.0);
}

// The six outward faces of a hex, each as its cycle rotated to start at its
// smallest id, sorted: equal for the same oriented hexahedron however its
// corners are labelled.
std::vector<std::array<Index, 4>> oriented_faces(const Hex& h) {
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  std::vector<std::array<Index, 4>> out;
  for (const auto& f : faces) {
    std::array<Index, 4> q = {h[f[0]], h[f[1]], h[f[2]], h[f[3]]};
    std::rotate(q.begin(), std::min_element(q.begin(), q.end()), q.end());
    out.push_back(q);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Real meshes written the way OpenVolumeMesh writes a hexahedral mesh (faces
// shared between cells, so many cells start with a half-face another cell
// created) read back with the same points and the same oriented hexes.
TEST(OvmReader, RealMeshesRoundTrip) {
  if (!test::shared_data_dir()) GTEST_SKIP() << "../shared/data (or $HQVIEW_DATA) not found";
  for (const char* relative :
       {"gao2016_sweeping/kitten_1.mesh", "gao2016_sweeping/Dolphin_padded.mesh", "livesu2016_skeleton/warrior.mesh",
        "livesu2015_edgecone/bunny_in.mesh", "li2012_srf/fandisk.mesh", "dualsheet2019/rockarm.vtk"}) {
    SCOPED_TRACE(relative);
    const LoadedMesh original = read_hex_mesh(*test::shared_data_dir() / "meshes" / relative);
    OvmWriter w;
    w.points = original.mesh.points;
    for (const Hex& h : original.mesh.hexes) w.add_hex(h);
    const LoadedMesh loaded = read_ovm(w.text(), "real.ovm");
    ASSERT_EQ(loaded.mesh.points.size(), original.mesh.points.size());
    for (std::size_t i = 0; i < loaded.mesh.points.size(); ++i) {
      ASSERT_EQ(loaded.mesh.points[i].x, original.mesh.points[i].x);
      ASSERT_EQ(loaded.mesh.points[i].y, original.mesh.points[i].y);
      ASSERT_EQ(loaded.mesh.points[i].z, original.mesh.points[i].z);
    }
    ASSERT_EQ(loaded.mesh.hexes.size(), original.mesh.hexes.size());
    std::size_t num_identical = 0;
    for (Index h = 0; h < original.mesh.num_hexes(); ++h) {
      const Hex& a = loaded.mesh.hexes[static_cast<std::size_t>(h)];
      const Hex& b = original.mesh.hexes[static_cast<std::size_t>(h)];
      num_identical += a == b;
      ASSERT_EQ(oriented_faces(a), oriented_faces(b)) << "hex " << h;
      ASSERT_NEAR(hex_scaled_jacobian(hex_corners(loaded.mesh, h)), hex_scaled_jacobian(hex_corners(original.mesh, h)),
                  1e-12)
          << "hex " << h;
    }
    // Cells whose first half-face they created themselves: exactly OVM's documented order.
    EXPECT_GT(num_identical, 0u);
    std::cout << "[ ovm ] " << relative << ": " << num_identical << " of " << original.mesh.hexes.size()
              << " hexes in the original corner order, the others rotated\n";
  }
}

TEST(OvmReader, Detection) {
  EXPECT_TRUE(looks_like_ovm("OVM ASCII\nVertices\n"));
  EXPECT_TRUE(looks_like_ovm("ovm binary"));
  EXPECT_FALSE(looks_like_ovm("OFF\n"));
}

TEST(OvmReader, Errors) {
  const auto error = [](const std::string& text) { return error_text<ParseError>([&] { read_ovm(text, "e.ovm"); }); };
  EXPECT_EQ(error(""), "e.ovm:1: empty file, expected 'OVM ASCII'");
  EXPECT_EQ(error("OVM BINARY\n"), "e.ovm:1: OVM BINARY files are not supported (write OVM ASCII)");
  EXPECT_EQ(error("OVM ASCII\nPoints\n"), "e.ovm:2: expected Vertices, got 'Points'");
  EXPECT_EQ(error("OVM ASCII\nVertices\n-1\n"), "e.ovm:3: negative number of Vertices: -1");
  EXPECT_EQ(error("OVM ASCII\nVertices\n100\n0 0 0\n"),
            "e.ovm:3: 100 Vertices cannot fit in the 7 bytes left in the file");
  EXPECT_EQ(error("OVM ASCII\nVertices\n1\n0 0 nan\n"), "e.ovm:4: non-finite coordinate (vertex 0)");
  EXPECT_EQ(error("OVM ASCII\nVertices\n1\n0 0 0\nEdges\n1\n0 1\n"),
            "e.ovm:7: vertex id 1 out of range [0, 1) (edge 0)");
  EXPECT_EQ(error("OVM ASCII\nVertices\n1\n0 0 0\nEdges\n1\n0 0\n"), "e.ovm:7: edge 0 joins vertex 0 to itself");

  const OvmWriter w = two_cubes();
  const std::string good = w.text();
  // The faces section starts after the edges; rewrite single lines of it.
  const auto replace_line = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  const std::size_t faces_line =
      static_cast<std::size_t>(std::count(good.begin(), good.begin() + good.find("Faces"), '\n')) + 1;
  const std::size_t cells_line =
      static_cast<std::size_t>(std::count(good.begin(), good.begin() + good.find("Polyhedra"), '\n')) + 1;
  std::string first_face = "4";
  for (const int he : w.faces[0]) first_face += " " + std::to_string(he);
  std::string swapped = "4 " + std::to_string(w.faces[0][1]) + " " + std::to_string(w.faces[0][0]) + " " +
                        std::to_string(w.faces[0][2]) + " " + std::to_string(w.faces[0][3]);
  EXPECT_EQ(error(replace_line(first_face + "\n", swapped + "\n")),
            "e.ovm:" + std::to_string(faces_line + 2) + ": the half-edges of face 0 do not form a cycle");
  EXPECT_EQ(error(replace_line(first_face + "\n", "4 0 2 4 999\n")),
            "e.ovm:" + std::to_string(faces_line + 2) + ": half-edge id 999 out of range [0, " +
                std::to_string(2 * w.edges.size()) + ") (face 0)");
  std::string first_cell = "6";
  for (const int hf : w.cells[0]) first_cell += " " + std::to_string(hf);
  EXPECT_EQ(error(replace_line(first_cell + "\n", "5 0 2 4 6 8\n")),
            "e.ovm:" + std::to_string(cells_line + 2) +
                ": polyhedron 0 has 0 triangles and 5 quadrilaterals: not a hexahedron, tetrahedron, wedge or pyramid");
  // A half-face of the wrong side.
  std::string flipped = "6 1";
  for (std::size_t k = 1; k < 6; ++k) flipped += " " + std::to_string(w.cells[0][k]);
  EXPECT_EQ(error(replace_line(first_cell + "\n", flipped + "\n")),
            "e.ovm:" + std::to_string(cells_line + 2) +
                ": polyhedron 0 is not a hexahedron: its half-faces are not "
                "consistently oriented");
  // The second cube's far face in place of one of the first's.
  std::string wrong = first_cell.substr(0, first_cell.rfind(' ')) + " " + std::to_string(w.cells[1][1]);
  const std::string prefix = "e.ovm:" + std::to_string(cells_line + 2) + ": polyhedron 0 is not a hexahedron: ";
  EXPECT_EQ(error(replace_line(first_cell + "\n", wrong + "\n")).substr(0, prefix.size()), prefix);
  EXPECT_EQ(error(replace_line(first_cell + "\n", "6 0 2 4 6 8 9999\n")),
            "e.ovm:" + std::to_string(cells_line + 2) + ": half-face id 9999 out of range [0, " +
                std::to_string(2 * w.faces.size()) + ") (polyhedron 0)");
  EXPECT_EQ(error("OVM ASCII\nVertices\n0\nEdges\n0\nFaces\n0\nPolyhedra\n0\n"),
            "e.ovm:9: no volume cells (no polyhedra)");
}

}  // namespace
}  // namespace hq
