#pragma once
// `--single-file`: report.html, one page that needs no other file. The
// bundle's index page with the stylesheet inline and every image as a data
// URI, the boundary page as a section of it (its ids prefixed `boundary-`),
// and optionally the 3D viewer with its scripts and data (an iframe's
// srcdoc). Links to the pages become in-page anchors; links to the images
// themselves go (the image is on the page); links to the data files
// (report.json, summary.md, data/...) stay, relative to the bundle; external
// URLs (https:) stay. Built from the written pages' text, so the pages'
// layout is the templates' own.

#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace hq {

enum class SingleFile { none, pages, viewer };

// "pages" (--single-file) or "viewer" (--single-file=viewer); throws
// ValueError for anything else.
SingleFile parse_single_file(std::string_view text);

struct SingleFileSources {
  std::string_view index_html;                    // the page the file is made of
  std::optional<std::string_view> boundary_html;  // a section of it when set
  std::optional<std::string_view> viewer_html;    // embedded when set
  std::string_view stylesheet;                    // replaces <link rel="stylesheet" href="style.css">
  // A bundle file's bytes by its relative path (an image, a viewer script);
  // nullopt when it is missing (the link is then left as it was).
  std::function<std::optional<std::string>(const std::string& relative_path)> read_file;
  std::string_view link_base;  // the pages' --link-base: stripped to find files; empty: relative links
  // A link to another mesh's page (batch: `PATH/index.html`) becomes this
  // path (`PATH/report.html`); empty: such links stay.
  std::function<std::optional<std::string>(const std::string& relative_path)> page_link;
};

// report.html's text. Deterministic (the same pages give the same bytes).
std::string single_file_html(const SingleFileSources& sources);

}  // namespace hq
