// Times the OpenCL BVH traversal against Embree on the same rays in one run: closest hits
// (rtcIntersect1) on random rays and shadow rays (rtcOccluded1) on segments toward points of the
// scene, Embree on one host thread per core. Each of the --runs rounds times both sides once,
// alternating which goes first; the table shows the medians of the rays/s and of the per-round
// ratios, so a burst of other load on the machine moves one round, not the result.
// Usage: bench_traversal [--device I] [--rays N] [--runs N] SCENE.json...
#include <algorithm>
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

namespace {

template <typename F>
double seconds(F&& f) {
  auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Timings {
  std::vector<double> cl, embree;  // rays/s per round
  std::vector<double> ratio;       // OpenCL / Embree per round
  void add(size_t rays, double t_cl, double t_embree) {
    cl.push_back(rays / t_cl);
    embree.push_back(rays / t_embree);
    ratio.push_back(t_embree / t_cl);
  }
};

void print_row(const std::string& scene, size_t triangles, const char* query, const Timings& t,
               const std::string& note) {
  std::printf("%-28s %10zu %-8s %12.3e %12.3e %7.3f  %5.3f-%5.3f  %s\n", scene.c_str(), triangles,
              query, median(t.cl), median(t.embree), median(t.ratio),
              *std::min_element(t.ratio.begin(), t.ratio.end()),
              *std::max_element(t.ratio.begin(), t.ratio.end()), note.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  int device = 0, runs = 5;
  size_t count = 1 << 20;
  std::vector<std::string> scenes;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--device") && i + 1 < argc)
      device = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--rays") && i + 1 < argc)
      count = std::strtoull(argv[++i], nullptr, 10);
    else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc)
      runs = std::max(1, std::atoi(argv[++i]));
    else
      scenes.push_back(argv[i]);
  }
  if (scenes.empty() || count == 0) {
    std::fprintf(stderr,
                 "usage: bench_traversal [--device I] [--rays N] [--runs N] SCENE.json...\n");
    return 2;
  }
  try {
    ClContext cl(device);
    std::printf("device: %s (%s); %zu rays per query, median of %d runs\n", cl.info().name.c_str(),
                cl.info().platform.c_str(), count, runs);
    std::printf("%-28s %10s %-8s %12s %12s %7s  %-11s  %s\n", "scene", "triangles", "query",
                "OpenCL ray/s", "Embree ray/s", "ratio", "ratio range", "");
    for (const std::string& path : scenes) {
      Scene scene = load_scene(path);
      FlatBvh bvh = build_bvh(scene.triangles);
      EmbreeScene embree(scene.triangles);
      ClTraversal traversal(cl, bvh);
      const std::vector<KRay> rays = random_rays(scene.triangles, count, 7);
      const std::vector<KRay> shadow = shadow_rays(scene.triangles, count, 8);
      std::vector<KHit> hits;
      std::vector<int> blocked;
      // Warm-up: kernel compiles, first transfers, Embree's thread pool.
      std::vector<KHit> cl_hits;
      std::vector<int> cl_blocked;
      traversal.closest(rays, cl_hits);
      traversal.occluded(shadow, cl_blocked);
      embree.intersect_all(rays, hits);
      embree.occluded_all(shadow, blocked);

      Timings closest, occluded;
      for (int r = 0; r < runs; ++r) {
        double a, b, c, d;
        if (r % 2 == 0) {
          a = seconds([&] { traversal.closest(rays, cl_hits); });
          b = seconds([&] { embree.intersect_all(rays, hits); });
          c = seconds([&] { traversal.occluded(shadow, cl_blocked); });
          d = seconds([&] { embree.occluded_all(shadow, blocked); });
        } else {
          b = seconds([&] { embree.intersect_all(rays, hits); });
          a = seconds([&] { traversal.closest(rays, cl_hits); });
          d = seconds([&] { embree.occluded_all(shadow, blocked); });
          c = seconds([&] { traversal.occluded(shadow, cl_blocked); });
        }
        closest.add(count, a, b);
        occluded.add(count, c, d);
      }
      // Both sides must answer the same queries; edge-grazing rays may differ.
      size_t hit_count = 0, differ = 0, blocked_count = 0, blocked_differ = 0;
      for (size_t i = 0; i < count; ++i) {
        hit_count += hits[i].prim >= 0;
        differ += hits[i].prim != cl_hits[i].prim;
        blocked_count += blocked[i] != 0;
        blocked_differ += (blocked[i] != 0) != (cl_blocked[i] != 0);
      }
      char note[128];
      std::snprintf(note, sizeof note, "%.1f %% hit, %zu differ", 100.0 * hit_count / count,
                    differ);
      print_row(path.substr(path.find_last_of('/') + 1), scene.triangles.size(), "closest", closest,
                note);
      std::snprintf(note, sizeof note, "%.1f %% blocked, %zu differ", 100.0 * blocked_count / count,
                    blocked_differ);
      print_row("", scene.triangles.size(), "shadow", occluded, note);
    }
    std::printf(
        "ratio = OpenCL rays/s / Embree rays/s on the same rays and host threads, per run; "
        "OpenCL times include writing the rays to the device and reading the results back\n");
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_traversal: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
