#include "core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"
#include "core/input_files.h"
#include "core/printable.h"

namespace kasha {

namespace {

std::string size_text(std::uint64_t bytes) {
  return bytes >= (std::uint64_t(1) << 30) ? std::to_string(bytes >> 30) + " GiB"
                                           : std::to_string(bytes >> 20) + " MiB";
}

// An open descriptor that closes itself.
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

// Opens without blocking (a FIFO with no writer would wait forever in a plain open) and checks,
// on the opened file itself, that it is a regular file within the limit. Returns its size.
std::uint64_t open_checked(const std::string& path, std::uint64_t max_bytes, Fd& file) {
  const std::string where = printable(path) + ": ";
  if (path.empty()) throw Error("(empty file name): cannot open file");
  file.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (file.fd < 0) {
    // A directory opens on Linux, but say what it is either way.
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
      throw Error(where + "is " + file_kind(st.st_mode) + ", not a file");
    throw Error(where + "cannot open file: " + std::strerror(errno));
  }
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) throw Error(where + "cannot open file: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw Error(where + "is " + file_kind(st.st_mode) + ", not a file");
  const auto size = static_cast<std::uint64_t>(st.st_size);
  note_input_file(path);  // no output may replace it (core/output_set.h)
  if (size > max_bytes)
    throw Error(where + "the file is " + std::to_string(size) + " bytes, over the " +
                size_text(max_bytes) + " an input of this kind may have");
  return size;
}

}  // namespace

std::string file_kind(mode_t mode) {
  if (S_ISREG(mode)) return "a file";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string read_input_file(const std::string& path, std::uint64_t max_bytes) {
  Fd file;
  const std::uint64_t size = open_checked(path, max_bytes, file);
  std::string text;
  text.reserve(size);
  char buffer[1 << 16];
  for (;;) {
    ssize_t n = ::read(file.fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Error(printable(path) + ": cannot read file: " + std::strerror(errno));
    if (n == 0) break;
    text.append(buffer, static_cast<size_t>(n));
    // The file may grow while it is read; the limit holds for what is read, not only the size.
    if (text.size() > max_bytes)
      throw Error(printable(path) + ": the file grew past the " + size_text(max_bytes) +
                  " an input of this kind may have");
  }
  return text;
}

void check_input_file(const std::string& path, std::uint64_t max_bytes) {
  Fd file;
  open_checked(path, max_bytes, file);
}

}  // namespace kasha
