#pragma once
// Files compiled into the binary (kernel sources, built-in spectral tables); see
// cmake/EmbedFiles.cmake.
#include <string>
#include <vector>

namespace kasha {

struct EmbeddedFile {
  std::string name;
  std::string contents;
};

const std::vector<EmbeddedFile>& kasha_embedded_kernels();
const std::vector<EmbeddedFile>& kasha_embedded_data();

// The contents of an embedded file by name; throws if it is not there (a build error, not user
// error).
const std::string& embedded_kernel(const std::string& name);
const std::string& embedded_data(const std::string& name);

}  // namespace kasha
