// Every mesh reader reads tetrahedra, wedges and pyramids into the mesh's
// blocks in VTK corner order (docs/formats.md, "Cell kinds"): one hybrid
// mesh (hybrid_mesh_files.h) written in every text format reads to the same
// cells, each with a positive volume by a split into tetrahedra that does
// not use HQView's tables, and each with its format's source_index. Then
// the bad cells of every format (a repeated node, a node out of range, a
// node count that does not match the type) and the hex-only analysis' rule
// (other kinds read, warned about; no hexahedron: refused).

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "error_text.h"
#include "hqview/io/abaqus_reader.h"
#include "hqview/io/gmsh_reader.h"
#include "hqview/io/medit_reader.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/io/ovm_reader.h"
#include "hqview/io/vtk_legacy_reader.h"
#include "hqview/io/vtu_reader.h"
#include "hybrid_mesh_files.h"
#include "temp_dir.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::error_text;
using test::HybridCell;
using test::HybridMesh;
using test::TempDir;

int vtk_type_of(CellKind kind) { return cell_kind_vtk_type(kind); }

// The corners of each block of a read mesh, as vectors, in block order.
std::vector<std::vector<int>> block_cells(const Mesh& mesh, CellKind kind) {
  std::vector<std::vector<int>> out;
  for_each_block(mesh, [&](auto k, const auto& cells) {
    if (k() != kind) return;
    for (const auto& c : cells) out.emplace_back(c.begin(), c.end());
  });
  return out;
}

struct Format {
  std::string file;
  std::string text;
  // The source index of the e-th cell of the file that is the i-th of its kind.
  std::function<std::int64_t(std::size_t e, std::size_t i)> source_index;
  bool is_rotated;  // OVM rebuilds a cell's corners from its faces: the same cell, its corners maybe rotated
};

TEST(CellBlocksReading, HybridMeshFixtureIsValid) {
  const HybridMesh m = test::hybrid_mesh();
  double total = 0;
  for (const HybridCell& c : m.cells) {
    const test::SplitVolume v = test::split_volume(m.points, c.vtk_type, c.vtk);
    EXPECT_GT(v.min_tet, 0.0) << c.vtk_type;
    total += v.total;
  }
  // 2 unit cubes + the unit box of the wedges + pyramid (base 1, height 0.6) + the two tets' 6 * 0.0933/0.0733 / 6.
  EXPECT_NEAR(total, 3.0 + 0.6 / 3 + 0.56 / 6 + 0.44 / 6, 1e-12);
}

TEST(CellBlocksReading, OneHybridMeshInEveryFormatReadsToTheSameCells) {
  const HybridMesh m = test::hybrid_mesh();
  const std::vector<Format> formats = {
      {"hybrid.mesh", test::write_medit(m), [](std::size_t, std::size_t i) { return std::int64_t(i + 1); }, false},
      {"hybrid.vtk", test::write_vtk_legacy(m), [](std::size_t e, std::size_t) { return std::int64_t(e); }, false},
      {"hybrid.vtu", test::write_vtu(m), [](std::size_t e, std::size_t) { return std::int64_t(e); }, false},
      {"hybrid22.msh", test::write_gmsh22(m), [](std::size_t e, std::size_t) { return std::int64_t(101 + e); }, false},
      {"hybrid41.msh", test::write_gmsh41(m), [](std::size_t e, std::size_t) { return std::int64_t(101 + e); }, false},
      {"hybrid.inp", test::write_abaqus(m), [](std::size_t e, std::size_t) { return std::int64_t(11 + e); }, false},
      {"hybrid.ovm", test::write_ovm(m), [](std::size_t e, std::size_t) { return std::int64_t(e); }, true},
  };
  const TempDir dir("hybrid_formats");
  for (const Format& format : formats) {
    SCOPED_TRACE(format.file);
    const auto path = dir.write(format.file, format.text);
    const LoadedMesh loaded = read_hex_mesh(path);
    ASSERT_EQ(loaded.mesh.points.size(), m.points.size());
    for (std::size_t i = 0; i < m.points.size(); ++i) {
      EXPECT_EQ(loaded.mesh.points[i].x, m.points[i][0]);
      EXPECT_EQ(loaded.mesh.points[i].y, m.points[i][1]);
      EXPECT_EQ(loaded.mesh.points[i].z, m.points[i][2]);
    }
    EXPECT_TRUE(loaded.warnings.empty());  // every kind is analysed
    for (const CellKind kind : {CellKind::hex, CellKind::tet, CellKind::wedge, CellKind::pyramid}) {
      SCOPED_TRACE(std::string(cell_kind_name(kind)));
      std::vector<std::vector<int>> expected;
      std::vector<std::int64_t> expected_source;
      for (std::size_t e = 0; e < m.cells.size(); ++e)
        if (m.cells[e].vtk_type == vtk_type_of(kind)) {
          expected_source.push_back(format.source_index(e, expected.size()));
          expected.push_back(m.cells[e].vtk);
        }
      std::vector<std::vector<int>> read = block_cells(loaded.mesh, kind);
      ASSERT_EQ(read.size(), expected.size());
      std::vector<std::int64_t> source;
      for (std::size_t i = 0; i < read.size(); ++i) source.push_back(cell_source_index(loaded.mesh, kind, i));
      EXPECT_EQ(source, expected_source);
      for (std::size_t i = 0; i < read.size(); ++i) {
        std::vector<std::array<double, 3>> points;
        for (const Vec3& p : loaded.mesh.points) points.push_back({p.x, p.y, p.z});
        const test::SplitVolume v = test::split_volume(points, vtk_type_of(kind), read[i]);
        EXPECT_GT(v.min_tet, 0.0) << "cell " << i;
        EXPECT_NEAR(v.total, test::split_volume(m.points, vtk_type_of(kind), expected[i]).total, 1e-12);
        if (format.is_rotated) {  // the same corners (and a positive volume, above)
          std::sort(read[i].begin(), read[i].end());
          std::sort(expected[i].begin(), expected[i].end());
        }
        EXPECT_EQ(read[i], expected[i]) << "cell " << i;
      }
    }
    EXPECT_TRUE(loaded.mesh.quads.empty());
    EXPECT_TRUE(loaded.mesh.triangles.empty());
  }
}

// A mirrored copy of the mesh (x -> -x) written with the same corner lists
// has every cell inverted: the readers keep the file's corners (they never
// reorient a cell to make its volume positive), so every split volume is
// negative. OVM, which rebuilds cells from outward faces, is the exception:
// its half-faces of the mirrored mesh point inward and are refused.
TEST(CellBlocksReading, MirroredMeshReadsAsInvertedCells) {
  HybridMesh m = test::hybrid_mesh();
  for (auto& p : m.points) p[0] = -p[0];
  const TempDir dir("hybrid_mirrored");
  for (const auto& [file, text] : std::vector<std::pair<std::string, std::string>>{
           {"m.mesh", test::write_medit(m)}, {"m.vtk", test::write_vtk_legacy(m)}, {"m.msh", test::write_gmsh22(m)},
           {"m.inp", test::write_abaqus(m)}}) {
    SCOPED_TRACE(file);
    const LoadedMesh loaded = read_hex_mesh(dir.write(file, text));
    std::vector<std::array<double, 3>> points;
    for (const Vec3& p : loaded.mesh.points) points.push_back({p.x, p.y, p.z});
    for (const CellKind kind : {CellKind::hex, CellKind::tet, CellKind::wedge, CellKind::pyramid})
      for (const auto& cell : block_cells(loaded.mesh, kind))
        EXPECT_LT(test::split_volume(points, vtk_type_of(kind), cell).total, 0.0) << cell_kind_name(kind);
  }
}

TEST(CellBlocksReading, TetrahedraOnlyAreReadAndAMeshWithoutVolumeCellsIsRefused) {
  const TempDir dir("no_hex");
  const std::string tet_only =
      "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n0 0 0 1 0 0 0 1 0 0 0 1\n"
      "CELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n10\n";
  const auto path = dir.write("t.vtk", tet_only);
  EXPECT_EQ(read_hex_mesh(path).mesh.tets.size(), 1u);
  const auto none = dir.write("n.vtk",
                              "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n"
                              "0 0 0 1 0 0 0 1 0 0 0 1\nCELLS 1 3\n2 0 1\nCELL_TYPES 1\n3\n");
  EXPECT_EQ(error_text<ParseError>([&] { read_hex_mesh(none); }), none.string() + ": no volume cells (1 cell of type 3)");
  // The reader itself reads the tetrahedron.
  const LoadedMesh loaded = read_vtk_legacy(tet_only, "t.vtk");
  ASSERT_EQ(loaded.mesh.tets.size(), 1u);
  EXPECT_EQ(loaded.mesh.tets[0], (std::array<Index, 4>{0, 1, 2, 3}));
  EXPECT_TRUE(loaded.mesh.hexes.empty());
}

// Item 9 of issue 46: a cell with a repeated node, a node out of range, a
// node count that does not match its type: path:line and what is wrong.
TEST(CellBlocksReading, BadCellsOfEveryKindAndFormat) {
  const auto medit = [](const std::string& section) {
    return error_text<ParseError>([&] {
      read_medit("MeshVersionFormatted 2\nDimension 3\nVertices\n6\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n1 0 1 0\n"
                 "0 1 1 0\n" +
                     section,
                 "m.mesh");
    });
  };
  EXPECT_EQ(medit("Tetrahedra\n1\n1 2 3 3 0\n"), "m.mesh:13: vertex id 3 repeated (tetrahedron 1 of 1)");
  EXPECT_EQ(medit("Prisms\n1\n1 2 3 4 5 7 0\n"), "m.mesh:13: vertex id 7 out of range [1, 6] (prism 1 of 1)");
  EXPECT_EQ(medit("Pyramids\n1\n1 2 3 4\nEnd\n"),
            "m.mesh:13: expected 5 vertex ids and a reference, got 4 values (pyramid 1 of 1)");

  const auto vtk = [](const std::string& cells) {
    return error_text<ParseError>([&] {
      read_vtk_legacy("# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 6 double\n"
                      "0 0 0 1 0 0 0 1 0 0 0 1 1 0 1 0 1 1\n" +
                          cells,
                      "m.vtk");
    });
  };
  EXPECT_EQ(vtk("CELLS 1 6\n5 0 1 2 3 4\nCELL_TYPES 1\n10\n"), "m.vtk:8: cell 0 has type 10 (tetra) but 5 points, expected 4");
  EXPECT_EQ(vtk("CELLS 1 7\n6 0 1 2 3 4 4\nCELL_TYPES 1\n13\n"), "m.vtk:8: point id 4 repeated (cell 0)");
  EXPECT_EQ(vtk("CELLS 1 6\n5 0 1 2 3 6\nCELL_TYPES 1\n14\n"), "m.vtk:8: point id 6 out of range [0, 6) (cell 0)");

  const auto vtu = [](const std::string& connectivity, const std::string& offsets, const std::string& type) {
    return error_text<ParseError>([&] {
      read_vtu("<VTKFile type=\"UnstructuredGrid\">\n<UnstructuredGrid><Piece NumberOfPoints=\"6\" NumberOfCells=\"1\">\n"
               "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\">0 0 0 1 0 0 0 1 0 0 0 1 1 0 1 0 1 1"
               "</DataArray></Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\">" +
                   connectivity + "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\">" + offsets +
                   "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\">" + type +
                   "</DataArray>\n</Cells></Piece></UnstructuredGrid></VTKFile>\n",
               "m.vtu");
    });
  };
  EXPECT_EQ(vtu("0 1 2 3 4", "5", "13"),
            "m.vtu:5: cell 0 has type 13 (wedge) but 5 points, expected 6 (DataArray 'connectivity')");
  EXPECT_EQ(vtu("0 1 2 2", "4", "10"), "m.vtu:5: point id 2 repeated (cell 0) (DataArray 'connectivity')");

  const auto gmsh = [](const std::string& element) {
    return error_text<ParseError>([&] {
      read_gmsh("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 0 1\n"
                "6 0 1 1\n$EndNodes\n$Elements\n1\n" +
                    element + "\n$EndElements\n",
                "m.msh");
    });
  };
  EXPECT_EQ(gmsh("7 4 2 0 1 1 2 3 4 5"), "m.msh:15: expected 4 node tags for tetrahedron 7, got 5");
  EXPECT_EQ(gmsh("7 6 2 0 1 1 2 3 4 5"), "m.msh:15: expected 6 node tags for wedge 7, got 5");
  EXPECT_EQ(gmsh("7 7 2 0 1 1 2 3 4 4"), "m.msh:15: node tag 4 repeated (element 7)");
  EXPECT_EQ(gmsh("7 4 2 0 1 1 2 3 9"), "m.msh:15: node tag 9 is not defined (element 7)");

  const auto abaqus = [](const std::string& elements) {
    return error_text<ParseError>([&] {
      read_abaqus("*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n5, 1, 0, 1\n6, 0, 1, 1\n" + elements, "m.inp");
    });
  };
  EXPECT_EQ(abaqus("*ELEMENT, TYPE=C3D6\n1, 1, 2, 3, 4, 5\n"), "m.inp:9: expected an element id and 6 node ids, got 6 fields");
  EXPECT_EQ(abaqus("*ELEMENT, TYPE=C3D4H\n1, 1, 2, 3, 3\n"), "m.inp:9: node 3 repeated (element 1)");
  EXPECT_EQ(abaqus("*ELEMENT, TYPE=DC3D6\n1, 1, 2, 3, 4, 5, 8\n"), "m.inp:9: node 8 is not defined (element 1)");
}

TEST(CellBlocksReading, OvmPolyhedraOfOtherShapesAreRefused) {
  // A tetrahedron whose last face is given reversed (inward).
  HybridMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.cells = {{10, {0, 1, 2, 3}}};
  std::string text = test::write_ovm(m);
  const std::size_t last = text.rfind("4 0 2 4 6");
  ASSERT_NE(last, std::string::npos) << text;
  text.replace(last, 9, "4 0 2 4 7");
  EXPECT_EQ(error_text<ParseError>([&] { read_ovm(text, "t.ovm"); }),
            "t.ovm:24: polyhedron 0 is not a tet: its half-faces are not consistently oriented");
}

}  // namespace
}  // namespace hq
