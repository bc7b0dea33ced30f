#include "render/device_scene.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include "color/cie_observer.h"
#include "colorimetry/radiance_factor.h"
#include "colorimetry/sample_colorimetry.h"
#include "opencl/device_buffer.h"
#include "opencl/upload.h"
#include "render/texture_program.h"
#include "scene/triangle_dpdu.h"
#include "spectrum/rgb_spectrum.h"

namespace kasha {

static int append(std::vector<float>& out, const std::vector<double>& values) {
  if (values.empty()) return -1;
  int offset = static_cast<int>(out.size());
  for (double v : values) out.push_back(static_cast<float>(v));
  return offset;
}

// The colour of a material's Lambert parts under equal-energy light, fluorescence included
// (what colorimetry computes with a flat lamp), normalized so a perfect white has Y = 1.
// A dielectric shows white (it loses nothing), a conductor its reflectance at normal incidence.
static void albedo_xyz(const Material& m, const WavelengthGrid& grid, const BinnedObserver& obs,
                       float out[3]) {
  const std::vector<double> flat(grid.bins, 1.0);
  std::vector<double> leaving = flat;
  if (m.kind == MaterialKind::measured) leaving = leaving_radiance(m, flat);
  if (m.kind == MaterialKind::conductor)
    for (int i = 0; i < grid.bins; ++i) {
      double n = m.eta_c[i], k = m.k_c[i];
      leaving[i] = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
    }
  Vec3d xyz = relative_xyz(obs, leaving, flat, grid.bin_nm, "albedo");
  for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(xyz[k] / 100);
}

std::vector<float> gloss_lobe_table(const GlossDesc& gloss) {
  const int K = KASHA_LOBE_CELLS;
  const double cone = gloss.cone_deg * M_PI / 180.0;
  auto profile = [&](double delta) {
    if (gloss.profile_deg.empty()) return 1.0;
    double d = delta * 180.0 / M_PI;
    const auto &x = gloss.profile_deg, &y = gloss.profile_value;
    if (d < x.front() || d > x.back()) return 0.0;
    size_t k = std::upper_bound(x.begin(), x.end(), d) - x.begin();
    if (k == 0) return y.front();
    if (k >= x.size()) return y.back();
    return y[k - 1] + (d - x[k - 1]) / (x[k] - x[k - 1]) * (y[k] - y[k - 1]);
  };
  std::vector<double> density(K), mass(K);
  double total = 0;
  for (int k = 0; k < K; ++k) {
    // Ring average of p weighted by sin δ (solid angle), by the midpoint rule on 32 sub-steps.
    double lo = cone * k / K, hi = cone * (k + 1) / K, num = 0, den = 0;
    for (int j = 0; j < 32; ++j) {
      double d = lo + (j + 0.5) * (hi - lo) / 32;
      num += profile(d) * std::sin(d);
      den += std::sin(d);
    }
    density[k] = den > 0 ? num / den : 0.0;
    mass[k] = density[k] * 2.0 * M_PI * (std::cos(lo) - std::cos(hi));
    total += mass[k];
  }
  std::vector<float> table(2 * K);
  double cdf = 0;
  for (int k = 0; k < K; ++k) {
    table[k] = static_cast<float>(density[k] / total);
    cdf += mass[k] / total;
    table[K + k] = static_cast<float>(cdf);
  }
  table[2 * K - 1] = 1.0f;
  return table;
}

// The offset of the bins' centre wavelengths in the spectra buffer, appended the first time an
// environment image or an RGB texture asks (both evaluate RGB sigmoids bin by bin).
int KernelSceneData::bin_centres(const Scene& scene) {
  if (lambda_ < 0) {
    lambda_ = static_cast<int>(spectra.size());
    for (int i = 0; i < scene.grid.bins; ++i)
      spectra.push_back(static_cast<float>(scene.grid.center(i)));
  }
  return lambda_;
}

// An image's KTexture: its texels after the spectra, as sigmoid coefficients (spectral) or the
// mean of R, G and B (scalar; clamped to [0, 1] for a concentration).
KTexture KernelSceneData::image_texture(const RgbImage& image, TextureWrap wrap, bool bilinear,
                                        TextureUse use, const Scene& scene) {
  const bool spectral = use == TextureUse::reflectance;
  KTexture k{};
  k.type = KASHA_TEXTURE_IMAGE;
  k.spectral = spectral;
  k.uscale = k.vscale = 1.0f;
  k.data = k.even = k.odd = k.lambda = -1;
  k.width = image.width;
  k.height = image.height;
  k.bilinear = bilinear;
  k.wrap = wrap == TextureWrap::repeat              ? KASHA_WRAP_REPEAT
           : wrap == TextureWrap::clamp             ? KASHA_WRAP_CLAMP
           : wrap == TextureWrap::octahedral_sphere ? KASHA_WRAP_OCTAHEDRAL
                                                    : KASHA_WRAP_BLACK;
  k.data = static_cast<int>(spectra.size());
  const size_t n = image.rgb.size() / 3;
  for (size_t p = 0; p < n; ++p) {
    const float* c = &image.rgb[3 * p];
    if (spectral) {
      SigmoidCoefficients q = rgb_sigmoid({c[0], c[1], c[2]});
      for (double v : q) spectra.push_back(static_cast<float>(v));
      spectra.push_back(0.0f);
    } else {
      const float mean = (c[0] + c[1] + c[2]) / 3.0f;
      spectra.push_back(use == TextureUse::concentration ? std::clamp(mean, 0.0f, 1.0f) : mean);
    }
  }
  if (spectral) k.lambda = bin_centres(scene);
  return k;
}

// A (u, v) image or checkerboard of values as the kernels look it up.
KTexture KernelSceneData::plain_texture(const Texture& t, TextureUse use, const Scene& scene) {
  KTexture k{};
  if (t.type == TextureType::image) {
    k = image_texture(t.image, t.wrap, t.bilinear, use, scene);
  } else {
    k.type = KASHA_TEXTURE_CHECKERBOARD;
    k.spectral = use == TextureUse::reflectance;
    k.data = k.even = k.odd = k.lambda = -1;
    if (k.spectral) {
      k.even = append(spectra, scene.grid.resample(*t.even));
      k.odd = append(spectra, scene.grid.resample(*t.odd));
    } else {
      k.even_value = static_cast<float>(t.even_value);
      k.odd_value = static_cast<float>(t.odd_value);
    }
  }
  k.uscale = static_cast<float>(t.uscale);
  k.vscale = static_cast<float>(t.vscale);
  k.udelta = static_cast<float>(t.udelta);
  k.vdelta = static_cast<float>(t.vdelta);
  return k;
}

// The kernels' view of the scene's textures (kernels/materials/texture.h): one KTexture per texture
// and use (spectral for a reflectance, scalar for a concentration), the texels after the spectra,
// and each triangle's texture coordinates in leaf order. A texture of textures is a program
// (render/texture_program.h) whose images are plain KTextures of their own.
void KernelSceneData::add_textures(const Scene& scene) {
  std::map<std::pair<int, TextureUse>, int> made;
  auto plain = [&](int index, TextureUse use) {
    auto found = made.find({index, use});
    if (found != made.end()) return found->second;
    textures.push_back(plain_texture(scene.textures[index], use, scene));
    return made[{index, use}] = static_cast<int>(textures.size() - 1);
  };
  std::map<const RgbImage*, int> palettes;
  TextureProgramTables tables{
      tex_ops, spectra,
      [&](const SpectrumPtr& s) { return append(spectra, scene.grid.resample(*s)); },
      // An image inside a program: its own value, unclamped (the program combines it).
      [&](int index, bool spectral) {
        return plain(index, spectral ? TextureUse::reflectance : TextureUse::emission);
      },
      [&](const RgbImage& image) {
        auto found = palettes.find(&image);
        if (found != palettes.end()) return found->second;
        textures.push_back(
            image_texture(image, TextureWrap::clamp, true, TextureUse::reflectance, scene));
        return palettes[&image] = static_cast<int>(textures.size() - 1);
      }};
  std::map<std::pair<int, TextureUse>, int> programs;
  auto texture = [&](int index, TextureUse use) {
    if (!scene.textures[index].program()) return plain(index, use);
    auto found = programs.find({index, use});
    if (found != programs.end()) return found->second;
    KTexture k = compile_texture_program(scene, index, use == TextureUse::reflectance, tables);
    textures.push_back(k);
    return programs[{index, use}] = static_cast<int>(textures.size() - 1);
  };
  for (size_t i = 0; i < materials.size(); ++i) {
    const MaterialTextures& mt = scene.material_textures[i];
    if (mt.reflectance >= 0)
      materials[i].reflectance_texture = texture(mt.reflectance, TextureUse::reflectance);
    if (mt.fluorescence >= 0)
      materials[i].fluorescence_texture = texture(mt.fluorescence, TextureUse::concentration);
    // A mix's amount is a scalar in [0, 1], as a concentration is.
    const auto& mix = scene.materials[i].mix;
    if (mix && mix->amount_texture >= 0)
      materials[i].mix.amount_texture = texture(mix->amount_texture, TextureUse::concentration);
    // A roughness too is a number in [0, 1].
    const Material& m = scene.materials[i];
    for (int axis = 0; axis < 2; ++axis)
      if (m.rough() && m.roughness.texture[axis] >= 0)
        materials[i].alpha_texture[axis] =
            texture(m.roughness.texture[axis], TextureUse::concentration);
  }
  std::vector<int> emitter_texture;
  for (const Emitter& e : scene.emitters)
    emitter_texture.push_back(e.texture >= 0 ? texture(e.texture, TextureUse::emission) : -1);
  // An alpha is a scalar in [0, 1], as a concentration is.
  const std::vector<int> alpha =
      alpha_textures(scene, [&](int index) { return texture(index, TextureUse::concentration); });
  for (const KTriangle& t : bvh.triangles) {
    KTexcoords c{};
    c.emission_texture = t.emitter >= 0 ? emitter_texture[t.emitter] : -1;
    c.alpha_texture = alpha[t.prim];
    const TriangleUv& uv = scene.uvs[t.prim];
    for (int k = 0; k < 3; ++k) {
      c.uv[2 * k] = static_cast<float>(uv[k].x());
      c.uv[2 * k + 1] = static_cast<float>(uv[k].y());
    }
    texcoords.push_back(c);
  }
}

// Per triangle in scene order, the KTexture of its shape's alpha (-1: none); a constant alpha
// becomes a checkerboard of that value on both squares.
std::vector<int> KernelSceneData::alpha_textures(const Scene& scene,
                                                 const std::function<int(int)>& scalar_texture) {
  std::vector<int> alpha(scene.triangles.size(), -1);
  for (const ShapeInfo& shape : scene.shapes) {
    if (!shape.cut_out()) continue;
    int k = -1;
    if (shape.alpha_texture >= 0) {
      k = scalar_texture(shape.alpha_texture);
    } else {
      KTexture c{};
      c.type = KASHA_TEXTURE_CHECKERBOARD;
      c.uscale = c.vscale = 1.0f;
      c.data = c.even = c.odd = c.lambda = -1;
      c.even_value = c.odd_value = static_cast<float>(shape.alpha);
      textures.push_back(c);
      k = static_cast<int>(textures.size()) - 1;
    }
    std::fill_n(alpha.begin() + shape.first_triangle, shape.triangle_count, k);
  }
  return alpha;
}

AlphaCutouts alpha_cutouts(const KernelSceneData& data) {
  AlphaCutouts a;
  bool any = false;
  for (const KTexcoords& c : data.texcoords) any = any || c.alpha_texture >= 0;
  if (!any) return a;
  a.texcoords.resize(data.texcoords.size());
  for (size_t i = 0; i < data.texcoords.size(); ++i)
    a.texcoords[data.bvh.triangles[i].prim] = data.texcoords[i];
  a.textures = data.textures;
  a.values = data.spectra;
  a.ops = data.tex_ops;
  return a;
}

KernelSceneData::KernelSceneData(const Scene& scene)
    : bvh(build_instanced_bvh(scene.triangles, scene.instances)),
      camera(scene.camera.to_kernel()),
      bin_nm(static_cast<float>(scene.grid.bin_nm)) {
  BinnedObserver obs(scene.grid);
  // The zero spectrum that kernels read in place of a material's absent part (offset 0).
  spectra.assign(scene.grid.bins, 0.0f);
  for (const Material& m : scene.materials) materials.push_back(kernel_material(m, scene, obs));
  // A normal map is looked up at the texture coordinates, in the frame of ∂p/∂u.
  const bool normal_mapped = scene.normal_mapped();
  if (scene.textured() || scene.emission_textured() || scene.cut_out() || normal_mapped)
    add_textures(scene);
  if (normal_mapped) add_normal_maps(scene);
  if (scene.shading_normals()) add_shading_normals(scene);
  if (scene.anisotropic() || normal_mapped) add_tangents(scene);
  for (const Emitter& e : scene.emitters) append(emitter_radiance, e.per_bin);
  for (const Light& l : scene.lights) append(emitter_radiance, l.per_bin);
  add_light_sampling(scene);
  media = device_media(scene, bvh.triangles, total_power, spectra);
  camera_medium = scene.camera_medium;
  for (size_t k = 0; k < lights.size(); ++k) lights[k].medium = scene.light_media[k];
}

// pbrt-v4's ∂p/∂u of each leaf triangle, from its texture coordinates (scene/triangle_dpdu.h).
void KernelSceneData::add_tangents(const Scene& scene) {
  for (const KTriangle& t : bvh.triangles) {
    const Triangle p = {Eigen::Vector3d(t.v0[0], t.v0[1], t.v0[2]),
                        Eigen::Vector3d(t.v1[0], t.v1[1], t.v1[2]),
                        Eigen::Vector3d(t.v2[0], t.v2[1], t.v2[2])};
    const Eigen::Vector3d d = triangle_dpdu(p, scene.uvs[t.prim]);
    tangents.push_back({{float(d.x()), float(d.y()), float(d.z())}, 0.0f});
  }
}

// The share of the Lambert part's samples sent through the surface: mean τ over mean ρ + τ, a
// constant of the material so every integrator's densities agree (kernels/materials/surface.h).
static float transmit_share(const Material& m) {
  double rho = 0, tau = 0;
  for (size_t i = 0; i < m.tau.size(); ++i) rho += m.rho[i], tau += m.tau[i];
  if (!(tau > 0)) return 0.0f;
  // Neither side's share quite 0, so a texture or spectrum that reflects where the mean
  // does not is still sampled.
  return static_cast<float>(std::clamp(tau / (rho + tau), 0.05, 0.95));
}

// A material in kernel layout, its spectra and gloss lobe appended to `spectra` and `lobes`.
KMaterial KernelSceneData::kernel_material(const Material& m, const Scene& scene,
                                           const BinnedObserver& obs) {
  KMaterial k{};
  k.passive = append(spectra, m.rho);
  k.excitation = append(spectra, m.a);
  k.transmittance = append(spectra, m.tau);
  k.transmit_share = transmit_share(m);
  k.emission = append(spectra, m.e_hat);
  k.gloss = static_cast<float>(m.gloss_reflectance());
  k.lobe = -1;
  if (m.gloss && !m.gloss->mirror) {
    k.lobe = static_cast<int>(lobes.size());
    k.cone_rad = static_cast<float>(m.gloss->cone_deg * M_PI / 180.0);
    std::vector<float> t = gloss_lobe_table(*m.gloss);
    lobes.insert(lobes.end(), t.begin(), t.end());
  }
  for (double a : m.a) k.excitation_sum += static_cast<float>(a);
  k.kind = m.kind == MaterialKind::dielectric  ? KASHA_KIND_DIELECTRIC
           : m.kind == MaterialKind::conductor ? KASHA_KIND_CONDUCTOR
           : m.kind == MaterialKind::mix       ? KASHA_KIND_MIX
           : m.kind == MaterialKind::interface ? KASHA_KIND_INTERFACE
                                               : KASHA_KIND_MEASURED;
  static_assert(kMaxMixDepth == KASHA_MIX_DEPTH, "mix depths differ");
  k.mix.materials[0] = k.mix.materials[1] = k.mix.amount_texture = -1;
  if (m.mix) {
    k.mix.materials[0] = m.mix->materials[0];
    k.mix.materials[1] = m.mix->materials[1];
    k.mix.amount = static_cast<float>(m.mix->amount);
  }
  k.eta = static_cast<float>(m.eta);
  k.thin = m.thin ? 1 : 0;
  k.eta_spectrum = append(spectra, m.kind == MaterialKind::conductor ? m.eta_c : m.eta_bins);
  k.k_spectrum = append(spectra, m.k_c);
  if (m.rough()) {
    k.alpha[0] = static_cast<float>(m.roughness.alpha_x);
    k.alpha[1] = static_cast<float>(m.roughness.alpha_y);
  }
  k.alpha_texture[0] = k.alpha_texture[1] = -1;  // set by add_textures
  k.remap_alpha = m.roughness.remap ? 1 : 0;
  k.coat_table = -1;
  if (m.coat) add_coat(*m.coat, k);
  if (!m.lambert_transmission.empty()) add_lambert_shape(*m.coat, m.lambert_transmission, k);
  k.under_coat = m.under_coat ? 1 : 0;
  k.layer_scale = static_cast<float>(m.layer_scale);
  albedo_xyz(m, scene.grid, obs, k.albedo_xyz);
  k.reflectance_texture = k.fluorescence_texture = k.normal_map = -1;
  return k;
}

// A coat's constants in `k`; a rough coat's tables appended to `spectra`.
void KernelSceneData::add_coat(const CoatDesc& c, KMaterial& k) {
  k.coat_eta = static_cast<float>(c.eta);
  k.coat_thickness = static_cast<float>(c.thickness);
  if (c.rough()) {
    static_assert(kCoatTableSize == KASHA_COAT_TABLE, "coat table sizes differ");
    const CoatTables t = rough_coat_tables(c);
    k.coat_alpha = static_cast<float>(c.alpha);
    k.coat_table = append(spectra, t.reflect);
    append(spectra, t.transmit);
    k.coat_internal = static_cast<float>(t.internal);
    k.coat_albedo = static_cast<float>(t.mean / (c.eta * c.eta));
  } else {
    k.coat_internal = static_cast<float>(coat_internal_reflectance(c));
    k.coat_albedo = static_cast<float>(coat_mean_transmission(c) / (c.eta * c.eta));
  }
}

// A layered metal's Lambert part (material/layered_metal.h): the coat's E(μ) (a smooth coat's
// F(μ), which the kernels do not read) and the part's own t(μ) as its coat table, no internal
// reflectance, and τ̄ / η² from that t(μ).
void KernelSceneData::add_lambert_shape(const CoatDesc& c, const std::vector<double>& t,
                                        KMaterial& k) {
  std::vector<double> reflect(kCoatTableSize);
  const CoatTables rough = c.rough() ? rough_coat_tables(c) : CoatTables{};
  for (int i = 0; i < kCoatTableSize; ++i)
    reflect[i] = c.rough()
                     ? rough.reflect[i]
                     : fresnel_dielectric(static_cast<double>(i) / (kCoatTableSize - 1), c.eta);
  k.coat_table = append(spectra, reflect);
  append(spectra, t);
  k.coat_internal = 0;
  k.coat_albedo = static_cast<float>(coat_table_mean(t) / (c.eta * c.eta));
}

// Each normal map a used material has, as a KTexture of three floats a texel (the image's RGB,
// kernels/materials/normal_map.h), repeating and bilinear as pbrt-v4 looks normal maps up.
void KernelSceneData::add_normal_maps(const Scene& scene) {
  std::vector<int> made(scene.normal_maps.size(), -1);
  for (int i : scene.used_materials()) {
    const int map = scene.material_textures[i].normal_map;
    if (map < 0) continue;
    if (made[map] < 0) {
      const RgbImage& image = scene.normal_maps[map].image;
      KTexture k{};
      k.type = KASHA_TEXTURE_IMAGE;
      k.width = image.width;
      k.height = image.height;
      k.wrap = KASHA_WRAP_REPEAT;
      k.bilinear = 1;
      k.uscale = k.vscale = 1.0f;
      k.even = k.odd = k.lambda = -1;
      k.data = static_cast<int>(spectra.size());
      spectra.insert(spectra.end(), image.rgb.begin(), image.rgb.end());
      textures.push_back(k);
      made[map] = static_cast<int>(textures.size()) - 1;
    }
    materials[i].normal_map = made[map];
  }
}

void KernelSceneData::add_shading_normals(const Scene& scene) {
  for (const KTriangle& t : bvh.triangles) {
    KShadingNormals n{};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) n.n[3 * k + c] = static_cast<float>(scene.normals[t.prim][k][c]);
    normals.push_back(n);
  }
}

// Per emitting triangle (`emitting`, leaf order), its shape's sphere light (radius 0: none); empty
// where no shape is one. The radius holds the float vertices as the kernels test them, from the
// float centre, with a margin for the kernels' rounding: the mesh lies inside the cone sampled.
static std::vector<KSphereLight> sphere_lights(const Scene& scene,
                                               const std::vector<KTriangle>& tris,
                                               const std::vector<int>& emitting) {
  std::vector<int> shape_of(scene.triangles.size(), -1);
  bool any = false;
  for (size_t k = 0; k < scene.shapes.size(); ++k) {
    const ShapeInfo& s = scene.shapes[k];
    if (!s.sphere_light) continue;
    any = true;
    std::fill_n(shape_of.begin() + s.first_triangle, s.triangle_count, static_cast<int>(k));
  }
  if (!any) return {};
  std::vector<KSphereLight> out(emitting.size(), KSphereLight{});
  std::vector<double> reach(scene.shapes.size(), 0.0);
  for (int pass = 0; pass < 2; ++pass)
    for (size_t j = 0; j < emitting.size(); ++j) {
      const KTriangle& t = tris[emitting[j]];
      const int k = shape_of[t.prim];
      if (k < 0) continue;
      const Eigen::Vector3d c = scene.shapes[k].sphere_light->centre.cast<float>().cast<double>();
      KSphereLight& l = out[j];
      for (int a = 0; a < 3; ++a) l.centre[a] = static_cast<float>(c[a]);
      if (pass == 0) {
        for (const float* v : {t.v0, t.v1, t.v2})
          reach[k] = std::max(reach[k], (Eigen::Vector3d(v[0], v[1], v[2]) - c).norm());
      } else {
        l.radius = static_cast<float>(reach[k] * (1 + 1e-5) + 1e-6 * c.cwiseAbs().maxCoeff());
      }
    }
  return out;
}

// Lights, in leaf order so kernels index the triangles they traverse: the emitting triangles,
// then the lights that are not triangles, each picked in proportion to its power.
void KernelSceneData::add_light_sampling(const Scene& scene) {
  std::vector<double> power;
  const auto sample = [&](int light, double p) {
    light_tri.push_back(light);
    power.push_back(p);
    total_power += p;
  };
  std::vector<double> radiance_sum;
  for (const Emitter& e : scene.emitters)
    radiance_sum.push_back(e.integrated_radiance(scene.grid.bin_nm));
  for (size_t i = 0; i < bvh.triangles.size(); ++i) {
    const KTriangle& t = bvh.triangles[i];
    if (t.emitter < 0) continue;
    double p = emitted_power(t, radiance_sum[t.emitter]) * scene.emitters[t.emitter].texture_mean;
    if (p > 0) sample(static_cast<int>(i), p);
  }
  light_triangles = static_cast<int>(light_tri.size());
  light_spheres = sphere_lights(scene, bvh.triangles, light_tri);
  light_bvh = build_light_bvh(bvh.triangles, light_tri, power, light_spheres);
  Eigen::Vector3d centre;
  double radius;
  scene.bounding_sphere(centre, radius);
  for (size_t k = 0; k < scene.lights.size(); ++k) {
    const Light& l = scene.lights[k];
    lights.push_back(kernel_light(l, static_cast<int>(scene.emitters.size() + k), centre, radius));
    if (l.environment) add_environment(l, scene, lights.back());
    double p = l.power(scene.grid.bin_nm, radius);
    if (p > 0) sample(~static_cast<int>(k), p);
  }
  double cdf = 0;
  for (size_t j = 0; j < power.size(); ++j) {
    light_cdf.push_back(static_cast<float>((cdf += power[j]) / total_power));
    if (light_tri[j] < 0) lights[~light_tri[j]].pick = static_cast<float>(power[j] / total_power);
  }
  if (!light_cdf.empty()) light_cdf.back() = 1.0f;
  // An emission texture weighs its emitter's triangles by its mean (their power above).
  for (size_t e = 0; e < radiance_sum.size(); ++e)
    emitter_area_pdf.push_back(total_power > 0 ? static_cast<float>(M_PI * radiance_sum[e] *
                                                                    scene.emitters[e].texture_mean /
                                                                    total_power)
                                               : 0.0f);
}

// A light that is not a triangle in kernel layout; a distant or infinite one is placed at the
// centre of the scene's bounding sphere.
KLight KernelSceneData::kernel_light(const Light& l, int spectrum, const Eigen::Vector3d& centre,
                                     double radius) {
  KLight kl{};
  kl.type = l.type == LightType::point     ? KASHA_LIGHT_POINT
            : l.type == LightType::spot    ? KASHA_LIGHT_SPOT
            : l.type == LightType::distant ? KASHA_LIGHT_DISTANT
                                           : KASHA_LIGHT_INFINITE;
  kl.spectrum = spectrum;
  kl.image = kl.distribution = -1;
  const bool far = l.type == LightType::distant || l.type == LightType::infinite;
  const Eigen::Vector3d at = far ? centre : l.position;
  for (int c = 0; c < 3; ++c) {
    kl.position[c] = static_cast<float>(at[c]);
    kl.axis[c] = static_cast<float>(l.direction[c]);
  }
  kl.radius = static_cast<float>(radius);
  kl.cos_total = static_cast<float>(l.cos_total());
  kl.cos_falloff = static_cast<float>(l.cos_falloff());
  kl.lambda = -1;
  return kl;
}

// An environment light's image and its sampling distribution, appended to `spectra`.
void KernelSceneData::add_environment(const Light& l, const Scene& scene, KLight& kl) {
  const EnvironmentImage& env = *l.environment;
  const EnvironmentData& d = *l.environment_data;
  kl.width = env.image.width;
  kl.height = env.image.height;
  kl.mapping = env.mapping == EnvironmentMapping::equal_area ? KASHA_MAPPING_EQUAL_AREA
                                                             : KASHA_MAPPING_LATLONG;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) kl.to_light[3 * r + c] = static_cast<float>(env.to_light(r, c));
  kl.general = env.orthogonal ? 0 : 1;
  kl.image = static_cast<int>(spectra.size());
  spectra.insert(spectra.end(), d.texels.begin(), d.texels.end());
  kl.distribution = static_cast<int>(spectra.size());
  spectra.insert(spectra.end(), d.distribution.begin(), d.distribution.end());
  kl.lambda = bin_centres(scene);
}

size_t KernelSceneData::bytes() const {
  return bvh.nodes.size() * sizeof(KBvhNode) + bvh.leaves.size() * sizeof(KBvhLeaf) +
         bvh.triangles.size() * sizeof(KTriangle) + materials.size() * sizeof(KMaterial) +
         lights.size() * sizeof(KLight) + textures.size() * sizeof(KTexture) +
         texcoords.size() * sizeof(KTexcoords) + normals.size() * sizeof(KShadingNormals) +
         (spectra.size() + lobes.size() + emitter_radiance.size() + light_cdf.size() +
          emitter_area_pdf.size()) *
             sizeof(float) +
         light_tri.size() * sizeof(int) + light_spheres.size() * sizeof(KSphereLight) +
         light_bvh.nodes.size() * sizeof(KLightNode) +
         light_bvh.trails.size() * sizeof(std::uint64_t) +
         bvh.instances.size() * sizeof(KInstance) + tangents.size() * sizeof(KTangent) +
         tex_ops.size() * sizeof(KTexOp) + media.media.size() * sizeof(KMedium) +
         media.tri_media.size() * sizeof(KTriMedia);
}

// Scratch spectra per work item: an environment texel's radiance, then a textured reflectance
// and a textured excitation, then a coated material's effective reflectance, emission and
// excitation (kernels/materials/coat.h).
static int scratch_texture_offset(const Scene& scene) {
  return scene.has_environment() ? scene.grid.bins : 0;
}

static int scratch_coat_offset(const Scene& scene) {
  // A texture's reflectance, excitation and (over a transmitting material) transmittance.
  const int slots = scene.transmissive() ? 3 : 2;
  return scratch_texture_offset(scene) + (scene.textured() ? slots * scene.grid.bins : 0);
}

static int scratch_media_offset(const Scene& scene) {
  return scratch_coat_offset(scene) + (scene.coated() ? 3 * scene.grid.bins : 0);
}

// The most components a colour grid of the scene has (kernels/media/colour_grid.h), 0: none.
static size_t grid_components(const Scene& scene) {
  size_t most = 0;
  if (scene.has_media())
    for (const Medium& m : scene.media) most = std::max(most, m.components.size());
  return most;
}

// After the coat's: a shadow ray's transmittance through media (kernels/media/medium.h).
static int scratch_components_offset(const Scene& scene) {
  return scratch_media_offset(scene) + (scene.has_media() ? scene.grid.bins : 0);
}

// Then a colour grid's σt and σs at two points (kernels/media/colour_grid.h).
int scratch_floats(const Scene& scene) {
  return scratch_components_offset(scene) + (grid_components(scene) > 0 ? 4 * scene.grid.bins : 0);
}

KernelDefines scene_defines(const Scene& scene, bool spectral_film) {
  KernelDefines d;
  d["KASHA_BINS"] = std::to_string(scene.grid.bins);
  d["KASHA_SPECTRAL_FILM"] = spectral_film ? "1" : "0";
  d["KASHA_FILM_ROWS"] = std::to_string(spectral_film ? scene.grid.bins : 3);
  d["KASHA_FLUORESCENCE"] = scene.fluorescent() ? "1" : "0";
  d["KASHA_GLOSS"] = scene.glossy() ? "1" : "0";
  d["KASHA_DIELECTRIC"] = scene.uses(MaterialKind::dielectric) ? "1" : "0";
  d["KASHA_CONDUCTOR"] = scene.uses(MaterialKind::conductor) ? "1" : "0";
  d["KASHA_DISPERSION"] = scene.dispersive() ? "1" : "0";
  d["KASHA_ROUGH"] = scene.rough() ? "1" : "0";
  d["KASHA_ANISOTROPIC"] = scene.anisotropic() ? "1" : "0";
  d["KASHA_ROUGHNESS_TEXTURES"] = scene.roughness_textured() ? "1" : "0";
  // Each light kind's code only where the scene has one (docs/lights.md).
  d["KASHA_LIGHT_SOURCES"] = scene.lights.empty() ? "0" : "1";
  d["KASHA_SPOT_LIGHTS"] = scene.has_light(LightType::spot) ? "1" : "0";
  d["KASHA_INFINITE_LIGHTS"] = scene.has_light(LightType::infinite) ? "1" : "0";
  const bool spheres = std::any_of(scene.shapes.begin(), scene.shapes.end(),
                                   [](const ShapeInfo& s) { return s.sphere_light.has_value(); });
  d["KASHA_SPHERE_LIGHTS"] = spheres ? "1" : "0";
  d["KASHA_ENVIRONMENT"] = scene.has_environment() ? "1" : "0";
  // Spectra computed per work item on the way (an environment texel's radiance).
  d["KASHA_SCRATCH_FLOATS"] = std::to_string(scratch_floats(scene));
  d["KASHA_TEXTURES"] = scene.textured() || scene.emission_textured() ? "1" : "0";
  d["KASHA_EMISSION_TEXTURES"] = scene.emission_textured() ? "1" : "0";
  const bool programs = std::any_of(scene.textures.begin(), scene.textures.end(),
                                    [](const Texture& t) { return t.program(); });
  d["KASHA_TEXTURE_PROGRAMS"] = programs ? "1" : "0";
  d["KASHA_ALPHA"] = scene.cut_out() ? "1" : "0";
  d["KASHA_INSTANCES"] = scene.instances.empty() ? "0" : "1";
  d["KASHA_SCRATCH_TEXTURES"] = std::to_string(scratch_texture_offset(scene));
  d["KASHA_COATED"] = scene.coated() ? "1" : "0";
  d["KASHA_TRANSMISSION"] = scene.transmissive() ? "1" : "0";
  d["KASHA_THIN"] = scene.thin() ? "1" : "0";
  d["KASHA_MIX"] = scene.mixed() ? "1" : "0";
  // A normal map shades about a normal of its own, as vertex normals do.
  d["KASHA_SHADING_NORMALS"] = scene.shading_normals() || scene.normal_mapped() ? "1" : "0";
  d["KASHA_VERTEX_NORMALS"] = scene.shading_normals() ? "1" : "0";
  d["KASHA_NORMAL_MAPS"] = scene.normal_mapped() ? "1" : "0";
  d["KASHA_SCRATCH_COAT"] = std::to_string(scratch_coat_offset(scene));
  // Media only where a ray can travel in one (docs/media.md): other scenes keep their kernels.
  d["KASHA_MEDIA"] = scene.has_media() ? "1" : "0";
  d["KASHA_SCATTERING"] = scene.scattering() ? "1" : "0";
  d["KASHA_MEDIUM_BOUNDARIES"] = scene.triangle_media.empty() ? "0" : "1";
  const bool grids =
      scene.has_media() && std::any_of(scene.media.begin(), scene.media.end(),
                                       [](const Medium& m) { return m.grid.has_value(); });
  d["KASHA_MEDIUM_GRIDS"] = grids ? "1" : "0";
  d["KASHA_MEDIUM_EMISSION"] = scene.emitting_medium() >= 0 ? "1" : "0";
  // A blackbody's spectrum is computed per collision, in registers: only where a medium has one.
  const bool blackbody = scene.emitting_medium() >= 0 &&
                         std::any_of(scene.media.begin(), scene.media.end(),
                                     [](const Medium& m) { return m.blackbody.has_value(); });
  d["KASHA_MEDIUM_BLACKBODY"] = grids && blackbody ? "1" : "0";
  d["KASHA_MEDIA_COUNT"] = std::to_string(std::max<size_t>(1, scene.media.size()));
  d["KASHA_SCRATCH_MEDIA"] = std::to_string(scratch_media_offset(scene));
  // A colour grid's components: private arrays that size, a trail slot each.
  d["KASHA_GRID_COMPONENTS"] = std::to_string(grid_components(scene));
  size_t slots = std::max<size_t>(1, scene.media.size());
  for (const Medium& m : scene.media) slots += std::max<size_t>(1, m.components.size()) - 1;
  d["KASHA_TRAIL_SLOTS"] = std::to_string(slots);
  d["KASHA_SCRATCH_COMPONENTS"] = std::to_string(scratch_components_offset(scene));
  return d;
}

int DeviceScene::bind(cl::Kernel& k, int a, size_t items) {
  // The launch's scratch spectra: grown to the largest launch so far, never shrunk.
  const size_t need = std::max<size_t>(1, items * scratch_floats_) * sizeof(float);
  if (need > scratch_bytes_) {
    scratch_ = device_buffer(cl_, need, "the work items' scratch spectra");
    scratch_bytes_ = need;
  }
  k.setArg(a++, params_);
  k.setArg(a++, tables_);
  k.setArg(a++, scratch_);
  return a;
}

DeviceScene::DeviceScene(ClContext& cl, const Scene& scene)
    : data_(scene), cl_(cl), scratch_floats_(scratch_floats(scene)) {
  KSceneParams& p = params_;
  p.camera = data_.camera;
  p.light_count = static_cast<int>(data_.light_tri.size());
  p.bin_nm = data_.bin_nm;
  p.light_sources = static_cast<int>(data_.lights.size());
  p.light_triangles = data_.light_triangles;
  p.camera_medium = data_.camera_medium;
  Eigen::Vector3d centre;
  double radius;
  scene.bounding_sphere(centre, radius);
  p.scene_radius = static_cast<float>(radius);
  for (int k = 0; k < 3; ++k) p.scene_center[k] = static_cast<float>(centre[k]);
  tables_ = upload_tables(cl, {host_table(data_.bvh.nodes, p.nodes),
                               host_table(data_.bvh.leaves, p.leaves),
                               host_table(data_.bvh.triangles, p.tris),
                               host_table(data_.materials, p.materials),
                               host_table(data_.spectra, p.spectra),
                               host_table(data_.lobes, p.lobes),
                               host_table(data_.emitter_radiance, p.emitter_radiance),
                               host_table(data_.emitter_area_pdf, p.emitter_area_pdf),
                               host_table(data_.light_tri, p.light_tri),
                               host_table(data_.light_cdf, p.light_cdf),
                               host_table(data_.lights, p.lights),
                               host_table(data_.textures, p.textures),
                               host_table(data_.texcoords, p.texcoords),
                               host_table(data_.normals, p.normals),
                               host_table(data_.light_bvh.nodes, p.light_nodes),
                               host_table(data_.light_bvh.trails, p.light_trails),
                               host_table(data_.bvh.instances, p.instances),
                               host_table(data_.tangents, p.tangents),
                               host_table(data_.light_spheres, p.light_spheres),
                               host_table(data_.tex_ops, p.tex_ops),
                               host_table(data_.media.media, p.media),
                               host_table(data_.media.tri_media, p.tri_media)});
}

}  // namespace kasha
