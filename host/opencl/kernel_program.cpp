#include "opencl/kernel_program.h"

#include <unistd.h>

#include <cstdio>
#include <regex>
#include <set>
#include <sstream>

#include "core/embedded_file.h"
#include "core/error.h"
#include "core/interrupt.h"

namespace kasha {

std::string build_options(const KernelDefines& defines) {
  std::string out;
  for (const auto& [name, value] : defines)
    out += (out.empty() ? "" : " ") + std::string("-D ") + name + "=" + value;
  return out;
}

// Appends `text`, the contents of the kernel file `name`, with its quoted #includes of embedded
// files inlined, each once (`seen` holds the files already inlined).
static void inline_text(const std::string& text, const std::string& name,
                        std::set<std::string>& seen, std::ostringstream& out) {
  static const std::regex include_line(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  out << "#line 1 \"" << name << "\"\n";
  while (std::getline(in, line)) {
    ++line_no;
    std::smatch m;
    if (std::regex_match(line, m, include_line)) {
      const std::string file = m[1];
      if (seen.insert(file).second) inline_text(embedded_kernel(file), file, seen, out);
      out << "#line " << line_no + 1 << " \"" << name << "\"\n";
    } else {
      out << line << "\n";
    }
  }
}

std::string assemble_kernel_source_text(const std::string& source, const std::string& name) {
  std::set<std::string> seen{name};
  std::ostringstream out;
  inline_text(source, name, seen, out);
  return out.str();
}

std::string assemble_kernel_source(const std::string& main_file) {
  return assemble_kernel_source_text(embedded_kernel(main_file), main_file);
}

namespace {
// The compiler inside PoCL prints straight to stderr ("1 error generated." when a signal cuts it
// short). A build holds fd 2 in a temporary file and passes it on unless it was interrupted, so
// an interrupt stays one line.
class HeldStderr {
 public:
  HeldStderr() {
    std::fflush(stderr);
    file_ = std::tmpfile();
    saved_ = file_ ? dup(STDERR_FILENO) : -1;
    if (saved_ < 0 || dup2(fileno(file_), STDERR_FILENO) < 0)
      release(false);  // not held: the build prints as before
    else
      set_interrupt_message_fd(saved_);
  }
  ~HeldStderr() { release(!interrupt_requested()); }
  HeldStderr(const HeldStderr&) = delete;
  HeldStderr& operator=(const HeldStderr&) = delete;

 private:
  void release(bool pass_on) {
    if (saved_ >= 0) {
      std::fflush(stderr);
      dup2(saved_, STDERR_FILENO);
      set_interrupt_message_fd(STDERR_FILENO);
      close(saved_);
      saved_ = -1;
      if (pass_on) {
        std::rewind(file_);
        char buf[4096];
        for (size_t n; (n = std::fread(buf, 1, sizeof buf, file_)) > 0;)
          std::fwrite(buf, 1, n, stderr);
      }
    }
    if (file_) std::fclose(file_);
    file_ = nullptr;
  }
  FILE* file_ = nullptr;
  int saved_ = -1;
};
}  // namespace

cl::Program build_program(ClContext& cl, const std::string& source, const KernelDefines& defines,
                          const std::string& what) {
  std::string options = build_options(defines);
  cl::Program program;
  try {
    program = cl::Program(cl.context(), source);
  } catch (const cl::Error& e) {
    if (interrupt_requested()) throw Interrupted();
    throw Error("OpenCL: cannot create program " + what + ": " + cl_error_text(e));
  }
  cl_int status = CL_SUCCESS;
  {
    HeldStderr held;
    try {
      status = program.build({cl.device()}, options.c_str());
    } catch (const cl::BuildError& e) {
      status = e.err();
    } catch (const cl::Error& e) {
      status = e.err();
    }
  }
  // A signal also reaches the compiler's processes (a terminal or `timeout` signals the whole
  // group), failing the build: that is the interrupt, not a kernel error with its build log.
  if (status != CL_SUCCESS && interrupt_requested()) throw Interrupted();
  if (status != CL_SUCCESS) {
    std::string log;
    try {
      log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(cl.device());
    } catch (const cl::Error&) {
      log = "(no build log)";
    }
    throw Error("OpenCL kernel build failed for " + what + " on " + cl.info().name + " (error " +
                std::to_string(status) + ", options: " + options + "); build log:\n" + log);
  }
  return program;
}

}  // namespace kasha
