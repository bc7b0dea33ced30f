// `kasha info`: what a scene needs before it is rendered: its grid, features, geometry, kernel
// build options, record sizes and a memory estimate.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/command.h"
#include "cli/command_line_errors.h"
#include "cli/render_options.h"
#include "core/printable.h"
#include "opencl/device.h"
#include "render/device_scene.h"
#include "render/record_bytes.h"
#include "scene/scene.h"

namespace kasha {

namespace {
std::string bytes_text(double b) {
  char t[64];
  if (b >= 1 << 30)
    std::snprintf(t, sizeof t, "%.2f GiB", b / (1 << 30));
  else if (b >= 1 << 20)
    std::snprintf(t, sizeof t, "%.2f MiB", b / (1 << 20));
  else if (b >= 1 << 10)
    std::snprintf(t, sizeof t, "%.1f KiB", b / (1 << 10));
  else
    std::snprintf(t, sizeof t, "%.0f B", b);
  return t;
}

}  // namespace

static int run_info(const std::string& scene_path, bool spectral, const std::string& lamp,
                    const std::vector<MaterialOverride>& materials, double bin_nm) {
  Scene scene = load_scene(scene_path, bins_request(bin_nm), lamp, materials);
  KernelSceneData data(scene);
  int emitting_triangles = 0;
  for (const Emitter& e : scene.emitters) emitting_triangles += e.triangle_count;
  // The file name and lamp names are input bytes: printable() keeps terminal controls out.
  std::printf("scene: %s\n", printable(scene_path).c_str());
  std::printf("wavelengths: %s\n", scene.grid.describe().c_str());
  auto yes = [](bool b) { return b ? "yes" : "no"; };
  std::printf(
      "features: fluorescence %s, gloss %s, dielectric %s, conductor %s, dispersion %s, rough %s, "
      "coated %s, shading normals %s, normal maps %s, textures %s, emission textures %s, "
      "environment %s\n",
      yes(scene.fluorescent()), yes(scene.glossy()), yes(scene.uses(MaterialKind::dielectric)),
      yes(scene.uses(MaterialKind::conductor)), yes(scene.dispersive()), yes(scene.rough()),
      yes(scene.coated()), yes(scene.shading_normals()), yes(scene.normal_mapped()),
      yes(scene.textured()), yes(scene.emission_textured()), yes(scene.has_environment()));
  std::printf("materials: %zu; shapes: %zu; triangles: %zu; emitters: %zu (%d triangles)\n",
              scene.materials.size(), scene.shapes.size(), scene.triangles.size(),
              scene.emitters.size(), emitting_triangles);
  // Participating media (docs/media.md): each one's name, the camera's, and the boundaries.
  if (scene.has_media()) {
    std::string names;
    for (const MediumDesc& m : scene.medium_descs) names += (names.empty() ? "" : ", ") + printable(m.name);
    const long boundaries = std::count_if(scene.shapes.begin(), scene.shapes.end(),
                                          [](const ShapeInfo& s) { return s.medium.transition(); });
    std::printf("media: %zu (%s); camera in %s; shapes bounding media: %ld\n", scene.medium_descs.size(),
                names.c_str(),
                scene.camera_medium >= 0 ? printable(scene.medium_descs[scene.camera_medium].name).c_str()
                                         : "vacuum",
                boundaries);
  }
  if (!scene.instances.empty())
    std::printf("instances: %zu of %zu objects; triangles placed: %zu (each stored once)\n",
                scene.instances.placements.size(), scene.instances.objects.size(),
                scene.placed_triangles());
  // The lights that are not shapes, with the share of light sampling each gets (its power's).
  for (size_t k = 0; k < scene.lights.size(); ++k) {
    const Light& l = scene.lights[k];
    std::printf("light %zu: %s, %.4g W, picked %.3g %%\n", k, light_type_name(l.type),
                data.total_power > 0 ? data.lights[k].pick * data.total_power : 0.0,
                100.0 * data.lights[k].pick);
  }
  if (!scene.lamp_names.empty()) {
    std::string names;
    for (const std::string& n : scene.lamp_names)
      names += (names.empty() ? "" : ", ") + printable(n);
    std::printf("lamp: %s (lamps: %s)\n", printable(scene.lamp).c_str(), names.c_str());
  }
  std::printf("bvh: %zu nodes, %zu leaves, depth %d (Embree SAH, %d-wide, leaves of <= %d)\n",
              data.bvh.nodes.size(), data.bvh.leaves.size(), data.bvh.depth, KASHA_BVH_WIDTH,
              KASHA_BVH_LEAF_SIZE);
  std::printf("camera: %dx%d, fov %g deg\n", scene.camera.width, scene.camera.height,
              scene.camera.fov_deg);
  std::printf("kernel build options: %s\n", build_options(scene_defines(scene, spectral)).c_str());
  size_t rows_count = spectral ? scene.grid.bins : 3;
  const bool media = scene.scattering();
  std::printf(
      "photon mapping: %zu bytes per photon (position, normal, key, %d bins%s); %zu bytes per "
      "visible point (geometry 8 values%s%s)\n",
      photon_record_bytes(scene), scene.grid.bins, media ? ", direction" : "",
      visible_point_bytes(scene, spectral),
      scene.fluorescent()
          ? (", K = C∘d + c bᵀ: 2N + R = " + std::to_string(2 * scene.grid.bins + rows_count) +
             " values")
                .c_str()
          : (", K = C∘d: N = " + std::to_string(scene.grid.bins) + " values").c_str(),
      media ? ", ωo and g in a medium: 4 values" : "");
  size_t pixels = static_cast<size_t>(scene.camera.width) * scene.camera.height;
  size_t rows = spectral ? scene.grid.bins : 3;
  std::printf(
      "memory: scene %s (bvh %s, triangles %s, materials and spectra %s); film %s on the device, "
      "%s on the host\n",
      bytes_text(data.bytes()).c_str(),
      bytes_text(data.bvh.nodes.size() * sizeof(KBvhNode) +
                 data.bvh.leaves.size() * sizeof(KBvhLeaf))
          .c_str(),
      bytes_text(data.bvh.triangles.size() * sizeof(KTriangle)).c_str(),
      bytes_text(data.materials.size() * sizeof(KMaterial) +
                 (data.spectra.size() + data.emitter_radiance.size()) * sizeof(float))
          .c_str(),
      bytes_text(pixels * rows * sizeof(float)).c_str(),
      bytes_text(pixels * rows * sizeof(double)).c_str());
  return 0;
}

static Command::Action declare_info(CLI::App& app) {
  struct Args {
    std::string scene, lamp;
    std::vector<MaterialOverride> materials;
    bool spectral = false;
    double bin_nm = 0;
  };
  auto a = std::make_shared<Args>();
  app.add_option("scene", a->scene, "scene: kasha JSON or pbrt-v4 (.pbrt)")->required();
  app.add_flag("--spectral", a->spectral, "report for a spectral film");
  app.add_option("--lamp", a->lamp, "switch on this one of the scene's \"lamps\"");
  cli::add_material_option(app, a->materials);
  cli::add_bin_option(app, a->bin_nm);
  return [a] { return run_info(a->scene, a->spectral, a->lamp, a->materials, a->bin_nm); };
}

KASHA_REGISTER_COMMAND(info, "info",
                       "what a scene needs: bins, features, memory, kernel build options", 2, false,
                       declare_info);

}  // namespace kasha
