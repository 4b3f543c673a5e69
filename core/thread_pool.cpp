#include "core/thread_pool.h"

#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/error.h"

namespace dp::core {

int hardware_threads() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : int(n);
}

void parallel_for(int64_t count, int threads, const std::function<void(int64_t, int)>& fn,
                  const std::atomic<bool>* stop) {
  if (threads <= 0) threads = hardware_threads();
  std::atomic<int64_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&](int thread) {
    for (;;) {
      if (stop && stop->load(std::memory_order_relaxed)) return;
      const int64_t item = next.fetch_add(1);
      if (item >= count) return;
      try {
        fn(item, thread);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        next.store(count);
      }
    }
  };
  if (threads == 1 || count <= 1) {
    worker(0);
  } else {
    std::vector<std::thread> pool;
    try {
      for (int t = 0; t < threads; ++t) pool.emplace_back(worker, t);
    } catch (const std::exception& e) {  // std::system_error, or bad_alloc growing `pool`
      // A thread that cannot start (thread or memory limit): stop and join the ones
      // that did, since destroying a joinable std::thread calls std::terminate.
      next.store(count);
      for (auto& t : pool) t.join();
      throw Error("cannot start worker thread " + std::to_string(pool.size() + 1) + " of " + std::to_string(threads) +
                  " (" + e.what() + "); try fewer --threads");
    }
    for (auto& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace dp::core
