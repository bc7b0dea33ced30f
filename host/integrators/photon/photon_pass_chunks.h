#pragma once
// A photon-mapping pass's photons, shared among devices: traced and gathered in chunks of fixed
// photon ranges by whichever worker comes free (this device's instance first, then the others'
// or their proxies on other MPI ranks), through the ordered work distributor
// (render/ordered_work.h), and the chunks' gathers added on the host in chunk order — so one
// device or several give the same image, bit for bit.
#include <cstddef>
#include <vector>

#include "render/pass_chunks.h"
#include "render/pass_control.h"

namespace kasha {

// Photons per chunk for a pass of `photons`: about eight chunks, of at least 2^15 photons each
// (enough to share a pass among a few devices, few enough that the gathers' per-pixel work stays
// small).
size_t chunk_photons(size_t photons);

// A chunk's photons shrunk so its records fit `capacity` (the smallest store) with a margin, at
// `per_photon` records per photon as measured (a chunk that overflows is traced in halves).
size_t fitting_chunk_photons(size_t photons, size_t capacity, double per_photon);

// The pass's photons [0, photons) in chunks of `chunk` over `workers` (workers[0] is this
// device's, whose control shows progress; the others get `control` without it), each given
// `inputs` before its first chunk. Once `control` says stop, chunks after the first are left
// out. `flux_size`, `pixels`: the gather's sizes.
ChunkResult share_pass(int pass, size_t photons, size_t chunk,
                       const std::vector<ChunkWorker*>& workers, const PassInputs& inputs,
                       const PassControl& control, size_t flux_size, size_t pixels);

}  // namespace kasha
