#pragma once
// The control channel of an MPI job, beside the ranks' work: rank 0 tells every other rank to
// interrupt (Ctrl-C) or to stop (the job is over), and each answers at once from a thread of its
// own, whatever its devices are doing. An answer is how rank 0 knows a rank is alive: when one
// dies, mpirun sends SIGTERM to the others — an interrupt — so rank 0, once interrupted, gives a
// rank that does not answer half a second, then names it in one line and exits non-zero.
#include <atomic>
#include <thread>
#include <vector>

namespace kasha::mpi {

// How long rank 0 waits for an answer: well within the second that mpirun (Open MPI's
// odls_base_sigkill_timeout) leaves between its SIGTERM and its SIGKILL.
constexpr double kAnswerSeconds = 0.5;

// Rank 0's side: a thread that, once interrupt_requested(), tells every rank and checks their
// answers.
class RankWatch {
 public:
  explicit RankWatch(int size);
  ~RankWatch();
  RankWatch(const RankWatch&) = delete;
  RankWatch& operator=(const RankWatch&) = delete;
  // After an interrupt: returns once every rank has answered it, or ends the process naming one
  // that did not. Before one: returns at once. From one thread only.
  void settle();
  // Tells every rank to stop and waits for their answers; false (with a line on stderr) when one
  // gave none.
  bool stop_all();

 private:
  void watch();
  int size_;
  std::atomic<bool> ending_{false};
  std::thread thread_;
};

// The other ranks' side: a thread that raises the interrupt flag when told, and ends when told to
// stop.
class ControlListener {
 public:
  ControlListener();
  ~ControlListener();
  ControlListener(const ControlListener&) = delete;
  ControlListener& operator=(const ControlListener&) = delete;
  bool stopped() const { return stopped_; }
  void wait_stopped();  // until rank 0 says stop (or MPI fails)

 private:
  void listen();
  std::atomic<bool> stopped_{false};
  std::thread thread_;
};

}  // namespace kasha::mpi
