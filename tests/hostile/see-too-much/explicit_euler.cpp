// Hostile: looks around (issue 29: "which test is calling", "seeing too much"): every other
// process's command line (the test process's names the test and the run) and a file the
// suite plants beside the grader's build (world-readable), then prints what it found where
// the student reads it, and takes no step.
#include <dirent.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <string>

#include "explicit_euler.h"

namespace {
void show(const std::string& what, const std::string& path, const char* only = nullptr) {
  char buf[2048] = {};
  const int f = open(path.c_str(), O_RDONLY);
  const ssize_t n = f >= 0 ? read(f, buf, sizeof buf - 1) : -1;
  if (f >= 0) close(f);
  for (ssize_t i = 0; i < n; ++i) buf[i] = buf[i] ? buf[i] : ' ';
  if (n > 0 && (!only || std::strstr(buf, only))) {  // only what is worth seeing
    const std::string line = what + ": " + std::string(buf, std::size_t(n)) + "\n";
    if (write(2, line.data(), line.size()) < 0) {
    }
  }
}
}  // namespace

void explicit_euler_step(const wb::Dynamics&, double, wb::Mat2X&, wb::Mat2X&, wb::Scratch&) {
  static bool done = false;
  if (done) return;
  done = true;
  const std::string self = std::to_string(getpid());
  if (DIR* d = opendir("/proc")) {
    while (dirent* e = readdir(d)) {
      if (e->d_name[0] < '1' || e->d_name[0] > '9' || self == e->d_name) continue;
      show(std::string("process ") + e->d_name, std::string("/proc/") + e->d_name + "/cmdline",
           "NoTests");  // the test process: its command line names the test and the run
    }
    closedir(d);
  }
  char exe[4096] = {};
  if (readlink("/proc/self/exe", exe, sizeof exe - 1) > 0) {
    std::string dir(exe);
    dir = dir.substr(0, dir.rfind('/'));  // .../grade-build/run
    dir = dir.substr(0, dir.rfind('/'));  // .../grade-build
    show("beside the build", dir + "/wb-hostile-view.txt");
    show("the tests", dir + "/src/tests/euler/test_E1_explicit_euler.cpp");
  }
}
