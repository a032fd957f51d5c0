// build_topology with tets, wedges and pyramids beside the hexes: faces
// matched across kinds, the boundary as every face used once (closed, outward,
// enclosing the mesh's volume), non-conforming quad/two-triangle interfaces,
// the hex edges touching non-hex cells. Meshes built here by hand and by
// Debian's Gmsh (built-in kernel; MSH 2.2 read by a parser in this file, so
// the test does not depend on the readers).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <unordered_map>
#include <unistd.h>
#include <vector>

#include "hqview/core/vec3.h"
#include "hqview/mesh/topology.h"
#include "io/gmsh_run.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

using Tet = std::array<Index, 4>;
using Wedge = std::array<Index, 6>;
using Pyramid = std::array<Index, 5>;

// A hybrid mesh as plain blocks (the Mesh of ARCHITECTURE.md "Cell kinds").
struct Hybrid {
  HexMesh hex;  // points and hexes
  std::vector<Tet> tets;
  std::vector<Wedge> wedges;
  std::vector<Pyramid> pyramids;
  // The whole mesh: the hex part's points and hexes with the other blocks.
  Mesh mesh() const {
    Mesh m = hex;
    m.tets = tets;
    m.wedges = wedges;
    m.pyramids = pyramids;
    return m;
  }
  Topology topology() const { return build_topology(mesh()); }
  Index add(Vec3 p) {
    hex.points.push_back(p);
    return static_cast<Index>(hex.points.size() - 1);
  }
};

// Every edge of every volume cell once (a < b), ascending: sorted and
// deduplicated whole, the way the topology did before it bucketed them.
std::vector<Edge> every_edge_once(const Mesh& mesh) {
  std::vector<Edge> edges;
  for_each_block(mesh, [&](auto kind, const auto& cells) {
    if constexpr (CellKindTable<kind()>::dimension == 3)
      for (const auto& cell : cells)
        for (const auto& e : CellKindTable<kind()>::edges) {
          const Index a = cell[static_cast<std::size_t>(e[0])], b = cell[static_cast<std::size_t>(e[1])];
          edges.push_back({std::min(a, b), std::max(a, b)});
        }
  });
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

double signed_volume6(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return dot(cross(b - a, c - a), d - a);
}

// Every boundary face (hex quads, non-hex quads, triangles) as a polygon.
std::vector<std::vector<Index>> boundary_polygons(const Topology& t) {
  std::vector<std::vector<Index>> out;
  for (Index f : t.boundary_faces) {
    const Quad& q = t.faces[static_cast<std::size_t>(f)];
    out.push_back({q.begin(), q.end()});
  }
  for (const Quad& q : t.boundary_quads_non_hex) out.push_back({q.begin(), q.end()});
  for (const Tri& tri : t.boundary_triangles) out.push_back({tri.begin(), tri.end()});
  return out;
}

// Every boundary edge in exactly two boundary faces, used once in each
// direction (the faces are consistently outward).
void expect_closed_and_oriented(const Topology& t) {
  std::map<Edge, int> uses;
  std::map<Edge, int> directed;
  for (const auto& poly : boundary_polygons(t))
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Index a = poly[i], b = poly[(i + 1) % poly.size()];
      ++uses[{std::min(a, b), std::max(a, b)}];
      ++directed[{a, b}];
    }
  int open = 0, twisted = 0;
  for (const auto& [e, n] : uses) open += n != 2;
  for (const auto& [e, n] : directed) twisted += n != 1;
  EXPECT_EQ(open, 0) << "boundary edges not in exactly two boundary faces";
  EXPECT_EQ(twisted, 0) << "boundary edges used twice in one direction";
}

// The volume the boundary encloses (divergence theorem over fan triangles).
double enclosed_volume(const HexMesh& mesh, const Topology& t) {
  double v6 = 0;
  const Vec3 o{0, 0, 0};
  for (const auto& poly : boundary_polygons(t))
    for (std::size_t i = 1; i + 1 < poly.size(); ++i)
      v6 += signed_volume6(o, mesh.points[static_cast<std::size_t>(poly[0])],
                           mesh.points[static_cast<std::size_t>(poly[i])],
                           mesh.points[static_cast<std::size_t>(poly[i + 1])]);
  return v6 / 6.0;
}

// A unit cube hex at the origin: points 0..7 in VTK order.
Hybrid cube() {
  Hybrid m;
  m.hex = test::unit_cube();
  return m;
}

// Orients a tet so that it is valid in VTK order.
Tet valid_tet(const HexMesh& mesh, Tet t) {
  const auto& p = mesh.points;
  if (signed_volume6(p[t[0]], p[t[1]], p[t[2]], p[t[3]]) < 0) std::swap(t[1], t[2]);
  return t;
}

TEST(TopologyAcrossKinds, PureHexWithNoOtherCellsIsTheHexOnlyBuild) {
  const HexMesh mesh = test::box_grid(3, 2, 4);
  // Surface blocks are not read: a quad beside the hexes changes nothing.
  Mesh with_quad = mesh;
  with_quad.quads.push_back({0, 1, 2, 3});
  const Topology a = build_topology(mesh), b = build_topology(with_quad);
  EXPECT_TRUE(std::equal(a.faces.begin(), a.faces.end(), b.faces.begin(), b.faces.end()));
  EXPECT_EQ(a.boundary_faces, b.boundary_faces);
  EXPECT_EQ(a.boundary_vertices, b.boundary_vertices);
  EXPECT_EQ(a.edges, b.edges);
  EXPECT_TRUE(b.boundary_triangles.empty());
  EXPECT_TRUE(b.boundary_quads_non_hex.empty());
  EXPECT_TRUE(b.non_conforming_faces.empty());
  EXPECT_TRUE(b.edge_touches_non_hex.empty());
  EXPECT_TRUE(b.all_edges.empty());  // `edges` is every edge
  EXPECT_EQ(b.num_non_manifold_faces_non_hex, 0);
}

// A hex, a pyramid on its top face, a tet on a pyramid side and a second tet
// on that tet: conforming, 5 + 3 + 2 + 3 boundary faces.
TEST(TopologyAcrossKinds, HexPyramidTetsConforming) {
  Hybrid m = cube();
  const Index apex = m.add({0.5, 0.5, 2.0});
  m.pyramids.push_back({4, 5, 6, 7, apex});  // base counter-clockwise seen from the apex
  const Index t = m.add({0.5, -1.0, 1.5});
  m.tets.push_back(valid_tet(m.hex, {4, 5, apex, t}));
  const Index u = m.add({1.5, -1.0, 2.0});
  m.tets.push_back(valid_tet(m.hex, {5, apex, t, u}));
  const Topology topo = m.topology();
  EXPECT_EQ(topo.boundary_faces.size(), 5u);  // the hex's top face is the pyramid's base
  EXPECT_TRUE(topo.boundary_quads_non_hex.empty());
  EXPECT_EQ(topo.boundary_triangles.size(), 3u + 2u + 3u);
  EXPECT_TRUE(topo.non_conforming_faces.empty());
  EXPECT_EQ(topo.num_non_manifold_faces_non_hex, 0);
  expect_closed_and_oriented(topo);
  // Cell ids: hex 0, tets 1-2, pyramid 3.
  std::map<Index, int> per_cell;
  for (Index c : topo.boundary_triangle_cells) ++per_cell[c];
  EXPECT_EQ(per_cell, (std::map<Index, int>{{1, 2}, {2, 3}, {3, 3}}));
  const auto& p = m.hex.points;
  const double expected = 1.0 + 1.0 / 3.0 + std::abs(signed_volume6(p[4], p[5], p[apex], p[t])) / 6 +
                          std::abs(signed_volume6(p[5], p[apex], p[t], p[u])) / 6;
  EXPECT_NEAR(enclosed_volume(m.hex, topo), expected, 1e-12);
  EXPECT_EQ(topo.boundary_vertices.size(), 11u);
  EXPECT_TRUE(topo.unreferenced_vertices.empty());
  // The hex's 12 edges: the top four are pyramid edges too, edge 4-5 a tet edge.
  ASSERT_EQ(topo.edge_touches_non_hex.size(), 12u);
  int touching = 0;
  for (std::size_t i = 0; i < topo.edges.size(); ++i) {
    const Edge& e = topo.edges[i];
    const bool top = e[0] >= 4 && e[1] >= 4;
    EXPECT_EQ(topo.edge_touches_non_hex[i] != 0, top) << e[0] << "-" << e[1];
    touching += topo.edge_touches_non_hex[i];
  }
  EXPECT_EQ(touching, 4);
  EXPECT_EQ(topo.all_edges, every_edge_once(m.mesh()));
  EXPECT_EQ(topo.all_edges.size(), 12u + 4u + 3u + 3u);  // the hex's, the pyramid's 4 to the apex, 3 new per tet
}

// A column of three wedges over the triangle (0,0)-(1,0)-(0,1), beside a
// column of three hexes over [0,1] x [-1,0]: wedge quads against hex quads.
TEST(TopologyAcrossKinds, WedgeColumnBesideHexColumn) {
  Hybrid m;
  // Points: layer z = 0..3, each with (0,0) (1,0) (0,1) (0,-1) (1,-1).
  std::array<std::array<Index, 5>, 4> at{};
  for (int z = 0; z < 4; ++z) {
    const double zz = z;
    at[z] = {m.add({0, 0, zz}), m.add({1, 0, zz}), m.add({0, 1, zz}), m.add({0, -1, zz}), m.add({1, -1, zz})};
  }
  for (int z = 0; z < 3; ++z) {
    const auto &lo = at[z], &hi = at[z + 1];
    // VTK wedge: the first triangle's normal points away from the second.
    m.wedges.push_back({lo[0], lo[2], lo[1], hi[0], hi[2], hi[1]});
    m.hex.hexes.push_back({lo[3], lo[4], lo[1], lo[0], hi[3], hi[4], hi[1], hi[0]});
  }
  const Topology topo = m.topology();
  // Hexes: 3 x 4 sides minus the 3 faces at y = 0, plus top and bottom.
  EXPECT_EQ(topo.boundary_faces.size(), 3u * 3u + 2u);
  // Wedges: 3 x 2 quad sides (the third is against the hexes), 2 triangles.
  EXPECT_EQ(topo.boundary_quads_non_hex.size(), 6u);
  EXPECT_EQ(topo.boundary_triangles.size(), 2u);
  EXPECT_TRUE(topo.non_conforming_faces.empty());
  expect_closed_and_oriented(topo);
  EXPECT_NEAR(enclosed_volume(m.hex, topo), 3.0 + 1.5, 1e-12);
  for (Index c : topo.boundary_quad_non_hex_cells) EXPECT_TRUE(c >= 3 && c < 6) << c;
}

// A hex whose top quad meets two tets' triangles (split along 4-6): one
// non-conforming face, neither the quad nor the triangles on the boundary.
TEST(TopologyAcrossKinds, QuadAgainstTwoTrianglesIsNonConforming) {
  Hybrid m = cube();
  const Index apex = m.add({0.5, 0.5, 2.0});
  m.tets.push_back(valid_tet(m.hex, {4, 5, 6, apex}));
  m.tets.push_back(valid_tet(m.hex, {4, 6, 7, apex}));
  const Topology topo = m.topology();
  ASSERT_EQ(topo.non_conforming_faces.size(), 1u);
  const NonConformingFace& nc = topo.non_conforming_faces[0];
  EXPECT_EQ(nc.quad_cell, 0);
  EXPECT_EQ(nc.triangle_cells, (std::array<Index, 2>{1, 2}));
  EXPECT_EQ(nc.quad_kind, CellKind::hex);
  EXPECT_EQ(nc.triangle_kinds, (std::array<CellKind, 2>{CellKind::tet, CellKind::tet}));
  EXPECT_EQ(nc.quad, (Quad{4, 5, 6, 7}));  // the hex's top face, outward (+z)
  EXPECT_EQ(topo.boundary_faces.size(), 5u);
  // 2 x 4 faces: 4-6-apex shared by the tets, 4-5-6 and 4-6-7 on the quad.
  EXPECT_EQ(topo.boundary_triangles.size(), 4u);
  for (const Tri& t : topo.boundary_triangles) EXPECT_TRUE(std::count(t.begin(), t.end(), apex) == 1);
  expect_closed_and_oriented(topo);
  EXPECT_NEAR(enclosed_volume(m.hex, topo), 1.0 + 1.0 / 3.0, 1e-12);
  // One tet alone on half the quad is no interface: the quad stays boundary.
  m.tets.pop_back();
  const Topology half = m.topology();
  EXPECT_TRUE(half.non_conforming_faces.empty());
  EXPECT_EQ(half.boundary_faces.size(), 6u);
  EXPECT_EQ(half.boundary_triangles.size(), 4u);
}

// An n^3 hex grid beside an n^3 grid of cubes each split into 6 tets around
// its main diagonal (Kuhn: conforming among themselves, every cube face split
// along the diagonal from its lowest to its highest corner): the n^2 faces
// of the interface are non-conforming, the boundary is closed.
TEST(TopologyAcrossKinds, KuhnTetGridBesideHexGridHasTheInterfaceNonConforming) {
  for (int n : {1, 3}) {
    Hybrid m;
    m.hex = test::box_grid(2 * n, n, n);  // x in [0, 2n]; the tets replace x >= n
    const auto id = [&](int i, int j, int k) { return static_cast<Index>(i + (2 * n + 1) * (j + (n + 1) * k)); };
    std::vector<Hex> hexes;
    for (const Hex& h : m.hex.hexes)
      if (m.hex.points[static_cast<std::size_t>(h[0])].x < n) hexes.push_back(h);
    m.hex.hexes = hexes;
    const std::array<std::array<int, 3>, 6> perms = {{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = n; i < 2 * n; ++i)
          for (const auto& perm : perms) {
            std::array<int, 3> c = {i, j, k};
            Tet t;
            t[0] = id(c[0], c[1], c[2]);
            for (int s = 0; s < 3; ++s) {
              ++c[static_cast<std::size_t>(perm[static_cast<std::size_t>(s)])];
              t[static_cast<std::size_t>(s) + 1] = id(c[0], c[1], c[2]);
            }
            m.tets.push_back(valid_tet(m.hex, t));
          }
    const Topology topo = m.topology();
    const auto nn = static_cast<std::size_t>(n * n);
    EXPECT_EQ(topo.non_conforming_faces.size(), nn) << n;
    EXPECT_EQ(topo.boundary_faces.size(), 5 * nn) << n;
    EXPECT_EQ(topo.boundary_triangles.size(), 2 * 5 * nn) << n;
    for (const NonConformingFace& nc : topo.non_conforming_faces) {
      EXPECT_LT(nc.quad_cell, static_cast<Index>(m.hex.hexes.size()));
      for (Index v : nc.quad) EXPECT_EQ(m.hex.points[static_cast<std::size_t>(v)].x, n);
    }
    expect_closed_and_oriented(topo);
    EXPECT_NEAR(enclosed_volume(m.hex, topo), 2.0 * n * n * n, 1e-9);
    EXPECT_EQ(topo.num_non_manifold_faces_non_hex, 0);
    EXPECT_EQ(topo.all_edges, every_edge_once(m.mesh())) << n;
    // Either way, a tet-only mesh's edges are its own (no hex edges at all).
    Mesh tets_only = m.mesh();
    tets_only.hexes.clear();
    const Topology t = build_topology(tets_only);
    EXPECT_TRUE(t.edges.empty());
    EXPECT_EQ(t.all_edges, every_edge_once(tets_only)) << n;
  }
}

// Two pyramids on one hex face: a face used by three cells.
TEST(TopologyAcrossKinds, TwoPyramidsOnOneHexFaceAreNonManifold) {
  Hybrid m = cube();
  m.pyramids.push_back({4, 5, 6, 7, m.add({0.5, 0.5, 2.0})});
  m.pyramids.push_back({4, 5, 6, 7, m.add({0.5, 0.5, 3.0})});
  const Topology topo = m.topology();
  EXPECT_EQ(topo.num_non_manifold_faces_non_hex, 1);
  EXPECT_EQ(topo.boundary_faces.size(), 5u);
  EXPECT_EQ(topo.boundary_triangles.size(), 8u);
}

// ---- Meshes from Gmsh ----

struct MshFile {
  Hybrid mesh;
  std::vector<std::vector<Index>> surface_elements;  // 2D elements (triangles, quads), 0-based point ids
};

// MSH 2.2 ASCII: nodes, then elements of types 2 (triangle), 3 (quad),
// 4 (tet), 5 (hex), 6 (prism), 7 (pyramid). Gmsh's prism has its first
// triangle's normal towards the second: permuted to VTK's order.
MshFile read_msh22(const std::filesystem::path& path) {
  std::ifstream in(path);
  MshFile out;
  std::unordered_map<long, Index> node;
  std::string line;
  while (std::getline(in, line)) {
    if (line == "$Nodes") {
      long n = 0;
      in >> n;
      for (long i = 0; i < n; ++i) {
        long tag;
        Vec3 p;
        in >> tag >> p.x >> p.y >> p.z;
        node[tag] = out.mesh.add(p);
      }
    } else if (line == "$Elements") {
      long n = 0;
      in >> n;
      for (long i = 0; i < n; ++i) {
        long tag, type, ntags;
        in >> tag >> type >> ntags;
        for (long k = 0; k < ntags; ++k) in >> tag;
        const std::map<long, int> sizes = {{2, 3}, {3, 4}, {4, 4}, {5, 8}, {6, 6}, {7, 5}};
        std::vector<Index> v(static_cast<std::size_t>(sizes.at(type)));
        for (Index& x : v) {
          long t;
          in >> t;
          x = node.at(t);
        }
        if (type == 2 || type == 3) out.surface_elements.push_back(v);
        if (type == 4) out.mesh.tets.push_back({v[0], v[1], v[2], v[3]});
        if (type == 5) out.mesh.hex.hexes.push_back({v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7]});
        if (type == 6) out.mesh.wedges.push_back({v[0], v[2], v[1], v[3], v[5], v[4]});
        if (type == 7) out.mesh.pyramids.push_back({v[0], v[1], v[2], v[3], v[4]});
      }
    }
  }
  return out;
}

// Runs Gmsh on a .geo text; the MSH 2.2 file, or nullopt without Gmsh.
std::optional<MshFile> gmsh(const std::string& name, const std::string& geo) {
#ifdef HQ_GMSH_PATH
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("hq_topology_" + name + "_" +
                                                                             std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "m.geo") << geo;
  const std::string command = std::string(HQ_GMSH_PATH) + " -3 -format msh22 -nt 1 " + (dir / "m.geo").string() +
                              " -o " + (dir / "m.msh").string() + " > " + (dir / "log").string() + " 2>&1";
  if (std::system(command.c_str()) != 0) {
    ADD_FAILURE() << "gmsh failed: " << command;
    return std::nullopt;
  }
  MshFile file = read_msh22(dir / "m.msh");
  std::filesystem::remove_all(dir);
  return file;
#else
  (void)name;
  (void)geo;
  return std::nullopt;
#endif
}

// The surface elements Gmsh wrote, split into quads and triangles, leaving
// out those with every point on the plane x = x_interface.
std::pair<std::size_t, std::size_t> outer_quads_and_triangles(const MshFile& f, double x_interface) {
  std::size_t quads = 0, tris = 0;
  for (const auto& e : f.surface_elements) {
    bool on = true;
    for (Index v : e) on = on && f.mesh.hex.points[static_cast<std::size_t>(v)].x == x_interface;
    if (on) continue;
    (e.size() == 4 ? quads : tris) += 1;
  }
  return {quads, tris};
}

// The topology of a Gmsh mesh whose interface is the plane x = 1, its
// boundary closed and outward, its boundary quads and triangles as many as
// the surface elements Gmsh wrote off the interface (returned).
std::tuple<Topology, std::size_t, std::size_t> topology_against_file(const MshFile& file) {
  Topology topo = file.mesh.topology();
  const auto [quads, tris] = outer_quads_and_triangles(file, 1.0);
  EXPECT_EQ(topo.boundary_faces.size() + topo.boundary_quads_non_hex.size(), quads);
  EXPECT_EQ(topo.boundary_triangles.size(), tris);
  expect_closed_and_oriented(topo);
  return {std::move(topo), quads, tris};
}

using test::kTwoSquares;

// A transfinite recombined box [0,1]^3 (125 hexes) next to a tetrahedral box
// [1,2] x [0,1]^2 sharing the face x = 1: Gmsh puts a pyramid on each quad.
const std::string kHexTetBoxes = R"(
lc = 0.25;
)" + std::string(kTwoSquares) + R"(
Transfinite Curve{1,2,3,4}=6; Transfinite Surface{1}; Recombine Surface{1};
a[] = Extrude{0,0,1}{Surface{1}; Layers{5}; Recombine;};
b[] = Extrude{0,0,1}{Surface{2};};
Coherence;
Physical Volume(1) = {a[1], b[1]};
Physical Surface(2) = {Surface{:}};
)";

TEST(TopologyAcrossKinds, GmshHexPyramidTetBoxes) {
  const auto file = gmsh("boxes", kHexTetBoxes);
  if (!file) GTEST_SKIP() << "gmsh not found at configure time";
  const Hybrid& m = file->mesh;
  ASSERT_EQ(m.hex.hexes.size(), 125u);
  ASSERT_EQ(m.pyramids.size(), 25u);  // one per quad of the interface
  ASSERT_GT(m.tets.size(), 100u);
  EXPECT_TRUE(m.wedges.empty());
  const auto [topo, quads, tris] = topology_against_file(*file);
  EXPECT_EQ(quads, 125u);
  EXPECT_TRUE(topo.non_conforming_faces.empty());
  EXPECT_EQ(topo.num_non_manifold_faces_non_hex, 0);
  EXPECT_TRUE(topo.unreferenced_vertices.empty());
  expect_closed_and_oriented(topo);
  EXPECT_NEAR(enclosed_volume(m.hex, topo), 2.0, 1e-12);
  // The hex edges on the interface (5 x 6 x 2 grid lines) touch pyramids.
  EXPECT_EQ(std::count(topo.edge_touches_non_hex.begin(), topo.edge_touches_non_hex.end(), 1), 60);

  // Each pyramid split into two tets along its base diagonal 0-2: the hex
  // quads of the interface now meet two triangles each.
  Hybrid split = m;
  for (const Pyramid& p : split.pyramids) {
    split.tets.push_back({p[0], p[1], p[2], p[4]});
    split.tets.push_back({p[0], p[2], p[3], p[4]});
  }
  split.pyramids.clear();
  const Topology nc = split.topology();
  EXPECT_EQ(nc.non_conforming_faces.size(), 25u);
  for (const NonConformingFace& f : nc.non_conforming_faces) {
    EXPECT_LT(f.quad_cell, 125);
    EXPECT_GE(f.triangle_cells[0], 125);
  }
  EXPECT_EQ(nc.boundary_faces.size(), topo.boundary_faces.size());
  EXPECT_EQ(nc.boundary_triangles.size(), topo.boundary_triangles.size());
  expect_closed_and_oriented(nc);
  EXPECT_NEAR(enclosed_volume(split.hex, nc), 2.0, 1e-12);
}

// A mixed surface (a recombined transfinite square beside a triangulated
// one) extruded in 3 recombined layers: hexes and wedges.
const std::string kExtrudedMixed = R"(
lc = 0.3;
)" + std::string(kTwoSquares) + R"(
Transfinite Curve{1,2,3,4}=5; Transfinite Surface{1}; Recombine Surface{1};
e[] = Extrude{0,0,0.6}{Surface{1,2}; Layers{3}; Recombine;};
Physical Volume(1) = {Volume{:}};
Physical Surface(2) = {Surface{:}};
)";

TEST(TopologyAcrossKinds, GmshExtrudedMixedSurfaceHexesAndWedges) {
  const auto file = gmsh("extruded", kExtrudedMixed);
  if (!file) GTEST_SKIP() << "gmsh not found at configure time";
  const Hybrid& m = file->mesh;
  ASSERT_EQ(m.hex.hexes.size(), 16u * 3u);
  ASSERT_GT(m.wedges.size(), 0u);
  EXPECT_TRUE(m.tets.empty());
  EXPECT_TRUE(m.pyramids.empty());
  const auto [topo, quads, tris] = topology_against_file(*file);
  EXPECT_EQ(tris, 2 * m.wedges.size() / 3);  // bottom and top of the wedge columns
  EXPECT_TRUE(topo.non_conforming_faces.empty());
  expect_closed_and_oriented(topo);
  EXPECT_NEAR(enclosed_volume(m.hex, topo), 2.0 * 0.6, 1e-12);
}

}  // namespace
}  // namespace hq
