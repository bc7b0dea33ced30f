#include "core/output_set.h"

#include <sys/stat.h>
#include <sys/vfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "core/input_file.h"
#include "core/input_files.h"
#include "core/interrupt.h"
#include "core/printable.h"

namespace kasha {

namespace fs = std::filesystem;

namespace {

constexpr long kProcMagic = 0x9fa0, kSysfsMagic = 0x62656572;  // <linux/magic.h>

// Whether a failed stat only says the path does not exist (yet): any other errno (a name too long,
// a link loop, no permission) is the option's error, raised now rather than after the work.
bool only_missing(int error) {
  return error == ENOENT || error == ENOTDIR;
}

[[noreturn]] void fail_stat(const std::string& where, int error) {
  throw Error(where + ": " + error_words(std::error_code(error, std::generic_category())));
}

struct Input {
  std::string path, what;
};

struct Output {
  std::string option, path;
  bool directory = false;
  bool existed = false;   // a folder that exists: its files are moved into it one by one
  std::string temporary;  // the written file or the staging folder; empty until then
  std::string where() const { return option + " " + path; }
};

// The same file: the same device and inode when both exist, else the same path once links are
// resolved (an output that does not exist yet can still be named twice).
bool same_file(const std::string& a, const std::string& b) {
  struct stat sa, sb;
  if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0)
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  std::error_code ea, eb;
  fs::path ca = fs::weakly_canonical(fs::absolute(a, ea), ea);
  fs::path cb = fs::weakly_canonical(fs::absolute(b, eb), eb);
  return !ea && !eb && ca == cb;
}

std::string folder_of(const std::string& path) {
  fs::path dir = fs::path(path).parent_path();
  return dir.empty() ? "." : dir.string();
}

// The folder exists, is an ordinary file system (not /proc or /sys) and takes a new file: tried
// with a probe file, since permission bits say nothing of read-only mounts, quotas or root.
void check_folder(const std::string& dir, const std::string& where) {
  struct stat st;
  if (::stat(dir.c_str(), &st) != 0) {
    const int error = errno;
    if (!only_missing(error)) fail_stat(where + ": directory " + dir, error);
    throw Error(where + ": directory " + dir + " does not exist");
  }
  if (!S_ISDIR(st.st_mode)) throw Error(where + ": " + dir + " is not a directory");
  struct statfs fsinfo;
  if (::statfs(dir.c_str(), &fsinfo) == 0 && (static_cast<long>(fsinfo.f_type) == kProcMagic ||
                                              static_cast<long>(fsinfo.f_type) == kSysfsMagic))
    throw Error(where + ": " + dir + " is in /proc or /sys, where no file can be written");
  std::string probe = (fs::path(dir) / ".kasha-probe-XXXXXX").string();
  int fd = ::mkstemp(probe.data());
  if (fd < 0)
    throw Error(where + ": cannot write in directory " + dir + ": " + std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
}

// A path in the same folder as `path`, so the final rename stays within one file system; the
// extension is kept last for writers that choose a format by it (matplotlib).
std::string temporary_beside(const std::string& path, int serial) {
  fs::path p(path);
  fs::path dir = p.parent_path();
  std::string name = "." + p.filename().string() + ".kasha-" + std::to_string(::getpid()) + "-" +
                     std::to_string(serial) + p.extension().string();
  return (dir / name).string();
}

// "out/" and "out" name the same folder; renames and sibling names need the latter.
std::string without_trailing_slash(std::string path) {
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  return path;
}

// The files written into a staging folder; a failure to list them is the output's error.
std::vector<fs::path> files_in(const std::string& dir, const std::string& where) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    out.push_back(it->path());
  if (ec) throw Error(where + ": cannot list the files written: " + error_words(ec));
  return out;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); !from.empty() && at != std::string::npos;
       at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

}  // namespace

struct OutputSet::Impl {
  std::vector<Input> inputs;
  std::vector<Output> outputs;
  int serial = 0;
  bool committed = false;

  Output& find(const std::string& path) {
    for (Output& o : outputs)
      if (o.path == path) return o;
    throw Error(path + ": not declared as an output");  // a programming error
  }

  void check_identity(const Output& o, size_t index) const {
    if (!o.directory)
      for (const Input& in : inputs)
        if (same_file(o.path, in.path)) throw Error(o.where() + ": is " + in.what + " " + in.path);
    for (size_t k = 0; k < index; ++k)
      if (same_file(o.path, outputs[k].path))
        throw Error(o.where() + ": is the same file as " + outputs[k].where());
  }
};

OutputSet::OutputSet() : impl_(std::make_unique<Impl>()) {}

OutputSet::~OutputSet() {
  if (impl_->committed) return;
  for (const Output& o : impl_->outputs)
    if (!o.temporary.empty()) {
      std::error_code ec;
      fs::remove_all(o.temporary, ec);
    }
}

void OutputSet::input(const std::string& path, const std::string& what) {
  if (!path.empty()) impl_->inputs.push_back({path, what});
}

void OutputSet::file(const std::string& option, const std::string& path) {
  if (path.empty()) return;
  Output o;
  o.option = option;
  o.path = path;
  struct stat st;
  const int found = ::lstat(path.c_str(), &st), error = errno;
  if (found == 0) {
    if (S_ISLNK(st.st_mode)) {
      std::error_code ec;
      // Renaming over a link replaces the link: refused rather than guessing what was meant.
      throw Error(o.where() + ": is a symbolic link (to " + fs::read_symlink(path, ec).string() +
                  "), not a regular file");
    }
    if (!S_ISREG(st.st_mode)) throw Error(o.where() + ": is " + file_kind(st.st_mode));
  } else if (!only_missing(error)) {
    fail_stat(o.where(), error);
  }
  check_folder(folder_of(path), o.where());
  impl_->outputs.push_back(o);
  impl_->check_identity(impl_->outputs.back(), impl_->outputs.size() - 1);
}

void OutputSet::directory(const std::string& option, const std::string& path) {
  if (path.empty()) return;
  Output o;
  o.option = option;
  o.path = path;
  o.directory = true;
  struct stat st;
  const int found = ::stat(path.c_str(), &st), error = errno;
  if (found == 0) {
    if (!S_ISDIR(st.st_mode))
      throw Error(o.where() + ": is " + file_kind(st.st_mode) + ", not a directory");
    check_folder(path, o.where());
    o.existed = true;
  } else if (!only_missing(error)) {
    fail_stat(o.where(), error);
  } else if (::lstat(path.c_str(), &st) == 0) {
    throw Error(o.where() + ": is a symbolic link to a missing directory");
  } else {
    check_folder(folder_of(without_trailing_slash(path)), o.where());
  }
  impl_->outputs.push_back(o);
  impl_->check_identity(impl_->outputs.back(), impl_->outputs.size() - 1);
}

void OutputSet::inputs_read(const std::string& what) {
  for (const std::string& path : input_files_read()) input(path, what);
  check();
}

void OutputSet::check() const {
  for (size_t k = 0; k < impl_->outputs.size(); ++k) impl_->check_identity(impl_->outputs[k], k);
}

void OutputSet::write(const std::string& path,
                      const std::function<void(const std::string&)>& writer) {
  Output& o = impl_->find(path);
  std::string tmp = temporary_beside(path, impl_->serial++);
  // Messages name the output as the user gave it, not its temporary, and start with the option;
  // a kasha::Error that names something else (an input) keeps its own WHERE.
  try {
    writer(tmp);
  } catch (const Error& e) {
    std::error_code ec;
    fs::remove(tmp, ec);
    std::string text = replace_all(e.what(), tmp, path);
    throw Error(text.rfind(path + ":", 0) == 0 ? o.option + " " + text : text);
  } catch (const Interrupted&) {  // reported as such, not as a write that failed
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  } catch (const std::exception& e) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw Error(o.where() + ": cannot write: " + replace_all(library_error_text(e), tmp, path));
  }
  o.temporary = tmp;
}

std::string OutputSet::staging(const std::string& path) {
  Output& o = impl_->find(path);
  if (!o.temporary.empty()) return o.temporary;
  // Inside a folder that exists (its other files stay), else beside it, renamed whole.
  std::string tmp = o.existed ? (fs::path(path) / (".kasha-" + std::to_string(::getpid()) + "-" +
                                                   std::to_string(impl_->serial++)))
                                    .string()
                              : temporary_beside(without_trailing_slash(path), impl_->serial++);
  std::error_code ec;
  fs::create_directory(tmp, ec);
  if (ec) throw Error(o.where() + ": cannot create a folder in it: " + error_words(ec));
  o.temporary = tmp;
  return tmp;
}

void OutputSet::commit() {
  check();
  // Everything a folder's files would replace is checked before the first rename.
  for (const Output& o : impl_->outputs) {
    if (!o.directory || !o.existed || o.temporary.empty()) continue;
    for (const fs::path& written : files_in(o.temporary, o.where())) {
      const std::string target = (fs::path(o.path) / written.filename()).string();
      struct stat st;
      if (::lstat(target.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
        throw Error(o.where() + ": " + target + " is " +
                    (S_ISLNK(st.st_mode) ? std::string("a symbolic link") : file_kind(st.st_mode)) +
                    ", which kasha does not replace");
      for (const Input& in : impl_->inputs)
        if (same_file(target, in.path))
          throw Error(o.where() + ": would replace " + in.what + " " + in.path);
      for (const Output& other : impl_->outputs)
        if (!other.directory && same_file(target, other.path))
          throw Error(o.where() + ": would replace " + other.where());
    }
  }
  for (Output& o : impl_->outputs) {
    if (o.temporary.empty()) continue;
    std::error_code ec;
    if (o.directory && o.existed) {
      for (const fs::path& written : files_in(o.temporary, o.where())) {
        fs::rename(written, fs::path(o.path) / written.filename(), ec);
        if (ec) break;
      }
      if (!ec) fs::remove_all(o.temporary, ec);
    } else {
      fs::rename(o.temporary, without_trailing_slash(o.path), ec);
    }
    if (ec)
      throw Error(o.where() + ": cannot move the finished output into place: " + error_words(ec));
    o.temporary.clear();
  }
  impl_->committed = true;
}

}  // namespace kasha
