#include "mpi/remote_ranks.h"

#include <optional>

#include "core/error.h"
#include "core/interrupt.h"
#include "mpi/mpi_transport.h"
#include "mpi/mpi_world.h"

namespace kasha {

RemoteRanks::RemoteRanks(const std::string& integrator, const std::string& render) {
  const int size = MpiWorld::get().size();
  std::vector<std::optional<mpi::Hello>> hellos(size);
  // Ranks set up at once (scene, devices, kernel builds): hellos come in any order, and the first
  // of a rank that failed ends the wait.
  mpi::Backoff backoff;
  for (int waiting = size - 1; waiting > 0;) {
    if (interrupt_requested()) {
      MpiWorld::get().settle_interrupt();  // a rank that died is named, not the interrupt
      throw Interrupted();
    }
    bool any = false;
    for (int r = 1; r < size; ++r)
      if (!hellos[r])
        if (std::optional<std::vector<char>> bytes = mpi::try_receive(r, mpi::kHelloTag)) {
          hellos[r] = mpi::decode_hello(*bytes);
          if (!hellos[r]->error.empty())
            throw Error("rank " + std::to_string(r) + ": " + hellos[r]->error);
          if (hellos[r]->render != render)
            throw Error("rank " + std::to_string(r) +
                        ": its command line renders another image than rank 0's (the ranks "
                        "may differ in --device and --memory only)");
          --waiting;
          any = true;
        }
    if (!any) backoff.pause();
  }
  for (int r = 1; r < size; ++r) {
    for (size_t d = 0; d < hellos[r]->devices.size(); ++d)
      lanes_.push_back(
          std::make_unique<RemoteLane>(r, static_cast<int>(d), integrator, hellos[r]->devices[d]));
  }
}

std::vector<Integrator*> RemoteRanks::lanes() const {
  std::vector<Integrator*> out;
  for (const auto& lane : lanes_) out.push_back(lane.get());
  return out;
}

}  // namespace kasha
