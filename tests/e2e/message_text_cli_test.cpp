// Messages are text (issue 46): a mesh whose file NAME holds a byte that is
// not UTF-8 (0xA6) and ESC (0x1B), analysed, refused and run in a batch.
// Everything hqview writes (standard error, report.json, the pages, the
// viewer, index.json, junit.xml, summary.md) is valid UTF-8 without control
// characters and shows the name as bad\xa6\x1bname; links still reach the
// bundle (percent-encoded bytes). Three runs of hqview on one-hex meshes.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli_runner.h"
#include "support/fixtures.h"
#include "support/text_checks.h"

namespace hq::test {
namespace HQ_TEST_UNIT {

namespace fs = std::filesystem;

const std::string kName = "bad\xa6\x1bname";     // on disk
const std::string kShown = "bad\\xa6\\x1bname";  // as every output shows it

// Valid UTF-8, no control character but line breaks (and tabs in files).
void expect_text(const std::string& what, const std::string& bytes, std::string_view allowed = "\n") {
  EXPECT_TRUE(is_valid_utf8(bytes)) << what << " is not UTF-8";
  const std::size_t at = find_control_character(bytes, allowed);
  EXPECT_EQ(at, std::string::npos) << what << ": control character at byte " << at;
}

void expect_file_text(const fs::path& file, const std::string& must_contain) {
  ASSERT_TRUE(fs::is_regular_file(file)) << file;
  const std::string text = read_text(file);
  expect_text(file.filename().string(), text, "\n\t");
  EXPECT_NE(text.find(must_contain), std::string::npos) << file << " lacks " << must_contain;
}

TEST(MessagesAreText, MeshFileNamedWithBytesThatAreNotUtf8) {
  const fs::path root = fresh_output_dir("message_text");
  const fs::path in = root / "in";
  fs::create_directories(in);
  const fs::path mesh = in / (kName + ".mesh"), refused = in / (kName + "-flip.vtu");
  fs::copy_file(source_dir() / "tests/bad_inputs/medit_one_hex.mesh", mesh);
  fs::copy_file(source_dir() / "tests/bad_inputs/vtu_not_utf8_closing_tag.vtu", refused);
  const std::string in_shown = in.string() + "/";  // the build tree's path is ASCII

  // analyze, drawing a chart and a 3D view whose titles hold the name (Cairo
  // refused the raw bytes: "internal error" before issue 46).
  const fs::path bundle = root / "bundle";
  const CliResult a = run_hqview({"analyze", mesh.string(), "-o", bundle.string(), "--views", "histogram,overview"});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  expect_text("analyze's stderr", a.err);
  EXPECT_EQ(read_report(bundle)["input"]["mesh"]["path"], kShown + ".mesh");
  expect_file_text(bundle / "report.json", "\"" + std::string("bad\\\\xa6\\\\x1bname.mesh") + "\"");
  expect_file_text(bundle / "index.html", "<span class=\"file\">" + kShown + ".mesh</span>");
  expect_file_text(bundle / "summary.md", "## HQView: bad\\\\xa6\\\\x1bname\\.mesh");
  expect_file_text(bundle / "viewer.html", "<h1>" + kShown + ".mesh</h1>");
  expect_file_text(bundle / "viewer/data.js", "\"name\":\"bad\\\\xa6\\\\x1bname.mesh\"");
  EXPECT_TRUE(fs::is_regular_file(bundle / "views/histogram.png"));

  // A refusal quoting the file: the path and the flipped tag escaped.
  const CliResult r = run_hqview({"analyze", refused.string(), "-o", (root / "refused").string(), "--no-render", "-q"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.err, "hqview: " + in_shown + kShown +
                       "-flip.vtu:5: closing tag </D\\xa6\\x1btaArray> does not match <DataArray> (line 5)\n");

  // batch: both meshes; index.json, junit.xml, index.html, summary.md.
  const fs::path batch = root / "batch";
  const CliResult b = run_hqview({"batch", in.string(), "-o", batch.string(), "--no-render"});
  EXPECT_EQ(b.exit_code, 3) << b.err;  // one mesh failed on its input
  expect_text("batch's stderr", b.err);
  EXPECT_NE(b.err.find("] failed " + kShown + "-flip.vtu ("), std::string::npos) << b.err;
  EXPECT_NE(b.err.find("] ok " + kShown + ".mesh ("), std::string::npos) << b.err;
  expect_file_text(batch / "index.json", "bad\\\\xa6\\\\x1bname.mesh");
  const nlohmann::json index = nlohmann::json::parse(read_text(batch / "index.json"));  // throws on invalid UTF-8
  ASSERT_EQ(index["meshes"].size(), 2u);
  EXPECT_EQ(index["meshes"][0]["path"], kShown + "-flip.vtu");
  EXPECT_EQ(index["meshes"][0]["error"],
            in_shown + kShown + "-flip.vtu:5: closing tag </D\\xa6\\x1btaArray> does not match <DataArray> (line 5)");
  EXPECT_EQ(index["meshes"][1]["path"], kShown + ".mesh");
  expect_file_text(batch / "junit.xml", "<testcase classname=\"hqview\" name=\"" + kShown + ".mesh\"/>");
  expect_file_text(batch / "junit.xml", "closing tag &lt;/D\\xa6\\x1btaArray&gt;");
  const std::string parse_junit = "python3 -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' '" +
                                  (batch / "junit.xml").string() + "'";
  EXPECT_EQ(std::system(parse_junit.c_str()), 0) << "junit.xml is not well-formed XML";
  // The page shows the escaped name and links to the bundle by its bytes.
  expect_file_text(batch / "index.html", kShown + ".<wbr>mesh");  // a break after the dot (html_with_breaks)
  expect_file_text(batch / "index.html", "href=\"bad%A6%1Bname.mesh/index.html\"");
  EXPECT_TRUE(fs::is_regular_file(batch / (kName + ".mesh") / "index.html"));
  expect_file_text(batch / "summary.md", "[bad\\\\xa6\\\\x1bname\\.mesh](bad%A6%1Bname.mesh/index.html)");
}

}  // namespace
}  // namespace hq::test
