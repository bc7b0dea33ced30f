#pragma once
// What the progressive loop tells whoever watches a render after each pass (render/
// progressive_render.h): the pass, the render time so far and the work done, with the film as it
// stands. The convergence log (study/convergence_log.h) is one such observer; what it measures
// after a pass does not count towards the render's time.
#include <string>

#include "film/film.h"

namespace kasha {

struct PassRecord {
  std::string integrator;
  int pass = 0;                             // passes done, 1, 2, ...
  double seconds = 0;                       // rendering time so far
  long long camera_paths = 0, photons = 0;  // so far
};

class PassObserver {
 public:
  virtual ~PassObserver() = default;
  virtual void pass_done(const PassRecord& record, const Film& film) = 0;
};

}  // namespace kasha
