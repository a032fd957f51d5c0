// The cell-block mesh (mesh/mesh.h): blocks visited in CellKind order with
// their kind's table, counts per kind and over all kinds, and a pure-hex mesh
// whose hex ids are the cell ids.

#include "hqview/mesh/mesh.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hqview/mesh/hex_mesh.h"

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

}  // namespace
}  // namespace hq
