#include "render/device_media.h"

namespace kasha {

static int append_spectrum(std::vector<float>& spectra, const std::vector<double>& v) {
  const int at = static_cast<int>(spectra.size());
  for (double x : v) spectra.push_back(static_cast<float>(x));
  return at;
}

DeviceMedia device_media(const Scene& scene, const std::vector<KTriangle>& leaf_triangles,
                         std::vector<float>& spectra) {
  DeviceMedia d;
  for (const Medium& m : scene.media) {
    std::vector<double> sigma_t(m.sigma_a.size());
    for (size_t i = 0; i < sigma_t.size(); ++i) sigma_t[i] = m.sigma_a[i] + m.sigma_s[i];
    KMedium k{};
    // A fluorophore's absorption is part of the extinction; its re-emission a collision's branch.
    for (const Fluorophore& f : m.fluorophores) {
      KFluorophore& kf = k.fluorophore[k.fluorophores++];
      kf.absorption = append_spectrum(spectra, f.absorption);
      kf.emission = append_spectrum(spectra, f.e_hat);
      kf.yield = static_cast<float>(f.quantum_yield);
      double sum = 0;
      for (size_t i = 0; i < sigma_t.size(); ++i) sigma_t[i] += f.absorption[i], sum += f.absorption[i];
      kf.absorption_sum = static_cast<float>(sum);
    }
    k.sigma_t = append_spectrum(spectra, sigma_t);
    k.sigma_s = append_spectrum(spectra, m.sigma_s);
    k.g = static_cast<float>(m.g);
    double sigma_sum = 0, scattered = 0, reemitted = 0;
    for (size_t i = 0; i < sigma_t.size(); ++i) sigma_sum += sigma_t[i], scattered += m.sigma_s[i];
    for (int f = 0; f < k.fluorophores; ++f)
      reemitted += static_cast<double>(k.fluorophore[f].yield) * k.fluorophore[f].absorption_sum;
    k.sigma_mean = sigma_t.empty() ? 0.0f : static_cast<float>(sigma_sum / sigma_t.size());
    k.events = static_cast<float>(scattered + reemitted);
    k.elastic_share = k.events > 0 ? static_cast<float>(scattered / (scattered + reemitted)) : 0.0f;
    d.media.push_back(k);
  }
  if (!scene.triangle_media.empty())
    for (const KTriangle& t : leaf_triangles) {
      const MediumInterface& mi = scene.triangle_media[t.prim];
      d.tri_media.push_back({mi.inside, mi.outside});
    }
  return d;
}

}  // namespace kasha
