#pragma once
// TextScanner: a forward-only cursor over an in-memory text buffer for the
// ASCII readers (MEDIT .mesh, legacy VTK). It tracks the 1-based line number
// of the current position, skips whitespace and (optionally) `#` comments,
// and reads tokens, integers and doubles with std::from_chars, without
// allocating. Every error goes through fail(), which throws
// ParseError(name, line, message): "name:line: message".
//
// Two ways of moving over whitespace:
//   skip_space()  crosses newlines and comment lines (token-based formats);
//   skip_blank()  stays on the current line (line-based entries), so a
//                 reader can tell "7 values on this line" from "8".
// Numbers must be followed by whitespace or the end of the text: "12abc" is
// not an integer. A leading '+' is accepted. read_bytes() hands out raw
// binary data (big-endian VTK) and keeps the line count right past it.

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "hqview/core/error.h"
#include "hqview/core/progress.h"

namespace hq::detail {

inline constexpr bool is_space(char c) {
  return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}
inline constexpr bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// ASCII case-insensitive equality (keywords).
bool iequals(std::string_view a, std::string_view b);
// True when text starts with prefix, ignoring ASCII case.
bool istarts_with(std::string_view text, std::string_view prefix);
// text from its first character that is neither whitespace nor in a `#`
// comment line (empty when there is none): where a format's signature is
// looked for.
std::string_view after_blanks_and_comments(std::string_view text);
// A token for an error message: quoted, at most its first 40 bytes (then
// "..."; never cut inside a UTF-8 character), as message_text (bytes that
// are not UTF-8 and control characters written as \xhh).
std::string quote(std::string_view token);

class TextScanner {
 public:
  TextScanner(std::string_view text, std::string name, bool has_hash_comments)
      : begin_(text.data()),
        pos_(text.data()),
        end_(text.data() + text.size()),
        name_(std::move(name)),
        has_hash_comments_(has_hash_comments) {
    progress::set_total(text.size());  // the reading stage's bar: bytes scanned
  }

  // A scanner over text [first, last) of `whole`, starting at line `line`
  // (its messages name that line, as `whole`'s would), for a part of a
  // section read on another thread: it draws no progress.
  TextScanner(const TextScanner& whole, std::size_t first, std::size_t last, std::int64_t line)
      : begin_(whole.begin_ + first),
        pos_(begin_),
        end_(whole.begin_ + last),
        name_(whole.name_),
        line_(line),
        has_hash_comments_(whole.has_hash_comments_),
        reports_progress_(false) {}

  const std::string& name() const { return name_; }
  std::int64_t line() const { return line_; }
  std::size_t offset() const { return static_cast<std::size_t>(pos_ - begin_); }
  std::size_t remaining() const { return static_cast<std::size_t>(end_ - pos_); }
  bool at_end() const { return pos_ == end_; }

  // Skips whitespace, newlines and comments. Returns false at the end of the text.
  bool skip_space() {
    while (pos_ != end_) {
      const char c = *pos_;
      if (c == '\n') {
        if ((++line_ & 0xFFFF) == 0 && reports_progress_) progress::set_done(offset());
        ++pos_;
      } else if (is_blank(c)) {
        ++pos_;
      } else if (c == '#' && has_hash_comments_) {
        skip_comment();
      } else {
        return true;
      }
    }
    return false;
  }

  // Skips blanks and a comment on the current line, not its newline. Returns
  // true when a token follows on the same line.
  bool skip_blank() {
    while (pos_ != end_ && is_blank(*pos_)) ++pos_;
    if (pos_ == end_) return false;
    if (*pos_ == '#' && has_hash_comments_) {
      skip_comment();
      return false;
    }
    return *pos_ != '\n';
  }

  // The whitespace-delimited token at the current position (empty at
  // whitespace or the end); read_token() also moves past it.
  std::string_view peek_token() const {
    const char* p = pos_;
    while (p != end_ && !is_space(*p)) ++p;
    return {pos_, static_cast<std::size_t>(p - pos_)};
  }
  std::string_view read_token() {
    const std::string_view token = peek_token();
    pos_ += token.size();
    return token;
  }

  // Parses the token at the current position as an integer / a double. On
  // failure (not a number, out of range, trailing garbage) returns false and
  // does not move.
  bool read_int(std::int64_t& value) {
    const char* p = number_start();
    const auto [ptr, ec] = std::from_chars(p, end_, value);
    if (ec != std::errc{} || (ptr != end_ && !is_space(*ptr))) return false;
    pos_ = ptr;
    return true;
  }
  bool read_double(double& value) {
    const char* p = number_start();
    const auto [ptr, ec] = std::from_chars(p, end_, value);
    if (ec != std::errc{} || (ptr != end_ && !is_space(*ptr))) return false;
    pos_ = ptr;
    return true;
  }

  // A place in the text: its offset and its line.
  struct Mark {
    std::size_t offset = 0;
    std::int64_t line = 0;
  };
  // Where the next n entries lie when each takes one line, found as
  // skip_space() would (blank and comment lines between them skipped),
  // without moving: the start of entry every[k] for each k (ascending
  // entry indices) in `starts`, and in `end` the end of the n-th entry's
  // line (at its newline, not past it). False when fewer lines follow.
  bool mark_entry_lines(std::int64_t n, const std::vector<std::int64_t>& every, std::vector<Mark>& starts,
                        Mark& end) const;
  // Moves to a mark found by mark_entry_lines().
  void move_to(const Mark& mark) {
    pos_ = begin_ + mark.offset;
    line_ = mark.line;
    if (reports_progress_) progress::set_done(offset());
  }

  // Counts the tokens left on the current line (comments excluded) and moves
  // to its end. For error messages.
  std::int64_t count_tokens_on_line();

  // The rest of the current line without its line break ("\n" or "\r\n");
  // moves past the line break.
  std::string_view read_line();

  // If only blanks (and a comment) remain on the current line, moves past its
  // newline and returns true; otherwise does not move past the token and
  // returns false.
  bool finish_line();

  // Takes n raw bytes (binary data), counting the newlines among them so
  // that line numbers after the data stay those of a text editor. The caller
  // checks remaining() first.
  std::string_view read_bytes(std::size_t n);

  // Throws ParseError at the current line (at the end of the text: its last
  // line) / at the given line (0: no line).
  [[noreturn]] void fail(const std::string& message) const;
  [[noreturn]] void fail_at(std::int64_t line, const std::string& message) const;

 private:
  void skip_comment() {
    while (pos_ != end_ && *pos_ != '\n') ++pos_;
  }
  // from_chars does not take a leading '+'; skip one when a digit or a dot follows.
  const char* number_start() const {
    if (pos_ != end_ && *pos_ == '+' && pos_ + 1 != end_ && (pos_[1] == '.' || (pos_[1] >= '0' && pos_[1] <= '9')))
      return pos_ + 1;
    return pos_;
  }

  const char* begin_;
  const char* pos_;
  const char* end_;
  std::string name_;
  std::int64_t line_ = 1;
  bool has_hash_comments_;
  bool reports_progress_ = true;
};

// True when `count` entries of at least `min_bytes` bytes each (the last one
// may lack its 1-byte separator when `ascii`) cannot fit in `remaining`
// bytes. Overflow-free for any count.
constexpr bool exceeds_remaining(std::int64_t count, std::int64_t min_bytes, std::size_t remaining, bool ascii) {
  if (count <= 0) return false;
  const auto room = static_cast<std::uint64_t>(remaining) + (ascii ? 1u : 0u);
  return static_cast<std::uint64_t>(count) > room / static_cast<std::uint64_t>(min_bytes);
}

}  // namespace hq::detail
