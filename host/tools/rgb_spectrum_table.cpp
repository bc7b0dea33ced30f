// Build-time tool: fits the RGB → spectrum coefficient table (spectrum/rgb_spectrum_fit.h) and
// writes it as raw little-endian floats, which the build links into kasha
// (spectrum/rgb_spectrum.cpp).
//   rgb_spectrum_table CMF_1931.csv D65.csv OUT.bin
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "spectrum/rgb_spectrum_fit.h"

using namespace kasha;

// wavelength → the columns after it, of a CSV with one header line.
static std::map<int, std::vector<double>> read_csv(const char* path) {
  std::ifstream in(path);
  if (!in) {
    std::fprintf(stderr, "rgb_spectrum_table: cannot read %s\n", path);
    std::exit(1);
  }
  std::map<int, std::vector<double>> rows;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(s, cell, ',')) v.push_back(std::stod(cell));
    if (v.size() < 2) continue;
    int nm = static_cast<int>(v[0] + 0.5);
    v.erase(v.begin());
    rows[nm] = v;
  }
  return rows;
}

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: rgb_spectrum_table CMF.csv D65.csv OUT.bin\n");
    return 2;
  }
  auto cmf = read_csv(argv[1]), d65 = read_csv(argv[2]);
  FitObserver obs;
  for (int nm = 360; nm <= 780; nm += 5) {  // where both tables have data
    if (!cmf.count(nm) || !d65.count(nm)) {
      std::fprintf(stderr, "rgb_spectrum_table: no data at %d nm\n", nm);
      return 1;
    }
    obs.x.push_back(cmf[nm][0]);
    obs.y.push_back(cmf[nm][1]);
    obs.z.push_back(cmf[nm][2]);
    obs.d65.push_back(d65[nm][0]);
  }
  std::vector<float> table = fit_rgb_table(obs);
  std::filesystem::path path(argv[3]);
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(table.data()), table.size() * sizeof(float));
  if (!out) {
    std::fprintf(stderr, "rgb_spectrum_table: cannot write %s\n", argv[3]);
    return 1;
  }
  return 0;
}
