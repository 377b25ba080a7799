// Hostile: reads what its namespace's init and its own process show of the grader (issue 42:
// "the worker can read its namespace init's command line", the launcher's flags with the run
// folder's path): /proc/1/cmdline and /proc/1/environ, its parent's, its own command line,
// executable and folder, and prints all of it where the results show it. The suite refuses
// results that name its scratch folder or the launcher's flags.
#include <fcntl.h>
#include <unistd.h>

#include <cstring>
#include <string>

#include "explicit_euler.h"

namespace {
void say(const std::string& what, const std::string& text) {
  const std::string line = "init-cmdline: " + what + ": " + text + "\n";
  if (write(2, line.data(), line.size()) < 0) {
  }
}

void show_file(const std::string& path) {
  char buf[4096] = {};
  const int f = open(path.c_str(), O_RDONLY);
  const ssize_t n = f >= 0 ? read(f, buf, sizeof buf - 1) : -1;
  if (f >= 0) close(f);
  for (ssize_t i = 0; i < n; ++i) buf[i] = buf[i] ? buf[i] : ' ';
  if (n > 0) say(path, std::string(buf, std::size_t(n)));
}
}  // namespace

void explicit_euler_step(const wb::Dynamics&, double, wb::Mat2X&, wb::Mat2X&, wb::Scratch&) {
  static bool done = false;
  if (done) return;
  done = true;
  for (const char* p : {"/proc/1/cmdline", "/proc/1/environ", "/proc/self/cmdline",
                        "/proc/self/environ", "/proc/self/mountinfo"})
    show_file(p);
  show_file("/proc/" + std::to_string(getppid()) + "/cmdline");
  char path[4096] = {};
  if (readlink("/proc/self/exe", path, sizeof path - 1) > 0) say("its executable", path);
  if (getcwd(path, sizeof path)) say("its folder", path);
  say("its name", program_invocation_name);
}
