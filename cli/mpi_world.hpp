#pragma once
// The ranks `swell sweep` shares its runs over: MPI's world when mpirun started this process
// (and the build has MPI: SWELL_WITH_MPI), else a world of one. Only the main thread calls MPI
// (MPI_THREAD_FUNNELED); worker threads hand their rows to it.
#include <string>
#include <vector>

namespace swell::cli {

class MpiWorld {
 public:
  // Joins MPI when the environment says mpirun (or srun with PMIx) started this process, so
  // that a plain `swell sweep` never pays MPI's start-up. Throws InvalidInput when it was
  // started by mpirun with several ranks but this build has no MPI (each rank would run the
  // whole sweep).
  MpiWorld();
  ~MpiWorld();  // MPI_Finalize
  MpiWorld(const MpiWorld&) = delete;
  MpiWorld& operator=(const MpiWorld&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }

  // Rank 0's `text` to every rank.
  void broadcast(std::string& text) const;
  // Any rank to rank 0: one message (a row, an error, or the end of a rank's work).
  enum class Tag { row = 1, failure = 2, finished = 3 };
  void send_to_root(Tag tag, const std::string& text) const;
  // Rank 0: a waiting message if there is one (false: none now).
  bool receive(Tag& tag, std::string& text, int& source) const;

 private:
  int rank_ = 0, size_ = 1;
  bool joined_ = false;
};

}  // namespace swell::cli
