// Parallel loop over work items on `threads` std::threads with dynamic scheduling.
// Determinism is the caller's job: derive every random stream from the item index,
// never from the thread index.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

namespace dp::core {

// Number of hardware threads (>= 1).
int hardware_threads();

// Calls fn(item, thread) for item in [0, count). Items are handed out in order; once
// `stop` (if given) becomes true, no further items start. Exceptions thrown by fn are
// rethrown on the calling thread after all workers have finished. If a worker thread
// cannot be started (system thread or memory limit), the started ones are joined and a
// dp::Error says so (no item runs after that; items already done stay done).
void parallel_for(int64_t count, int threads, const std::function<void(int64_t item, int thread)>& fn,
                  const std::atomic<bool>* stop = nullptr);

}  // namespace dp::core
