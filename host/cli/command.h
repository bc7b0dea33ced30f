#pragma once
// kasha's subcommands, each defined in its own host/cli/*_command.cpp: its name, a line of help
// and a function that declares its options (with their validation) on its CLI11 app and returns
// the action to run once they are parsed. Each file registers its command with one
// KASHA_REGISTER_COMMAND line; main.cpp builds the command line from this registry and
// dispatches.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace kasha {

struct Command {
  using Action = std::function<int()>;
  std::string name, description;
  int order = 0;  // its place in `kasha --help`
  // Under mpirun, every rank runs it (render: ranks > 0 serve rank 0); other commands run on
  // rank 0 alone while the others wait.
  bool every_rank = false;
  std::function<Action(CLI::App&)> declare;
};

class CommandRegistry {
 public:
  static const std::vector<Command>& all();  // in `order`
  struct Registrar {
    explicit Registrar(Command command);
  };
};

// The exit code and one line on stderr for the exception in flight (call inside a catch):
// `kasha: interrupted` (130) for an interrupt or a failure after one, else
// `kasha: error: WHAT` (1).
int report_failure();

}  // namespace kasha

#define KASHA_REGISTER_COMMAND(ID, ...) \
  static const ::kasha::CommandRegistry::Registrar kasha_command_##ID(::kasha::Command{__VA_ARGS__})
