#pragma once
// report.json (docs/contract.md, schema_version 2) as one JSON value, built
// once per run: the bundle writer prints it, gates and batch rows read it
// (json_path.h). Fixed key order, shortest round-trip floats, NaN/Inf as
// null, no timestamps or absolute paths.

#include <string>

#include <nlohmann/json.hpp>

#include "hqview/report/report_model.h"

namespace hq {

inline constexpr int kSchemaVersion = 2;

using ReportDocument = nlohmann::ordered_json;

// The whole report of model.
ReportDocument report_document(const ReportModel& model);

// Replaces the document's `gates` (evaluated on the document itself).
void set_report_gates(ReportDocument& document, const GateSummary& gates);

// The report.json text of a document, ending with a newline (invalid UTF-8
// in names from input is replaced, never thrown on).
std::string report_json_text(const ReportDocument& document);

// report_json_text(report_document(model)).
std::string report_json(const ReportModel& model);

}  // namespace hq
