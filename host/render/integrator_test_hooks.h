#pragma once
// Switches the tests set on an integrator, not on the command line: they reach the integrator
// beside its settings (render/integrator_registry.h's IntegratorSetup), never the fingerprint.

namespace kasha {

struct IntegratorTestHooks {
  bool full_matrix = false;        // backward: carry the full rows × N path matrix
  int photons_per_item = 64;       // forward: photons per work item
  int vcm_length = 0;              // vcm, bpt, ppm: only paths of this many segments (0: all)
  bool vcm_emission_only = false;  // vcm, bpt: only camera paths hitting emitters, unweighted
  bool vcm_drop_density = false;   // vcm, bpt: a wrong MIS weight (kernels/vcm/vcm_modes.h)
  bool vcm_no_seen_light = false;  // vcm, bpt, ppm: the camera paths alone take the light seen
                                   // through delta bounces (no vcm_seen_light samples)
};

}  // namespace kasha
