#pragma once
// kasha's whole command line, built from the command registry (cli/command.h): parsed, dispatched
// and every failure turned into its one line and exit code
// (docs/commands.md#errors-and-exit-codes). main.cpp runs it once per process; the fuzz harness
// runs it in process, case after case.

namespace kasha {

// The exit code of `kasha ARGS…` on this MPI rank (MpiWorld::get()). Under MPI, ranks > 0 run
// only a command that every rank runs (render: they serve rank 0) and otherwise say so; other
// commands run on rank 0 alone.
int run_command_line(int argc, char** argv);

}  // namespace kasha
