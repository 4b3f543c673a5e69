// Memory bandwidth of this machine: a STREAM-style triad a = b + s c over three float
// arrays of 64 MiB each (far beyond the caches), on 1..T threads, best of 10 runs.
// Prints GB/s counting the three streams, and counting the write-allocate read of `a`
// too (what a cache-based CPU moves). The L1 grid solve is bandwidth bound (issue 18):
// its per-iteration traffic divided by this figure is a lower bound on its time
// (bench/RESULTS.md, "the bandwidth bound").
// Usage: bench_bandwidth [max_threads=2]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

int main(int argc, char** argv) {
  const int max_threads = argc > 1 ? std::max(1, std::atoi(argv[1])) : 2;
  const size_t n = size_t(1) << 24;
  std::vector<float> a(n, 0.0f), b(n, 1.0f), c(n, 2.0f);
  std::printf("threads,triad_GBps,triad_with_write_allocate_GBps\n");
  for (int threads = 1; threads <= max_threads; ++threads) {
    double best = 1e30;
    for (int rep = 0; rep < 10; ++rep) {
      const auto t0 = std::chrono::steady_clock::now();
      std::vector<std::thread> team;
      for (int t = 0; t < threads; ++t)
        team.emplace_back([&, t] {
          const size_t i0 = n * size_t(t) / size_t(threads), i1 = n * size_t(t + 1) / size_t(threads);
          for (size_t i = i0; i < i1; ++i) a[i] = b[i] + 1.5f * c[i];
        });
      for (std::thread& th : team) th.join();
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    const double bytes = 4.0 * double(n);
    std::printf("%d,%.2f,%.2f\n", threads, 3.0 * bytes / best / 1e9, 4.0 * bytes / best / 1e9);
  }
  // Keep the stores observable.
  return a[n / 2] == 4.0f ? 0 : 1;
}
