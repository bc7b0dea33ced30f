#include "core/python_script.h"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>

#include "core/embedded_file.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "core/printable.h"

extern char** environ;

namespace kasha {

namespace {

const std::string kPython = "/usr/bin/python3";
constexpr size_t kKeptOutput = 16384;  // the tail of the child's output, where its error is
constexpr size_t kLongestLine = 400;   // of that error, in the one-line message

struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

// The script's stdin: an in-memory file, so the run keeps no scratch file on any disk.
int input_file(const std::string& text, const std::string& who) {
  Fd f{::memfd_create("kasha-plot-input", MFD_CLOEXEC)};
  size_t done = 0;
  while (f.fd >= 0 && done < text.size()) {
    ssize_t n = ::write(f.fd, text.data() + done, text.size() - done);
    if (n > 0)
      done += static_cast<size_t>(n);
    else if (n == 0 || errno != EINTR)
      break;
  }
  if (f.fd < 0 || done < text.size())
    throw Error(who + ": cannot pass the data to the plotter: " + std::strerror(errno));
  ::lseek(f.fd, 0, SEEK_SET);
  int fd = f.fd;
  f.fd = -1;
  return fd;
}

void sleep_ms(long ms) {
  timespec t{0, ms * 1000000};
  ::nanosleep(&t, nullptr);
}

// The plotter while it runs. Whatever way the caller leaves (an interrupt, an exception), the
// child is stopped and waited for: no orphan goes on writing beside the user's file.
struct Child {
  pid_t pid = -1;
  int status = 0;

  ~Child() {
    if (pid > 0) stop();
  }
  // waitpid; true once the child is gone (its status kept).
  bool reaped(int options) {
    for (;;) {
      pid_t r = ::waitpid(pid, &status, options);
      if (r == pid || (r < 0 && errno != EINTR)) {
        pid = -1;
        return true;
      }
      if (r == 0 || (options & WNOHANG)) return false;
    }
  }
  // SIGTERM, then SIGKILL should it still run a second later.
  void stop() {
    ::kill(pid, SIGTERM);
    for (int k = 0; k < 100; ++k) {
      if (reaped(WNOHANG)) return;
      sleep_ms(10);
    }
    ::kill(pid, SIGKILL);
    reaped(0);
  }
};

// SIGCHLD as the default while the child runs: inherited as ignored, it would have the kernel reap
// the child unseen (waitpid: ECHILD, no exit status to judge the plot by).
struct ChildrenWaitable {
  struct sigaction before = {};
  ChildrenWaitable() {
    struct sigaction action = {};
    action.sa_handler = SIG_DFL;
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGCHLD, &action, &before);
  }
  ~ChildrenWaitable() { ::sigaction(SIGCHLD, &before, nullptr); }
};

void keep(std::string& output, const char* bytes, size_t n) {
  output.append(bytes, n);
  if (output.size() > 2 * kKeptOutput) output.erase(0, output.size() - kKeptOutput);
}

// The last line with text: a Python traceback ends with its exception.
std::string last_line(const std::string& output) {
  size_t end = output.find_last_not_of(" \t\r\n");
  if (end == std::string::npos) return "";
  size_t newline = output.rfind('\n', end);
  size_t begin = newline == std::string::npos ? 0 : newline + 1;
  std::string line = output.substr(begin, end + 1 - begin);
  if (line.size() > kLongestLine) {
    size_t cut = kLongestLine;
    while (cut > 0 && (static_cast<unsigned char>(line[cut]) & 0xC0) == 0x80) --cut;  // UTF-8
    line = line.substr(0, cut) + "…";
  }
  return line;
}

std::string failure(int status, const std::string& output) {
  std::string line = last_line(output);
  if (!line.empty()) {
    std::string why = as_one_line(line);
    if (line.find("No module named") != std::string::npos)
      why += " (the plots need Debian's python3-matplotlib and python3-numpy)";
    return why;
  }
  if (WIFEXITED(status))
    return kPython + " exited with status " + std::to_string(WEXITSTATUS(status));
  return kPython + " was ended by signal " + std::to_string(WTERMSIG(status)) + " (" +
         strsignal(WTERMSIG(status)) + ")";
}

}  // namespace

void run_embedded_python(const std::string& script, const std::vector<std::string>& args,
                         const std::string& who, const std::string& input) {
  // -I: neither PYTHON* variables, the user's site-packages nor the current folder (a numpy.py
  // there) change what the compiled-in script runs with.
  std::vector<std::string> words = {kPython, "-I", "-c", embedded_data(script)};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);

  Fd in{input_file(input, who)};
  int ends[2];
  if (::pipe2(ends, O_CLOEXEC) != 0)
    throw Error(who + ": cannot start the plotter: " + std::strerror(errno));
  Fd out{ends[0]}, out_child{ends[1]};

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in.fd, STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, out_child.fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, out_child.fd, STDERR_FILENO);
  // The child takes signals as a fresh process would, even where kasha was started with them
  // ignored (in the background of a script): a terminal's Ctrl-C reaches it too.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (int s : {SIGINT, SIGTERM, SIGQUIT, SIGPIPE}) sigaddset(&defaults, s);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);

  // From here a signal only raises the flag, so the child is stopped and waited for below.
  InterruptsDeferred deferred;
  ChildrenWaitable waitable;
  Child child;
  int spawned =
      posix_spawn(&child.pid, kPython.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (spawned != 0) {
    child.pid = -1;
    throw Error(
        who + ": cannot run " + kPython +
        " (the plots need Debian's python3 with python3-matplotlib): " + std::strerror(spawned));
  }
  ::close(out_child.fd);
  out_child.fd = -1;

  std::string output;
  char buffer[4096];
  bool reading = true;
  while (!child.reaped(WNOHANG)) {
    if (interrupt_requested()) {
      child.stop();
      throw Interrupted();
    }
    // A signal ends the poll early; the timeout bounds the wait when another thread took it.
    pollfd ready{out.fd, POLLIN, 0};
    if (::poll(&ready, reading ? 1 : 0, 50) > 0) {
      ssize_t n = ::read(out.fd, buffer, sizeof buffer);
      if (n > 0)
        keep(output, buffer, static_cast<size_t>(n));
      else if (n == 0 || errno != EINTR)
        reading = false;
    }
  }
  if (interrupt_requested()) throw Interrupted();
  // The rest of its output, without waiting on anything the script may have left holding the pipe.
  ::fcntl(out.fd, F_SETFL, O_NONBLOCK);
  for (ssize_t n; reading && (n = ::read(out.fd, buffer, sizeof buffer)) != 0;) {
    if (n > 0)
      keep(output, buffer, static_cast<size_t>(n));
    else if (errno != EINTR)
      break;
  }
  if (!WIFEXITED(child.status) || WEXITSTATUS(child.status) != 0)
    throw Error(who + ": plotting failed: " + failure(child.status, output));
}

}  // namespace kasha
