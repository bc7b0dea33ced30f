// Times the OpenCL BVH traversal against Embree's rtcIntersect1 on the same rays in one run and
// prints rays/s for both and their ratio. Usage: bench_traversal [--device I] [--rays N]
// SCENE.json...
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/error.h"
#include "geometry/bvh.h"
#include "geometry/cl_traversal.h"
#include "geometry/embree_scene.h"
#include "geometry/random_rays.h"
#include "scene/scene.h"

using namespace kasha;

template <typename F>
static double best_seconds(F&& f, int repeats) {
  double best = 1e30;
  for (int i = 0; i < repeats; ++i) {
    auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

int main(int argc, char** argv) {
  int device = 0;
  size_t count = 1 << 20;
  std::vector<std::string> scenes;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--device") && i + 1 < argc)
      device = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--rays") && i + 1 < argc)
      count = std::strtoull(argv[++i], nullptr, 10);
    else
      scenes.push_back(argv[i]);
  }
  if (scenes.empty()) {
    std::fprintf(stderr, "usage: bench_traversal [--device I] [--rays N] SCENE.json...\n");
    return 2;
  }
  try {
    ClContext cl(device);
    std::printf("device: %s (%s)\n", cl.info().name.c_str(), cl.info().platform.c_str());
    std::printf("%-36s %10s %14s %14s %8s\n", "scene", "triangles", "OpenCL rays/s",
                "Embree rays/s", "ratio");
    for (const std::string& path : scenes) {
      Scene scene = load_scene(path);
      FlatBvh bvh = build_bvh(scene.triangles);
      EmbreeScene embree(scene.triangles);
      ClTraversal traversal(cl, bvh);
      std::vector<KRay> rays = random_rays(scene.triangles, count, 7);
      std::vector<KHit> hits;
      traversal.closest(rays);  // warm-up: kernel compile and first transfer
      double t_cl = best_seconds([&] { traversal.closest(rays); }, 3);
      double t_em = best_seconds([&] { embree.intersect_all(rays, hits); }, 3);
      std::printf("%-36s %10zu %14.3e %14.3e %8.3f\n", path.c_str(), scene.triangles.size(),
                  count / t_cl, count / t_em, t_em / t_cl);
    }
    std::printf(
        "ratio = OpenCL rays/s / Embree rays/s, closest hit, same rays, same host threads\n");
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_traversal: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
