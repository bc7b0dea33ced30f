#pragma once
// A pass shared in chunks, for an integrator whose passes build on the ones before (photon
// mapping: integrators/photon/photon_pass_chunks.h). The main device prepares the pass (the
// camera pass), then the pass's photons are traced and gathered in fixed chunks by whichever
// worker comes free — the integrator's instances on other devices, or their proxies on other MPI
// ranks (mpi/remote_lane.h) — and the chunks' gathers add up in chunk order.
#include <atomic>
#include <cstddef>
#include <vector>

#include "render/pass_control.h"

namespace kasha {

// What the camera pass leaves for the workers: visible points, radii and the grid's cell size.
struct PassInputs {
  std::vector<float> visible_points, radius, cell;
};

// The gather of some of a pass's photons: per pixel Σ K·Φ (pixels × rows) and the count, with
// what tracing them took.
struct ChunkResult {
  std::vector<double> flux;
  std::vector<int> found;
  double traced = 0, records = 0, cut = 0, trace_s = 0, gather_s = 0;
  double overflows = 0;  // ranges traced again in halves
  double gathers = 0;    // gathers of a store: each queries every visible point
  double closest_rays = 0, shadow_rays = 0;
  double per_photon = 0;     // the most records a photon of a whole range stored
  std::vector<double> work;  // photons traced per device index, with several
};

class ChunkWorker {
 public:
  virtual ~ChunkWorker() = default;
  // Photon records its store holds: chunks are sized to fit the smallest.
  virtual size_t chunk_capacity() const = 0;
  // The pass's deadline (progress is the main device's to show).
  virtual void set_chunk_control(const PassControl& control) = 0;
  // A copy of the main device's visible points, radii and cell size for this pass.
  virtual void take_inputs(const PassInputs& inputs) = 0;
  // Traces and gathers photons [first, first + count) of pass `pass`; `progress` counts the
  // photons traced on every worker (the main device shows it).
  virtual ChunkResult trace_chunk(int pass, size_t first, size_t count,
                                  std::atomic<size_t>& progress) = 0;
};

}  // namespace kasha
