#pragma once
// What the progressive loop asks of an integrator: the result of one more pass, which the film
// accumulates (film/pass_result.h). Integrators are made by name from the registry
// (render/integrator_registry.h).
#include <map>
#include <string>
#include <vector>

#include "film/pass_result.h"
#include "render/pass_chunks.h"
#include "render/pass_control.h"

namespace kasha {

class Integrator {
 public:
  virtual ~Integrator() = default;
  const std::string& name() const { return name_; }
  // Computes pass number `pass` (0, 1, ...) with fresh random numbers; accumulates nothing itself.
  // Under a control (set_control) the pass may end early with what it has done (its fraction).
  virtual PassResult render_pass(int pass) = 0;
  void set_control(const PassControl& control) { control_ = control; }
  virtual long long camera_paths_per_pass() const = 0;
  virtual long long photons_per_pass() const = 0;
  // The device buffers it allocated beyond the scene's and the film's tables: bytes by purpose.
  virtual std::map<std::string, size_t> device_buffers() const { return {}; }
  // Seconds its kernels ran so far (enqueue to finish), and the options they were built with:
  // what `kasha bench` reports beside the wall-clock time.
  virtual double device_seconds() const { return 0; }
  virtual std::string build_options() const { return {}; }

  // Several devices (render/render_job.h). Passes that depend on nothing before them are handed
  // out whole, one a device (render/pass_scheduler.h). An integrator whose passes build on the
  // last (photon mapping's radii) shares each pass in chunks instead (render/pass_chunks.h): it
  // returns its chunk worker here, and its first instance is given the others' in set_helpers.
  virtual ChunkWorker* chunk_worker() { return nullptr; }
  virtual void set_helpers(const std::vector<ChunkWorker*>& helpers) { (void)helpers; }

 protected:
  void rename(const std::string& name) { name_ = name; }
  PassControl control_;  // no deadline by default: passes run whole unless Ctrl-C

 private:
  friend class IntegratorRegistry;
  std::string name_;
};

}  // namespace kasha
