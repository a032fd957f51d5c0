#include "hqview/io/text_scanner.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <cmath>
#include <limits>

#include "io/error_text.h"

namespace hq::detail {
namespace HQ_TEST_UNIT {

using hq::test::error_text;

// The entry lines of a section as skip_space() finds them: blank and
// comment lines skipped, a comment after an entry kept on its line; marks
// by hand from the text below.
TEST(TextScanner, MarksEntryLinesAsSkipSpaceFindsThem) {
  const std::string text =
      "4\n"             // line 1, offsets 0-1
      "a 1\n"           // line 2, entry 0 at offset 2
      "\n"              // line 3
      "# note\n"        // line 4, offsets 7-13
      "  b 2 # c\r\n"   // line 5, offsets 14-24: entry 1 at 16 (after 2 blanks)
      "c 3\n"           // line 6, entry 2 at offset 25
      "\t\n"            // line 7, offsets 29-30
      "d 4\n"           // line 8, entry 3 at offset 31; its newline at 34
      "rest\n";
  TextScanner s(text, "t", true);
  std::int64_t n = 0;
  ASSERT_TRUE(s.read_int(n));
  std::vector<TextScanner::Mark> starts;
  TextScanner::Mark end;
  ASSERT_TRUE(s.mark_entry_lines(4, {0, 1, 3}, starts, end));
  ASSERT_EQ(starts.size(), 3u);
  EXPECT_EQ(starts[0].offset, 2u);
  EXPECT_EQ(starts[0].line, 2);
  EXPECT_EQ(starts[1].offset, 16u);
  EXPECT_EQ(starts[1].line, 5);
  EXPECT_EQ(starts[2].offset, 31u);
  EXPECT_EQ(starts[2].line, 8);
  EXPECT_EQ(end.offset, 34u);
  EXPECT_EQ(end.line, 8);
  EXPECT_EQ(s.line(), 1);  // not moved
  // A part read from its mark by its own scanner sees the same lines.
  TextScanner part(s, starts[1].offset, starts[2].offset, starts[1].line);
  ASSERT_TRUE(part.skip_space());
  EXPECT_EQ(part.read_token(), "b");
  ASSERT_TRUE(part.skip_space());
  EXPECT_EQ(part.read_token(), "2");
  ASSERT_TRUE(part.skip_space());
  EXPECT_EQ(part.line(), 6);
  EXPECT_EQ(part.read_token(), "c");
  // After the last entry: where reading goes on, with its line.
  s.move_to(end);
  ASSERT_TRUE(s.skip_space());
  EXPECT_EQ(s.line(), 9);
  EXPECT_EQ(s.read_token(), "rest");
  // Fewer entry lines than asked for.
  TextScanner again(text, "t", true);
  EXPECT_FALSE(again.mark_entry_lines(7, {0}, starts, end));
}

TEST(TextScanner, SkipsSpaceAndCommentsCountingLines) {
  TextScanner s("  # comment\n\n\tVertices # trailing\r\n 12", "t", true);
  ASSERT_TRUE(s.skip_space());
  EXPECT_EQ(s.line(), 3);
  EXPECT_EQ(s.read_token(), "Vertices");
  EXPECT_FALSE(s.skip_blank());  // the comment ends the line
  ASSERT_TRUE(s.skip_space());
  EXPECT_EQ(s.line(), 4);
  std::int64_t n = 0;
  EXPECT_TRUE(s.read_int(n));
  EXPECT_EQ(n, 12);
  EXPECT_FALSE(s.skip_space());
  EXPECT_TRUE(s.at_end());
}

TEST(TextScanner, HashIsATokenWithoutComments) {
  TextScanner s("# vtk", "t", false);
  ASSERT_TRUE(s.skip_space());
  EXPECT_EQ(s.read_token(), "#");
}

TEST(TextScanner, ReadsNumbersOnlyWhenTheWholeTokenIsOne) {
  TextScanner s("12abc 1.5e3 +7 -2 +.5 1e999 nan", "t", false);
  std::int64_t i = 0;
  double d = 0.0;
  ASSERT_TRUE(s.skip_space());
  EXPECT_FALSE(s.read_int(i));
  EXPECT_FALSE(s.read_double(d));
  EXPECT_EQ(s.read_token(), "12abc");  // did not move on failure
  s.skip_space();
  EXPECT_FALSE(s.read_int(i));
  EXPECT_TRUE(s.read_double(d));
  EXPECT_EQ(d, 1500.0);
  s.skip_space();
  EXPECT_TRUE(s.read_int(i));
  EXPECT_EQ(i, 7);
  s.skip_space();
  EXPECT_TRUE(s.read_int(i));
  EXPECT_EQ(i, -2);
  s.skip_space();
  EXPECT_TRUE(s.read_double(d));
  EXPECT_EQ(d, 0.5);
  s.skip_space();
  EXPECT_FALSE(s.read_double(d));  // out of range
  s.read_token();
  s.skip_space();
  EXPECT_TRUE(s.read_double(d));  // the caller rejects non-finite values
  EXPECT_TRUE(std::isnan(d));
}

TEST(TextScanner, IntegerOverflowIsNotANumber) {
  TextScanner s("99999999999999999999", "t", false);
  std::int64_t i = 0;
  EXPECT_FALSE(s.read_int(i));
}

TEST(TextScanner, LineAwareReading) {
  TextScanner s("1 2 3\n4", "t", false);
  std::int64_t v = 0;
  ASSERT_TRUE(s.skip_blank());
  ASSERT_TRUE(s.read_int(v));
  EXPECT_EQ(s.count_tokens_on_line(), 2);
  EXPECT_FALSE(s.skip_blank());
  EXPECT_TRUE(s.finish_line());
  EXPECT_EQ(s.line(), 2);
  EXPECT_TRUE(s.skip_blank());
  EXPECT_FALSE(s.finish_line());
}

TEST(TextScanner, ReadLineStripsCarriageReturn) {
  TextScanner s("title\r\nnext", "t", false);
  EXPECT_EQ(s.read_line(), "title");
  EXPECT_EQ(s.line(), 2);
  EXPECT_EQ(s.read_line(), "next");
  EXPECT_TRUE(s.at_end());
}

TEST(TextScanner, ReadBytesCountsNewlines) {
  using namespace std::string_literals;
  const std::string text = "A\n\x00\n\n\x01\nB"s;
  TextScanner s(std::string_view(text.data(), text.size()), "t", false);
  s.read_line();
  EXPECT_EQ(s.read_bytes(4).size(), 4u);
  EXPECT_EQ(s.line(), 4);
  ASSERT_TRUE(s.skip_space());
  EXPECT_EQ(s.line(), 5);
  EXPECT_EQ(s.offset(), text.size() - 1);
}

TEST(TextScanner, FailThrowsParseErrorWithNameAndLine) {
  TextScanner s("a\nb", "file.mesh", false);
  s.read_line();
  EXPECT_EQ(error_text<ParseError>([&] { s.fail("bad thing"); }), "file.mesh:2: bad thing");
  EXPECT_EQ(error_text<ParseError>([&] { s.fail_at(0, "no line"); }), "file.mesh: no line");
}

TEST(TextScanner, QuoteShortensAndEscapes) {
  EXPECT_EQ(quote("abc"), "'abc'");
  EXPECT_EQ(quote(std::string_view("a\x01\xff", 3)), "'a\\x01\\xff'");
  EXPECT_EQ(quote(std::string(50, 'x')), "'" + std::string(40, 'x') + "...'");
  // Valid UTF-8 is kept, never cut inside a character; invalid bytes, ESC as \xhh.
  EXPECT_EQ(quote("caf\xc3\xa9 \xa6\x1b"), "'caf\xc3\xa9 \\xa6\\x1b'");
  EXPECT_EQ(quote(std::string(39, 'x') + "\xc3\xa9yz"), "'" + std::string(39, 'x') + "...'");
  EXPECT_EQ(quote(std::string(39, 'x') + "\xa6\xa6yz"), "'" + std::string(39, 'x') + "\\xa6...'");
}

TEST(TextScanner, CaseInsensitiveHelpers) {
  EXPECT_TRUE(iequals("Hexahedra", "HEXAHEDRA"));
  EXPECT_FALSE(iequals("Hexahedra", "Hexaedra"));
  EXPECT_TRUE(istarts_with("# VTK DataFile Version 3.0", "# vtk DataFile"));
  EXPECT_FALSE(istarts_with("# vt", "# vtk"));
}

TEST(TextScanner, ExceedsRemainingIsOverflowFree) {
  EXPECT_FALSE(exceeds_remaining(3, 2, 5, true));  // "1 2 3"
  EXPECT_TRUE(exceeds_remaining(3, 2, 4, true));
  EXPECT_FALSE(exceeds_remaining(3, 4, 12, false));
  EXPECT_TRUE(exceeds_remaining(3, 4, 11, false));
  EXPECT_TRUE(exceeds_remaining(std::numeric_limits<std::int64_t>::max(), 8, 100, false));
  EXPECT_FALSE(exceeds_remaining(0, 8, 0, false));
}

}  // namespace
}  // namespace hq::detail
