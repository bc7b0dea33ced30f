#pragma once
// This process's place in an MPI job: rank and size, and MPI's start and end. MPI starts only when
// the process was launched by mpirun (Open MPI's, MPICH's or a PMIx launcher's environment), so a
// plain `kasha …` never touches MPI; without an MPI build, or alone, the process is rank 0 of 1.
// Rank 0 runs the command; the other ranks serve it (mpi/render_server.h) or wait for its end,
// their output silenced: rank 0 prints for the job.
#include <memory>

#include "mpi/rank_control.h"

namespace kasha {

class MpiWorld {
 public:
  // At the start of main. Throws kasha::Error when MPI fails to start or lacks
  // MPI_THREAD_MULTIPLE (a rank's devices talk to rank 0 from a thread each).
  MpiWorld(int* argc, char*** argv);
  ~MpiWorld();
  MpiWorld(const MpiWorld&) = delete;
  MpiWorld& operator=(const MpiWorld&) = delete;

  // The job's world, or a world of one before (and without) MpiWorld.
  static const MpiWorld& get();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool several() const { return size_ > 1; }
  // Ranks > 0: whether rank 0 said the job is over.
  bool stopped() const { return listener_ && listener_->stopped(); }
  // Rank 0, after an interrupt: once every rank has answered it (mpi/rank_control.h).
  void settle_interrupt() const {
    if (watch_) watch_->settle();
  }

  // The job's end. Rank 0 tells every other rank to stop and waits for their answers; the others
  // wait for that. Returns false (rank 0, with a line on stderr) when a rank gave no answer: MPI
  // is then left unfinalized, as finalizing waits for every rank.
  bool finalize();

 private:
  MpiWorld() = default;  // alone
  int rank_ = 0, size_ = 1;
  bool initialized_ = false;
  std::unique_ptr<mpi::RankWatch> watch_;           // rank 0 of several
  std::unique_ptr<mpi::ControlListener> listener_;  // the other ranks
};

}  // namespace kasha
