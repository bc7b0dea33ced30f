#include "core/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/interrupt.h"
#include "core/printable.h"

namespace kasha {

void write_atomically(const std::string& path,
                      const std::function<void(const std::string&)>& write) {
  namespace fs = std::filesystem;
  fs::path target(path);
  fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;  // a name too long or a link loop: this file's error, in words
  if (!fs::is_directory(dir, ec))
    throw Error(path + ": cannot write: directory " + dir.string() +
                (ec && ec != std::errc::no_such_file_or_directory ? ": " + error_words(ec)
                                                                  : " does not exist"));
  fs::path tmp = dir / ("." + target.filename().string() + ".tmp" + std::to_string(getpid()) +
                        target.extension().string());
  try {
    write(tmp.string());
    fs::rename(tmp, target, ec);
    if (ec) throw Error(path + ": cannot write: " + error_words(ec));
  } catch (const Error&) {
    fs::remove(tmp, ec);
    throw;
  } catch (const Interrupted&) {  // reported as such, not as a write that failed
    fs::remove(tmp, ec);
    throw;
  } catch (const std::exception& e) {
    fs::remove(tmp, ec);
    throw Error(path + ": cannot write: " + library_error_text(e));
  }
}

void write_text_atomically(const std::string& path, const std::string& text) {
  write_atomically(path, [&](const std::string& tmp) {
    write_stream_file(tmp, path, [&](std::ostream& out) { out << text; });
  });
}

void check_flushed(std::ostream& out, const std::string& name) {
  errno = 0;
  if (out) out.flush();
  if (!out)
    throw Error(name + ": write failed" + (errno ? std::string(": ") + std::strerror(errno) : ""));
}

void write_stream_file(const std::string& file, const std::string& name,
                       const std::function<void(std::ofstream&)>& fill) {
  std::ofstream out(file, std::ios::binary);
  if (!out) throw Error(name + ": cannot open for writing: " + std::strerror(errno));
  fill(out);
  check_flushed(out, name);
  // close() writes what the flush left and closes the descriptor; either can fail (NFS, quota).
  errno = 0;
  out.close();
  if (out.fail())
    throw Error(name + ": write failed" + (errno ? std::string(": ") + std::strerror(errno) : ""));
}

}  // namespace kasha
