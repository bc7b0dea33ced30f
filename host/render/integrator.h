#pragma once
// What the progressive render loop asks of an integrator: one more pass into the film.
#include <string>

#include "film/film.h"

namespace kasha {

class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual std::string name() const = 0;
  // Adds pass number `pass` (0, 1, ...) to the film; each pass uses fresh random numbers.
  virtual void render_pass(int pass, Film& film) = 0;
  virtual long long camera_paths_per_pass() const = 0;
  virtual long long photons_per_pass() const = 0;
  // Samples left out of the film because they were not finite (reported, never hidden).
  virtual long long rejected_samples() const { return 0; }
};

}  // namespace kasha
