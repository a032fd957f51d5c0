// Hex structure against closed forms (grids, a grid with a cavity, a size
// jump), an independent count of the valences (a std::map of vertex pairs),
// and the meshes of ../shared/data.
#include "hqview/structure/structure.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>

#include "hqview/quality/cell_volume.h"
#include "hqview/quality/hex_metrics.h"

#include "hqview/io/mesh_reader.h"
#include "hqview/mesh/cell_faces.h"
#include "support/fixtures.h"
#include "support/mixed_grid.h"

namespace hq {
namespace HQ_TEST_UNIT {

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

// A graded bar of 3 hexes of unit cross-section and widths 1, 8 and 27
// (x = 0, 1, 9, 36): volumes 1, 8, 27, equivalent edge lengths (cube roots)
// 1, 2, 3, so by hand the gradations are 2, max(2, 3/2) = 2 and 3/2 (a
// volume ratio would say 8, 8 and 27/8).
TEST(Structure, GradationIsTheLargestEdgeLengthRatioToAFaceNeighbour) {
  HexMesh mesh = test::box_grid(3, 1, 1);
  for (Vec3& p : mesh.points) p.x = p.x < 0.5 ? 0.0 : p.x < 1.5 ? 1.0 : p.x < 2.5 ? 9.0 : 36.0;
  const HexStructure s = structure_of(mesh);
  ASSERT_EQ(s.cell_gradation.size(), 3u);
  EXPECT_NEAR(s.cell_gradation[0], 2.0, 1e-12);
  EXPECT_NEAR(s.cell_gradation[1], 2.0, 1e-12);
  EXPECT_NEAR(s.cell_gradation[2], 1.5, 1e-12);
  EXPECT_EQ(s.num_gradation_above_2, 0);  // strictly above
  EXPECT_EQ(s.num_gradation_above_4, 0);
  EXPECT_NEAR(s.gradation.max, 2.0, 1e-12);
  // Its last hex 4 times as wide (x = 36 -> 117, width 108): lengths 1, 2,
  // cbrt(108) = 4.762, gradations 2, cbrt(108) / 2 = 2.381 twice.
  for (Vec3& p : mesh.points)
    if (p.x > 30.0) p.x = 117.0;
  const HexStructure t = structure_of(mesh);
  EXPECT_NEAR(t.cell_gradation[1], std::cbrt(108.0) / 2.0, 1e-12);
  EXPECT_NEAR(t.cell_gradation[2], std::cbrt(108.0) / 2.0, 1e-12);
  EXPECT_EQ(t.num_gradation_above_2, 2);
}

// ---- Hybrid meshes: size gradation across kinds, nodes at the interface ----

// The point's id in `mesh`, added when new.
Index point_id(Mesh& mesh, const Vec3& p) {
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    if (norm(mesh.points[i] - p) < 1e-12) return static_cast<Index>(i);
  mesh.points.push_back(p);
  return static_cast<Index>(mesh.points.size() - 1);
}

// Appends a cell of kind K over the given corner positions, reordered
// (two corners of its first face swapped, and of its second for a wedge)
// when Verdict's volume comes out negative.
template <CellKind K>
void add_cell(Mesh& mesh, std::array<Vec3, CellKindTable<K>::num_corners> p) {
  if (cell_volume<K>(p) < 0) {
    std::swap(p[1], p[2]);
    if constexpr (K == CellKind::wedge) std::swap(p[4], p[5]);
  }
  std::array<Index, CellKindTable<K>::num_corners> ids;
  for (std::size_t i = 0; i < p.size(); ++i) ids[i] = point_id(mesh, p[i]);
  cell_block<K>(mesh).push_back(ids);
}

// The unit cube [0,1]^3 (cell 0); on its top the regular pyramid of unit
// edges (cell 3: apex at height 1/sqrt 2), on the pyramid's y = 0 side the
// regular tet of unit edges with its apex pushed out to `tet_scale` times
// its height (cell 1); on the cube's x = 1 side the right prism over an
// equilateral triangle of unit edges (cell 2). Sizes V / V1 (cell_volume.h):
// cube 1, pyramid 1, wedge 1, tet tet_scale.
Mesh kinds_tower(double tet_scale) {
  Mesh mesh;
  const std::array<Vec3, 8> c = {Vec3{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  add_cell<CellKind::hex>(mesh, c);
  const Vec3 apex{0.5, 0.5, 1 + 1 / std::sqrt(2.0)};
  // The pyramid's side triangle (4, 5, apex) is equilateral; the regular tet
  // on it has its fourth corner at the centroid plus sqrt(2/3) along the
  // outward normal.
  const Vec3 a = c[4], b = c[5];
  const Vec3 centroid = (1.0 / 3.0) * (a + b + apex);
  Vec3 normal = normalized(cross(b - a, apex - a));
  if (dot(normal, Vec3{0, -1, 0}) < 0) normal = -1.0 * normal;
  add_cell<CellKind::tet>(mesh, {a, b, apex, centroid + tet_scale * std::sqrt(2.0 / 3.0) * normal});
  // The prism: the cube's x = 1 face is its quad face (1, 2, 6, 5): the
  // triangles (1, 2, q) and (5, 6, q') with q at x = 1 + sqrt(3)/2.
  const double ridge = 1 + std::sqrt(3.0) / 2;
  add_cell<CellKind::wedge>(mesh, {c[1], c[2], Vec3{ridge, 0.5, 0}, c[5], c[6], Vec3{ridge, 0.5, 1}});
  add_cell<CellKind::pyramid>(mesh, {c[4], c[5], c[6], c[7], apex});
  return mesh;
}

TEST(HybridGradation, RegularCellsOfEachKindGradeOneAndATetTwiceAsLargeTwo) {
  const Mesh regular = kinds_tower(1.0);
  ASSERT_EQ(regular.tets.size() + regular.wedges.size() + regular.pyramids.size(), 3u);
  const HexStructure r = structure_of(regular);
  ASSERT_EQ(r.cell_gradation.size(), 4u);  // hex, tet, wedge, pyramid (cell ids)
  for (std::size_t c = 0; c < 4; ++c) EXPECT_NEAR(r.cell_gradation[c], 1.0, 1e-12) << c;
  // The tet twice as high (twice the volume): equivalent edge cbrt(2)
  // against the pyramid's 1.
  const HexStructure t = structure_of(kinds_tower(2.0));
  EXPECT_NEAR(t.cell_gradation[0], 1.0, 1e-12);  // the cube: pyramid 1, wedge 1
  EXPECT_NEAR(t.cell_gradation[1], std::cbrt(2.0), 1e-12);  // the tet
  EXPECT_NEAR(t.cell_gradation[2], 1.0, 1e-12);  // the wedge: only the cube
  EXPECT_NEAR(t.cell_gradation[3], std::cbrt(2.0), 1e-12);  // the pyramid: the tet
  EXPECT_EQ(t.gradation.count, 4);
  EXPECT_EQ(t.num_gradation_above_2, 0);  // strictly above
}

// The unit cube beside the 6 Kuhn tets of [1,2] x [0,1]^2 (the path x, y, z
// in every order): the shared x = 1 face is the cube's quad against two
// tet triangles (non-conforming). A Kuhn tet has volume 1/6, so
// (1/6) / (sqrt 2 / 12) = sqrt 2 regular unit tets, equivalent edge
// cbrt(sqrt 2) = 2^(1/6): the cube and the two tets on the interface grade
// 2^(1/6), the other four tets (only tet neighbours) 1.
Mesh cube_and_kuhn_tets() {
  Mesh mesh;
  const auto corner = [](double x0, int i) {
    static constexpr std::array<std::array<int, 3>, 8> k = {
        {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
    return Vec3{x0 + k[static_cast<std::size_t>(i)][0], double(k[static_cast<std::size_t>(i)][1]),
                double(k[static_cast<std::size_t>(i)][2])};
  };
  std::array<Vec3, 8> cube;
  for (int i = 0; i < 8; ++i) cube[static_cast<std::size_t>(i)] = corner(0, i);
  add_cell<CellKind::hex>(mesh, cube);
  for (const auto& [a, b] : std::array<std::array<int, 2>, 6>{{{1, 2}, {1, 5}, {3, 2}, {3, 7}, {4, 5}, {4, 7}}})
    add_cell<CellKind::tet>(mesh, {corner(1, 0), corner(1, a), corner(1, b), corner(1, 6)});
  return mesh;
}

TEST(HybridGradation, ANonConformingInterfaceComparesTheQuadsCellWithItsTriangles) {
  const Mesh mesh = cube_and_kuhn_tets();
  const Topology topology = build_topology(mesh);
  ASSERT_EQ(topology.non_conforming_faces.size(), 1u);
  const HexStructure s = compute_structure(mesh, topology);
  ASSERT_EQ(s.cell_gradation.size(), 7u);
  EXPECT_NEAR(s.cell_gradation[0], std::pow(2.0, 1.0 / 6.0), 1e-12);
  int at_interface = 0;
  for (Index t : topology.non_conforming_faces[0].triangle_cells) {
    EXPECT_NEAR(s.cell_gradation[static_cast<std::size_t>(t)], std::pow(2.0, 1.0 / 6.0), 1e-12) << t;
    ++at_interface;
  }
  EXPECT_EQ(at_interface, 2);
  int ones = 0;
  for (std::size_t c = 1; c < 7; ++c) ones += std::abs(s.cell_gradation[c] - 1.0) < 1e-12;
  EXPECT_EQ(ones, 4);
}

// The gradation read from the topology's matched faces (what the pipeline
// runs) equals the gradation from the faces matched here (a topology without
// that table), bit for bit, on a jittered grid of every kind with conforming
// and non-conforming interfaces and a non-manifold face.
TEST(HybridGradation, TheTopologysMatchedFacesGiveTheSameGradationAsItsOwnMatching) {
  const Mesh mesh = test::mixed_grid(4, 0.2);
  const Topology topology = build_topology(mesh);
  ASSERT_FALSE(topology.cell_face_offsets.empty());
  Topology without_table = topology;
  without_table.cell_face_offsets.clear();
  without_table.cell_face_uses.clear();
  const HexStructure a = compute_structure(mesh, topology), b = compute_structure(mesh, without_table);
  ASSERT_EQ(a.cell_gradation.size(), static_cast<std::size_t>(num_volume_cells(mesh)));
  ASSERT_EQ(a.cell_gradation.size(), b.cell_gradation.size());
  EXPECT_EQ(std::memcmp(a.cell_gradation.data(), b.cell_gradation.data(), a.cell_gradation.size() * sizeof(double)), 0);
  EXPECT_EQ(a.num_gradation_above_2, b.num_gradation_above_2);
  // Jittered: many cells differ from a face neighbour (the grid's Kuhn tets
  // and pyramids are not all positive: those compare with no one).
  int graded = 0;
  for (double g : a.cell_gradation) {
    if (!std::isnan(g)) {
      EXPECT_GE(g, 1.0);
    }
    graded += g > 1.0;
  }
  EXPECT_GT(graded, static_cast<int>(a.cell_gradation.size()) / 3);
}

// The same mesh's hex part: its 4 edges on the x = 1 face touch tets; the
// other 8 are boundary edges of valence 1. The corners at x = 0 join 3
// singular edges (nodes); those at x = 1 one (where the hex part ends:
// interface ends, not nodes). Curves: the 4 edges of x = 0 and the 4 along x.
TEST(HybridStructure, CurvesCutAtTheNonHexCellsEndWithoutANode) {
  const HexStructure s = structure_of(cube_and_kuhn_tets());
  EXPECT_EQ(s.num_edges_touching_non_hex, 4);
  EXPECT_EQ(s.num_singular_edges_boundary, 8);
  EXPECT_EQ(s.nodes.size(), 4u);
  for (Index v : s.nodes) EXPECT_EQ(cube_and_kuhn_tets().points[static_cast<std::size_t>(v)].x, 0.0);
  EXPECT_EQ(s.num_interface_ends, 4);
  EXPECT_EQ(s.num_curves, 8);
  for (Index length : s.curve_lengths) EXPECT_EQ(length, 1);
  // A pure-hex mesh has no interface end (a unit cube: 8 nodes).
  EXPECT_EQ(structure_of(test::unit_cube()).num_interface_ends, 0);
  EXPECT_EQ(structure_of(test::unit_cube()).nodes.size(), 8u);
}

// A hex ball of 7 blocks: an n^3 grid of the cube [-1, 1]^3 and, on each of
// its 6 faces, an n x n x m block from the face out to the sphere of radius
// 3 (points on a seam are merged by their rounded coordinates).
HexMesh seven_block_ball(int n, int m) {
  HexMesh mesh;
  std::map<std::array<long long, 3>, Index> ids;
  auto vertex = [&](Vec3 p) {
    const std::array<long long, 3> key{std::llround(p.x * 1e9), std::llround(p.y * 1e9), std::llround(p.z * 1e9)};
    const auto [it, fresh] = ids.emplace(key, static_cast<Index>(mesh.points.size()));
    if (fresh) mesh.points.push_back(p);
    return it->second;
  };
  auto add_block = [&](auto point) {  // point(i, j, k) on an n x n x m lattice
    for (int k = 0; k < m; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          Hex h;
          const int c[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
          for (int v = 0; v < 8; ++v) h[static_cast<std::size_t>(v)] = vertex(point(i + c[v][0], j + c[v][1], k + c[v][2]));
          mesh.hexes.push_back(h);
        }
  };
  const double step = 2.0 / n;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        Hex h;
        const int c[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
        for (int v = 0; v < 8; ++v)
          h[static_cast<std::size_t>(v)] = vertex({-1 + step * (i + c[v][0]), -1 + step * (j + c[v][1]), -1 + step * (k + c[v][2])});
        mesh.hexes.push_back(h);
      }
  // Face blocks: axis a, side s; (u, v) across the face, t outwards.
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-1, 1})
      add_block([&, axis, side](int i, int j, int k) {
        const double u = -1 + step * i, v = -1 + step * j, t = static_cast<double>(k) / m;
        double q[3];
        q[axis] = side;
        q[(axis + 1) % 3] = u;
        q[(axis + 2) % 3] = v;
        const Vec3 face{q[0], q[1], q[2]};
        const Vec3 out = 3.0 * normalized(face);
        return (1 - t) * face + t * out;
      });
  // Orientation: the -side blocks come out mirrored; flip them so every
  // hex has a positive volume (structure does not care, gradation does).
  for (Hex& h : mesh.hexes) {
    HexCorners p;
    for (int v = 0; v < 8; ++v) p[static_cast<std::size_t>(v)] = mesh.points[static_cast<std::size_t>(h[static_cast<std::size_t>(v)])];
    if (hex_volume(p) < 0) {
      std::swap(h[1], h[3]);
      std::swap(h[5], h[7]);
    }
  }
  return mesh;
}

TEST(Structure, ABallOfSevenBlocksHasTheSingularEdgesOfItsConstruction) {
  // n >= 3: with 2 x 2 quads a face the sphere's seams fold by more than 45
  // degrees, and valence 2 would rightly be irregular there.
  for (auto [n, m] : {std::pair{3, 2}, std::pair{4, 3}, std::pair{5, 1}}) {
    const HexMesh mesh = seven_block_ball(n, m);
    ASSERT_EQ(mesh.hexes.size(), static_cast<std::size_t>(n * n * n + 6 * n * n * m));
    // Vertices: the cube lattice plus m shells of the cube's surface lattice.
    ASSERT_EQ(mesh.points.size(), static_cast<std::size_t>((n + 1) * (n + 1) * (n + 1) + m * (6 * n * n + 2)));
    const HexStructure s = structure_of(mesh);
    // By hand: each of the cube's 12 edges has 3 hexes around it (one of the
    // cube, one of each of the two blocks on its faces): 12 n edges of
    // valence 3. From each of the cube's 8 corners a radial line of m edges
    // runs to the sphere between 3 blocks: valence 3. The sphere is smooth,
    // every boundary edge has 2 hexes (flat: 2 expected).
    EXPECT_EQ(s.interior_by_valence, (std::map<Index, Index>{{3, 12 * n + 8 * m}})) << n << m;
    EXPECT_EQ(s.num_singular_edges_boundary, 0) << n << m;
    EXPECT_EQ(s.num_irregular_edges_boundary, 0) << n << m;
    EXPECT_EQ(s.num_nonmanifold_edges, 0) << n << m;
    // Nodes: the 8 corners (4 singular edges each) and the 8 radial lines'
    // ends on the sphere (1 each); curves: 12 cube edges and 8 radial lines.
    EXPECT_EQ(s.nodes.size(), 16u) << n << m;
    EXPECT_EQ(s.num_curves, 20) << n << m;
    std::map<Index, int> lengths;
    for (Index l : s.curve_lengths) ++lengths[l];
    if (n != m) {
      EXPECT_EQ(lengths, (std::map<Index, int>{{n, 12}, {m, 8}})) << n << m;
    }
    EXPECT_EQ(s.num_singular_vertices, 12 * (n - 1) + 8 + 8 * m) << n << m;
    EXPECT_GE(s.gradation.min, 1.0);
  }
}

TEST(Structure, TheBundledBallIsAMappedGridWithTwelveIrregularSeams) {
  // examples/ball.mesh maps a 10^3 grid onto the ball: no interior
  // singularity; the grid's 12 box edges keep valence 1 on a smooth sphere,
  // where 2 is expected: 120 singular boundary edges, all irregular.
  const HexMesh mesh = read_hex_mesh(test::source_dir() / "examples" / "ball.mesh").mesh;
  const HexStructure s = structure_of(mesh);
  EXPECT_EQ(s.num_singular_edges_interior, 0);
  EXPECT_EQ(s.boundary_by_valence, (std::map<Index, Index>{{1, 120}}));
  EXPECT_EQ(s.num_irregular_edges_boundary, 120);
  EXPECT_EQ(s.num_curves, 12);
  EXPECT_EQ(s.nodes.size(), 8u);
  for (const StructureEdge& e : s.edges) {
    EXPECT_TRUE(e.singular && e.irregular);
    EXPECT_EQ(e.ideal_valence, 2);
  }
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
    Index listed_singular = 0;
    for (const StructureEdge& e : s.edges) {
      listed_singular += e.singular;
      EXPECT_EQ(e.curve != kNoIndex, e.singular) << name;
    }
    EXPECT_EQ(total, listed_singular) << name;
  }
}

TEST(Structure, BadInputIsCountedNotFatal) {
  // Two grids sharing only an edge: that edge has valence 2 but 4 boundary
  // faces (non-manifold); a duplicate hex doubles valences; an unreferenced
  // vertex is no edge at all.
  HexMesh mesh = test::unit_cube();
  const HexMesh other = test::unit_cube();
  const Index base = static_cast<Index>(mesh.points.size());
  for (Vec3 p : other.points) mesh.points.push_back(p + Vec3{1, 1, 0});
  Hex h = other.hexes[0];
  for (Index& v : h) v += base;
  mesh.hexes.push_back(h);
  // Merge the second cube's x = 0, y = 0 edge (points (1,1,0) and (1,1,1)) with the first's.
  for (Index& v : mesh.hexes[1]) {
    const Vec3 p = mesh.points[static_cast<std::size_t>(v)];
    for (Index w = 0; w < base; ++w)
      if (squared_norm(mesh.points[static_cast<std::size_t>(w)] - p) == 0.0) v = w;
  }
  mesh.points.push_back({9, 9, 9});  // unreferenced
  HexStructure s = structure_of(mesh);
  EXPECT_EQ(s.num_nonmanifold_edges, 1);
  EXPECT_EQ(s.num_edges, 23);
  mesh.hexes.push_back(mesh.hexes[0]);  // a duplicate
  s = structure_of(mesh);
  EXPECT_EQ(s.num_edges, 23);
  expect_map_counts(mesh, s, "duplicate");
}


// A 2 x 2 x 2 grid with a pyramid on each of its 4 top faces: the 12 hex
// edges in the top plane are pyramid edges too. They are listed with
// touches_non_hex, never singular or irregular, and kept out of the
// singularity graph; every other edge is what the pure grid gives.
TEST(Structure, EdgesTouchingPyramidsAreNeitherSingularNorRegular) {
  const HexMesh grid = test::grid(2);
  const HexStructure pure = structure_of(grid);
  HexMesh mesh = grid;
  std::vector<std::array<Index, 5>> pyramids;
  for (const Hex& h : grid.hexes) {
    if (grid.points[static_cast<std::size_t>(h[4])].z != 2.0) continue;
    Vec3 c{};
    for (int i = 4; i < 8; ++i) c = c + grid.points[static_cast<std::size_t>(h[i])];
    mesh.points.push_back(0.25 * c + Vec3{0, 0, 0.5});
    pyramids.push_back({h[4], h[5], h[6], h[7], static_cast<Index>(mesh.points.size() - 1)});
  }
  ASSERT_EQ(pyramids.size(), 4u);
  mesh.pyramids = pyramids;
  const Topology topo = build_topology(mesh);
  const HexStructure s = compute_structure(mesh, topo);
  const auto on_top = [&](const Edge& e) {
    return mesh.points[static_cast<std::size_t>(e[0])].z == 2.0 && mesh.points[static_cast<std::size_t>(e[1])].z == 2.0;
  };
  EXPECT_EQ(s.num_edges, pure.num_edges);
  EXPECT_EQ(s.num_edges_touching_non_hex, 12);
  EXPECT_EQ(pure.num_edges_touching_non_hex, 0);
  std::map<Edge, StructureEdge> rows, pure_rows;
  for (const StructureEdge& e : s.edges) rows[e.vertices] = e;
  for (const StructureEdge& e : pure.edges) pure_rows[e.vertices] = e;
  Index pure_singular_on_top = 0;
  for (const auto& [v, e] : pure_rows) {
    EXPECT_FALSE(e.touches_non_hex);
    if (on_top(v)) {
      pure_singular_on_top += e.singular;
      continue;
    }
    ASSERT_TRUE(rows.count(v));
    EXPECT_EQ(rows[v].singular, e.singular);
    EXPECT_EQ(rows[v].valence, e.valence);
    EXPECT_EQ(rows[v].kind, e.kind);
    EXPECT_FALSE(rows[v].touches_non_hex);
  }
  Index touching = 0;
  for (const auto& [v, e] : rows) {
    EXPECT_EQ(e.touches_non_hex, on_top(v));
    if (!e.touches_non_hex) continue;
    ++touching;
    EXPECT_FALSE(e.singular);
    EXPECT_FALSE(e.irregular);
    EXPECT_EQ(e.curve, kNoIndex);
    EXPECT_EQ(e.valence, std::count_if(mesh.hexes.begin(), mesh.hexes.end(), [&](const Hex& h) {
                return std::count(h.begin(), h.end(), v[0]) && std::count(h.begin(), h.end(), v[1]);
              }));
  }
  EXPECT_EQ(touching, 12);
  int on_boundary = 0;
  for (const auto& [v, e] : rows) on_boundary += e.touches_non_hex && e.kind == EdgeKind::boundary;
  // Every top edge is on the whole mesh's boundary: the 8 rim edges on a hex
  // side quad and a pyramid triangle, the 4 through the centre in the valley
  // between two pyramids' triangles.
  EXPECT_EQ(on_boundary, 12);
  EXPECT_EQ(s.num_singular_edges_boundary, pure.num_singular_edges_boundary - pure_singular_on_top);
  EXPECT_EQ(s.num_singular_edges_interior, pure.num_singular_edges_interior);
  EXPECT_EQ(s.num_nonmanifold_edges, 0);
}

}  // namespace
}  // namespace hq
