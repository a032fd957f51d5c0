// Quad-mesh structure (structure/quad_structure.h) on meshes built here
// whose irregular vertices, separatrices and patches are derived by hand.

#include "hqview/structure/quad_structure.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "io/temp_dir.h"
#include "support/surface_fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

using Quad = std::array<Index, 4>;

// Points deduplicated by an integer key.
class PointSet {
 public:
  Index add(std::tuple<int, int, int> key, Vec3 p) {
    const auto [it, is_new] = ids_.emplace(key, static_cast<Index>(points.size()));
    if (is_new) points.push_back(p);
    return it->second;
  }
  std::vector<Vec3> points;

 private:
  std::map<std::tuple<int, int, int>, Index> ids_;
};

// An nx x ny grid of unit quads in the plane z = 0, counter-clockwise,
// `rotate` radians about the z axis and each interior point moved by up to
// `jitter` (deterministically).
Mesh grid(int nx, int ny, double rotate = 0, double jitter = 0) {
  Mesh mesh;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const bool interior = i > 0 && j > 0 && i < nx && j < ny;
      const double x = i + (interior ? jitter * std::sin(7.0 * i + 3.0 * j) : 0);
      const double y = j + (interior ? jitter * std::cos(5.0 * i - 2.0 * j) : 0);
      mesh.points.push_back(
          {x * std::cos(rotate) - y * std::sin(rotate), x * std::sin(rotate) + y * std::cos(rotate), 0});
    }
  const auto id = [&](int i, int j) { return static_cast<Index>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) mesh.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return mesh;
}

TEST(QuadStructure, RegularGridHasNoIrregularVertexAndOnePatch) {
  for (const Mesh& mesh : {grid(5, 3), grid(4, 4, 0.7, 0.2), grid(1, 1)}) {
    const QuadStructure s = compute_quad_structure(mesh);
    EXPECT_EQ(s.num_irregular, 0);
    EXPECT_EQ(s.num_separatrices, 0);
    EXPECT_EQ(s.num_traced_edges, 0);
    EXPECT_EQ(s.num_patches, 1);
    EXPECT_EQ(s.num_unclassified, 0);
  }
  const Mesh mesh = grid(5, 3);
  const QuadStructure s = compute_quad_structure(mesh);
  EXPECT_EQ(s.num_edges, 5 * 4 + 6 * 3);
  EXPECT_EQ(s.num_boundary_edges, 16);
  EXPECT_EQ(s.valence[0], 1);  // a corner: one quad, 90 degrees, ideal 1
  EXPECT_EQ(s.ideal_valence[0], 1);
  EXPECT_EQ(s.vertex_kind[0], QuadVertexKind::boundary);
  EXPECT_EQ(s.ideal_valence[1], 2);  // the smooth boundary
  EXPECT_EQ(s.ideal_valence[7], 4);  // interior
  EXPECT_EQ(s.vertex_kind[7], QuadVertexKind::interior);
}

TEST(QuadStructure, ConcaveCornerOfAnLShapeIsRegular) {
  // A 2 x 2 grid without its top right quad: the concave corner (1, 1)
  // has 3 quads over 270 degrees, ideal round(270 / 90) = 3.
  Mesh mesh = grid(2, 2);
  mesh.quads.pop_back();
  const QuadStructure s = compute_quad_structure(mesh);
  EXPECT_EQ(s.ideal_valence[4], 3);
  EXPECT_EQ(s.num_irregular, 0);
  EXPECT_EQ(s.num_patches, 1);
}

TEST(QuadStructure, BoundaryVertexOffItsIdealValence) {
  // Three parallelograms fanned over the upper half plane around the origin
  // (vertex 0) of a straight boundary: 3 quads over 180 degrees, ideal 2.
  Mesh mesh;
  mesh.points.push_back({0, 0, 0});
  for (int k = 0; k <= 3; ++k)
    mesh.points.push_back({std::cos(k * std::numbers::pi / 3), std::sin(k * std::numbers::pi / 3), 0});
  for (Index k = 0; k < 3; ++k) {
    mesh.points.push_back(mesh.points[static_cast<std::size_t>(k + 1)] + mesh.points[static_cast<std::size_t>(k + 2)]);
    mesh.quads.push_back({0, k + 1, static_cast<Index>(5 + k), k + 2});
  }
  const QuadStructure s = compute_quad_structure(mesh);
  EXPECT_EQ(s.vertex_kind[0], QuadVertexKind::boundary);
  EXPECT_EQ(s.valence[0], 3);
  EXPECT_EQ(s.ideal_valence[0], 2);
  EXPECT_TRUE(s.irregular[0]);
  EXPECT_EQ(s.ideal_valence[1], 1);  // 120 degrees: round(1.33)
  // Two interior edges from it, each to the boundary at once; 3 patches.
  EXPECT_EQ(s.num_patches, 3);
}

TEST(QuadStructure, HoleEdgesAreNotBoundary) {
  // A 3 x 3 grid without its centre quad, whose edges a reader marked as
  // holes (a skipped polygon): the 4 vertices around it are unclassified.
  Mesh mesh = grid(3, 3);
  mesh.quads.erase(mesh.quads.begin() + 4);
  const QuadStructure open = compute_quad_structure(mesh);
  EXPECT_EQ(open.num_boundary_edges, 16);
  EXPECT_EQ(open.num_irregular, 0);  // 3 quads over 270 degrees: ideal 3
  QuadStructureOptions options;
  options.hole_edges = {{5, 6}, {5, 9}, {6, 10}, {9, 10}};
  const QuadStructure holed = compute_quad_structure(mesh, options);
  EXPECT_EQ(holed.num_boundary_edges, 12);
  EXPECT_EQ(holed.num_unclassified, 4);
  for (const Index v : {5, 6, 9, 10})
    EXPECT_EQ(holed.vertex_kind[static_cast<std::size_t>(v)], QuadVertexKind::unclassified);
}

// The cube [-1, 1]^3's faces, each an n x n grid, projected to the unit
// sphere: 8 vertices of valence 3 (the cube's corners), 12 separatrices
// along the cube's edges (n edges each, from corner to corner), 6 patches.
Mesh cube_sphere(int n) { return test::quad_cube_sphere(n); }

TEST(QuadStructure, CubeSphere) {
  for (const int n : {1, 2, 5}) {
    const Mesh mesh = cube_sphere(n);
    ASSERT_EQ(mesh.points.size(), static_cast<std::size_t>(6 * n * n + 2));  // Euler: V - E + F = 2
    const QuadStructure s = compute_quad_structure(mesh);
    EXPECT_EQ(s.num_boundary_edges, 0);
    EXPECT_EQ(s.num_irregular, 8) << n;
    EXPECT_EQ(s.num_irregular_interior, 8);
    EXPECT_EQ(s.interior_by_valence, (std::map<Index, Index>{{3, 8}}));
    for (const Index v : s.irregular_vertices) {
      const Vec3 p = mesh.points[static_cast<std::size_t>(v)] * std::sqrt(3.0);
      EXPECT_NEAR(std::abs(p.x) + std::abs(p.y) + std::abs(p.z), 3.0, 1e-12);  // a cube corner
    }
    EXPECT_EQ(s.num_separatrices, 12);
    EXPECT_EQ(s.num_traced_edges, 12 * n);
    for (std::size_t k = 0; k < s.separatrix_end.size(); ++k) {
      EXPECT_EQ(s.separatrix_end[k], SeparatrixEnd::irregular_vertex);
      EXPECT_EQ(s.separatrix_offsets[k + 1] - s.separatrix_offsets[k], n + 1);
    }
    EXPECT_EQ(s.num_patches, 6);
    // Each patch is one cube face: n * n quads.
    std::map<Index, int> sizes;
    for (const Index p : s.quad_patch) ++sizes[p];
    for (const auto& [patch, size] : sizes) EXPECT_EQ(size, n * n);
    EXPECT_FALSE(s.is_capped);
  }
}

TEST(QuadStructure, WorkCap) {
  QuadStructureOptions options;
  options.max_traced_edges = 7;
  const QuadStructure s = compute_quad_structure(cube_sphere(3), options);
  EXPECT_TRUE(s.is_capped);
  EXPECT_EQ(s.num_traced_edges, 7);
  EXPECT_EQ(s.separatrix_end.back(), SeparatrixEnd::cap);
  EXPECT_EQ(s.num_separatrices, 3);  // 3 + 3 + 1 edges
}

// A twisted torus: an m x n grid of quads whose columns wrap (i + m = i)
// and whose rows wrap with a shift, (i, j + n) = (i + shift, j), so with
// gcd(m, shift) = 1 the lines of constant i form one helix through all m n
// vertices, winding n / ... around the torus before it closes. Quads (0, 0)
// and (1, 0) are re-split along the other diagonal of their hexagon
// h0 = (0,0), h1 = (1,0), h2 = (2,0), h3 = (2,1), h4 = (1,1), h5 = (0,1):
// the edge h1-h4 is replaced by h0-h3, so h1 and h4 get valence 3 and h0
// and h3 valence 5; every other vertex keeps its 4 quads and its straight
// lines. By hand:
//   - the helix, cut open at the missing edge h1-h4, is a path from h4 up
//     to h1 through h0 and h3: 3 separatrices, all its m n - 1 edges; each
//     winds around the torus, never meeting an irregular vertex for many
//     steps;
//   - the circles j = 0 (through h0, h1) and j = 1 (through h4, h3): two
//     separatrices each (of 1 and m - 1 edges), m edges each;
//   - the diagonal h0-h3: one separatrix of one edge;
//   so 8 separatrices and 2 m + m n traced edges. Every vertical edge and
//   both circles are cut: each column of quads between j = 1 and j = n is
//   one patch (m), each quad of row 0 another (m - 2 regular and the two
//   re-split ones): 2 m patches.
Mesh twisted_torus(int m, int n, int shift) {
  Mesh mesh;
  const auto normal = [&](int i, int j) {
    while (j >= n) j -= n, i += shift;
    while (j < 0) j += n, i -= shift;
    return std::pair{((i % m) + m) % m, j};
  };
  const auto id = [&](int i, int j) {
    const auto [a, b] = normal(i, j);
    return static_cast<Index>(b * m + a);
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i) {
      const double u = 2 * std::numbers::pi * (i + double(shift) * j / n) / m, v = 2 * std::numbers::pi * j / n;
      mesh.points.push_back({(3 + std::cos(v)) * std::cos(u), (3 + std::cos(v)) * std::sin(u), std::sin(v)});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i) {
      if (j == 0 && i < 2) continue;
      mesh.quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  const Index h0 = id(0, 0), h1 = id(1, 0), h2 = id(2, 0), h3 = id(2, 1), h4 = id(1, 1), h5 = id(0, 1);
  mesh.quads.push_back({h0, h1, h2, h3});
  mesh.quads.push_back({h3, h4, h5, h0});
  return mesh;
}

TEST(QuadStructure, TwistedTorus) {
  for (const auto& [m, n, shift] : {std::tuple{7, 5, 2}, std::tuple{5, 4, 3}, std::tuple{9, 6, 4}}) {
    const Mesh mesh = twisted_torus(m, n, shift);
    const QuadStructure s = compute_quad_structure(mesh);
    EXPECT_EQ(s.num_boundary_edges, 0);
    EXPECT_EQ(s.irregular_vertices, (std::vector<Index>{0, 1, static_cast<Index>(m + 1), static_cast<Index>(m + 2)}));
    EXPECT_EQ(s.interior_by_valence, (std::map<Index, Index>{{3, 2}, {5, 2}}));
    EXPECT_EQ(s.valence[0], 5);
    EXPECT_EQ(s.valence[1], 3);
    EXPECT_EQ(s.num_separatrices, 8) << m << " " << n;
    EXPECT_EQ(s.num_traced_edges, 2 * m + m * n);
    EXPECT_EQ(s.num_patches, 2 * m);
    std::int64_t longest = 0;
    for (std::size_t k = 0; k < s.separatrix_end.size(); ++k) {
      EXPECT_EQ(s.separatrix_end[k], SeparatrixEnd::irregular_vertex);
      longest = std::max(longest, s.separatrix_offsets[k + 1] - s.separatrix_offsets[k] - 1);
    }
    EXPECT_GE(longest, (m * n - 1 + 2) / 3);  // one of the helix's 3 pieces winds around the torus
    EXPECT_GT(longest, n);
  }
}

// A planar mesh with one vertex of valence 3 and one of valence 5: an
// equilateral triangle split into 3 quads around its centre c3 and a
// regular pentagon split into 5 quads around its centre c5, sharing the
// side AB (its midpoint M then has 4 quads), every quad then split in 2 x 2.
// Boundary corners: the triangle's 60 and the pentagon's 108 degrees (1
// quad, ideal 1), A and B 168 degrees (2 quads, ideal 2): all regular. By
// hand: c3 -> M -> c5 is one separatrix (4 edges); c3's two others and c5's
// four others reach the boundary (2 edges each): 7 separatrices, 16 edges.
// The original quads' centre edges are cut; the edges M-A and M-B are not:
// the triangle's and the pentagon's quads at A join (and at B), so 8 - 2 = 6
// patches.
Mesh triangle_and_pentagon() {
  const auto polygon = [](int sides, double flip) {
    // Regular polygon with side (0,0)-(1,0), on the side y * flip > 0, counter-clockwise.
    std::vector<Vec3> corners{{0, 0, 0}, {1, 0, 0}};
    double heading = 0;
    for (int k = 2; k < sides; ++k) {
      heading += flip * 2 * std::numbers::pi / sides;
      corners.push_back(corners.back() + Vec3{std::cos(heading), std::sin(heading), 0});
    }
    if (flip < 0) std::reverse(corners.begin(), corners.end());
    return corners;
  };
  PointSet set;
  const auto key = [](const Vec3& p) {
    return std::tuple{static_cast<int>(std::lround(p.x * 1e6)), static_cast<int>(std::lround(p.y * 1e6)), 0};
  };
  const auto add = [&](const Vec3& p) { return set.add(key(p), p); };
  Mesh mesh;
  for (const auto& [sides, flip] : {std::pair{5, 1.0}, std::pair{3, -1.0}}) {
    const std::vector<Vec3> c = polygon(sides, flip);
    Vec3 centre{0, 0, 0};
    for (const Vec3& p : c) centre = centre + p * (1.0 / sides);
    for (int k = 0; k < sides; ++k) {
      // The quad (centre, mid k-1, corner k, mid k), split in 2 x 2 at its edge midpoints and centroid.
      const Vec3 a = centre,
                 b = (c[static_cast<std::size_t>((k + sides - 1) % sides)] + c[static_cast<std::size_t>(k)]) * 0.5,
                 p = c[static_cast<std::size_t>(k)],
                 d = (c[static_cast<std::size_t>(k)] + c[static_cast<std::size_t>((k + 1) % sides)]) * 0.5;
      const Vec3 ab = (a + b) * 0.5, bp = (b + p) * 0.5, pd = (p + d) * 0.5, da = (d + a) * 0.5,
                 o = (a + b + p + d) * 0.25;
      for (const std::array<Vec3, 4>& q :
           {std::array{a, ab, o, da}, std::array{ab, b, bp, o}, std::array{o, bp, p, pd}, std::array{da, o, pd, d}})
        mesh.quads.push_back({add(q[0]), add(q[1]), add(q[2]), add(q[3])});
    }
  }
  mesh.points = set.points;
  return mesh;
}

TEST(QuadStructure, PlanarValenceFiveAndThree) {
  const Mesh mesh = triangle_and_pentagon();
  ASSERT_EQ(mesh.quads.size(), 32u);
  // Every quad counter-clockwise (a positive signed area), as built.
  for (const Quad& q : mesh.quads) {
    double area = 0;
    for (int k = 0; k < 4; ++k) {
      const Vec3& p = mesh.points[static_cast<std::size_t>(q[k])];
      const Vec3& r = mesh.points[static_cast<std::size_t>(q[(k + 1) % 4])];
      area += p.x * r.y - r.x * p.y;
    }
    ASSERT_GT(area, 0);
  }
  const QuadStructure s = compute_quad_structure(mesh);
  EXPECT_EQ(s.num_irregular, 2);
  EXPECT_EQ(s.num_irregular_boundary, 0);
  EXPECT_EQ(s.interior_by_valence, (std::map<Index, Index>{{3, 1}, {5, 1}}));
  EXPECT_EQ(s.num_separatrices, 7);
  EXPECT_EQ(s.num_traced_edges, 16);
  EXPECT_EQ(s.num_patches, 6);
  int to_irregular = 0, to_boundary = 0;
  for (const SeparatrixEnd end : s.separatrix_end) {
    to_irregular += end == SeparatrixEnd::irregular_vertex;
    to_boundary += end == SeparatrixEnd::boundary;
  }
  EXPECT_EQ(to_irregular, 1);
  EXPECT_EQ(to_boundary, 6);
  // Mirrored, the same structure.
  Mesh mirrored = mesh;
  for (Vec3& p : mirrored.points) p.x = -p.x;
  const QuadStructure m = compute_quad_structure(mirrored);
  EXPECT_EQ(m.num_separatrices, 7);
  EXPECT_EQ(m.num_patches, 6);
  EXPECT_EQ(m.irregular_vertices, s.irregular_vertices);
}

TEST(QuadStructure, TrianglesAndNonManifoldEdgesLeaveVerticesUnclassified) {
  Mesh mesh = grid(2, 1);
  mesh.points.push_back({1, -1, 0});
  mesh.triangles.push_back({0, 6, 1});  // below the first quad
  mesh.points.push_back({1, 0, 1});
  mesh.points.push_back({1, 1, 1});
  mesh.quads.push_back({1, 4, 8, 7});  // a third quad on the edge 1-4
  const QuadStructure s = compute_quad_structure(mesh);
  EXPECT_EQ(s.num_nonmanifold_edges, 1);
  for (const Index v : {0, 1, 4}) EXPECT_EQ(s.vertex_kind[static_cast<std::size_t>(v)], QuadVertexKind::unclassified);
  EXPECT_EQ(s.num_irregular, 0);
}

// A real quad mesh made by Debian's Gmsh (Mesh.Algorithm 6 and Recombine
// Surface, built-in kernel) on a 2 x 1 rectangle with a rectangular hole,
// read from its MEDIT file by a parse of its own. Properties:
//   - discrete Gauss-Bonnet: sum over interior vertices of (4 - valence)
//     plus over boundary vertices of (2 - valence) is 4 chi (an annulus: 0);
//   - the square's 4 convex corners have ideal valence 1, the hole's 4
//     concave ones 3, every other boundary vertex 2;
//   - every separatrix is a straight line: consecutive vertices share a quad
//     edge, each vertex inside it is a regular interior vertex where the
//     edges in and out lie on no common quad, and it ends at an irregular or
//     a boundary vertex; no edge is in two separatrices;
//   - quads across an untraced interior edge are in one patch, and each
//     patch is bounded by traced and boundary edges only (so the patch
//     count is the number of components).
std::vector<std::string> words_of(const std::string& text) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    std::size_t j = i;
    while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j]))) ++j;
    if (j > i) words.push_back(text.substr(i, j - i));
    i = j;
  }
  return words;
}

TEST(QuadStructure, GmshRecombinedMeshWithAHole) {
  test::TempDir dir("quad_structure");
  const std::string geo = R"(lc = 0.12;
Point(1)={0,0,0,lc}; Point(2)={2,0,0,lc}; Point(3)={2,1,0,lc}; Point(4)={0,1,0,lc};
Point(5)={0.5,0.3,0,lc}; Point(6)={0.8,0.3,0,lc}; Point(7)={0.8,0.7,0,lc}; Point(8)={0.5,0.7,0,lc};
Line(1)={1,2}; Line(2)={2,3}; Line(3)={3,4}; Line(4)={4,1};
Line(5)={5,6}; Line(6)={6,7}; Line(7)={7,8}; Line(8)={8,5};
Curve Loop(1)={1,2,3,4}; Curve Loop(2)={5,6,7,8}; Plane Surface(1)={1,2};
Mesh.Algorithm = 6; Recombine Surface{1};
)";
  const auto geo_path = dir.write("m.geo", geo);
  const std::string command = std::string(HQ_GMSH) + " -2 -nt 1 " + geo_path.string() + " -o " +
                              (dir.path() / "m.mesh").string() + " > " + (dir.path() / "log").string() + " 2>&1";
  if (std::system(command.c_str()) != 0) GTEST_SKIP() << "gmsh not available or failed: " << command;
  std::ifstream in(dir.path() / "m.mesh");
  const std::vector<std::string> w = words_of(std::string(std::istreambuf_iterator<char>(in), {}));
  Mesh mesh;
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (w[i] == "Vertices") {
      const int n = std::stoi(w[++i]);
      for (int k = 0; k < n; ++k, i += 4)
        mesh.points.push_back({std::stod(w[i + 1]), std::stod(w[i + 2]), std::stod(w[i + 3])});
    } else if (w[i] == "Quadrilaterals") {
      const int n = std::stoi(w[++i]);
      for (int k = 0; k < n; ++k, i += 5)
        mesh.quads.push_back(
            {std::stoi(w[i + 1]) - 1, std::stoi(w[i + 2]) - 1, std::stoi(w[i + 3]) - 1, std::stoi(w[i + 4]) - 1});
    }
  }
  ASSERT_GT(mesh.quads.size(), 100u);
  const QuadStructure s = compute_quad_structure(mesh);
  EXPECT_EQ(s.num_unclassified, 0);
  EXPECT_EQ(s.num_nonmanifold_edges, 0);
  EXPECT_GT(s.num_irregular, 0);  // a recombined mesh is not a grid
  int gauss_bonnet = 0, convex = 0, concave = 0;
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    if (s.vertex_kind[v] == QuadVertexKind::interior) gauss_bonnet += 4 - s.valence[v];
    if (s.vertex_kind[v] != QuadVertexKind::boundary) continue;
    gauss_bonnet += 2 - s.valence[v];
    const Vec3& p = mesh.points[v];
    const bool outer_corner = (p.x == 0 || p.x == 2) && (p.y == 0 || p.y == 1);
    const bool hole_corner = (p.x == 0.5 || p.x == 0.8) && (p.y == 0.3 || p.y == 0.7);
    convex += outer_corner;
    concave += hole_corner;
    EXPECT_EQ(s.ideal_valence[v], outer_corner ? 1 : hole_corner ? 3 : 2) << p.x << " " << p.y;
  }
  EXPECT_EQ(gauss_bonnet, 0);
  EXPECT_EQ(convex, 4);
  EXPECT_EQ(concave, 4);
  // Edges of the quads, and which quads hold them.
  std::map<std::pair<Index, Index>, std::vector<Index>> edge_quads;
  for (std::size_t q = 0; q < mesh.quads.size(); ++q)
    for (int k = 0; k < 4; ++k) {
      const Index a = mesh.quads[q][k], b = mesh.quads[q][(k + 1) % 4];
      edge_quads[{std::min(a, b), std::max(a, b)}].push_back(static_cast<Index>(q));
    }
  const auto key = [](Index a, Index b) { return std::pair{std::min(a, b), std::max(a, b)}; };
  std::map<std::pair<Index, Index>, int> traced;
  ASSERT_GT(s.num_separatrices, 0);
  for (Index k = 0; k < s.num_separatrices; ++k) {
    const auto first = static_cast<std::size_t>(s.separatrix_offsets[static_cast<std::size_t>(k)]);
    const auto last = static_cast<std::size_t>(s.separatrix_offsets[static_cast<std::size_t>(k) + 1]);
    ASSERT_GE(last - first, 2u);
    EXPECT_TRUE(s.irregular[static_cast<std::size_t>(s.separatrix_vertices[first])]);
    for (std::size_t i = first; i + 1 < last; ++i) {
      const auto e = key(s.separatrix_vertices[i], s.separatrix_vertices[i + 1]);
      ASSERT_TRUE(edge_quads.count(e)) << "not an edge";
      ++traced[e];
      if (i == first) continue;
      const auto v = static_cast<std::size_t>(s.separatrix_vertices[i]);
      EXPECT_EQ(s.vertex_kind[v], QuadVertexKind::interior);
      EXPECT_EQ(s.valence[v], 4);
      EXPECT_FALSE(s.irregular[v]);
      for (const Index q : edge_quads[key(s.separatrix_vertices[i - 1], s.separatrix_vertices[i])])
        for (const Index r : edge_quads[e]) EXPECT_NE(q, r) << "a turn, not a straight line";
    }
    const auto end = static_cast<std::size_t>(s.separatrix_vertices[last - 1]);
    EXPECT_TRUE(s.irregular[end] || s.vertex_kind[end] == QuadVertexKind::boundary);
  }
  EXPECT_EQ(static_cast<std::int64_t>(traced.size()), s.num_traced_edges);
  for (const auto& [edge, count] : traced) EXPECT_EQ(count, 1);
  for (const auto& [edge, quads] : edge_quads) {
    if (quads.size() != 2) continue;
    const bool same =
        s.quad_patch[static_cast<std::size_t>(quads[0])] == s.quad_patch[static_cast<std::size_t>(quads[1])];
    if (!traced.count(edge)) {
      EXPECT_TRUE(same);
    }
  }
  EXPECT_GT(s.num_patches, 1);
  RecordProperty("quads", static_cast<int>(mesh.quads.size()));
  RecordProperty("irregular", s.num_irregular);
  RecordProperty("separatrices", s.num_separatrices);
  RecordProperty("patches", s.num_patches);
}

}  // namespace
}  // namespace hq
