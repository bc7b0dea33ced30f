// Bad input of every class, end to end: exit code 1, exactly one `kasha: error:` line whose WHERE
// names the file (with its JSON path or line, or the option), input bytes escaped, and no file
// written. One table row per class; each row builds its inputs in a fresh scratch folder.
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "film/image.h"
#include "image/exr_io.h"
#include "simulated_instrument.h"
#include "test_support.h"

using namespace kasha;
namespace fs = std::filesystem;

namespace {

using test::shell_quoted;

// A small lit scene whose parts the cases replace: `material` is the material's JSON, `shape`
// the one shape's.
std::string scene_json(const std::string& material = R"({"passive": {"reflectance": 0.5}})",
                       const std::string& shape = R"({"type": "quad", "corner": [-1, -1, 0],
      "u": [2, 0, 0], "v": [0, 2, 0], "material": "m", "emission": "E"})") {
  return R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0], "width": 8, "height": 8},
    "materials": {"m": )" +
         material + R"(},
    "shapes": [)" +
         shape + "]}";
}

// An EEM in the layout of docs/formats.md#measurement-csv from a function of (emission, excitation)
// wavelengths.
std::string eem_csv(const std::vector<double>& ex, const std::vector<double>& em,
                    const std::function<double(double, double)>& value) {
  std::string s = "em\\ex";
  for (double l : ex) s += "," + std::to_string(l);
  s += "\n";
  for (double o : em) {
    s += std::to_string(o);
    for (double i : ex) s += "," + std::to_string(value(o, i));
    s += "\n";
  }
  return s;
}

std::vector<double> range_nm(double from, double to, double step) {
  std::vector<double> out;
  for (double l = from; l <= to + 1e-9; l += step) out.push_back(l);
  return out;
}

// The simulated fluorimeter's sample, etalon and reflectance files; returns the measure options.
std::string instrument_files(const std::string& d) {
  using namespace kasha::test;
  return write_instrument_files(d, Instrument::typical(false), brightened_paper());
}

// An EXR with R, G, B and one more channel named `extra` (bytes the project's writer never makes).
void write_exr_with_channel(const std::string& path, int size, const std::string& extra) {
  std::vector<float> pixels(static_cast<size_t>(size) * size, 0.5f);
  Imf::Header header(size, size);
  Imf::FrameBuffer fb;
  for (const std::string& name : {std::string("R"), std::string("G"), std::string("B"), extra}) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(pixels.data()), sizeof(float),
                               sizeof(float) * size));
  }
  Imf::OutputFile file(path.c_str(), header);
  file.setFrameBuffer(fb);
  file.writePixels(size);
}

struct Case {
  const char* name;
  // Writes the inputs into the folder and returns the arguments; OUT stands for the output path.
  std::function<std::string(const std::string& dir)> setup;
  std::vector<std::string> expected;  // substrings of the line: WHERE first, then what
};

std::string write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string render(const std::string& scene) {
  return "render " + shell_quoted(scene) + " --passes 1 -o OUT";
}

std::string measure(const std::string& options) {
  return "measure " + options + " -o OUT";
}

const std::vector<Case>& cases() {
  static const std::vector<Case> table = {
      // Input files that are not regular files.
      {"SceneIsADirectory",
       [](const std::string& d) {
         fs::create_directory(d + "/scene.json");
         return render(d + "/scene.json");
       },
       {"scene.json: is a directory, not a file"}},
      {"SceneIsAFifo",
       [](const std::string& d) {
         mkfifo((d + "/fifo.json").c_str(), 0600);
         return render(d + "/fifo.json");
       },
       {"fifo.json: is a FIFO (pipe), not a file"}},
      {"SceneIsDevZero",
       [](const std::string&) { return render("/dev/zero"); },
       {"/dev/zero: is a character device, not a file"}},
      {"CsvIsDevZero",
       [](const std::string& d) {
         return render(write(d + "/s.json", scene_json(R"({"passive": {"reflectance":
             {"csv": "/dev/zero"}}})")));
       },
       {"/dev/zero: is a character device, not a file"}},
      {"CsvIsAFifo",
       [](const std::string& d) {
         mkfifo((d + "/fifo.csv").c_str(), 0600);
         return render(write(d + "/s.json", scene_json(R"({"passive": {"reflectance":
             {"csv": "fifo.csv"}}})")));
       },
       {"fifo.csv: is a FIFO (pipe), not a file"}},
      {"CsvIsADirectory",
       [](const std::string& d) {
         fs::create_directory(d + "/table.csv");
         return render(write(d + "/s.json", scene_json(R"({"passive": {"reflectance":
             {"csv": "table.csv"}}})")));
       },
       {"table.csv: is a directory, not a file"}},
      {"CsvNameIsEmpty",
       [](const std::string& d) {
         return render(write(d + "/s.json", scene_json(R"({"passive": {"reflectance":
             {"csv": ""}}})")));
       },
       {"s.json: /materials/m/passive/reflectance/csv: empty file name"}},
      {"ObjIsADirectory",
       [](const std::string& d) {
         fs::create_directory(d + "/mesh.obj");
         return render(write(d + "/s.json", scene_json(R"({"passive": {"reflectance": 0.5}})",
                                                       R"({"type": "obj", "file": "mesh.obj",
                                                           "material": "m", "emission": "E"})")));
       },
       {"mesh.obj: is a directory, not a file"}},
      {"MaterialIsADirectory",
       [](const std::string& d) {
         fs::create_directory(d + "/paper.json");
         return render(write(d + "/s.json", scene_json(R"({"file": "paper.json"})")));
       },
       {"paper.json: is a directory, not a file"}},
      {"CsvOverTheSizeLimit",
       [](const std::string& d) {
         // Sparse: the size is what is checked, before anything is read.
         write(d + "/big.csv", "nm,value\n");
         fs::resize_file(d + "/big.csv", (std::uintmax_t(64) << 20) + 1);
         return render(write(d + "/s.json", scene_json(R"({"passive": {"reflectance":
             {"csv": "big.csv"}}})")));
       },
       {"big.csv: the file is 67108865 bytes, over the 64 MiB"}},
      {"MeasureSampleIsDevZero",
       [](const std::string& d) {
         std::string good = instrument_files(d);
         return measure(good.replace(good.find(d + "/s.csv"), d.size() + 6, "/dev/zero"));
       },
       {"/dev/zero: is a character device, not a file"}},
      {"MeasureSampleIsADirectory",
       [](const std::string& d) {
         fs::create_directory(d + "/dir.csv");
         return measure("--bispectral " + d + "/dir.csv");
       },
       {"dir.csv: is a directory, not a file"}},
      // Strict JSON.
      {"DuplicateKey",
       [](const std::string& d) {
         return render(write(d + "/s.json", R"({"kasha_scene": 1,
           "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0], "width": 8, "width": 16},
           "materials": {}, "shapes": []})"));
       },
       {"s.json: /camera/width: duplicate key \"width\""}},
      {"DuplicateKeyInAnArrayElement",
       [](const std::string& d) {
         return render(
             write(d + "/s.json", scene_json(R"({"passive": {"reflectance": 0.5}})",
                                             R"({"type": "sphere", "center": [0, 0, 0], "radius": 1,
                                            "material": "m"}, {"type": "sphere", "radius": 1,
                                            "center": [0, 0, 0], "radius": 2, "material": "m"})")));
       },
       {"s.json: /shapes/1/radius: duplicate key"}},
      {"NumberOverflow",
       [](const std::string& d) {
         return render(write(d + "/s.json", scene_json(R"({"passive": {"reflectance": 1e400}})")));
       },
       {"s.json: malformed JSON: ", "1e400"}},
      // OBJ lines.
      {"ObjIndexBeyond32Bits",
       [](const std::string& d) {
         write(d + "/mesh.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4294967297\n");
         return render(write(d + "/s.json", scene_json(R"({"passive": {"reflectance": 0.5}})",
                                                       R"({"type": "obj", "file": "mesh.obj",
                                                           "material": "m"})")));
       },
       {"mesh.obj: line 4: face vertex \"4294967297\" names no vertex"}},
      {"ObjVertexWithOneCoordinate",
       [](const std::string& d) {
         write(d + "/mesh.obj", "v 1\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
         return render(write(d + "/s.json", scene_json(R"({"passive": {"reflectance": 0.5}})",
                                                       R"({"type": "obj", "file": "mesh.obj",
                                                           "material": "m"})")));
       },
       {"mesh.obj: line 1: a vertex needs x, y and z"}},
      // Messages that must name their file.
      {"NoEmitterWithPower",
       [](const std::string& d) {
         return render(write(d + "/dark.json",
                             scene_json(R"({"passive": {"reflectance": 0.5}})",
                                        R"({"type": "quad", "corner": [-1, -1, 0], "u": [2, 0, 0],
                                            "v": [0, 2, 0], "material": "m",
                                            "emission": {"line_nm": 150}})"))) +
                " --integrator photon";
       },
       {"dark.json: no emitter has power"}},
      {"ReferenceOfAnotherSize",
       [](const std::string& d) {
         Image ref;
         ref.width = ref.height = 4;
         ref.xyz.assign(3 * 16, 0.5f);
         write_exr(d + "/ref.exr", ref);
         return render(write(d + "/s.json", scene_json())) + " --reference " + d + "/ref.exr";
       },
       {"ref.exr: the reference is 4x4 but the image is 8x8"}},
      {"EnergyGainNamesTheSample",
       [](const std::string& d) {
         using namespace kasha::test;
         Instrument in = Instrument::typical(false);
         write_instrument_files(d, in, brightened_paper());
         TrueMaterial hot = brightened_paper();
         hot.rho = [](double) { return 0.9; };
         write_eem_csv(d + "/hot.csv", in.measure(hot, nullptr, "hot.csv"));
         return measure("--sample " + d + "/hot.csv --etalon " + d +
                        "/e.csv --etalon-reflectance " + d + "/rho.csv");
       },
       {"hot.csv: energy gain at "}},
      {"ZeroSensitivityNamesItsFile",
       [](const std::string& d) {
         std::string good = instrument_files(d);
         write(d + "/narrow.csv", "nm,c\n500,1\n600,1\n");
         return measure(good.substr(0, good.find(" --sensitivity")) + " --sensitivity " + d +
                        "/narrow.csv");
       },
       {"narrow.csv: detector sensitivity is zero at "}},
      // Bytes from input, escaped when echoed.
      {"EscapeSequenceInACsvCell",
       [](const std::string& d) {
         write(d + "/esc.csv", "nm,value\n400,0.5\n500,\x1b[2J0.5\r\n");
         return render(write(d + "/s.json", scene_json(R"({"passive": {"reflectance":
             {"csv": "esc.csv"}}})")));
       },
       {"esc.csv: line 3, column 2: not a number: \"\\x1B[2J0.5\""}},
      {"EscapeSequenceInAnExrChannelName",
       [](const std::string& d) {
         write_exr_with_channel(d + "/ref.exr", 8, "S0.\x1b]0;owned\x07\rnm");
         return render(write(d + "/s.json", scene_json())) + " --reference " + d + "/ref.exr";
       },
       {"ref.exr: channel \"S0.\\x1B]0;owned\\x07\\x0Dnm\": not a spectral channel name"}},
      // Accepted before, invalid: a JASCO matrix over wavenumber.
      {"JascoMatrixIn1PerCm",
       [](const std::string& d) {
         std::string good = instrument_files(d);
         write(d + "/raman.txt",
               "TITLE\tEEM\r\nXUNITS\t1/CM\r\nNPOINTS\t3\r\nXYDATA\r\n\t350\t360\r\n"
               "420\t0.5\t0.25\r\n410\t1.5\t1.25\r\n400\t2\t3\r\n");
         return measure("--bispectral " + d + "/raman.txt");
       },
       {"raman.txt: x units are 1/CM, not NANOMETERS"}},
      // Measure's own checks: nothing that would become a material kasha refuses.
      {"MeasureAllZeroMatrix",
       [](const std::string& d) {
         write(d + "/zero.csv", eem_csv(range_nm(300, 500, 10), range_nm(300, 600, 5),
                                        [](double, double) { return 0.0; }));
         return measure("--bispectral " + d + "/zero.csv");
       },
       {"zero.csv: no reading is above zero (all zero)"}},
      {"MeasureAllNegativeReadings",
       [](const std::string& d) {
         std::string good = instrument_files(d);
         write(d + "/neg.csv", eem_csv(range_nm(300, 500, 10), range_nm(300, 600, 5),
                                       [](double, double) { return -0.25; }));
         return measure(good.replace(good.find(d + "/s.csv"), d.size() + 6, d + "/neg.csv"));
       },
       {"neg.csv: no reading is above zero (all zero or negative)"}},
      {"MeasureOneExcitationColumn",
       [](const std::string& d) {
         write(d + "/one.csv", eem_csv({400}, range_nm(300, 600, 5),
                                       [](double o, double i) { return o == i ? 1.0 : 0.01; }));
         return measure("--bispectral " + d + "/one.csv");
       },
       {"one.csv: only one excitation wavelength"}},
      {"MeasureBandWiderThanTheEmissionRange",
       [](const std::string& d) { return measure(instrument_files(d) + " --band-nm 999"); },
       {"--band-nm 999 nm: the band must be narrower than the emission range of ", "s.csv"}},
  };
  return table;
}

std::set<std::string> files_in(const std::string& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name != "stdout.txt" && name != "stderr.txt") out.insert(e.path().string());
  }
  return out;
}

class InputSafety : public ::testing::TestWithParam<Case> {};

TEST_P(InputSafety, OneLineNamingTheFileAndNothingWritten) {
  const Case& c = GetParam();
  const std::string dir = test::scratch_dir().string();
  fs::create_directories(dir);
  std::string args = c.setup(dir);
  const std::string out =
      dir + (args.rfind("render", 0) == 0 ? "/out/result.exr" : "/out/result.json");
  fs::create_directories(dir + "/out");
  for (size_t at; (at = args.find("OUT")) != std::string::npos;) args.replace(at, 3, out);
  const std::set<std::string> before = files_in(dir);
  // A guard against a hang (a FIFO read without end): Ctrl-C after 60 s gives 130, not 1.
  const test::CommandResult r = test::run_kasha_env("", args, 60);
  RecordProperty("message", r.err);  // the line, in --gtest_output=xml, for review
  EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("kasha: error: ", 0), 0u) << r.err;
  for (const std::string& part : c.expected)
    EXPECT_NE(r.err.find(part), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("json.exception"), std::string::npos) << r.err;
  // No byte that could move the cursor or end the line early.
  EXPECT_TRUE(std::none_of(r.err.begin(), r.err.end() - 1, [](char ch) {
    return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f;
  })) << r.err;
  EXPECT_EQ(files_in(dir), before) << "a file was written";
  EXPECT_FALSE(fs::exists(out));
}

INSTANTIATE_TEST_SUITE_P(EveryClass, InputSafety, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return std::string(info.param.name); });

}  // namespace

// The other side of measure's checks: a sample that reflects and does not fluoresce (nothing off
// the band) gives a passive material that a scene loads, not an all-zero emission it refuses.
TEST(InputSafetyMeasure, ASampleWithoutFluorescenceGivesALoadableMaterial) {
  const std::string d = test::scratch_dir().string();
  write(d + "/diag.csv", eem_csv(range_nm(400, 500, 10), range_nm(400, 500, 5),
                                 [](double o, double i) { return o == i ? 0.5 : 0.0; }));
  auto r = test::run_kasha("measure --bispectral " + d + "/diag.csv -o " + d + "/m.json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::string scene = write(d + "/s.json", scene_json(R"({"file": "m.json"})"));
  r = test::run_kasha("info " + shell_quoted(scene));
  EXPECT_EQ(r.exit_code, 0) << r.err;
}
