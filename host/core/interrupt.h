#pragma once
// SIGINT (Ctrl-C) and SIGTERM. At first a signal ends the process at once with one line and exit
// code 130 (nothing is written yet). A command that can stop early (render, converge, reference,
// bench) installs the deferred handler: a signal then only raises a flag, so the render loop can
// finish the pass in flight and write the image so far; a third signal ends the process at once.
#include <csignal>
#include <exception>

namespace kasha {

constexpr int kInterruptExitCode = 130;

// At the start of main: a signal prints `kasha: interrupted` and exits 130.
void install_exit_on_interrupt();
// For the commands that poll interrupt_requested().
void install_interrupt_handler();
// Whether a signal asked to stop. Each poll also puts kasha's handlers back where PoCL's LLVM
// replaced them with its one-shot ones (interrupt.cpp, reassert_handler).
bool interrupt_requested();
// Raises the flag as a signal would: an MPI rank told by rank 0 that the job was interrupted.
void request_interrupt();
// Where the handler writes `kasha: interrupted` (default 2): the original stderr while fd 2 is
// held elsewhere (a kernel build's compiler output).
void set_interrupt_message_fd(int fd);

// While alive, SIGINT and SIGTERM only raise interrupt_requested(), however many arrive, and
// interrupt blocking calls (EINTR): for a wait on a subprocess, which is then stopped and waited
// for, so no signal ends kasha with the child still running and its files left behind. The
// handlers before are restored after.
class InterruptsDeferred {
 public:
  InterruptsDeferred();
  ~InterruptsDeferred();
  InterruptsDeferred(const InterruptsDeferred&) = delete;
  InterruptsDeferred& operator=(const InterruptsDeferred&) = delete;

 private:
  struct sigaction int_before_ = {}, term_before_ = {};
};

// While alive, the calling thread blocks SIGINT and SIGTERM, and so does every thread it starts and
// every process those start (a mask is inherited). Around the OpenCL set-up: PoCL's worker threads
// compile a kernel's variants at its first launches and run the linker as a child; a Ctrl-C or
// mpirun's SIGTERM sent to the group killed that linker and PoCL aborted the whole process. The
// signals still reach kasha's handler through the threads that do not block them.
class SignalsBlockedInNewThreads {
 public:
  SignalsBlockedInNewThreads();
  ~SignalsBlockedInNewThreads();
  SignalsBlockedInNewThreads(const SignalsBlockedInNewThreads&) = delete;
  SignalsBlockedInNewThreads& operator=(const SignalsBlockedInNewThreads&) = delete;

 private:
  sigset_t before_;
};

// Thrown where an interrupt made an operation fail (a kernel build whose compiler was signalled):
// the command line reports the interrupt, not the failure.
class Interrupted : public std::exception {
 public:
  const char* what() const noexcept override { return "interrupted"; }
};

}  // namespace kasha
