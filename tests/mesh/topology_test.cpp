#include "hqview/mesh/topology.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "hqview/core/hex_topology.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

TEST(Topology, UnitCube) {
  const Topology topo = build_topology(test::unit_cube());
  EXPECT_EQ(topo.faces.size(), 6u);
  EXPECT_EQ(topo.boundary_faces.size(), 6u);
  EXPECT_EQ(topo.edges.size(), 12u);
  EXPECT_EQ(topo.boundary_vertices.size(), 8u);
  EXPECT_TRUE(topo.unreferenced_vertices.empty());
  EXPECT_TRUE(topo.non_manifold_faces.empty());
}

class GridTopology : public ::testing::TestWithParam<int> {};

// An n x n x n grid: 6n^2 boundary faces, (n+1)^3 vertices, 3n(n+1)^2
// edges, 3n^2(n+1) faces, (n+1)^3 - (n-1)^3 boundary vertices.
TEST_P(GridTopology, CountsMatchClosedForms) {
  const int n = GetParam();
  const HexMesh mesh = test::grid(n);
  const Topology topo = build_topology(mesh);
  const std::size_t m = static_cast<std::size_t>(n + 1);
  const std::size_t nn = static_cast<std::size_t>(n);
  EXPECT_EQ(mesh.points.size(), m * m * m);
  EXPECT_EQ(topo.boundary_faces.size(), 6 * nn * nn);
  EXPECT_EQ(topo.edges.size(), 3 * nn * m * m);
  EXPECT_EQ(topo.faces.size(), 3 * nn * nn * m);
  EXPECT_EQ(topo.boundary_vertices.size(), m * m * m - (nn - 1) * (nn - 1) * (nn - 1));
  EXPECT_EQ(topo.vertex_hex_offsets.back(), static_cast<Index>(8 * nn * nn * nn));
  EXPECT_TRUE(topo.non_manifold_faces.empty());
}

TEST_P(GridTopology, BoundaryFacesPointOutward) {
  const int n = GetParam();
  const HexMesh mesh = test::grid(n);
  const Topology topo = build_topology(mesh);
  const Vec3 centre{n / 2.0, n / 2.0, n / 2.0};
  for (Index f : topo.boundary_faces) {
    const Quad& q = topo.faces[static_cast<std::size_t>(f)];
    const Vec3 a = mesh.points[q[0]], b = mesh.points[q[1]], c = mesh.points[q[2]];
    const Vec3 normal = cross(b - a, c - a);
    EXPECT_GT(dot(normal, a - centre), 0.0) << "face " << f;
  }
}

TEST_P(GridTopology, VertexHexesAreTheIncidentHexesAscending) {
  const HexMesh mesh = test::grid(GetParam());
  const Topology topo = build_topology(mesh);
  for (Index v = 0; v < mesh.num_vertices(); ++v) {
    std::vector<Index> expected;
    for (Index h = 0; h < mesh.num_hexes(); ++h)
      if (std::count(mesh.hexes[h].begin(), mesh.hexes[h].end(), v)) expected.push_back(h);
    const std::vector<Index> got(topo.vertex_hexes.begin() + topo.vertex_hex_offsets[v],
                                 topo.vertex_hexes.begin() + topo.vertex_hex_offsets[v + 1]);
    EXPECT_EQ(got, expected) << "vertex " << v;
  }
}

TEST_P(GridTopology, HexFacesAreConsistent) {
  const HexMesh mesh = test::grid(GetParam());
  const Topology topo = build_topology(mesh);
  for (Index h = 0; h < mesh.num_hexes(); ++h)
    for (int f = 0; f < 6; ++f) {
      const Index face = topo.hex_faces[6 * h + f];
      std::set<Index> a, b(topo.faces[face].begin(), topo.faces[face].end());
      for (int k : kHexFaces[f]) a.insert(mesh.hexes[h][k]);
      EXPECT_EQ(a, b);
      const auto first = topo.face_hexes.begin() + topo.face_hex_offsets[face];
      const auto last = topo.face_hexes.begin() + topo.face_hex_offsets[face + 1];
      EXPECT_NE(std::find(first, last, h), last);
    }
}

INSTANTIATE_TEST_SUITE_P(Sizes, GridTopology, ::testing::Values(1, 2, 3, 5));

TEST(Topology, UnreferencedVerticesAndNonManifoldFaces) {
  HexMesh mesh = test::unit_cube();
  mesh.points.push_back({5, 5, 5});  // vertex 8: used by no hex
  // Two more hexes on the cube's top face (4 5 6 7), one above and one
  // duplicating the cube: the top face is then shared by three hexes.
  for (int i = 0; i < 4; ++i) mesh.points.push_back(mesh.points[4 + i] + Vec3{0, 0, 1});
  mesh.hexes.push_back({4, 5, 6, 7, 9, 10, 11, 12});
  mesh.hexes.push_back({0, 1, 2, 3, 4, 5, 6, 7});
  const Topology topo = build_topology(mesh);
  EXPECT_EQ(topo.unreferenced_vertices, std::vector<Index>{8});
  ASSERT_EQ(topo.non_manifold_faces.size(), 1u);
  const Quad top = topo.faces[topo.non_manifold_faces[0]];
  EXPECT_EQ(std::set<Index>(top.begin(), top.end()), (std::set<Index>{4, 5, 6, 7}));
  EXPECT_EQ(topo.num_face_hexes(topo.non_manifold_faces[0]), 3);
  // The duplicated cube's other faces are shared by two hexes, so only the
  // five free faces of the hex on top are boundary.
  EXPECT_EQ(topo.boundary_faces.size(), 5u);
}

TEST_P(GridTopology, BoundaryEdgesObeyEulerOnTheSphere) {
  // The boundary of an n^3 grid is a sphere: E = V + F - 2, and every
  // boundary edge is a mesh edge with both ends on the boundary.
  const HexMesh mesh = test::grid(GetParam());
  const Topology topo = build_topology(mesh);
  const std::vector<Edge> edges = boundary_edges(topo);
  EXPECT_EQ(edges.size(), topo.boundary_vertices.size() + topo.boundary_faces.size() - 2);
  EXPECT_TRUE(std::is_sorted(edges.begin(), edges.end()));
  for (const Edge& e : edges) {
    EXPECT_LT(e[0], e[1]);
    EXPECT_TRUE(topo.is_boundary_vertex[static_cast<std::size_t>(e[0])] &&
                topo.is_boundary_vertex[static_cast<std::size_t>(e[1])]);
    EXPECT_TRUE(std::binary_search(topo.edges.begin(), topo.edges.end(), e));
  }
}

}  // namespace
}  // namespace hq
