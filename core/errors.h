// Typed exceptions and the internal invariant check.
//
// Bad user input (config, mesh, dataset files) is reported with a typed exception that names
// the file and, where known, the line; a violated internal invariant throws InternalError with
// the source location. Numerical outcomes of solvers are data (StageStatus), not exceptions.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace symembed {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A configuration file or option is wrong (unknown key, wrong type, out of range, ...).
class ConfigError : public Error {
 public:
  using Error::Error;
};

// An input (mesh, ground truth, map file) is malformed or degenerate.
class InvalidInputError : public Error {
 public:
  using Error::Error;
};

// A file could not be opened, read or written.
class IoError : public Error {
 public:
  using Error::Error;
};

// A numerical solver failed in a way that makes its output unusable.
class SolverError : public Error {
 public:
  using Error::Error;
};

// An internal invariant does not hold: a bug, not bad input.
class InternalError : public Error {
 public:
  using Error::Error;
};

namespace detail {
[[noreturn]] void ThrowCheckFailure(const char* file, int line, const char* cond,
                                    const std::string& msg);
}  // namespace detail

}  // namespace symembed

// Throws symembed::InternalError("file:line: check `cond` failed: msg") when cond is false.
// msg may use stream syntax: SYMEMBED_CHECK(n > 0, "n=" << n).
#define SYMEMBED_CHECK(cond, msg)                                                   \
  do {                                                                              \
    if (!(cond)) {                                                                  \
      std::ostringstream symembed_check_stream_;                                    \
      symembed_check_stream_ << msg;                                                \
      ::symembed::detail::ThrowCheckFailure(__FILE__, __LINE__, #cond,              \
                                            symembed_check_stream_.str());          \
    }                                                                               \
  } while (false)
