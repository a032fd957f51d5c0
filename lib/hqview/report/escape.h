#pragma once
// The escapers for text that comes from input (file names, mesh comments,
// warnings, labels), one per output context. HTML text and attributes are
// escaped by the page templates (mustache's {{ }}); JSON by nlohmann.

#include <string>
#include <string_view>

namespace hq {

// Markdown text and table cells (summary.md of a bundle and of a batch):
// made inert for Markdown renderers (CommonMark, GitHub). Every ASCII
// punctuation character is backslash-escaped (`|` cannot end a cell, `[`
// cannot start a link) except < > &, which become &lt; &gt; &amp; so no HTML
// reaches the page; line breaks and other control characters become spaces
// (a table row stays one row). Not for code spans, where backslashes show.
std::string markdown_escape(std::string_view text);

// A relative path as a URL path (a link's destination in HTML or Markdown):
// every byte but unreserved ones and '/' percent-encoded, so '#', '?', '%'
// and spaces in file names keep links working.
std::string url_path(std::string_view path);

// XML text and attribute values (junit.xml; a page attribute): & < > " '
// as entities, tab and line breaks as character references, other control
// characters and bytes that are not UTF-8 as U+FFFD (XML 1.0 cannot hold them).
std::string xml_escape(std::string_view text);

// LaTeX text (comparison.tex): the TeX specials \ { } $ & # ^ _ ~ % escaped.
std::string latex_escape(std::string_view text);

}  // namespace hq
