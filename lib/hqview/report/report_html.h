#pragma once
// index.html and boundary.html from report_templates/ (embedded at build time) through
// kainjow-mustache, whose {{ }} tags HTML-escape every string: names and
// messages from input files can never inject markup.

#include <string>
#include <string_view>

#include "hqview/report/report_model.h"

namespace hq {

// index.html, the Mesh Quality Analysis page: headline, panels A–F linked
// by anchors (#cluster-K: C view of cluster K, #vertex-V / #corners-V: D / E
// views of vertex V, #cluster-row-K: its table row), tables.
std::string index_html(const ReportModel& model);
// boundary.html, the Boundary Error Analysis page. Requires
// model.analysis.boundary_error (throws hq::Error otherwise).
std::string boundary_html(const ReportModel& model);
// The one stylesheet of the bundle (style.css).
std::string_view report_stylesheet();

}  // namespace hq
