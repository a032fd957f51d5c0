#pragma once
// data/cells.csv and data/vertices.csv (CONTRACT.md "CSV columns").
// Ids are 0-based in file order; floats shortest round-trip; a column whose
// analysis stage has not run is written empty (never a made-up 0).

#include <ostream>

#include "hqview/report/report_model.h"

namespace hq {

void write_cells_csv(const ReportModel& model, std::ostream& out);
void write_vertices_csv(const ReportModel& model, std::ostream& out);

}  // namespace hq
