#pragma once
// data/cells.csv, data/vertices.csv, data/edges.csv and
// data/non_conforming_faces.csv (docs/contract.md "CSV columns").
// Ids are 0-based in file order; floats shortest round-trip; a column whose
// analysis stage has not run is written empty (never a made-up 0).

#include <ostream>

#include "hqview/quality/corner_jacobian.h"
#include "hqview/report/report_model.h"
#include "hqview/structure/structure.h"

namespace hq {

// The `degenerate` and `inverted` columns (also annotated.vtu's arrays):
// cell_is_degenerate and cell_is_inverted (quality_field.h).

// plain: the CSV text; gzip: the same bytes gzip'ed, as concatenated gzip
// members of a fixed number of rows each (the same file for any -j).
enum class TextEncoding { plain, gzip };

// Rows are formatted in parallel chunks and written in order.
void write_cells_csv(const ReportModel& model, std::ostream& out, TextEncoding encoding = TextEncoding::plain);
void write_vertices_csv(const ReportModel& model, std::ostream& out, TextEncoding encoding = TextEncoding::plain);
// One row per singular, irregular or non-manifold edge (HexStructure::edges).
void write_edges_csv(const ReportModel& model, std::ostream& out);
const char* edge_kind_name(EdgeKind kind);
// One row per non-conforming face (Topology::non_conforming_faces): a mesh
// with non-hex cells only.
void write_non_conforming_faces_csv(const ReportModel& model, std::ostream& out);

}  // namespace hq
