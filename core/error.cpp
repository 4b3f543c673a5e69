#include "core/error.h"

#include <cstdio>
#include <cstdlib>

namespace dp {

namespace {
std::string format_error(const std::string& message, const std::string& file, int line) {
  const std::string m = quote_input(message, 1000);
  if (file.empty()) return m;
  const std::string f = quote_input(file, 200);
  if (line <= 0) return f + ": " + m;
  return f + ":" + std::to_string(line) + ": " + m;
}
}  // namespace

std::string quote_input(std::string_view text, size_t max) {
  std::string out(text.substr(0, max));
  for (char& c : out)
    if ((unsigned char)c < 0x20 || c == 0x7f) c = (c == '\n' || c == '\t') ? ' ' : '?';
  return text.size() > max ? out + "..." : out;
}

Error::Error(const std::string& message, std::string file, int line)
    : std::runtime_error(format_error(message, file, line)),
      m_file(std::move(file)), m_line(line), m_message(message) {}

void check_failed(const char* expr, const char* file, int line, const std::string& msg) {
  std::fprintf(stderr, "%s:%d: internal check failed: %s (%s)\n", file, line, expr, msg.c_str());
  std::abort();
}

}  // namespace dp
