#include "core/error.h"

#include <cstdio>
#include <cstdlib>

namespace dp {

namespace {
std::string format_error(const std::string& message, const std::string& file, int line) {
  if (file.empty()) return message;
  if (line <= 0) return file + ": " + message;
  return file + ":" + std::to_string(line) + ": " + message;
}
}  // namespace

Error::Error(const std::string& message, std::string file, int line)
    : std::runtime_error(format_error(message, file, line)),
      m_file(std::move(file)), m_line(line), m_message(message) {}

void check_failed(const char* expr, const char* file, int line, const std::string& msg) {
  std::fprintf(stderr, "%s:%d: internal check failed: %s (%s)\n", file, line, expr, msg.c_str());
  std::abort();
}

}  // namespace dp
