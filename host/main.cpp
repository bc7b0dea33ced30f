// kasha: the command line of docs/commands.md. Each command declares its own options and action
// (host/cli/*_command.cpp, registered in cli/command.h); this file builds the command line from
// them, parses it and dispatches, on every MPI rank.
#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "cli/command.h"
#include "cli/command_line_errors.h"
#include "core/interrupt.h"
#include "core/warning.h"
#include "mpi/mpi_world.h"
#include "mpi/render_server.h"

using namespace kasha;

// The command line of this process. Under MPI, ranks > 0 run only a command that every rank
// runs (render: they serve rank 0) and otherwise say so; other commands run on rank 0 alone.
static int run(int argc, char** argv, const MpiWorld& world) {
  CLI::App app{"kasha: a spectral renderer for fluorescent materials"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "kasha " KASHA_VERSION);
  std::vector<Command::Action> actions;
  for (const Command& command : CommandRegistry::all())
    actions.push_back(command.declare(*app.add_subcommand(command.name, command.description)));
  cli::require_numbers(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (world.rank() > 0 && e.get_exit_code() != 0)
      refuse_render("its command line: " + cli::parse_error_line(app, e));
    return cli::exit_for_parse_error(app, e);
  }
  const std::string name = app.get_subcommands().front()->get_name();
  size_t index = 0;
  while (CommandRegistry::all()[index].name != name) ++index;
  const bool every_rank = CommandRegistry::all()[index].every_rank;
  if (world.rank() > 0 && !every_rank) {
    refuse_render("it runs kasha " + name + ", not render");
    return 0;
  }
  if (world.several() && !every_rank)
    warn(name + " runs on rank 0 alone under MPI; " +
         (world.size() == 2 ? std::string("the other rank waits")
                            : "the other " + std::to_string(world.size() - 1) + " ranks wait") +
         " for it");
  try {
    return actions[index]();
  } catch (...) {
    return report_failure();
  }
}

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
  const int code = run(argc, argv, *world);
  // Rank 0 speaks for the job: the other ranks' failures reached it in messages.
  if (!world->finalize()) return 1;
  return world->rank() == 0 ? code : 0;
}
