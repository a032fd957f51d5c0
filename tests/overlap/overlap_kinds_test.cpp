// Overlap across cell kinds (issue 46): cells of every kind as their
// triangle and quad faces. Hand-built meshes whose answers are worked out
// below (a tet through a tet, a tangled tet, a pyramid's apex in a
// neighbouring hex, an inverted wedge in the hex beside it, a wedge through
// a tet, touching across kinds), and a
// conforming hex-pyramid-tet mesh made by Debian's Gmsh, clean and with one
// vertex dragged through its neighbours, checked against an independent
// test: each cell as the intersection of its faces' half-spaces, a vertex
// strictly inside by those half-spaces and interiors that meet by a small
// linear programme (the largest ball inside both), in plain doubles.

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <vector>

#include "gmsh_run.h"
#include "hqview/core/box3.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/mesh/topology.h"
#include "hqview/overlap/cell_faces.h"
#include "hqview/overlap/overlap.h"
#include "hybrid_mesh_files.h"
#include "support/mixed_grid.h"
#include "temp_dir.h"

namespace hq {
namespace HQ_TEST_UNIT {

using Pairs = std::vector<std::array<Index, 2>>;

OverlapReport run(const Mesh& mesh, OverlapMode mode = OverlapMode::certificate) {
  return check_overlap(mesh, build_topology(mesh), OverlapOptions{.mode = mode});
}

Pairs pairs_of(const OverlapReport& r) {
  Pairs out;
  for (const IntersectingPair& p : r.intersecting_pairs) out.push_back(p.cells);
  return out;
}

// The signed volume of a cell by the split into tets of hybrid_mesh_files.h
// (written without HQView's tables).
double split_volume(const Mesh& mesh, int vtk_type, const std::vector<int>& corners) {
  std::vector<std::array<double, 3>> points;
  for (const Vec3& p : mesh.points) points.push_back({p.x, p.y, p.z});
  return test::split_volume(points, vtk_type, corners).total;
}

Index add_point(Mesh& mesh, Vec3 p) {
  mesh.points.push_back(p);
  return mesh.num_vertices() - 1;
}

// Appends a cell of points `at` (VTK order), flipped when its volume is
// negative, so a hand-built cell is valid whatever order it was written in.
void add_tet(Mesh& mesh, std::array<Vec3, 4> at) {
  std::array<Index, 4> c;
  for (int i = 0; i < 4; ++i) c[static_cast<std::size_t>(i)] = add_point(mesh, at[static_cast<std::size_t>(i)]);
  if (split_volume(mesh, 10, {c[0], c[1], c[2], c[3]}) < 0) std::swap(c[1], c[2]);
  mesh.tets.push_back(c);
}

Mesh unit_hex(Vec3 origin = {}) {
  Mesh mesh;
  const std::array<Vec3, 8> corners{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  Hex h;
  for (int i = 0; i < 8; ++i) h[static_cast<std::size_t>(i)] = add_point(mesh, corners[static_cast<std::size_t>(i)] + origin);
  mesh.hexes.push_back(h);
  return mesh;
}

// Both modes give exactly `expected` (and the same pairs).
void expect_pairs(const Mesh& mesh, const Pairs& expected, const char* what) {
  for (const OverlapMode mode : {OverlapMode::certificate, OverlapMode::exhaustive}) {
    const OverlapReport r = run(mesh, mode);
    EXPECT_EQ(pairs_of(r), expected) << what << " (" << overlap_mode_name(mode) << ")";
    std::set<Index> cells;
    for (const auto& p : expected) cells.insert(p.begin(), p.end());
    EXPECT_EQ(r.num_intersecting_cells, static_cast<Index>(cells.size())) << what;
  }
}

// ---- Hand-built meshes --------------------------------------------------------

// Two separate tets: a long thin one passes through the unit corner tet,
// entering by its face z = 0 and leaving by its slanted face, with no
// vertex of either inside the other (the test of interiors that meet).
TEST(OverlapKinds, TetThroughAnotherTetIsFoundWithNoVertexInside) {
  Mesh mesh;
  add_tet(mesh, {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}});
  add_tet(mesh, {{{0.2, 0.2, -1}, {0.3, 0.2, -1}, {0.2, 0.3, -1}, {0.25, 0.25, 2}}});
  expect_pairs(mesh, {{0, 1}}, "tet through tet");
  const OverlapReport r = run(mesh);
  ASSERT_EQ(r.intersecting_pairs.size(), 1u);
  EXPECT_EQ(r.intersecting_pairs[0].inside_vertex, kNoIndex);
  EXPECT_EQ(r.intersecting_pairs[0].kinds, (std::array<CellKind, 2>{CellKind::tet, CellKind::tet}));
  EXPECT_EQ(r.intersecting_pairs[0].source_indices, (std::array<std::int64_t, 2>{1, 2}));  // 1-based in the block
  EXPECT_TRUE(r.inverted_cells.empty());
  EXPECT_FALSE(r.certified_clean);
  // Moved by (0.5, 0.5, 0), the thin tet passes beside it (x + y > 1 on
  // the whole of it): nothing.
  Mesh apart = mesh;
  for (Index v = 4; v < 8; ++v) apart.points[static_cast<std::size_t>(v)] = apart.points[static_cast<std::size_t>(v)] + Vec3{0.5, 0.5, 0};
  expect_pairs(apart, {}, "thin tet beside");
}

// Two tets on one face (0 1 2); the apex of the second (4) is pushed through
// that face into the first: the second is inverted, and its apex lies
// inside the first.
TEST(OverlapKinds, TangledTetIsInvertedAndIntersectsItsNeighbour) {
  Mesh mesh;
  for (const Vec3 p : {Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0.3, 0.3, 1}, Vec3{0.3, 0.3, -1}})
    add_point(mesh, p);
  mesh.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  ASSERT_GT(split_volume(mesh, 10, {0, 1, 2, 3}), 0);
  ASSERT_GT(split_volume(mesh, 10, {0, 2, 1, 4}), 0);
  {
    const OverlapReport r = run(mesh);
    EXPECT_TRUE(r.certified_clean);
    EXPECT_TRUE(r.intersecting_pairs.empty());
  }
  // Inside tet 0: barycentric weights 0.4, 0.05, 0.05, 0.5 of its corners.
  mesh.points[4] = {0.2, 0.2, 0.5};
  expect_pairs(mesh, {{0, 1}}, "tangled tet");
  const OverlapReport r = run(mesh);
  EXPECT_EQ(r.inverted_cells, std::vector<Index>{1});
  ASSERT_EQ(r.intersecting_pairs.size(), 1u);
  EXPECT_EQ(r.intersecting_pairs[0].inside_vertex, 4);
}

// Hexes A = [0,1]^3, B = [1,2]x[0,1]^2 and C on B (z in [1,2]), a pyramid
// on A's top face (ids shared). Its apex leaning over into C: the pyramid is
// valid and intersects C (its apex inside); pushed down into B instead, it
// is inverted (below its base's plane) and intersects B.
TEST(OverlapKinds, PyramidApexInANeighbouringHex) {
  Mesh mesh = unit_hex();
  const Mesh b = unit_hex({1, 0, 0});
  // B shares A's x = 1 face: A's corners 1, 2, 6, 5 are B's 0, 3, 7, 4.
  Hex hb;
  const std::array<Index, 8> shared{1, kNoIndex, kNoIndex, 2, 5, kNoIndex, kNoIndex, 6};
  for (int i = 0; i < 8; ++i)
    hb[static_cast<std::size_t>(i)] = shared[static_cast<std::size_t>(i)] != kNoIndex
                                          ? shared[static_cast<std::size_t>(i)]
                                          : add_point(mesh, b.points[static_cast<std::size_t>(i)]);
  mesh.hexes.push_back(hb);
  // C on B's top face.
  Hex hc;
  for (int i = 0; i < 4; ++i) hc[static_cast<std::size_t>(i)] = hb[static_cast<std::size_t>(i + 4)];
  for (int i = 4; i < 8; ++i)
    hc[static_cast<std::size_t>(i)] = add_point(mesh, mesh.points[static_cast<std::size_t>(hb[static_cast<std::size_t>(i)])] + Vec3{0, 0, 1});
  mesh.hexes.push_back(hc);
  const Index apex = add_point(mesh, {0.5, 0.5, 1.5});
  mesh.pyramids.push_back({4, 5, 6, 7, apex});
  ASSERT_GT(split_volume(mesh, 14, {4, 5, 6, 7, apex}), 0);
  ASSERT_GT(split_volume(mesh, 12, std::vector<int>(hb.begin(), hb.end())), 0);
  ASSERT_GT(split_volume(mesh, 12, std::vector<int>(hc.begin(), hc.end())), 0);
  expect_pairs(mesh, {}, "pyramid upright");
  EXPECT_TRUE(run(mesh).certified_clean);

  mesh.points[static_cast<std::size_t>(apex)] = {1.5, 0.5, 1.5};  // inside C
  expect_pairs(mesh, {{2, 3}}, "apex in C");
  {
    const OverlapReport r = run(mesh);
    EXPECT_TRUE(r.inverted_cells.empty());
    ASSERT_EQ(r.intersecting_pairs.size(), 1u);
    EXPECT_EQ(r.intersecting_pairs[0].inside_vertex, apex);
    EXPECT_EQ(r.intersecting_pairs[0].kinds, (std::array<CellKind, 2>{CellKind::hex, CellKind::pyramid}));
    EXPECT_EQ(r.cell_intersecting, (std::vector<char>{0, 0, 1, 1}));
  }
  mesh.points[static_cast<std::size_t>(apex)] = {1.5, 0.5, 0.8};  // inside B, below the base
  expect_pairs(mesh, {{1, 3}}, "apex in B");
  const OverlapReport r = run(mesh);
  EXPECT_EQ(r.inverted_cells, std::vector<Index>{3});
  EXPECT_EQ(r.intersecting_pairs[0].inside_vertex, apex);
}

// A wedge on hex A's face x = 1 (A's corners 1, 5, 6, 2; its triangles in
// the planes y = 0 and y = 1): clean and certified. Its corner (2, 1, 0)
// pushed to (0.5, 0.8, 0.3), inside A: the corner frame there turns
// negative (det -0.7 by hand), so the wedge is inverted, and it intersects
// A with that corner inside.
TEST(OverlapKinds, InvertedWedgeIntersectsTheHexBesideIt) {
  Mesh mesh = unit_hex();
  const Index b0 = add_point(mesh, {2, 0, 0}), b1 = add_point(mesh, {2, 1, 0});
  mesh.wedges.push_back({1, b0, 5, 2, b1, 6});
  ASSERT_GT(split_volume(mesh, 13, {1, b0, 5, 2, b1, 6}), 0);
  {
    const OverlapReport r = run(mesh);
    EXPECT_TRUE(r.certified_clean);
    EXPECT_TRUE(r.intersecting_pairs.empty());
  }
  mesh.points[static_cast<std::size_t>(b1)] = {0.5, 0.8, 0.3};
  expect_pairs(mesh, {{0, 1}}, "wedge corner in the hex");
  const OverlapReport r = run(mesh);
  EXPECT_EQ(r.inverted_cells, std::vector<Index>{1});
  ASSERT_EQ(r.intersecting_pairs.size(), 1u);
  EXPECT_EQ(r.intersecting_pairs[0].inside_vertex, b1);
  EXPECT_EQ(r.intersecting_pairs[0].kinds, (std::array<CellKind, 2>{CellKind::hex, CellKind::wedge}));
}

// A wedge as a long bar along z (triangle of side 0.2 at the origin) through
// a tet that spans x, y in [-1, 2] at z in [0, 1]: the bar crosses the tet
// for z in [0, 0.3] (x = y = 0.05: (x+1)/3 + (y+1)/3 + z <= 1), and no
// vertex of either lies in the other.
TEST(OverlapKinds, WedgeThroughATetIsFound) {
  Mesh mesh;
  add_tet(mesh, {{{-1, -1, 0}, {2, -1, 0}, {-1, 2, 0}, {-1, -1, 1}}});
  std::array<Index, 6> w;
  const std::array<Vec3, 6> at{{{0, 0, -2}, {0, 0.2, -2}, {0.2, 0, -2}, {0, 0, 3}, {0, 0.2, 3}, {0.2, 0, 3}}};
  for (int i = 0; i < 6; ++i) w[static_cast<std::size_t>(i)] = add_point(mesh, at[static_cast<std::size_t>(i)]);
  mesh.wedges.push_back(w);
  ASSERT_GT(split_volume(mesh, 13, std::vector<int>(w.begin(), w.end())), 0);
  expect_pairs(mesh, {{0, 1}}, "wedge through tet");
  const OverlapReport r = run(mesh);
  EXPECT_EQ(r.intersecting_pairs[0].inside_vertex, kNoIndex);
  EXPECT_EQ(r.intersecting_pairs[0].kinds, (std::array<CellKind, 2>{CellKind::tet, CellKind::wedge}));
  EXPECT_TRUE(r.inverted_cells.empty());
  // Shifted by (1, 1, 0) the bar stands beyond the tet's slanted face
  // ((x+1)/3 + (y+1)/3 >= 4/3): nothing.
  for (Index v = 4; v < 10; ++v) mesh.points[static_cast<std::size_t>(v)] = mesh.points[static_cast<std::size_t>(v)] + Vec3{1, 1, 0};
  expect_pairs(mesh, {}, "wedge beside tet");
}

// A wedge with a slanted face in the plane x + y = 1 (its triangle (0,0),
// (0,1), (1,0), z in [0,4]) and cells on the other side touching it with
// their own vertex ids, each in its own band of z: a tet by a face, a tet
// by an edge, a pyramid by its apex on that face, and a tet whose corner
// coincides with a wedge corner. Their boxes overlap the wedge's with
// volume (the plane is slanted), so every pair is tested; none intersects.
// Cell ids: the tets 0, 1, 2, the wedge 3, the pyramid 4.
TEST(OverlapKinds, TouchingAcrossKindsIsNotIntersecting) {
  Mesh mesh;
  std::array<Index, 6> w;
  const std::array<Vec3, 6> at{{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 4}, {0, 1, 4}, {1, 0, 4}}};
  for (int i = 0; i < 6; ++i) w[static_cast<std::size_t>(i)] = add_point(mesh, at[static_cast<std::size_t>(i)]);
  mesh.wedges.push_back(w);
  ASSERT_GT(split_volume(mesh, 13, std::vector<int>(w.begin(), w.end())), 0);
  add_tet(mesh, {{{0.75, 0.25, 0.25}, {0.25, 0.75, 0.25}, {0.5, 0.5, 0.75}, {1, 1, 0.5}}});           // face on face
  add_tet(mesh, {{{0.875, 0.125, 1.25}, {0.125, 0.875, 1.75}, {1, 1, 1.25}, {1.25, 1.25, 1.75}}});    // edge in face
  add_tet(mesh, {{{0, 1, 4}, {0.5, 1.5, 3.5}, {1.5, 0.25, 3.75}, {1.25, 1.25, 4.5}}});              // corner on corner
  const Index apex = add_point(mesh, {0.5, 0.5, 2.5});                                               // on the face
  std::array<Index, 5> pyramid;
  const std::array<Vec3, 4> base{{{1.5, 0.5, 2.2}, {1.5, 0.5, 2.8}, {0.5, 1.5, 2.8}, {0.5, 1.5, 2.2}}};
  for (int i = 0; i < 4; ++i) pyramid[static_cast<std::size_t>(i)] = add_point(mesh, base[static_cast<std::size_t>(i)]);
  pyramid[4] = apex;
  if (split_volume(mesh, 14, std::vector<int>(pyramid.begin(), pyramid.end())) < 0) std::swap(pyramid[1], pyramid[3]);
  mesh.pyramids.push_back(pyramid);
  ASSERT_GT(split_volume(mesh, 14, std::vector<int>(pyramid.begin(), pyramid.end())), 0);
  expect_pairs(mesh, {}, "touching");
  const OverlapReport r = run(mesh, OverlapMode::exhaustive);
  EXPECT_EQ(r.num_candidate_pairs, 4);  // the wedge with each: their boxes overlap; the z bands keep the rest apart
  EXPECT_EQ(r.num_coincident_vertices, 2);  // the corner on the corner
  EXPECT_TRUE(r.inverted_cells.empty());
  // Pushed by (-0.01, -0.01, 0) towards the wedge, every one of them
  // intersects it (the corner tet by a sliver, with no vertex inside).
  for (std::size_t v = 6; v < mesh.points.size(); ++v) mesh.points[v] = mesh.points[v] - Vec3{0.01, 0.01, 0};
  expect_pairs(mesh, {{0, 3}, {1, 3}, {2, 3}, {3, 4}}, "pushed in");
  const OverlapReport pushed = run(mesh);
  EXPECT_EQ(pushed.intersecting_pairs[2].inside_vertex, kNoIndex);
  EXPECT_EQ(pushed.intersecting_pairs[3].inside_vertex, apex);
}

// The hand-built hybrid mesh (test::hybrid_mesh) as a Mesh of cell blocks.
Mesh hand_built_hybrid() {
  const test::HybridMesh h = test::hybrid_mesh();
  Mesh mesh;
  for (const auto& p : h.points) mesh.points.push_back({p[0], p[1], p[2]});
  for (const test::HybridCell& c : h.cells) {
    const auto& v = c.vtk;
    if (c.vtk_type == 12) mesh.hexes.push_back({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]});
    if (c.vtk_type == 10) mesh.tets.push_back({v[0], v[1], v[2], v[3]});
    if (c.vtk_type == 13) mesh.wedges.push_back({v[0], v[1], v[2], v[3], v[4], v[5]});
    if (c.vtk_type == 14) mesh.pyramids.push_back({v[0], v[1], v[2], v[3], v[4]});
  }
  return mesh;
}

// A conforming hybrid mesh by hand (2 hexes, 2 wedges, a pyramid, 2 tets,
// hybrid_mesh_files.h): clean, certified. Its pyramid's apex (16, also a
// corner of tet T1 = cell 2) pulled down into hex B (cell 1) below it, to
// (1.5, 0.5, 0.6): the pyramid (cell 6) goes below its base's plane z = 1
// and T1 below the plane of its face 8-11-17 (z = 2/3 there), both
// inverted, and 16 lies inside B: the pairs B-T1 and B-pyramid.
TEST(OverlapKinds, HandBuiltHybridMeshIsCleanUntilItsApexDrops) {
  Mesh mesh = hand_built_hybrid();
  for (const OverlapMode mode : {OverlapMode::certificate, OverlapMode::exhaustive}) {
    const OverlapReport r = run(mesh, mode);
    EXPECT_TRUE(r.intersecting_pairs.empty());
    EXPECT_TRUE(r.inverted_cells.empty());
    EXPECT_EQ(r.cell_intersecting.size(), 7u);
    if (mode == OverlapMode::certificate) {
      EXPECT_TRUE(r.certified_clean);
    }
  }
  mesh.points[16] = {1.5, 0.5, 0.6};
  expect_pairs(mesh, {{1, 2}, {1, 6}}, "apex dropped");
  const OverlapReport r = run(mesh);
  EXPECT_EQ(r.inverted_cells, (std::vector<Index>{2, 6}));
  ASSERT_EQ(r.intersecting_pairs.size(), 2u);
  EXPECT_EQ(r.intersecting_pairs[0].kinds, (std::array<CellKind, 2>{CellKind::hex, CellKind::tet}));
  EXPECT_EQ(r.intersecting_pairs[1].kinds, (std::array<CellKind, 2>{CellKind::hex, CellKind::pyramid}));
  for (const IntersectingPair& p : r.intersecting_pairs) EXPECT_EQ(p.inside_vertex, 16);
}

Mesh gmsh_hex_tet_mesh(const test::TempDir& dir);

// ---- The topology's matched faces, read by stages D-F ---------------------------

// Every face of every cell, matched by the topology, is the table the
// overlap's own sort gives (same faces, same order, same uses), at 1 and 2
// threads; and the overlap's answers on it are those of that table.
TEST(OverlapKinds, TopologyMatchedFacesAreTheOverlapsOwnSort) {
  const test::TempDir dir("overlap_kinds_faces");
  std::vector<std::pair<const char*, Mesh>> meshes;
  meshes.emplace_back("mixed grid", test::mixed_grid());
  {
    meshes.emplace_back("hand-built hybrid", hand_built_hybrid());
  }
  Mesh gmsh = gmsh_hex_tet_mesh(dir);
  if (!gmsh.hexes.empty()) meshes.emplace_back("gmsh hex-pyramid-tet", std::move(gmsh));
  for (const auto& [what, mesh] : meshes) {
    const detail::VolumeCells cells(mesh);
    std::vector<Index> offsets, uses;
    detail::match_cell_faces(cells, offsets, uses);
    ASSERT_EQ(uses.size(), static_cast<std::size_t>(6 * mesh.hexes.size() + 4 * mesh.tets.size() +
                                                    5 * (mesh.wedges.size() + mesh.pyramids.size())))
        << what;
    // The independent sort's table: each face's uses have the same sorted
    // vertex ids, and consecutive faces ascend (triangles, then quads).
    std::vector<std::vector<Index>> keys;
    for (std::size_t f = 0; f + 1 < offsets.size(); ++f) {
      std::vector<Index> key;
      for (Index i = offsets[f]; i < offsets[f + 1]; ++i) {
        const CellHalfFace u = cell_half_face(cells.first, uses[static_cast<std::size_t>(i)]);
        auto corners = detail::local_face_corners(cells.corners(u.cell), u.local);
        std::vector<Index> k(corners.begin(), corners[3] == kNoIndex ? corners.begin() + 3 : corners.end());
        std::sort(k.begin(), k.end());
        if (i == offsets[f]) key = k;
        EXPECT_EQ(k, key) << what << " face " << f;
      }
      if (!keys.empty()) {
        EXPECT_TRUE(keys.back().size() < key.size() || (keys.back().size() == key.size() && keys.back() < key)) << what;
      }
      keys.push_back(key);
    }
    for (const int threads : {1, 2}) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
      const Topology topo = build_topology(mesh);
      EXPECT_EQ(topo.cell_face_offsets, offsets) << what << ", " << threads << " threads";
      EXPECT_EQ(topo.cell_face_uses, uses) << what << ", " << threads << " threads";
      const detail::CellFaceMap map(cells, topo);
      EXPECT_TRUE(map.reads_topology()) << what;
    }
  }
  // The repeated tet {0, 1, 2, 6} of cube 1: its triangles 0-1-6 and 0-2-6
  // are inside the cube (shared with a neighbouring tet: 3 uses, non-manifold);
  // 0-1-2 is on the grid's bottom and 1-2-6 against the wedges' quad of cube
  // 2 (2 uses each).
  const Mesh& grid = meshes.front().second;
  const OverlapReport r = run(grid);
  EXPECT_EQ(r.non_manifold_faces.size(), 2u);
  EXPECT_EQ(r.duplicate_cells.size(), 1u);
  // A topology of the hexes alone: the overlap matches every face itself.
  Mesh hexes_only = grid;
  hexes_only.tets.clear();
  hexes_only.wedges.clear();
  hexes_only.pyramids.clear();
  const Topology hex_topo = build_topology(hexes_only);
  const detail::VolumeCells grid_cells(grid);
  const detail::CellFaceMap own(grid_cells, hex_topo);
  EXPECT_FALSE(own.reads_topology());
  EXPECT_EQ(own.offsets(), build_topology(grid).cell_face_offsets);
  const OverlapReport from_hexes = check_overlap(grid, hex_topo, OverlapOptions{});
  EXPECT_EQ(from_hexes.non_manifold_faces, r.non_manifold_faces);
  EXPECT_EQ(from_hexes.same_winding_faces, r.same_winding_faces);
  EXPECT_EQ(from_hexes.duplicate_cells, r.duplicate_cells);
  EXPECT_EQ(pairs_of(from_hexes), pairs_of(r));
}

// Repeated cells of every kind, in other corner orders and in threes (the
// repeats listed are every cell whose corner set a lower-numbered cell of
// its kind has), against a comparison of every pair of cells; a tet and a
// pyramid of the same hex share 4 corners, never the set.
TEST(OverlapKinds, DuplicateCellsInAnyCornerOrderAreEveryPairsVerdict) {
  Mesh mesh = test::mixed_grid(3);
  const auto reversed = [](auto cell) {
    std::reverse(cell.begin(), cell.end());
    return cell;
  };
  const auto rotated = [](auto cell) {
    std::rotate(cell.begin(), cell.begin() + 1, cell.end());
    return cell;
  };
  mesh.hexes.push_back(reversed(mesh.hexes[1]));
  mesh.hexes.push_back(rotated(mesh.hexes[1]));
  mesh.hexes.push_back(rotated(mesh.hexes[0]));
  mesh.tets.push_back(reversed(mesh.tets[7]));
  mesh.tets.push_back(rotated(mesh.tets[7]));
  mesh.tets.push_back(rotated(mesh.tets[11]));
  mesh.wedges.push_back(rotated(mesh.wedges[2]));
  mesh.pyramids.push_back(reversed(mesh.pyramids[3]));
  mesh.tets.push_back({mesh.pyramids[3][0], mesh.pyramids[3][1], mesh.pyramids[3][2], mesh.pyramids[3][4]});
  const detail::VolumeCells cells(mesh);
  const auto corner_set = [&](Index c) {
    const detail::CellCornerIds ids = cells.corners(c);
    std::vector<Index> set(ids.begin(), ids.end());
    std::sort(set.begin(), set.end());
    return set;
  };
  std::vector<Index> expected;
  for (Index c = 0; c < cells.size(); ++c)
    for (Index d = 0; d < c; ++d)
      if (corner_set(d) == corner_set(c)) {
        expected.push_back(c);
        break;
      }
  // The grid's own repeated tet, and the 8 above but the tet of 4 pyramid corners.
  ASSERT_EQ(expected.size(), 9u);
  for (const int threads : {1, 2}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    EXPECT_EQ(run(mesh).duplicate_cells, expected) << threads << " threads";
  }
}

// ---- A hybrid mesh by Gmsh, and an independent test -----------------------------

// A convex cell as the intersection of its faces' closed half-spaces
// n . x <= b (n unit, outward; a face's plane through 3 of its corners, the
// cell's volume sign making it outward even when the cell is inverted).
struct HalfSpaces {
  std::vector<std::array<double, 4>> planes;  // n.x, n.y, n.z, b
};

HalfSpaces half_spaces(const std::vector<Vec3>& corners, int vtk_type) {
  // Faces by 3 corners, outward for a valid cell in VTK order (independent
  // of core/cell_kinds.h: from VTK's node pictures).
  std::vector<std::array<int, 3>> faces;
  if (vtk_type == 10) faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  if (vtk_type == 14) faces = {{0, 3, 2}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  if (vtk_type == 12) faces = {{0, 3, 2}, {4, 5, 6}, {0, 1, 5}, {2, 3, 7}, {1, 2, 6}, {3, 0, 4}};
  if (vtk_type == 13) faces = {{0, 1, 2}, {3, 5, 4}, {0, 3, 4}, {1, 4, 5}, {2, 5, 3}};
  std::vector<std::array<double, 3>> pts;
  for (const Vec3& p : corners) pts.push_back({p.x, p.y, p.z});
  std::vector<int> ids(corners.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<int>(i);
  const double sign = test::split_volume(pts, vtk_type, ids).total < 0 ? -1.0 : 1.0;
  HalfSpaces h;
  for (const auto& f : faces) {
    const Vec3 a = corners[static_cast<std::size_t>(f[0])], b = corners[static_cast<std::size_t>(f[1])],
               c = corners[static_cast<std::size_t>(f[2])];
    Vec3 n = cross(b - a, c - a) * sign;
    n = n / norm(n);
    h.planes.push_back({n.x, n.y, n.z, dot(n, a)});
  }
  return h;
}

// x strictly inside by every half-space, by a margin.
bool strictly_inside(const HalfSpaces& h, const Vec3& x, double margin) {
  return std::all_of(h.planes.begin(), h.planes.end(),
                     [&](const auto& p) { return p[0] * x.x + p[1] * x.y + p[2] * x.z < p[3] - margin; });
}

// The radius of the largest ball inside both cells: max t over n.x + t <= b
// for every plane, by the vertices of that polytope in (x, y, z, t) (4 of
// the planes tight at a time). > 0: the interiors meet; <= 0: they do not.
double common_ball_radius(const HalfSpaces& a, const HalfSpaces& b) {
  std::vector<std::array<double, 4>> p = a.planes;
  p.insert(p.end(), b.planes.begin(), b.planes.end());
  const std::size_t m = p.size();
  double best = -1e300;
  std::array<std::size_t, 4> s{};
  for (s[0] = 0; s[0] < m; ++s[0])
    for (s[1] = s[0] + 1; s[1] < m; ++s[1])
      for (s[2] = s[1] + 1; s[2] < m; ++s[2])
        for (s[3] = s[2] + 1; s[3] < m; ++s[3]) {
          double A[4][5];
          for (int r = 0; r < 4; ++r) {
            const auto& q = p[s[static_cast<std::size_t>(r)]];
            A[r][0] = q[0], A[r][1] = q[1], A[r][2] = q[2], A[r][3] = 1.0, A[r][4] = q[3];
          }
          bool singular = false;  // Gaussian elimination with partial pivoting
          for (int c = 0; c < 4 && !singular; ++c) {
            int pivot = c;
            for (int r = c + 1; r < 4; ++r)
              if (std::abs(A[r][c]) > std::abs(A[pivot][c])) pivot = r;
            if (std::abs(A[pivot][c]) < 1e-12) {
              singular = true;
              break;
            }
            for (int k = 0; k < 5; ++k) std::swap(A[c][k], A[pivot][k]);
            for (int r = 0; r < 4; ++r)
              if (r != c) {
                const double f = A[r][c] / A[c][c];
                for (int k = c; k < 5; ++k) A[r][k] -= f * A[c][k];
              }
          }
          if (singular) continue;
          const double x = A[0][4] / A[0][0], y = A[1][4] / A[1][1], z = A[2][4] / A[2][2], t = A[3][4] / A[3][3];
          const bool feasible = std::all_of(p.begin(), p.end(), [&](const auto& q) {
            return q[0] * x + q[1] * y + q[2] * z + t <= q[3] + 1e-9;
          });
          if (feasible) best = std::max(best, t);
        }
  return best;
}

struct Cell {
  int vtk_type;
  std::vector<Index> ids;
};

std::vector<Cell> cells_of(const Mesh& mesh) {
  std::vector<Cell> cells;
  for (const auto& c : mesh.hexes) cells.push_back({12, {c.begin(), c.end()}});
  for (const auto& c : mesh.tets) cells.push_back({10, {c.begin(), c.end()}});
  for (const auto& c : mesh.wedges) cells.push_back({13, {c.begin(), c.end()}});
  for (const auto& c : mesh.pyramids) cells.push_back({14, {c.begin(), c.end()}});
  return cells;
}

Mesh gmsh_hex_tet_mesh(const test::TempDir& dir) {
  if (!test::run_gmsh(dir, test::kHexTetGeo, {"m.msh"})) return {};
  return read_hex_mesh(dir.path() / "m.msh").mesh;
}

TEST(OverlapKinds, GmshHybridMeshIsCleanAndADraggedVertexIsFoundAsTheIndependentTestSays) {
  const test::TempDir dir("overlap_kinds");
  const Mesh mesh = gmsh_hex_tet_mesh(dir);
  if (mesh.hexes.empty()) GTEST_SKIP() << "gmsh failed or is missing";
  ASSERT_EQ(mesh.hexes.size(), 64u);
  ASSERT_EQ(mesh.pyramids.size(), 16u);
  ASSERT_GT(mesh.tets.size(), 50u);
  ASSERT_TRUE(mesh.wedges.empty());
  const std::size_t num_cells = mesh.hexes.size() + mesh.tets.size() + mesh.pyramids.size();
  for (const OverlapMode mode : {OverlapMode::certificate, OverlapMode::exhaustive}) {
    const OverlapReport r = run(mesh, mode);
    EXPECT_EQ(r.num_intersecting_cells, 0) << overlap_mode_name(mode);
    EXPECT_TRUE(r.inverted_cells.empty());
    EXPECT_TRUE(r.coincident_groups.empty());
    EXPECT_EQ(r.cell_intersecting.size(), num_cells);
    if (mode == OverlapMode::certificate) {
      EXPECT_TRUE(r.certified_clean);
      EXPECT_EQ(r.num_candidate_pairs, 0);
    } else {
      EXPECT_GT(r.num_candidate_pairs, 1000);  // every kind against its neighbours
    }
  }

  // An interior vertex of the tet box (used by tets only, away from its
  // faces), dragged to the centroid of the nearest tet that is not one of
  // its own and lies at least 0.15 away: through the tets between.
  const std::vector<Cell> cells = cells_of(mesh);
  std::vector<std::vector<Index>> cells_of_vertex(mesh.points.size());
  for (std::size_t c = 0; c < cells.size(); ++c)
    for (Index v : cells[c].ids) cells_of_vertex[static_cast<std::size_t>(v)].push_back(static_cast<Index>(c));
  Index dragged = kNoIndex;
  for (std::size_t v = 0; v < mesh.points.size() && dragged == kNoIndex; ++v) {
    const Vec3 p = mesh.points[v];
    const auto& around = cells_of_vertex[v];
    if (around.empty() || p.x < 1.2 || p.x > 1.8 || p.y < 0.2 || p.y > 0.8 || p.z < 0.2 || p.z > 0.8) continue;
    if (std::all_of(around.begin(), around.end(), [&](Index c) { return cells[static_cast<std::size_t>(c)].vtk_type == 10; }))
      dragged = static_cast<Index>(v);
  }
  ASSERT_NE(dragged, kNoIndex);
  const auto& own = cells_of_vertex[static_cast<std::size_t>(dragged)];
  auto centroid = [&](const Cell& c) {
    Vec3 sum{};
    for (Index v : c.ids) sum = sum + mesh.points[static_cast<std::size_t>(v)];
    return sum / static_cast<double>(c.ids.size());
  };
  Index target = kNoIndex;
  double nearest = 1e300;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    if (cells[c].vtk_type != 10 || std::find(own.begin(), own.end(), static_cast<Index>(c)) != own.end()) continue;
    const double d = norm(centroid(cells[c]) - mesh.points[static_cast<std::size_t>(dragged)]);
    if (d >= 0.15 && d < nearest) {
      nearest = d;
      target = static_cast<Index>(c);
    }
  }
  ASSERT_NE(target, kNoIndex);
  Mesh moved = mesh;
  moved.points[static_cast<std::size_t>(dragged)] = centroid(cells[static_cast<std::size_t>(target)]);

  // The independent test, on every pair with a moved cell (the others did
  // not change and did not intersect).
  std::vector<HalfSpaces> h;
  std::vector<Box3> boxes;
  for (const Cell& c : cells) {
    std::vector<Vec3> corners;
    Box3 box;
    for (Index v : c.ids) {
      corners.push_back(moved.points[static_cast<std::size_t>(v)]);
      box.add(corners.back());
    }
    h.push_back(half_spaces(corners, c.vtk_type));
    boxes.push_back(box);
  }
  const double margin = 1e-9;
  std::set<std::array<Index, 2>> must, may;  // a vertex strictly inside; interiors meet
  for (Index a : own)
    for (Index b = 0; b < static_cast<Index>(cells.size()); ++b) {
      if (a == b || !boxes[static_cast<std::size_t>(a)].overlaps(boxes[static_cast<std::size_t>(b)])) continue;
      const std::array<Index, 2> pair{std::min(a, b), std::max(a, b)};
      const Cell &ca = cells[static_cast<std::size_t>(a)], &cb = cells[static_cast<std::size_t>(b)];
      auto vertex_in = [&](const Cell& from, const Cell& to, const HalfSpaces& to_h) {
        for (Index v : from.ids)
          if (std::find(to.ids.begin(), to.ids.end(), v) == to.ids.end() &&
              strictly_inside(to_h, moved.points[static_cast<std::size_t>(v)], margin))
            return true;
        return false;
      };
      if (vertex_in(ca, cb, h[static_cast<std::size_t>(b)]) || vertex_in(cb, ca, h[static_cast<std::size_t>(a)]))
        must.insert(pair);
      if (common_ball_radius(h[static_cast<std::size_t>(a)], h[static_cast<std::size_t>(b)]) > margin) may.insert(pair);
    }
  ASSERT_GE(must.size(), own.size());  // each moved cell holds the dragged vertex, now inside the target
  for (const OverlapMode mode : {OverlapMode::certificate, OverlapMode::exhaustive}) {
    const OverlapReport r = run(moved, mode);
    const Pairs found = pairs_of(r);
    const std::set<std::array<Index, 2>> found_set(found.begin(), found.end());
    for (const auto& p : must) EXPECT_TRUE(found_set.count(p)) << "missed " << p[0] << "-" << p[1];
    for (const auto& p : found) EXPECT_TRUE(may.count(p)) << "reported " << p[0] << "-" << p[1] << " whose interiors do not meet";
    for (Index c : own) EXPECT_EQ(r.cell_intersecting[static_cast<std::size_t>(c)], 1);
    EXPECT_EQ(r.cell_intersecting[static_cast<std::size_t>(target)], 1);
    for (const IntersectingPair& p : r.intersecting_pairs)
      EXPECT_EQ(p.kinds, (std::array<CellKind, 2>{CellKind::tet, CellKind::tet}));
  }
  // Any thread count: the same report.
  const OverlapReport two = run(moved);
  const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const OverlapReport single = run(moved);
  EXPECT_EQ(pairs_of(single), pairs_of(two));
  EXPECT_EQ(single.inverted_cells, two.inverted_cells);
  EXPECT_EQ(single.cell_intersecting, two.cell_intersecting);
}

}  // namespace
}  // namespace hq
