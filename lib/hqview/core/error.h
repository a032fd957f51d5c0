#pragma once
// HQView's exception hierarchy. The library throws; only main() prints and
// maps the type to an exit code (CONTRACT.md): ParseError / InputError -> 3,
// UsageError -> 2, anything else -> 4.

#include <cstdint>
#include <stdexcept>
#include <string>

namespace hq {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad user input that is not a file's content: a missing file, an unknown
// extension, an unreadable reference. Exit code 3.
class InputError : public Error {
 public:
  using Error::Error;
};

// A malformed file. what() reads "path:line: message" (line 0 = no line,
// then "path: message"). Exit code 3.
class ParseError : public InputError {
 public:
  ParseError(std::string path, std::int64_t line, const std::string& message)
      : InputError(format(path, line, message)), path_(std::move(path)), line_(line) {}

  const std::string& path() const { return path_; }
  std::int64_t line() const { return line_; }

 private:
  static std::string format(const std::string& path, std::int64_t line, const std::string& message) {
    return line > 0 ? path + ":" + std::to_string(line) + ": " + message : path + ": " + message;
  }
  std::string path_;
  std::int64_t line_;
};

// A mesh that parsed but cannot be analysed (no hexes, ids out of range).
// Exit code 3.
class InvalidMeshError : public InputError {
 public:
  using InputError::InputError;
};

// A bad option value or an output directory that must not be touched. Exit code 2.
class UsageError : public Error {
 public:
  using Error::Error;
};

// OpenGL / OSMesa failure. Exit code 4.
class RenderError : public Error {
 public:
  using Error::Error;
};

}  // namespace hq
