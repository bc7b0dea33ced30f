#pragma once
// What ranks > 0 run for `mpirun … kasha render …`: the same command line's scene (read from the
// same path: the ranks share a file system) on this rank's own --device list, one RenderJob per
// device, and a thread per device answering rank 0's requests on the device's tag (mpi/
// remote_lane.h) until rank 0 says stop. The rank writes nothing and prints nothing: a failure
// goes to rank 0 as one line, in the hello or in the answer to the request that failed.
#include <string>

#include "render/render_spec.h"

namespace kasha {

// Returns once rank 0 has said stop: 0, as a rank's failure is rank 0's to report.
int serve_render(const RenderSpec& spec);

// A rank > 0 that will not serve a render (its command line failed to parse, or names another
// command) says so in its hello, in case rank 0 renders and waits for it; `why` is one line.
void refuse_render(const std::string& why);

}  // namespace kasha
