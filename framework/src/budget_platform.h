// The budget's view of the platform (wb/budget.h): the one place that asks the
// operating system for CPU time, resident memory and a periodic look at them. POSIX
// has them all (framework/src/budget_clock.cpp: a watchdog thread); elsewhere
// (WebAssembly without threads) the CPU time is std::clock(), there is no ticker, and
// the step loops poll instead.
#pragma once
#include <cstddef>

namespace wb::budget::platform {

// CPU seconds the process has used since it started (all threads).
double cpu_seconds();
// Resident memory now (B); 0 when the platform cannot say. Allocates nothing.
double resident_bytes();
// Calls `tick` every `period` seconds from a watchdog thread of its own, for the rest
// of the process. False when there are no threads here.
bool start_ticker(double period, void (*tick)());
// Writes to stderr, async-signal-safe; then ends the process with `status` at once
// (no destructors, no atexit: the caller removed what must be removed).
void write_stderr(const char* s, std::size_t n);
[[noreturn]] void exit_now(int status);
// Blocks the calling thread until the watchdog, which is stopping the run, ends the
// process.
[[noreturn]] void wait_to_be_ended();

}  // namespace wb::budget::platform
