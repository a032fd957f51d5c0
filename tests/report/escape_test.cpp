// The escapers of report/escape.h on input text that is not UTF-8 or holds
// control characters (issue 46, "Messages are text"); Markdown's own rules
// are checked in report_pages_test.cpp.
#include "hqview/report/escape.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace hq {
namespace HQ_TEST_UNIT {

TEST(XmlEscape, WhatXml10ForbidsIsEscaped) {
  EXPECT_EQ(xml_escape("a<b>&\"'"), "a&lt;b&gt;&amp;&quot;&apos;");
  EXPECT_EQ(xml_escape("one\ntwo"), "one&#10;two");
  EXPECT_EQ(xml_escape("\t\r\x1b\x7f\xc2\x85"), "\\x09\\x0d\\x1b\\x7f\\xc2\\x85");
  EXPECT_EQ(xml_escape("D\xa6ta"), "D\\xa6ta");
  // U+FFFE and U+FFFF are valid UTF-8 but no XML 1.0 characters; U+FFFD is one.
  EXPECT_EQ(xml_escape("\xef\xbf\xbe|\xef\xbf\xbf|\xef\xbf\xbd"), "\\xef\\xbf\\xbe|\\xef\\xbf\\xbf|\xef\xbf\xbd");
  EXPECT_EQ(xml_escape("caf\xc3\xa9 \xf0\x9d\x84\x9e"), "caf\xc3\xa9 \xf0\x9d\x84\x9e");
}

TEST(HtmlEscape, MustacheEntitiesAfterMessageText) {
  EXPECT_EQ(html_escape("<script>\"x\" & 'y'</script>"),
            "&lt;script&gt;&quot;x&quot; &amp; &apos;y&apos;&lt;/script&gt;");
  EXPECT_EQ(html_escape("bad\xa6\x1bname.mesh"), "bad\\xa6\\x1bname.mesh");
  EXPECT_EQ(html_escape("two\nlines"), "two\\x0alines");
  EXPECT_EQ(html_escape("maillage \xc3\xa9"), "maillage \xc3\xa9");
}

TEST(JsonMessageText, EveryStringAndKeyEscapedNumbersKept) {
  nlohmann::ordered_json j = {{"path", "bad\xa6\x1bname.mesh"},
                              {"n", 3},
                              {"list", {"ok", "\x1b[31m", nullptr, 1.5}},
                              {"by_label", {{"m\xff", {{"x", "\xc2\x9b"}}}}}};
  const nlohmann::ordered_json e = json_message_text(j);
  EXPECT_EQ(e["path"], "bad\\xa6\\x1bname.mesh");
  EXPECT_EQ(e["n"], 3);
  EXPECT_EQ(e["list"], nlohmann::ordered_json({"ok", "\\x1b[31m", nullptr, 1.5}));
  ASSERT_TRUE(e["by_label"].contains("m\\xff"));
  EXPECT_EQ(e["by_label"]["m\\xff"]["x"], "\\xc2\\x9b");
  // Dumps without the replacement handler (it would throw on invalid UTF-8),
  // the key order kept; clean JSON is unchanged.
  EXPECT_EQ(e.dump(),
            "{\"path\":\"bad\\\\xa6\\\\x1bname.mesh\",\"n\":3,\"list\":[\"ok\",\"\\\\x1b[31m\",null,1.5],"
            "\"by_label\":{\"m\\\\xff\":{\"x\":\"\\\\xc2\\\\x9b\"}}}");
  const nlohmann::json clean = {{"a", {1, "b\\c \xc3\xa9"}}};
  EXPECT_EQ(json_message_text(clean), clean);
}

}  // namespace
}  // namespace hq
