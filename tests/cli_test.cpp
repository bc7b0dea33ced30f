// The command line end to end: bad input gives one clear line, a non-zero exit and no output;
// good input writes whole files; Ctrl-C writes the image so far.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "image/exr_io.h"
#include "test_support.h"

using namespace kasha;
using test::run_kasha;

namespace {

using test::shell_quoted;

void expect_one_line_error(const test::CommandResult& r, const std::string& expected) {
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace

TEST(Cli, RenderWritesExrAndPng) {
  std::string exr = (test::scratch_dir() / "c.exr").string(),
              png = (test::scratch_dir() / "c.png").string();
  auto r = run_kasha("render " + shell_quoted(test::source_path("scenes/cornell_box.json")) +
                     " --integrator debug --view albedo --passes 2 --spp 1 -o " +
                     shell_quoted(exr) + " --png " + shell_quoted(png));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Image img = read_exr(exr);
  EXPECT_EQ(img.width, 256);
  std::ifstream in(png, std::ios::binary);
  char sig[8] = {};
  in.read(sig, 8);
  EXPECT_EQ(std::string(sig + 1, 3), "PNG");
}

// `--device 0,0` (one device, two queues) writes the `--device 0` EXR byte for byte: photon
// mapping shares each pass's photons between them.
TEST(Cli, RenderOnTwoQueuesWritesTheOneDeviceFile) {
  const std::string scene = shell_quoted(test::source_path("scenes/cornell_box.json"));
  std::string files[2];
  for (int k = 0; k < 2; ++k) {
    files[k] = (test::scratch_dir() / ("device" + std::to_string(k) + ".exr")).string();
    auto r = run_kasha("render " + scene +
                       " --integrator photon --passes 2 --photons 70000 --spp 2 --device " +
                       (k ? "0,0" : "0") + " -o " + shell_quoted(files[k]));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    if (k) {
      EXPECT_NE(r.err.find("work per device: 0 ("), std::string::npos) << r.err;
    }
  }
  auto bytes = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_GT(bytes(files[0]).size(), 1000u);
  EXPECT_TRUE(bytes(files[0]) == bytes(files[1]));
}

TEST(Cli, LogHasARowPerPassWithErrorsAgainstAReference) {
  std::string scene = shell_quoted(test::source_path("scenes/torus.json"));
  std::string ref = (test::scratch_dir() / "ref.exr").string(),
              out = (test::scratch_dir() / "o.exr").string();
  std::string log = (test::scratch_dir() / "log.csv").string();
  ASSERT_EQ(run_kasha("render " + scene + " --passes 1 --photons 65536 -o " + shell_quoted(ref))
                .exit_code,
            0);
  auto r = run_kasha(
      "render " + scene + " --integrator photon --passes 3 --photons 4096 --seed 9 -o " +
      shell_quoted(out) + " --reference " + shell_quoted(ref) + " --log " + shell_quoted(log));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(log);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "integrator,pass,seconds,camera_paths,photons,rmse,relmse");
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    EXPECT_EQ(line.rfind("photon," + std::to_string(rows) + ",", 0), 0u) << line;
    EXPECT_NE(line.back(), ',') << "error columns must be filled: " << line;
  }
  EXPECT_EQ(rows, 3);
}

TEST(Cli, BadInputsGiveOneLineAndNoOutput) {
  std::string out = (test::scratch_dir() / "out.exr").string();
  std::string bad_json = test::write_file("bad.json", "{\"kasha_scene\": 1,");
  expect_one_line_error(
      run_kasha("render " + shell_quoted(bad_json) + " --passes 1 -o " + shell_quoted(out)),
      "bad.json: malformed JSON at line 1");
  expect_one_line_error(run_kasha("render /nonexistent.json --passes 1 -o " + shell_quoted(out)),
                        "/nonexistent.json: cannot open file");
  std::string gain = test::write_file("gain.json", R"({"kasha_scene": 1,
    "camera": {"position": [0,0,-3], "look_at": [0,0,0]},
    "materials": {"hot": {"passive": {"reflectance": 0.7}, "gloss": {"reflectance": 0.4, "mirror": true}}},
    "shapes": [{"type": "sphere", "center": [0,0,0], "radius": 1, "material": "hot"}]})");
  expect_one_line_error(
      run_kasha("render " + shell_quoted(gain) + " --passes 1 -o " + shell_quoted(out)),
      "material 'hot' (");
  expect_one_line_error(
      run_kasha("render " + shell_quoted(gain) + " --passes 1 -o " + shell_quoted(out)),
      "energy gain at 385 nm");
  std::string scene = shell_quoted(test::source_path("scenes/torus.json"));
  expect_one_line_error(run_kasha("render " + scene + " --passes 1 -o /nonexistent/dir/x.exr"),
                        "directory /nonexistent/dir does not exist");
  expect_one_line_error(
      run_kasha("render " + scene + " --passes 1 --view normals -o " + shell_quoted(out)),
      "--view: the vcm integrator does not take this option");
  expect_one_line_error(
      run_kasha("render " + scene + " --integrator backward --alpha 0.5 --passes 1 -o " +
                shell_quoted(out)),
      "--alpha: the backward integrator does not take this option (it takes --spp)");
  expect_one_line_error(
      run_kasha("render " + scene + " --integrator forward --gather host --passes 1 -o " +
                shell_quoted(out)),
      "--gather: the forward integrator does not take this option");
  expect_one_line_error(
      run_kasha("render " + scene + " --integrator debug --passes 1 --view normals --spectral -o " +
                shell_quoted(out)),
      "the normals view has no spectrum");
  expect_one_line_error(
      run_kasha("render " + scene + " --passes 1 --reference furnace -o " + shell_quoted(out)),
      "--reference furnace: " + test::source_path("scenes/torus.json") +
          " is not an analytic furnace: ");
  expect_one_line_error(run_kasha("render " + scene + " -o " + shell_quoted(out)),
                        "give --time SECONDS or --passes N");
  expect_one_line_error(
      run_kasha("render " + scene + " --passes 1 --device 42 -o " + shell_quoted(out)),
      "--device 42: no such OpenCL device");
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Cli, NoOpenClDeviceSaysHowToInstallPocl) {
  std::string out = (test::scratch_dir() / "out.exr").string();
  auto r = run_kasha("devices");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("0: "), std::string::npos);
  std::string empty = (test::scratch_dir() / "no-vendors").string();
  std::filesystem::create_directories(empty);
  r = test::run_kasha_env("OCL_ICD_VENDORS=" + shell_quoted(empty),
                          "render " + shell_quoted(test::source_path("scenes/torus.json")) +
                              " --passes 1 -o " + shell_quoted(out));
  expect_one_line_error(r, "no OpenCL device found");
  EXPECT_NE(r.err.find("pocl-opencl-icd"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Cli, InfoReportsGridFeaturesOptionsAndMemory) {
  auto r = run_kasha("info " + shell_quoted(test::source_path("scenes/cornell_box.json")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* s : {"wavelengths: 300–780 nm, 48 bins of 10 nm", "fluorescence yes",
                        "-D KASHA_BINS=48", "-D KASHA_FLUORESCENCE=1",
                        "memory: ", "photon mapping: 224 bytes per photon (position, normal, key",
                        "428 bytes per visible point", "2N + R = 99 values"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s << "\n" << r.out;
  // --bin-nm replaces the scene's bin width; the range stays what its spectra need.
  r = run_kasha("info " + shell_quoted(test::source_path("scenes/cornell_box.json")) +
                " --bin-nm 5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("wavelengths: 300–780 nm, 96 bins of 5 nm"), std::string::npos) << r.out;
  expect_one_line_error(
      run_kasha("info " + shell_quoted(test::source_path("scenes/cornell_box.json")) +
                " --bin-nm 0.01"),
      "--bin-nm: 0.01 is not in [0.1, 1000]");
}

TEST(Cli, CtrlCWritesTheImageSoFar) {
  std::string out = (test::scratch_dir() / "i.exr").string();
  auto r = test::run_kasha_env("",
                               "render " + shell_quoted(test::source_path("scenes/torus.json")) +
                                   " --time 120 --photons 4096 -o " + shell_quoted(out),
                               /*interrupt_after_s=*/3);
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_NE(r.err.find("interrupted: writing the image after"), std::string::npos) << r.err;
  Image img = read_exr(out);
  EXPECT_EQ(img.width, 192);
}

TEST(Cli, CompareReportsErrorsWithAndWithoutTheLampPixels) {
  std::string scene = test::source_path("scenes/cornell_classic.json");
  std::string a = (test::scratch_dir() / "a.exr").string(),
              b = (test::scratch_dir() / "b.exr").string();
  ASSERT_EQ(run_kasha("render " + shell_quoted(scene) +
                      " --integrator debug --passes 1 --spp 1 -o " + shell_quoted(a))
                .exit_code,
            0);
  ASSERT_EQ(run_kasha("render " + shell_quoted(scene) +
                      " --integrator debug --passes 1 --spp 1 --seed 2 -o " + shell_quoted(b))
                .exit_code,
            0);
  auto same = run_kasha("compare " + shell_quoted(a) + " " + shell_quoted(a) + " --scene " +
                        shell_quoted(scene));
  ASSERT_EQ(same.exit_code, 0) << same.err;
  EXPECT_EQ(same.out,
            "rmse 0 relmse 0 | without the 612 pixels that see an emitter: rmse 0 relmse 0\n");
  // Two emission views differ only at the lamp's edges: the error is nearly all in its pixels.
  auto other = run_kasha("compare " + shell_quoted(a) + " " + shell_quoted(b) + " --scene " +
                         shell_quoted(scene));
  ASSERT_EQ(other.exit_code, 0) << other.err;
  double all = -1, rel = -1, rest = -1, rest_rel = -1;
  int lamp = 0;
  ASSERT_EQ(
      std::sscanf(
          other.out.c_str(),
          "rmse %lf relmse %lf | without the %d pixels that see an emitter: rmse %lf relmse %lf",
          &all, &rel, &lamp, &rest, &rest_rel),
      5)
      << other.out;
  EXPECT_EQ(lamp, 612);
  EXPECT_GT(all, 0);
  EXPECT_LT(rest, 0.05 * all) << other.out;
  // Block means: the two differ at scattered edge pixels, which 8 x 8 averaging mostly cancels.
  auto blocks = run_kasha("compare " + shell_quoted(a) + " " + shell_quoted(b) + " --block 8");
  ASSERT_EQ(blocks.exit_code, 0) << blocks.err;
  double block_rmse = -1, block_rel = -1, all2 = -1, rel2 = -1;
  ASSERT_EQ(
      std::sscanf(blocks.out.c_str(), "rmse %lf relmse %lf | 8x8 block means: rmse %lf relmse %lf",
                  &all2, &rel2, &block_rmse, &block_rel),
      4)
      << blocks.out;
  EXPECT_EQ(all2, all);
  EXPECT_GT(block_rmse, 0);
  EXPECT_LT(block_rmse, 0.5 * all) << blocks.out;
  expect_one_line_error(
      run_kasha("compare " + shell_quoted(a) + " " + shell_quoted(a) + " --scene " +
                shell_quoted(test::source_path("scenes/torus.json"))),
      "its camera is");
}

TEST(Cli, EveryPhysicalIntegratorRefusesASceneWithoutLight) {
  // The only emitter's line lies below the grid: the same one line from each physical integrator,
  // and nothing written (the debug views still render).
  std::string scene = test::write_file("dark.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0], "width": 8, "height": 8},
    "materials": {"grey": {"passive": {"reflectance": 0.5}}},
    "shapes": [{"type": "quad", "corner": [-1, -1, 0], "u": [2, 0, 0], "v": [0, 2, 0],
                "material": "grey", "emission": {"line_nm": 150}}]})");
  std::string out = (test::scratch_dir() / "dark.exr").string();
  for (const char* integrator : {"backward", "forward", "photon"}) {
    expect_one_line_error(run_kasha("render " + shell_quoted(scene) + " --integrator " +
                                    integrator + " --passes 1 -o " + shell_quoted(out)),
                          "no emitter has power on the wavelength grid");
    EXPECT_FALSE(std::filesystem::exists(out)) << integrator;
  }
  EXPECT_EQ(run_kasha("render " + shell_quoted(scene) + " --integrator debug --passes 1 -o " +
                      shell_quoted(out))
                .exit_code,
            0);
}

TEST(Cli, RenderWarnsWhenTheDepthGuardCutsPaths) {
  // A furnace that keeps 99.99 % of its light: paths outlive a guard of --depth-guard 1000, which
  // biases the image, and each integrator says how much weight the guard cut. Roulette keeps a
  // path's expected weight, so after the guard's 1000 scatterings it is ρ^1000 = 0.9048 of the
  // start: each path carries about 0 or 1, so the share has a binomial error over the paths traced.
  std::string scene = test::write_file("stiff.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, 0], "look_at": [1, 0, 0], "fov_deg": 60, "width": 4, "height": 4},
    "materials": {"white": {"passive": {"reflectance": 0.9999}}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white",
                "inward": true, "emission": "E"}]})");
  std::string out = (test::scratch_dir() / "stiff.exr").string();
  const double expected = std::pow(0.9999, 1000);
  const std::pair<const char*, double> runs[] = {{"--integrator backward --spp 64", 16 * 64},
                                                 {"--integrator forward --photons 1000", 1000},
                                                 {"--integrator photon --photons 200", 200}};
  for (const auto& [options, paths] : runs) {
    auto r = run_kasha("render " + shell_quoted(scene) + " " + options +
                       " --depth-guard 1000 --passes 1 -o " + shell_quoted(out));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const std::string lead =
        "kasha: warning: paths reaching the 1000-vertex depth guard were cut "
        "still carrying ";
    const size_t at = r.err.find(lead);
    ASSERT_NE(at, std::string::npos) << options << "\n" << r.err;
    const double share = std::atof(r.err.c_str() + at + lead.size());
    const double sigma = std::sqrt(expected * (1 - expected) / paths);
    std::printf("  %s: cut share %.4f, expected %.4f ± %.4f\n", options, share, expected, sigma);
    EXPECT_NEAR(share, expected, 4 * sigma + 0.005) << options;
  }
  auto plain =
      run_kasha("render " + shell_quoted(test::source_path("scenes/furnace_fluorescent.json")) +
                " --integrator backward --spp 2 --passes 1 -o " + shell_quoted(out));
  EXPECT_EQ(plain.err.find("depth guard"), std::string::npos) << plain.err;
}
