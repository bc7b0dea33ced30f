#include "core/atomic_file.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace kasha {

void write_atomically(const std::string& path,
                      const std::function<void(const std::string&)>& write) {
  namespace fs = std::filesystem;
  fs::path target(path);
  fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  if (!fs::is_directory(dir))
    throw Error(path + ": cannot write: directory " + dir.string() + " does not exist");
  fs::path tmp = dir / ("." + target.filename().string() + ".tmp" + std::to_string(getpid()) +
                        target.extension().string());
  try {
    write(tmp.string());
    fs::rename(tmp, target);
  } catch (const Error&) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  } catch (const std::exception& e) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw Error(path + ": cannot write: " + e.what());
  }
}

void write_text_atomically(const std::string& path, const std::string& text) {
  write_atomically(path, [&](const std::string& tmp) {
    std::ofstream out(tmp);
    out << text;
    if (!out) throw Error(path + ": write failed");
  });
}

}  // namespace kasha
