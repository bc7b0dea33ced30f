#include "core/interrupt.h"

#include <pthread.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <initializer_list>

namespace kasha {

namespace {
std::atomic<int> g_requests{0};
std::atomic<int> g_message_fd{STDERR_FILENO};

// write(2) and _exit are async-signal-safe; stdio is not. `after_progress`: a progress line
// (ended by \r, not \n) may be on the terminal, so the message starts a line of its own.
void exit_interrupted(bool after_progress) {
  static const char line[] = "\nkasha: interrupted\n";
  const char* from = after_progress ? line : line + 1;
  ssize_t ignored = write(g_message_fd, from, sizeof line - 1 - (from - line));
  (void)ignored;
  _exit(kInterruptExitCode);
}

extern "C" void on_signal_exit(int) {
  exit_interrupted(false);
}

// Counts rather than resetting to the default action: one Ctrl-C can arrive twice (a shell or
// `timeout` signals both the process and its group), and that must not kill the writer.
extern "C" void on_signal_flag(int) {
  if (++g_requests >= 3) exit_interrupted(true);
}

extern "C" void on_signal_count(int) {
  ++g_requests;
}

// The handler kasha last installed, and its flags: what reassert_handler() puts back.
std::atomic<void (*)(int)> g_handler{nullptr};
std::atomic<int> g_flags{0};

void install(void (*handler)(int), int flags = SA_RESTART, struct sigaction* int_before = nullptr,
             struct sigaction* term_before = nullptr) {
  struct sigaction action = {};
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  action.sa_flags = flags;  // SA_RESTART: blocking reads and writes carry on; the flag is polled
  g_handler = handler;
  g_flags = flags;
  sigaction(SIGINT, &action, int_before);
  sigaction(SIGTERM, &action, term_before);
}

// PoCL's LLVM installs its own handlers over kasha's the first time it compiles lazily (a
// kernel's variant at its first launch, in a worker thread). They are one-shot (SA_RESETHAND):
// the signal that runs one resets the action to the default, so a second signal in the moment
// before LLVM puts kasha's back (Ctrl-C and `timeout` signal both the process and its group)
// killed kasha without a word or an image. kasha takes its handlers back whenever it polls.
void reassert_handler() {
  void (*handler)(int) = g_handler;
  if (!handler) return;
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction current = {};
    if (sigaction(sig, nullptr, &current) != 0 || current.sa_handler == handler) continue;
    struct sigaction action = {};
    action.sa_handler = handler;
    sigemptyset(&action.sa_mask);
    action.sa_flags = g_flags;
    sigaction(sig, &action, nullptr);
  }
}
}  // namespace

void install_exit_on_interrupt() {
  install(on_signal_exit);
}

void install_interrupt_handler() {
  g_requests = 0;
  install(on_signal_flag);
}

InterruptsDeferred::InterruptsDeferred() {
  install(on_signal_count, 0, &int_before_, &term_before_);
}

InterruptsDeferred::~InterruptsDeferred() {
  g_handler = int_before_.sa_handler == SIG_DFL || int_before_.sa_handler == SIG_IGN
                  ? nullptr
                  : int_before_.sa_handler;
  g_flags = int_before_.sa_flags;
  sigaction(SIGINT, &int_before_, nullptr);
  sigaction(SIGTERM, &term_before_, nullptr);
}

SignalsBlockedInNewThreads::SignalsBlockedInNewThreads() {
  sigset_t block;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &block, &before_);
}

SignalsBlockedInNewThreads::~SignalsBlockedInNewThreads() {
  pthread_sigmask(SIG_SETMASK, &before_, nullptr);  // a signal that came meanwhile arrives now
}

void set_interrupt_message_fd(int fd) {
  g_message_fd = fd;
}

void request_interrupt() {
  int none = 0;
  g_requests.compare_exchange_strong(none, 1);  // a signal's count stays as it is
}

bool interrupt_requested() {
  reassert_handler();
  return g_requests > 0;
}

}  // namespace kasha
