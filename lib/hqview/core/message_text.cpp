#include "hqview/core/message_text.h"

namespace hq {

std::size_t utf8_sequence_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[i + k]); };
  const unsigned char lead = byte(0);
  if (lead < 0x80) return 1;
  // Unicode 15, table 3-7 (well-formed UTF-8 byte sequences): the second
  // byte's range depends on the lead, which rules out overlong forms
  // (E0 80..9F, F0 80..8F), surrogates (ED A0..BF) and code points above
  // U+10FFFF (F4 90..BF); C0, C1 and F5..FF never lead.
  std::size_t length = 0;
  unsigned char low = 0x80, high = 0xBF;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) low = 0xA0;
    if (lead == 0xED) high = 0x9F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) low = 0x90;
    if (lead == 0xF4) high = 0x8F;
  } else {
    return 0;
  }
  if (text.size() - i < length) return 0;
  if (byte(1) < low || byte(1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k)
    if (byte(k) < 0x80 || byte(k) > 0xBF) return 0;
  return length;
}

std::string message_text(std::string_view bytes, LineBreaks line_breaks) {
  static constexpr char kHex[] = "0123456789abcdef";
  const auto escape = [](std::string& out, unsigned char b) {
    out += "\\x";
    out += kHex[b >> 4];
    out += kHex[b & 15];
  };
  std::string out;
  out.reserve(bytes.size());
  for (std::size_t i = 0; i < bytes.size();) {
    const auto b = static_cast<unsigned char>(bytes[i]);
    const std::size_t n = utf8_sequence_length(bytes, i);
    const bool is_c0_or_del = n == 1 && (b < 0x20 || b == 0x7F) && !(b == '\n' && line_breaks == LineBreaks::kept);
    const bool is_c1 = n == 2 && b == 0xC2 && static_cast<unsigned char>(bytes[i + 1]) < 0xA0;  // U+0080..U+009F
    if (n == 0) {
      escape(out, b);
      ++i;
    } else if (is_c0_or_del || is_c1) {
      for (std::size_t k = 0; k < n; ++k) escape(out, static_cast<unsigned char>(bytes[i + k]));
      i += n;
    } else {
      out.append(bytes.substr(i, n));
      i += n;
    }
  }
  return out;
}

}  // namespace hq
