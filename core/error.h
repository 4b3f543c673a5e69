// Typed errors and internal checks.
// `dp::Error` is what a user can cause (scene, config, CLI, files): it carries the file
// and line it refers to and prints as one line "file:line: message" (a backstop keeps
// it short: the file name is cut to 200 characters, the message to 1000, line breaks
// become spaces; callers still quote user input with quote_input). `DP_CHECK` guards
// internal invariants and is always on; `DP_DCHECK` only in debug builds.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace dp {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message, std::string file = {}, int line = 0);
  const std::string& file() const { return m_file; }
  int line() const { return m_line; }
  const std::string& message() const { return m_message; }

 private:
  std::string m_file;
  int m_line;
  std::string m_message;
};

// Error in a parsed input file (scene, experiment, ...).
class ParseError : public Error {
 public:
  using Error::Error;
};
// A file could not be opened, read or written.
class IoError : public Error {
 public:
  using Error::Error;
};
// A value is out of range or inconsistent (negative radius, ior <= 0, ...).
class ValueError : public Error {
 public:
  using Error::Error;
};

// `text` (user input: a value, a name, a line of a file) for quoting in a one-line
// message: at most `max` characters, then "...", control characters shown as '?'.
std::string quote_input(std::string_view text, size_t max = 60);

[[noreturn]] void check_failed(const char* expr, const char* file, int line, const std::string& msg);

}  // namespace dp

#define DP_CHECK(cond, msg)                                           \
  do {                                                                \
    if (!(cond)) ::dp::check_failed(#cond, __FILE__, __LINE__, (msg)); \
  } while (0)

#ifndef NDEBUG
#define DP_DCHECK(cond, msg) DP_CHECK(cond, msg)
#else
#define DP_DCHECK(cond, msg) \
  do {                       \
  } while (0)
#endif
