// The budget's platform layer (budget_platform.h): POSIX clocks, /proc's resident
// size, and a watchdog thread that looks at them every few milliseconds; std::clock()
// and no ticker where there are no threads (WebAssembly without pthreads).
//
// Why a thread and not a CPU-time timer signal (ITIMER_PROF): while a process CPU
// timer is armed, Linux answers CLOCK_PROCESS_CPUTIME_ID (std::clock) from its tick
// samples, a few milliseconds coarse, and the summary's cpu_s would lose its precision;
// a signal also interrupts the run's system calls. The thread costs a wake-up every
// period (about 0.2 % of a core at 2 ms) and changes nothing the run measures.
#include "budget_platform.h"

#include <ctime>

#include "wb/budget.h"  // WB_BUDGET_THREAD

#if WB_BUDGET_THREAD
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <thread>
#else
#include <cstdio>
#include <cstdlib>
#endif

namespace wb::budget::platform {

#if WB_BUDGET_THREAD

namespace {

long g_page = 4096;  // set before the ticker starts

}  // namespace

double cpu_seconds() {
  timespec ts{};
  if (::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0) return 0.0;
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double resident_bytes() {
  // /proc/self/statm: "size resident shared ..." in pages (Linux). Elsewhere the
  // open fails and the memory is not watched.
  const int fd = ::open("/proc/self/statm", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return 0.0;
  char buf[128];
  const ssize_t n = ::read(fd, buf, sizeof buf - 1);
  ::close(fd);
  if (n <= 0) return 0.0;
  std::size_t i = 0;
  while (i < std::size_t(n) && buf[i] != ' ') ++i;  // skip "size"
  ++i;
  double pages = 0;
  for (; i < std::size_t(n) && buf[i] >= '0' && buf[i] <= '9'; ++i) {
    pages = 10 * pages + (buf[i] - '0');
  }
  return pages * double(g_page);
}

bool start_ticker(double period, void (*tick)()) {
  const long page = ::sysconf(_SC_PAGESIZE);
  if (page > 0) g_page = page;
  try {
    // Detached: it never ends by itself, and the process's exit ends it. It allocates
    // nothing and touches only the budget's plain globals.
    std::thread([period, tick] {
      const auto dt = std::chrono::duration<double>(period);
      for (;;) {
        std::this_thread::sleep_for(dt);
        tick();
      }
    }).detach();
    return true;
  } catch (...) {
    return false;  // no threads here: the step loops poll
  }
}

void write_stderr(const char* s, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(2, s, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return;
    s += w;
    n -= std::size_t(w);
  }
}

void exit_now(int status) { ::_exit(status); }

void wait_to_be_ended() {
  for (;;) ::pause();
}

#else  // no threads: the step loops and phases poll std::clock(); memory is not watched

double cpu_seconds() {
  const std::clock_t c = std::clock();
  return c == std::clock_t(-1) ? 0.0 : double(c) / CLOCKS_PER_SEC;
}

double resident_bytes() { return 0.0; }

bool start_ticker(double, void (*)()) { return false; }

void write_stderr(const char* s, std::size_t n) {
  std::fwrite(s, 1, n, stderr);
  std::fflush(stderr);
}

void exit_now(int status) { std::_Exit(status); }

void wait_to_be_ended() { std::_Exit(2); }  // no watchdog thread here: never reached

#endif

}  // namespace wb::budget::platform
