#pragma once
// Shared body of the reader fuzz targets: feed the bytes to one reader and
// accept only hq::Error (ParseError, InputError, ...) as a rejection. Any
// other exception escapes to libFuzzer and is reported as a finding, as are
// crashes and sanitizer reports.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "hqview/core/error.h"

namespace hq::fuzz {

template <class Reader>
int run_reader(const std::uint8_t* data, std::size_t size, Reader&& reader) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    (void)reader(bytes, std::string("fuzz-input"));
  } catch (const hq::Error&) {
    // A clean rejection of malformed input.
  }
  return 0;
}

}  // namespace hq::fuzz
