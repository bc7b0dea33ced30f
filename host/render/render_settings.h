#pragma once
// The render settings, described once: each setting's option name, help, value range and which
// integrators take it. The command line declares its options from this table (cli/
// render_options.h), the integrator registry checks a render's options against it, and MPI ranks
// compare renders by the fingerprint it yields (render/render_spec.h).
#include <string>
#include <variant>
#include <vector>

#include "shared_types.h"

namespace kasha {

// Every integrator's settings, filled by name; each integrator reads the ones it takes.
struct IntegratorSettings {
  int spp = 0;  // --spp: camera paths per pixel per pass (0: the integrator's default)
  static constexpr int kDefaultSpp = 16;  // backward's and debug's
  long long photons = 0;  // --photons: photons (vcm: light subpaths) per pass (0: the default)
  static constexpr long long kDefaultPhotons = 1 << 18;  // forward's and photon mapping's
  double alpha = 0.8;  // --alpha: SPPM radius reduction (pbrt-v4: 2/3; 0.8 measured better here)
  double radius = 0;   // --radius: initial gather radius (0: from the pixel footprint)
  bool edge_correction = true;           // --edge-correction: gathers and merges at edges
  std::string gather = "auto";           // --gather: where photon mapping gathers (device, host)
  std::string merges = "auto";           // --merges: what vcm merges (auto, caustic, first, every)
  std::string view = "emission";         // --view: the debug view
  unsigned seed = 1;                     // --seed (every integrator)
  std::string sampler = "sobol";         // --sampler (every integrator): sobol or independent
  int max_depth = KASHA_MAX_PATH_DEPTH;  // --max-depth (every integrator): the path-length guard
  unsigned long long memory = 0;  // --memory: photon mapping's store budget, bytes (0: automatic)
  // Test hooks, not on the command line.
  bool full_matrix = false;   // backward: carry the full rows × N path matrix
  int photons_per_item = 64;  // forward: photons per work item
  int vcm_length = 0;              // vcm, bpt, ppm: only paths of this many segments (0: all)
  bool vcm_emission_only = false;  // vcm, bpt: only camera paths hitting emitters, unweighted
  bool vcm_drop_density = false;   // vcm, bpt: a wrong MIS weight (kernels/vcm.cl)
  bool vcm_no_seen_light = false;  // vcm, bpt, ppm: the camera paths alone take the light seen
                                   // through delta bounces (no vcm_seen_light samples)
};

// Where a setting's value lives in IntegratorSettings.
using SettingField =
    std::variant<int*, long long*, unsigned*, unsigned long long*, double*, bool*, std::string*>;

struct RenderSetting {
  enum class Value {
    integer,   // within [lo, hi]
    number,    // finite, within [lo, hi]
    positive,  // finite, in (0, hi]
    bytes,     // bytes with an optional unit (512MiB, 2GB), within [lo, hi]
    flag,      // --name or --name=false
    choice,    // one of `choices`
  };
  std::string name, help;
  Value value;
  double lo = 0, hi = 0;
  std::vector<std::string> choices;
  bool common = false;      // every integrator takes it (else the registry lists who does)
  bool device_own = false;  // a device's own (its memory): not part of what the image depends on
  SettingField (*field)(IntegratorSettings&);
};

const std::vector<RenderSetting>& render_settings();
const RenderSetting& render_setting(const std::string& name);  // throws for an unknown name

// The settings' values as text, in the table's order, the device's own left out: what a render's
// image depends on besides its scene, integrator and film.
std::string settings_fingerprint(const IntegratorSettings& settings);

}  // namespace kasha
