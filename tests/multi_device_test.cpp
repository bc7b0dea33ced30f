// Several devices in one process (render/render_job.h): `--device 0,0` — the same device twice,
// two queues — must give the one-device image bit for bit, for every integrator, as passes (or
// photon mapping's chunks of photons) are handed out to whichever device comes free and added
// up in a fixed order.
#include <gtest/gtest.h>

#include <cstring>

#include "core/error.h"
#include "opencl/device_list.h"
#include "render/record_bytes.h"
#include "render/render_job.h"
#include "test_support.h"

using namespace kasha;

namespace {

struct Rendered {
  Image image;
  PassCounters counters;
};

Rendered render_on(const std::vector<int>& devices, const std::string& scene_path,
                   const std::string& integrator, IntegratorSettings settings, int passes,
                   int size = 32) {
  Scene scene = load_scene(scene_path);
  scene.camera.width = scene.camera.height = size;
  DeviceSet set(devices);
  RenderJob job(set.upload(scene), scene, integrator, settings, /*spectral*/ true);
  RenderOptions options;
  options.stop.passes = passes;
  options.show_progress = false;
  RenderSummary summary = job.run(options);
  EXPECT_EQ(summary.passes, passes);
  return {job.film().image(), job.film().counters()};
}

void expect_same_bits(const Image& a, const Image& b) {
  ASSERT_EQ(a.xyz.size(), b.xyz.size());
  ASSERT_EQ(a.spectral.size(), b.spectral.size());
  double sum = 0;
  for (float v : a.xyz) sum += v;
  EXPECT_GT(sum, 0) << "a black image proves nothing";
  EXPECT_EQ(std::memcmp(a.xyz.data(), b.xyz.data(), a.xyz.size() * sizeof(float)), 0);
  EXPECT_EQ(std::memcmp(a.spectral.data(), b.spectral.data(), a.spectral.size() * sizeof(float)),
            0);
  size_t differ = 0;
  for (size_t i = 0; i < a.spectral.size(); ++i) differ += a.spectral[i] != b.spectral[i];
  EXPECT_EQ(differ, 0u) << "of " << a.spectral.size() << " values";
}

}  // namespace

class TwoQueues : public ::testing::TestWithParam<std::string> {};

TEST_P(TwoQueues, GiveTheOneDeviceImageBitForBit) {
  const std::string integrator = GetParam();
  IntegratorSettings s;
  s.photons = 40000;
  s.spp = 4;
  const int passes = 4;
  const std::string scene = test::source_path("scenes/cornell_box.json");
  Rendered one = render_on({0}, scene, integrator, s, passes);
  Rendered two = render_on({0, 0}, scene, integrator, s, passes);
  expect_same_bits(one.image, two.image);
  // Both queues took part: their work adds up to the whole.
  const double whole = integrator == "photon" ? double(s.photons) * passes : double(passes);
  EXPECT_DOUBLE_EQ(two.counters.work_of(0) + two.counters.work_of(1), whole);
}

INSTANTIATE_TEST_SUITE_P(EveryIntegrator, TwoQueues,
                         ::testing::ValuesIn(IntegratorRegistry::names(false)),
                         [](const auto& info) { return info.param; });

// Photon mapping's chunks: several a pass in a store so small, and photon paths so long (a
// furnace of albedo 0.95 stores ~20 records a photon), that chunks overflow and are traced again
// in halves; and the host's gather — each the same twice on one queue and on three.
TEST(TwoQueues, PhotonMappingChunksSplitsAndHostGatherAreDeterministic) {
  const std::string path = test::write_file("furnace_095.json",
                                            R"({"kasha_scene": 1,
  "camera": {"position": [0.2, -0.1, 0.3], "look_at": [1, 0.3, -0.5], "fov_deg": 60, "width": 24, "height": 24},
  "materials": {"white": {"passive": {"reflectance": 0.95}}},
  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 2, "material": "white", "inward": true,
              "emission": {"blackbody_K": 5000, "scale": 1}}]})");
  Scene scene = load_scene(path);
  for (Gather gather : {Gather::device, Gather::host}) {
    SCOPED_TRACE("--gather " + choice_name(gather));
    IntegratorSettings s;
    s.photons = 8000;
    s.spp = 2;
    s.gather = gather;
    s.memory = 8000 * (photon_record_bytes(scene) + 8);
    Rendered one = render_on({0}, path, "photon", s, 3, 24);
    Rendered again = render_on({0}, path, "photon", s, 3, 24);
    Rendered three = render_on({0, 0, 0}, path, "photon", s, 3, 24);
    expect_same_bits(one.image, again.image);
    expect_same_bits(one.image, three.image);
    EXPECT_GT(one.counters.photon_store_overflows, 0) << "chunks were traced again in halves";
  }
}

TEST(DeviceList, ParsesIndicesListsAndAll) {
  EXPECT_EQ(parse_device_list("0"), std::vector<int>({0}));
  EXPECT_EQ(parse_device_list("0,0"), std::vector<int>({0, 0}));
  EXPECT_EQ(parse_device_list("all").size(), list_devices().size());
  for (const char* bad : {"", "0,", ",0", "a", "-1", "0,,0", "1e3"}) {
    std::string msg = test::error_of([&] { parse_device_list(bad); });
    EXPECT_EQ(msg.rfind(std::string("--device ") + bad + ": ", 0), 0u) << bad << ": " << msg;
    EXPECT_NE(msg.find("device index"), std::string::npos) << bad << ": " << msg;
  }
  std::string msg = test::error_of([] { parse_device_list("0,99"); });
  EXPECT_NE(msg.find("--device 0,99: no such OpenCL device 99"), std::string::npos) << msg;
}
