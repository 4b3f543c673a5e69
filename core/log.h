// Leveled logging to stderr. The level is process-wide configuration set once by the
// CLI (not mutable render state); messages below it are dropped.
#pragma once

#include <sstream>
#include <string>

namespace dp::log {

enum class Level { debug = 0, info = 1, warn = 2, error = 3, quiet = 4 };

void set_level(Level level);
Level level();
void write(Level level, const std::string& message);

template <typename... Args>
std::string concat(Args&&... args) {
  std::ostringstream os;
  (os << ... << args);
  return os.str();
}

template <typename... Args> void debug(Args&&... a) { if (level() <= Level::debug) write(Level::debug, concat(a...)); }
template <typename... Args> void info(Args&&... a) { if (level() <= Level::info) write(Level::info, concat(a...)); }
template <typename... Args> void warn(Args&&... a) { if (level() <= Level::warn) write(Level::warn, concat(a...)); }
template <typename... Args> void error(Args&&... a) { if (level() <= Level::error) write(Level::error, concat(a...)); }

}  // namespace dp::log
