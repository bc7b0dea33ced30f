// Output safety (docs/commands.md#errors-and-exit-codes, issue 13): every output path is checked
// before any work, no output replaces an input, another output or a non-regular file, and a failed
// command leaves every file as it was. Each case runs the binary on a tiny scene and compares the
// whole folder before and after; the checks fail before any rendering, so no case waits for
// kernels.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "core/atomic_file.h"
#include "core/output_set.h"
#include "test_support.h"

using namespace kasha;
namespace fs = std::filesystem;

namespace {

// What a file is: its kind, and for a regular file its size and contents' hash, for a link its
// target. Equal snapshots: nothing was written, removed or changed.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator();
       ++it) {
    const fs::path& p = it->path();
    struct stat st;
    lstat(p.c_str(), &st);
    std::string d;
    if (S_ISLNK(st.st_mode)) {
      d = "link to " + fs::read_symlink(p).string();
    } else if (S_ISREG(st.st_mode)) {
      std::ifstream in(p, std::ios::binary);
      std::stringstream text;
      text << in.rdbuf();
      unsigned long long h = 1469598103934665603ULL;
      for (unsigned char c : text.str()) h = (h ^ c) * 1099511628211ULL;
      d = "file " + std::to_string(st.st_size) + " " + std::to_string(h);
    } else {
      d = "mode " + std::to_string(st.st_mode & S_IFMT);
    }
    out[p.string()] = d;
  }
  return out;
}

void expect_same(const std::map<std::string, std::string>& before,
                 const std::map<std::string, std::string>& after, const std::string& label) {
  for (const auto& [path, d] : after) {
    auto it = before.find(path);
    if (it == before.end())
      ADD_FAILURE() << label << ": written: " << path;
    else if (it->second != d)
      ADD_FAILURE() << label << ": changed: " << path;
  }
  for (const auto& [path, d] : before)
    if (!after.count(path)) ADD_FAILURE() << label << ": removed: " << path;
}

// A 4×4 scene with a material file and a CSV spectrum, so that files the scene names are
// inputs too.
std::string write_scene(const fs::path& d) {
  std::ofstream(d / "data.csv") << "nm,value\n300,0.5\n800,0.5\n";
  std::ofstream(d / "mat.json")
      << R"({"kasha_material": 1, "passive": {"reflectance": {"csv": "data.csv"}}})";
  std::ofstream(d / "scene.json") << R"({"kasha_scene": 1,
    "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "fov_deg": 40, "width": 4, "height": 4},
    "materials": {"m": {"file": "mat.json"}},
    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 2, "material": "m", "inward": true,
                "emission": 0.5}]})";
  return (d / "scene.json").string();
}

struct Case {
  std::string name;
  std::string args;     // $D stands for the case's folder
  std::string message;  // after "kasha: error: ", with $D
};

std::string expand(std::string s, const std::string& d) {
  for (size_t at = s.find("$D"); at != std::string::npos; at = s.find("$D", at + d.size()))
    s.replace(at, 2, d);
  return s;
}

}  // namespace

TEST(OutputSafety, EveryBadOutputIsOneLineAndChangesNothing) {
  const std::string r = "render $D/scene.json --integrator debug --passes 1 --spp 1 ";
  const std::string m =
      "measure --sample $D/s.csv --etalon $D/e.csv --etalon-reflectance $D/rho.csv ";
  std::vector<Case> cases = {
      // Outputs that are inputs.
      {"-o is the scene", r + "-o $D/scene.json",
       "-o $D/scene.json: is the scene file $D/scene.json"},
      {"--log is the scene", r + "-o $D/o.exr --log $D/scene.json",
       "--log $D/scene.json: is the scene file $D/scene.json"},
      {"-o is a material the scene names", r + "-o $D/mat.json",
       "-o $D/mat.json: is the scene's material or data file"},
      {"-o is a CSV the scene names", r + "-o $D/data.csv",
       "-o $D/data.csv: is the scene's material or data file"},
      {"-o is the reference", r + "-o $D/ref.exr --reference $D/ref.exr",
       "-o $D/ref.exr: is the --reference image $D/ref.exr"},
      {"-o is a hard link to the scene", r + "-o $D/hard.json",
       "-o $D/hard.json: is the scene file"},
      {"-o is the scene through a linked folder", r + "-o $D/linkdir/scene.json",
       "-o $D/linkdir/scene.json: is the scene file"},
      {"measure -o is --sample", m + "-o $D/s.csv", "-o $D/s.csv: is the --sample file $D/s.csv"},
      {"measure -o is --etalon-reflectance", m + "-o $D/rho.csv",
       "-o $D/rho.csv: is the --etalon-reflectance file"},
      {"reference -o is the scene", "reference $D/scene.json --time 1 -o $D/scene.json",
       "-o $D/scene.json: is the scene file"},
      {"preview -o is the image", "preview $D/ref.exr -o $D/ref.exr",
       "-o $D/ref.exr: is the image"},
      {"colorimetry --json is the material", "colorimetry $D/mat.json --json $D/mat.json",
       "--json $D/mat.json: is the material file"},
      {"regions --json is the image", "regions $D/scene.json $D/ref.exr --json $D/ref.exr",
       "--json $D/ref.exr: is the image"},
      // Outputs that are each other.
      {"--png is -o", r + "-o $D/o.exr --png $D/o.exr",
       "--png $D/o.exr: is the same file as -o $D/o.exr"},
      {"--log is --png through ./", r + "-o $D/o.exr --png $D/p.png --log $D/./p.png",
       "--log $D/./p.png: is the same file as --png $D/p.png"},
      {"measure --plots is -o", m + "-o $D/m.json --plots $D/m.json",
       "--plots $D/m.json: is the same file as -o $D/m.json"},
      // Non-regular files.
      {"-o is a symbolic link", r + "-o $D/link.exr", "-o $D/link.exr: is a symbolic link"},
      {"-o is a device", r + "-o /dev/full", "-o /dev/full: is a character device"},
      {"reference -o is a device", "reference $D/scene.json --time 1 -o /dev/full",
       "-o /dev/full: is a character device"},
      {"--png is a FIFO", r + "-o $D/o.exr --png $D/fifo", "--png $D/fifo: is a FIFO"},
      {"-o is a directory", r + "-o $D/sub", "-o $D/sub: is a directory"},
      {"measure --plots is a file", m + "-o $D/m.json --plots $D/s.csv",
       "--plots $D/s.csv: is a file, not a directory"},
      {"converge -o is a file", "converge $D/scene.json --time 1 -o $D/s.csv",
       "-o $D/s.csv: is a file, not a directory"},
      // Places that cannot take the file, found before any work.
      {"-o under /proc", r + "-o /proc/kasha.exr", "-o /proc/kasha.exr: /proc is in /proc or /sys"},
      {"--log under /sys", r + "-o $D/o.exr --log /sys/kasha.csv",
       "--log /sys/kasha.csv: /sys is in /proc or /sys"},
      {"-o in a missing folder", r + "-o $D/missing/o.exr",
       "-o $D/missing/o.exr: directory $D/missing does not exist"},
      {"reference -o in a missing folder", "reference $D/scene.json --time 1 -o $D/missing/r.exr",
       "-o $D/missing/r.exr: directory $D/missing does not exist"},
      {"converge -o below a file", "converge $D/scene.json --time 1 -o $D/s.csv/sub",
       "-o $D/s.csv/sub: $D/s.csv is not a directory"},
      // A failed converge leaves no folder (it is made as a temporary, renamed when complete).
      {"converge fails after its checks",
       "converge $D/scene.json --time 1 --reference $D/ref.exr -o $D/study", "$D/ref.exr: "},
  };
  if (geteuid() != 0)  // root writes in any folder whatever its mode bits
    cases.push_back({"-o in a read-only folder", r + "-o $D/ro/o.exr",
                     "-o $D/ro/o.exr: cannot write in directory $D/ro: Permission denied"});

  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path dir = test::scratch_dir() / "case";
    fs::remove_all(dir);
    fs::create_directories(dir / "sub");
    fs::create_directories(dir / "ro");
    write_scene(dir);
    for (const char* name : {"s.csv", "e.csv", "rho.csv", "ref.exr", "victim.exr"})
      std::ofstream(dir / name) << "not read: the check comes first\n";
    fs::create_hard_link(dir / "scene.json", dir / "hard.json");
    fs::create_directory_symlink(dir, dir / "linkdir");
    fs::create_symlink(dir / "victim.exr", dir / "link.exr");
    ASSERT_EQ(mkfifo((dir / "fifo").c_str(), 0644), 0);
    fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec);

    const auto before = snapshot(dir);
    struct stat full_before;
    ASSERT_EQ(stat("/dev/full", &full_before), 0);
    test::CommandResult result = test::run_kasha(expand(c.args, dir.string()));
    const std::string expected = "kasha: error: " + expand(c.message, dir.string());

    EXPECT_EQ(result.exit_code, 1) << result.err;
    EXPECT_EQ(result.err.rfind(expected, 0), 0u) << "expected: " << expected << "\n" << result.err;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    expect_same(before, snapshot(dir), c.name);
    struct stat full_after;
    ASSERT_EQ(stat("/dev/full", &full_after), 0);
    EXPECT_TRUE(S_ISCHR(full_after.st_mode) && full_after.st_rdev == full_before.st_rdev);
    fs::permissions(dir / "ro", fs::perms::owner_all);
  }
}

// Outputs appear together or not at all: one writer failing leaves none of the others.
TEST(OutputSafety, AFailedOutputLeavesNoOther) {
  const fs::path dir = test::scratch_dir();
  const std::string exr = (dir / "o.exr").string(), png = (dir / "o.png").string();
  std::ofstream(exr) << "the old image\n";
  const auto before = snapshot(dir);
  {
    OutputSet outputs;
    outputs.file("-o", exr);
    outputs.file("--png", png);
    outputs.write(exr, [](const std::string& tmp) { std::ofstream(tmp) << "new"; });
    std::string message = test::error_of([&] {
      outputs.write(png, [](const std::string& tmp) {
        std::ofstream(tmp) << "half";
        throw Error(tmp + ": PNG encoding failed");
      });
    });
    // The message names the output as given, not its temporary.
    EXPECT_EQ(message, "--png " + png + ": PNG encoding failed");
  }
  expect_same(before, snapshot(dir), "after a failed --png");
}

TEST(OutputSafety, AFolderOutputAppearsWhole) {
  const fs::path dir = test::scratch_dir();
  const std::string study = (dir / "study").string(), material = (dir / "m.json").string();
  {
    OutputSet outputs;  // measure --plots failing after the material was written
    outputs.file("-o", material);
    outputs.directory("--plots", study);
    outputs.write(material, [](const std::string& tmp) { std::ofstream(tmp) << "{}"; });
    std::ofstream(fs::path(outputs.staging(study)) / "raw.csv") << "1\n";
  }
  EXPECT_TRUE(fs::is_empty(dir)) << "nothing committed, nothing left";
  {
    OutputSet outputs;
    outputs.directory("-o", study);
    std::ofstream(fs::path(outputs.staging(study)) / "log.csv") << "1\n";
    EXPECT_FALSE(fs::exists(study));
    outputs.commit();
  }
  EXPECT_TRUE(fs::exists(fs::path(study) / "log.csv"));
  {
    OutputSet outputs;  // an existing folder: its files are replaced, the others stay
    std::ofstream(fs::path(study) / "mine.txt") << "keep\n";
    outputs.directory("-o", study);
    std::ofstream(fs::path(outputs.staging(study)) / "log.csv") << "2\n";
    outputs.commit();
  }
  std::ifstream log(fs::path(study) / "log.csv");
  std::string line;
  std::getline(log, line);
  EXPECT_EQ(line, "2");
  EXPECT_TRUE(fs::exists(fs::path(study) / "mine.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(study), fs::directory_iterator()), 2);
}

// A full disk shows only when the stream is flushed: the writer must report it (the --log that
// exited 0 with a 0-byte file). /dev/full fails every write with ENOSPC; it is written through,
// never renamed over.
TEST(OutputSafety, AWriteThatFailsAtTheFlushIsReported) {
  std::string message = test::error_of([] {
    write_stream_file("/dev/full", "--log out.csv",
                      [](std::ofstream& out) { out << "a,b\n1,2\n"; });
  });
  EXPECT_EQ(message.rfind("--log out.csv: write failed", 0), 0u) << message;

  // Any stream that fails at its flush: a buffer that takes bytes but cannot sync them.
  struct FailingBuffer : std::stringbuf {
    int sync() override { return -1; }
  } buffer;
  std::ostream out(&buffer);
  out << "rows";
  EXPECT_EQ(
      test::error_of([&] { check_flushed(out, "log.csv"); }).rfind("log.csv: write failed", 0), 0u);
}

// A full disk while the plotter writes (RLIMIT_FSIZE, with SIGXFSZ ignored so the write fails with
// EFBIG): one line naming --plot and the user's file, with the plotter's reason, and no file left.
TEST(OutputSafety, AFullDiskDuringAPlotNamesTheUsersFile) {
  const fs::path d = test::scratch_dir() / "case";
  fs::create_directories(d);
  const std::string png = (d / "o.png").string();
  // ulimit -f 20: 10 or 20 KiB (dash or bash): room for the result, not for the PNG (~40 KiB).
  test::CommandResult r =
      test::run_kasha_env("X=1 sh -c 'trap \"\" XFSZ; ulimit -f 20; exec \"$0\" \"$@\"'",
                          "colorimetry '" + test::source_path("scenes/materials/postit.json") +
                              "' --plot '" + png + "'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(r.err.rfind("kasha: error: --plot " + png + ": plotting failed: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(".kasha-"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(fs::is_empty(d));
}

namespace {

// An excitation–emission matrix in the CSV layout of docs/formats.md#measurement-csv, reading(λo,
// λi).
void write_eem(const fs::path& file, const std::vector<double>& ex,
               const std::function<double(double, double)>& reading) {
  std::ofstream out(file);
  out << "em\\ex";
  for (double li : ex) out << "," << li;
  out << "\n";
  for (double lo = 300; lo <= 700; lo += 5) {
    out << lo;
    for (double li : ex) out << "," << reading(lo, li);
    out << "\n";
  }
}

}  // namespace

// measure reads back what it writes with render's loader: a degenerate measurement is one line
// naming its input, and no material file appears.
TEST(OutputSafety, MeasureWritesNoMaterialRenderWouldRefuse) {
  const fs::path d = test::scratch_dir() / "case";
  fs::create_directories(d);
  std::vector<double> ex;
  for (double l = 300; l <= 600; l += 10) ex.push_back(l);
  auto band = [](double lo, double li) { return std::exp(-0.5 * (lo - li) * (lo - li) / 16); };
  write_eem(d / "e.csv", ex, band);
  write_eem(d / "s.csv", ex, [&](double lo, double li) { return 0.7 * band(lo, li); });
  write_eem(d / "zero.csv", ex, [](double, double) { return 0.0; });
  write_eem(d / "negative.csv", ex,
            [&](double lo, double li) { return -0.7 * band(lo, li) - 0.01; });
  write_eem(d / "one_s.csv", {400}, [&](double lo, double li) { return 0.7 * band(lo, li); });
  write_eem(d / "one_e.csv", {400}, band);
  std::ofstream(d / "rho.csv") << "nm,rho\n250,0.97\n850,0.98\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      // Refused where the input is read (its own checks), before any material is made.
      {"--sample $D/zero.csv --etalon $D/e.csv", "$D/zero.csv: no reading is above zero"},
      {"--sample $D/negative.csv --etalon $D/e.csv", "$D/negative.csv: no reading is above zero"},
      {"--sample $D/one_s.csv --etalon $D/one_e.csv",
       "$D/one_s.csv: only one excitation wavelength"},
      {"--sample $D/s.csv --etalon $D/e.csv --band-nm 500", "--band-nm 500 nm: the band must be"},
  };
  const auto before = snapshot(d);
  for (const auto& [args, message] : cases) {
    SCOPED_TRACE(args);
    test::CommandResult r =
        test::run_kasha("measure --etalon-reflectance " + (d / "rho.csv").string() + " " +
                        expand(args, d.string()) + " -o " + (d / "m.json").string());
    const std::string expected = "kasha: error: " + expand(message, d.string());
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_EQ(r.err.rfind(expected, 0), 0u) << "expected: " << expected << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    expect_same(before, snapshot(d), args);
  }
}
