#pragma once
// What kind of failure an exception is, decided in one place: the command
// line turns it into an exit code (docs/contract.md), `batch` into a mesh's
// status and its own exit code.

namespace hq {

enum class ErrorKind {
  usage,        // ValueError: a value the caller chose (exit 2)
  input,        // InputError, ParseError, InvalidMeshError (exit 3)
  environment,  // EnvironmentError, std::filesystem::filesystem_error, std::bad_alloc (exit 5)
  interrupted,  // Interrupted: a signal (exit 128 + signal)
  internal,     // anything else: a bug (exit 4)
};

// The kind of the exception being handled (call inside a catch block).
ErrorKind kind_of_current_exception();

}  // namespace hq
