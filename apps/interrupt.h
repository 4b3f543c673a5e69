// SIGINT and SIGTERM for the deltapath CLI (issue #18). main() installs the handlers
// before any command runs; until a command says it can stop cleanly, a signal prints one
// line, removes the temporary file being written (if any) and exits 128 + signal with
// nothing written. `render` and `experiment` call enable_graceful_stop() once the scene
// is loaded: the first signal then only sets the stop flag the integrators poll
// (RenderOptions::stop), the command writes what was rendered (marked partial) and main
// exits 128 + signal (130 for SIGINT, 143 for SIGTERM). A second signal exits at once
// (128 + its number) without writing anything more. The handler only touches atomics
// and calls write(2), unlink(2) and _exit(2).
#pragma once

#include <atomic>

namespace dp::apps {

// Installs the SIGINT/SIGTERM handlers (immediate mode). Called once by main().
void install_signal_handlers();
// The one line printed (after "deltapath: SIGTERM: ") when a signal exits before the
// graceful stop is enabled; `line` must be a string literal (the handler reads it).
void set_early_exit_message(const char* line);
// From now on the first signal requests a stop (sets stop_flag()) instead of exiting.
void enable_graceful_stop();
// The flag the first signal sets; pass it as RenderOptions::stop.
const std::atomic<bool>* stop_flag();
// The first signal received (SIGINT, SIGTERM), or 0.
int received_signal();
// 128 + received_signal(), or 0 when no signal arrived: the exit status of an
// interrupted command that wrote its partial results.
int interrupted_exit_status();
// "SIGINT", "SIGTERM" or "signal".
const char* signal_name(int sig);

}  // namespace dp::apps
