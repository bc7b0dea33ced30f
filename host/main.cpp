// kasha: the command line of docs/commands.md (cli/command_line.h), on every MPI rank.
#include <memory>

#include "cli/command.h"
#include "cli/command_line.h"
#include "core/interrupt.h"
#include "mpi/mpi_world.h"

using namespace kasha;

int main(int argc, char** argv) {
  install_exit_on_interrupt();  // render, converge, reference and bench take over with their own
  std::unique_ptr<MpiWorld> world;
  try {
    world = std::make_unique<MpiWorld>(&argc, &argv);  // starts MPI only under mpirun
  } catch (...) {
    return report_failure();
  }
  // Ranks > 0 end when rank 0 says so: a signal (mpirun's SIGTERM on Ctrl-C) only raises the flag
  // their work and rank 0's questions see (mpi/rank_control.h), lest they vanish unanswering.
  if (world->rank() > 0) install_interrupt_handler();
  const int code = run_command_line(argc, argv);
  // Rank 0 speaks for the job: the other ranks' failures reached it in messages.
  if (!world->finalize()) return 1;
  return world->rank() == 0 ? code : 0;
}
