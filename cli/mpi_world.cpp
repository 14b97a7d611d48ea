#include "mpi_world.hpp"

#include <cstdlib>
#include <string>

#ifdef SWELL_HAVE_MPI
#include <mpi.h>
#endif

#include "swell/reference/errors.hpp"

namespace swell::cli {
namespace {

// The world size the launcher announces: Open MPI's mpirun, PMIx (Slurm's srun --mpi=pmix),
// MPICH's PMI. 0 when no launcher started this process.
int launcher_world_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "PMI_SIZE"}) {
    if (const char* value = std::getenv(name)) return std::atoi(value);
  }
  return std::getenv("PMIX_RANK") ? 1 : 0;
}

}  // namespace

MpiWorld::MpiWorld() {
  const int launched = launcher_world_size();
#ifdef SWELL_HAVE_MPI
  if (launched > 0) {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    joined_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
#else
  if (launched > 1) {
    throw InvalidInput("started by mpirun with " + std::to_string(launched) +
                       " ranks, but this swell was built without MPI (each rank would run the "
                       "whole sweep): build with SWELL_WITH_MPI=ON (libopenmpi-dev), or split the "
                       "work with --shard i/n");
  }
#endif
}

MpiWorld::~MpiWorld() {
#ifdef SWELL_HAVE_MPI
  if (joined_) MPI_Finalize();
#endif
}

void MpiWorld::broadcast(std::string& text) const {
#ifdef SWELL_HAVE_MPI
  if (!joined_ || size_ == 1) return;
  unsigned long long length = text.size();
  MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  text.resize(length);
  // MPI counts are int: long texts go in pieces.
  constexpr unsigned long long kPiece = 1ull << 30;
  for (unsigned long long at = 0; at < length; at += kPiece) {
    MPI_Bcast(text.data() + at, int(std::min(kPiece, length - at)), MPI_CHAR, 0, MPI_COMM_WORLD);
  }
#else
  (void)text;
#endif
}

void MpiWorld::send_to_root(Tag tag, const std::string& text) const {
#ifdef SWELL_HAVE_MPI
  if (!joined_) return;
  MPI_Send(text.data(), int(text.size()), MPI_CHAR, 0, int(tag), MPI_COMM_WORLD);
#else
  (void)tag;
  (void)text;
#endif
}

bool MpiWorld::receive(Tag& tag, std::string& text, int& source) const {
#ifdef SWELL_HAVE_MPI
  if (!joined_ || size_ == 1) return false;
  int waiting = 0;
  MPI_Status status;
  MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &waiting, &status);
  if (!waiting) return false;
  int count = 0;
  MPI_Get_count(&status, MPI_CHAR, &count);
  text.resize(std::size_t(count));
  MPI_Recv(text.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  tag = Tag(status.MPI_TAG);
  source = status.MPI_SOURCE;
  return true;
#else
  (void)tag;
  (void)text;
  (void)source;
  return false;
#endif
}

}  // namespace swell::cli
