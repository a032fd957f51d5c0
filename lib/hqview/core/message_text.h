#pragma once
// Text from input (file names, tokens a reader quotes, labels, error
// messages) made safe to show: every sink of HQView's messages (standard
// error, report.json, index.json, junit.xml, the pages, summary.md, charts)
// passes what it shows through message_text, so no input byte can garble a
// terminal, a log or a page (docs/contract.md, "Messages are text").

#include <string>
#include <string_view>

namespace hq {

// Whether '\n' is kept (text of several lines that HQView composes: a JUnit
// failure body, `diff`'s report) or escaped (one message, one line).
enum class LineBreaks { escaped, kept };

// bytes with valid UTF-8 (RFC 3629: shortest form, no surrogates, at most
// U+10FFFF) kept as it is, except the control characters C0 (U+0000 to
// U+001F), DEL (U+007F) and C1 (U+0080 to U+009F). Every byte that is not
// part of a valid sequence (a stray continuation byte, a truncated or
// overlong sequence, a surrogate, 0xF5 to 0xFF) and every byte of a control
// character becomes the four characters \xHH (two lowercase hex digits):
// "\xa6" for the byte 0xA6, "\x1b" for ESC, "\xc2\x85" for U+0085 (NEL).
// The result is valid UTF-8 without control characters (but '\n' when
// line_breaks is kept). A backslash is kept as it is, so the escaping is
// not reversible ("\xa6" in the input shows as itself) but idempotent:
// message_text(message_text(s)) == message_text(s), and text that is
// already valid UTF-8 without controls (every ASCII path, every UTF-8 name)
// is returned unchanged, byte for byte.
std::string message_text(std::string_view bytes, LineBreaks line_breaks = LineBreaks::escaped);

// The length of the valid UTF-8 sequence that starts at text[i] (1 to 4),
// 0 when none does (the rules of message_text).
std::size_t utf8_sequence_length(std::string_view text, std::size_t i);

}  // namespace hq
