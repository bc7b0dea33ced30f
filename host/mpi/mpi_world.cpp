#include "mpi/mpi_world.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "core/error.h"

#ifdef KASHA_HAVE_MPI
#include <mpi.h>
#endif

namespace kasha {

namespace {
const MpiWorld* g_world = nullptr;

// The world's size as the launcher's environment gives it: 0 when not launched by mpirun (Open
// MPI's, MPICH's or a PMIx launcher's), which is known before MPI starts.
int launched_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* size = std::getenv(name)) return std::max(1, std::atoi(size));
  return std::getenv("PMIX_RANK") ? 1 : 0;
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
  if (g_world || launched_size() == 0) return;
#ifndef KASHA_HAVE_MPI
  // Several copies of a build without MPI would each render the whole image into the same file.
  if (launched_size() > 1) {
    const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
    if (!rank) rank = std::getenv("PMI_RANK");
    if (rank && std::atoi(rank) > 0) silence();
    throw Error(
        "mpirun: this kasha was built without MPI (KASHA_MPI=OFF); rebuild with MPI "
        "installed (scripts/setup.sh) to render on several ranks");
  }
#else
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
