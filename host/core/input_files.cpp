#include "core/input_files.h"

#include <mutex>

namespace kasha {

namespace {
std::mutex& lock() {
  static std::mutex m;
  return m;
}
std::vector<std::string>& files() {
  static std::vector<std::string> f;
  return f;
}
}  // namespace

void note_input_file(const std::string& path) {
  std::lock_guard<std::mutex> guard(lock());
  files().push_back(path);
}

std::vector<std::string> input_files_read() {
  std::lock_guard<std::mutex> guard(lock());
  return files();
}

void forget_input_files() {
  std::lock_guard<std::mutex> guard(lock());
  files().clear();
}

}  // namespace kasha
