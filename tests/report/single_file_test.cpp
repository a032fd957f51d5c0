// --single-file: report.html from the pages (single_file.h).

#include "hqview/report/single_file.h"

#include <gtest/gtest.h>

#include <map>

#include "hqview/core/error.h"

namespace hq {
namespace HQ_TEST_UNIT {

const std::map<std::string, std::string> kFiles = {
    {"views/main.png", std::string("\x89PNG\r\n\x1a\n", 8)},
    {"views/a b.svg", "<svg/>"},
    {"viewer/v.js", "var s = '</script><b>'; var t = 1 < 2;"},
};

SingleFileSources sources(const std::string& index, const std::string* boundary, const std::string* viewer) {
  SingleFileSources s;
  s.index_html = index;
  if (boundary) s.boundary_html = *boundary;
  if (viewer) s.viewer_html = *viewer;
  s.stylesheet = "body{color:red}\n";
  s.read_file = [](const std::string& p) -> std::optional<std::string> {
    const auto it = kFiles.find(p);
    return it == kFiles.end() ? std::nullopt : std::optional<std::string>(it->second);
  };
  return s;
}

TEST(SingleFile, InlinesStyleImagesAndTheBoundaryPage) {
  const std::string index =
      "<html><head><link rel=\"stylesheet\" href=\"style.css\"></head><body id=\"top\">"
      "<a href=\"views/main.png\"><img src=\"views/main.png\" alt=\"A\"></a>"
      "<img src=\"views/a%20b.svg\"><a href=\"boundary.html\">B</a> <a href=\"boundary.html#views\">BV</a>"
      "<a href=\"viewer.html#cluster-2\">3D</a> <a href=\"report.json\">json</a> <a href=\"data/edges.csv\">e</a>"
      "<a href=\"#quality\">q</a> <a href=\"https://doi.org/x?a=1&amp;b=2\">doi</a></body></html>";
  const std::string boundary =
      "<html><body><h1 id=\"views\">V</h1><a href=\"index.html#quality\">back</a> <a href=\"#views\">v</a>"
      "<img src=\"views/missing.png\"></body></html>";
  const std::string html = single_file_html(sources(index, &boundary, nullptr));
  EXPECT_EQ(html.find("style.css"), std::string::npos);
  EXPECT_NE(html.find("<style>\nbody{color:red}\n</style>"), std::string::npos);
  EXPECT_NE(html.find("<a><img src=\"data:image/png;base64,iVBORw0KGgo=\" alt=\"A\"></a>"), std::string::npos) << html;
  EXPECT_NE(html.find("<img src=\"data:image/svg+xml;base64,PHN2Zy8+\">"), std::string::npos);  // %20 decoded
  EXPECT_NE(html.find("<a href=\"#boundary\">B</a>"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"#boundary-views\">BV</a>"), std::string::npos);
  EXPECT_NE(html.find("<a>3D</a>"), std::string::npos);  // no viewer embedded: the link goes
  EXPECT_NE(html.find("<a href=\"report.json\">json</a>"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"data/edges.csv\">e</a>"), std::string::npos);
  EXPECT_NE(html.find("<a href=\"#quality\">q</a>"), std::string::npos);
  EXPECT_NE(html.find("href=\"https://doi.org/x?a=1&amp;b=2\""), std::string::npos);
  // The boundary section: ids prefixed, links back to the index in-page.
  EXPECT_NE(html.find("<section id=\"boundary\""), std::string::npos);
  EXPECT_NE(html.find("<h1 id=\"boundary-views\">V</h1><a href=\"#quality\">back</a> <a href=\"#boundary-views\">"),
            std::string::npos);
  EXPECT_NE(html.find("<img src=\"views/missing.png\">"), std::string::npos);  // a missing file: left as it was
  EXPECT_LT(html.find("<section id=\"boundary\""), html.find("</body>"));
  EXPECT_EQ(html, single_file_html(sources(index, &boundary, nullptr)));  // deterministic
}

TEST(SingleFile, EmbedsTheViewerWithItsScripts) {
  const std::string index = "<html><body><a href=\"viewer.html#cluster-2\">3D</a></body></html>";
  const std::string viewer =
      "<html><body><a href=\"index.html\">back</a><script src=\"viewer/v.js\"></script></body></html>";
  const std::string html = single_file_html(sources(index, nullptr, &viewer));
  EXPECT_NE(html.find("<a href=\"#viewer\">3D</a>"), std::string::npos);
  // srcdoc holds the viewer with the script inline: '"' and '&' escaped for
  // the attribute, "</script" inside the script broken up.
  const std::size_t at = html.find("srcdoc=\"");
  ASSERT_NE(at, std::string::npos);
  const std::string srcdoc = html.substr(at + 8, html.find('"', at + 8) - at - 8);
  EXPECT_NE(srcdoc.find("<script>var s = '<\\/script><b>'; var t = 1 < 2;</script>"), std::string::npos) << srcdoc;
  EXPECT_NE(srcdoc.find("<a>back</a>"), std::string::npos);
  EXPECT_EQ(srcdoc.find("viewer/v.js"), std::string::npos);
  const std::string missing = "<html><body><script src=\"viewer/none.js\"></script></body></html>";
  EXPECT_THROW(single_file_html(sources(index, nullptr, &missing)), Error);
  EXPECT_EQ(parse_single_file("pages"), SingleFile::pages);
  EXPECT_EQ(parse_single_file("viewer"), SingleFile::viewer);
  EXPECT_THROW(parse_single_file("all"), ValueError);
}

}  // namespace
}  // namespace hq
