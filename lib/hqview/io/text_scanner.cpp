#include "hqview/io/text_scanner.h"

#include <cstring>

#include <algorithm>
#include <cstdio>

#include "hqview/core/message_text.h"

namespace hq::detail {

namespace {
constexpr char to_lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }
}  // namespace

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (to_lower(a[i]) != to_lower(b[i])) return false;
  return true;
}

bool istarts_with(std::string_view text, std::string_view prefix) {
  return text.size() >= prefix.size() && iequals(text.substr(0, prefix.size()), prefix);
}

std::string_view after_blanks_and_comments(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    if (is_space(text[i])) {
      ++i;
    } else if (text[i] == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else {
      break;
    }
  }
  return text.substr(i);
}

std::string quote(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  std::size_t shown = std::min(token.size(), kMaxShown);
  if (shown < token.size()) {
    // A valid character that the limit would cut in two is left out whole.
    std::size_t start = shown;
    while (start > 0 && shown - start < 3 && (static_cast<unsigned char>(token[start]) & 0xC0) == 0x80) --start;
    if (start < shown && start + utf8_sequence_length(token, start) > shown) shown = start;
  }
  return "'" + message_text(token.substr(0, shown)) + (shown < token.size() ? "..." : "") + "'";
}

std::int64_t TextScanner::count_tokens_on_line() {
  std::int64_t count = 0;
  while (skip_blank()) {
    read_token();
    ++count;
  }
  return count;
}

std::string_view TextScanner::read_line() {
  const char* start = pos_;
  while (pos_ != end_ && *pos_ != '\n') ++pos_;
  std::string_view line(start, static_cast<std::size_t>(pos_ - start));
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (pos_ != end_) {
    ++pos_;
    ++line_;
  }
  return line;
}

bool TextScanner::finish_line() {
  if (skip_blank()) return false;
  if (pos_ != end_) {
    ++pos_;  // the newline
    if ((++line_ & 0xFFFF) == 0) progress::set_done(offset());
  }
  return true;
}

std::string_view TextScanner::read_bytes(std::size_t n) {
  n = std::min(n, remaining());
  const std::string_view bytes(pos_, n);
  line_ += std::count(bytes.begin(), bytes.end(), '\n');
  pos_ += n;
  return bytes;
}

bool TextScanner::mark_entry_lines(std::int64_t n, const std::vector<std::int64_t>& every, std::vector<Mark>& starts,
                                   Mark& end) const {
  starts.clear();
  const char* p = pos_;
  std::int64_t line = line_, entries = 0;
  std::size_t next = 0;
  const auto to_newline = [&] {
    const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end_ - p));
    p = nl != nullptr ? static_cast<const char*>(nl) : end_;
  };
  while (entries < n) {
    while (p != end_ && is_blank(*p)) ++p;
    if (p == end_) return false;
    if (*p == '\n') {
      ++line;
      ++p;
    } else if (*p == '#' && has_hash_comments_) {
      to_newline();
    } else {
      if (next < every.size() && every[next] == entries) {
        starts.push_back({static_cast<std::size_t>(p - begin_), line});
        ++next;
      }
      ++entries;
      to_newline();
    }
  }
  end = {static_cast<std::size_t>(p - begin_), line};
  return true;
}

void TextScanner::fail(const std::string& message) const {
  // At the end of a text whose last line is complete, the error belongs to
  // that last line, not to the empty one after it.
  const bool after_last_line = pos_ == end_ && pos_ != begin_ && end_[-1] == '\n';
  throw ParseError(name_, after_last_line ? line_ - 1 : line_, message);
}

void TextScanner::fail_at(std::int64_t line, const std::string& message) const {
  throw ParseError(name_, line, message);
}

}  // namespace hq::detail
