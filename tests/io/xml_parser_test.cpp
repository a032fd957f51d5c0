// The small XML parser behind the .vtu reader: elements, attributes, text,
// comments, stopping at AppendedData, and its errors.

#include "hqview/io/xml_parser.h"

#include <gtest/gtest.h>

#include "error_text.h"

namespace hq::detail {
namespace HQ_TEST_UNIT {

using test::error_text;

TEST(XmlParser, ElementsAttributesAndText) {
  const XmlDocument doc = parse_xml(
      "<?xml version=\"1.0\"?>\n<!-- a comment -->\n<!DOCTYPE x>\n<a k='1' v=\"a&lt;b&amp;&#65;&#x42;\">\n"
      "  <b>text here</b>\n  <c/>\n<![CDATA[ignored <x> ]]></a>\n",
      "t.xml");
  ASSERT_EQ(doc.elements.size(), 3u);
  const XmlElement& a = doc.elements[0];
  EXPECT_EQ(a.name, "a");
  EXPECT_EQ(a.line, 4);
  EXPECT_EQ(*a.attribute("k"), "1");
  EXPECT_EQ(*a.attribute("v"), "a<b&AB");
  EXPECT_EQ(a.attribute("missing"), nullptr);
  ASSERT_EQ(a.children.size(), 2u);
  const XmlElement& b = doc.elements[a.children[0]];
  EXPECT_EQ(b.name, "b");
  EXPECT_EQ(b.text, "text here");
  EXPECT_EQ(b.line, 5);
  EXPECT_EQ(b.text_line, 5);
  EXPECT_EQ(doc.elements[a.children[1]].name, "c");
  EXPECT_EQ(doc.stop_element, static_cast<std::size_t>(-1));
}

TEST(XmlParser, StopsAtTheNamedElement) {
  const std::string bytes = "<r>\n<AppendedData encoding=\"raw\">_\x01\x02<</r>";
  const XmlDocument doc = parse_xml(bytes, "t.xml", "AppendedData");
  ASSERT_EQ(doc.elements.size(), 2u);
  EXPECT_EQ(doc.stop_element, 1u);
  EXPECT_EQ(bytes.substr(doc.stop_offset, 1), "_");
}

TEST(XmlParser, Errors) {
  const auto error = [](const std::string& text) { return error_text<ParseError>([&] { parse_xml(text, "t.xml"); }); };
  EXPECT_EQ(error(""), "t.xml:1: no XML element");
  EXPECT_EQ(error("<a>\n<b>\n</a>"), "t.xml:3: closing tag </a> does not match <b> (line 2)");
  EXPECT_EQ(error("<a>\n<b>"), "t.xml:2: unexpected end of file: element <b> (line 2) is not closed");
  EXPECT_EQ(error("<a x=1/>"), "t.xml:1: expected a quoted value for attribute x");
  EXPECT_EQ(error("<a x='1' x='2'/>"), "t.xml:1: repeated attribute x");
  EXPECT_EQ(error("<a x='1/>"), "t.xml:1: unterminated value of attribute x");
  EXPECT_EQ(error("<a x='&bogus;'/>"), "t.xml:1: unknown entity &bogus;");
  EXPECT_EQ(error("<a/>\n<b/>"), "t.xml:2: a second root element");
  EXPECT_EQ(error("<a/>\ntrailing"), "t.xml:2: text after the root element");
  EXPECT_EQ(error("junk <a/>"), "t.xml:1: text before the root element");
  EXPECT_EQ(error("<a><!-- open"), "t.xml:1: unterminated comment");
  EXPECT_EQ(error("</a>"), "t.xml:1: closing tag </a> without an open element");
  EXPECT_EQ(error("<a x='1'y='2'/>"), "t.xml:1: expected a space, '>' or '/>' in <a>, got 'y'");
  EXPECT_EQ(error("<a\n"), "t.xml:1: unexpected end of file in the start tag <a>");
}

}  // namespace
}  // namespace hq::detail
