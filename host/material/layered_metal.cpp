#include "material/layered_metal.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <mutex>
#include <random>
#include <tuple>

#include "material/ggx.h"

namespace kasha {

double layered_metal_alpha(const CoatDesc& coat, double alpha_metal) {
  const double spread = coat.rough() ? coat.alpha * (1 - 1 / coat.eta) : 0.0;
  return std::max(1e-3, std::sqrt(alpha_metal * alpha_metal + spread * spread / 2));
}

namespace {

// pbrt-v4's FrComplex: a conductor's Fresnel reflectance at cos θ, index eta + ik.
double fresnel_complex(double cos_i, double eta, double k) {
  using C = std::complex<double>;
  const C n(eta, k);
  const double c = std::clamp(cos_i, 0.0, 1.0), s2 = 1 - c * c;
  const C cos_t = std::sqrt(C(1) - C(s2) / (n * n));
  const C r_parl = (n * c - cos_t) / (n * c + cos_t), r_perp = (c - n * cos_t) / (c + n * cos_t);
  return (std::norm(r_parl) + std::norm(r_perp)) / 2;
}

// The coat as the walk sees it: t(μ) for light crossing it at cos θ = μ outside (either way),
// and the albedo of its reflection from outside.
struct CoatView {
  const CoatDesc& coat;
  CoatTables tables;
  double transmission(double mu) const {
    return coat.rough() ? coat_table_at(tables.transmit, mu) : coat_transmission(coat, mu);
  }
  double reflection(double mu) const {
    return coat.rough() ? coat_table_at(tables.reflect, mu) : fresnel_dielectric(mu, coat.eta);
  }
};

// The light a walk carries out of the layer (or, for the coat's reflection, off it): a scalar
// weight and the metal bounces it took, whose Fresnel factors each bin applies.
struct Exit {
  double weight = 0;
  std::vector<double> cos_m;
  bool coat = false;  // reflected by the coat without entering
};

using Vec = Eigen::Vector3d;

// Light meeting an interface of relative index eta (the far side's over the near side's) from
// the side z > 0, going along -w: a visible facet (a smooth interface's is the normal), then
// reflection with the facet's Fresnel reflectance or refraction, as pbrt-v4's DielectricBxDF
// samples; *d the direction of travel after it, the weight G/G1 (flux). False: lost.
bool cross_interface(const HostGgx& ggx, bool smooth, double eta, const Vec& w, double u0,
                     double u1, double uc, Vec* d, double* weight, bool* reflected) {
  const Vec m = smooth ? Vec(0, 0, 1) : ggx.sample_visible(w, u0, u1);
  const double c = w.dot(m), F = fresnel_dielectric(c, eta);
  *reflected = uc < F;
  if (*reflected) {
    *d = -w + 2 * c * m;
    if (d->z() <= 0) return false;
  } else {
    const double s2 = (1 - c * c) / (eta * eta);
    *d = (-w / eta + (c / eta - std::sqrt(std::max(0.0, 1 - s2))) * m).normalized();
    if (d->z() >= 0) return false;
  }
  const Vec back = *reflected ? *d : Vec(-*d);
  *weight = smooth ? 1.0 : ggx.g(w, Vec(back.x(), back.y(), std::abs(back.z()))) / ggx.g1(w);
  return true;
}

// pbrt-v4's layered walk (LayeredBxDF) as flux: light arriving at cos θ = mu meets the coat,
// enters, and bounces between the metal and the coat's underside until it leaves or is lost;
// every bounce kept (pbrt-v4 stops at maxdepth, five metal bounces by default).
Exit walk(const CoatDesc& coat, const HostGgx& top, const HostGgx& metal, double mu,
          std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const bool smooth = !coat.rough();
  Exit out;
  Vec d, w(std::sqrt(std::max(0.0, 1 - mu * mu)), 0, mu);
  double g;
  bool reflected;
  if (!cross_interface(top, smooth, coat.eta, w, u(rng), u(rng), u(rng), &d, &g, &reflected))
    return out;
  out.weight = g;
  if (reflected) {
    out.coat = true;
    return out;
  }
  for (int bounce = 0; bounce < 64; ++bounce) {
    w = -d;  // pointing up, away from the metal
    out.weight *= std::exp(-coat.thickness / w.z());
    const Vec m = metal.sample_visible(w, u(rng), u(rng));
    const Vec r = -w + 2 * w.dot(m) * m;
    if (r.z() <= 0) break;
    out.cos_m.push_back(w.dot(m));
    out.weight *= metal.g(w, r) / metal.g1(w) * std::exp(-coat.thickness / r.z());
    // The coat from below: in a frame turned over, it is met from z > 0.
    const Vec flipped(-r.x(), -r.y(), r.z());
    if (!cross_interface(top, smooth, 1 / coat.eta, flipped, u(rng), u(rng), u(rng), &d, &g,
                         &reflected))
      break;
    out.weight *= g;
    if (!reflected) return out;       // left through the coat
    d = Vec(-d.x(), -d.y(), -d.z());  // back down, in the layer's frame
  }
  out.weight = 0;
  return out;
}

// The albedo of the kernels' once-scattered metal lobe (metal_under_coat.h) at cos θ = mu for
// one visible normal: t(μo) G/G1 t(μi), and the facet's cosine for Fc; 0 where it leaves below
// the horizon or beyond the coat's escape cone.
double once_scattered(const CoatView& c, const HostGgx& ggx, double mu, double u0, double u1,
                      double* cos_m) {
  const double eta = c.coat.eta, s = std::sqrt(std::max(0.0, 1 - mu * mu)) / eta;
  if (s >= 1) return 0;  // a coat below the outside's index: no way in at this angle
  const Vec v(s, 0, std::sqrt(1 - s * s));
  const Vec m = ggx.sample_visible(v, u0, u1);
  *cos_m = v.dot(m);
  const Vec r = -v + 2 * *cos_m * m;
  const double sin2_out = (1 - r.z() * r.z()) * eta * eta;
  if (r.z() <= 0 || sin2_out >= 1) return 0;
  return c.transmission(mu) * ggx.g(v, r) / ggx.g1(v) * c.transmission(std::sqrt(1 - sin2_out));
}

// Per bin, over the walks: the light that leaves the layer, that part of it after one metal
// bounce, and what the kernels' once-scattered lobe gives; and the coat's reflection.
// And per band of incidence cosines (kBands equal bands), the paths, and their layer's and
// once-scattered light over the bins: the angular shape of what the Lambert part carries.
constexpr int kBands = 16;
struct WalkSums {
  std::vector<double> layer, first, once;
  double reflect = 0;
  double band_paths[kBands] = {}, band_layer[kBands] = {}, band_once[kBands] = {};
  explicit WalkSums(int bins) : layer(bins, 0), first(bins, 0), once(bins, 0) {}
  void add(const WalkSums& o) {
    for (size_t i = 0; i < layer.size(); ++i) {
      layer[i] += o.layer[i];
      first[i] += o.first[i];
      once[i] += o.once[i];
    }
    reflect += o.reflect;
    for (int b = 0; b < kBands; ++b) {
      band_paths[b] += o.band_paths[b];
      band_layer[b] += o.band_layer[b];
      band_once[b] += o.band_once[b];
    }
  }
};

// Walks in chunks of their own seeds (the result does not depend on the threads), incidence
// cosine-weighted and stratified over all of them.
WalkSums walk_sums(const CoatView& c, const HostGgx& top, const HostGgx& metal, const HostGgx& lobe,
                   const std::vector<double>& eta, const std::vector<double>& k) {
  const int chunks = 128, per_chunk = 512, paths = chunks * per_chunk;
  const int bins = static_cast<int>(eta.size());
  std::vector<WalkSums> parts(chunks, WalkSums(bins));
  tbb::parallel_for(0, chunks, [&](int chunk) {
    std::mt19937_64 rng(0x6b617368u + chunk);
    std::uniform_real_distribution<double> u(0, 1);
    WalkSums& s = parts[chunk];
    for (int j = 0; j < per_chunk; ++j) {
      const double mu = std::sqrt((chunk + j * chunks + u(rng)) / paths);
      s.reflect += c.reflection(mu);
      const Exit e = walk(c.coat, top, metal, mu, rng);
      double cos_m = 0;
      const double o = once_scattered(c, lobe, mu, u(rng), u(rng), &cos_m);
      const int band = std::min(kBands - 1, static_cast<int>(mu * kBands));
      s.band_paths[band] += 1;
      for (int i = 0; i < bins; ++i) {
        const double n = eta[i] / c.coat.eta, kk = k[i] / c.coat.eta;
        if (o > 0) {
          const double once = o * fresnel_complex(cos_m, n, kk);
          s.once[i] += once;
          s.band_once[band] += once / bins;
        }
        if (e.coat || e.weight == 0) continue;
        double w = e.weight;
        for (double cm : e.cos_m) w *= fresnel_complex(cm, n, kk);
        s.layer[i] += w;
        s.band_layer[band] += w / bins;
        if (e.cos_m.size() == 1) s.first[i] += w;
      }
    }
  });
  WalkSums sums(bins);
  for (const WalkSums& p : parts) sums.add(p);
  const double scale = 1.0 / paths;
  for (int i = 0; i < bins; ++i) {
    sums.layer[i] *= scale;
    sums.first[i] *= scale;
    sums.once[i] *= scale;
  }
  sums.reflect *= scale;
  return sums;
}

// t(μ) = η s(μ) at kCoatTableSize cosines: the remaining light's albedo per band (at the bands'
// centres, linear between them), normalised so that ∫ s 2μ dμ = 1 as the kernels read the table.
std::vector<double> lambert_shape(const WalkSums& w, double once_scale, double eta) {
  double rest[kBands];
  for (int b = 0; b < kBands; ++b)
    rest[b] = w.band_paths[b] > 0
                  ? std::max(0.0, w.band_layer[b] - once_scale * w.band_once[b]) / w.band_paths[b]
                  : 0.0;
  std::vector<double> t(kCoatTableSize);
  for (int i = 0; i < kCoatTableSize; ++i) {
    const double mu = static_cast<double>(i) / (kCoatTableSize - 1);
    const double x = std::clamp(mu * kBands - 0.5, 0.0, kBands - 1.0);
    const int b = std::min(kBands - 2, static_cast<int>(x));
    t[i] = rest[b] + (x - b) * (rest[b + 1] - rest[b]);
  }
  const double mean = coat_table_mean(t);
  for (double& v : t) v = mean > 0 ? eta * v / mean : eta;
  return t;
}

LayeredMetalParts compute_parts(const CoatDesc& coat, double alpha_metal, double alpha,
                                const std::vector<double>& eta, const std::vector<double>& k) {
  const CoatView c{coat, coat.rough() ? rough_coat_tables(coat) : CoatTables{}};
  const HostGgx top{coat.alpha}, metal{std::max(alpha_metal, 1e-4)}, lobe{alpha};
  const int bins = static_cast<int>(eta.size());
  const WalkSums w = walk_sums(c, top, metal, lobe, eta, k);
  // The once-scattered lobe crosses the coat by smooth refraction; through a rough coat the walk's
  // light that meets the metal once leaves less (facets that turn it back, masking at both
  // crossings): the lobe is scaled to the walk's share, the same at every wavelength (it varies by
  // under 0.5 % between bins for gold; the walk's noise in it is about 0.3 %).
  double first_sum = 0, once_sum = 0;
  for (int i = 0; i < bins; ++i) {
    first_sum += w.first[i];
    once_sum += w.once[i];
  }
  LayeredMetalParts parts;
  // Under a smooth coat the lobe is the walk's once-scattered light exactly: no factor (the
  // walk's estimate of 1 is within about 1 % of it).
  if (coat.rough() && once_sum > 0) parts.once_scale = first_sum / once_sum;
  // The Lambert part, f = ρ(λ) s(μo) s(μi) / π with ∫ s(μ) 2μ dμ = 1 (reciprocal, albedo ρ s(μo)):
  // ρ the layer's remaining light per bin under uniform light, s its shape over the incidence
  // bands, the same at every wavelength. In the coat's form t(μo) t(μi) / (π η²) ρ: t = η s.
  double once_mean = 0, rest_mean = 0;
  for (int i = 0; i < bins; ++i) {
    const double rest = std::max(0.0, w.layer[i] - parts.once_scale * w.once[i]);
    once_mean += parts.once_scale * w.once[i] / bins;
    rest_mean += rest / bins;
    parts.scattered.push_back(rest);
  }
  parts.shape = lambert_shape(w, parts.once_scale, coat.eta);
  // Each part is chosen at points in proportion to its albedo (within [0.1, 0.9]), so neither
  // scale is large.
  const double lambert = w.reflect + rest_mean;
  parts.lambert_share = std::clamp(lambert / std::max(1e-9, lambert + once_mean), 0.1, 0.9);
  return parts;
}

}  // namespace

// Scenes give many materials one layered metal (and the fuzz harness one scene many times):
// each distinct one is walked once.
LayeredMetalParts layered_metal_parts(const CoatDesc& coat, double alpha_metal, double alpha,
                                      const std::vector<double>& eta,
                                      const std::vector<double>& k) {
  using Key =
      std::tuple<double, double, double, double, double, std::vector<double>, std::vector<double>>;
  static std::mutex mutex;
  static std::map<Key, LayeredMetalParts> cache;
  const Key key{coat.eta, coat.thickness, coat.alpha, alpha_metal, alpha, eta, k};
  {
    std::lock_guard<std::mutex> lock(mutex);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
  }
  LayeredMetalParts parts = compute_parts(coat, alpha_metal, alpha, eta, k);
  std::lock_guard<std::mutex> lock(mutex);
  return cache.emplace(key, std::move(parts)).first->second;
}

}  // namespace kasha
