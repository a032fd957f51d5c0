#pragma once
// summary.md: a short Markdown summary of one analysis for pull requests and
// CI job summaries (headline numbers, gates, links to the key PNGs).

#include <string>

#include "hqview/report/report_model.h"

namespace hq {

// summary.md of the bundle, with links relative to the bundle root.
// With a link base (--link-base, normalized): the key view (the first of
// the Views list) is shown inline at the top of the list, and every link is
// absolute under the base (link_base.h).
std::string summary_markdown(const ReportModel& model, const std::string& link_base = "");

}  // namespace hq
