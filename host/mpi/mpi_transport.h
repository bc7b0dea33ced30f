#pragma once
// Point-to-point messages between MPI ranks, polled rather than blocked on: a receive is tried
// (MPI_Improbe) and a send is started and tested (MPI_Isend), and the caller sleeps briefly
// between tries, so a wait can notice an interrupt or a stop and never hangs in MPI. Messages go
// on MPI_COMM_WORLD with MPI_ERRORS_RETURN: an MPI failure throws kasha::Error. Without an MPI
// build these throw too (a process alone never calls them).
#include <memory>
#include <optional>
#include <vector>

namespace kasha::mpi {

// Tags: device d of a rank talks on tag d (render/remote_lane.h); these are the job's own.
constexpr int kControlTag = 32000;  // rank 0 → rank: interrupt, stop
constexpr int kAnswerTag = 32001;   // rank → rank 0: the control message arrived
constexpr int kHelloTag = 32002;    // rank → rank 0: its devices, or why it has none
constexpr int kMaxDevices = 31999;

// The next message from `source` with `tag`, if one has arrived.
std::optional<std::vector<char>> try_receive(int source, int tag);

// A send in flight; done() once the bytes have left (MPI may still be delivering them). Each
// test of a send moves it on, so a large one is tested in a tight loop (wait): sleeping between
// tests would stretch a rendezvous send's fragments over milliseconds each.
class Outgoing {
 public:
  Outgoing(int destination, int tag, std::vector<char> bytes);
  ~Outgoing();  // a send not done is left to MPI, with its bytes (only on a failing job's way out)
  Outgoing(const Outgoing&) = delete;
  Outgoing& operator=(const Outgoing&) = delete;
  bool done();
  // Tests until done, yielding the core between tests; false if `give_up` said so first.
  template <typename GiveUp>
  bool wait(GiveUp give_up) {
    while (!done())
      if (give_up())
        return false;
      else
        yield();
    return true;
  }
  bool wait() {
    return wait([] { return false; });
  }

 private:
  static void yield();
  struct State;
  std::unique_ptr<State> state_;
};

// Sleeps between polls: 20 µs at first, doubling to 1 ms, so a quick answer costs little latency
// and a long wait little CPU.
class Backoff {
 public:
  void pause();
  void reset() { micros_ = 20; }

 private:
  int micros_ = 20;
};

}  // namespace kasha::mpi
