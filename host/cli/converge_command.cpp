// `kasha converge`: error against run time for several integrators on one scene, against a
// reference it renders and caches, or one given (an EXR or the analytic furnace).
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>

#include "cli/command.h"
#include "cli/command_line_errors.h"
#include "cli/render_options.h"
#include "core/interrupt.h"
#include "core/output_set.h"
#include "core/printable.h"
#include "study/convergence_study.h"
#include "study/reference_image.h"

namespace kasha {

static int run_converge(const std::string& scene, const std::string& integrators,
                        StudyOptions study) {
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
  if (study.reference != kFurnaceReference) outputs.input(study.reference, "the --reference image");
  const std::string out_dir = study.out_dir;
  outputs.directory("-o", out_dir);
  study.out_dir = outputs.staging(out_dir);
  StudyResult r = run_convergence_study(scene, study);
  outputs.inputs_read("the scene's material or data file");
  outputs.commit();
  std::printf(
      "converge: reference %s; wrote "
      "%s/{summary.md,summary.csv,convergence.png,images.png,log_*.csv}\n",
      printable(r.reference_description).c_str(), printable(out_dir).c_str());
  std::ifstream summary(out_dir + "/summary.md");
  std::printf("%s", std::string(std::istreambuf_iterator<char>(summary), {}).c_str());
  return 0;
}

static Command::Action declare_converge(CLI::App& app) {
  struct Args {
    std::string scene, integrators;
    StudyOptions study;
  };
  auto a = std::make_shared<Args>();
  StudyOptions& study = a->study;
  app.add_option("scene", a->scene, "scene JSON file")->required();
  app.add_option("--integrators", a->integrators, "comma-separated (default: every physical one)")
      ->check(cli::list_of(IntegratorRegistry::names(true), "integrator"));
  app.add_option("--time", study.seconds, "rendering seconds per integrator and run")
      ->required()
      ->check(cli::positive_number(cli::kMaxSeconds));
  app.add_option("--reference", study.reference,
                 "reference EXR or `furnace` (default: cached next to the scene)");
  app.add_option("--reference-time", study.reference_seconds,
                 "seconds for a new cached reference (default 4 × time × integrators)")
      ->check(cli::positive_number(cli::kMaxSeconds));
  app.add_option("--repeats", study.repeats, "runs per integrator, seeds 1..K, for error bars")
      ->check(cli::integer_within(1, 1000));
  app.add_option("--target", study.target,
                 "RMSE whose time to reach is reported (default: the worst final)")
      ->check(cli::positive_number());
  cli::add_setting_options(app, study.settings, {"--spp", "--photons"});
  cli::add_device_option(app, study.device);
  cli::add_setting_options(app, study.settings, {"--sampler"});
  app.add_option("-o,--output", study.out_dir, "directory for logs, plot, images and summary")
      ->required();
  return [a] { return run_converge(a->scene, a->integrators, a->study); };
}

KASHA_REGISTER_COMMAND(converge, "converge", "error against run time for several integrators", 9,
                       false, declare_converge);

}  // namespace kasha
