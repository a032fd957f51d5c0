#pragma once
// summary.md: a short Markdown summary of one analysis for pull requests and
// CI job summaries (headline numbers, gates, links to the key PNGs).

#include <string>

#include "hqview/report/report_model.h"

namespace hq {

// summary.md of the bundle, with links relative to the bundle root.
std::string summary_markdown(const ReportModel& model);

}  // namespace hq
