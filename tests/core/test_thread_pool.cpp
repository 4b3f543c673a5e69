// parallel_for: every item once, exceptions rethrown, and (issue 18) a worker thread
// that cannot start is a dp::Error after the started threads are joined. Before, the
// std::thread vector was destroyed with joinable threads in it: std::terminate
// ("terminate called without an active exception"), e.g. for --threads 100000.
#include <catch2/catch.hpp>
#include <sys/resource.h>

#include <atomic>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "core/error.h"
#include "core/thread_pool.h"

using namespace dp;

TEST_CASE("parallel_for: every item once, exceptions reach the caller", "[unit]") {
  std::vector<std::atomic<int>> seen(1000);
  core::parallel_for(1000, 4, [&](int64_t i, int) { seen[size_t(i)].fetch_add(1); });
  for (const auto& s : seen) CHECK(s.load() == 1);
  CHECK_THROWS_AS(core::parallel_for(100, 3, [](int64_t i, int) { if (i == 50) throw std::runtime_error("x"); }),
                  std::runtime_error);
}

#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)  // sanitizers reserve terabytes of address space
TEST_CASE("parallel_for: a thread that cannot start is an error, not std::terminate", "[unit]") {
  // Leave ~256 MB of address space: each thread reserves an 8 MB stack, so some of the
  // 4096 threads start and one fails with std::system_error (EAGAIN).
  long pages = 0, page = 4096;
  if (FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%ld", &pages) != 1) pages = 0;
    std::fclose(f);
  }
  REQUIRE(pages > 0);
  rlimit old{};
  REQUIRE(getrlimit(RLIMIT_AS, &old) == 0);
  rlimit low = old;
  low.rlim_cur = rlim_t(pages * page) + (rlim_t(256) << 20);
  if (old.rlim_max != RLIM_INFINITY && low.rlim_cur > old.rlim_max) low.rlim_cur = old.rlim_max;
  REQUIRE(setrlimit(RLIMIT_AS, &low) == 0);
  std::atomic<int64_t> done{0};
  bool threw = false;
  std::string what;
  try {
    core::parallel_for(1 << 20, 4096, [&](int64_t, int) { done.fetch_add(1); });
  } catch (const Error& e) {
    threw = true;
    what = e.what();
  }
  setrlimit(RLIMIT_AS, &old);
  INFO(what);
  CHECK(threw);
  CHECK(what.find("cannot start worker thread") != std::string::npos);
}
#endif
