// index.html, boundary.html and summary.md from hand-built report models:
// escaping of input text, the anchors that link panels A–F, the bar links of
// chart B, and the Markdown escaping as a CommonMark reader undoes it.

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <string>

#include "hqview/core/error.h"
#include "hqview/report/report_html.h"
#include "hqview/report/escape.h"
#include "hqview/report/report_markdown.h"

namespace hq {
namespace HQ_TEST_UNIT {

// CommonMark's reading of escaped text: "\c" is c for ASCII punctuation c,
// and the three entities markdown_escape writes.
std::string commonmark_unescape(const std::string& md) {
  std::string out;
  for (std::size_t i = 0; i < md.size(); ++i) {
    if (md[i] == '\\' && i + 1 < md.size() && std::ispunct(static_cast<unsigned char>(md[i + 1]))) {
      out += md[++i];
    } else if (md.compare(i, 5, "&amp;") == 0) {
      out += '&';
      i += 4;
    } else if (md.compare(i, 4, "&lt;") == 0) {
      out += '<';
      i += 3;
    } else if (md.compare(i, 4, "&gt;") == 0) {
      out += '>';
      i += 3;
    } else {
      out += md[i];
    }
  }
  return out;
}

TEST(MarkdownEscape, HandExamples) {
  EXPECT_EQ(markdown_escape("ball.mesh"), "ball\\.mesh");
  EXPECT_EQ(markdown_escape("a_b*c"), "a\\_b\\*c");
  EXPECT_EQ(markdown_escape("<b>&"), "&lt;b&gt;&amp;");
  EXPECT_EQ(markdown_escape("[x](javascript:y)"), "\\[x\\]\\(javascript\\:y\\)");
  EXPECT_EQ(markdown_escape("@team #1 | `c`"), "\\@team \\#1 \\| \\`c\\`");
  // Control characters and bytes that are not UTF-8 as \xhh (its backslash
  // escaped: it reads "\x0a"), so a table row stays one row.
  EXPECT_EQ(markdown_escape("two\nlines\r\tend"), "two\\\\x0alines\\\\x0d\\\\x09end");
  EXPECT_EQ(markdown_escape("</D\xa6ta\x1b[2J>"), "&lt;\\/D\\\\xa6ta\\\\x1b\\[2J&gt;");
  EXPECT_EQ(markdown_escape("maillage é"), "maillage é");  // UTF-8 passes through
}

TEST(MarkdownEscape, EveryPrintableAsciiReadsBackLiterally) {
  std::string all;
  for (int c = 0x20; c < 0x7f; ++c) all += static_cast<char>(c);
  const std::string md = markdown_escape(all);
  EXPECT_EQ(commonmark_unescape(md), all);
  EXPECT_EQ(md.find('<'), std::string::npos);
  EXPECT_EQ(md.find('>'), std::string::npos);
  // Every punctuation character left is escaped or part of an entity.
  for (std::size_t i = 0; i < md.size(); ++i) {
    const char c = md[i];
    if (!std::ispunct(static_cast<unsigned char>(c)) || c == '\\') continue;
    const bool escaped = i > 0 && md[i - 1] == '\\';
    const bool in_entity = c == '&' || c == ';';
    EXPECT_TRUE(escaped || in_entity) << "unescaped '" << c << "' at " << i << " in " << md;
  }
}

// A file name (no '/') that would run script in a page that did not escape it.
const std::string kEvilName = "x<script>alert(1)<img src=y onerror=alert(3)>\"q'&amp;[l](u)*.mesh";

// A model with 4 vertices, 3 in 2 clusters (0: vertices 0 and 1, 1: vertex 2),
// a C view of cluster 0, D and E views of vertex 1, and chart B with bars on
// vertices 1, 2, 0 (worst first).
ReportModel linked_model() {
  ReportModel m;
  m.tool_version = "9.9.9";
  m.analysis.mesh_input = {kEvilName, "medit", std::string(64, 'a')};
  m.analysis.warnings = {"line 3: <img src=x onerror=alert(2)> & more"};
  m.analysis.field.vertex_quality = {0.2, -0.5, 0.1, 0.9};
  m.analysis.quality.worst_vertices = {{1, -0.5, {}}, {2, 0.1, {}}, {3, 0.9, {}}};
  GlyphResult& g = m.analysis.glyphs.emplace();
  g.vertex_cluster = {0, 0, 1, kNoIndex};
  g.clusters = {{0, 2, 0, {}, -0.5, 1.5, 0.1}, {1, 1, 2, {}, 0.1, 0.9, 0.05}};
  g.options.top_clusters = 1;
  m.views.push_back({"clusters", "C: sub-region", {"views/cluster_0.png"}, {{0, kNoIndex, {}}}});
  m.views.push_back({"local", "D: local", {"views/local_v1.png"}, {{0, 1, {}}}});
  m.views.push_back(
      {"corners", "E: corners", {"views/corners_v1.svg", "views/corners_v1.png"}, {{0, 1, {}}, {0, 1, {}}}});
  ViewFileLinks bars;
  bars.hotspots = {{{0.1, 0.2, 0.05, 0.5, {}}, 1}, {{0.15, 0.2, 0.05, 0.5, {}}, 2}, {{0.2, 0.2, 0.05, 0.5, {}}, 0}};
  m.views.push_back(
      {"sorted_quality", "B: sorted", {"views/sorted_quality.svg", "views/sorted_quality.png"}, {bars, bars}});
  return m;
}

// The pages' one script is the template's lightbox (issue 45): no input
// text reaches a script element.
bool only_the_lightbox_script(const std::string& html) {
  const std::size_t first = html.find("<script");
  return first != std::string::npos && html.compare(first, 25, "<script id=\"hq-lightbox\">") == 0 &&
         html.find("<script", first + 1) == std::string::npos;
}

TEST(IndexHtml, InputTextIsEscapedAndNoScriptIsWritten) {
  const std::string html = index_html(linked_model());
  EXPECT_TRUE(only_the_lightbox_script(html));
  EXPECT_EQ(html.find("<img src=x"), std::string::npos);
  EXPECT_EQ(html.find("<img src=y"), std::string::npos);
  const std::string shown =
      "x&lt;script&gt;alert(1)&lt;img src=y onerror=alert(3)&gt;&quot;q&apos;&amp;amp;[l](u)*.mesh";
  EXPECT_NE(html.find("<title>" + shown), std::string::npos);
  EXPECT_NE(html.find("<span class=\"file\">" + shown + "</span>"), std::string::npos);
  EXPECT_NE(html.find("line 3: &lt;img src=x onerror=alert(2)&gt; &amp; more"), std::string::npos);
}

TEST(IndexHtml, PanelsLinkClusterRowsToCAndCToDAndE) {
  const std::string html = index_html(linked_model());
  // Anchors: C of cluster 0, D and E of vertex 1, the table rows.
  for (const char* id : {"id=\"cluster-0\"", "id=\"vertex-1\"", "id=\"corners-1\"", "id=\"cluster-row-0\"",
                         "id=\"cluster-row-1\"", "id=\"view-sorted_quality\""})
    EXPECT_NE(html.find(id), std::string::npos) << id;
  // The PNG twins of charts are not shown (their SVG is).
  EXPECT_EQ(html.find("src=\"views/corners_v1.png\""), std::string::npos);
  // Cluster 0's row leads to its C view, and to D and E of its vertex.
  const std::size_t row0 = html.find("id=\"cluster-row-0\"");
  const std::string row = html.substr(row0, html.find("</tr>", row0) - row0);
  EXPECT_NE(row.find("href=\"#cluster-0\""), std::string::npos) << row;
  EXPECT_NE(row.find("href=\"#vertex-1\""), std::string::npos) << row;
  EXPECT_NE(row.find("href=\"#corners-1\""), std::string::npos) << row;
  // Cluster 1 has no C view: its id is not a link.
  const std::size_t row1 = html.find("id=\"cluster-row-1\"");
  EXPECT_EQ(html.substr(row1, html.find("</tr>", row1) - row1).find("href=\"#cluster-1\""), std::string::npos);
  // Worst vertex rows link where the vertex is shown; vertex 3 (no cluster,
  // no view) is plain text, never an empty link.
  EXPECT_NE(html.find("<tr id=\"worst-vertex-1\"><td><a href=\"#cluster-0\">1</a>"), std::string::npos);
  EXPECT_NE(html.find("<tr id=\"worst-vertex-2\"><td><a href=\"#cluster-row-1\">2</a>"), std::string::npos);
  EXPECT_NE(html.find("<tr id=\"worst-vertex-3\"><td>3</td>"), std::string::npos);
  EXPECT_EQ(html.find("href=\"\""), std::string::npos);
  // The C view links to D, E and back to the row.
  const std::size_t c0 = html.find("id=\"cluster-0\"");
  const std::string caption = html.substr(c0, html.find("</figure>", c0) - c0);
  for (const char* href : {"href=\"#vertex-1\"", "href=\"#corners-1\"", "href=\"#cluster-row-0\""})
    EXPECT_NE(caption.find(href), std::string::npos) << href;
}

TEST(IndexHtml, ChartBarsLinkWhereTheirVertexIsShown) {
  const std::string html = index_html(linked_model());
  // Bar 1 (vertex 1): its cluster 0 has a C view. Bar 2 (vertex 2): cluster
  // 1 has no C and vertex 2 no D view: its table row. Bar 3 (vertex 0):
  // cluster 0's C view. Positions in percent of the image.
  const std::string bar1 =
      "<a class=\"hotspot\" href=\"#cluster-0\" style=\"left:10.0000%;top:20.0000%;width:5.0000%;height:50.0000%\"";
  const std::string bar2 =
      "<a class=\"hotspot\" href=\"#cluster-row-1\" style=\"left:15.0000%;top:20.0000%;width:5.0000%;height:50.0000%\"";
  const std::string bar3 =
      "<a class=\"hotspot\" href=\"#cluster-0\" style=\"left:20.0000%;top:20.0000%;width:5.0000%;height:50.0000%\"";
  const std::size_t p1 = html.find(bar1), p2 = html.find(bar2), p3 = html.find(bar3);
  ASSERT_NE(p1, std::string::npos);
  ASSERT_NE(p2, std::string::npos);
  ASSERT_NE(p3, std::string::npos);
  EXPECT_LT(p1, p2);
  EXPECT_LT(p2, p3);
  EXPECT_NE(html.find("title=\"rank 1: vertex 1, quality -0.5\""), std::string::npos);
}

TEST(IndexHtml, DataFilesAndBoundaryPageAreLinkedOnlyWhenWritten) {
  ReportModel m = linked_model();
  // --data none: no per-cell file linked, the page says how to get them.
  m.data = parse_data_formats("none");
  std::string none = index_html(m);
  EXPECT_EQ(none.find("data/annotated.vtu"), std::string::npos);
  EXPECT_EQ(none.find("data/cells.csv"), std::string::npos);
  EXPECT_NE(none.find("href=\"data/edges.csv\""), std::string::npos);
  EXPECT_NE(none.find("<code>--data none</code>"), std::string::npos);
  EXPECT_EQ(none.find("href=\"boundary.html\""), std::string::npos);
  // csv.gz: the gzip'ed tables, not the plain ones or the VTU.
  m.data = parse_data_formats("csv.gz");
  const std::string gz = index_html(m);
  EXPECT_NE(gz.find("href=\"data/cells.csv.gz\""), std::string::npos);
  EXPECT_NE(gz.find("href=\"data/vertices.csv.gz\""), std::string::npos);
  EXPECT_EQ(gz.find("href=\"data/cells.csv\""), std::string::npos);
  EXPECT_EQ(gz.find("data/annotated.vtu"), std::string::npos);
  EXPECT_EQ(gz.find("<code>--data csv.gz</code>"), std::string::npos);  // no hint when the tables are there
  m.data = DataFormats{};  // the default: the compressed VTU, and how to get the tables
  const std::string vtu = index_html(m);
  EXPECT_EQ(vtu.find("href=\"data/cells.csv"), std::string::npos);
  EXPECT_NE(vtu.find("href=\"data/annotated.vtu\""), std::string::npos);
  EXPECT_NE(vtu.find("<code>--data csv.gz</code>"), std::string::npos);
  BoundaryError& e = m.analysis.boundary_error.emplace();
  e.hausdorff_relative = 0.0125;  // the vertex figure: not the headline's
  e.reference_bbox_diagonal = 2.0;
  e.sampled_symmetric = 0.09;
  const std::string html = index_html(m);
  EXPECT_NE(html.find("href=\"data/annotated.vtu\""), std::string::npos);
  EXPECT_NE(html.find("href=\"boundary.html\""), std::string::npos);
  EXPECT_NE(html.find("4.5 %"), std::string::npos);  // the sampled symmetric Hausdorff in the headline, named
  EXPECT_NE(html.find("Hausdorff distance (sampled, symmetric)"), std::string::npos);
  EXPECT_EQ(html.find("1.25 %"), std::string::npos);
  // summary.md's headline row: the sampled symmetric figure, named.
  const std::string md = summary_markdown(m);
  EXPECT_NE(md.find("| Hausdorff, sampled symmetric (% of bbox diagonal) |"), std::string::npos) << md;
  EXPECT_NE(md.find(" 4.5 % |"), std::string::npos) << md;
}

// On a mesh with a tet the panels and the statistics speak of cells of
// every kind, not of hexes (46q review Q-M9); a pure-hex mesh keeps its words.
TEST(IndexHtml, HybridMeshPagesSayCellsWhereHexOnlyPagesSayHexes) {
  ReportModel m = linked_model();
  const std::string hexes = index_html(m);
  EXPECT_NE(hexes.find("all 8 corners of every hex"), std::string::npos);
  EXPECT_NE(hexes.find("one-ring hexes of a vertex"), std::string::npos);
  m.analysis.mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.analysis.mesh.tets.push_back({0, 1, 2, 3});
  const std::string cells = index_html(m);
  EXPECT_EQ(cells.find("all 8 corners of every hex"), std::string::npos);
  EXPECT_EQ(cells.find("one-ring hexes"), std::string::npos);
  EXPECT_EQ(cells.find("The hexes around a chosen vertex"), std::string::npos);
  EXPECT_NE(cells.find("8 per hex, 4 per tet, 6 per wedge"), std::string::npos);
  EXPECT_NE(cells.find("one-ring cells of a vertex"), std::string::npos);
  EXPECT_NE(cells.find("of each cell&apos;s kind"), std::string::npos);
}

// The navigation bar's section names, in order.
std::vector<std::string> nav_sections(const std::string& html) {
  std::vector<std::string> names;
  const std::size_t begin = html.find("<nav"), end = html.find("</nav>");
  for (std::size_t at = html.find("<a href=", begin); at < end; at = html.find("<a href=", at + 1)) {
    const std::size_t from = html.find('>', at) + 1;
    names.push_back(html.substr(from, html.find("</a>", from) - from));
  }
  return names;
}

// A compare page (46r review M2): the same sections as the page of the same
// views without --compare, plus the comparison; it names the panels drawn
// (the first mesh's) and says where the compared mesh's own are. Panel A's
// and S's texts follow the views drawn: no glyph sentence without view A's
// glyph images, no gradation sentence without its image.
TEST(IndexHtml, ComparePageKeepsTheSectionsAndSaysWhatIsWhose) {
  ReportModel plain = linked_model();
  plain.analysis.mesh_input.path = "hextet2.msh";
  for (const char* id : {"overview", "main", "structure", "size_gradation"})
    plain.views.push_back({id, id, {std::string("views/") + id + ".png"}, {}});
  ReportModel compared = plain;
  compared.analysis.compare.emplace().input.path = "dir/hextet.msh";
  compared.views.push_back({"compare", "compare", {"views/compare.png"}, {}});
  const std::vector<std::string> without = nav_sections(index_html(plain));
  const std::string html = index_html(compared);
  const std::vector<std::string> with = nav_sections(html);
  // Every panel of the plain page, in its order, then F, then the rest.
  std::vector<std::string> panels(without.begin(), std::find(without.begin(), without.end(), "Statistics"));
  for (const char* name : {"A main", "S structure", "B sorted quality", "C clusters", "D local", "E corners"})
    EXPECT_NE(std::find(panels.begin(), panels.end(), name), panels.end()) << name;
  std::vector<std::string> expected = panels;
  expected.push_back("F reference");
  expected.push_back("Comparison");
  expected.insert(expected.end(), std::find(without.begin(), without.end(), "Statistics"), without.end());
  EXPECT_EQ(with, expected);
  // The scope sentence names each panel drawn, the compared mesh and its command.
  const std::size_t scope = html.find("id=\"compare-scope\"");
  ASSERT_NE(scope, std::string::npos);
  const std::string sentence = html.substr(scope, html.find("</p>", scope) - scope);
  for (const std::string& name : panels) EXPECT_NE(sentence.find(name), std::string::npos) << name << " in " << sentence;
  EXPECT_NE(sentence.find("show hextet2.msh only"), std::string::npos) << sentence;
  EXPECT_NE(sentence.find("hqview analyze hextet.msh with the same --views"), std::string::npos) << sentence;
  EXPECT_NE(sentence.find("compare view (panel F)"), std::string::npos) << sentence;
  // Panel A's and S's texts from their views.
  EXPECT_NE(html.find("Then sphere glyphs sit on bad vertices"), std::string::npos);
  EXPECT_NE(html.find("a smooth grading stays pale by design"), std::string::npos);
  ReportModel overview_only = compared;
  std::erase_if(overview_only.views, [](const ViewEntry& v) { return v.id == "main" || v.id == "size_gradation"; });
  const std::string fewer = index_html(overview_only);
  EXPECT_NE(fewer.find("First the overview"), std::string::npos);
  EXPECT_NE(fewer.find("A · Overview: vertex quality on the boundary"), std::string::npos);
  EXPECT_EQ(fewer.find("glyphs sit on bad vertices"), std::string::npos);
  EXPECT_EQ(fewer.find("size gradation image"), std::string::npos);
  EXPECT_NE(fewer.find("The singular edges"), std::string::npos);
  // A mesh with a tet: its overview is of corner quality (each face its own
  // kind's corners), as its legend says.
  overview_only.analysis.mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  overview_only.analysis.mesh.tets.push_back({0, 1, 2, 3});
  const std::string hybrid = index_html(overview_only);
  EXPECT_NE(hybrid.find("A · Overview: corner quality on the boundary"), std::string::npos);
  EXPECT_NE(hybrid.find("First the overview: the boundary coloured by corner quality (each face: its own cell kind&apos;s corners)"),
            std::string::npos);
}

TEST(BoundaryHtml, StatisticsViewsAndTheWayBack) {
  ReportModel m = linked_model();
  EXPECT_THROW(boundary_html(m), Error);
  BoundaryError& e = m.analysis.boundary_error.emplace();
  e.reference_bbox_diagonal = 2.0;
  e.sampled_symmetric = 0.06;             // the headline: 3 % of the diagonal
  e.relative_mesh_to_reference = 0.005;   // the papers' vertex figure
  e.on_surface_tolerance = 0.002;         // the noise floor: 0.1 %
  e.fraction_outside = 0.25;
  e.fraction_on_surface = 0.5;
  e.fraction_inside = 0.25;
  e.signed_stats.count = 7;
  e.signed_stats.max = 0.5;
  e.warnings = {"<b>far</b>"};
  m.analysis.reference_input = InputFile{"ref<&>.off", "off", std::string(64, 'b')};
  m.views.push_back(
      {"boundary_error", "Boundary error", {"views/boundary_error_front.png", "views/boundary_error_back.png"}, {}});
  m.views.push_back({"boundary_area", "Area", {"views/boundary_area.svg", "views/boundary_area.png"}, {}});
  const std::string html = boundary_html(m);
  EXPECT_NE(html.find("<h1>Boundary Error Analysis</h1>"), std::string::npos);
  EXPECT_NE(html.find("href=\"index.html\""), std::string::npos);
  EXPECT_NE(html.find("src=\"views/boundary_error_front.png\""), std::string::npos);
  EXPECT_NE(html.find("src=\"views/boundary_error_back.png\""), std::string::npos);
  EXPECT_NE(html.find("src=\"views/boundary_area.svg\""), std::string::npos);
  EXPECT_NE(html.find(">3 %<"), std::string::npos);    // 0.06 / 2 of the diagonal
  EXPECT_NE(html.find(">0.5 %<"), std::string::npos);  // the vertex figure
  EXPECT_NE(html.find(">25.0/50.0/25.0 %<"), std::string::npos);  // area outside / on / inside
  EXPECT_NE(html.find("on: |error| ≤ 0.1 % of the diagonal"), std::string::npos);
  EXPECT_NE(html.find("Hausdorff distance (sampled, symmetric)"), std::string::npos);
  EXPECT_NE(html.find("ref&lt;&amp;&gt;.off"), std::string::npos);
  EXPECT_NE(html.find("&lt;b&gt;far&lt;/b&gt;"), std::string::npos);
  EXPECT_EQ(html.find("<b>"), std::string::npos);
  EXPECT_TRUE(only_the_lightbox_script(html));
}

TEST(SummaryMarkdown, HeadlineGatesAndLinksWithInputEscaped) {
  ReportModel m = linked_model();
  m.analysis.mesh_summary.num_vertices = 3;
  m.analysis.mesh_summary.num_hexes = 1;
  m.analysis.quality.scaled_jacobian.min = -0.5;
  m.analysis.quality.scaled_jacobian.mean = 0.25;
  m.analysis.quality.scaled_jacobian.num_inverted = 1;
  m.gates = {false, {{"quality.scaled_jacobian.min>=0.2", -0.5, false}}};
  const std::string md = summary_markdown(m);
  // No HTML from input survives; the name reads back literally.
  EXPECT_EQ(md.find('<'), std::string::npos) << md;
  const std::string heading = md.substr(0, md.find('\n'));
  EXPECT_EQ(commonmark_unescape(heading), "## HQView: " + kEvilName);
  EXPECT_NE(md.find("| 3 | 1 | -0.5 | 0.25 | 1 | not checked |"), std::string::npos) << md;
  EXPECT_NE(md.find("### Gates: **failed**"), std::string::npos);
  EXPECT_NE(md.find("| quality\\.scaled\\_jacobian\\.min&gt;\\=0\\.2 | -0.5 | **fail** |"), std::string::npos) << md;
  EXPECT_NE(md.find("- line 3\\: &lt;img src\\=x onerror\\=alert\\(2\\)&gt; &amp; more"), std::string::npos) << md;
  // Links to the key PNGs, relative to the bundle (the PNG twin of a chart).
  EXPECT_NE(md.find("](views/cluster_0.png)"), std::string::npos);
  EXPECT_NE(md.find("](views/sorted_quality.png)"), std::string::npos);
  EXPECT_NE(md.find("](views/corners_v1.png)"), std::string::npos);
  EXPECT_EQ(md.find("boundary.html"), std::string::npos);
}

}  // namespace
}  // namespace hq
