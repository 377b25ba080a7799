// The measured budget (wb/budget.h): phases sampled by a watchdog, the limits checked
// at every look, and the line that stops a run. What the watchdog calls allocates
// nothing and takes no lock (the run may be inside malloc when it looks): no stdio,
// numbers formatted by hand into a fixed buffer, then write(2) and _exit.
#include "wb/budget.h"

#include <atomic>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "budget_platform.h"
#include "wb/input.h"
#include "wb/output.h"

namespace wb::budget {

std::atomic<int> g_phase{kLoad};
long g_countdown = LONG_MAX;

namespace {

// The watchdog's period (s): a stopped run passes its limit by about this much, and
// each look costs a few microseconds (about 0.2 % of a core at 2 ms).
constexpr double kTickSeconds = 0.002;
// The resident size is read every kRssEvery ticks, and at every tick once it is above
// half the memory limit (reading /proc costs a few microseconds).
constexpr int kRssEvery = 5;
// Without a ticker, poll() reads the clock about this often (CPU seconds).
constexpr double kPollSeconds = 0.01;

// Set by start(), before the ticker runs; read by the ticker.
double g_limit_s = 0, g_limit_b = 0;
char g_prefix[720];    // "<exe>: error: <file>: ", one line of valid UTF-8
char g_time_flag[64];  // "--max-time 3"
char g_mem_flag[64];   // "--max-memory 400"
bool g_started = false, g_ticker = false;

// Written by the running code, read by the ticker.
std::atomic<double> g_total{0};      // steps of the plan; 0: not known yet
std::atomic<long long> g_done{0};    // steps done
std::atomic<double> g_loop_cpu{-1};  // CPU seconds when the step loops started; < 0: not yet

// The watchdog's own state. g_state: 0 watching, 1 finished (the run is over, or said
// its own error), 2 stopping (the watchdog is writing its line): whichever comes first
// wins, so that a process says exactly one of the two.
long g_samples[kPhaseCount];
std::atomic<int> g_state{0};
constexpr int kWatching = 0, kFinished = 1, kStopping = 2;
long g_ticks = 0;
double g_rss_prev = 0, g_rss_growth = 0;

long g_poll_every = 1;
double g_poll_cpu = 0;

static_assert(std::atomic<double>::is_always_lock_free, "read by the watchdog, lock-free");
static_assert(std::atomic<long long>::is_always_lock_free, "read by the watchdog, lock-free");

const char* const kPhaseNames[kPhaseCount] = {
    "reading and checking the scene file",
    "building the run (the world, the initial checks, a solver's analysis)",
    "the integrator's arithmetic",
    "the force terms",
    "the energy and momentum of each step (the divergence rule)",
    "the broad and narrow phases (candidate pairs and contacts)",
    "the contact impulses",
    "the hinges",
    "the implicit solve (Newton: assembly and factorisations)",
    "the conjugate gradient iterations",
    "writing the outputs",
    "the sweep's rk4 reference",
};

// A fixed buffer the stopping line is written into, signal-safely.
struct Line {
  char s[1400];
  std::size_t n = 0;
  void add(const char* t) {
    while (*t && n < sizeof s - 1) s[n++] = *t++;
  }
  void add_uint(unsigned long long x) {
    char d[24];
    int k = 0;
    do {
      d[k++] = char('0' + x % 10);
      x /= 10;
    } while (x > 0);
    while (k > 0 && n < sizeof s - 1) s[n++] = d[--k];
  }
  // x >= 0 with `decimals` digits after the point (rounded).
  void add_fixed(double x, int decimals) {
    if (!(x >= 0) || x > 1e18) {
      add(x > 0 ? "a very large number of" : "?");
      return;
    }
    double scale = 1;
    for (int k = 0; k < decimals; ++k) scale *= 10;
    const unsigned long long v = (unsigned long long)(x * scale + 0.5);
    add_uint(v / (unsigned long long)scale);
    if (decimals > 0) {
      add(".");
      unsigned long long f = v % (unsigned long long)scale;
      for (int k = decimals - 1; k >= 0; --k) {
        unsigned long long p = 1;
        for (int q = 0; q < k; ++q) p *= 10;
        const char c[2] = {char('0' + (f / p) % 10), 0};
        add(c);
      }
    }
  }
  // A duration in words: "3.2 s", "12 minutes", "4.2 hours", "31 days".
  void add_duration(double s) {
    if (!(s < 1e15)) {
      add("forever");
    } else if (s < 10) {
      add_fixed(s, 2);
      add(" s");
    } else if (s < 120) {
      add_fixed(s, 0);
      add(" s");
    } else if (s < 7200) {
      add_fixed(s / 60, 0);
      add(" minutes");
    } else if (s < 2 * 86400) {
      add_fixed(s / 3600, 1);
      add(" hours");
    } else {
      add_fixed(s / 86400, 0);
      add(" days");
    }
  }
  void add_mib(double b) {
    add_fixed(b / (1024.0 * 1024.0), 0);
    add(" MiB");
  }
};

// The phase that took the most samples, and its share of them (%).
int costliest(int& percent) {
  long total = 0, best = -1;
  int p = g_phase.load(std::memory_order_relaxed);
  for (int k = 0; k < kPhaseCount; ++k) {
    total += g_samples[k];
    if (g_samples[k] > best) best = g_samples[k], p = k;
  }
  percent = total > 0 ? int(100.0 * double(best) / double(total) + 0.5) : 100;
  return p;
}

// "; at step 12 of 1000, the whole run would take about 4.2 hours"
void add_progress(Line& l, double cpu) {
  const double total = g_total.load(std::memory_order_relaxed);
  const long long done = g_done.load(std::memory_order_relaxed);
  const double loop_cpu = g_loop_cpu.load(std::memory_order_relaxed);
  if (loop_cpu < 0 || !(total > 0)) {
    l.add(", before its first step");
    if (total > 0) {
      l.add(" (the run has ");
      l.add_fixed(total, 0);
      l.add(" steps)");
    }
    return;
  }
  const double looped = cpu - loop_cpu;
  if (done <= 0) {
    l.add("; its first step of ");
    l.add_fixed(total, 0);
    l.add(" was not done: the whole run would take more than ");
    l.add_duration(loop_cpu + looped * total);
    return;
  }
  l.add("; at step ");
  l.add_uint((unsigned long long)done);
  l.add(" of ");
  l.add_fixed(total, 0);
  l.add(", the whole run would take about ");
  l.add_duration(loop_cpu + looped * total / double(done));
}

void stop(bool memory, double cpu, double rss) {
  int expected = kWatching;
  if (!g_state.compare_exchange_strong(expected, kStopping)) return;  // finished first
  Line l;
  l.add(g_prefix);
  if (memory) {
    l.add("stopped at ");
    l.add_mib(rss);
    l.add(" of memory, its limit (");
    l.add(g_mem_flag);
    l.add("), while in ");
    l.add(phase_name(g_phase.load(std::memory_order_relaxed)));
    if (g_rss_growth > 0) {
      l.add(", growing ");
      l.add_mib(g_rss_growth);
      l.add(" in its last ");
      l.add_fixed(1000 * kTickSeconds * kRssEvery, 0);
      l.add(" ms of CPU");
    }
  } else {
    int percent = 0;
    const int p = costliest(percent);
    l.add("stopped after ");
    l.add_duration(cpu);
    l.add(" of CPU, its limit (");
    l.add(g_time_flag);
    l.add("): ");
    l.add_uint((unsigned long long)percent);
    l.add(" % of it in ");
    l.add(phase_name(p));
  }
  add_progress(l, cpu);
  l.add(" (docs/scenes.md, \"Cost\")\n");
  remove_temporaries();
  platform::write_stderr(l.s, l.n);
  platform::exit_now(2);
}

// One look at the clocks: from the ticker's handler, or from poll().
void check() {
  if (g_state.load() != kWatching) return;
  ++g_ticks;
  const int p = g_phase.load(std::memory_order_relaxed);
  if (p >= 0 && p < kPhaseCount) ++g_samples[p];
  const double cpu = platform::cpu_seconds();
  if (cpu >= g_limit_s - kTickSeconds) return stop(false, cpu, 0);
  if (g_ticks % kRssEvery == 0 || g_rss_prev > 0.5 * g_limit_b) {
    const double rss = platform::resident_bytes();
    if (rss > 0) {
      // Stop before the limit when the growth of the last reading would pass it twice
      // over by the next: memory can grow by tens of MiB in a few milliseconds.
      const double growth = rss - g_rss_prev;
      if (g_ticks % kRssEvery == 0) g_rss_growth = growth;
      g_rss_prev = rss;
      if (rss + 2 * (growth > 0 ? growth : 0) >= g_limit_b) stop(true, cpu, rss);
    }
  }
}

void tick() { check(); }

void render_flag(char* out, std::size_t size, const char* flag, double x) {
  std::string s(flag);
  s += ' ';
  append_number(s, x);
  // 17 digits are what a double needs; a flag's value reads better short.
  char shortest[40];
  std::snprintf(shortest, sizeof shortest, "%.6g", x);
  if (std::strtod(shortest, nullptr) == x) s = std::string(flag) + " " + shortest;
  std::snprintf(out, size, "%s", s.c_str());
}

}  // namespace

const char* phase_name(int p) { return p >= 0 && p < kPhaseCount ? kPhaseNames[p] : "the run"; }

void start(const Limits& limits, const std::string& exe, const std::string& file) {
  const std::string prefix = one_line(exe + ": error: " + file + ": ", 600);
  std::snprintf(g_prefix, sizeof g_prefix, "%s", prefix.c_str());
  render_flag(g_time_flag, sizeof g_time_flag, "--max-time", limits.seconds);
  render_flag(g_mem_flag, sizeof g_mem_flag, "--max-memory", limits.bytes / (1024.0 * 1024.0));
  g_limit_s = limits.seconds;
  g_limit_b = limits.bytes;
  if (g_started) return;
  g_started = true;
  g_ticker = platform::start_ticker(kTickSeconds, tick);
  if (!g_ticker) {  // poll() reads the clock instead, first at the next step
    g_poll_cpu = platform::cpu_seconds();
    g_countdown = 1;
  }
}

void finish() {
  int expected = kWatching;
  if (g_state.compare_exchange_strong(expected, kFinished) || expected == kFinished) return;
  // The watchdog is stopping the run: it ends the process in a moment; say nothing.
  platform::wait_to_be_ended();
}

void plan(double total_steps) { g_total.store(total_steps, std::memory_order_relaxed); }

void loop_started() {
  if (g_loop_cpu.load(std::memory_order_relaxed) < 0) {
    g_loop_cpu.store(platform::cpu_seconds(), std::memory_order_relaxed);
  }
}

void step_done() {
  g_done.store(g_done.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
  if (--g_countdown <= 0) poll_clock();
}

void poll_clock() {
  if (g_ticker || !g_started) {
    g_countdown = LONG_MAX;
    return;
  }
  // Aim for one look every kPollSeconds: scale the countdown by the time the last took.
  const double now = platform::cpu_seconds(), took = now - g_poll_cpu;
  g_poll_cpu = now;
  check();
  double every = took > 0 ? double(g_poll_every) * kPollSeconds / took : 2.0 * g_poll_every;
  if (!(every >= 1)) every = 1;
  if (every > 1e6) every = 1e6;
  g_poll_every = long(every);
  g_countdown = g_poll_every;
}

std::string out_of_memory_text() {
  std::string s = "stopped: an allocation failed (the machine has no memory for it) while in " +
                  std::string(phase_name(g_phase.load()));
  const double total = g_total.load(), done = double(g_done.load());
  if (total > 0 && g_loop_cpu.load() >= 0) {
    s += ", at step " + std::to_string((long long)done) + " of " +
         std::to_string((long long)total);
  }
  return s + "; --max-memory stops a run before that (docs/scenes.md, \"Cost\")";
}

bool watching() { return g_started; }

double cpu_seconds() { return platform::cpu_seconds(); }

double resident_bytes() { return platform::resident_bytes(); }

}  // namespace wb::budget
