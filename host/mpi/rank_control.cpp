#include "mpi/rank_control.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "core/error.h"
#include "core/interrupt.h"
#include "mpi/mpi_transport.h"

namespace kasha::mpi {

namespace {
constexpr char kInterrupt = 'i', kStop = 's';
using Clock = std::chrono::steady_clock;

std::vector<char> one(char c) {
  return {c};
}

bool answered(int rank, char what) {
  // Answers come in the order asked; an interrupt's may still be waiting before a stop's.
  while (std::optional<std::vector<char>> m = try_receive(rank, kAnswerTag))
    if (m->size() == 1 && (*m)[0] == what) return true;
  return false;
}

[[noreturn]] void give_up(int rank, const char* after) {
  // Printed and exited here rather than thrown: mpirun kills rank 0 about a second after its
  // SIGTERM, too soon to unwind a render (nothing is written before the end of a render).
  std::fprintf(stderr,
               "kasha: error: rank %d: no answer within %.1f s of the %s: the rank died or "
               "hangs (mpirun names a rank that died)\n",
               rank, kAnswerSeconds, after);
  std::fflush(stderr);
  std::_Exit(1);
}
}  // namespace

RankWatch::RankWatch(int size) : size_(size), thread_([this] { watch(); }) {}

RankWatch::~RankWatch() {
  ending_ = true;
  if (thread_.joinable()) thread_.join();
}

void RankWatch::watch() {
  try {
    while (!ending_ && !interrupt_requested())
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    if (ending_) return;
    std::vector<std::unique_ptr<Outgoing>> told;
    for (int r = 1; r < size_; ++r)
      told.push_back(std::make_unique<Outgoing>(r, kControlTag, one(kInterrupt)));
    const auto t0 = Clock::now();
    std::vector<bool> heard(size_, false);
    heard[0] = true;
    Backoff backoff;
    for (int waiting = size_ - 1; waiting > 0 && !ending_;) {
      for (int r = 1; r < size_; ++r)
        if (!heard[r] && answered(r, kInterrupt)) {
          heard[r] = true;
          --waiting;
        }
      if (waiting == 0) break;
      if (std::chrono::duration<double>(Clock::now() - t0).count() > kAnswerSeconds)
        for (int r = 1; r < size_; ++r)
          if (!heard[r]) give_up(r, "interrupt");
      backoff.pause();
    }
    for (auto& t : told) t->wait([this] { return ending_.load(); });
  } catch (const Error& e) {
    // An MPI failure here means a rank is gone: the same verdict, with MPI's words.
    std::fprintf(stderr, "kasha: error: %s\n", e.what());
    std::fflush(stderr);
    std::_Exit(1);
  }
}

void RankWatch::settle() {
  if (interrupt_requested() && thread_.joinable()) thread_.join();
}

bool RankWatch::stop_all() {
  settle();  // an interrupt's verdict first: a rank that died is named as such
  ending_ = true;
  if (thread_.joinable()) thread_.join();
  std::vector<std::unique_ptr<Outgoing>> told;
  for (int r = 1; r < size_; ++r)
    told.push_back(std::make_unique<Outgoing>(r, kControlTag, one(kStop)));
  const auto t0 = Clock::now();
  std::vector<bool> heard(size_, false);
  Backoff backoff;
  for (int waiting = size_ - 1; waiting > 0;) {
    for (int r = 1; r < size_; ++r)
      if (!heard[r] && answered(r, kStop)) {
        heard[r] = true;
        --waiting;
      }
    if (waiting == 0) break;
    if (std::chrono::duration<double>(Clock::now() - t0).count() > kAnswerSeconds) {
      for (int r = 1; r < size_; ++r)
        if (!heard[r])
          std::fprintf(stderr,
                       "kasha: error: rank %d: no answer within %.1f s of the stop: the rank "
                       "died or hangs\n",
                       r, kAnswerSeconds);
      return false;
    }
    backoff.pause();
  }
  for (auto& t : told) t->wait();
  return true;
}

ControlListener::ControlListener() : thread_([this] { listen(); }) {}

ControlListener::~ControlListener() {
  thread_.join();
}

void ControlListener::wait_stopped() {
  while (!stopped_) std::this_thread::sleep_for(std::chrono::milliseconds(2));
}

void ControlListener::listen() {
  Backoff backoff;
  std::vector<std::unique_ptr<Outgoing>> answers;
  try {
    while (!stopped_) {
      std::optional<std::vector<char>> m = try_receive(0, kControlTag);
      if (!m) {
        backoff.pause();
        continue;
      }
      backoff.reset();
      const char what = m->size() == 1 ? (*m)[0] : '?';
      if (what == kInterrupt) request_interrupt();
      answers.push_back(std::make_unique<Outgoing>(0, kAnswerTag, one(what)));
      if (what == kStop) {
        for (auto& a : answers) a->wait();
        stopped_ = true;
      }
    }
  } catch (const Error&) {
    stopped_ = true;  // MPI failed: rank 0 is gone, and nothing of this rank is left to report
  }
}

}  // namespace kasha::mpi
