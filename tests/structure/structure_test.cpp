// Hex structure against closed forms (grids, a grid with a cavity, a size
// jump), an independent count of the valences (a std::map of vertex pairs),
// and the meshes of ../shared/data.
#include "hqview/structure/structure.h"

#include <gtest/gtest.h>

#include <cmath>

#include "hqview/io/mesh_reader.h"
#include "support/fixtures.h"

namespace hq {
namespace {

HexStructure structure_of(const HexMesh& mesh) { return compute_structure(mesh, build_topology(mesh)); }

TEST(Structure, AGridHasTwelveBoundaryCurvesAndEightNodes) {
  for (int n : {1, 2, 3, 5}) {
    const HexStructure s = structure_of(test::grid(n));
    EXPECT_EQ(s.num_edges, 3 * n * (n + 1) * (n + 1)) << n;
    EXPECT_EQ(s.num_singular_edges_interior, 0) << n;
    EXPECT_EQ(s.num_singular_edges_boundary, 12 * n) << n;  // valence 1 along the box's edges
    EXPECT_EQ(s.boundary_by_valence, (std::map<Index, Index>{{1, 12 * n}})) << n;
    EXPECT_EQ(s.num_irregular_edges_boundary, 0) << n;      // 90 degrees: valence 1 expected
    EXPECT_EQ(s.num_nonmanifold_edges, 0) << n;
    EXPECT_EQ(s.nodes.size(), 8u) << n;
    EXPECT_EQ(s.num_curves, 12) << n;
    for (Index length : s.curve_lengths) EXPECT_EQ(length, n) << n;
    EXPECT_EQ(s.num_singular_vertices, 12 * (n - 1) + 8) << n;
    // Equal unit hexes: every gradation is 1 (a single hex has no neighbour).
    if (n > 1) {
      EXPECT_DOUBLE_EQ(s.gradation.max, 1.0) << n;
      EXPECT_EQ(s.num_gradation_above_2, 0) << n;
    } else {
      EXPECT_TRUE(std::isnan(s.cell_gradation[0]));
    }
  }
}

TEST(Structure, ACavityAddsTwelveConcaveBoundaryEdgesOfValenceThree) {
  HexMesh mesh = test::grid(3);
  mesh.hexes.erase(mesh.hexes.begin() + 13);  // the centre hex
  const HexStructure s = structure_of(mesh);
  EXPECT_EQ(s.num_singular_edges_interior, 0);
  EXPECT_EQ(s.boundary_by_valence, (std::map<Index, Index>{{1, 36}, {3, 12}}));
  EXPECT_EQ(s.num_irregular_edges_boundary, 0);  // 270 degrees inside: valence 3 expected
  EXPECT_EQ(s.nodes.size(), 16u);
  EXPECT_EQ(s.num_curves, 24);
}

TEST(Structure, IrregularWhenTheValenceDoesNotFitTheAngle) {
  // A 2x2x1 slab: its top and bottom centre edges are flat (180 degrees:
  // valence 2 expected and found), the box edges right angles (valence 1).
  EXPECT_EQ(structure_of(test::box_grid(2, 2, 1)).num_irregular_edges_boundary, 0);
  // One hex with its top x = 1 edge pushed out by 1 in x: the side face
  // slants, the bottom edge under it opens to 135 degrees (round(1.5) = 2
  // expected, valence 1: irregular), the top edge closes to 45 (1 expected).
  HexMesh wedge = test::unit_cube();
  for (Vec3& p : wedge.points)
    if (p.x > 0.5 && p.z > 0.5) p.x += 1.0;
  const HexStructure w = structure_of(wedge);
  EXPECT_EQ(w.num_irregular_edges_boundary, 1);
  EXPECT_EQ(w.num_singular_edges_boundary, 12);
}

TEST(Structure, GradationIsTheLargestVolumeRatioToAFaceNeighbour) {
  HexMesh mesh = test::box_grid(3, 1, 1);
  // x = 3 -> x = 6: the last hex is 4 times the middle one.
  for (Vec3& p : mesh.points)
    if (p.x > 2.5) p.x = 6.0;
  const HexStructure s = structure_of(mesh);
  ASSERT_EQ(s.cell_gradation.size(), 3u);
  EXPECT_NEAR(s.cell_gradation[0], 1.0, 1e-12);
  EXPECT_NEAR(s.cell_gradation[1], 4.0, 1e-12);
  EXPECT_NEAR(s.cell_gradation[2], 4.0, 1e-12);
  EXPECT_EQ(s.num_gradation_above_2, 2);
  EXPECT_EQ(s.num_gradation_above_4, 0);  // strictly above
}

// The counts from the map of vertex pairs and an independent boundary test.
void expect_map_counts(const HexMesh& mesh, const HexStructure& s, const std::string& what) {
  const std::map<Edge, Index> valence = edge_valences_by_map(mesh);
  const Topology topology = build_topology(mesh);
  std::map<Edge, int> boundary_faces;
  for (Index f : topology.boundary_faces) {
    const Quad& q = topology.faces[static_cast<std::size_t>(f)];
    for (int c = 0; c < 4; ++c) {
      Index a = q[static_cast<std::size_t>(c)], b = q[static_cast<std::size_t>((c + 1) % 4)];
      if (a > b) std::swap(a, b);
      ++boundary_faces[{a, b}];
    }
  }
  Index interior = 0, boundary = 0, nonmanifold = 0;
  for (const auto& [e, v] : valence) {
    const auto it = boundary_faces.find(e);
    const int nf = it == boundary_faces.end() ? 0 : it->second;
    if (nf == 0) interior += v != 4;
    else if (nf == 2) boundary += v != 2;
    else ++nonmanifold;
  }
  EXPECT_EQ(static_cast<Index>(valence.size()), s.num_edges) << what;
  EXPECT_EQ(interior, s.num_singular_edges_interior) << what;
  EXPECT_EQ(boundary, s.num_singular_edges_boundary) << what;
  EXPECT_EQ(nonmanifold, s.num_nonmanifold_edges) << what;
}

TEST(Structure, SharedMeshesMatchTheMapOfVertexPairs) {
  const auto data = test::shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data absent";
  for (const char* name : {"gao2016_sweeping/hand7_1.mesh", "gao2016_sweeping/kitten_1.mesh",
                           "livesu2016_skeleton/armadillo.mesh", "li2012_srf/fandisk.mesh", "dualsheet2019/rockarm.vtk"}) {
    const HexMesh mesh = read_hex_mesh(*data / "meshes" / name).mesh;
    const HexStructure s = structure_of(mesh);
    expect_map_counts(mesh, s, name);
    // Every singular edge is on exactly one curve; the lengths add up.
    Index total = 0;
    for (Index l : s.curve_lengths) total += l;
    EXPECT_EQ(total, static_cast<Index>(s.singular_edges.size())) << name;
    for (const SingularEdge& e : s.singular_edges) EXPECT_NE(e.curve, kNoIndex) << name;
  }
}

}  // namespace
}  // namespace hq
