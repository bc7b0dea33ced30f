// A fuzz harness over kasha's inputs: mutated scene JSON (lights included), material files,
// spectrum CSVs, environment PNGs, OBJ and PLY meshes (PLY also gzip-compressed) and reference
// EXRs (from the shipped ones), loaded
// the way `kasha info` and `render` load them. Every case must either load or fail with one
// kasha::Error line — no other exception, crash or hang; scenes that load are also rendered at 8×8
// for one pass by a physical integrator, and the image must be finite. A handful go through the
// binary, which must exit 0 or 1 with at most one `kasha: error:` line. The cases are drawn from a
// fixed seed; KASHA_FUZZ_CASES sets how many (CI runs more of them in the sanitizer build,
// scripts/test.sh). Below them, the commands colorimetry, regions, compare, preview and delta-e are
// fuzzed in process against the whole contract of docs/commands.md#errors-and-exit-codes.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <qoi.h>
#include <signal.h>
#include <stb_image_write.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli/command_line.h"
#include "core/gzip_input.h"
#include "core/printable.h"
#include "image/exr_io.h"
#include "image/png_preview.h"
#include "image/rgb_image.h"
#include "mesh_writers.h"
#include "render/device_scene.h"
#include "render/render_job.h"
#include "scene/ply_mesh.h"
#include "scene/scene.h"
#include "test_support.h"
#include "vdb_writer.h"

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/common_interface_defs.h>
#define KASHA_FUZZ_SANITIZED 1  // ASan and UBSan call a death callback after their report
#endif

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
    "paper": {"file": "paper.json", "textures": {"reflectance": "print", "fluorescence": "ink"}},
    "wall": {"passive": {"reflectance": {"csv": "reflectance.csv", "column": "red"}},
             "gloss": {"reflectance": 0.05, "cone_deg": 12}},
    "lamp": {"passive": {"reflectance": 0.2}, "coat": {"eta": 1.4, "thickness": 0.02, "roughness": 0.1}},
    "lacquer": {"passive": {"reflectance": 0.6}, "coat": {}},
    "glass": {"dielectric": {"eta": {"sellmeier": {"B": [1.04, 0.23, 1.01], "C_um2": [0.006, 0.02, 103.6]}},
                             "roughness": 0.05}},
    "metal": {"conductor": {"eta": {"nm": [200, 900], "value": [0.2, 0.3]}, "k": 3, "uroughness": 0.1,
                            "vroughness": 0.3}}
  },
  "shapes": [
    {"type": "box", "min": [-1, -1, -1], "max": [1, 1, 1.5], "material": "wall", "inward": true},
    {"type": "obj", "file": "mesh.obj", "material": "paper",
     "transform": {"scale": 0.3, "translate": [0, -0.4, 0.6]}},
    {"type": "quad", "corner": [-0.3, 0.99, 0.2], "u": [0.6, 0, 0], "v": [0, 0, 0.6],
     "material": "lamp", "emission": {"csv": "lamp.csv", "scale": 0.02}},
    {"type": "sphere", "center": [0.5, 0.5, 1.0], "radius": 0.2, "material": "paper"},
    {"type": "sphere", "center": [-0.5, -0.6, 0.9], "radius": 0.2, "segments": 12, "material": "glass",
     "medium": {"inside": "ink", "outside": null}},
    {"type": "sphere", "center": [0, 0.2, 0.8], "radius": 0.15, "segments": 8, "interface": true,
     "medium": {"inside": "haze"}},
    {"type": "box", "min": [0.15, 0.1, 0.3], "max": [0.45, 0.5, 0.7], "interface": true,
     "medium": {"inside": "smoke"}},
    {"type": "box", "min": [-0.7, 0.3, 0.9], "max": [-0.3, 0.7, 1.3], "interface": true,
     "medium": {"inside": "cloud"}},
    {"type": "box", "min": [-0.2, 0.6, 1.2], "max": [0.1, 0.9, 1.5], "interface": true,
     "medium": {"inside": "puff"}},
    {"type": "box", "min": [0.5, 0.6, 0.2], "max": [0.8, 0.9, 0.5], "interface": true,
     "medium": {"inside": "tint"}},
    {"type": "box", "min": [0.4, -1, 0.2], "max": [0.7, -0.7, 0.5], "material": "metal"},
    {"type": "box", "min": [-0.8, -1, 1.1], "max": [-0.5, -0.8, 1.4], "material": "lacquer"},
    {"type": "mesh", "file": "mesh.ply", "material": "lacquer", "transform": {"scale": 0.2, "translate": [0.2, -0.9, 0.3]}},
    {"type": "mesh", "file": "mesh.glb", "material": "wall", "transform": {"scale": 0.2, "translate": [-0.4, -0.9, 0.3]}}
  ],
  "media": {
    "ink": {"type": "homogeneous", "sigma_a": {"nm": [380, 780], "value": [4, 0.5]}, "sigma_s": 0, "scale": 2},
    "haze": {"sigma_a": 0.3, "sigma_s": 0, "g": 0.2},
    "smoke": {"type": "grid", "sigma_a": 0.2, "sigma_s": 3, "g": 0.4,
              "density": {"size": [2, 3, 2], "values": [0, 1, 2, 0.5, 1, 0, 3, 1, 0.2, 0.7, 1.5, 0]},
              "bounds": {"min": [-0.2, -0.2, -0.2], "max": [0.2, 0.2, 0.2]},
              "transform": {"rotate": {"axis": [0, 1, 0], "deg": 30}, "translate": [0.3, 0.3, 0.5]}},
    "cloud": {"type": "grid", "sigma_a": 0.5, "sigma_s": 4, "density": {"vdb": "grid.vdb"},
              "transform": {"translate": [-0.5, 0.5, 1.1]}},
    "tint": {"type": "rgbgrid", "size": [2, 1, 2], "scale": 3, "g": -0.2,
             "sigma_a": {"rgb_values": [1, 0.2, 0.1, 0, 0, 0, 0.5, 0.1, 0.05, 0.2, 0.4, 1]},
             "sigma_s": {"rgb_values": [0.5, 0.5, 0.5, 1, 1, 1, 0.2, 0.2, 0.2, 0.1, 0.3, 0.9]},
             "emission": {"rgb_values": [2, 1, 0.5, 0, 0, 0, 1, 1, 1, 0.3, 0.6, 2]}, "emission_scale": 0.5,
             "bounds": {"min": [0.5, 0.6, 0.2], "max": [0.8, 0.9, 0.5]}},
    "puff": {"type": "grid", "sigma_a": 0.3, "sigma_s": 2, "density": {"vdb": "grid.nvdb"},
             "transform": {"translate": [-0.05, 0.75, 1.35]}},
    "ember": {"type": "grid", "sigma_a": 2, "sigma_s": 0.1, "density": {"vdb": "grid.nvdb"},
              "temperature": {"vdb": "grid.nvdb", "grid": "density"}, "temperature_scale": 2000,
              "temperature_offset": 0.1, "emission_scale": {"values": [
              1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2,
              0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1,
              2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5,
              1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2, 0.5, 1, 2,
              0.5, 1, 2, 0.5, 1, 2, 0.5, 1]}},
    "glow": {"sigma_a": 0.01, "sigma_s": 0.5, "fluorophores": [
      {"absorption": {"nm": [380, 480], "value": [2, 0]}, "quantum_yield": 0.9, "emission": {"gaussian_nm": 520, "fwhm_nm": 40}},
      {"molar_absorption": 7e4, "concentration": 1e-6, "unit_cm": 100, "emission": {"line_nm": 610}},
      {"dye": "dye.json", "concentration": 2e-6, "quantum_yield": 0.8}]}
  },
  "textures": {
    "print": {"type": "image", "file": "sky.png", "filter": "bilinear", "wrap": "repeat", "uscale": 2},
    "ink": {"type": "checkerboard", "even": 1, "odd": 0.25, "uscale": 4, "vscale": 4}
  },
  "lights": [
    {"type": "point", "position": [0.2, 0.8, 0.9], "intensity": {"rgb_illuminant": [0.01, 0.02, 0.01]},
     "medium": null},
    {"type": "spot", "from": [-0.5, 0.9, 0.5], "to": [0, -1, 1], "intensity": 0.01, "cone_deg": 25,
     "cone_delta_deg": 5},
    {"type": "distant", "from": [0, 1, 0], "to": [0.1, 0, 0.2], "irradiance": {"rgb": [0.2, 0.5, 0.3]}},
    {"type": "infinite", "image": "sky.png", "mapping": "latlong", "scale": 0.5,
     "transform": {"rotate": {"axis": [1, 0, 0], "deg": -90}}}
  ]})";

struct Seeds {
  fs::path dir;
  std::string scene, material, reflectance, lamp, mesh, sky;  // sky: PNG bytes
  std::string ply, glb;  // binary: a PLY and a GLB mesh (read by Assimp)
  std::string dye, dye_table;  // a dye file (scenes/dyes) and its table
  std::string vdb;             // an OpenVDB file: a small grid of densities
  std::string nvdb;            // the same grid as a zipped NanoVDB file
};

// A binary mutation (a PNG, a VDB): flipped bytes, the 32-bit fields at bytes 16 and 20
// overwritten (a PNG's width and height; a VDB's library version and the start of its header), or
// the file cut short.
std::string mutated_binary(std::string b, std::mt19937& rng) {
  const int kind = static_cast<int>(rng() % 3);
  if (kind == 0) {
    const int flips = 1 + static_cast<int>(rng() % 8);
    for (int k = 0; k < flips; ++k) b[rng() % b.size()] ^= static_cast<char>(1 << (rng() % 8));
  } else if (kind == 1 && b.size() > 24) {
    // IHDR's width and height: big-endian at bytes 16 and 20.
    static const std::vector<uint32_t> values = {0, 1, 0x7fffffff, 0xffffffff, 65536, 1u << 28};
    const uint32_t v = values[rng() % values.size()];
    const size_t at = 16 + 4 * (rng() % 2);
    for (int k = 0; k < 4; ++k) b[at + k] = static_cast<char>(v >> (24 - 8 * k));
  }
  if (kind == 2 || rng() % 10 == 0) b.resize(rng() % b.size());
  return b;
}

// The torus with shading normals: three `vn` (one unnormalized, one zero) named by its faces'
// vertices in turn, so mutations meet `vn` lines and i//n references too.
std::string with_normals(const std::string& obj) {
  std::istringstream in(obj);
  std::ostringstream out;
  out << "vn 0 0 1\nvn 0 2 2\nvn 0 0 0\n";
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("f ", 0) != 0) {
      out << line << "\n";
      continue;
    }
    std::istringstream words(line.substr(2));
    out << "f";
    for (std::string w; words >> w;) out << " " << w << "//" << (std::stol(w) % 3 + 1);
    out << "\n";
  }
  return out.str();
}

Seeds make_seeds() {
  Seeds s;
  s.dir = scratch_dir();
  s.scene = kSeedScene;
  s.material = read_text(source_path("scenes/materials/brightened_paper.json"));
  s.reflectance = read_text(source_path("scenes/data/ColorChecker24_Ohta1997_380_780_5nm.csv"));
  s.lamp = read_text(source_path("scenes/data/CIE_D65_300_780.csv"));
  s.mesh = with_normals(read_text(source_path("scenes/meshes/torus.obj")));
  s.ply = mesh_ply(tent_mesh(), true);
  s.glb = mesh_glb(tent_mesh());
  s.dye = read_text(source_path("scenes/dyes/fluorescein_basic_ethanol.json"));
  for (size_t at; (at = s.dye.find("fluorescein_basic_ethanol.csv")) != std::string::npos;)
    s.dye.replace(at, std::string("fluorescein_basic_ethanol.csv").size(), "dye.csv");
  s.dye_table = read_text(source_path("scenes/dyes/fluorescein_basic_ethanol.csv"));
  TestVdbGrid grid;  // 3 × 2 × 3 voxels of 0.1, about the origin
  grid.origin = {-1, -1, -1};
  grid.size = {3, 2, 3};
  grid.values = {0.5, 1, 2, 0, 3, 1, 0.2, 0.7, 1.5, 0, 1, 2, 0.4, 0.9, 0, 2.5, 1.2, 0.3};
  grid.index_to_world = Eigen::Scaling(0.1);
  write_vdb((s.dir / "seed_grid.vdb").string(), {grid});
  s.vdb = read_text(s.dir / "seed_grid.vdb");
  write_nvdb((s.dir / "seed_grid.nvdb").string(), {grid}, true);
  s.nvdb = read_text(s.dir / "seed_grid.nvdb");
  Image sky;  // a small sky, bright above
  sky.width = 16;
  sky.height = 8;
  for (int y = 0; y < sky.height; ++y)
    for (int x = 0; x < sky.width; ++x)
      for (float v : {0.3f + 0.1f * (8 - y), 0.4f, 0.9f - 0.05f * x}) sky.xyz.push_back(v);
  write_png_preview((s.dir / "seed_sky.png").string(), sky, 1.0);
  s.sky = read_text(s.dir / "seed_sky.png");
  return s;
}

// Writes the case's files (one of them mutated) and returns the scene's path.
std::string write_case(const Seeds& s, int which, std::mt19937& rng) {
  write_text(s.dir / "paper.json", which == 1 ? mutated(s.material, rng) : s.material);
  write_text(s.dir / "reflectance.csv", which == 2 ? mutated(s.reflectance, rng) : s.reflectance);
  write_text(s.dir / "lamp.csv", which == 3 ? mutated(s.lamp, rng) : s.lamp);
  write_text(s.dir / "mesh.obj", which == 4 ? mutated(s.mesh, rng) : s.mesh);
  write_text(s.dir / "sky.png", which == 5 ? mutated_binary(s.sky, rng) : s.sky);
  write_text(s.dir / "mesh.ply", which == 6 ? mutated(s.ply, rng) : s.ply);
  write_text(s.dir / "mesh.glb", which == 7 ? mutated(s.glb, rng) : s.glb);
  write_text(s.dir / "dye.json", which == 8 ? mutated(s.dye, rng) : s.dye);
  write_text(s.dir / "dye.csv", s.dye_table);
  // OpenVDB allocates what a mutated header says (terabytes): a std::bad_alloc, one line here,
  // but AddressSanitizer aborts on it, so scripts/sanitize.sh leaves the grid seeds whole. Input 9
  // is the OpenVDB file or the NanoVDB one, by turns.
  static const bool vdb_whole = std::getenv("KASHA_FUZZ_VDB_WHOLE") != nullptr;
  const bool grids = which == 9 && !vdb_whole, nano = grids && rng() % 2 == 0;
  write_text(s.dir / "grid.vdb", grids && !nano ? mutated_binary(s.vdb, rng) : s.vdb);
  write_text(s.dir / "grid.nvdb", nano ? mutated_binary(s.nvdb, rng) : s.nvdb);
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

// One pass of `integrator` on a scene that loaded, at one sample per pixel: every pixel finite,
// or a kasha::Error of one line (no emitter with power left, say). 1 when it rendered.
int render_one_pass(ClContext& cl, const Scene& scene, const std::string& integrator, int c) {
  IntegratorSettings settings;
  settings.spp = 1;
  settings.photons = 2048;
  settings.seed = static_cast<unsigned>(c);
  try {
    DeviceScene device_scene(cl, scene);
    RenderJob job(cl, scene, device_scene, integrator, settings, false);
    job.pass(0);
    for (float v : job.film().image().xyz) {
      EXPECT_TRUE(std::isfinite(v)) << integrator << " wrote a non-finite pixel";
      if (!std::isfinite(v)) return 0;
    }
    return 1;
  } catch (const Error& e) {
    EXPECT_TRUE(one_line(e.what())) << e.what();
    return 0;
  }
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
    // scene, material, reflectance CSV, lamp CSV, OBJ, PNG, PLY, GLB, dye, VDB or NanoVDB
    const int which = c % 10;
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
      rendered += render_one_pass(cl, scene, integrators[(c / 4) % integrators.size()], c);
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

namespace {

// A pbrt-v4 scene with most of what the importer reads (host/scene/pbrt/), an included file, a
// PLY mesh, a PNG texture and a kasha material file beside it.
const char* kSeedPbrt = R"(# the fuzz seed
LookAt 0 1 3  0 0.5 0  0 1 0
Camera "perspective" "float fov" [45]
Film "rgb" "integer xresolution" [8] "integer yresolution" [8] "string filename" "x.exr"
Sampler "halton" "integer pixelsamples" 4
PixelFilter "triangle" "float xradius" 1.5
WorldBegin
Attribute "shape" "float radius" 0.25
Texture "checks" "spectrum" "checkerboard" "float uscale" 4 "rgb tex1" [0.8 0.7 0.6] "rgb tex2" [0.1 0.2 0.3]
Texture "sky" "spectrum" "imagemap" "string filename" "sky.png" "string wrap" "clamp" "float scale" 0.9
MakeNamedMaterial "floor" "string type" "diffuse" "texture reflectance" "checks"
MakeNamedMaterial "print" "string type" "diffuse" "texture reflectance" "sky"
MakeNamedMaterial "lacquer" "string type" "coateddiffuse" "rgb reflectance" [0.5 0.2 0.1] "float roughness" 0.1
MakeNamedMaterial "glass" "string type" "dielectric" "spectrum eta" "glass-BK7"
MakeNamedMaterial "gold" "string type" "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" "float uroughness" 0.1 "float vroughness" 0.1
MakeNamedMaterial "paper" "string type" "kasha" "string file" "paper.json"
MakeNamedMaterial "leaf" "string type" "diffusetransmission" "rgb transmittance" [0.3 0.5 0.2] "float scale" 0.9
MakeNamedMaterial "sheet" "string type" "thindielectric" "float eta" 1.4
MakeNamedMaterial "brushed" "string type" "conductor" "rgb eta" [0.2 0.9 1.1] "rgb k" [3.9 2.4 2.2] "float roughness" 0.2
MakeNamedMaterial "varnish" "string type" "coatedconductor" "spectrum conductor.eta" "metal-Au-eta" "spectrum conductor.k" "metal-Au-k" "float interface.eta" 1.4 "float thickness" 0.05
MakeNamedMaterial "paint" "string type" "coatedconductor" "spectrum conductor.eta" "metal-Al-eta" "spectrum conductor.k" "metal-Al-k" "float conductor.roughness" 0.05 "float interface.roughness" 0.02
Texture "holes" "float" "checkerboard" "float uscale" 8 "float vscale" 8 "float tex1" 1 "float tex2" 0
MakeNamedMaterial "worn" "string type" "mix" "string materials" ["lacquer" "gold"] "texture amount" "holes"
AttributeBegin
  Scale 2 2 2
  Texture "noise" "float" "fbm" "integer octaves" 3
AttributeEnd
Texture "cloud" "spectrum" "mix" "texture tex1" "checks" "rgb tex2" [0.2 0.3 0.4] "texture amount" "noise"
Texture "spots" "spectrum" "dots" "texture inside" "cloud" "rgb outside" [0.5 0.5 0.5] "string mapping" "planar"
Texture "stone" "spectrum" "marble" "float variation" 0.3
Texture "veins" "spectrum" "scale" "texture tex" "stone" "texture scale" "noise"
Texture "cut" "float" "checkerboard" "integer dimension" 3 "float tex1" 1 "texture tex2" "noise"
MakeNamedMaterial "dotted" "string type" "diffuse" "texture reflectance" "spots"
MakeNamedMaterial "marbled" "string type" "diffuse" "texture reflectance" "veins"
LightSource "point" "point3 from" [0 2 0] "blackbody I" 4000 "float scale" 2
LightSource "spot" "point3 from" [1 2 1] "point3 to" [0 0 0] "rgb I" [0.5 0.6 0.7] "float coneangle" 25
LightSource "distant" "point3 from" [0 1 0] "point3 to" [0.2 0 0.1] "spectrum L" [400 1 700 2] "float scale" 0.3
LightSource "infinite" "rgb L" [0.1 0.2 0.3]
AttributeBegin
  AreaLightSource "diffuse" "spectrum L" "stdillum-D65" "float scale" 4 "bool twosided" true
  Translate 0 2 0
  Rotate 90 1 0 0
  Shape "disk" "float radius" 0.3
AttributeEnd
NamedMaterial "floor"
Shape "trianglemesh" "point3 P" [-2 0 -2  2 0 -2  2 0 2  -2 0 2] "integer indices" [0 2 1  0 3 2]
    "point2 uv" [0 0 1 0 1 1 0 1] "normal N" [0 1 0  0 1 0  0 1 0  0 1 0]
Include "part.pbrt"
NamedMaterial "leaf"
Shape "trianglemesh" "point3 P" [-1 0.1 -1  1 0.1 -1  1 0.6 -1] "point2 uv" [0 0 1 0 1 1] "texture alpha" "holes"
NamedMaterial "sheet"
Shape "trianglemesh" "point3 P" [-1 0.1 -1.2  1 0.6 -1.2  -1 0.6 -1.2] "float alpha" 0.5
NamedMaterial "brushed"
Shape "sphere" "float radius" 0.2
AttributeBegin
  NamedMaterial "varnish"
  Translate 0.5 0.3 0.6
  Shape "sphere" "float radius" 0.1
AttributeEnd
AttributeBegin
  NamedMaterial "paint"
  Translate 0.8 0.3 0.2
  Shape "sphere" "float radius" 0.1
AttributeEnd
AttributeBegin
  NamedMaterial "worn"
  Translate -0.5 0.3 0.6
  Shape "sphere" "float radius" 0.15
AttributeEnd
MakeNamedMedium "ink" "string type" "homogeneous" "rgb sigma_a" [0.5 2 4] "rgb sigma_s" [0 0 0] "float scale" 2
MakeNamedMedium "tint" "string type" "rgbgrid" "integer nx" 2 "rgb sigma_a" [1 0.2 0.1 0.2 0.4 1]
  "rgb Le" [0.5 1 2 2 1 0.5] "float Lescale" 0.7
  "point3 p0" [0.5 0.6 0.2] "point3 p1" [0.8 0.9 0.5] "float scale" 2 "float g" 0.5
MakeNamedMedium "haze" "string type" "homogeneous" "spectrum sigma_a" [400 0.1 830 0.3] "float sigma_s" 0 "float g" 0.3
AttributeBegin
  Translate 0.2 0.5 0
  MakeNamedMedium "smoke" "string type" "uniformgrid" "integer nx" 2 "integer ny" 1 "integer nz" 2
    "float density" [0 1 2 0.5] "rgb sigma_s" [1 2 1] "float scale" 2 "point3 p0" [-0.2 -0.2 -0.2] "point3 p1" [0.2 0.2 0.2]
  MediumInterface "smoke" ""
  Material "interface"
  Shape "sphere" "float radius" 0.2
AttributeEnd
AttributeBegin
  MediumInterface "ink" ""
  NamedMaterial "glass"
  Translate -0.3 0.3 0.3
  Shape "sphere" "float radius" 0.12
AttributeEnd
AttributeBegin
  MediumInterface "haze" ""
  Material "interface"
  Translate 0.3 0.4 -0.3
  Shape "sphere" "float radius" 0.2
AttributeEnd
AttributeBegin
  NamedMaterial "marbled"
  Translate 0 0.3 -0.6
  Shape "sphere" "float radius" 0.15 "texture alpha" "cut"
AttributeEnd
AttributeBegin
  NamedMaterial "dotted"
  Translate 0 0.01 1
  Rotate -90 1 0 0
  Shape "disk" "float radius" 0.3
AttributeEnd
ObjectBegin "thing"
  NamedMaterial "paper"
  Shape "bilinearmesh" "point3 P" [0 0 0  0.4 0 0  0 0.4 0  0.4 0.4 0]
ObjectEnd
AttributeBegin
  Transform [1 0 0 0  0 1 0 0  0 0 1 0  -0.8 0.1 0.5 1]
  ObjectInstance "thing"
AttributeEnd
AttributeBegin
  Translate 0.6 0.1 -0.2
  Rotate 30 0 1 0
  Scale 1 -1 1
  ObjectInstance "thing"
AttributeEnd
)";

const char* kSeedPbrtPart = R"(AttributeBegin
  NamedMaterial "glass"
  Translate 0.5 0.25 0
  Shape "sphere"
AttributeEnd
AttributeBegin
  NamedMaterial "gold"
  ConcatTransform [0.3 0 0 0  0 0.3 0 0  0 0 0.3 0  -0.5 0.2 -0.5 1]
  ReverseOrientation
  Shape "plymesh" "string filename" "mesh.ply"
AttributeEnd
AttributeBegin
  NamedMaterial "lacquer"
  Translate 0 0.2 -0.8
  Shape "cylinder" "float zmin" 0 "float zmax" 0.3 "float phimax" 270
AttributeEnd
)";

}  // namespace

// Mutated pbrt-v4 scenes (the main file or its included one): each loads or is refused with one
// line, the files it reads stay as they were, and one in four that loads renders finite pixels.
TEST(Fuzz, MutatedPbrtScenesLoadOrGiveOneLine) {
  const Seeds seeds = make_seeds();
  // An eighth of the count (at least 100): each case tessellates a sphere and a cylinder, about
  // 140 ms under the sanitizers.
  const int cases = std::max(100, fuzz_cases(400) / 8);
  std::mt19937 rng(20261203);
  static ClContext cl(0);
  write_text(seeds.dir / "paper.json", seeds.material);
  write_text(seeds.dir / "mesh.ply", seeds.ply);
  write_text(seeds.dir / "sky.png", seeds.sky);
  const fs::path main = seeds.dir / "scene.pbrt", part = seeds.dir / "part.pbrt";
  write_text(main, kSeedPbrt);
  write_text(part, kSeedPbrtPart);
  ASSERT_NO_THROW(load_scene(main.string())) << "the seed itself must load";
  const std::vector<std::string> integrators = IntegratorRegistry::names(true);
  int loaded = 0, refused = 0, rendered = 0;
  for (int c = 0; c < cases; ++c) {
    const std::string text = c % 3 == 2 ? mutated(kSeedPbrtPart, rng) : mutated(kSeedPbrt, rng);
    const fs::path& target = c % 3 == 2 ? part : main;
    write_text(main, c % 3 == 2 ? std::string(kSeedPbrt) : text);
    write_text(part, c % 3 == 2 ? text : std::string(kSeedPbrtPart));
    SCOPED_TRACE("case " + std::to_string(c) + ": " + target.filename().string());
    try {
      Scene scene = load_scene(main.string());
      ++loaded;
      if (c % 4 == 0 && scene.camera.width * scene.camera.height <= 64) {
        rendered += render_one_pass(cl, scene, integrators[(c / 4) % integrators.size()], c);
      }
    } catch (const Error& e) {
      ++refused;
      EXPECT_TRUE(one_line(e.what())) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not a kasha::Error: " << e.what() << "\n" << text;
    }
    EXPECT_EQ(read_text(target), text) << "an input file changed";
    EXPECT_EQ(read_text(seeds.dir / "mesh.ply"), seeds.ply) << "an input file changed";
  }
  std::printf("  %d pbrt cases: %d loaded (%d rendered), %d refused with one line\n", cases, loaded,
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

// kasha's PLY reader and gzip inflater (host/scene/ply_mesh.cpp, host/core/gzip_input.cpp), in
// process: binary and ASCII seeds with quads, normals and texture coordinates, mutated as text
// and as bytes, and a gzip of one, each read or refused with one kasha::Error line.
static std::string gzip_bytes(const std::string& data) {
  uLongf size = compressBound(static_cast<uLong>(data.size())) + 64;
  std::string out(size, '\0');
  z_stream z{};
  deflateInit2(&z, 6, Z_DEFLATED, 16 + 15, 8, Z_DEFAULT_STRATEGY);
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

TEST(Fuzz, MutatedPlyAndGzipMeshesReadOrGiveOneLine) {
  const std::string quads =
      "ply\nformat ascii 1.0\ncomment quads\nelement vertex 5\nproperty double x\nproperty double "
      "y\n"
      "property double z\nproperty float texture_s\nproperty float texture_t\nproperty short nx\n"
      "property short ny\nproperty short nz\nelement face 3\nproperty list int uint "
      "vertex_indices\n"
      "property int face_indices\nelement extra 1\nproperty list uchar float values\nend_header\n"
      "0 0 0 0 0 0 0 1\n1 0 0 1 0 0 0 1\n1 1 0 1 1 0 0 1\n0 1 0 0 1 0 0 1\n2 2 0 1 1 0 0 1\n"
      "4 0 1 2 3 0\n5 0 1 2 3 4 1\n3 2 3 4 2\n2 0.5 1.5\n";
  const std::vector<std::string> seeds = {mesh_ply(tent_mesh(), true), mesh_ply(tent_mesh(), false),
                                          quads};
  std::mt19937 rng(11);
  const int cases = fuzz_cases(400);
  int read = 0, refused = 0;
  for (int c = 0; c < cases; ++c) {
    std::string b = seeds[c % seeds.size()];
    if (rng() % 2) {
      b = mutate(b, rng);
    } else {
      const int flips = 1 + static_cast<int>(rng() % 8);
      for (int k = 0; k < flips; ++k) b[rng() % b.size()] ^= static_cast<char>(1 << (rng() % 8));
      if (rng() % 4 == 0) b.resize(rng() % b.size());
    }
    try {
      if (c % 5 == 4) {  // a gzip of it, cut short or with a flipped byte now and then
        std::string z = gzip_bytes(b);
        if (rng() % 2) z[rng() % z.size()] ^= static_cast<char>(1 << (rng() % 8));
        if (rng() % 3 == 0) z.resize(rng() % z.size());
        b = gunzip(z, "mutated.ply.gz", std::uint64_t(1) << 20);
      }
      const ShapeMesh m = ply_mesh_triangles(parse_ply(b, "mutated.ply"), "mutated.ply");
      EXPECT_EQ(m.tris.size(), m.uv.size());
      ++read;
    } catch (const Error& e) {
      ++refused;
      EXPECT_TRUE(one_line(e.what())) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "case " << c << ": not a kasha::Error: " << e.what();
    }
  }
  std::printf("  %d PLY files: %d read, %d refused with one line\n", cases, read, refused);
  EXPECT_GT(read, 0);
  EXPECT_GT(refused, 0);
}

// The images scenes read (image/rgb_image.h), each format's seed made here: flipped bytes,
// cut-short files and headers claiming sizes up to 2^32 must read or give one line, with no
// image beyond the pixel limit (sizes are checked before the pixels are allocated).
TEST(Fuzz, MutatedSceneImagesReadOrGiveOneLine) {
  const fs::path dir = scratch_dir();
  const unsigned char px[48] = {0,   9,   18,  27,  36, 45, 54, 63,  72,  81,  90,  99,
                                108, 117, 126, 135, 1,  2,  3,  4,   5,   6,   7,   8,
                                9,   10,  11,  12,  13, 14, 15, 16,  200, 210, 220, 230,
                                240, 250, 255, 0,   0,  7,  77, 177, 17,  27,  37,  47};
  std::vector<float> f(px, px + 48);
  ASSERT_TRUE(stbi_write_png((dir / "seed.png").string().c_str(), 4, 4, 3, px, 12));
  ASSERT_TRUE(stbi_write_tga((dir / "seed.tga").string().c_str(), 4, 4, 3, px));
  ASSERT_TRUE(stbi_write_hdr((dir / "seed.hdr").string().c_str(), 4, 4, 3, f.data()));
  std::string pfm = "PF\n4 4\n-1.0\n";
  pfm.append(reinterpret_cast<const char*>(f.data()), 4 * f.size());
  write_text(dir / "seed.pfm", pfm);
  qoi_desc desc{4, 4, 3, QOI_SRGB};
  int qoi_size = 0;
  void* qoi = qoi_encode(px, &desc, &qoi_size);
  ASSERT_NE(qoi, nullptr);
  write_text(dir / "seed.qoi", std::string(static_cast<char*>(qoi), qoi_size));
  std::free(qoi);
  std::mt19937 rng(41);
  const int cases = fuzz_cases(400) / 2;
  int read = 0, refused = 0;
  for (int c = 0; c < cases; ++c) {
    const char* ext = std::array<const char*, 5>{"png", "tga", "hdr", "pfm", "qoi"}[c % 5];
    std::string b = read_text(dir / (std::string("seed.") + ext));
    const int flips = static_cast<int>(rng() % 6);
    for (int k = 0; k < flips; ++k) b[rng() % b.size()] ^= static_cast<char>(1 << (rng() % 8));
    if (rng() % 3 == 0) {  // a size field of the header (where each format keeps it) made huge
      const size_t at = std::string(ext) == "tga" ? 12 : std::string(ext) == "qoi" ? 4 : 16;
      for (size_t k = at; k < std::min(b.size(), at + 4); ++k) b[k] = static_cast<char>(rng());
      if (std::string(ext) == "pfm") b.replace(3, 1, std::to_string(rng()));
    }
    if (rng() % 4 == 0) b.resize(rng() % b.size());
    const fs::path p = dir / (std::string("mutated.") + ext);
    write_text(p, b);
    try {
      RgbImage r = read_rgb_image(p.string());
      EXPECT_LE(static_cast<long long>(r.width) * r.height, kMaxScenePixels);
      EXPECT_EQ(r.rgb.size(), 3 * size_t(r.width) * r.height);
      ++read;
    } catch (const Error& e) {
      ++refused;
      EXPECT_TRUE(one_line(e.what())) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "case " << c << " (" << ext << "): not a kasha::Error: " << e.what();
    }
  }
  std::printf("  %d images: %d read, %d refused with one line\n", cases, read, refused);
  EXPECT_GT(read, 0);
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

// ---------------------------------------------------------------------------------------------
// The commands, in process: colorimetry, regions, compare, preview and delta-e, each run
// KASHA_FUZZ_CASES times (default 500) through run_command_line (cli/command_line.h) on mutated
// material JSON, spectra, scenes, EXRs, L*,a*,b* texts and option values. Each case must keep the
// contract of docs/commands.md#errors-and-exit-codes: exit 0, 1 or 2; on failure exactly one
// stderr line `kasha: error: WHERE: what is wrong` and no output file; valid UTF-8 without
// control bytes; no library's own text; no NaN or infinity printed or written (a NaN that
// nlohmann::json writes shows as null). A crash or a sanitizer finding prints the case's command
// line and its stderr on the real stderr; a case that runs past KASHA_FUZZ_CASE_SECONDS (default
// 60) is reported as a hang and ends the run. The findings are gathered per class, with the
// first example of each and its inputs kept under tests/tmp/fuzz-findings/; classes still
// known to fail are listed in known_failing() (KASHA_FUZZ_STRICT=1 fails them too);
// KASHA_FUZZ_LOG=FILE logs every case. `--plot` (a Python subprocess) is left out: too slow.
// ---------------------------------------------------------------------------------------------

namespace {

using nlohmann::json;

// ---- Running a command line in process, with a crash and hang report ----

char g_case_text[16384];                  // the command line in flight, for crash and hang reports
char g_err_path[4096];                    // where its stderr goes
int g_real_err = STDERR_FILENO;           // the test's own stderr, while fd 2 is captured
std::atomic<long long> g_deadline_ms{0};  // 0: no case in flight

long long now_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

void put(const char* s) {
  ssize_t ignored = write(g_real_err, s, std::strlen(s));
  (void)ignored;
}

// Async-signal-safe: the case and what it wrote to stderr so far (a sanitizer's report included).
void report_case(const char* what) {
  put("\nkasha_fuzz: ");
  put(what);
  put(" in:\n  ");
  put(g_case_text);
  put("\n-- its stderr:\n");
  int fd = open(g_err_path, O_RDONLY);
  if (fd >= 0) {
    char buf[4096];
    ssize_t n;
    while ((n = read(fd, buf, sizeof buf)) > 0) {
      ssize_t ignored = write(g_real_err, buf, n);
      (void)ignored;
    }
    close(fd);
  }
  put("\n-- end\n");
}

extern "C" void on_fatal_signal(int sig) {
  report_case("CRASH (fatal signal)");
  signal(sig, SIG_DFL);
  raise(sig);
}

#ifdef KASHA_FUZZ_SANITIZED
extern "C" void on_sanitizer_death() {
  report_case("CRASH (sanitizer finding)");
}
#endif

double case_seconds() {
  const char* s = std::getenv("KASHA_FUZZ_CASE_SECONDS");
  return s ? std::max(1.0, std::atof(s)) : 60.0;
}

void start_in_process_runs() {
  static bool started = false;
  if (started) return;
  started = true;
  g_real_err = dup(STDERR_FILENO);
#ifdef KASHA_FUZZ_SANITIZED
  __sanitizer_set_death_callback(on_sanitizer_death);  // ASan and UBSan report, then call this
#else
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) signal(sig, on_fatal_signal);
#endif
  std::thread([] {
    for (;;) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      const long long deadline = g_deadline_ms;
      if (deadline != 0 && now_ms() > deadline) {
        report_case("HANG (past KASHA_FUZZ_CASE_SECONDS)");
        _exit(124);
      }
    }
  }).detach();
}

// A shell word for the reports: plain when safe, else $'…' with \xNN for odd bytes.
std::string shell_word(const std::string& s) {
  bool plain = !s.empty();
  for (unsigned char c : s)
    if (!(std::isalnum(c) || std::strchr("/._-,=+:@%", c))) plain = false;
  if (plain) return s;
  std::string out = "$'";
  for (unsigned char c : s) {
    if (c == '\'' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20 || c >= 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "'";
}

struct Outcome {
  int code = 0;
  std::string out, err, command;
  bool threw = false;  // an exception left run_command_line
  long long ms = 0;    // how long it ran
};

// `kasha ARGS…` in this process, its stdout and stderr captured through fds 1 and 2.
Outcome run_in_process(const fs::path& capture_dir, const std::vector<std::string>& args) {
  start_in_process_runs();
  Outcome r;
  r.command = "kasha";
  for (const std::string& a : args) r.command += " " + shell_word(a);
  std::snprintf(g_case_text, sizeof g_case_text, "%s", r.command.c_str());
  const std::string out_path = (capture_dir / "stdout.txt").string(),
                    err_path = (capture_dir / "stderr.txt").string();
  std::snprintf(g_err_path, sizeof g_err_path, "%s", err_path.c_str());
  std::vector<std::string> words = {"kasha"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);

  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  const int saved_in = dup(0), saved_out = dup(1), saved_err = dup(2);
  const int in = open("/dev/null", O_RDONLY),
            out = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644),
            err = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  dup2(in, 0);
  dup2(out, 1);
  dup2(err, 2);
  close(in);
  close(out);
  close(err);
  const long long start = now_ms();
  g_deadline_ms = start + static_cast<long long>(1000 * case_seconds());
  try {
    r.code = kasha::run_command_line(static_cast<int>(words.size()), argv.data());
  } catch (...) {
    r.threw = true;
    r.code = -1;
  }
  g_deadline_ms = 0;
  r.ms = now_ms() - start;
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  dup2(saved_in, 0);
  dup2(saved_out, 1);
  dup2(saved_err, 2);
  close(saved_in);
  close(saved_out);
  close(saved_err);
  r.out = read_text(out_path);
  r.err = read_text(err_path);
  return r;
}

// ---- The checks ----

// Text as the contract wants its lines: valid UTF-8, no control bytes but the newline.
bool clean_text(const std::string& text) {
  for (char c : text)
    if ((static_cast<unsigned char>(c) < 0x20 && c != '\n') || c == 0x7f) return false;
  return valid_utf8(text);
}

// A NaN or an infinity written as a number: nan, -nan, inf, infinity (any case) as a word.
bool has_non_finite_token(const std::string& text) {
  static const std::regex token("(^|[^A-Za-z0-9_])[-+]?(nan|inf|infinity)([^A-Za-z0-9_]|$)",
                                std::regex::icase);
  return std::regex_search(text, token);
}

// Wording that comes from a library rather than from kasha: C++ exception texts, nlohmann's,
// OpenEXR's (Iex), CLI11's, glibc's.
std::string library_text(const std::string& text) {
  static const std::vector<std::string> marks = {"std::",
                                                 "basic_string",
                                                 "what()",
                                                 "terminate called",
                                                 "[json.exception",
                                                 "vector::",
                                                 "stoi",
                                                 "stod",
                                                 "stof",
                                                 "bad_alloc",
                                                 "bad_array_new",
                                                 "Iex",
                                                 "Imf::",
                                                 "Error reading",
                                                 "Cannot read",
                                                 "Cannot open",
                                                 "Unexpected end",
                                                 "Early end",
                                                 "Invalid argument",
                                                 "CLI::",
                                                 "Unable to",
                                                 "Reading past",
                                                 "Unsupported",
                                                 "Attempt to",
                                                 "Failed",
                                                 "Invalid ",
                                                 "lexical_cast",
                                                 "syntax error while parsing",
                                                 "type must be",
                                                 "cannot use operator",
                                                 "Could not",
                                                 "Run with --help"};
  for (const std::string& m : marks)
    if (text.find(m) != std::string::npos) return m;
  return "";
}

// A JSON document kasha wrote: "" if it is fine, else what is wrong (null stands for a NaN).
std::string json_output_problem(const std::string& text) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const std::exception&) {
    return "not valid JSON";
  }
  bool in_beta = false;
  std::function<bool(const json&)> has_null = [&](const json& j) {
    if (j.is_null()) return true;
    if (j.is_number_float() && !std::isfinite(j.get<double>())) return true;
    if (j.is_object()) {
      for (const auto& [key, value] : j.items()) {
        // colorimetry's β per bin ("beta": {"value": [...]}) is null where the lamp leaves the
        // bin unlit: undefined, as docs/colorimetry.md says, not a NaN result.
        if (key == "value" && value.is_array() && in_beta) {
          for (const json& b : value)
            if (!b.is_null() && has_null(b)) return true;
          continue;
        }
        const bool was = in_beta;
        in_beta = key.rfind("beta", 0) == 0;
        const bool bad = has_null(value);
        in_beta = was;
        if (bad) return true;
      }
    } else if (j.is_array()) {
      for (const json& k : j)
        if (has_null(k)) return true;
    }
    return false;
  };
  return has_null(doc) ? "a null (a NaN or infinity) in JSON" : "";
}

struct Finding {
  int count = 0;
  std::string command, detail, kept;  // the first example and where its inputs were kept
};

// One target's findings, by class and a short signature of what went wrong.
class Findings {
 public:
  Findings(std::string target, fs::path case_dir)
      : target_(std::move(target)), case_dir_(std::move(case_dir)) {
    std::error_code ec;
    fs::remove_all(fs::path(KASHA_TEST_TMP) / "fuzz-findings" / target_, ec);  // a former run's
  }

  void count(const Outcome& r) {
    ++exits_[r.code];
    if (r.ms >= slowest_.ms) slowest_ = r;
  }

  void add(const std::string& kind, const std::string& detail, const Outcome& r) {
    const std::string key = kind + " | " + signature(kind, detail);
    Finding& f = found_[key];
    if (f.count++ > 0) return;
    f.command = r.command;
    f.detail = printable(detail.substr(0, 400));
    if (found_.size() <= 60) {  // the inputs of the first example of each
      fs::path keep =
          fs::path(KASHA_TEST_TMP) / "fuzz-findings" / target_ / std::to_string(found_.size());
      std::error_code ec;
      fs::remove_all(keep, ec);
      fs::create_directories(keep, ec);
      fs::copy(case_dir_, keep / "in", fs::copy_options::recursive, ec);
      write_text(keep / "command.txt", r.command + "\n" + kind + ": " + f.detail + "\n");
      f.kept = keep.string();
    }
  }

  // Prints the findings (the case folder written D/); fails the test once for each class not in
  // `known` (KASHA_FUZZ_STRICT=1: for every class).
  void report(int cases, const std::set<std::string>& known) const {
    const bool strict = std::getenv("KASHA_FUZZ_STRICT") != nullptr;
    std::string exits;
    for (const auto& [code, n] : exits_)
      exits += " " + std::to_string(n) + " exit " + std::to_string(code) + ",";
    std::printf("  %s: %d cases (%s), %zu distinct findings (D = %s)\n", target_.c_str(), cases,
                exits.substr(1, exits.size() - 2).c_str(), found_.size(),
                case_dir_.string().c_str());
    std::printf("  the slowest case, %lld ms: %s\n", slowest_.ms,
                shorter(slowest_.command).c_str());
    std::map<std::string, int> per_kind;
    for (const auto& [key, f] : found_) {
      const std::string kind = key.substr(0, key.find(" | "));
      per_kind[kind] += f.count;
      std::printf("  [%s] x%d: %s\n      %s\n", kind.c_str(), f.count, shorter(f.detail).c_str(),
                  shorter(f.command).c_str());
    }
    for (const std::string& kind : known)
      if (per_kind.count(kind) == 0)
        std::printf("  (%s: tolerated as a known failure but not seen: remove it from the list?)\n",
                    kind.c_str());
    for (const auto& [kind, count] : per_kind) {
      if (!strict && known.count(kind) > 0)
        std::printf("  (%s: %d cases tolerated for now, a known failure)\n", kind.c_str(), count);
      else
        ADD_FAILURE() << target_ << ": " << count << " cases of class \"" << kind
                      << "\" (listed above; inputs under " << KASHA_TEST_TMP << "/fuzz-findings)";
    }
  }

 private:
  std::string shorter(std::string text) const {
    const std::string dir = case_dir_.string() + "/";
    for (size_t at; (at = text.find(dir)) != std::string::npos;) text.replace(at, dir.size(), "D/");
    return text;
  }

  // What tells findings apart: the message with paths, numbers and quoted values blanked.
  static std::string signature(const std::string& kind, const std::string& detail) {
    if (kind == "raw library text") return detail.substr(0, detail.find(" in: "));  // the mark
    std::string s = std::regex_replace(detail, std::regex("/[^ :]*"), "P");
    s = std::regex_replace(s, std::regex("\"[^\"]*\""), "Q");
    s = std::regex_replace(s, std::regex("[-+]?(nan|inf)", std::regex::icase), "N");
    s = std::regex_replace(s, std::regex("[-+0-9.e]*[0-9][-+0-9.e]*"), "#");
    return s.substr(0, 60);
  }

  std::string target_;
  fs::path case_dir_;
  std::map<std::string, Finding> found_;
  std::map<int, int> exits_;
  Outcome slowest_;
};

// Checks one case against the contract. `outputs`: the files the command line asks it to write
// (each removed before the case); `dir`: the folder that must hold nothing else afterwards but
// `inputs`.
void check_case(Findings& findings, const Outcome& r, const std::vector<fs::path>& outputs,
                const fs::path& dir, const std::set<std::string>& inputs) {
  if (r.threw) findings.add("crash", "an exception left run_command_line", r);
  if (r.code != 0 && r.code != 1 && r.code != 2)
    findings.add("exit code", "exit " + std::to_string(r.code) + ": " + r.err, r);
  if (r.code != 0) {
    const size_t lines = std::count(r.err.begin(), r.err.end(), '\n');
    const std::string first = r.err.substr(0, r.err.find('\n'));
    if (lines != 1 || r.err.back() != '\n')
      findings.add("second line", std::to_string(lines) + " lines: " + r.err, r);
    else if (first.rfind("kasha: error: ", 0) != 0 ||
             first.find(": ", std::strlen("kasha: error: ")) == std::string::npos)
      findings.add("error line", first, r);
  }
  if (!clean_text(r.out)) findings.add("control bytes", "stdout: " + r.out.substr(0, 300), r);
  if (!clean_text(r.err)) findings.add("control bytes", "stderr: " + r.err, r);
  const std::string mark = library_text(r.err + r.out);
  if (!mark.empty()) findings.add("raw library text", "\"" + mark + "\" in: " + r.err, r);
  if (has_non_finite_token(r.out)) findings.add("nan", "stdout: " + r.out.substr(0, 600), r);
  for (const fs::path& p : outputs) {
    if (inputs.count(p.filename().string())) continue;  // an input given as an output
    const bool exists = fs::exists(fs::symlink_status(p));
    if (r.code != 0 && exists)
      findings.add("file left behind", p.filename().string() + " after: " + r.err, r);
    if (r.code != 0 || !exists) continue;
    const std::string text = read_text(p);
    const std::string ext = p.extension().string();
    if (ext == ".json") {
      const std::string problem = json_output_problem(text);
      if (!problem.empty()) findings.add("nan", p.filename().string() + ": " + problem, r);
    }
    if ((ext == ".json" || ext == ".csv") && has_non_finite_token(text))
      findings.add("nan", p.filename().string() + ": " + text.substr(0, 300), r);
    // A file's strings may hold DEL (JSON leaves it as it is), not C0 control bytes or bad UTF-8.
    const bool c0 = std::any_of(text.begin(), text.end(), [](char ch) {
      return static_cast<unsigned char>(ch) < 0x20 && ch != '\n';
    });
    if ((ext == ".json" || ext == ".csv") && (c0 || !valid_utf8(text)))
      findings.add("control bytes", p.filename().string() + " is not clean text", r);
  }
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (inputs.count(name) == 0 &&
        std::find(outputs.begin(), outputs.end(), e.path()) == outputs.end())
      findings.add("file left behind", "a stray " + printable(name) + " after: " + r.err, r);
  }
}

// Names that error messages must escape: control bytes, a newline, bytes that are not UTF-8.
const std::vector<std::string> kOddNames = {"\x1b[31mred", "bad\xff",           "new\nline",
                                            "tab\there",   "\xc3\xa9t\xc3\xa9", "del\x7f"};

// Runs one case and checks it: `inputs` are the names of the files in `dir` it reads, which must
// be left as they were; `outputs` the files it is asked to write. Now and then an input given on
// the command line is renamed to one of kOddNames first.
void run_and_check(Findings& findings, std::mt19937& rng, const fs::path& dir,
                   std::vector<std::string> args, std::vector<fs::path> outputs,
                   std::set<std::string> inputs) {
  if (!inputs.empty() && std::uniform_int_distribution<int>(0, 19)(rng) == 0) {
    std::vector<std::string> names(inputs.begin(), inputs.end());
    const std::string from = names[rng() % names.size()];
    const fs::path old_path = dir / from;
    const std::string to = kOddNames[rng() % kOddNames.size()] + old_path.extension().string();
    bool named = false;
    for (std::string& a : args)
      if (a == old_path.string()) a = (dir / to).string(), named = true;
    if (named) {
      fs::rename(old_path, dir / to);
      inputs.erase(from);
      inputs.insert(to);
    }
  }
  std::map<std::string, std::string> before;
  for (const std::string& name : inputs)
    if (fs::exists(dir / name)) before[name] = read_text(dir / name);
  const Outcome r = run_in_process(dir.parent_path() / "capture", args);
  findings.count(r);
  if (const char* log = std::getenv("KASHA_FUZZ_LOG")) {  // every case, for a closer look
    std::ofstream out(log, std::ios::app);
    out << r.command << "\n  exit " << r.code << " (" << r.ms << " ms): " << printable(r.err)
        << "\n";
  }
  check_case(findings, r, outputs, dir, inputs);
  for (const auto& [name, text] : before)
    if (!fs::exists(dir / name) || read_text(dir / name) != text)
      findings.add("file left behind", "the input " + printable(name) + " was changed; " + r.err,
                   r);
}

// ---- Mutations ----

size_t pick(std::mt19937& rng, size_t n) {
  return std::uniform_int_distribution<size_t>(0, n - 1)(rng);
}

template <typename T>
const T& one_of(const std::vector<T>& v, std::mt19937& rng) {
  return v[pick(rng, v.size())];
}

bool chance(std::mt19937& rng, double p) {
  return std::uniform_real_distribution<double>(0, 1)(rng) < p;
}

// A value a JSON node may become.
json odd_json(std::mt19937& rng) {
  static const std::vector<json> values = {
      0,
      -0.0,
      -1,
      1,
      0.5,
      2,
      10,
      1e308,
      -1e308,
      1e-320,
      3.5e38,
      4294967297LL,
      -2147483649LL,
      1e19,
      json(18446744073709551615ULL),
      "",
      "x",
      "\x1b[31mred",
      "tab\there",
      std::string("nul\0byte", 8),
      "\xc3\xa9t\xc3\xa9",
      "D65",
      "nan",
      "inf",
      "1e400",
      nullptr,
      true,
      false,
      json::array(),
      json::object(),
      json::parse(std::string(40, '[') + std::string(40, ']')),
      json::array({0}),
      json::array({1, 2, 3}),
      json::array({1e308, -1e308, 0}),
      json::parse(R"({"nm": [400, 500], "value": [1, 1]})"),
      json::parse(R"({"nm": [500, 400], "value": [1, 1]})"),
      json::parse(R"({"nm": [400, 400], "value": [1, 1e30]})"),
      json::parse(R"({"csv": "missing.csv"})"),
      json::parse(R"({"file": "missing.json"})"),
      json::parse(R"({"blackbody_K": 1e6})"),
      json::parse(R"({"blackbody_K": 1})"),
      json::parse(R"({"gaussian_nm": 500, "fwhm_nm": 1e-300})"),
      json::parse(R"({"gaussian_nm": 1e300, "fwhm_nm": 1e300})"),
      json::parse(R"({"line_nm": 405})"),
      json::parse(R"({"line_nm": 1e-300})"),
      json::parse(R"({"scale": 1e30})")};
  return one_of(values, rng);
}

void collect(json& j, std::vector<json*>& nodes) {
  nodes.push_back(&j);
  if (j.is_structured())
    for (json& k : j) collect(k, nodes);
}

// One structural mutation of a JSON document: a node replaced, scaled, removed, added to,
// reordered or wrapped.
void mutate_json(json& root, std::mt19937& rng) {
  std::vector<json*> nodes;
  collect(root, nodes);
  json& n = *one_of(nodes, rng);
  static const std::vector<std::string> keys = {
      "x",        "scale", "nm",   "value",   "column",      "csv",          "file",  "emission",
      "material", "type",  "name", "passive", "reflectance", "fluorescence", "width", "height"};
  switch (pick(rng, 6)) {
    case 0:
      n = odd_json(rng);
      break;
    case 1:
      if (n.is_number()) {
        static const std::vector<double> factors = {-1,     0,         1e10, 1e-10, 1e300,
                                                    1e-300, 1 + 1e-15, 1000, 0.001};
        const double v = n.get<double>() * one_of(factors, rng);
        n = std::isfinite(v) ? json(v) : json(1e308);
      } else {
        n = odd_json(rng);
      }
      break;
    case 2:
      if (n.is_object() && !n.empty()) {
        auto it = n.begin();
        std::advance(it, pick(rng, n.size()));
        n.erase(it);
      } else if (n.is_array() && !n.empty()) {
        if (chance(rng, 0.5))
          n.erase(n.begin() + pick(rng, n.size()));
        else
          n.erase(n.begin() + pick(rng, n.size()), n.end());
      } else {
        n = odd_json(rng);
      }
      break;
    case 3:
      if (n.is_object())
        n[one_of(keys, rng)] = odd_json(rng);
      else if (n.is_array())
        n.push_back(n.empty() || chance(rng, 0.3) ? odd_json(rng) : n[pick(rng, n.size())]);
      else
        n = odd_json(rng);
      break;
    case 4:
      if (n.is_array() && n.size() > 1) {
        if (chance(rng, 0.5))
          std::reverse(n.begin(), n.end());
        else
          n[pick(rng, n.size())] = n[pick(rng, n.size())];
      } else {
        n = odd_json(rng);
      }
      break;
    default:
      n = chance(rng, 0.5) ? json::array({n}) : json{{"scale", n}};
  }
}

// A mutated JSON text: mostly structural mutations of the document (it still parses), else
// text mutations (it mostly does not).
std::string mutated_json(const std::string& text, std::mt19937& rng) {
  if (chance(rng, 0.75)) {
    try {
      json doc = json::parse(text);
      const int rounds = 1 + static_cast<int>(pick(rng, 3));
      for (int k = 0; k < rounds; ++k) mutate_json(doc, rng);
      return doc.dump(chance(rng, 0.5) ? 1 : -1);
    } catch (const std::exception&) {
    }
  }
  return mutated(text, rng);
}

// ---- EXRs ----

// A pixel value: mostly ordinary, sometimes one a reader must cope with.
float pixel_value(std::mt19937& rng) {
  static const std::vector<float> odd = {0.0f,      -0.0f,   -1.0f,   NAN,    INFINITY,
                                         -INFINITY, 1e38f,   3.4e38f, 1e-45f, 65504.0f,
                                         1e-30f,    -1e-30f, 1e20f};
  if (chance(rng, 0.97)) return std::uniform_real_distribution<float>(0, 2)(rng);
  return one_of(odd, rng);
}

// An image of w×h, sometimes spectral (on one of a few grids), with odd values when `odd`.
Image make_image(std::mt19937& rng, int w, int h, bool odd) {
  Image img;
  img.width = w;
  img.height = h;
  img.xyz.resize(3 * img.pixels());
  for (float& v : img.xyz)
    v = odd ? pixel_value(rng) : std::uniform_real_distribution<float>(0, 2)(rng);
  if (chance(rng, 0.5)) {
    static const std::vector<WavelengthGrid> grids = {
        {380, 10, 40}, {300, 10, 48}, {380, 100, 4}, {400, 1, 3}, {200, 0.5, 2}};
    img.grid = one_of(grids, rng);
    img.spectral.resize(img.pixels() * img.grid.bins);
    for (float& v : img.spectral)
      v = odd ? pixel_value(rng) : std::uniform_real_distribution<float>(0, 1)(rng);
  }
  return img;
}

std::string exr_bytes(const Image& img, const fs::path& scratch) {
  write_exr(scratch.string(), img);
  std::string bytes = read_text(scratch);
  fs::remove(scratch);
  return bytes;
}

// A binary mutation of an EXR: flipped bytes, a box of its header (the data window) or a channel
// name overwritten, or the file cut short.
std::string mutated_exr(std::string b, std::mt19937& rng) {
  const int kind = static_cast<int>(pick(rng, 5));
  if (kind == 0 || b.size() < 64) {
    const int flips = 1 + static_cast<int>(pick(rng, 8));
    for (int k = 0; k < flips; ++k) b[pick(rng, b.size())] ^= static_cast<char>(1 << pick(rng, 8));
  } else if (kind == 1 || kind == 2) {
    // "dataWindow\0box2i\0" + int32 size + xMin, yMin, xMax, yMax
    const std::string name = chance(rng, 0.7) ? std::string("dataWindow\0box2i\0", 17)
                                              : std::string("displayWindow\0box2i\0", 20);
    const size_t at = b.find(name);
    if (at != std::string::npos && at + name.size() + 20 <= b.size()) {
      static const std::vector<int32_t> values = {
          0, -1, 1, 7, 8, 65535, 1 << 20, 1 << 30, INT32_MAX, INT32_MIN, -65536};
      const int32_t v = one_of(values, rng);
      std::memcpy(&b[at + name.size() + 4 + 4 * pick(rng, 4)], &v, 4);
    }
  } else if (kind == 3) {
    // A channel name of the same length: "S0.555,000000nm" or one of the XYZ layer's.
    static const std::vector<std::string> names = {
        "S0.nan,000000nm", "S0.inf,000000nm", "S0.-55,000000nm", "S0.000,000000nm",
        "S0.1e9,000000nm", "S0.555,00000Xnm", "S0.385,000000nm", "S0.005,000000nm",
        "S0.0x1,000000nm", "S0.   ,000000nm"};
    std::vector<size_t> at;
    for (size_t i = b.find("S0."); i != std::string::npos && at.size() < 200;
         i = b.find("S0.", i + 1))
      at.push_back(i);
    if (!at.empty()) {
      const std::string& n = one_of(names, rng);
      const size_t i = one_of(at, rng);
      if (i + n.size() <= b.size()) b.replace(i, n.size(), n);
    } else {
      const size_t i = b.find("XYZ.");
      if (i != std::string::npos && i + 5 <= b.size())
        b[i + 4] = one_of(std::vector<char>{'Q', 'x', 'X', 'Y', '\xff'}, rng);
    }
  }
  if (kind == 4 || chance(rng, 0.1)) b.resize(pick(rng, b.size()));
  return b;
}

// ---- Option values ----

const std::vector<std::string> kOddValues = {
    "",   "nan", "inf", "-inf", "1e400", "-1",       "0",      "-0", "1e-320", "0x10",
    "1e", " 1",  "1 ",  "١",    "\xff",  "\x1b[31m", "--json", "-",  "2,",     "1.5"};

std::string number_value(const std::vector<std::string>& good, std::mt19937& rng) {
  return chance(rng, 0.8) ? one_of(good, rng) : one_of(kOddValues, rng);
}

// A spectrum argument (spectrum/spectrum_argument.h): a built-in name, a number, a JSON value
// (mutated) or a CSV file, written into dir under `name` (mutated).
std::string spectrum_argument(std::mt19937& rng, const fs::path& dir, const std::string& name,
                              const std::vector<std::string>& csv_seeds,
                              std::set<std::string>& inputs) {
  static const std::vector<std::string> builtins = {"D65", "A",    "F11", "E", "D50",  "F2", "F7",
                                                    "d65", "D65 ", "",    "X", "\xff", "D6"};
  static const std::vector<std::string> values = {
      R"({"blackbody_K": 5000})",
      R"({"gaussian_nm": 450, "fwhm_nm": 20})",
      R"({"line_nm": 405})",
      R"({"nm": [300, 400, 500, 600, 700, 780], "value": [0, 1, 2, 2, 1, 0.5]})",
      R"({"blackbody_K": 6500, "scale": 0.001})",
      "0.5",
      "1"};
  switch (pick(rng, 4)) {
    case 0:
      return one_of(builtins, rng);
    case 1:
      return mutated_json(one_of(values, rng), rng);
    case 2:
      return one_of(values, rng);
    default: {
      const std::string& seed = one_of(csv_seeds, rng);
      write_text(dir / name, chance(rng, 0.8) ? mutated(seed, rng) : seed);
      inputs.insert(name);
      return (dir / name).string();
    }
  }
}

// Anything at all on a command line now and then: an unknown option, a flag without its
// value, help.
void maybe_junk(std::vector<std::string>& args, std::mt19937& rng) {
  static const std::vector<std::vector<std::string>> junk = {
      {"--bogus"}, {"--"}, {"-"},     {"--help"},    {"\xff"},
      {"--json"},  {"-o"}, {"extra"}, {"--scale=2"}, {"--margin", "1", "--margin", "2"}};
  if (!chance(rng, 0.05)) return;
  const auto& j = one_of(junk, rng);
  args.insert(args.begin() + 1 + pick(rng, args.size()), j.begin(), j.end());
}

// The path given for an output: mostly `name` in the case's folder (listed in `outputs`),
// sometimes one of the inputs, another output, a file in a missing folder or the folder itself.
std::string output_path(std::mt19937& rng, const fs::path& dir, const std::string& name,
                        const std::set<std::string>& inputs, std::vector<fs::path>& outputs) {
  const int k = std::uniform_int_distribution<int>(0, 99)(rng);
  fs::path p = dir / name;
  if (k < 4 && !inputs.empty()) {
    auto it = inputs.begin();
    std::advance(it, pick(rng, inputs.size()));
    p = dir / *it;
  } else if (k < 7 && !outputs.empty()) {
    p = one_of(outputs, rng);
  } else if (k < 9) {
    p = dir / "missing" / name;
  } else if (k < 10) {
    return dir.string();
  }
  if (std::find(outputs.begin(), outputs.end(), p) == outputs.end()) outputs.push_back(p);
  return p.string();
}

// A fresh folder for a case: its inputs and outputs, nothing else.
fs::path fresh_case_dir(const fs::path& root) {
  const fs::path dir = root / "case";
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

int command_cases() {
  return fuzz_cases(500);
}

// The classes a target tolerates for now (the fixes are under way in other branches), reported
// but not failed; KASHA_FUZZ_STRICT=1 fails them too.
std::set<std::string> known_failing(const std::string& target) {
  // None: every class fails the run. A class a fix is still under way for may be listed here for
  // a while, by target, and is then reported but not failed (KASHA_FUZZ_STRICT=1 fails it too).
  static const std::map<std::string, std::set<std::string>> known = {};
  auto it = known.find(target);
  return it == known.end() ? std::set<std::string>{} : it->second;
}

// The regions and compare scene: three shapes on an 8×6 camera, one of them with a material file.
const char* const kRegionsScene = R"({"kasha_scene": 1,
  "camera": {"position": [0, 0, -2], "look_at": [0, 0, 0], "fov_deg": 60, "width": 8, "height": 6},
  "materials": {
    "white": {"passive": {"reflectance": 0.8}},
    "red": {"passive": {"reflectance": {"nm": [400, 550, 700], "value": [0.1, 0.2, 0.9]}}},
    "paper": {"file": "paper.json", "textures": {"reflectance": "print", "fluorescence": "ink"}},
    "lamp": {"passive": {"reflectance": 0.1}}
  },
  "shapes": [
    {"type": "box", "min": [-2, -2, -2.5], "max": [2, 2, 2], "material": "white", "inward": true},
    {"type": "sphere", "center": [-0.5, 0, 0.5], "radius": 0.6, "material": "red"},
    {"type": "sphere", "center": [0.7, 0.2, 0.3], "radius": 0.4, "material": "paper"},
    {"type": "quad", "corner": [-0.5, 1.99, -0.5], "u": [1, 0, 0], "v": [0, 0, 1],
     "material": "lamp", "emission": "D65"},
    {"type": "obj", "file": "cube.obj", "material": "red",
     "transform": {"scale": 0.3, "translate": [0.2, -0.9, 0.2]}}
  ]})";

// A cube for the scene's "obj" shape.
const char* const kCubeObj = R"(# a unit cube
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 4 7 3
f 4 8 7
f 1 5 8
f 1 8 4
f 2 3 7
f 2 7 6
)";

struct CommandSeeds {
  std::vector<std::string> materials, csvs;
  std::string paper;
};

const CommandSeeds& command_seeds() {
  static const CommandSeeds s = [] {
    CommandSeeds c;
    for (const char* m : {"scenes/materials/brightened_paper.json", "scenes/materials/postit.json"})
      c.materials.push_back(read_text(source_path(m)));
    for (const char* f :
         {"scenes/data/CIE_A_300_780.csv", "scenes/data/CIE_D65_300_780.csv",
          "scenes/data/RIT_Pointer_Philips_TL-84.csv", "scenes/data/uv_blacklight_model.csv"})
      c.csvs.push_back(read_text(source_path(f)));
    c.paper = c.materials[0];
    return c;
  }();
  return s;
}

// Writes an EXR for a case: mostly the scene camera's size, with odd values now and then, and
// binary-mutated when `mutate`.
void write_case_exr(std::mt19937& rng, const fs::path& dir, const std::string& name, bool mutate,
                    std::set<std::string>& inputs) {
  const int w = chance(rng, 0.85) ? 8 : 1 + static_cast<int>(pick(rng, 9));
  const int h = chance(rng, 0.85) ? 6 : 1 + static_cast<int>(pick(rng, 9));
  std::string bytes =
      exr_bytes(make_image(rng, w, h, chance(rng, 0.3)), dir.parent_path() / "seed.exr");
  if (mutate) bytes = mutated_exr(bytes, rng);
  write_text(dir / name, bytes);
  inputs.insert(name);
}

void write_regions_scene(std::mt19937& rng, const fs::path& dir, bool mutate, bool mutate_paper,
                         std::set<std::string>& inputs) {
  std::string scene = kRegionsScene;
  if (chance(rng, 0.05)) {  // a material named with a control byte, printed in the table
    for (size_t at; (at = scene.find("\"red\"")) != std::string::npos;)
      scene.replace(at, 5, "\"r\\u001b[31med\"");
  }
  write_text(dir / "scene.json", mutate ? mutated_json(scene, rng) : scene);
  const std::string& paper = command_seeds().paper;
  write_text(dir / "paper.json", mutate_paper ? mutated_json(paper, rng) : paper);
  write_text(dir / "cube.obj", mutate && chance(rng, 0.3) ? mutated(kCubeObj, rng) : kCubeObj);
  inputs.insert("scene.json");
  inputs.insert("paper.json");
  inputs.insert("cube.obj");
}

}  // namespace

TEST(Fuzz, ColorimetryKeepsTheContract) {
  const fs::path root = scratch_dir();
  const CommandSeeds& seeds = command_seeds();
  Findings findings("colorimetry", root / "case");
  std::mt19937 rng(24001);
  const int cases = command_cases();
  fs::create_directories(root / "capture");
  for (int c = 0; c < cases; ++c) {
    const fs::path dir = fresh_case_dir(root);
    std::set<std::string> inputs = {"material.json"};
    const std::string& material = one_of(seeds.materials, rng);
    const int focus = static_cast<int>(pick(rng, 3));  // the material, the spectra, the options
    write_text(dir / "material.json",
               focus == 0 || chance(rng, 0.1) ? mutated_json(material, rng) : material);
    std::vector<std::string> args = {"colorimetry", (dir / "material.json").string()};
    const int illuminants = static_cast<int>(pick(rng, focus == 1 ? 4 : 2));
    for (int k = 0; k < illuminants; ++k) {
      args.push_back("--illuminant");
      args.push_back(
          spectrum_argument(rng, dir, "lamp" + std::to_string(k) + ".csv", seeds.csvs, inputs));
    }
    const double p = focus == 2 ? 0.6 : 0.2;
    if (chance(rng, p)) {
      args.push_back("--observer");
      args.push_back(number_value({"2", "10", "2", "10", "2", "10", "3", "10.0"}, rng));
    }
    if (chance(rng, p)) {
      args.push_back("--bin-nm");
      args.push_back(number_value({"10", "5", "1", "20", "100", "0.09", "100.0001", "33.3", "7",
                                   "2.5", "1e-9", "0.5", "0.1", "3"},
                                  rng));
    }
    std::vector<fs::path> outputs;
    const bool as_is = chance(rng, focus == 1 ? 0.5 : 0.25);
    if (as_is) {
      args.push_back("--as-is");
      args.push_back(spectrum_argument(rng, dir, "as_is.csv", seeds.csvs, inputs));
    }
    if (chance(rng, as_is ? 0.5 : 0.03)) {
      args.push_back("--write-as-is");
      args.push_back(output_path(rng, dir, "as_is_out.json", inputs, outputs));
    }
    if (chance(rng, 0.4)) {
      args.push_back("--json");
      args.push_back(output_path(rng, dir, "out.json", inputs, outputs));
    }
    if (chance(rng, 0.4)) {
      args.push_back("--csv");
      args.push_back(output_path(rng, dir, "out.csv", inputs, outputs));
    }
    maybe_junk(args, rng);
    run_and_check(findings, rng, dir, args, outputs, inputs);
  }
  findings.report(cases, known_failing("colorimetry"));
}

TEST(Fuzz, RegionsKeepsTheContract) {
  const fs::path root = scratch_dir();
  Findings findings("regions", root / "case");
  std::mt19937 rng(24002);
  const int cases = command_cases();
  fs::create_directories(root / "capture");
  for (int c = 0; c < cases; ++c) {
    const fs::path dir = fresh_case_dir(root);
    std::set<std::string> inputs;
    const int focus = static_cast<int>(pick(rng, 4));  // the scene, its material, the EXRs, options
    write_regions_scene(rng, dir, focus == 0, focus == 1, inputs);
    write_case_exr(rng, dir, "image.exr", focus == 2 && chance(rng, 0.7), inputs);
    std::vector<std::string> args = {"regions", (dir / "scene.json").string(),
                                     (dir / "image.exr").string()};
    if (chance(rng, 0.4)) {
      write_case_exr(rng, dir, "white.exr", focus == 2 && chance(rng, 0.5), inputs);
      args.push_back("--white");
      args.push_back((dir / "white.exr").string());
    }
    if (chance(rng, focus == 3 ? 0.8 : 0.2)) {
      args.push_back("--margin");
      args.push_back(number_value({"0", "1", "2", "0.5", "3", "1048576", "1048577", "100"}, rng));
    }
    std::vector<fs::path> outputs;
    if (chance(rng, 0.5)) {
      args.push_back("--json");
      args.push_back(output_path(rng, dir, "out.json", inputs, outputs));
    }
    maybe_junk(args, rng);
    run_and_check(findings, rng, dir, args, outputs, inputs);
  }
  findings.report(cases, known_failing("regions"));
}

TEST(Fuzz, CompareKeepsTheContract) {
  const fs::path root = scratch_dir();
  Findings findings("compare", root / "case");
  std::mt19937 rng(24003);
  const int cases = command_cases();
  fs::create_directories(root / "capture");
  for (int c = 0; c < cases; ++c) {
    const fs::path dir = fresh_case_dir(root);
    std::set<std::string> inputs;
    const int focus = static_cast<int>(pick(rng, 3));  // the image, the reference, the scene
    write_case_exr(rng, dir, "image.exr", focus == 0, inputs);
    write_case_exr(rng, dir, "reference.exr", focus == 1, inputs);
    std::vector<std::string> args = {"compare", (dir / "image.exr").string(),
                                     (dir / "reference.exr").string()};
    if (focus == 2 || chance(rng, 0.3)) {
      write_regions_scene(rng, dir, focus == 2, focus == 2 && chance(rng, 0.3), inputs);
      args.push_back("--scene");
      args.push_back((dir / "scene.json").string());
    }
    maybe_junk(args, rng);
    run_and_check(findings, rng, dir, args, {}, inputs);
  }
  findings.report(cases, known_failing("compare"));
}

TEST(Fuzz, PreviewKeepsTheContract) {
  const fs::path root = scratch_dir();
  Findings findings("preview", root / "case");
  std::mt19937 rng(24004);
  const int cases = command_cases();
  fs::create_directories(root / "capture");
  for (int c = 0; c < cases; ++c) {
    const fs::path dir = fresh_case_dir(root);
    std::set<std::string> inputs;
    write_case_exr(rng, dir, "image.exr", chance(rng, 0.7), inputs);
    std::vector<fs::path> outputs;
    std::vector<std::string> args = {"preview", (dir / "image.exr").string(), "-o",
                                     output_path(rng, dir, "out.png", inputs, outputs)};
    if (chance(rng, 0.5)) {
      args.push_back("--scale");
      args.push_back(number_value(
          {"1", "0.5", "1e-300", "1e300", "1e30", "1e-30", "1e301", "4.9e-324", "100"}, rng));
    }
    maybe_junk(args, rng);
    run_and_check(findings, rng, dir, args, outputs, inputs);
  }
  findings.report(cases, known_failing("preview"));
}

TEST(Fuzz, DeltaEKeepsTheContract) {
  const fs::path root = scratch_dir();
  Findings findings("delta-e", root / "case");
  std::mt19937 rng(24005);
  const int cases = command_cases();
  fs::create_directories(root / "capture");
  const std::vector<std::string> labs = {
      "50,2.6772,-79.7751", "50,0,-82.7485",     "0,0,0",      "100,0,0",         "50,0.0001,0",
      "50,-0.0001,0",       "1e308,1e308,1e308", "-1e308,0,0", "50,1e300,-1e300", "50,1e-320,0",
      "50,2.5,0",           "50,-2.5,-0"};
  for (int c = 0; c < cases; ++c) {
    const fs::path dir = fresh_case_dir(root);
    std::vector<std::string> args = {"delta-e"};
    for (int k = 0; k < 2; ++k) {
      std::string lab = one_of(labs, rng);
      if (chance(rng, 0.6)) lab = mutated(lab, rng);
      args.push_back(lab);
    }
    maybe_junk(args, rng);
    run_and_check(findings, rng, dir, args, {}, {});
  }
  findings.report(cases, known_failing("delta-e"));
}
