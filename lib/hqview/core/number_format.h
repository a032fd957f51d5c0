#pragma once
// Numbers as text. Data (report.json, CSV, VTU, sort keys): the shortest
// round-trip decimal text of a double (std::to_chars), same value, same
// bytes. Display (pages, Markdown, legends): a fixed number of significant
// digits, thousands separators for counts.

#include <charconv>
#include <cmath>
#include <cstdio>
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

// Display text: `digits` significant digits (printf %g), "–" for NaN/Inf.
inline std::string display_number(double v, int digits = 6) {
  if (!std::isfinite(v)) return "–";
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

// A count with thousands separators ("1,234,567"): 6- and 7-digit counts
// readable at a glance.
inline std::string display_count(long long v) {
  const std::string digits = std::to_string(v < 0 ? -v : v);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return v < 0 ? "-" + out : out;
}

inline void append_int(std::string& out, long long v) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  out.append(buffer, result.ptr);
}

}  // namespace hq
