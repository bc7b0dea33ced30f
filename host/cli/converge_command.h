#pragma once
// `kasha converge` and `kasha reference`: error against run time, and the references it needs.
#include <string>

#include "study/convergence_study.h"

namespace kasha {

// `integrators` is the comma-separated list from the command line.
int run_converge(const std::string& scene, const std::string& integrators, StudyOptions study);
int run_reference(const std::string& scene, double seconds, unsigned seed, const std::string& device,
                  const std::string& out);

}  // namespace kasha
