#pragma once
// Small text helpers shared by readers, rules and pages.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace hq {

// Space, tab, line feed, carriage return, vertical tab, form feed.
inline constexpr std::string_view kWhitespace = " \t\n\r\v\f";

// text without the leading and trailing characters of `chars`.
inline std::string_view trim(std::string_view text, std::string_view chars = kWhitespace) {
  const auto first = text.find_first_not_of(chars);
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(chars);
  return text.substr(first, last - first + 1);
}

// The pieces of text between separators ("a,,b" -> "a", "", "b"; "" -> "").
inline std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> pieces;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(separator, start);
    pieces.push_back(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) return pieces;
    start = end + 1;
  }
}

// A cell noun ("hex", "cell", "quad", "triangle", "face") for n of them:
// the noun itself for 1, else its plural ("hexes", "cells", ...).
inline std::string plural(std::string_view noun, std::size_t n = 2) {
  if (n == 1) return std::string(noun);
  return std::string(noun) + (noun.ends_with('x') ? "es" : "s");
}

}  // namespace hq
