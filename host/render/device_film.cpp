#include "render/device_film.h"

#include <algorithm>

#include "color/cie_observer.h"
#include "opencl/device_buffer.h"
#include "opencl/upload.h"

namespace kasha {

DeviceFilm::DeviceFilm(ClContext& cl, const Film& film)
    : cl_(cl), pixels_(film.pixels()), rows_(film.rows()), spectral_(film.spectral()) {
  const WavelengthGrid& grid = film.grid();
  BinnedObserver obs(grid);
  const int n = grid.bins;
  cmf_.resize(3 * n);
  importance_.resize(n);
  for (int i = 0; i < n; ++i) {
    cmf_[i] = static_cast<float>(obs.x[i] * grid.bin_nm);
    cmf_[n + i] = static_cast<float>(obs.y[i] * grid.bin_nm);
    cmf_[2 * n + i] = static_cast<float>(obs.z[i] * grid.bin_nm);
    importance_[i] = cmf_[i] + cmf_[n + i] + cmf_[2 * n + i];
  }
  float peak = *std::max_element(importance_.begin(), importance_.end());
  for (float& v : importance_) v += 0.05f * peak;
  std::vector<float> tables = cmf_;
  tables.insert(tables.end(), importance_.begin(), importance_.end());
  tables_ = upload(cl, tables);
  ray_counts_ = upload(cl, std::vector<cl_uint>(4, 0));
}

int DeviceFilm::bind(cl::Kernel& k, int a) const {
  k.setArg(a++, tables_);
  k.setArg(a++, ray_counts_);
  return a;
}

DeviceFilm::RayCounts DeviceFilm::take_ray_counts() {
  cl_uint words[4];
  cl_.queue().enqueueReadBuffer(ray_counts_, CL_TRUE, 0, sizeof words, words);
  cl_.queue().enqueueFillBuffer(ray_counts_, cl_uint(0), 0, sizeof words);
  auto count = [&](int k) { return words[k] + 4294967296.0 * words[k + 1]; };
  return {count(0), count(2)};
}

cl::Buffer& DeviceFilm::pixel_sums() {
  if (!sums_())
    sums_ = device_buffer(cl_, pixels_ * rows_ * sizeof(float), "the film's per-pixel sums");
  return sums_;
}

void DeviceFilm::clear_pixel_sums() {
  cl_.queue().enqueueFillBuffer(pixel_sums(), 0.0f, 0, pixels_ * rows_ * sizeof(float));
}

std::vector<double> DeviceFilm::read_pixel_sums() {
  std::vector<float> sums(pixels_ * rows_);
  cl_.queue().enqueueReadBuffer(pixel_sums(), CL_TRUE, 0, sums.size() * sizeof(float), sums.data());
  return std::vector<double>(sums.begin(), sums.end());
}

}  // namespace kasha
