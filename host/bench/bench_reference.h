#pragma once
// A bench scene as bench renders it — at the bench resolution — with the reference its images are
// validated against: the analytic furnace, or an EXR shipped in scenes/bench/ that
// `kasha bench --make-references SECONDS` renders with the reference integrator (backward, the
// lowest-variance unbiased one) on a trusted device. Shipped rather than rendered on the device
// under test, which would validate a wrong device against its own wrong image.
#include <string>

#include "bench/bench_scenes.h"
#include "film/image.h"
#include "scene/scene.h"

namespace kasha {

struct LoadedBenchScene {
  const BenchScene* bench = nullptr;
  std::string path;            // the scene file
  std::string reference_path;  // the reference EXR, or empty for the furnace
  Scene scene;                 // its camera at the bench resolution
  size_t triangles = 0;
  Image reference;  // empty until load_bench_reference
  std::string reference_description;
};

// The scene at the bench resolution; throws kasha::Error for a scene that does not load.
LoadedBenchScene load_bench_scene(const BenchScene& bench, const std::string& scenes_dir);

// Its reference; throws kasha::Error naming the file when it is missing, of another size, or
// made for another version of the scene file (its recorded fingerprint differs), with the
// command that remakes it.
void load_bench_reference(LoadedBenchScene& s);

}  // namespace kasha
