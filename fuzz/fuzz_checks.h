// What every fuzz target checks of a message, and how it reports a finding
// (fuzz/README.md): each target passes its own name.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include "wb/cost.h"

namespace fuzzcheck {

// The fuzzers skip what the cost model says is slow (a run of `steps` steps of
// `c`, at the iteration caps, above `seconds` of an optimised build): so every
// input they run is cheap, and one the model wrongly calls cheap times out
// (-timeout), a finding.
inline bool too_slow(const wb::StepCost& c, double steps, double seconds) {
  return c.once.cap_seconds() + steps * c.step.cap_seconds() > seconds;
}

// Warnings go to std::cerr (wb::say): not while fuzzing (findings use stderr).
inline void quiet() {
  static const bool done = [] {
    std::cerr.setstate(std::ios::badbit);
    return true;
  }();
  (void)done;
}

[[noreturn]] inline void finding(const char* target, const char* what,
                                 const std::string& detail) {
  std::fprintf(stderr, "%s: %s: %s\n", target, what, detail.c_str());
  std::abort();
}

// An independent check of UTF-8 (not the one the library uses).
inline bool valid_utf8(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const unsigned c = static_cast<unsigned char>(s[i]);
    const std::size_t n = c < 0x80           ? 1
                          : (c >> 5) == 0x6  ? 2
                          : (c >> 4) == 0xE  ? 3
                          : (c >> 3) == 0x1E ? 4
                                             : 0;
    if (n == 0 || i + n > s.size()) return false;
    std::uint32_t cp = n == 1 ? c : n == 2 ? (c & 0x1F) : n == 3 ? (c & 0x0F) : (c & 0x07);
    for (std::size_t k = 1; k < n; ++k) {
      const unsigned d = static_cast<unsigned char>(s[i + k]);
      if ((d >> 6) != 0x2) return false;
      cp = (cp << 6) | (d & 0x3F);
    }
    const std::uint32_t min_cp[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < min_cp[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += n;
  }
  return true;
}

// One line, valid UTF-8, at most max_bytes: what every message must be.
inline void check_message(const char* target, const std::string& m, std::size_t max_bytes) {
  if (m.size() > max_bytes) {
    finding(target, "message too long", std::to_string(m.size()) + " bytes");
  }
  if (!valid_utf8(m)) finding(target, "message is not valid UTF-8", m);
  for (unsigned char c : m) {
    if (c < 0x20 || c == 0x7F) finding(target, "message holds a control character", m);
  }
  if (m.find("\xC2\x85") != std::string::npos || m.find("\xE2\x80\xA8") != std::string::npos ||
      m.find("\xE2\x80\xA9") != std::string::npos) {
    finding(target, "message holds a Unicode line break", m);
  }
}

}  // namespace fuzzcheck
