#pragma once
// index.html from report_templates/ (embedded at build time) through
// kainjow-mustache, whose {{ }} tags HTML-escape every string: names and
// messages from input files can never inject markup.

#include <string>
#include <string_view>

#include "hqview/report/report_model.h"

namespace hq {

std::string index_html(const ReportModel& model);
// The one stylesheet of the bundle (style.css).
std::string_view report_stylesheet();

}  // namespace hq
