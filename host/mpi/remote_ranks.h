#pragma once
// Rank 0's view of the other ranks of a render: every rank's hello (the devices it serves, or
// the one line of why it has none), and a RemoteLane per device, which rank 0's RenderJob adds to
// its own devices.
#include <memory>
#include <string>
#include <vector>

#include "mpi/remote_lane.h"

namespace kasha {

class RemoteRanks {
 public:
  // Waits for the hello of every rank of the world but 0. Throws kasha::Error `rank R: what` for
  // a rank that failed to set up, and Interrupted on an interrupt.
  // `render`: rank 0's render_fingerprint (mpi/render_server.h), which every rank's must equal.
  RemoteRanks(const std::string& integrator, const std::string& render);

  std::vector<Integrator*> lanes() const;
  const std::vector<std::unique_ptr<RemoteLane>>& devices() const { return lanes_; }

 private:
  std::vector<std::unique_ptr<RemoteLane>> lanes_;
};

}  // namespace kasha
