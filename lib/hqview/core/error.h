#pragma once
// HQView's exception hierarchy. The library throws these typed errors and
// never prints or decides an exit code; the command line (apps/hqview) maps
// each type to one (docs/contract.md).

#include <cstdint>
#include <stdexcept>
#include <string>

namespace hq {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bad input that is not a file's content: a missing file, an unknown
// extension, an unreadable reference.
class InputError : public Error {
 public:
  using Error::Error;
};

// A malformed file. what() reads "path:line: message" (line 0 = no line,
// then "path: message").
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
class InvalidMeshError : public InputError {
 public:
  using InputError::InputError;
};

// A value the caller chose that cannot be used: a rule or id that names
// nothing in this mesh or report, a name that is not a format or metric, an
// output directory that must not be replaced. Not the content of a file.
class ValueError : public Error {
 public:
  using Error::Error;
};

// The machine refused what the run needs: no space left on the device, a
// file size limit, a read-only file system, a permission, too many levels of
// symbolic links, no memory. Neither the input nor a bug: a pipeline may
// retry elsewhere (exit code 5). what() names the path and the cause.
class EnvironmentError : public Error {
 public:
  using Error::Error;
};

// OpenGL / OSMesa failure.
class RenderError : public Error {
 public:
  using Error::Error;
};

}  // namespace hq
