// The MPI runtime as `render --mpi` uses it (issue 17). Built against Open MPI when CMake
// finds it (DP_HAVE_MPI); otherwise every function reports that this build has no MPI.
// Rank 0 gathers the other ranks' byte strings (point to point, in chunks: no 2 GiB
// limit). A rank that fails after start() calls abort(): MPI_Abort ends every rank, so
// the job fails loudly instead of hanging or writing a partial image.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace dp::apps {

struct MpiWorld {
  int rank = 0, size = 1;
};

// Whether this build links MPI.
bool mpi_built();
// Whether this process was started by mpirun/mpiexec with more than one rank (Open MPI,
// MPICH/PMI or PMIx environment variables).
bool under_mpirun();
// MPI_Init (once); throws dp::Error when this build has no MPI.
MpiWorld mpi_start();
void mpi_stop();                                    // MPI_Finalize
[[noreturn]] void mpi_abort(const std::string& message);  // prints the message, MPI_Abort(1)
// Rank 0 calls `take(r, bytes)` for every rank's bytes in rank order (its own first),
// receiving one rank's at a time (memory: two ranks' worth, whatever the rank count);
// the other ranks send theirs and return.
void mpi_gather_each(const std::vector<uint8_t>& mine,
                     const std::function<void(int rank, const std::vector<uint8_t>& bytes)>& take);

}  // namespace dp::apps
