// The forward integrator (light tracing): its power bookkeeping and a film that does not depend
// on how work is split (its furnace and agreement tests are in integrator_*_test.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "render_support.h"
#include "study/furnace.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;

TEST(Forward, PowerIsConservedInAClosedScene) {
  // Photons cut after 3 bounces: absorbed (what hits took away, roulette included) + escaped +
  // still in flight = emitted exactly. Next to nothing escapes a closed scene: a photon in about
  // 10^5 slips through the float cracks of a tessellated sphere (issue 12's ray offsets).
  RenderSettings s;
  s.integrator = "forward";
  s.passes = 2;
  s.integrator_settings.photons = 100000;
  s.integrator_settings.max_depth = 3;
  for (const char* scene : {"furnace_fluorescent.json", "furnace_mirror.json", "furnace_uv.json"}) {
    RenderResult r = render_scene(source_path(std::string("scenes/") + scene), s);
    const double emitted = r.tallies.at("power emitted (W)"),
                 absorbed = r.tallies.at("power absorbed (W)"),
                 escaped = r.tallies.at("power escaped (W)"),
                 in_flight = r.tallies.at("power in flight (W)");
    EXPECT_NEAR(absorbed + escaped + in_flight, emitted, 1e-5 * emitted) << scene;
    EXPECT_LT(escaped, 1e-5 * emitted) << scene;
    EXPECT_GT(in_flight, 0.05 * emitted) << scene;  // the cut leaves photons in flight
    // A pass's photons carry the lights' total power.
    KernelSceneData data(r.scene);
    EXPECT_NEAR(emitted, 2 * data.total_power, 1e-4 * data.total_power) << scene;
  }
}

TEST(Forward, ImageDoesNotDependOnHowWorkIsSplit) {
  // The same photons spread over work items of 64, 7 and 1 photons: each photon's random numbers
  // depend on its index only and the fixed-point film adds exactly, so the images are identical.
  RenderSettings a;
  a.integrator = "forward";
  a.spectral = false;
  a.passes = 1;
  a.integrator_settings.photons = 40000;
  std::vector<float> reference;
  for (int per_item : {64, 7, 1}) {
    a.integrator_settings.photons_per_item = per_item;
    RenderResult r = render_scene(source_path("scenes/furnace_fluorescent.json"), a);
    if (reference.empty()) reference = r.image.xyz;
    EXPECT_EQ(r.image.xyz, reference) << per_item << " photons per work item";
  }
}
