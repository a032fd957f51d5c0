// data/non_conforming_faces.csv and report.json's mesh counts for a hex
// whose top quad meets two tets (one non-conforming face).
#include <gtest/gtest.h>

#include <sstream>

#include "hqview/mesh/mesh_summary.h"
#include "hqview/report/data_files.h"
#include "hqview/report/report_csv.h"
#include "support/fixtures.h"

namespace hq {
namespace HQ_TEST_UNIT {

TEST(NonConformingCsv, OneRowPerFaceWithItsCellsAndDiagonal) {
  ReportModel model;
  HexMesh& mesh = model.analysis.mesh;
  mesh = test::unit_cube();
  mesh.points.push_back({0.5, 0.5, 2.0});                                   // 8, the apex
  mesh.tets = {{4, 5, 6, 8}, {4, 6, 7, 8}};  // split along 4-6
  model.analysis.topology = build_topology(mesh);
  std::ostringstream out;
  write_non_conforming_faces_csv(model, out);
  EXPECT_EQ(out.str(),
            "face,v0,v1,v2,v3,split_v0,split_v1,quad_cell,quad_cell_type,triangle_cell_a,triangle_cell_a_type,"
            "triangle_cell_b,triangle_cell_b_type\n"
            "0,4,5,6,7,4,6,0,hex,1,tet,2,tet\n");
  const MeshSummary s = summarize_mesh(mesh, model.analysis.topology);
  EXPECT_EQ(s.num_non_conforming_faces, 1);
  EXPECT_EQ(s.num_boundary_faces, 5 + 4);  // 5 hex quads, 4 tet triangles off the interface
  EXPECT_EQ(s.num_unreferenced_vertices, 0);
  EXPECT_EQ(s.bbox_max.z, 2.0);  // the apex frames the mesh too

  // The file is in the bundle's list only for a mesh with non-hex cells.
  DataFormats formats;
  EXPECT_EQ(data_files(formats).back().path, "data/edges.csv");
  formats.non_conforming_faces = true;
  EXPECT_EQ(data_files(formats).back().path, "data/non_conforming_faces.csv");
}

TEST(NonConformingCsv, PureHexHasNoneAndTheHexCounts) {
  const HexMesh mesh = test::grid(2);
  const Topology topo = build_topology(mesh);
  const MeshSummary s = summarize_mesh(mesh, topo);
  EXPECT_EQ(s.num_non_conforming_faces, 0);
  EXPECT_EQ(s.num_boundary_faces, 24);
  EXPECT_EQ(s.num_non_manifold_faces, 0);
}

}  // namespace
}  // namespace hq
