// `kasha devices`: the OpenCL platforms and devices, with the index `--device` takes.
#include <cstdio>

#include "cli/command.h"
#include "opencl/device.h"

namespace kasha {

static int run_devices() {
  for (const DeviceInfo& d : list_devices()) {
    std::printf("%d: %s — %s [%s, %s, %u compute units, %.1f GiB]\n", d.index, d.platform.c_str(),
                d.name.c_str(), d.type.c_str(), d.version.c_str(), d.compute_units,
                d.global_mem_bytes / 1073741824.0);
  }
  return 0;
}

KASHA_REGISTER_COMMAND(devices, "devices", "list OpenCL platforms and devices", 1, false,
                       [](CLI::App&) -> Command::Action { return run_devices; });

}  // namespace kasha
