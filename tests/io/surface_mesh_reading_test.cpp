// Surface meshes (issue 47): every non-polygon reader reads quadrilaterals
// and triangles into the mesh's quad and triangle blocks when the file has
// no volume cell (docs/formats.md, "Surface meshes"). One small mesh (two
// quads and a triangle) written in every format reads to the same cells
// with each format's source_index; VTK's pixel is reordered like a voxel and
// its polygon of 3 or 4 points read; --dimension picks the cells; quads
// with repeated corners become triangles or are left out, with warnings.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "error_text.h"
#include "hqview/io/abaqus_reader.h"
#include "hqview/io/gmsh_reader.h"
#include "hqview/io/medit_reader.h"
#include "hqview/io/vtk_legacy_reader.h"
#include "hqview/io/vtu_reader.h"

namespace hq {
namespace HQ_TEST_UNIT {

using test::error_text;

// Points of a 3 x 2 grid in z = 0 and (3, 0.5, 0): quads (0,1,4,3),
// (1,2,5,4), triangle (2,6,5), all counter-clockwise seen from +z.
const char* const kPoints = "0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n3 0.5 0\n";
const std::vector<std::array<Index, 4>> kQuads = {{0, 1, 4, 3}, {1, 2, 5, 4}};
const std::vector<std::array<Index, 3>> kTriangles = {{2, 6, 5}};

std::string vtk(const std::string& cells, const std::string& types, int num_cells, int size) {
  return "# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 7 double\n" + std::string(kPoints) +
         "CELLS " + std::to_string(num_cells) + " " + std::to_string(size) + "\n" + cells + "CELL_TYPES " +
         std::to_string(num_cells) + "\n" + types;
}

void expect_cells(const LoadedMesh& loaded, const std::vector<std::int64_t>& quad_sources,
                  const std::vector<std::int64_t>& triangle_sources) {
  EXPECT_EQ(loaded.mesh.points.size(), 7u);
  EXPECT_TRUE(loaded.mesh.hexes.empty());
  EXPECT_EQ(loaded.mesh.quads, kQuads);
  EXPECT_EQ(loaded.mesh.triangles, kTriangles);
  for (std::size_t i = 0; i < quad_sources.size(); ++i)
    EXPECT_EQ(cell_source_index(loaded.mesh, CellKind::quad, i), quad_sources[i]);
  for (std::size_t i = 0; i < triangle_sources.size(); ++i)
    EXPECT_EQ(cell_source_index(loaded.mesh, CellKind::triangle, i), triangle_sources[i]);
  EXPECT_TRUE(is_surface_mesh(loaded.mesh));
}

TEST(SurfaceMeshReading, EveryFormatReadsTheSameQuadsAndTriangles) {
  // MEDIT: the 1-based entry of its section.
  const std::string medit = "MeshVersionFormatted 2\nDimension 3\nVertices 7\n0 0 0 0\n1 0 0 0\n2 0 0 0\n0 1 0 0\n"
                            "1 1 0 0\n2 1 0 0\n3 0.5 0 0\nQuadrilaterals 2\n1 2 5 4 0\n2 3 6 5 0\n"
                            "Triangles 1\n3 7 6 0\nEdges 1\n1 2 0\nEnd\n";
  const LoadedMesh m = read_medit(medit, "m.mesh");
  expect_cells(m, {1, 2}, {1});
  EXPECT_TRUE(m.warnings.empty());
  // Legacy VTK: the 0-based cell id; a line cell skipped, as a note (a
  // line is below a surface mesh's dimension: the file's curve, not a cell).
  const LoadedMesh v = read_vtk_legacy(vtk("4 0 1 4 3\n3 2 6 5\n4 1 2 5 4\n2 0 1\n", "9\n5\n9\n3\n", 4, 17), "t.vtk");
  expect_cells(v, {0, 2}, {1});
  EXPECT_TRUE(v.warnings.empty());
  EXPECT_EQ(v.notes, std::vector<std::string>{"t.vtk: 1 cell of unread types skipped (type 3)"});
  // VTU (ASCII).
  const std::string vtu = R"(<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">
<UnstructuredGrid><Piece NumberOfPoints="7" NumberOfCells="3">
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">)" +
                          std::string(kPoints) + R"(</DataArray></Points>
<Cells>
<DataArray type="Int64" Name="connectivity" format="ascii">0 1 4 3 2 6 5 1 2 5 4</DataArray>
<DataArray type="Int64" Name="offsets" format="ascii">4 7 11</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">9 5 9</DataArray>
</Cells></Piece></UnstructuredGrid></VTKFile>
)";
  expect_cells(read_vtu(vtu, "t.vtu"), {0, 2}, {1});
  // Gmsh 2.2: the element tag; a point element (a geometric point's tag) skipped as a note.
  const std::string gmsh = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n7\n1 0 0 0\n2 1 0 0\n3 2 0 0\n4 0 1 0\n"
                           "5 1 1 0\n6 2 1 0\n7 3 0.5 0\n$EndNodes\n$Elements\n4\n1 15 2 0 1 1\n"
                           "2 3 2 0 1 1 2 5 4\n3 2 2 0 1 3 7 6\n4 3 2 0 1 2 3 6 5\n$EndElements\n";
  const LoadedMesh g = read_gmsh(gmsh, "t.msh");
  expect_cells(g, {2, 4}, {3});
  EXPECT_TRUE(g.warnings.empty());
  EXPECT_EQ(g.notes, std::vector<std::string>{"t.msh: 1 element of unread types skipped (type 15)"});
  // Gmsh 4.1: the same elements in blocks.
  const std::string gmsh4 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 7 1 7\n2 1 0 7\n1\n2\n3\n4\n5\n6\n7\n"
                            "0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n3 0.5 0\n$EndNodes\n$Elements\n"
                            "2 3 2 4\n2 1 3 2\n2 1 2 5 4\n4 2 3 6 5\n2 1 2 1\n3 3 7 6\n$EndElements\n";
  expect_cells(read_gmsh(gmsh4, "t4.msh"), {2, 4}, {3});
  // Abaqus: the element label; S4R and CPS3 among the documented families.
  const std::string inp = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 2, 0, 0\n4, 0, 1, 0\n5, 1, 1, 0\n6, 2, 1, 0\n7, 3, 0.5, 0\n"
                          "*ELEMENT, TYPE=S4R\n10, 1, 2, 5, 4\n11, 2, 3, 6, 5\n*ELEMENT, TYPE=CPS3\n20, 3, 7, 6\n";
  expect_cells(read_abaqus(inp, "t.inp"), {10, 11}, {20});
}

// Gmsh writes the points (15) and curves (1) of a surface mesh's geometry
// beside its quads: a note, not a warning (the 47e review's "90 elements of
// unread types skipped (types 1, 15)" on every Gmsh planar mesh). A face
// type the reader does not read (36, a 16-node quad) is of the mesh's own
// dimension: still a warning, on its own.
TEST(SurfaceMeshReading, GmshGeometryPointsAndLinesAreNotesUnreadFacesWarnings) {
  const std::string gmsh = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n7\n1 0 0 0\n2 1 0 0\n3 2 0 0\n4 0 1 0\n"
                           "5 1 1 0\n6 2 1 0\n7 3 0.5 0\n$EndNodes\n$Elements\n7\n1 15 2 0 1 1\n2 1 2 0 1 1 2\n"
                           "3 1 2 0 1 2 3\n4 3 2 0 1 1 2 5 4\n5 2 2 0 1 3 7 6\n6 3 2 0 1 2 3 6 5\n"
                           "7 36 2 0 1 1 2 3 4 5 6 7 1 2 3 4 5 6 7 1 2\n$EndElements\n";
  const LoadedMesh g = read_gmsh(gmsh, "g.msh");
  expect_cells(g, {4, 6}, {5});
  EXPECT_EQ(g.notes, std::vector<std::string>{"g.msh: 3 elements of unread types skipped (types 1, 15)"});
  EXPECT_EQ(g.warnings, std::vector<std::string>{"g.msh: 1 element of unread types skipped (type 36)"});
}

TEST(SurfaceMeshReading, PixelsPolygonsAndSecondOrderCells) {
  // A pixel lists its corners x fastest: (0,1,3,4) is the quad (0,1,4,3).
  // Polygons of 4 and 3 points are a quad and a triangle; one of 5 points is
  // skipped by its type; a quadratic quad (23) is read by its corners.
  const LoadedMesh v = read_vtk_legacy(
      vtk("4 0 1 3 4\n4 1 2 5 4\n3 2 6 5\n5 0 1 2 5 4\n8 0 1 4 3 1 2 5 4\n", "8\n7\n7\n7\n23\n", 5, 29), "p.vtk");
  EXPECT_EQ(v.mesh.quads, (std::vector<std::array<Index, 4>>{{0, 1, 4, 3}, {1, 2, 5, 4}, {0, 1, 4, 3}}));
  EXPECT_EQ(v.mesh.triangles, kTriangles);
  ASSERT_EQ(v.warnings.size(), 2u);
  EXPECT_EQ(v.warnings[0], "p.vtk: 1 cell of unread types skipped (type 7)");
  EXPECT_EQ(v.warnings[1],
            "p.vtk: 1 higher-order cell read by its corner nodes only (1 of type 23): its other nodes are ignored, so "
            "curved cells are measured as straight-sided ones");
}

// A hexahedron on points 0-7 of a unit cube with one of its quads.
std::string hex_and_quad() {
  return "# vtk DataFile Version 3.0\nh\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
         "0 0 1\n1 0 1\n1 1 1\n0 1 1\nCELLS 2 14\n8 0 1 2 3 4 5 6 7\n4 0 3 2 1\nCELL_TYPES 2\n12\n9\n";
}

TEST(SurfaceMeshReading, DimensionChoosesTheCells) {
  // auto: a file with a volume cell is a volume mesh, its quad skipped as before.
  const LoadedMesh volume = read_vtk_legacy(hex_and_quad(), "h.vtk");
  EXPECT_EQ(volume.mesh.hexes.size(), 1u);
  EXPECT_TRUE(volume.mesh.quads.empty());
  EXPECT_TRUE(volume.mesh.source_index[static_cast<std::size_t>(CellKind::quad)].empty());
  // A volume mesh's skipped boundary quad is a note, not a warning.
  EXPECT_TRUE(volume.warnings.empty());
  EXPECT_EQ(volume.notes, std::vector<std::string>{"h.vtk: 1 cell of unread types skipped (type 9)"});
  // surface: the quad, the hexahedron left out and said so.
  ReadLimits surface;
  surface.dimension = MeshDimension::surface;
  const LoadedMesh s = read_vtk_legacy(hex_and_quad(), "h.vtk", surface);
  EXPECT_TRUE(s.mesh.hexes.empty());
  EXPECT_EQ(s.mesh.quads, (std::vector<std::array<Index, 4>>{{0, 3, 2, 1}}));
  EXPECT_EQ(cell_source_index(s.mesh, CellKind::quad, 0), 1);
  EXPECT_EQ(s.warnings, std::vector<std::string>{"h.vtk: 1 volume cell left out (--dimension surface)"});
  // volume on a surface file: refused as a file without volume cells.
  ReadLimits volume_only;
  volume_only.dimension = MeshDimension::volume;
  EXPECT_EQ(error_text<ParseError>([&] {
              read_vtk_legacy(vtk("4 0 1 4 3\n3 2 6 5\n", "9\n5\n", 2, 9), "q.vtk", volume_only);
            }),
            "q.vtk: no volume cells (2 cells of types 5, 9)");
  EXPECT_EQ(error_text<ParseError>([&] {
              read_medit("MeshVersionFormatted 2\nDimension 3\nVertices 1\n0 0 0 0\nEnd\n", "e.mesh", surface);
            }),
            "e.mesh: no surface cells (quadrilaterals or triangles)");
}

TEST(SurfaceMeshReading, RepeatedCornersCollapseOrLeaveTheCellOut) {
  // (0,1,4,4): one collapsed edge, the triangle (4,0,1); (0,1,0,3): opposite
  // corners equal, no area: left out.
  const LoadedMesh v =
      read_vtk_legacy(vtk("4 0 1 4 4\n4 0 1 0 3\n4 1 2 5 4\n", "9\n9\n9\n", 3, 15), "r.vtk");
  EXPECT_EQ(v.mesh.quads, (std::vector<std::array<Index, 4>>{{1, 2, 5, 4}}));
  EXPECT_EQ(v.mesh.triangles, (std::vector<std::array<Index, 3>>{{4, 0, 1}}));
  EXPECT_EQ(cell_source_index(v.mesh, CellKind::triangle, 0), 0);
  EXPECT_EQ(cell_source_index(v.mesh, CellKind::quad, 0), 2);
  EXPECT_EQ(v.warnings, (std::vector<std::string>{
                            "r.vtk: 1 quadrilateral with a repeated corner read as a triangle: cell 0",
                            "r.vtk: 1 surface cell with repeated corners left out (no area): cell 1"}));
  // Nothing left to analyse: refused (exit 3 from the command line).
  EXPECT_EQ(error_text<ParseError>([&] { read_vtk_legacy(vtk("4 0 1 0 3\n", "9\n", 1, 5), "n.vtk"); }),
            "n.vtk: no surface cells with an area (every quadrilateral and triangle repeats a corner)");
  // MEDIT numbers them by their entry.
  const LoadedMesh m = read_medit(
      "MeshVersionFormatted 2\nDimension 3\nVertices 4\n0 0 0 0\n1 0 0 0\n1 1 0 0\n0 1 0 0\n"
      "Quadrilaterals 2\n1 2 3 4 0\n1 2 3 3 0\nEnd\n",
      "c.mesh");
  EXPECT_EQ(m.mesh.triangles, (std::vector<std::array<Index, 3>>{{2, 0, 1}}));
  EXPECT_EQ(cell_source_index(m.mesh, CellKind::triangle, 0), 2);
  EXPECT_EQ(m.warnings, std::vector<std::string>{
                            "c.mesh: 1 quadrilateral with a repeated corner read as a triangle: cell 2"});
}

TEST(SurfaceMeshReading, MalformedSurfaceCellsFailOnlyASurfaceMesh) {
  // A point id out of range in a quad: the surface mesh is refused with its
  // place; a volume mesh skips the quad unread, as before.
  EXPECT_EQ(error_text<ParseError>([&] { read_vtk_legacy(vtk("4 0 1 4 9\n", "9\n", 1, 5), "b.vtk"); }),
            "b.vtk:14: point id 9 out of range [0, 7) (cell 0)");
  const std::string hex_bad_quad = hex_and_quad().substr(0, hex_and_quad().find("4 0 3 2 1")) + "4 0 3 2 99\nCELL_TYPES 2\n12\n9\n";
  EXPECT_EQ(read_vtk_legacy(hex_bad_quad, "h.vtk").mesh.hexes.size(), 1u);
  EXPECT_EQ(error_text<ParseError>([&] {
              read_abaqus("*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n*ELEMENT, TYPE=S3\n1, 1, 2, 4\n", "b.inp");
            }),
            "b.inp:6: node 4 is not defined (element 1)");
}

}  // namespace
}  // namespace hq
