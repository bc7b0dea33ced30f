// A fuzz harness over kasha's inputs: mutated scene JSON, material files, spectrum CSVs, OBJ
// meshes and reference EXRs (from the shipped ones), loaded the way `kasha info` and `render`
// load them. Every case must either load or fail with one kasha::Error line — no other
// exception, crash or hang; scenes that load are also rendered at 8×8 for one pass by a physical
// integrator, and the image must be finite. A handful go through the binary, which must exit 0
// or 1 with at most one `kasha: error:` line. The cases are drawn from a fixed seed;
// KASHA_FUZZ_CASES sets how many (CI runs more of them in the sanitizer build, scripts/test.sh).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/printable.h"
#include "image/exr_io.h"
#include "render/device_scene.h"
#include "render/render_job.h"
#include "scene/scene.h"
#include "test_support.h"

using namespace kasha;
using namespace kasha::test;
namespace fs = std::filesystem;

namespace {

int fuzz_cases(int fallback) {
  const char* n = std::getenv("KASHA_FUZZ_CASES");
  return n ? std::max(1, std::atoi(n)) : fallback;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

// Values a mutated number becomes: beyond float and double, non-finite spellings, signs, zero,
// huge integers and exponents at the edges of what the loaders accept.
const std::vector<std::string> kNumbers = {
    "0",          "-0",          "-1",   "1e400",       "-1e400",    "1e38",
    "3.5e38",     "1e-45",       "1e30", "1e31",        "1e18",      "1e19",
    "nan",        "inf",         "-inf", "NaN",         "1e-300",    "2147483647",
    "4294967297", "-2147483649", "1e9",  "0.999999999", "1.0000001", "00012",
    "1.",         ".5",          "0x10", "1e",          "--1",       "1e+308"};

// One text mutation: a number replaced, a span deleted or duplicated, a byte flipped or an odd
// token inserted, or the text cut short.
std::string mutate(std::string text, std::mt19937& rng) {
  auto pick = [&](size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng); };
  const int kinds = 6;
  switch (pick(kinds)) {
    case 0: {  // a number token
      std::vector<std::pair<size_t, size_t>> numbers;
      for (size_t i = 0; i < text.size();) {
        if ((std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '-') &&
            (i == 0 || !std::isalnum(static_cast<unsigned char>(text[i - 1])))) {
          size_t j = i + 1;
          while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) ||
                                     text[j] == '.' || text[j] == '-' || text[j] == '+'))
            ++j;
          numbers.emplace_back(i, j - i);
          i = j;
        } else {
          ++i;
        }
      }
      if (numbers.empty()) return text;
      auto [at, len] = numbers[pick(numbers.size())];
      return text.replace(at, len, kNumbers[pick(kNumbers.size())]);
    }
    case 1: {  // delete a span
      if (text.empty()) return text;
      size_t at = pick(text.size()), len = 1 + pick(std::min<size_t>(64, text.size() - at));
      return text.erase(at, len);
    }
    case 2: {  // duplicate a span
      if (text.empty()) return text;
      size_t at = pick(text.size()), len = 1 + pick(std::min<size_t>(128, text.size() - at));
      return text.insert(at, text.substr(at, len));
    }
    case 3: {  // flip a byte
      if (text.empty()) return text;
      text[pick(text.size())] ^= static_cast<char>(1 << pick(8));
      return text;
    }
    case 4: {  // an odd token
      static const std::vector<std::string> tokens = {"{",        "}",
                                                      "[",        "]",
                                                      ",",        ":",
                                                      "\"\"",     "null",
                                                      "true",     "\"x\": 1,",
                                                      "\x1b[31m", "\r",
                                                      "\n",       std::string("\0", 1),
                                                      "\xff",     "#",
                                                      "v 1",      "f 1 2 99999999999",
                                                      "-1",       "1e400"};
      return text.insert(pick(text.size() + 1), tokens[pick(tokens.size())]);
    }
    default:  // cut short
      return text.substr(0, pick(text.size() + 1));
  }
}

std::string mutated(const std::string& text, std::mt19937& rng) {
  std::string t = text;
  const int rounds = 1 + static_cast<int>(rng() % 3);
  for (int k = 0; k < rounds; ++k) t = mutate(t, rng);
  return t;
}

// A small scene using every kind of input file, on the default grid (so renders share kernels).
const char* const kSeedScene = R"({"kasha_scene": 1,
  "camera": {"position": [0.1, 0.2, -0.6], "look_at": [0, 0, 1], "fov_deg": 70, "width": 8, "height": 8},
  "materials": {
    "paper": {"file": "paper.json"},
    "wall": {"passive": {"reflectance": {"csv": "reflectance.csv", "column": "red"}},
             "gloss": {"reflectance": 0.05, "cone_deg": 12}},
    "lamp": {"passive": {"reflectance": 0.2}}
  },
  "shapes": [
    {"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1.5], "material": "wall", "inward": true},
    {"type": "obj", "file": "mesh.obj", "material": "paper",
     "transform": {"scale": 0.3, "translate": [0, -0.4, 0.6]}},
    {"type": "quad", "corner": [-0.3, 0.99, 0.2], "u": [0.6, 0, 0], "v": [0, 0, 0.6],
     "material": "lamp", "emission": {"csv": "lamp.csv", "scale": 0.02}},
    {"type": "sphere", "center": [0.5, 0.5, 1.0], "radius": 0.2, "material": "paper"}
  ]})";

struct Seeds {
  fs::path dir;
  std::string scene, material, reflectance, lamp, mesh;
};

Seeds make_seeds() {
  Seeds s;
  s.dir = scratch_dir();
  s.scene = kSeedScene;
  s.material = read_text(source_path("scenes/materials/brightened_paper.json"));
  s.reflectance = read_text(source_path("scenes/data/ColorChecker24_Ohta1997_380_780_5nm.csv"));
  s.lamp = read_text(source_path("scenes/data/CIE_D65_300_780.csv"));
  s.mesh = read_text(source_path("scenes/meshes/torus.obj"));
  return s;
}

// Writes the case's files (one of them mutated) and returns the scene's path.
std::string write_case(const Seeds& s, int which, std::mt19937& rng) {
  write_text(s.dir / "paper.json", which == 1 ? mutated(s.material, rng) : s.material);
  write_text(s.dir / "reflectance.csv", which == 2 ? mutated(s.reflectance, rng) : s.reflectance);
  write_text(s.dir / "lamp.csv", which == 3 ? mutated(s.lamp, rng) : s.lamp);
  write_text(s.dir / "mesh.obj", which == 4 ? mutated(s.mesh, rng) : s.mesh);
  const fs::path scene = s.dir / "scene.json";
  write_text(scene, which == 0 ? mutated(s.scene, rng) : s.scene);
  return scene.string();
}

// One printable line: no control bytes (input is escaped when echoed) and valid UTF-8.
bool one_line(const std::string& message) {
  for (char c : message)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return false;
  return !message.empty() && valid_utf8(message);
}

}  // namespace

TEST(Fuzz, MutatedInputsLoadOrGiveOneLineAndRenderFinite) {
  const Seeds seeds = make_seeds();
  const int cases = fuzz_cases(400);
  std::mt19937 rng(20261201);
  static ClContext cl(0);
  const Scene reference = load_scene(write_case(seeds, -1, rng));
  const std::vector<std::string> integrators = IntegratorRegistry::names(true);
  int loaded = 0, refused = 0, rendered = 0;
  for (int c = 0; c < cases; ++c) {
    const int which = c % 5;  // scene, material, reflectance CSV, lamp CSV, OBJ
    const std::string path = write_case(seeds, which, rng);
    SCOPED_TRACE("case " + std::to_string(c) + ", input " + std::to_string(which));
    try {
      Scene scene = load_scene(path);
      ++loaded;
      // Every fourth scene that loads on the seed's grid (so kernels are shared) is rendered.
      if (c % 4 != 0 || scene.grid.bins != reference.grid.bins ||
          scene.grid.min_nm != reference.grid.min_nm ||
          scene.camera.width * scene.camera.height > 64)
        continue;
      IntegratorSettings settings;
      settings.spp = 1;
      settings.photons = 2048;
      settings.seed = static_cast<unsigned>(c);
      const std::string& integrator = integrators[(c / 4) % integrators.size()];
      try {
        DeviceScene device_scene(cl, scene);
        RenderJob job(cl, scene, device_scene, integrator, settings, false);
        job.pass(0);
        Image image = job.film().image();
        for (float v : image.xyz)
          ASSERT_TRUE(std::isfinite(v)) << integrator << " wrote a non-finite pixel";
        ++rendered;
      } catch (const Error& e) {
        EXPECT_TRUE(one_line(e.what())) << e.what();  // e.g. no emitter with power left
      }
    } catch (const Error& e) {
      ++refused;
      EXPECT_TRUE(one_line(e.what())) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a kasha::Error: " << e.what() << "\n" << read_text(path);
    }
  }
  std::printf("  %d cases: %d loaded (%d rendered), %d refused with one line\n", cases, loaded,
              rendered, refused);
  EXPECT_GT(loaded, 0);
  EXPECT_GT(refused, 0);
}

TEST(Fuzz, MutatedReferenceExrsReadOrGiveOneLine) {
  const fs::path dir = scratch_dir();
  Image img;
  img.width = 4;
  img.height = 3;
  img.grid = load_scene(source_path("scenes/furnace_passive.json")).grid;
  img.xyz.assign(3 * 12, 0.25f);
  img.spectral.assign(12 * img.grid.bins, 0.5f);
  const fs::path seed = dir / "seed.exr";
  write_exr(seed.string(), img);
  const std::string bytes = read_text(seed);
  std::mt19937 rng(7);
  const int cases = fuzz_cases(400) / 2;
  int read = 0, refused = 0;
  for (int c = 0; c < cases; ++c) {
    std::string b = bytes;
    // Binary mutations: flipped bytes and cut-short files (text mutations mean little here).
    const int flips = 1 + static_cast<int>(rng() % 8);
    for (int k = 0; k < flips; ++k) b[rng() % b.size()] ^= static_cast<char>(1 << (rng() % 8));
    if (rng() % 4 == 0) b.resize(rng() % b.size());
    const fs::path p = dir / "mutated.exr";
    write_text(p, b);
    try {
      Image r = read_exr(p.string());
      ++read;
    } catch (const Error& e) {
      ++refused;
      EXPECT_TRUE(one_line(e.what())) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "case " << c << ": not a kasha::Error: " << e.what();
    }
  }
  std::printf("  %d EXRs: %d read, %d refused with one line\n", cases, read, refused);
  EXPECT_GT(refused, 0);
}

TEST(Fuzz, TheBinaryExitsZeroOrOneWithAtMostOneErrorLine) {
  const Seeds seeds = make_seeds();
  std::mt19937 rng(99);
  const int cases = std::max(8, fuzz_cases(400) / 20);
  for (int c = 0; c < cases; ++c) {
    const std::string path = write_case(seeds, c % 5, rng);
    CommandResult r = run_kasha("info '" + path + "'");
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1)
        << "case " << c << ": exit " << r.exit_code << "\n"
        << r.err;
    if (r.exit_code != 0) {
      EXPECT_EQ(r.err.rfind("kasha: error: ", 0), 0u) << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_TRUE(one_line(r.err.substr(0, r.err.size() - 1))) << r.err;
    }
  }
}
