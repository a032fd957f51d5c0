// The cell-block mesh (mesh/mesh.h): blocks visited in CellKind order with
// their kind's table, counts per kind and over all kinds, and a pure-hex mesh
// whose hex ids are the cell ids.

#include "hqview/mesh/mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/surface_topology.h"

namespace hq {
namespace HQ_TEST_UNIT {

Mesh mixed_mesh() {
  Mesh mesh;
  mesh.points.resize(9);
  mesh.hexes = {{0, 1, 2, 3, 4, 5, 6, 7}};
  mesh.tets = {{0, 1, 2, 8}, {1, 2, 3, 8}};
  mesh.wedges = {{0, 1, 2, 4, 5, 6}};
  mesh.pyramids = {{4, 5, 6, 7, 8}, {0, 1, 2, 3, 8}, {0, 3, 2, 1, 8}};
  mesh.triangles = {{0, 1, 2}};
  return mesh;
}

TEST(Mesh, ForEachBlockVisitsEveryKindInBlockOrderWithItsTable) {
  const Mesh mesh = mixed_mesh();
  std::vector<std::string> visited;
  for_each_block(mesh, [&](auto kind, const auto& cells) {
    using Table = CellKindTable<kind()>;
    static_assert(std::tuple_size_v<typename std::decay_t<decltype(cells)>::value_type> == Table::num_corners);
    visited.push_back(std::string(Table::name) + ":" + std::to_string(cells.size()));
  });
  EXPECT_EQ(visited, (std::vector<std::string>{"hex:1", "tet:2", "wedge:1", "pyramid:3", "quad:0", "triangle:1"}));
}

TEST(Mesh, CountsPerKindAndOverall) {
  const Mesh mesh = mixed_mesh();
  EXPECT_EQ(num_cells_of(mesh, CellKind::hex), 1);
  EXPECT_EQ(num_cells_of(mesh, CellKind::tet), 2);
  EXPECT_EQ(num_cells_of(mesh, CellKind::wedge), 1);
  EXPECT_EQ(num_cells_of(mesh, CellKind::pyramid), 3);
  EXPECT_EQ(num_cells_of(mesh, CellKind::quad), 0);
  EXPECT_EQ(num_cells(mesh), 8);
  EXPECT_EQ(mesh.num_hexes(), 1);
  EXPECT_EQ(mesh.num_vertices(), 9);
  EXPECT_EQ(&cell_block<CellKind::pyramid>(mesh), &mesh.pyramids);
}

TEST(Mesh, HexMeshIsTheSameType) {
  HexMesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  mesh.hexes = {{0, 1, 2, 3, 4, 5, 6, 7}};
  const Mesh& same = mesh;
  EXPECT_EQ(num_cells(same), 1);
  EXPECT_EQ(hex_corners(same, 0)[6].x, 1.0);
  for (const auto& source : same.source_index) EXPECT_TRUE(source.empty());  // built in code: none stored
  EXPECT_EQ(cell_source_index(same, CellKind::hex, 0), 1);                   // implicit: the 1-based position
}

// A disk of 40 triangles around one centre (its 80 half-edges from the centre
// in one bucket: ordered by a stable sort, not by insertion), one of them
// reversed, and a quad on the rim: every count by hand.
TEST(SurfaceTopology, FanOfFortyTrianglesWithOneReversedAndAQuad) {
  Mesh mesh;
  constexpr int n = 40;
  mesh.points.push_back({0, 0, 0});
  for (int i = 0; i < n; ++i) {
    const double a = 2 * 3.141592653589793 * i / n;
    mesh.points.push_back({std::cos(a), std::sin(a), 0});
  }
  for (int i = 0; i < n; ++i) {
    const Index b = 1 + i, c = 1 + (i + 1) % n;
    mesh.triangles.push_back(i == 17 ? std::array<Index, 3>{0, c, b} : std::array<Index, 3>{0, b, c});
  }
  mesh.points.push_back({1, 0.2, 0});
  mesh.points.push_back({1.2, 0.4, 0});
  mesh.quads.push_back({2, 1, n + 1, n + 2});  // the rim edge 1-2 run the other way than by triangle 0
  const SurfaceTopology t = build_surface_topology(mesh);
  // Edges: 40 spokes, 40 rim edges, 3 more of the quad.
  ASSERT_EQ(t.edges.size(), 83u);
  EXPECT_TRUE(std::is_sorted(t.edges.begin(), t.edges.end()));
  EXPECT_EQ(std::adjacent_find(t.edges.begin(), t.edges.end()), t.edges.end());
  EXPECT_EQ(t.num_boundary_edges, 39 + 3);
  EXPECT_EQ(t.num_non_manifold_edges, 0);
  EXPECT_EQ(t.num_components, 1);
  EXPECT_EQ(t.num_reversed, 1);
  std::vector<char> reversed(n + 1, 0);
  reversed[1 + 17] = 1;  // faces: the quad (0), then the triangles
  EXPECT_EQ(t.is_reversed, reversed);
  for (std::size_t e = 0; e < t.edges.size(); ++e) {
    const bool is_shared = t.edges[e][0] == 0 || t.edges[e] == std::array<Index, 2>{1, 2};
    EXPECT_EQ(t.edge_num_faces[e], is_shared ? 2 : 1) << t.edges[e][0] << "-" << t.edges[e][1];
  }
}

}  // namespace
}  // namespace hq
