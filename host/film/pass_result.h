#pragma once
// What one pass computes, kept apart from accumulating it into the film: sums that add up over
// passes in a fixed order, so that passes computed elsewhere (other devices, other processes) give
// the same image once accumulated.
#include <functional>
#include <vector>

#include "film/pass_counters.h"

namespace kasha {

// An image an integrator keeps on the device (photon mapping's SPPM statistics), read when the
// image is wanted rather than every pass: pixels × rows, radiance per nm. Valid while the
// integrator that handed it out lives.
using KeptImage = std::function<std::vector<float>()>;

struct PassResult {
  int pass = 0;
  long long samples = 0;  // samples per pixel that `sums` adds up
  // When a pass was cut short (deadline, Ctrl-C) after some pixels' samples: each pixel's own
  // count, which `samples` then is the least of; empty when every pixel has `samples`.
  std::vector<long long> pixel_samples;
  std::vector<double> sums;  // pixels × film rows
  double fraction = 1;       // of the pass's work done: < 1 when it was cut short
  KeptImage kept;            // if set: the integrator's image so far, added to the sums' mean
  PassCounters counters;     // what the pass counted besides its image: rejections, power, times
};

}  // namespace kasha
