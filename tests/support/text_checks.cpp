#include "support/text_checks.h"

#include <iconv.h>

#include <stdexcept>

namespace hq::test {

bool is_valid_utf8(std::string_view bytes) {
  iconv_t cd = ::iconv_open("UTF-32LE", "UTF-8");
  if (cd == reinterpret_cast<iconv_t>(-1)) throw std::runtime_error("iconv_open(UTF-32LE, UTF-8) failed");
  std::string in(bytes);
  std::string out(4 * bytes.size() + 4, '\0');
  char* in_ptr = in.data();
  char* out_ptr = out.data();
  std::size_t in_left = in.size(), out_left = out.size();
  const std::size_t result = ::iconv(cd, &in_ptr, &in_left, &out_ptr, &out_left);
  ::iconv_close(cd);
  return result != static_cast<std::size_t>(-1) && in_left == 0;
}

std::size_t find_control_character(std::string_view text, std::string_view allowed) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto b = static_cast<unsigned char>(text[i]);
    if ((b < 0x20 || b == 0x7F) && allowed.find(static_cast<char>(b)) == std::string_view::npos) return i;
    if (b == 0xC2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) < 0xA0) return i;
  }
  return std::string_view::npos;
}

}  // namespace hq::test
