// kasha's SIGINT/SIGTERM handling against PoCL's LLVM (host/core/interrupt.cpp): LLVM installs
// one-shot handlers (SA_RESETHAND) over kasha's when it first compiles lazily; a poll of
// interrupt_requested() takes kasha's back, so a second Ctrl-C cannot meet the default action.
// And the threads PoCL starts while the OpenCL set-up runs block both signals (so do the linker
// processes they start), while the calling thread's mask comes back as it was.
#include <gtest/gtest.h>
#include <pthread.h>

#include <csignal>
#include <thread>

#include "core/interrupt.h"

using namespace kasha;

namespace {
extern "C" void foreign_one_shot(int) {}

void (*handler_of(int sig))(int) {
  struct sigaction current = {};
  sigaction(sig, nullptr, &current);
  return current.sa_handler;
}
}  // namespace

TEST(Interrupt, APollTakesKashasHandlersBackFromAOneShotOne) {
  struct sigaction int_before = {}, term_before = {};
  sigaction(SIGINT, nullptr, &int_before);
  sigaction(SIGTERM, nullptr, &term_before);
  install_interrupt_handler();
  void (*kasha_handler)(int) = handler_of(SIGINT);
  ASSERT_NE(kasha_handler, SIG_DFL);
  // What LLVM's RegisterHandlers does.
  struct sigaction llvm = {};
  llvm.sa_handler = foreign_one_shot;
  sigemptyset(&llvm.sa_mask);
  llvm.sa_flags = SA_NODEFER | SA_RESETHAND;
  sigaction(SIGINT, &llvm, nullptr);
  sigaction(SIGTERM, &llvm, nullptr);
  EXPECT_FALSE(interrupt_requested());
  EXPECT_EQ(handler_of(SIGINT), kasha_handler);
  EXPECT_EQ(handler_of(SIGTERM), kasha_handler);
  struct sigaction now = {};
  sigaction(SIGINT, nullptr, &now);
  EXPECT_EQ(now.sa_flags & SA_RESETHAND, 0);
  sigaction(SIGINT, &int_before, nullptr);
  sigaction(SIGTERM, &term_before, nullptr);
}

TEST(Interrupt, ThreadsStartedDuringTheSetUpBlockTheSignalsAndTheCallerDoesNotAfter) {
  sigset_t before;
  pthread_sigmask(SIG_SETMASK, nullptr, &before);
  bool thread_blocks_int = false, thread_blocks_term = false;
  {
    SignalsBlockedInNewThreads set_up;
    std::thread worker([&] {
      sigset_t mask;
      pthread_sigmask(SIG_SETMASK, nullptr, &mask);
      thread_blocks_int = sigismember(&mask, SIGINT) == 1;
      thread_blocks_term = sigismember(&mask, SIGTERM) == 1;
    });
    worker.join();
  }
  EXPECT_TRUE(thread_blocks_int);
  EXPECT_TRUE(thread_blocks_term);
  sigset_t after;
  pthread_sigmask(SIG_SETMASK, nullptr, &after);
  EXPECT_EQ(sigismember(&after, SIGINT), sigismember(&before, SIGINT));
  EXPECT_EQ(sigismember(&after, SIGTERM), sigismember(&before, SIGTERM));
}
