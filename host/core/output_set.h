#pragma once
// The outputs of one command (docs/commands.md#errors-and-exit-codes). Every output path is checked
// before any work: its folder exists and is writable, it is not a directory, a link, a device or
// another non-regular file, nor under /proc or /sys, and it is none of the command's inputs nor
// another of its outputs (after resolving links). Outputs are written to temporaries beside their
// targets and renamed into place together by commit(), only once all of them are complete; whatever
// was not committed is removed, so a failed command leaves no file written or changed.
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace kasha {

class OutputSet {
 public:
  OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  ~OutputSet();  // removes the temporaries of an uncommitted set

  // A file the command reads, which no output may replace; `what` names it in messages
  // ("the scene file"). Inputs that do not exist are left to their readers to report.
  void input(const std::string& path, const std::string& what);
  // An output file given by `option` (the WHERE of messages); checked now. Empty: not given.
  void file(const std::string& option, const std::string& path);
  // An output folder: created whole if it does not exist, else its files are replaced one by one.
  void directory(const std::string& option, const std::string& path);
  // Adds every file read so far (core/input_files.h) as an input and checks the outputs again:
  // the files a scene names are known only once it is loaded.
  void inputs_read(const std::string& what);
  void check() const;

  // Writes output file `path` through writer(temporary); errors name the option and the path.
  void write(const std::string& path, const std::function<void(const std::string&)>& writer);
  // The temporary folder where the files of output folder `path` are to be written.
  std::string staging(const std::string& path);
  // Renames every written output into place; after a failure nothing is renamed.
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kasha
