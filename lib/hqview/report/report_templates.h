#pragma once
// The files of report_templates/ (page templates and the stylesheet),
// embedded into hq_report at build time by cmake/EmbedFiles.cmake.

#include <string_view>

namespace hq {
namespace detail {
std::string_view embedded_file(std::string_view name);  // generated; empty when unknown
}

// The bytes of report_templates/NAME, e.g. "index.html.mustache".
inline std::string_view report_template(std::string_view name) { return detail::embedded_file(name); }

}  // namespace hq
