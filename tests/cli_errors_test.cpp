// The command line's error path: every bad command line is one line `kasha: error: WHERE: …` with
// exit code 2 and writes nothing; input and run errors exit 1; SIGINT and SIGTERM exit 130, at any
// moment (kernel compilation included), with the image so far when there is one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "cli/command_line_errors.h"
#include "image/exr_io.h"
#include "opencl/device_list.h"
#include "test_support.h"

using namespace kasha;
namespace fs = std::filesystem;

namespace {

std::string quoted(const std::string& s) {
  return "'" + s + "'";
}

// Replaces each {name} in `text` by vars[name].
std::string expand(std::string text, const std::vector<std::pair<std::string, std::string>>& vars) {
  for (const auto& [name, value] : vars)
    for (size_t at; (at = text.find("{" + name + "}")) != std::string::npos;)
      text.replace(at, name.size() + 2, value);
  return text;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// A CLI11 error kept with its own type (translation looks at it).
template <typename E>
std::shared_ptr<CLI::ParseError> held(E e) {
  return std::make_shared<E>(std::move(e));
}

bool empty_dir(const fs::path& dir) {
  return fs::is_directory(dir) && fs::directory_iterator(dir) == fs::directory_iterator();
}

struct Case {
  std::string args;   // {scene}: a good scene; {out}: the scratch folder that must stay empty
  int exit_code;      // 2: usage, 1: input or run error
  std::string where;  // expected after "kasha: error: " (a prefix of the rest of the line)
};

// Runs `args` with `signal` sent after `after_s` seconds (fractions allowed) to kasha's process
// group, as a terminal does for Ctrl-C (test_support.h).
test::CommandResult run_with_signal(const std::string& env, const std::string& args,
                                    const char* signal, double after_s) {
  return test::run_kasha_signalled(env, args, signal, after_s);
}

// Runs each case with {out} (an empty folder that must stay empty) and `vars` expanded in its
// arguments and in its expected WHERE: one line, the exit code, nothing on stdout, nothing written.
void expect_cases(const std::vector<Case>& cases,
                  std::vector<std::pair<std::string, std::string>> vars, const fs::path& out) {
  vars.push_back({"out", out.string()});
  for (const Case& c : cases) {
    const std::string args = expand(c.args, vars);
    test::CommandResult r = test::run_kasha(args);
    SCOPED_TRACE("kasha " + args);
    EXPECT_EQ(r.exit_code, c.exit_code) << r.err;
    const std::vector<std::string> err = lines(r.err);
    ASSERT_EQ(err.size(), 1u) << r.err;
    EXPECT_EQ(err[0].rfind("kasha: error: " + expand(c.where, vars), 0), 0u) << err[0];
    EXPECT_EQ(r.out, "") << "printed before the error was known";
    EXPECT_TRUE(empty_dir(out)) << "something was written";
    fs::remove_all(out);
    fs::create_directories(out);
  }
}

}  // namespace

TEST(CliErrors, EveryBadCommandLineIsOneLineWithExitCode2AndNoOutput) {
  const fs::path out = test::scratch_dir() / "out";
  fs::create_directories(out);
  const std::string scene = test::source_path("scenes/torus.json");
  const std::string render = "render {scene} -o {out}/a.exr ";
  const std::string converge = "converge {scene} -o {out}/c --time 1 ";
  const std::string measure = "measure --bispectral {scene} -o {out}/m.json ";
  const std::vector<Case> cases = {
      // subcommands and options
      {"", 2, "command line: give a subcommand: devices, info, render"},
      {"rendr {scene}", 2, "rendr: unknown subcommand (did you mean render?)"},
      {"--bogus", 2, "--bogus: unknown option of kasha"},
      {"render {scene} --passes 1 --tim 5 -o {out}/a.exr", 2,
       "--tim: unknown option of kasha render (did you mean --time?)"},
      {"render {scene} --passes 1 -o {out}/a.exr extra.json", 2,
       "extra.json: unexpected argument to kasha render"},
      {"render {scene} --passes 1", 2, "--output: required (see kasha render --help)"},
      {"render --passes 1 -o {out}/a.exr", 2, "scene: required"},
      {render + "--time", 2, "--time: a value is required"},
      {render + "--integrator bogus --passes 1", 2, "--integrator: \"bogus\" is not one of"},
      {render + "--sampler sobl --passes 1", 2,
       "--sampler: \"sobl\" is not one of sobol, independent (did you mean sobol?)"},
      {"render {scene} -o {out}/a.exr", 2, "render: give --time SECONDS or --passes N"},
      {render + "--integrator backward --photons 5 --passes 1", 2,
       "--photons: the backward integrator does not take this option (it takes --spp)"},
      // finite numbers (--time nan used to hang)
      {render + "--time nan", 2, "--time: nan is not a finite number"},
      {render + "--time inf", 2, "--time: inf is not a finite number"},
      {render + "--time -inf", 2, "--time: -inf is not a finite number"},
      {render + "--time -5", 2, "--time: -5 is not positive"},
      {render + "--time 1e308", 2, "--time: 1e308 is more than 1e+09"},
      {render + "--time abc", 2, "--time: \"abc\" is not a number"},
      {render + "--passes 1 --radius nan", 2, "--radius: nan is not a finite number"},
      {render + "--passes 1 --radius -1", 2, "--radius: -1 is not positive"},
      {render + "--passes 1 --alpha nan", 2, "--alpha: nan is not a finite number"},
      {render + "--passes 1 --alpha 1", 2, "--alpha: 1 is not in [0.01, 0.99]"},
      // integers
      {render + "--passes 1.5", 2, "--passes: \"1.5\" is not an integer"},
      {render + "--passes 0", 2, "--passes: 0 is not in [1, 2147483647]"},
      {render + "--passes 1 --photons -1", 2, "--photons: -1 is not in [1, 2147483647]"},
      {render + "--passes 1 --photons 2147483648", 2, "--photons: 2147483648 is not in"},
      {render + "--passes 1 --photons 1e6", 2, "--photons: \"1e6\" is not an integer"},
      {render + "--passes 1 --spp 0", 2, "--spp: 0 is not in [1, 1048576]"},
      {render + "--passes 1 --seed -1", 2, "--seed: -1 is not in [0, 4294967295]"},
      {render + "--passes 1 --device -1", 2, "--device: \"-1\" is not a device index"},
      {render + "--passes 1 --device 0,", 2, "--device: give a device index, indices separated"},
      {render + "--passes 1 --device 0,,1", 2, "--device: \"\" is not a device index"},
      {render + "--passes 1 --device al", 2, "--device: \"al\" is not a device index"},
      {render + "--passes 1 --memory 0", 2, "--memory: 0 is not in"},
      {render + "--passes 1 --depth-guard 0", 2, "--depth-guard: 0 is not in"},
      {render + "--passes 1 --max-depth -1", 2,
       "--max-depth: -1 is not in [0, 1073741824] (or scene)"},
      {render + "--passes 1 --max-depth deep", 2,
       "--max-depth: \"deep\" is not an integer (or scene)"},
      // the path as given, unquoted: DepthCap.TheSceneCapIsThePbrtIntegratorsMaxdepth checks the rest
      {render + "--passes 1 --max-depth scene", 2, "--max-depth: scene: /"},
      // measure
      {measure + "--band-nm nan", 2, "--band-nm: nan is not a finite number"},
      {measure + "--band-nm 1e300", 2, "--band-nm: 1e300 is more than 1000"},
      {measure + "--cone-deg nan", 2, "--cone-deg: nan is not a finite number"},
      {measure + "--name '\xff'", 2, "--name: \"\\xFF\" is not valid UTF-8"},
      {"measure -o {out}/m.json --sample {scene} --bispectral {scene}", 2,
       "--sample: cannot be given with --bispectral"},
      {"measure -o {out}/m.json --etalon {scene}", 2, "measure: give --sample, --etalon and"},
      // converge
      {converge + "--spp 0", 2, "--spp: 0 is not in"},
      {converge + "--reference-time -5", 2, "--reference-time: -5 is not positive"},
      {converge + "--target -1", 2, "--target: -1 is not positive"},
      {converge + "--integrators photon,photon", 2, "--integrators: \"photon\" is given twice"},
      {converge + "--integrators photon,bogus", 2, "--integrators: unknown integrator \"bogus\""},
      {converge + "--integrators photon,", 2, "--integrators: give a comma-separated list"},
      {converge + "--repeats 0", 2, "--repeats: 0 is not in"},
      {"converge {scene} -o {out}/c --time nan", 2, "--time: nan is not a finite number"},
      {"converge {scene} -o {out}/c", 2, "--time: required"},
      // the other subcommands
      {"reference {scene} -o {out}/r.exr --time nan", 2, "--time: nan is not a finite number"},
      {"colorimetry {scene} --observer 5", 2, "--observer: \"5\" is not one of 2, 10"},
      {"colorimetry {scene} --bin-nm nan", 2, "--bin-nm: nan is not a finite number"},
      {"preview {scene} -o {out}/p.png --scale nan", 2, "--scale: nan is not a finite number"},
      {"regions {scene} {scene} --margin nan", 2, "--margin: nan is not a finite number"},
      {"info {scene} --spectral=abc", 2, "--spectral: \"abc\" is not true or false"},
      // delta-e: each colour three finite numbers within the documented range (they used to exit 1
      // as input errors; 1e308 printed -nan)
      {"delta-e 50,0,0 50,0", 2, "lab2: \"50,0\" is not L*,a*,b* (three numbers separated by"},
      {"delta-e 50,0 50,0,0", 2, "lab1: \"50,0\" is not L*,a*,b*"},
      {"delta-e 50,0,0 50", 2, "lab2: \"50\" is not L*,a*,b*"},
      {"delta-e 50,0,0 50,0,0,", 2, "lab2: \"50,0,0,\" is not L*,a*,b*"},
      {"delta-e 50,0,0 50,0,0,0", 2, "lab2: \"50,0,0,0\" is not L*,a*,b*"},
      {"delta-e 50,0,0 '50;0;0'", 2, "lab2: \"50;0;0\" is not L*,a*,b*"},
      {"delta-e 50,0,0 abc", 2, "lab2: \"abc\" is not L*,a*,b*"},
      {"delta-e 50,0,0 ,0,0", 2, "lab2: L* is empty in \",0,0\""},
      {"delta-e 50,0,0 50,,0", 2, "lab2: a* is empty in \"50,,0\""},
      {"delta-e 50,0,0 50,0,", 2, "lab2: b* is empty in \"50,0,\""},
      {"delta-e 50,0,0 ,,", 2, "lab2: L* is empty in \",,\""},
      {"delta-e 50,0,0 50,x,0", 2, "lab2: a* \"x\" is not a number"},
      {"delta-e 50,0,0 '50,0,1 2'", 2, "lab2: b* \"1 2\" is not a number"},
      {"delta-e nan,0,0 50,0,0", 2, "lab1: L* nan is not a finite number"},
      {"delta-e 50,0,0 50,inf,0", 2, "lab2: a* inf is not a finite number"},
      {"delta-e 50,0,0 50,0,-inf", 2, "lab2: b* -inf is not a finite number"},
      {"delta-e 50,0,0 50,0,1e999", 2, "lab2: b* 1e999 is not a finite number"},
      {"delta-e 50,0,0 1e308,0,0", 2, "lab2: L* 1e308 is not in [0, 10000]"},
      {"delta-e 50,0,0 50,-1e5,0", 2, "lab2: a* -1e5 is not in [-10000, 10000]"},
      {"delta-e 50,0,0 -- -1,0,0", 2, "lab2: L* -1 is not in [0, 10000]"},
      {"delta-e 50,0,0 ''", 2, "lab2: the value is empty"},
      {"delta-e 50,0,0", 2, "lab2: required"},
      {"delta-e 50,0,0 50,0,0 1,2,3", 2, "1,2,3: unexpected argument to kasha delta-e"},
      // input errors: exit 1, bytes from the command line escaped
      {"render /nonexistent.json --passes 1 -o {out}/a.exr", 1, "/nonexistent.json: "},
      {"render '/nonexistent\xff\x1b.json' --passes 1 -o {out}/a.exr", 1,
       "/nonexistent\\xFF\\x1B.json: "},
  };
  expect_cases(cases, {{"scene", quoted(scene)}}, out);
}

// A value that is not there is a usage error before any work: an option given twice, an empty
// value (which would read as not given, or fail only once the image is rendered) or another option
// taken as the value.
TEST(CliErrors, RepeatedEmptyAndMissingValuesAreUsageErrors) {
  const fs::path out = test::scratch_dir() / "out";
  fs::create_directories(out);
  const std::string scene = test::source_path("scenes/torus.json");
  std::string devices = "0";
  for (size_t k = 1; k <= kMaxDeviceListEntries; ++k) devices += ",0";
  const std::vector<Case> cases = {
      {"render {scene} --passes 1 --passes 2 -o {out}/a.exr", 2,
       "--passes: given 2 times; give it once"},
      {"render {scene} --passes 1 -o {out}/a.exr -o {out}/b.exr", 2,
       "--output: given 2 times; give it once"},
      {"render {scene} --time= -o {out}/a.exr", 2, "--time: a value is required (-o is an option)"},
      {"render {scene} --passes 1 -o {out}/a.exr --lamp --png", 2,
       "--lamp: a value is required (--png is an option)"},
      {"render {scene} --passes 1 -o ''", 2, "--output: the value is empty"},
      {"render {scene} --passes 1 -o {out}/a.exr --lamp ''", 2, "--lamp: the value is empty"},
      {"render {scene} --passes 1 -o {out}/a.exr --time ''", 2, "--time: the value is empty"},
      {"render '' --passes 1 -o {out}/a.exr", 2, "scene: the value is empty"},
      {"reference {scene} --time 1 -o ''", 2, "--output: the value is empty"},
      {"regions {scene} {scene} --json ''", 2, "--json: the value is empty"},
      {"compare {scene} {scene} --scene ''", 2, "--scene: the value is empty"},
      {"colorimetry {scene} --write-as-is {out}/w.json", 2, "--write-as-is: needs --as-is"},
      {"render {scene} --passes 1 -o {out}/a.exr --device " + devices, 2,
       "--device: more than 64 devices in the list"},
  };
  for (const Case& c : cases) {
    const std::string args = expand(c.args, {{"scene", quoted(scene)}, {"out", out.string()}});
    test::CommandResult r = test::run_kasha(args);
    SCOPED_TRACE("kasha " + args.substr(0, 200));
    EXPECT_EQ(r.exit_code, c.exit_code) << r.err;
    const std::vector<std::string> err = lines(r.err);
    ASSERT_EQ(err.size(), 1u) << r.err;
    EXPECT_EQ(err[0].rfind("kasha: error: " + c.where, 0), 0u) << err[0];
    EXPECT_TRUE(empty_dir(out)) << "something was written";
  }
}

// Every parse error CLI11 can raise (each of its error classes and their factories, CLI11 2.1)
// becomes kasha's `WHERE: what` in kasha's words, none in CLI11's.
TEST(CliErrors, EveryKindOfCli11ErrorIsTranslated) {
  CLI::App app{"kasha"};
  CLI::App* render = app.add_subcommand("render", "");
  double time = 0;
  bool flag = false;
  render->add_option("--time", time, "");
  render->add_flag("--spectral", flag, "");
  app.parse(std::vector<std::string>{"render"});  // the subcommand the errors belong to
  const std::vector<std::pair<std::shared_ptr<CLI::ParseError>, std::string>> cases = {
      {held(CLI::ConversionError("--time", std::vector<std::string>{"abc"})),
       "--time: \"abc\" is not a number"},
      {held(CLI::ConversionError("abc", "--time")), "--time: \"abc\" is not a number"},
      {held(CLI::ConversionError("--time", std::vector<std::string>{""})),
       "--time: the value is empty"},
      {held(CLI::ConversionError::TooManyInputsFlag("--spectral")),
       "--spectral: a flag takes no value"},
      {held(CLI::ConversionError::TrueFalse("--spectral")), "--spectral: a flag takes no value"},
      {held(CLI::ValidationError("--time", "5 is too long")), "--time: 5 is too long"},
      {held(CLI::RequiredError("--time")), "--time: required (see kasha render --help)"},
      {held(CLI::RequiredError::Subcommand(1)), "kasha render: give a subcommand"},
      {held(CLI::RequiredError::Subcommand(2)), "kasha render: give a subcommand"},
      {held(CLI::RequiredError::Option(1, 1, 0, "--a, --b")),
       "kasha render: give exactly one of --a, --b"},
      {held(CLI::RequiredError::Option(1, 1, 2, "--a, --b")),
       "kasha render: give exactly one of --a, --b"},
      {held(CLI::RequiredError::Option(1, 3, 0, "--a, --b")),
       "kasha render: give at least one of --a, --b"},
      {held(CLI::RequiredError::Option(2, 3, 1, "--a, --b")),
       "kasha render: give at least 2 of --a, --b"},
      {held(CLI::RequiredError::Option(0, 1, 2, "--a, --b")),
       "kasha render: give at most 1 of --a, --b"},
      {held(CLI::RequiredError::Option(0, 2, 3, "--a, --b")),
       "kasha render: give at most 2 of --a, --b"},
      {held(CLI::ArgumentMismatch("--time", 1, 0)), "--time: a value is required"},
      {held(CLI::ArgumentMismatch("--time", -2, 1)), "--time: a value is required"},
      {held(CLI::ArgumentMismatch::AtLeast("--time", 2, 1)), "--time: at least 2 values, got 1"},
      {held(CLI::ArgumentMismatch::AtMost("--time", 1, 3)), "--time: given 3 times; give it once"},
      {held(CLI::ArgumentMismatch::AtMost("--time", 2, 3)), "--time: at most 2 values, got 3"},
      {held(CLI::ArgumentMismatch::TypedAtLeast("--time", 1, "FLOAT")),
       "--time: a value is required"},
      {held(CLI::ArgumentMismatch::FlagOverride("--spectral")),
       "--spectral: a flag takes no value"},
      {held(CLI::RequiresError("--time", "--spectral")), "--time: needs --spectral"},
      {held(CLI::ExcludesError("--time", "--spectral")), "--time: cannot be given with --spectral"},
      {held(CLI::ExtrasError(std::vector<std::string>{"extra.json"})),
       "extra.json: unexpected argument to kasha render"},
      {held(CLI::ExtrasError("render", std::vector<std::string>{"--bogus"})),
       "--bogus: unknown option of kasha render"},
      {held(CLI::FileError::Missing("kasha.ini")),
       "kasha render: a configuration file is not taken"},
      {held(CLI::ConfigError::Extras("x")), "kasha render: a configuration file is not taken"},
      {held(CLI::ConfigError::NotConfigurable("--time")),
       "kasha render: a configuration file is not taken"},
      {held(CLI::InvalidError("scene")), "kasha render: the command line could not be read"},
      {held(CLI::HorribleError("x")), "kasha render: the command line could not be read"},
      {held(CLI::RuntimeError()), "kasha render: the command line could not be read"},
  };
  for (const auto& [error, expected] : cases) {
    SCOPED_TRACE(error->what());
    const std::string line = cli::parse_error_line(app, *error);
    EXPECT_EQ(line.rfind(expected, 0), 0u) << line;
    // A validation error is ours already (`NAME: what`, worded by kasha's validators).
    if (!dynamic_cast<const CLI::ValidationError*>(error.get())) {
      EXPECT_EQ(line.find(error->what()), std::string::npos) << "CLI11's own words: " << line;
    }
  }
}

TEST(CliErrors, HelpAndVersionPrintNormallyWithExitCode0) {
  for (const char* args : {"--help", "render --help", "converge --help", "--version"}) {
    test::CommandResult r = test::run_kasha(args);
    EXPECT_EQ(r.exit_code, 0) << args << ": " << r.err;
    EXPECT_FALSE(r.out.empty()) << args;
    EXPECT_EQ(r.err.find("error"), std::string::npos) << args << ": " << r.err;
  }
  test::CommandResult help = test::run_kasha("render --help");
  // Bounds read as numbers a reader writes, not DBL_MAX's 309 digits.
  EXPECT_NE(help.out.find("--time FLOAT:in (0, 1e+09]"), std::string::npos) << help.out;
  EXPECT_EQ(help.out.find("179769313486231570"), std::string::npos) << help.out;
}

TEST(CliErrors, CtrlCDuringAColdKernelBuildExits130WithOneLine) {
  // A fresh kernel cache: the first build takes seconds, and a signal 0.3 s in most likely
  // arrives during it (or else during the first pass: then the image so far is written). Either
  // way: exit 130, no error line and no build log.
  const fs::path cache = test::scratch_dir() / "cold-cache";
  fs::create_directories(cache);
  const std::string out = (test::scratch_dir() / "cold.exr").string();
  for (const char* signal : {"INT", "TERM"}) {
    fs::remove_all(cache);
    fs::create_directories(cache);
    test::CommandResult r =
        run_with_signal("POCL_CACHE_DIR=" + quoted(cache.string()),
                        "render " + quoted(test::source_path("scenes/cornell_box.json")) +
                            " --time 60 --photons 4096 -o " + quoted(out),
                        signal, 0.3);
    SCOPED_TRACE(signal);
    EXPECT_EQ(r.exit_code, 130) << r.err;
    EXPECT_EQ(r.err.find("kasha: error"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("build log"), std::string::npos) << r.err;
    if (fs::exists(out)) {
      EXPECT_NE(r.err.find("interrupted: writing the image after"), std::string::npos) << r.err;
      fs::remove(out);
    } else {
      EXPECT_EQ(r.err, "kasha: interrupted\n");
    }
  }
}

TEST(CliErrors, SigtermDuringARenderWritesTheImageAndExits130) {
  const std::string out = (test::scratch_dir() / "term.exr").string();
  // The signal must land while rendering, not while PoCL compiles and links the kernels (a cold
  // cache, as in CI): its linker, in kasha's process group, dies of it and PoCL aborts. One short
  // render first compiles them.
  const std::string warm = (test::scratch_dir() / "warm.exr").string();
  ASSERT_EQ(test::run_kasha("render " + quoted(test::source_path("scenes/torus.json")) +
                            " --passes 1 --photons 4096 -o " + quoted(warm))
                .exit_code,
            0);
  test::CommandResult r =
      run_with_signal("",
                      "render " + quoted(test::source_path("scenes/torus.json")) +
                          " --time 120 --photons 4096 -o " + quoted(out),
                      "TERM", 3);
  EXPECT_EQ(r.exit_code, 130) << r.err;
  EXPECT_NE(r.err.find("interrupted: writing the image after"), std::string::npos) << r.err;
  EXPECT_EQ(read_exr(out).width, 192);
}

// The plotter is a child that signals reach and kasha waits for: Ctrl-C (kasha and its group) and
// SIGINT or SIGTERM to kasha alone during a plot (~1 s; a signal 0.4 s in lands in it, or else
// before it) exit 130 with the one line, leaving no file and no scratch folder.
TEST(CliErrors, ASignalDuringAPlotStopsThePlotterAndLeavesNothing) {
  const fs::path out = test::scratch_dir() / "plot";
  const std::string args =
      "colorimetry " + quoted(test::source_path("scenes/materials/postit.json")) + " --plot " +
      quoted((out / "p.png").string()) + " --json " + quoted((out / "p.json").string());
  for (const std::string signal : {"INT", "TERM", "Ctrl-C"}) {
    SCOPED_TRACE(signal);
    fs::remove_all(out);
    fs::create_directories(out);
    test::CommandResult r;
    // The plot takes about half a second: a signal after 0.4 s can come after it is done on an
    // idle machine, so shorter delays are tried until one falls inside the plot.
    for (double after : {0.4, 0.25, 0.15, 0.08}) {
      fs::remove_all(out);
      fs::create_directories(out);
      if (signal == "Ctrl-C") {
        r = run_with_signal("", args, "INT", after);
      } else {  // to kasha alone: started in the background by a shell, which prints its pid
        r = test::run_kasha_env("X=1 sh -c '\"$0\" \"$@\" & echo $!; sleep " +
                                    std::to_string(after) + "; kill -" + signal + " $!; wait $!'",
                                args);
        ASSERT_FALSE(r.out.empty());
        EXPECT_FALSE(fs::exists(fs::temp_directory_path() /
                                ("kasha-colorimetry-" + r.out.substr(0, r.out.find('\n')))));
      }
      if (r.exit_code != 0) break;  // 0: the plot was done before the signal
    }
    EXPECT_EQ(r.exit_code, 130) << r.err;
    EXPECT_EQ(r.err, "kasha: interrupted\n");
    EXPECT_TRUE(empty_dir(out));
  }
}

TEST(CliErrors, FileNamesThatAreNotUtf8AreEscapedInJson) {
  // JSON needs UTF-8: such a name used to fail inside nlohmann (type_error.316).
  const std::string material = test::write_file(
      "m\xff.json", R"({"kasha_material": 1, "name": "w", "passive": {"reflectance": 0.5}})");
  const std::string json = (test::scratch_dir() / "c.json").string();
  test::CommandResult r =
      test::run_kasha("colorimetry " + quoted(material) + " --json " + quoted(json));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(json);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(text.find("m\\\\xFF.json"), std::string::npos) << text;
}

TEST(CliErrors, FileSystemAndJsonErrorsNameTheOptionWithoutLibraryText) {
  // std::filesystem's "filesystem error: status: File name too long" and nlohmann's
  // "[json.exception…]" used to pass through; each is now the option's or the file's own line.
  const fs::path out = test::scratch_dir() / "out";
  fs::create_directories(out);
  const fs::path loop = test::scratch_dir() / "loop.csv";
  fs::create_symlink(loop.filename(), loop);  // a link to itself
  const std::string material = test::write_file(
      "m.json", R"({"kasha_material": 1, "name": "w", "passive": {"reflectance": 0.5}})");
  const std::string colorimetry = "colorimetry " + quoted(material) + " ";
  const std::vector<Case> cases = {
      {colorimetry + "--illuminant {long}", 1,
       "--illuminant {long}: cannot open file: file name too long"},
      {colorimetry + "--illuminant {loop}", 1,
       "--illuminant {loop}: cannot open file: too many levels of symbolic links"},
      {colorimetry + "--json {out}/{long}.json", 1, "--json {out}/{long}.json: file name too long"},
      // checked before the render, not after it
      {"render {scene} --passes 1 -o {out}/{long}.exr", 1,
       "-o {out}/{long}.exr: file name too long"},
      // JSON given on the command line is read as strictly as a file
      {colorimetry + "--illuminant '{\"line_nm\": 500, \"line_nm\": 600}'", 1,
       "--illuminant {\"line_nm\": 500, \"line_nm\": 600}: /line_nm: duplicate key \"line_nm\""},
  };
  expect_cases(cases,
               {{"scene", quoted(test::source_path("scenes/torus.json"))},
                {"long", std::string(300, 'a')},
                {"loop", loop.string()}},
               out);
}

TEST(CliErrors, NamesOnTheTerminalAreEscaped) {
  // A scene file and lamp names holding terminal controls: info prints them escaped.
  const std::string scene = test::write_file("s\x1b[2J.json", R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, -2], "look_at": [0, 0, 0], "fov_deg": 90, "width": 4, "height": 4},
    "materials": {"grey": {"passive": {"reflectance": 0.5}}},
    "lamps": {"\u001b[31mred\u0007": 1, "plain": 2}, "lamp": "plain",
    "shapes": [{"type": "quad", "corner": [-2, -2, 0], "u": [4, 0, 0], "v": [0, 4, 0],
                "material": "grey", "lamp": true}]})");
  test::CommandResult r = test::run_kasha("info " + quoted(scene));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find('\x07'), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("s\\x1B[2J.json"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\\x1B[31mred\\x07"), std::string::npos) << r.out;
}
