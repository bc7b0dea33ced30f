#pragma once
// A device of another MPI rank as rank 0's render sees it (render/render_job.h): an Integrator
// whose passes are rendered there (the PassScheduler hands it passes as it does a local device),
// and for photon mapping a ChunkWorker that traces chunks of a pass's photons there. Each call
// sends one request on the device's tag and waits, polling, for the one answer; an answer of
// failure throws kasha::Error `rank R: what`.
#include <atomic>
#include <string>

#include "mpi/render_messages.h"
#include "render/integrator.h"
#include "render/pass_chunks.h"

namespace kasha {

class RemoteLane : public Integrator, public ChunkWorker {
 public:
  RemoteLane(int rank, int device, const std::string& integrator, const mpi::RemoteDevice& info);

  int rank() const { return rank_; }
  // "rank R device D (NAME)"
  std::string description() const;

  PassResult render_pass(int pass) override;
  // Rank 0's own instance stands for every lane in these (render/pass_scheduler.h).
  long long camera_paths_per_pass() const override { return 0; }
  long long photons_per_pass() const override { return 0; }

  ChunkWorker* chunk_worker() override { return this; }
  size_t chunk_capacity() const override { return static_cast<size_t>(info_.capacity); }
  void set_chunk_control(const PassControl& control) override { set_control(control); }
  void take_inputs(const PassInputs& inputs) override;
  ChunkResult trace_chunk(int pass, size_t first, size_t count,
                          std::atomic<size_t>& progress) override;

 private:
  void send(const mpi::Request& request);
  mpi::Reply receive(mpi::Kind expected);

  int rank_, device_;
  mpi::RemoteDevice info_;
};

}  // namespace kasha
