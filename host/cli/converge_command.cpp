#include "cli/converge_command.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/interrupt.h"
#include "core/output_set.h"
#include "study/reference_image.h"

namespace kasha {

int run_converge(const std::string& scene, const std::string& integrators, StudyOptions study) {
  install_interrupt_handler();
  if (!integrators.empty()) {  // else every physical integrator
    study.integrators.clear();
    std::stringstream list(integrators);
    for (std::string name; std::getline(list, name, ',');) study.integrators.push_back(name);
  }
  // The folder is made as a temporary and renamed once the study is complete, so a failed run
  // leaves none (or, when it exists, leaves its files as they were).
  OutputSet outputs;
  outputs.input(scene, "the scene file");
  if (study.reference != "furnace") outputs.input(study.reference, "the --reference image");
  const std::string out_dir = study.out_dir;
  outputs.directory("-o", out_dir);
  study.out_dir = outputs.staging(out_dir);
  StudyResult r = run_convergence_study(scene, study);
  outputs.inputs_read("the scene's material or data file");
  outputs.commit();
  std::printf(
      "converge: reference %s; wrote "
      "%s/{summary.md,summary.csv,convergence.png,images.png,log_*.csv}\n",
      r.reference_description.c_str(), out_dir.c_str());
  std::ifstream summary(out_dir + "/summary.md");
  std::printf("%s", std::string(std::istreambuf_iterator<char>(summary), {}).c_str());
  return 0;
}

int run_reference(const std::string& scene_path, double seconds, unsigned seed,
                  const std::string& device,
                  const std::string& out) {
  install_interrupt_handler();
  OutputSet outputs;
  outputs.input(scene_path, "the scene file");
  outputs.file("-o", out);
  Scene scene = load_scene(scene_path);
  outputs.inputs_read("the scene's material or data file");
  DeviceSet devices(device);
  ReferenceInfo info;
  Image image = render_reference(devices, scene, seconds, seed, info, true);
  outputs.write(out, [&](const std::string& tmp) { write_reference(tmp, image, info); });
  outputs.commit();
  std::fprintf(stderr, "wrote %s: %s, %.1f s, %lld samples per pixel\n", out.c_str(),
               info.integrator.c_str(), info.seconds, info.samples_per_pixel);
  return 0;
}

}  // namespace kasha
