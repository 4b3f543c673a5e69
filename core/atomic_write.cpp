#include "core/atomic_write.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace dp::core {

namespace {

// Temporary files being written right now. A slot is claimed (free -> filling), its
// name copied, then published (-> active); the signal handler only reads active slots.
// Writers are few (the main thread, sometimes a helper), so a handful of slots suffice;
// a writer that finds none still writes atomically, only without cleanup on a signal.
enum SlotState : int { kFree = 0, kFilling = 1, kActive = 2 };
constexpr size_t kSlots = 8;
constexpr size_t kMaxPath = 4096;
struct PendingSlot {
  std::atomic<int> state{kFree};
  char path[kMaxPath] = {};
};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads these flags");
std::array<PendingSlot, kSlots> g_pending;

class PendingRegistration {
 public:
  explicit PendingRegistration(const std::string& tmp) {
    if (tmp.size() + 1 > kMaxPath) return;
    for (auto& s : g_pending) {
      int expected = kFree;
      if (s.state.compare_exchange_strong(expected, kFilling)) {
        std::memcpy(s.path, tmp.c_str(), tmp.size() + 1);
        s.state.store(kActive);
        m_slot = &s;
        return;
      }
    }
  }
  ~PendingRegistration() {
    if (m_slot) m_slot->state.store(kFree);
  }
  PendingRegistration(const PendingRegistration&) = delete;
  PendingRegistration& operator=(const PendingRegistration&) = delete;

 private:
  PendingSlot* m_slot = nullptr;
};

void remove_quietly(const std::string& path) {
  std::error_code ec;
  std::filesystem::remove(path, ec);
}

}  // namespace

std::string temp_path(const std::string& path) { return path + ".tmp-" + std::to_string(long(::getpid())); }

void write_atomically(const std::string& path, const std::function<void(const std::string& tmp)>& write) {
  const std::string tmp = temp_path(path);
  PendingRegistration pending(tmp);
  try {
    write(tmp);
  } catch (...) {
    remove_quietly(tmp);
    throw;
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    remove_quietly(tmp);
    throw IoError("cannot write (rename from " + tmp + " failed: " + ec.message() + ")", path);
  }
}

void write_file_atomically(const std::string& path, std::string_view contents) {
  write_atomically(path, [&](const std::string& tmp) {
    std::ofstream f(tmp, std::ios::binary);
    if (!f) throw IoError("cannot write", path);
    f.write(contents.data(), std::streamsize(contents.size()));
    f.close();
    if (!f) throw IoError("write failed (disk full?)", path);
  });
}

void remove_pending_temp_files() noexcept {
  for (auto& s : g_pending)
    if (s.state.load() == kActive) ::unlink(s.path);
}

}  // namespace dp::core
