// Higher-order cells read by their corners, and 8-node hexahedra with
// repeated corners read as the wedges, pyramids and tetrahedra they collapse
// to (docs/formats.md, "Higher-order cells" and "Collapsed hexahedra").
//
// The hybrid mesh of hybrid_mesh_files.h (2 hexahedra, 2 wedges, a pyramid,
// 2 tetrahedra) is written with higher-order cells in every text format:
// its corner ids stay, the other nodes (edge midpoints, then face and body
// points) are new points after them. Each file must read to the linear
// mesh's cells, in VTK order, with the format's source index, and one
// warning naming the types and counts. The collapse patterns are made here
// from a hand-written list of the hexahedron's faces and edges, not from
// the reader's rotations, on a perturbed cube: every one must give a cell
// of the right kind with a positive volume by hybrid_mesh_files.h's split.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include "error_text.h"
#include "hqview/io/abaqus_reader.h"
#include "hqview/io/cell_reading.h"
#include "hqview/io/gmsh_reader.h"
#include "hqview/io/medit_reader.h"
#include "hqview/io/vtk_legacy_reader.h"
#include "hqview/io/vtu_reader.h"
#include "hybrid_mesh_files.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::error_text;
using test::HybridMesh;

// The edges of each linear kind in VTK's quadratic-cell order.
std::vector<std::array<int, 2>> edges_of(int vtk_type) {
  switch (vtk_type) {
    case 12:
      return {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    case 13:
      return {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}};
    case 14:
      return {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 4}, {1, 4}, {2, 4}, {3, 4}};
    default:
      return {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  }
}

// How one linear kind is written as a higher-order cell: its VTK type, Gmsh
// type, Abaqus element name and node count.
struct HigherOrderType {
  int vtk;
  int gmsh;
  const char* abaqus;
  int num_nodes;
  int gmsh_num_nodes = 0;  // 0: num_nodes (Gmsh reads the first so many)
};

// Quadratic (serendipity): VTK 24-27, Gmsh 11, 17, 18, 19, Abaqus C3D10M,
// C3D20R, C3D15 (no Abaqus pyramid of second order: C3D5).
HigherOrderType quadratic(int vtk_type) {
  switch (vtk_type) {
    case 12:
      return {25, 17, "C3D20R", 20};
    case 13:
      return {26, 18, "C3D15", 15};
    case 14:
      return {27, 19, "C3D5", 13};
    default:
      return {24, 11, "C3D10M", 10};
  }
}

// Full second order: triquadratic hexahedron 29, biquadratic-quadratic wedge
// 32, triquadratic pyramid 37, Lagrange tetrahedron 71 (order 2); Gmsh 12,
// 13, 14, 11; Abaqus C3D27 (27 nodes), C3D15V (18), C3D10.
HigherOrderType full(int vtk_type) {
  switch (vtk_type) {
    case 12:
      return {29, 12, "C3D27", 27};
    case 13:
      return {32, 13, "C3D15V", 18};
    case 14:
      return {37, 14, "C3D5", 19, 14};
    default:
      return {71, 11, "C3D10", 10};
  }
}

// Lagrange cells of order 3 (hexahedron 64 points, tetrahedron 20, wedge
// 40) and 2 (pyramid 14); Bezier would read the same.
HigherOrderType lagrange(int vtk_type) {
  switch (vtk_type) {
    case 12:
      return {72, 92, "C3D8", 64};
    case 13:
      return {73, 90, "C3D6", 40};
    case 14:
      return {74, 14, "C3D5", 14};
    default:
      return {71, 29, "C3D4", 20};
  }
}

struct HigherOrderCell {
  int linear_type;
  std::vector<int> vtk;    // corners, VTK order
  HigherOrderType type;
  std::vector<int> extra;  // the other nodes' ids
};

struct HigherOrderMesh {
  std::vector<std::array<double, 3>> points;
  std::vector<HigherOrderCell> cells;
};

// The hybrid mesh's cells with new nodes: edge midpoints, then points near
// the centroid, each a new point after the mesh's.
HigherOrderMesh higher_order(const HybridMesh& m, HigherOrderType (*type_of)(int)) {
  HigherOrderMesh out{m.points, {}};
  for (const test::HybridCell& c : m.cells) {
    HigherOrderCell cell{c.vtk_type, c.vtk, type_of(c.vtk_type), {}};
    const int extra = cell.type.num_nodes - static_cast<int>(c.vtk.size());
    const std::vector<std::array<int, 2>> edges = edges_of(c.vtk_type);
    std::array<double, 3> centroid{};
    for (const int v : c.vtk)
      for (int k = 0; k < 3; ++k) centroid[k] += m.points[static_cast<std::size_t>(v)][k] / double(c.vtk.size());
    for (int i = 0; i < extra; ++i) {
      std::array<double, 3> p = centroid;
      if (i < static_cast<int>(edges.size())) {
        const auto& a = m.points[static_cast<std::size_t>(c.vtk[static_cast<std::size_t>(edges[i][0])])];
        const auto& b = m.points[static_cast<std::size_t>(c.vtk[static_cast<std::size_t>(edges[i][1])])];
        for (int k = 0; k < 3; ++k) p[k] = (a[k] + b[k]) / 2;
      } else {
        p[0] += 1e-3 * i;
      }
      cell.extra.push_back(static_cast<int>(out.points.size()));
      out.points.push_back(p);
    }
    out.cells.push_back(cell);
  }
  return out;
}

// All node ids of a cell in a format's order: its corners (wedges flipped
// for Gmsh and Abaqus), then the others.
std::vector<int> nodes_of(const HigherOrderCell& c, bool wedge_flipped) {
  std::vector<int> nodes = c.linear_type == 13 && wedge_flipped ? test::flipped_wedge(c.vtk) : c.vtk;
  nodes.insert(nodes.end(), c.extra.begin(), c.extra.end());
  return nodes;
}
std::vector<int> gmsh_nodes_of(const HigherOrderCell& c) {
  std::vector<int> nodes = nodes_of(c, true);
  if (c.type.gmsh_num_nodes > 0) nodes.resize(static_cast<std::size_t>(c.type.gmsh_num_nodes));
  return nodes;
}

std::string write_vtk(const HigherOrderMesh& m) {
  std::string s = "# vtk DataFile Version 4.2\nq\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS " +
                  std::to_string(m.points.size()) + " double\n";
  for (const auto& p : m.points) s += test::coordinates(p) + "\n";
  std::size_t size = 0;
  for (const HigherOrderCell& c : m.cells) size += 1 + static_cast<std::size_t>(c.type.num_nodes);
  s += "CELLS " + std::to_string(m.cells.size()) + " " + std::to_string(size) + "\n";
  for (const HigherOrderCell& c : m.cells)
    s += std::to_string(c.type.num_nodes) + " " + test::ids(nodes_of(c, false), 0) + "\n";
  s += "CELL_TYPES " + std::to_string(m.cells.size()) + "\n";
  for (const HigherOrderCell& c : m.cells) s += std::to_string(c.type.vtk) + "\n";
  return s;
}

std::string write_vtu(const HigherOrderMesh& m) {
  std::string points, connectivity, offsets, types;
  for (const auto& p : m.points) points += test::coordinates(p) + " ";
  int offset = 0;
  for (const HigherOrderCell& c : m.cells) {
    connectivity += test::ids(nodes_of(c, false), 0) + " ";
    offset += c.type.num_nodes;
    offsets += std::to_string(offset) + " ";
    types += std::to_string(c.type.vtk) + " ";
  }
  return test::vtu_text(m.points.size(), m.cells.size(), points, connectivity, offsets, types);
}

std::string gmsh_nodes_section(const HigherOrderMesh& m) {
  std::string s = "$Nodes\n" + std::to_string(m.points.size()) + "\n";
  for (std::size_t i = 0; i < m.points.size(); ++i) s += std::to_string(i + 1) + " " + test::coordinates(m.points[i]) + "\n";
  return s + "$EndNodes\n";
}

// MSH 2.2 ASCII, element tags 101, 102, ...
std::string write_gmsh22(const HigherOrderMesh& m) {
  std::string s = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n" + gmsh_nodes_section(m) + "$Elements\n" +
                  std::to_string(m.cells.size()) + "\n";
  for (std::size_t e = 0; e < m.cells.size(); ++e)
    s += std::to_string(101 + e) + " " + std::to_string(m.cells[e].type.gmsh) + " 2 0 1 " +
         test::ids(gmsh_nodes_of(m.cells[e]), 1) + "\n";
  return s + "$EndElements\n";
}

// MSH 2.2 binary (little-endian): one element block per element.
std::string write_gmsh22_binary(const HigherOrderMesh& m) {
  std::string s = "$MeshFormat\n2.2 1 8\n";
  const auto put_int = [&](std::int32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); };
  put_int(1);
  s += "\n$EndMeshFormat\n$Nodes\n" + std::to_string(m.points.size()) + "\n";
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    put_int(static_cast<std::int32_t>(i + 1));
    s.append(reinterpret_cast<const char*>(m.points[i].data()), 24);
  }
  s += "\n$EndNodes\n$Elements\n" + std::to_string(m.cells.size()) + "\n";
  for (std::size_t e = 0; e < m.cells.size(); ++e) {
    put_int(m.cells[e].type.gmsh);
    put_int(1);  // elements that follow
    put_int(0);  // tags
    put_int(static_cast<std::int32_t>(101 + e));
    for (const int id : gmsh_nodes_of(m.cells[e])) put_int(id + 1);
  }
  return s + "\n$EndElements\n";
}

// MSH 4.1 ASCII: one block per element, tags as 2.2.
std::string write_gmsh41(const HigherOrderMesh& m) {
  const std::size_t n = m.points.size();
  std::string s = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 " + std::to_string(n) + " 1 " + std::to_string(n) +
                  "\n3 1 0 " + std::to_string(n) + "\n";
  for (std::size_t i = 0; i < n; ++i) s += std::to_string(i + 1) + "\n";
  for (const auto& p : m.points) s += test::coordinates(p) + "\n";
  s += "$EndNodes\n$Elements\n" + std::to_string(m.cells.size()) + " " + std::to_string(m.cells.size()) + " 101 " +
       std::to_string(100 + m.cells.size()) + "\n";
  for (std::size_t e = 0; e < m.cells.size(); ++e)
    s += "3 1 " + std::to_string(m.cells[e].type.gmsh) + " 1\n" + std::to_string(101 + e) + " " +
         test::ids(gmsh_nodes_of(m.cells[e]), 1) + "\n";
  return s + "$EndElements\n";
}

// Abaqus: one *ELEMENT block per element, labels 11, 12, ...; a record of
// more than 10 nodes continues on the next line (its line ends with a comma),
// as Abaqus writes them.
std::string write_abaqus(const HigherOrderMesh& m) {
  std::string s = "*NODE\n";
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const auto& p = m.points[i];
    s += std::to_string(i + 1) + ", " + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]) + "\n";
  }
  for (std::size_t e = 0; e < m.cells.size(); ++e) {
    const HigherOrderCell& c = m.cells[e];
    std::vector<int> nodes = nodes_of(c, true);
    const std::string name = c.type.abaqus;
    if (name == "C3D5" || name == "C3D8" || name == "C3D6" || name == "C3D4") nodes.resize(c.vtk.size());
    s += "*ELEMENT, TYPE=" + name + "\n" + std::to_string(11 + e);
    for (std::size_t j = 0; j < nodes.size(); ++j) s += std::string(j > 0 && j % 10 == 0 ? ",\n" : ", ") + std::to_string(nodes[j] + 1);
    s += "\n";
  }
  return s;
}

// MEDIT: hexahedra of 27 vertices as HexahedraQ2, of 20 in a Hexahedra
// section (as Gmsh writes them), 10-vertex tetrahedra as TetrahedraP2;
// prisms (flipped) and pyramids by their corners. Source index: the
// 1-based entry of the section.
std::string write_medit(const HigherOrderMesh& m) {
  std::string s = "MeshVersionFormatted 2\nDimension 3\nVertices\n" + std::to_string(m.points.size()) + "\n";
  for (const auto& p : m.points) s += test::coordinates(p) + " 0\n";
  for (const int type : {12, 10, 13, 14}) {
    std::string keyword, lines;
    int n = 0;
    for (const HigherOrderCell& c : m.cells) {
      if (c.linear_type != type) continue;
      std::vector<int> nodes = nodes_of(c, true);
      if (type == 12) keyword = c.type.num_nodes == 27 ? "HexahedraQ2" : "Hexahedra";
      if (type == 10) keyword = c.type.num_nodes == 10 ? "TetrahedraP2" : "Tetrahedra";
      if (type == 13 || type == 14) {
        keyword = type == 13 ? "Prisms" : "Pyramids";
        nodes.resize(c.vtk.size());
      }
      lines += test::ids(nodes, 1) + " " + std::to_string(++n) + "\n";
    }
    s += keyword + "\n" + std::to_string(n) + "\n" + lines;
  }
  return s + "End\n";
}

std::int64_t section_entry(std::size_t e) {  // the hybrid mesh's cells, by kind, in file order
  const test::HybridMesh m = test::hybrid_mesh();
  std::int64_t i = 0;
  for (std::size_t f = 0; f <= e; ++f)
    if (m.cells[f].vtk_type == m.cells[e].vtk_type) ++i;
  return i;
}

// The corners of a block of a read mesh.
template <CellKind K>
std::vector<std::vector<int>> corners_of(const Mesh& mesh) {
  std::vector<std::vector<int>> out;
  for (const auto& c : cell_block<K>(mesh)) out.emplace_back(c.begin(), c.end());
  return out;
}

// The read mesh has the hybrid mesh's cells (VTK order, by kind, in file
// order) with source indices source(e) of their file position e.
void expect_hybrid_cells(const Mesh& mesh, const HybridMesh& m, std::int64_t (*source)(std::size_t)) {
  const auto check = [&](CellKind kind, const std::vector<std::vector<int>>& read) {
    SCOPED_TRACE(std::string(cell_kind_name(kind)));
    std::vector<std::vector<int>> expected;
    std::vector<std::int64_t> expected_source, read_source;
    for (std::size_t e = 0; e < m.cells.size(); ++e)
      if (m.cells[e].vtk_type == cell_kind_vtk_type(kind)) {
        expected.push_back(m.cells[e].vtk);
        expected_source.push_back(source(e));
      }
    for (std::size_t i = 0; i < read.size(); ++i) read_source.push_back(cell_source_index(mesh, kind, i));
    EXPECT_EQ(read, expected);
    EXPECT_EQ(read_source, expected_source);
    std::vector<std::array<double, 3>> points;
    for (const Vec3& p : mesh.points) points.push_back({p.x, p.y, p.z});
    for (const auto& cell : read) EXPECT_GT(test::split_volume(points, cell_kind_vtk_type(kind), cell).min_tet, 0.0);
  };
  check(CellKind::hex, corners_of<CellKind::hex>(mesh));
  check(CellKind::tet, corners_of<CellKind::tet>(mesh));
  check(CellKind::wedge, corners_of<CellKind::wedge>(mesh));
  check(CellKind::pyramid, corners_of<CellKind::pyramid>(mesh));
}

std::int64_t file_position(std::size_t e) { return static_cast<std::int64_t>(e); }
std::int64_t gmsh_tag(std::size_t e) { return static_cast<std::int64_t>(101 + e); }
std::int64_t abaqus_label(std::size_t e) { return static_cast<std::int64_t>(11 + e); }

TEST(HigherOrderCells, QuadraticMeshInEveryFormatReadsToTheLinearCells) {
  const HybridMesh m = test::hybrid_mesh();
  const HigherOrderMesh q = higher_order(m, quadratic);
  const std::string tail =
      "): their other nodes are ignored, so curved cells are measured as straight-sided ones";
  {
    const LoadedMesh loaded = read_vtk_legacy(write_vtk(q), "q.vtk");
    expect_hybrid_cells(loaded.mesh, m, file_position);
    EXPECT_EQ(loaded.mesh.points.size(), q.points.size());
    EXPECT_EQ(loaded.warnings, std::vector<std::string>{"q.vtk: 7 higher-order cells read by their corner nodes only "
                                                        "(2 of type 24, 2 of type 25, 2 of type 26, 1 of type 27" +
                                                        tail});
  }
  {
    const LoadedMesh loaded = read_vtu(write_vtu(q), "q.vtu");
    expect_hybrid_cells(loaded.mesh, m, file_position);
    EXPECT_EQ(loaded.warnings, std::vector<std::string>{"q.vtu: 7 higher-order cells read by their corner nodes only "
                                                        "(2 of type 24, 2 of type 25, 2 of type 26, 1 of type 27" +
                                                        tail});
  }
  const std::string gmsh_warning =
      ": 7 higher-order elements read by their corner nodes only (2 of type 11, 2 of type 17, 2 of type 18, 1 of "
      "type 19" +
      tail;
  for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
           {"q22.msh", write_gmsh22(q)}, {"q22b.msh", write_gmsh22_binary(q)}, {"q41.msh", write_gmsh41(q)}}) {
    SCOPED_TRACE(name);
    const LoadedMesh loaded = read_gmsh(text, name);
    expect_hybrid_cells(loaded.mesh, m, gmsh_tag);
    EXPECT_EQ(loaded.warnings, std::vector<std::string>{name + gmsh_warning});
  }
  {
    const LoadedMesh loaded = read_abaqus(write_abaqus(q), "q.inp");
    expect_hybrid_cells(loaded.mesh, m, abaqus_label);
    EXPECT_EQ(loaded.warnings, std::vector<std::string>{"q.inp: 6 higher-order elements read by their corner nodes "
                                                        "only (2 of type C3D10M, 2 of type C3D15, 2 of type C3D20R" +
                                                        tail});
  }
  {
    const LoadedMesh loaded = read_medit(write_medit(q), "q.mesh");
    expect_hybrid_cells(loaded.mesh, m, section_entry);
    EXPECT_EQ(loaded.warnings, std::vector<std::string>{"q.mesh: 4 higher-order cells read by their corner nodes only "
                                                        "(2 of type Hexahedra (20 vertices), 2 of type TetrahedraP2" +
                                                        tail});
  }
}

TEST(HigherOrderCells, FullSecondOrderAndLagrangeCellsReadToTheLinearCells) {
  const HybridMesh m = test::hybrid_mesh();
  for (const auto& [what, type_of] : std::vector<std::pair<std::string, HigherOrderType (*)(int)>>{
           {"full", full}, {"lagrange", lagrange}}) {
    SCOPED_TRACE(what);
    const HigherOrderMesh q = higher_order(m, type_of);
    const LoadedMesh vtk = read_vtk_legacy(write_vtk(q), "q.vtk");
    expect_hybrid_cells(vtk.mesh, m, file_position);
    ASSERT_EQ(vtk.warnings.size(), 1u);
    expect_hybrid_cells(read_vtu(write_vtu(q), "q.vtu").mesh, m, file_position);
    expect_hybrid_cells(read_gmsh(write_gmsh22(q), "q.msh").mesh, m, gmsh_tag);
    expect_hybrid_cells(read_gmsh(write_gmsh22_binary(q), "q.msh").mesh, m, gmsh_tag);
    expect_hybrid_cells(read_abaqus(write_abaqus(q), "q.inp").mesh, m, abaqus_label);
    if (what == "full") {
      const LoadedMesh medit = read_medit(write_medit(q), "q.mesh");
      expect_hybrid_cells(medit.mesh, m, section_entry);
      EXPECT_EQ(medit.warnings, std::vector<std::string>{"q.mesh: 4 higher-order cells read by their corner nodes only "
                                                         "(2 of type HexahedraQ2, 2 of type TetrahedraP2): their other "
                                                         "nodes are ignored, so curved cells are measured as "
                                                         "straight-sided ones"});
    }
  }
  EXPECT_EQ(read_vtk_legacy(write_vtk(higher_order(m, full)), "q.vtk").warnings,
            std::vector<std::string>{"q.vtk: 7 higher-order cells read by their corner nodes only (2 of type 29, 2 of "
                                     "type 32, 1 of type 37, 2 of type 71): their other nodes are ignored, so curved "
                                     "cells are measured as straight-sided ones"});
  EXPECT_EQ(read_abaqus(write_abaqus(higher_order(m, full)), "q.inp").warnings,
            std::vector<std::string>{"q.inp: 6 higher-order elements read by their corner nodes only (2 of type "
                                     "C3D10, 2 of type C3D15V, 2 of type C3D27): their other nodes are ignored, so "
                                     "curved cells are measured as straight-sided ones"});
}

// Gmsh 4.8 writes its 14-node pyramid as a VTK_PYRAMID of 14 points.
TEST(HigherOrderCells, GmshsFourteenPointVtkPyramidIsReadByItsCorners) {
  const HybridMesh m = test::hybrid_mesh();
  HigherOrderMesh q = higher_order(m, lagrange);
  for (HigherOrderCell& c : q.cells)
    if (c.linear_type == 14) c.type.vtk = 14;
  const LoadedMesh loaded = read_vtk_legacy(write_vtk(q), "q.vtk");
  expect_hybrid_cells(loaded.mesh, m, file_position);
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_NE(loaded.warnings[0].find("1 of type 14 (14 points, as Gmsh writes a second-order pyramid)"),
            std::string::npos)
      << loaded.warnings[0];
}

// A wrong node count of a higher-order type, or a bad id among the nodes
// that are not corners: path:line and what is wrong.
TEST(HigherOrderCells, BadHigherOrderCellsAreRefused) {
  const std::string points =
      "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 10 double\n"
      "0 0 0 1 0 0 0 1 0 0 0 1 .5 0 0 .5 .5 0 0 .5 0 0 0 .5 .5 0 .5 0 .5 .5\n";
  const auto vtk = [&](const std::string& cells) {
    return error_text<ParseError>([&] { read_vtk_legacy(points + cells, "m.vtk"); });
  };
  EXPECT_EQ(vtk("CELLS 1 10\n9 0 1 2 3 4 5 6 7 8\nCELL_TYPES 1\n24\n"),
            "m.vtk:8: cell 0 has type 24 (quadratic tetra) but 9 points, expected 10");
  EXPECT_EQ(vtk("CELLS 1 10\n9 0 1 2 3 4 5 6 7 8\nCELL_TYPES 1\n71\n"),
            "m.vtk:8: cell 0 has type 71 (Lagrange tetrahedron) but 9 points, expected 4, 10, 15, 20, 35, ... (a "
            "Lagrange tetrahedron's)");
  EXPECT_EQ(vtk("CELLS 1 11\n10 0 1 2 3 4 5 6 7 8 10\nCELL_TYPES 1\n24\n"),
            "m.vtk:8: point id 10 out of range [0, 10) (cell 0)");
  EXPECT_EQ(vtk("CELLS 1 11\n10 0 1 2 2 4 5 6 7 8 9\nCELL_TYPES 1\n24\n"), "m.vtk:8: point id 2 repeated (cell 0)");
  EXPECT_EQ(vtk("CELLS 1 10\n9 0 1 2 3 4 5 6 7 8\nCELL_TYPES 1\n72\n"),
            "m.vtk:8: cell 0 has type 72 (Lagrange hexahedron) but 9 points, expected 8, 12, 16, 18, 20, ... (a "
            "Lagrange hexahedron's)");
  // Mid-edge nodes may repeat each other (only corners are cells' vertices).
  EXPECT_EQ(read_vtk_legacy(points + "CELLS 1 11\n10 0 1 2 3 4 4 4 4 4 4\nCELL_TYPES 1\n24\n", "m.vtk").mesh.tets.size(),
            1u);

  const auto gmsh = [](const std::string& element) {
    return error_text<ParseError>([&] {
      read_gmsh("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
                "$Elements\n1\n" +
                    element + "\n$EndElements\n",
                "m.msh");
    });
  };
  EXPECT_EQ(gmsh("7 11 2 0 1 1 2 3 4 1 2 3 4 1"), "m.msh:13: expected 10 node tags for tetrahedron 7 (type 11), got 9");
  EXPECT_EQ(gmsh("7 11 2 0 1 1 2 3 4 1 2 3 4 1 9"), "m.msh:13: node tag 9 is not defined (element 7)");

  const auto abaqus = [](const std::string& elements) {
    return error_text<ParseError>(
        [&] { read_abaqus("*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n" + elements, "m.inp"); });
  };
  EXPECT_EQ(abaqus("*ELEMENT, TYPE=C3D10\n1, 1, 2, 3, 4, 1, 2, 3, 4, 1\n"),
            "m.inp:7: expected an element id and 10 node ids, got 10 fields (C3D10)");
  EXPECT_EQ(abaqus("*ELEMENT, TYPE=C3D15V\n1, 1, 2, 3, 4, 1, 2, 3, 4, 1, 2,\n3, 4\n"),
            "m.inp:8: expected an element id and 15 to 18 node ids, got 13 fields (C3D15V)");
  EXPECT_EQ(abaqus("*ELEMENT, TYPE=C3D10H\n1, 1, 2, 3, 4, 1, 2, 3, 4, 1, 5\n"),
            "m.inp:7: node 5 is not defined (element 1)");

  const auto medit = [](const std::string& sections) {
    return error_text<ParseError>([&] {
      read_medit("MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n" + sections,
                 "m.mesh");
    });
  };
  EXPECT_EQ(medit("TetrahedraP2\n1\n1 2 3 4 1 2 3 4 1 2\nEnd\n"),
            "m.mesh:11: expected 10 vertex ids and a reference, got 10 values (tetrahedron 1 of 1)");
  EXPECT_EQ(medit("TetrahedraP2\n1\n1 2 3 4 1 2 3 4 1 5 0\n"),
            "m.mesh:11: vertex id 5 out of range [1, 4] (tetrahedron 1 of 1)");
  EXPECT_EQ(medit("TetrahedraP2\n1\n1 2 3 3 1 2 3 4 1 2 0\n"), "m.mesh:11: vertex id 3 repeated (tetrahedron 1 of 1)");
  EXPECT_EQ(medit("Tetrahedra\n1\n1 2 3 4 0\nTetrahedraP2\n0\n"),
            "m.mesh:12: TetrahedraP2 section beside the Tetrahedra section at line 9 (one section per cell kind)");
}

// --- collapsed hexahedra ------------------------------------------------------

// A valid hexahedron: the unit cube, perturbed (no two faces parallel).
std::vector<std::array<double, 3>> perturbed_cube() {
  return {{0, 0, 0}, {1.1, 0.05, 0}, {1.2, 1, 0.1}, {-0.1, 0.9, 0},
          {0.05, 0, 1}, {1, -0.1, 1.2}, {1.1, 1.1, 1}, {0, 1, 0.9}};
}

// The hexahedron's faces, each as a cycle of its corners, and which are
// opposite, written out by hand (VTK_HEXAHEDRON numbering).
constexpr std::array<std::array<int, 4>, 6> kFaces = {{
    {0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 2, 6, 7}, {1, 2, 6, 5}, {0, 3, 7, 4},
}};
constexpr int kOpposite[6] = {1, 0, 3, 2, 5, 4};

struct Pattern {
  std::array<Index, 8> ids;
  CellKind kind;
};

// Every collapse pattern: a face to one of its corners (pyramid); two
// opposite edges of a face, each to one end (wedge); a face to a corner and
// one edge of the opposite face (tetrahedron).
std::vector<Pattern> collapse_patterns() {
  std::vector<Pattern> out;
  const auto identity = [] {
    std::array<Index, 8> ids;
    for (int i = 0; i < 8; ++i) ids[static_cast<std::size_t>(i)] = i;
    return ids;
  };
  for (int f = 0; f < 6; ++f) {
    const auto& face = kFaces[static_cast<std::size_t>(f)];
    std::array<Index, 8> pyramid = identity();
    for (const int v : face) pyramid[static_cast<std::size_t>(v)] = face[0];
    out.push_back({pyramid, CellKind::pyramid});
    for (int k = 0; k < 2; ++k) {  // edges (k, k+1) and (k+2, k+3) of the cycle
      std::array<Index, 8> wedge = identity();
      wedge[static_cast<std::size_t>(face[static_cast<std::size_t>(k + 1)])] = face[static_cast<std::size_t>(k)];
      wedge[static_cast<std::size_t>(face[static_cast<std::size_t>((k + 3) % 4)])] = face[static_cast<std::size_t>(k + 2)];
      out.push_back({wedge, CellKind::wedge});
    }
    const auto& other = kFaces[static_cast<std::size_t>(kOpposite[f])];
    for (int k = 0; k < 4; ++k) {
      std::array<Index, 8> tet = pyramid;
      tet[static_cast<std::size_t>(other[static_cast<std::size_t>((k + 1) % 4)])] = other[static_cast<std::size_t>(k)];
      out.push_back({tet, CellKind::tet});
    }
  }
  return out;
}

TEST(CollapsedHexahedra, EveryCollapsePatternGivesAValidCellOfItsKind) {
  const std::vector<std::array<double, 3>> p = perturbed_cube();
  const std::vector<Pattern> patterns = collapse_patterns();
  ASSERT_EQ(patterns.size(), 6u + 12u + 24u);
  for (const Pattern& pattern : patterns) {
    SCOPED_TRACE(test::ids(std::vector<int>(pattern.ids.begin(), pattern.ids.end()), 0));
    const std::optional<detail::CollapsedHex> collapsed = detail::collapse_hex(pattern.ids);
    ASSERT_TRUE(collapsed.has_value());
    EXPECT_EQ(collapsed->kind, pattern.kind);
    const int n = cell_kind_num_corners(pattern.kind);
    const std::vector<int> corners(collapsed->corners.begin(), collapsed->corners.begin() + n);
    EXPECT_EQ(std::set<int>(corners.begin(), corners.end()), std::set<int>(pattern.ids.begin(), pattern.ids.end()));
    EXPECT_GT(test::split_volume(p, cell_kind_vtk_type(pattern.kind), corners).min_tet, 0.0);
  }
}

TEST(CollapsedHexahedra, OtherRepeatedCornersAreNotACollapse) {
  for (const std::array<Index, 8>& ids : std::vector<std::array<Index, 8>>{
           {0, 1, 2, 3, 4, 5, 6, 7},  // none repeated
           {0, 0, 2, 3, 4, 5, 6, 7},  // one edge
           {0, 1, 2, 3, 4, 5, 0, 7},  // a diagonal
           {0, 0, 0, 0, 0, 0, 0, 0},  // one point
           {0, 0, 2, 3, 4, 5, 6, 6},  // two parallel edges not on one face
           {0, 0, 0, 3, 4, 5, 6, 7},  // two edges of one face meeting at a corner
           {0, 1, 2, 2, 4, 5, 6, 6},  // (control: the ANSYS wedge)
       }) {
    const bool is_control = ids[2] == ids[3] && ids[6] == ids[7] && ids[0] != ids[1];
    EXPECT_EQ(detail::collapse_hex(ids).has_value(), is_control) << test::ids(std::vector<int>(ids.begin(), ids.end()), 0);
  }
}

// The documented patterns (1-based: ANSYS's wedge 3=4, 7=8 and tetrahedron
// 3=4, 5=6=7=8; the pyramid 5=6=7=8) in each format that writes hexahedra,
// with the warning; any other repetition is refused as before.
TEST(CollapsedHexahedra, EveryFormatReadsThemAsTheirKind) {
  const std::vector<std::array<double, 3>> p = perturbed_cube();
  const std::vector<std::vector<int>> hexes = {
      {0, 1, 2, 2, 4, 5, 6, 6}, {0, 1, 2, 3, 4, 4, 4, 4}, {0, 1, 2, 2, 4, 4, 4, 4}, {0, 1, 2, 3, 4, 5, 6, 7}};
  std::string vtk = "# vtk DataFile Version 4.2\nc\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n";
  std::string gmsh = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n8\n";
  std::string abaqus = "*NODE\n";
  for (std::size_t i = 0; i < p.size(); ++i) {
    vtk += test::coordinates(p[i]) + "\n";
    gmsh += std::to_string(i + 1) + " " + test::coordinates(p[i]) + "\n";
    abaqus += std::to_string(i + 1) + ", " + std::to_string(p[i][0]) + ", " + std::to_string(p[i][1]) + ", " +
              std::to_string(p[i][2]) + "\n";
  }
  vtk += "CELLS 4 36\n";
  gmsh += "$EndNodes\n$Elements\n4\n";
  abaqus += "*ELEMENT, TYPE=C3D8R\n";
  for (std::size_t e = 0; e < hexes.size(); ++e) {
    vtk += "8 " + test::ids(hexes[e], 0) + "\n";
    gmsh += std::to_string(101 + e) + " 5 2 0 1 " + test::ids(hexes[e], 1) + "\n";
    abaqus += std::to_string(11 + e) + ", " + test::ids(hexes[e], 1, ", ") + "\n";
  }
  vtk += "CELL_TYPES 4\n12\n12\n12\n12\n";
  gmsh += "$EndElements\n";
  const auto expect = [&](const LoadedMesh& loaded, const std::string& warning, std::int64_t (*source)(std::size_t)) {
    ASSERT_EQ(loaded.mesh.hexes.size(), 1u);
    ASSERT_EQ(loaded.mesh.wedges.size(), 1u);
    ASSERT_EQ(loaded.mesh.pyramids.size(), 1u);
    ASSERT_EQ(loaded.mesh.tets.size(), 1u);
    // The wedge's triangles (0,2,1) and (4,6,5) in VTK order, its base (0,1,2,3), its (0,1,2,4).
    EXPECT_EQ(loaded.mesh.wedges[0], (CellCorners<CellKind::wedge>{0, 2, 1, 4, 6, 5}));
    EXPECT_EQ(loaded.mesh.pyramids[0], (CellCorners<CellKind::pyramid>{0, 1, 2, 3, 4}));
    EXPECT_EQ(loaded.mesh.tets[0], (CellCorners<CellKind::tet>{0, 1, 2, 4}));
    EXPECT_EQ(cell_source_index(loaded.mesh, CellKind::wedge, 0), source(0));
    EXPECT_EQ(cell_source_index(loaded.mesh, CellKind::pyramid, 0), source(1));
    EXPECT_EQ(cell_source_index(loaded.mesh, CellKind::tet, 0), source(2));
    EXPECT_EQ(cell_source_index(loaded.mesh, CellKind::hex, 0), source(3));
    EXPECT_GT(test::split_volume(p, 13, {0, 2, 1, 4, 6, 5}).min_tet, 0.0);
    EXPECT_EQ(loaded.warnings, std::vector<std::string>{warning});
  };
  expect(read_vtk_legacy(vtk, "c.vtk"),
         "c.vtk: 3 hexahedra with repeated corners read as the cells they collapse to (1 wedge, 1 pyramid, 1 "
         "tetrahedron): cells 0, 1, 2",
         file_position);
  expect(read_gmsh(gmsh, "c.msh"),
         "c.msh: 3 hexahedra with repeated corners read as the cells they collapse to (1 wedge, 1 pyramid, 1 "
         "tetrahedron): elements 101, 102, 103",
         gmsh_tag);
  expect(read_abaqus(abaqus, "c.inp"),
         "c.inp: 3 hexahedra with repeated corners read as the cells they collapse to (1 wedge, 1 pyramid, 1 "
         "tetrahedron): elements 11, 12, 13",
         abaqus_label);

  // Another repetition: refused with the message of a repeated node.
  const auto bad = [&](const std::string& from, const std::string& to) {
    std::string text = from == "c.vtk" ? vtk : from == "c.msh" ? gmsh : abaqus;
    const std::size_t at = text.find(to.substr(0, to.find('|')));
    text.replace(at, to.find('|'), to.substr(to.find('|') + 1));
    return text;
  };
  EXPECT_EQ(error_text<ParseError>([&] { read_vtk_legacy(bad("c.vtk", "8 0 1 2 2 4 5 6 6|8 0 1 2 2 4 5 6 0"), "c.vtk"); }),
            "c.vtk:15: point id 2 repeated (cell 0)");
  EXPECT_EQ(error_text<ParseError>([&] { read_gmsh(bad("c.msh", "1 2 3 3 5 6 7 7|1 2 3 3 5 6 7 1"), "c.msh"); }),
            "c.msh:17: node tag 3 repeated (element 101)");
  EXPECT_EQ(error_text<ParseError>([&] { read_abaqus(bad("c.inp", "1, 2, 3, 3, 5, 6, 7, 7|1, 2, 3, 3, 5, 5, 7, 7"), "c.inp"); }),
            "c.inp:11: node 3 repeated (element 11)");
}

// MEDIT: collapsed entries of a Hexahedra section move to their kind's
// block with their Hexahedra entry as source index, after the entries of
// that kind's own section (a Prisms entry here); the hexahedra left keep
// their entry numbers.
TEST(CollapsedHexahedra, MeditHexahedraMoveToTheirKind) {
  const std::vector<std::array<double, 3>> p = perturbed_cube();
  std::string text = "MeshVersionFormatted 2\nDimension 3\nVertices\n8\n";
  for (const auto& q : p) text += test::coordinates(q) + " 0\n";
  text += "Prisms\n1\n1 2 3 5 6 7 0\nHexahedra\n4\n1 2 3 3 5 6 7 7 0\n1 2 3 4 5 6 7 8 0\n1 2 3 4 5 5 5 5 0\n"
          "1 2 3 3 5 5 5 5 0\nEnd\n";
  const LoadedMesh loaded = read_medit(text, "c.mesh");
  ASSERT_EQ(loaded.mesh.hexes.size(), 1u);
  ASSERT_EQ(loaded.mesh.wedges.size(), 2u);
  ASSERT_EQ(loaded.mesh.pyramids.size(), 1u);
  ASSERT_EQ(loaded.mesh.tets.size(), 1u);
  // The Prisms entry (MEDIT's order, flipped) and the collapsed hexahedron give the same wedge.
  EXPECT_EQ(loaded.mesh.wedges[0], (CellCorners<CellKind::wedge>{0, 2, 1, 4, 6, 5}));
  EXPECT_EQ(loaded.mesh.wedges[1], (CellCorners<CellKind::wedge>{0, 2, 1, 4, 6, 5}));
  EXPECT_EQ(loaded.mesh.pyramids[0], (CellCorners<CellKind::pyramid>{0, 1, 2, 3, 4}));
  EXPECT_EQ(loaded.mesh.tets[0], (CellCorners<CellKind::tet>{0, 1, 2, 4}));
  EXPECT_EQ(loaded.mesh.source_index[static_cast<std::size_t>(CellKind::hex)], (std::vector<std::int64_t>{2}));
  EXPECT_EQ(loaded.mesh.source_index[static_cast<std::size_t>(CellKind::wedge)], (std::vector<std::int64_t>{1, 1}));
  EXPECT_EQ(cell_source_index(loaded.mesh, CellKind::pyramid, 0), 3);
  EXPECT_EQ(cell_source_index(loaded.mesh, CellKind::tet, 0), 4);
  EXPECT_EQ(loaded.warnings, std::vector<std::string>{"c.mesh: 3 hexahedra with repeated corners read as the cells "
                                                      "they collapse to (1 wedge, 1 pyramid, 1 tetrahedron): cells "
                                                      "1, 3, 4"});
  // Another repetition is refused as before.
  text.replace(text.find("1 2 3 3 5 6 7 7 0"), 17, "1 2 3 3 5 6 7 1 0");
  EXPECT_EQ(error_text<ParseError>([&] { read_medit(text, "c.mesh"); }),
            "c.mesh:18: vertex id 3 repeated (hexahedron 1 of 4)");
}

// The collapse of a higher-order hexahedron's corners (a 20-node brick
// degenerated to a wedge, as HyperMesh writes it: 1-based corners 2=3, 6=7)
// and the collapsed hexahedra of a VTU, binary legacy VTK and a voxel.
TEST(CollapsedHexahedra, HigherOrderAndVtuHexahedraCollapseToo) {
  const std::vector<std::array<double, 3>> p = perturbed_cube();
  std::string points;
  for (const auto& q : p) points += test::coordinates(q) + " ";
  const std::string vtu =
      "<VTKFile type=\"UnstructuredGrid\">\n<UnstructuredGrid><Piece NumberOfPoints=\"8\" NumberOfCells=\"1\">\n"
      "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\">" +
      points +
      "</DataArray></Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\">0 1 1 3 4 5 5 7 "
      "0 1 1 3 4 5 5 7 0 1 2 3</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\">20</DataArray>\n"
      "<DataArray type=\"UInt8\" Name=\"types\">25</DataArray>\n</Cells></Piece></UnstructuredGrid></VTKFile>\n";
  const LoadedMesh loaded = read_vtu(vtu, "c.vtu");
  ASSERT_EQ(loaded.mesh.wedges.size(), 1u);
  EXPECT_TRUE(loaded.mesh.hexes.empty());
  const std::vector<int> wedge(loaded.mesh.wedges[0].begin(), loaded.mesh.wedges[0].end());
  EXPECT_EQ(std::set<int>(wedge.begin(), wedge.end()), (std::set<int>{0, 1, 3, 4, 5, 7}));
  EXPECT_GT(test::split_volume(p, 13, wedge).min_tet, 0.0);
  EXPECT_EQ(loaded.warnings,
            (std::vector<std::string>{"c.vtu: 1 higher-order cell read by its corner nodes only (1 of type 25): "
                                      "its other nodes are ignored, so curved cells are measured as straight-sided "
                                      "ones",
                                      "c.vtu: 1 hexahedron with repeated corners read as the cells they collapse to "
                                      "(1 wedge): cell 0"}));
}

}  // namespace
}  // namespace hq
