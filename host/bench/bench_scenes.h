#pragma once
// The fixed scenes of `kasha bench` (LuxMark's fixed scene set): each rendered by every physical
// integrator that can render it, at a fixed resolution, and validated against its reference.
#include <string>
#include <vector>

namespace kasha {

struct BenchScene {
  std::string name;  // as the table and the JSON record name it
  std::string file;  // the scene, relative to the scenes folder
  // The resolution bench renders at (the scene's camera otherwise): at most 128 on a side, so a
  // 2-second run on a CPU device still gathers enough samples per pixel to be validated.
  int width = 0, height = 0;
  // "furnace" (the analytic value), or a reference EXR relative to the scenes folder, rendered by
  // `kasha bench --make-references` at this resolution with the reference integrator.
  std::string reference;
  // The camera sees the scene's light through an ideal mirror: integrators whose registry trait
  // says they cannot (forward: a delta lobe never reflects a photon into a pinhole) are not run.
  bool camera_sees_mirror = false;
  // The largest validation error (bench_validation.h) of a valid image: calibrated from 2-second
  // runs (README, "kasha bench"), well below what a factor π or a black image gives.
  double bound = 0;
  // Integrators not run on it, though they render it: their short runs' noise lies above the
  // bound (bpt finds a caustic seen in a mirror only by camera paths that hit the lamp).
  std::vector<std::string> left_out = {};
};

const std::vector<BenchScene>& bench_scenes();

// The integrators bench runs on a scene: every physical one of the registry that can render it.
std::vector<std::string> bench_integrators(const BenchScene& scene);

// The scenes folder of the source tree this kasha was built from (--scenes overrides it).
std::string default_bench_scenes_dir();

}  // namespace kasha
