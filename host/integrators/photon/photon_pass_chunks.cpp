#include "integrators/photon/photon_pass_chunks.h"

#include <algorithm>
#include <atomic>

#include "film/pass_result.h"
#include "render/ordered_work.h"

namespace kasha {

namespace {
constexpr size_t kChunksPerPass = 8;
constexpr size_t kChunkPhotons = 1 << 15;

void add_chunk(ChunkResult& total, const ChunkResult& c) {
  for (size_t i = 0; i < c.flux.size(); ++i) total.flux[i] += c.flux[i];
  for (size_t p = 0; p < c.found.size(); ++p) total.found[p] += c.found[p];
  total.traced += c.traced;
  total.records += c.records;
  total.cut += c.cut;
  total.overflows += c.overflows;
  total.gathers += c.gathers;
  total.closest_rays += c.closest_rays;
  total.shadow_rays += c.shadow_rays;
  total.trace_s += c.trace_s;
  total.gather_s += c.gather_s;
  total.per_photon = std::max(total.per_photon, c.per_photon);
}
}  // namespace

size_t chunk_photons(size_t photons) {
  return std::min(photons,
                  std::max(kChunkPhotons, (photons + kChunksPerPass - 1) / kChunksPerPass));
}

size_t fitting_chunk_photons(size_t photons, size_t capacity, double per_photon) {
  const size_t fit = static_cast<size_t>(static_cast<double>(capacity) / (per_photon * 1.25));
  return std::clamp<size_t>(fit, 1, chunk_photons(photons));
}

ChunkResult share_pass(int pass, size_t photons, size_t chunk,
                       const std::vector<ChunkWorker*>& workers, const PassInputs& inputs,
                       const PassControl& control, size_t flux_size, size_t pixels) {
  const size_t chunks = (photons + chunk - 1) / chunk;
  std::vector<double> work_done(workers.size(), 0.0);  // each written by its worker's thread only
  // Given the pass's inputs; not vector<bool>, as each worker's thread writes its own element.
  std::vector<char> ready(workers.size(), 0);
  std::atomic<size_t> progress{0};
  PassControl quiet = control;
  quiet.progress = nullptr;  // progress is the first worker's to show
  OrderedWork<ChunkResult> work(workers.size(), [&](size_t lane, long long c) {
    ChunkWorker& worker = *workers[lane];
    if (lane > 0 && !ready[lane]) {
      worker.set_chunk_control(quiet);
      worker.take_inputs(inputs);
      ready[lane] = 1;
    }
    const size_t first = static_cast<size_t>(c) * chunk;
    ChunkResult result;
    // Every worker's deadline is this pass's, so it is checked here for all.
    if (c == 0 || !control.stop_now())
      result = worker.trace_chunk(pass, first, std::min(chunk, photons - first), progress);
    work_done[lane] += result.traced;
    return result;
  });
  work.allow_until(static_cast<long long>(chunks));
  ChunkResult total;
  total.flux.assign(flux_size, 0.0);
  total.found.assign(pixels, 0);
  for (size_t c = 0; c < chunks; ++c) add_chunk(total, work.take(static_cast<long long>(c)));
  if (workers.size() > 1) total.work = work_done;
  return total;
}

}  // namespace kasha
