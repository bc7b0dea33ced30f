#include "cli/converge_command.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/interrupt.h"
#include "study/reference_image.h"

namespace kasha {

int run_converge(const std::string& scene, const std::string& integrators, StudyOptions study) {
  install_interrupt_handler();
  if (!integrators.empty()) {  // else every physical integrator
    study.integrators.clear();
    std::stringstream list(integrators);
    for (std::string name; std::getline(list, name, ',');) study.integrators.push_back(name);
  }
  StudyResult r = run_convergence_study(scene, study);
  std::printf(
      "converge: reference %s; wrote "
      "%s/{summary.md,summary.csv,convergence.png,images.png,log_*.csv}\n",
      r.reference_description.c_str(), study.out_dir.c_str());
  std::ifstream summary(study.out_dir + "/summary.md");
  std::printf("%s", std::string(std::istreambuf_iterator<char>(summary), {}).c_str());
  return 0;
}

int run_reference(const std::string& scene_path, double seconds, unsigned seed, int device,
                  const std::string& out) {
  install_interrupt_handler();
  Scene scene = load_scene(scene_path);
  ClContext cl(device);
  ReferenceInfo info;
  Image image = render_reference(cl, scene, seconds, seed, info, true);
  write_reference(out, image, info);
  std::fprintf(stderr, "wrote %s: %s, %.1f s, %lld samples per pixel\n", out.c_str(),
               info.integrator.c_str(), info.seconds, info.samples_per_pixel);
  return 0;
}

}  // namespace kasha
