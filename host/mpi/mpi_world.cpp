#include "mpi/mpi_world.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

#include "core/error.h"

#ifdef KASHA_HAVE_MPI
#include <mpi.h>
#endif

namespace kasha {

namespace {
const MpiWorld* g_world = nullptr;

bool launched_by_mpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

// Ranks > 0 print nothing (their errors reach rank 0 in messages); KASHA_MPI_RANK_OUTPUT=1 keeps
// their stdout and stderr, for debugging.
void silence() {
  const char* keep = std::getenv("KASHA_MPI_RANK_OUTPUT");
  if (keep && std::string(keep) == "1") return;
  const int null = open("/dev/null", O_WRONLY);
  if (null < 0) return;
  dup2(null, STDOUT_FILENO);
  dup2(null, STDERR_FILENO);
  close(null);
}
}  // namespace

const MpiWorld& MpiWorld::get() {
  static const MpiWorld alone;
  return g_world ? *g_world : alone;
}

MpiWorld::MpiWorld(int* argc, char*** argv) {
  (void)argc;
  (void)argv;
#ifdef KASHA_HAVE_MPI
  if (g_world || !launched_by_mpirun()) return;
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_MULTIPLE, &provided) != MPI_SUCCESS)
    throw Error("MPI: MPI_Init_thread failed");
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  if (rank_ > 0) silence();
  if (provided < MPI_THREAD_MULTIPLE) {
    MPI_Finalize();
    throw Error(
        "MPI: the MPI library gives no MPI_THREAD_MULTIPLE, which kasha's device threads "
        "need");
  }
  initialized_ = true;
  g_world = this;
  if (size_ > 1) {
    if (rank_ == 0)
      watch_ = std::make_unique<mpi::RankWatch>(size_);
    else
      listener_ = std::make_unique<mpi::ControlListener>();
  }
#endif
}

bool MpiWorld::finalize() {
  if (!initialized_) return true;
  bool ok = true;
  if (watch_) ok = watch_->stop_all();
  if (listener_) listener_->wait_stopped();
  watch_.reset();
  listener_.reset();
  initialized_ = false;
#ifdef KASHA_HAVE_MPI
  if (ok) MPI_Finalize();
#endif
  return ok;
}

MpiWorld::~MpiWorld() {
  if (g_world == this) {
    finalize();
    g_world = nullptr;
  }
}

}  // namespace kasha
