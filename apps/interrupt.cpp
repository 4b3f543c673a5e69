#include "apps/interrupt.h"

#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>

#include "core/atomic_write.h"

namespace dp::apps {

namespace {

static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free &&
                  std::atomic<const char*>::is_always_lock_free,
              "the signal handler may only touch lock-free atomics");
std::atomic<bool> g_stop{false};
std::atomic<bool> g_graceful{false};
std::atomic<int> g_signals{0};  // signals received so far
std::atomic<int> g_first{0};    // the first one's number
std::atomic<const char*> g_early_message{"interrupted; exiting (files already written are complete)"};

void say(const char* text) noexcept {
  size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, text, left);
    if (n <= 0) return;
    text += n;
    left -= size_t(n);
  }
}

extern "C" void on_signal(int sig) {
  const int saved_errno = errno;
  const int count = g_signals.fetch_add(1) + 1;
  if (count == 1 && g_graceful.load()) {
    g_first.store(sig);
    g_stop.store(true);
    say("\ndeltapath: ");
    say(signal_name(sig));
    say(": stopping at the next tile boundary (signal again to quit at once, writing nothing more)\n");
    errno = saved_errno;
    return;
  }
  core::remove_pending_temp_files();
  say(count == 1 ? "deltapath: " : "\ndeltapath: ");
  say(signal_name(sig));
  say(": ");
  say(count == 1 ? g_early_message.load() : "second signal: quitting without writing");
  say("\n");
  ::_exit(128 + sig);
}

}  // namespace

const char* signal_name(int sig) {
  switch (sig) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "signal";
  }
}

void install_signal_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;  // file writes in progress resume after the handler returns
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

void set_early_exit_message(const char* line) { g_early_message.store(line); }
void enable_graceful_stop() { g_graceful.store(true); }
const std::atomic<bool>* stop_flag() { return &g_stop; }
int received_signal() { return g_first.load(); }
int interrupted_exit_status() {
  const int sig = received_signal();
  return sig ? 128 + sig : 0;
}

}  // namespace dp::apps
