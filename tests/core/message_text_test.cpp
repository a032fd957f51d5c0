#include "hqview/core/message_text.h"

#include "support/text_checks.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <string_view>

namespace hq {
namespace HQ_TEST_UNIT {

using namespace std::string_literals;

using test::find_control_character;
using test::is_valid_utf8;

TEST(MessageText, ValidUtf8IsKeptByteForByte) {
  for (const std::string& text :
       {"plain ASCII: a/b c.mesh"s, "caf\xc3\xa9"s, "\xe2\x82\xac 5"s, "\xf0\x9d\x84\x9e"s,
        "\xe6\x97\xa5\xe6\x9c\xac.vtu"s, "\xc2\xa0 no-break space (U+00A0)"s, "\xed\x9f\xbf (U+D7FF)"s,
        "\xee\x80\x80 (U+E000)"s, "\xf4\x8f\xbf\xbf (U+10FFFF)"s, "back\\slash \\x41"s, ""s})
    EXPECT_EQ(message_text(text), text);
}

TEST(MessageText, BytesThatAreNotUtf8AreEscapedOneByOne) {
  EXPECT_EQ(message_text("</D\xa6taArray>"), "</D\\xa6taArray>");  // the known case (issue 46)
  EXPECT_EQ(message_text("\x80"), "\\x80");                        // stray continuation byte
  EXPECT_EQ(message_text("\xff\xfe"), "\\xff\\xfe");
  EXPECT_EQ(message_text("\xf5\x80\x80\x80"), "\\xf5\\x80\\x80\\x80");  // no lead above F4
  // Overlong encodings of '/' (U+002F): 2, 3 and 4 bytes.
  EXPECT_EQ(message_text("\xc0\xaf"), "\\xc0\\xaf");
  EXPECT_EQ(message_text("\xc1\xbf"), "\\xc1\\xbf");
  EXPECT_EQ(message_text("\xe0\x80\xaf"), "\\xe0\\x80\\xaf");
  EXPECT_EQ(message_text("\xf0\x80\x80\xaf"), "\\xf0\\x80\\x80\\xaf");
  // Surrogates U+D800 and U+DFFF, a code point above U+10FFFF.
  EXPECT_EQ(message_text("\xed\xa0\x80"), "\\xed\\xa0\\x80");
  EXPECT_EQ(message_text("\xed\xbf\xbf"), "\\xed\\xbf\\xbf");
  EXPECT_EQ(message_text("\xf4\x90\x80\x80"), "\\xf4\\x90\\x80\\x80");
  // Truncated sequences: before an ASCII byte, at the end, before another lead.
  EXPECT_EQ(message_text("\xe2\x82"
                         "a"),
            "\\xe2\\x82a");
  EXPECT_EQ(message_text("x\xf0\x9f\x98"), "x\\xf0\\x9f\\x98");
  EXPECT_EQ(message_text("\xe2\xe2\x82\xac"), "\\xe2\xe2\x82\xac");
}

TEST(MessageText, ControlCharactersAreEscaped) {
  EXPECT_EQ(message_text("a\x1b[31mred"), "a\\x1b[31mred");
  EXPECT_EQ(message_text("\t\r\n\x7f"), "\\x09\\x0d\\x0a\\x7f");
  EXPECT_EQ(message_text(std::string_view("a\0b", 3)), "a\\x00b");
  EXPECT_EQ(message_text("\x1f "), "\\x1f ");
  // C1: U+0080, U+0085 (NEL), U+009B (CSI), U+009F escaped byte by byte; U+00A0 is not a control.
  EXPECT_EQ(message_text("\xc2\x80\xc2\x85\xc2\x9b\xc2\x9f\xc2\xa0"),
            "\\xc2\\x80\\xc2\\x85\\xc2\\x9b\\xc2\\x9f\xc2\xa0");
  // A lone C1 byte (Latin-1 CSI) is not UTF-8 at all.
  EXPECT_EQ(message_text("\x9b"
                         "2J"),
            "\\x9b2J");
}

TEST(MessageText, LineBreaksKeptOnlyWhenAsked) {
  EXPECT_EQ(message_text("one\ntwo\r\n", LineBreaks::kept), "one\ntwo\\x0d\n");
  EXPECT_EQ(message_text("one\ntwo", LineBreaks::escaped), "one\\x0atwo");
  EXPECT_EQ(message_text("\t\x1b\n", LineBreaks::kept), "\\x09\\x1b\n");
}

// Any bytes: the result is valid UTF-8 (by iconv) without control
// characters, escaping again changes nothing, and clean input is unchanged.
TEST(MessageText, AnyBytesGiveTextAndEscapingIsIdempotent) {
  std::mt19937_64 rng(46);
  int num_changed = 0;
  for (int i = 0; i < 20000; ++i) {
    std::string bytes(rng() % 12, '\0');
    for (char& c : bytes) {
      const auto r = rng();
      // Bias towards lead and continuation bytes so valid sequences occur too.
      c = static_cast<char>(r % 3 == 0 ? 0x80 + (r >> 8) % 64 : r % 3 == 1 ? 0xC0 + (r >> 8) % 64 : (r >> 8) % 256);
    }
    for (const LineBreaks lb : {LineBreaks::escaped, LineBreaks::kept}) {
      const std::string text = message_text(bytes, lb);
      ASSERT_TRUE(is_valid_utf8(text)) << "input " << i;
      const std::string_view allowed = lb == LineBreaks::kept ? "\n" : "";
      ASSERT_EQ(find_control_character(text, allowed), std::string_view::npos) << "input " << i;
      ASSERT_EQ(message_text(text, lb), text) << "input " << i;
      if (is_valid_utf8(bytes) && find_control_character(bytes, allowed) == std::string_view::npos) {
        ASSERT_EQ(text, bytes) << "input " << i;
      }
      num_changed += text != bytes;
    }
  }
  EXPECT_GT(num_changed, 1000);
}

TEST(Utf8SequenceLength, LengthsOfValidSequences) {
  EXPECT_EQ(utf8_sequence_length("a", 0), 1u);
  EXPECT_EQ(utf8_sequence_length("\xc3\xa9", 0), 2u);
  EXPECT_EQ(utf8_sequence_length("\xe2\x82\xac", 0), 3u);
  EXPECT_EQ(utf8_sequence_length("\xf0\x9d\x84\x9e", 0), 4u);
  EXPECT_EQ(utf8_sequence_length("\xf0\x9d\x84", 0), 0u);
  EXPECT_EQ(utf8_sequence_length("x\xa6", 1), 0u);
}

}  // namespace
}  // namespace hq
