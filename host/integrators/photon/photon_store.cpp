#include "integrators/photon/photon_store.h"

#include <algorithm>
#include <chrono>

#include "core/error.h"
#include "core/interrupt.h"
#include "opencl/device_buffer.h"
#include "shared/launch_records.h"

namespace kasha {

PhotonStore::PhotonStore(KernelLauncher& device, const cl::Program& program, long long photons,
                         unsigned seed, int photon_floats, size_t bytes_per_record,
                         size_t chunk_photons, unsigned long long memory)
    : device_(device),
      kernel_(program, "trace_photon_map"),
      photons_(photons),
      seed_(seed),
      photon_floats_(photon_floats) {
  ClContext& cl = device.cl();
  const size_t items = (photons_ + kPhotonsPerItem - 1) / kPhotonsPerItem;
  counter_ = device_buffer(cl, sizeof(cl_int), "photon: the store counter");
  cut_ = device_buffer(cl, items * sizeof(cl_float),
                       "photon: the depth-guard tallies of --photons " + std::to_string(photons_));
  // The store holds a chunk of a pass's photons at about four records each (what ordinary
  // albedos store) with a margin, within the memory budget; chunks that store more are traced in
  // smaller pieces, so memory stays the same however long photon paths get.
  const size_t budget = memory > 0 ? static_cast<size_t>(memory) : default_memory_budget(cl.info());
  // At least 2^18 records, so a pass of few photons with long paths fills the store in
  // launches of many photons rather than one photon at a time.
  capacity_ = std::min<size_t>({std::max<size_t>(chunk_photons * 5 + 1024, 1u << 18),
                                budget / bytes_per_record, (1u << 31) - 1});
  if (capacity_ < 1)
    throw Error("--memory: " + std::to_string(budget) + " bytes hold no photon record (" +
                std::to_string(bytes_per_record) + " bytes each)");
  store_ = device_buffer(cl, bytes(), "photon: the photon store (--memory, --photons)");
}

void PhotonStore::trace(int pass, size_t first, size_t count, const PassControl& control,
                        std::atomic<size_t>& progress, const Gather& gather, ChunkResult& c) {
  size_t done = 0, stored = 0;
  double cut = 0, trace_s = 0;
  while (done < count) {
    if ((done > 0 || first > 0) && control.stop_now()) break;
    const size_t n = pacer_.next(count - done);
    auto t = std::chrono::steady_clock::now();
    const double device_before = device_.launched_seconds();
    cl_int after = launch_photons(pass, first + done, n, 0, stored);
    trace_s += device_.launched_seconds() - device_before;
    if (static_cast<size_t>(after) > capacity_) {
      c.trace_s += trace_s;
      progress -= done;
      if (count == 1) {
        trace_long_photon(pass, first, gather, c);
        progress += 1;
      } else {
        // The halves measure their own records per photon for the next pass's chunks: a bound
        // from this overflow would let one photon of a long walk shrink every chunk after it.
        c.overflows += 1;
        trace(pass, first, count / 2, control, progress, gather, c);
        trace(pass, first + count / 2, count - count / 2, control, progress, gather, c);
      }
      return;
    }
    pacer_.record(n, seconds_since(t));
    cut += device_.read_sum<cl_float>(cut_, (n + kPhotonsPerItem - 1) / kPhotonsPerItem);
    stored = after;
    done += n;
    progress += n;
    control.report(static_cast<double>(progress) / photons_);
  }
  if (stored > 0) gather(stored, c);
  c.trace_s += trace_s;
  c.traced += static_cast<double>(done);
  c.cut += cut;
  if (done == count && done > 0)
    c.per_photon = std::max(c.per_photon, static_cast<double>(stored) / done);
}

// Photons [first, first + count) into the store from slot `stored`, `skip` stores passed over
// per photon; returns the store's count afterwards.
cl_int PhotonStore::launch_photons(int pass, size_t first, size_t count, int skip, size_t stored) {
  cl_int start = static_cast<cl_int>(stored);
  device_.cl().queue().enqueueWriteBuffer(counter_, CL_TRUE, 0, sizeof(cl_int), &start);
  const int per_item = count == 1 ? 1 : kPhotonsPerItem;
  const KPhotonTraceLaunch record{static_cast<int>(photons_),
                                  static_cast<int>(first),
                                  static_cast<int>(count),
                                  per_item,
                                  skip,
                                  static_cast<int>(capacity_),
                                  seed_,
                                  static_cast<uint>(pass)};
  device_.launch_range(kernel_, 0, (count + per_item - 1) / per_item, record, store_, counter_,
                       cut_);
  cl_int after = 0;
  device_.cl().queue().enqueueReadBuffer(counter_, CL_TRUE, 0, sizeof(cl_int), &after);
  if (after < 0) return static_cast<cl_int>(capacity_) + 1;  // wrapped: overflowed for sure
  return after;
}

// A photon whose stores exceed the store, traced again once per store-full of them (its path
// is the same each time: its random numbers come from its index).
void PhotonStore::trace_long_photon(int pass, size_t index, const Gather& gather, ChunkResult& c) {
  for (size_t skip = 0;; skip += capacity_) {
    if (skip > (1u << 31) - 1) throw Error("photon: one photon stored more than 2^31 records");
    double t = device_.launched_seconds();
    cl_int after = launch_photons(pass, index, 1, static_cast<int>(skip), 0);
    c.trace_s += device_.launched_seconds() - t;
    if (skip == 0) c.cut += device_.read_sum<cl_float>(cut_, 1);
    const size_t stored = std::min<size_t>(static_cast<size_t>(after), capacity_);
    if (stored > 0) gather(stored, c);
    if (static_cast<size_t>(after) <= capacity_ || interrupt_requested()) break;
  }
  c.traced += 1;  // a photon cut short by Ctrl-C loses its remaining stores; rare
}

}  // namespace kasha
