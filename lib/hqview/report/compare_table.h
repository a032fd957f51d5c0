#pragma once
// The side-by-side table of --compare: both meshes' headline numbers and
// their differences (MESH2 - MESH), for index.html and summary.md (the same
// rows as report.json compare.headline and compare.differences, plus a few
// mesh and quality numbers). Display text only: report.json keeps the values.
// `diff` of two report.json shows the same rows for baseline and current.

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "hqview/analysis/analysis.h"
#include "hqview/report/key_quantity.h"

namespace hq {

struct CompareTableRow {
  std::string label;       // "min scaled Jacobian"
  std::string mine;        // MESH's value, display text
  std::string theirs;      // MESH2's value
  std::string difference;  // MESH2 - MESH, signed ("+8,496", "-0.178"); "0" when equal up to rounding (relative 1e-12), "–" when undefined
  bool is_worse = false;   // MESH2 is worse on a key where lower (or higher) is better
};

struct CompareTable {
  std::string mine_name, theirs_name;  // file names (not escaped)
  std::vector<CompareTableRow> rows;
  std::string alignment;  // how the compare view places MESH2 ("" when as read)
};

// The numbers of one mesh the table shows; NaN: not known (a null or missing
// key of a report.json). Counts are whole numbers.
struct CompareNumbers {
  double num_vertices = 0, num_hexes = 0;
  // Composition (report.json headline.num_cells_by_kind, hex_fraction,
  // hex_volume_fraction): volume cells of every kind, tets, wedges,
  // pyramids; hexes / cells by count and by volume.
  double num_cells = 0, num_tets = 0, num_wedges = 0, num_pyramids = 0;
  double hex_fraction = 0, hex_volume_fraction = 0;
  double sj_min = 0, sj_mean = 0, sj_p05 = 0;
  double num_inverted = 0, num_degenerate = 0;
  double vertex_quality_min = 0;
  double num_boundary_faces = 0;
  double bbox_diagonal = 0, edge_length_mean = 0;
  // A surface mesh's cells and boundary edges (issue 47): headline
  // num_cells_by_kind.quad / .triangle, mesh.num_boundary_edges; 0 on a
  // volume mesh, NaN in a report written before surface meshes.
  double num_quads = 0, num_triangles = 0, num_boundary_edges = 0;
};

CompareNumbers compare_numbers(const MeshSummary& mesh, const QualitySummary& quality,
                               const CellComposition& composition);
// From a report.json's `headline`, `mesh` and `quality` objects (or its
// compare block's); a report written before the composition keys has NaN
// there.
CompareNumbers compare_numbers(const nlohmann::json& headline, const nlohmann::json& mesh,
                               const nlohmann::json& quality);

// Which cells the two meshes' numbers run over: surface when both are
// surface meshes, hex when both have only hexes, else volume (every kind).
MeshCells mesh_cells(const CompareNumbers& mine, const CompareNumbers& theirs);

// The rows, `theirs` - `mine` (is_worse: `theirs` is worse). When either
// mesh has a tet, wedge or pyramid, the composition rows follow the
// hexahedra row: cells (every kind), tetrahedra, wedges, pyramids, hex
// fraction by count and by volume (lower is worse: a hex-dominant mesher
// aims at hexes); two pure-hex meshes show none of them. When either is a
// surface mesh: quadrilaterals (and triangles when either has one) and
// boundary edges; two surface meshes show no hexahedra and no boundary
// faces row. Inverted and degenerate rows name the cells (mesh_cells).
std::vector<CompareTableRow> compare_rows(const CompareNumbers& mine, const CompareNumbers& theirs);

// Precondition: analysis.compare holds a value.
CompareTable compare_table(const Analysis& analysis);

}  // namespace hq
