#pragma once
// Photon mapping's photon store on the device: its size (a chunk of a pass's photons at about
// four records each, within the memory budget), and photons traced into it in launches of
// bounded time. A range whose records overflow the store is traced again as two halves — a split
// that depends on the store's size only, so the same photons give the same records on any
// device — and a photon that alone overflows it is traced again once per store-full. Each full
// store is handed to a gather (the device's grid, or the host's k-d tree).
#include <atomic>
#include <functional>
#include <string>

#include "render/kernel_launcher.h"
#include "render/launch_pacer.h"
#include "render/pass_chunks.h"
#include "render/pass_control.h"

namespace kasha {

// Photons a work item traces in one launch.
constexpr int kPhotonsPerItem = 64;

class PhotonStore {
 public:
  // `bytes_per_record`: what a record costs on the device (its floats and what the gather keeps
  // per record); `chunk_photons`: photons a chunk holds at most.
  PhotonStore(KernelLauncher& device, const cl::Program& program, long long photons, unsigned seed,
              int photon_floats, size_t bytes_per_record, size_t chunk_photons,
              unsigned long long memory);

  size_t capacity() const { return capacity_; }  // records it holds
  const cl::Buffer& records() const { return store_; }
  size_t bytes() const { return capacity_ * photon_floats_ * sizeof(float); }

  // Gathers the first `count` records of the store into the chunk's result.
  using Gather = std::function<void(size_t count, ChunkResult& c)>;

  // Photons [first, first + count) of pass `pass` into the empty store, then gathered; stops
  // early on the control's deadline or Ctrl-C. `progress` counts the photons traced on every
  // device; the control's progress is told its share of the pass's photons.
  void trace(int pass, size_t first, size_t count, const PassControl& control,
             std::atomic<size_t>& progress, const Gather& gather, ChunkResult& c);

 private:
  cl_int launch_photons(int pass, size_t first, size_t count, int skip, size_t stored);
  void trace_long_photon(int pass, size_t index, const Gather& gather, ChunkResult& c);

  KernelLauncher& device_;
  cl::Kernel kernel_;
  long long photons_;  // per pass
  unsigned seed_;
  int photon_floats_;
  size_t capacity_;
  LaunchPacer pacer_{0.2, 256};  // in photons: the first launch is small, as paths may be long
  cl::Buffer store_, counter_, cut_;
};

}  // namespace kasha
