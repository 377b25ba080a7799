// Hostile: sits out the test's time limit without being seen as idle: a futex wait with a
// timeout of 8 s, then a few ticks of CPU, again and again (issue 29: "sleeping": the idle
// rule watched for 10 s without any CPU). When the timed wait is refused, it waits on its own
// request pipe with no timeout (which never gets data while the test waits for the answer).
#include <errno.h>
#include <linux/futex.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include "explicit_euler.h"

void explicit_euler_step(const wb::Dynamics&, double, wb::Mat2X&, wb::Mat2X&, wb::Scratch&) {
  int word = 0;
  for (;;) {
    timespec ts{8, 0};
    const long r = syscall(SYS_futex, &word, FUTEX_WAIT_PRIVATE, 0, &ts, nullptr, 0);
    if (r != 0 && errno != ETIMEDOUT && errno != EINTR) {  // refused: wait for good instead
      char c;
      for (int fd = 3; fd < 16; ++fd)
        if (read(fd, &c, 1) >= 0) break;
      return;
    }
    for (volatile long k = 0; k < 3000000; ++k) {
    }
  }
}
