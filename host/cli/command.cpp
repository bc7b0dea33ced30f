#include "cli/command.h"

#include <algorithm>
#include <cstdio>
#include <new>

#include "core/interrupt.h"
#include "opencl/failure_text.h"

namespace kasha {

static std::vector<Command>& entries() {
  static std::vector<Command> registry;  // filled during static initialization
  return registry;
}

CommandRegistry::Registrar::Registrar(Command command) {
  auto& e = entries();
  e.insert(std::upper_bound(e.begin(), e.end(), command,
                            [](const Command& a, const Command& b) { return a.order < b.order; }),
           std::move(command));
}

const std::vector<Command>& CommandRegistry::all() {
  return entries();
}

static int report_interrupt() {
  std::fprintf(stderr, "kasha: interrupted\n");
  return kInterruptExitCode;
}

// Input and run errors: exit 1. A failure after a signal (a device call or a compiler cut short)
// is the interrupt's doing: that is what is reported.
int report_failure() {
  try {
    throw;
  } catch (const Interrupted&) {
    return report_interrupt();
  } catch (const std::bad_alloc&) {
    // Nothing may be allocated here: the message is a literal.
    std::fputs("kasha: error: out of memory (the input needs more memory than kasha may take)\n",
               stderr);
    return 1;
  } catch (...) {
    if (interrupt_requested()) return report_interrupt();
    std::fprintf(stderr, "kasha: error: %s\n", failure_text().c_str());
    return 1;
  }
}

}  // namespace kasha
