#pragma once
// report.json (CONTRACT.md, schema_version 1): fixed key order, shortest
// round-trip floats, NaN/Inf as null, no timestamps or absolute paths.

#include <string>

#include "hqview/report/report_model.h"

namespace hq {

inline constexpr int kSchemaVersion = 1;

// The whole report.json text, ending with a newline.
std::string report_json(const ReportModel& model);

}  // namespace hq
