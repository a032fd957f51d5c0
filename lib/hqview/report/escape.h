#pragma once
// The escapers for text that comes from input (file names, mesh comments,
// warnings, labels), one per output context. Each first makes the text a
// message (core/message_text.h: bytes that are not UTF-8 and control
// characters as \xHH), then escapes it for its context.

#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace hq {

// Markdown text and table cells (summary.md of a bundle and of a batch):
// made inert for Markdown renderers (CommonMark, GitHub). Every ASCII
// punctuation character is backslash-escaped (`|` cannot end a cell, `[`
// cannot start a link) except < > &, which become &lt; &gt; &amp; so no HTML
// reaches the page; line breaks and other control characters show as \xHH
// (a table row stays one row). Not for code spans, where backslashes show.
std::string markdown_escape(std::string_view text);

// A relative path as a URL path (a link's destination in HTML or Markdown):
// every byte but unreserved ones and '/' percent-encoded, so '#', '?', '%'
// and spaces in file names keep links working.
std::string url_path(std::string_view path);

// XML text and attribute values (junit.xml; a page attribute): & < > " '
// as entities, '\n' as a character reference, other control characters
// and bytes that are not UTF-8 as \xHH (message_text), and the two
// characters XML 1.0 forbids that are valid UTF-8, U+FFFE and U+FFFF, as
// their bytes (\xef\xbf\xbe, \xef\xbf\xbf).
std::string xml_escape(std::string_view text);

// HTML text and attribute values (the escape of every {{ }} of the page
// templates): message_text, then & < > " ' as &amp; &lt; &gt; &quot; &apos;
// (mustache's own set).
std::string html_escape(std::string_view text);

// A copy of a JSON value with every string, and every object key, as
// message_text (report.json, index.json, the viewer's data, `batch --list`).
// A name that is not UTF-8 or holds control characters therefore does not
// round-trip through the JSON; valid UTF-8 without controls is unchanged.
template <class Json>
Json json_message_text(const Json& value);

// LaTeX text (comparison.tex): the TeX specials \ { } $ & # ^ _ ~ % escaped.
std::string latex_escape(std::string_view text);

}  // namespace hq
