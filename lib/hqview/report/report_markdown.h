#pragma once
// summary.md: a short Markdown summary of one analysis for pull requests and
// CI job summaries (headline numbers, gates, links to the key PNGs).

#include <string>
#include <string_view>

#include "hqview/report/report_model.h"

namespace hq {

// Text from input (file names, warnings) made inert for Markdown renderers
// (CommonMark, GitHub): every ASCII punctuation character is backslash-escaped
// except < > &, which become &lt; &gt; &amp; so no HTML reaches the page; line
// breaks and other control characters become spaces (a table row stays one row).
std::string markdown_escape(std::string_view text);

// summary.md of the bundle, with links relative to the bundle root.
std::string summary_markdown(const ReportModel& model);

}  // namespace hq
