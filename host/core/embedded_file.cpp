#include "core/embedded_file.h"

#include <stdexcept>

namespace kasha {

static const std::string& find_embedded(const std::vector<EmbeddedFile>& files,
                                        const std::string& name) {
  for (const EmbeddedFile& f : files)
    if (f.name == name) return f.contents;
  throw std::logic_error("embedded file '" + name + "' is missing from the build");
}

const std::string& embedded_kernel(const std::string& name) {
  return find_embedded(kasha_embedded_kernels(), name);
}

const std::string& embedded_data(const std::string& name) {
  return find_embedded(kasha_embedded_data(), name);
}

}  // namespace kasha
