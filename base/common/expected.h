// A value or the reason there is none: what fallible engine calls return.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace hitl {

/// What kind of failure an Error is: what the user has to change, and so the exit code
/// (cli/common_options.h maps kinds to the exit-code table in one place, exit_code()).
/// Usage, Input and Unavailable stop a command before it runs (exit 2); Failed is a command that
/// ran and did not get what it asked for (exit 1). The three "could not start" kinds are kept
/// apart because the user's fix differs: the command line, a file or value, or the machine.
enum class ErrorKind {
  /// It ran and failed: no answer, the board refused, a check failed, a connection was lost,
  /// the path to the board (adb, the relay) did not come up. The default, so that `Error{"..."}`
  /// written before kinds existed keeps its meaning.
  Failed,
  /// The command line itself: options that exclude each other, a value an option does not take.
  Usage,
  /// A file or a value from outside is missing or malformed: a vehicle, world or trajectory file,
  /// a .params file, a dialect XML, a tlog, a port number, an address that does not parse.
  Input,
  /// A resource on this machine cannot be opened: a port in use, an address that cannot be bound
  /// or resolved, a socket that cannot be created, a file that cannot be written.
  Unavailable,
};

/// "failed", "usage", "input", "unavailable": the word --json output uses.
inline const char* to_string(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::Failed: return "failed";
    case ErrorKind::Usage: return "usage";
    case ErrorKind::Input: return "input";
    case ErrorKind::Unavailable: return "unavailable";
  }
  return "failed";
}

/// Why a call failed, in words a user can act on ("UDP port 14570 is already in use"), and its kind.
/// The message names the input and the problem ("vehicle file 'x.json': ..."), never the CLI option
/// it came from: cli/ adds the flag.
struct Error {
  std::string message;
  ErrorKind kind = ErrorKind::Failed;

  static Error usage(std::string message) { return Error{std::move(message), ErrorKind::Usage}; }
  static Error input(std::string message) { return Error{std::move(message), ErrorKind::Input}; }
  static Error unavailable(std::string message) { return Error{std::move(message), ErrorKind::Unavailable}; }
  static Error failed(std::string message) { return Error{std::move(message), ErrorKind::Failed}; }

  /// The same kind with words before the message ("--vehicle: " + message).
  Error prefixed(const std::string& before) const { return Error{before + message, kind}; }
  /// The same kind with words after the message (a hint).
  Error suffixed(const std::string& after) const { return Error{message + after, kind}; }
};

template <class T>
class Expected {
 public:
  Expected(T value) : v_(std::move(value)) {}          // NOLINT: implicit by design
  Expected(Error error) : v_(std::move(error)) {}      // NOLINT: implicit by design

  bool ok() const { return std::holds_alternative<T>(v_); }
  explicit operator bool() const { return ok(); }
  T& value() & { return std::get<T>(v_); }
  const T& value() const& { return std::get<T>(v_); }
  T&& value() && { return std::get<T>(std::move(v_)); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T&& operator*() && { return std::move(*this).value(); }
  const Error& error() const { return std::get<Error>(v_); }

 private:
  std::variant<T, Error> v_;
};

/// For calls that return nothing on success.
struct Ok {};
using Status = Expected<Ok>;

}  // namespace hitl
