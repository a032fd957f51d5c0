#pragma once
// Checks that output is text (issue 46, "Messages are text"), independent of
// hq::message_text: UTF-8 validity by glibc's iconv.

#include <string>
#include <string_view>

namespace hq::test {

// True when bytes are valid UTF-8 (iconv refuses overlong forms, surrogates
// and code points above U+10FFFF).
bool is_valid_utf8(std::string_view bytes);

// The offset of the first control character of UTF-8 text (C0 but the
// characters of `allowed`, DEL, C1 U+0080..U+009F), npos when none.
std::size_t find_control_character(std::string_view text, std::string_view allowed = "\n");

}  // namespace hq::test
