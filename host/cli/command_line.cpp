#include "cli/command_line.h"

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/command_line_errors.h"
#include "core/input_files.h"
#include "core/warning.h"
#include "mpi/mpi_world.h"
#include "mpi/render_server.h"

namespace kasha {

int run_command_line(int argc, char** argv) {
  const MpiWorld& world = MpiWorld::get();
  forget_input_files();  // a previous command line's inputs (in process) are not this one's
  CLI::App app{"kasha: a spectral renderer for fluorescent materials"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "kasha " KASHA_VERSION);
  std::vector<Command::Action> actions;
  for (const Command& command : CommandRegistry::all())
    actions.push_back(command.declare(*app.add_subcommand(command.name, command.description)));
  cli::require_values(app);
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

}  // namespace kasha
