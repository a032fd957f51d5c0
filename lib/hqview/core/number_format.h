#pragma once
// Shortest round-trip decimal text of a double (std::to_chars), the one
// float format of every HQView output: same value, same bytes.

#include <charconv>
#include <cmath>
#include <string>

namespace hq {

// Appends the shortest text that reads back as v; NaN/Inf append `if_not_finite`.
inline void append_double(std::string& out, double v, const char* if_not_finite = "") {
  if (!std::isfinite(v)) {
    out += if_not_finite;
    return;
  }
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  out.append(buffer, result.ptr);
}

inline std::string format_double(double v, const char* if_not_finite = "") {
  std::string s;
  append_double(s, v, if_not_finite);
  return s;
}

inline void append_int(std::string& out, long long v) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  out.append(buffer, result.ptr);
}

}  // namespace hq
