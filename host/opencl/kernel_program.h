#pragma once
// Kernel programs built at run time from the sources compiled into the binary, with per-scene
// preprocessor definitions (docs/architecture.md).
#include <map>
#include <string>
#include <vector>

#include "opencl/device.h"

namespace kasha {

// Preprocessor definitions, rendered as "-D NAME=VALUE" in a stable order.
using KernelDefines = std::map<std::string, std::string>;
std::string build_options(const KernelDefines& defines);

// The source of an embedded kernel file with its quoted #includes of other embedded files inlined
// (each once), so the text PoCL caches on is the whole program.
std::string assemble_kernel_source(const std::string& main_file);
// The same for a source text that is not embedded (a test kernel), named `name` in #line markers.
std::string assemble_kernel_source_text(const std::string& source, const std::string& name);

// Builds a program; a failure throws kasha::Error carrying the device's build log.
cl::Program build_program(ClContext& cl, const std::string& source, const KernelDefines& defines,
                          const std::string& what);

}  // namespace kasha
