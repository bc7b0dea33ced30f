#include "render/kernel_launcher.h"

#include <algorithm>

namespace kasha {

size_t KernelLauncher::work_group_size(cl::Kernel& kernel) {
  size_t most = kernel.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(cl_.device());
  return std::max<size_t>(1, std::min<size_t>(64, most));
}

}  // namespace kasha
