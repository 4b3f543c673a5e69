#include "core/log.h"

#include <atomic>
#include <cstdio>
#include <mutex>

namespace dp::log {

namespace {
std::atomic<Level> g_level{Level::info};
std::mutex g_mutex;
const char* prefix(Level l) {
  switch (l) {
    case Level::debug: return "[debug] ";
    case Level::info: return "";
    case Level::warn: return "warning: ";
    case Level::error: return "error: ";
    default: return "";
  }
}
}  // namespace

void set_level(Level l) { g_level.store(l); }
Level level() { return g_level.load(); }
void write(Level l, const std::string& message) {
  std::lock_guard<std::mutex> lock(g_mutex);
  std::fprintf(stderr, "%s%s\n", prefix(l), message.c_str());
}

}  // namespace dp::log
