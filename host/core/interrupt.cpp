#include "core/interrupt.h"

#include <unistd.h>

#include <atomic>
#include <csignal>

namespace kasha {

namespace {
std::atomic<int> g_requests{0};
// Counts rather than resetting to the default action: one Ctrl-C can arrive twice (a shell or
// `timeout` signals both the process and its group), and that must not kill the writer.
extern "C" void on_sigint(int) {
  if (++g_requests >= 3) _exit(130);
}
}  // namespace

void install_interrupt_handler() {
  g_requests = 0;
  std::signal(SIGINT, on_sigint);
}

bool interrupt_requested() {
  return g_requests > 0;
}

}  // namespace kasha
