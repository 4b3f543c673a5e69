#include "apps/mpi_world.h"

#include <cstdio>
#include <algorithm>
#include <cstdlib>

#include "core/error.h"

#ifdef DP_HAVE_MPI
#include <mpi.h>
#endif

namespace dp::apps {

bool mpi_built() {
#ifdef DP_HAVE_MPI
  return true;
#else
  return false;
#endif
}

bool under_mpirun() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"}) {
    const char* v = std::getenv(var);
    if (v && std::atoi(v) > 1) return true;
  }
  return false;
}

#ifdef DP_HAVE_MPI
namespace {
constexpr int kChunk = 1 << 30;  // bytes per message
constexpr int kTag = 17;
}  // namespace

MpiWorld mpi_start() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) MPI_Init(nullptr, nullptr);
  MpiWorld w;
  MPI_Comm_rank(MPI_COMM_WORLD, &w.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &w.size);
  return w;
}

void mpi_stop() {
  int finalised = 0;
  MPI_Finalized(&finalised);
  if (!finalised) MPI_Finalize();
}

void mpi_abort(const std::string& message) {
  std::fprintf(stderr, "deltapath: %s\n", message.c_str());
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, 1);
  std::exit(1);
}

void mpi_gather_each(const std::vector<uint8_t>& mine,
                     const std::function<void(int rank, const std::vector<uint8_t>& bytes)>& take) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  uint64_t n = mine.size();
  std::vector<uint64_t> sizes(size_t(size), 0);
  MPI_Gather(&n, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  if (rank != 0) {
    for (uint64_t at = 0; at < n; at += kChunk)
      MPI_Send(mine.data() + at, int(std::min<uint64_t>(kChunk, n - at)), MPI_BYTE, 0, kTag, MPI_COMM_WORLD);
    return;
  }
  take(0, mine);
  std::vector<uint8_t> b;
  for (int r = 1; r < size; ++r) {
    b.resize(size_t(sizes[size_t(r)]));
    for (uint64_t at = 0; at < b.size(); at += kChunk)
      MPI_Recv(b.data() + at, int(std::min<uint64_t>(kChunk, b.size() - at)), MPI_BYTE, r, kTag, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
    take(r, b);
  }
}
#else
MpiWorld mpi_start() {
  throw Error("this deltapath was built without MPI (install libopenmpi-dev and rebuild: scripts/build.sh)",
              "command line");
}
void mpi_stop() {}
void mpi_abort(const std::string& message) {
  std::fprintf(stderr, "deltapath: %s\n", message.c_str());
  std::exit(1);
}
void mpi_gather_each(const std::vector<uint8_t>& mine,
                     const std::function<void(int rank, const std::vector<uint8_t>& bytes)>& take) {
  take(0, mine);
}
#endif

}  // namespace dp::apps
