// Writes the simulated fluorimeter's measurement of the brightened paper (the instrument and the
// material `kasha measure` is tested on, with the excitation scanned up to 780 nm so the passive
// reflectance covers the visible range) into a directory, and prints the `kasha measure` options
// that read it: how scenes/materials/brightened_paper.json was made.
#include <cstdio>
#include <filesystem>

#include "simulated_instrument.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: simulate_fluorimeter DIR\n");
    return 2;
  }
  std::filesystem::create_directories(argv[1]);
  using namespace kasha::test;
  std::printf(
      "%s\n",
      write_instrument_files(argv[1], Instrument::visible_scan(), brightened_paper()).c_str());
  return 0;
}
