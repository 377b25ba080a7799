// The cost model's sums, limits and messages (wb/cost.h).
#include "wb/cost.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "wb/output.h"

namespace wb {

namespace {

std::string fmt(double x) {
  std::string s;
  append_number(s, x);
  return s;
}

// A count as digits when it is a whole number a reader can take in, else 3 digits.
std::string count_text(double x) {
  char buf[32];
  if (x == std::floor(x) && std::abs(x) < 1e15) {
    std::snprintf(buf, sizeof buf, "%.0f", x);
  } else {
    std::snprintf(buf, sizeof buf, "%.3g", x);
  }
  return buf;
}

// A whole number of the flag's unit at least `x` (+ 10 %: the estimate is an estimate).
std::string flag_value(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f", std::ceil(1.1 * x));
  return buf;
}

const CostTerm* largest(const std::vector<CostTerm>& terms, double CostTerm::*field) {
  const CostTerm* best = nullptr;
  for (const CostTerm& t : terms) {
    if (!best || t.*field > best->*field) best = &t;
  }
  return best;
}

std::string term_text(const CostTerm& t) {
  return t.what + (t.key.empty() ? "" : " [" + t.key + "]");
}

}  // namespace

void Estimate::add(const std::string& what, const std::string& key, double units,
                   double seconds_per_unit, double bytes, double cap_units) {
  CostTerm t;
  t.what = what;
  t.key = key;
  t.seconds = units * seconds_per_unit;
  t.cap_seconds = (cap_units >= units ? cap_units : units) * seconds_per_unit;
  t.bytes = bytes;
  terms_.push_back(std::move(t));
}

void Estimate::add_times(const Estimate& e, double times, const std::string& how, bool hold) {
  for (const CostTerm& t : e.terms_) {
    CostTerm s = t;
    s.what += how;
    s.seconds *= times;
    s.cap_seconds *= times;
    if (!hold) s.bytes = 0;  // memory is held once, not repeated
    terms_.push_back(std::move(s));
  }
}

double Estimate::seconds() const {
  double s = 0;
  for (const CostTerm& t : terms_) s += t.seconds;
  return s;
}

double Estimate::cap_seconds() const {
  double s = 0;
  for (const CostTerm& t : terms_) s += t.cap_seconds;
  return s;
}

double Estimate::bytes() const {
  double b = 0;
  for (const CostTerm& t : terms_) b += t.bytes;
  return b;
}

std::string seconds_text(double s) {
  char buf[48];
  if (!std::isfinite(s)) return "forever";
  if (s < 1.0) {
    std::snprintf(buf, sizeof buf, "%.2g s", s);
  } else if (s < 120) {
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  } else if (s < 7200) {
    std::snprintf(buf, sizeof buf, "%.0f minutes", s / 60);
  } else if (s < 2 * 86400) {
    std::snprintf(buf, sizeof buf, "%.1f hours", s / 3600);
  } else {
    std::snprintf(buf, sizeof buf, "%.3g days", s / 86400);
  }
  return buf;
}

std::string bytes_text(double b) {
  char buf[48];
  if (!std::isfinite(b)) return "unbounded memory";
  if (b < 1024.0 * 1024 * 1024) {
    std::snprintf(buf, sizeof buf, "%.0f MiB", b / (1024.0 * 1024));
  } else {
    std::snprintf(buf, sizeof buf, "%.3g GiB", b / (1024.0 * 1024 * 1024));
  }
  return buf;
}

std::string describe_estimate(const Estimate& e) {
  std::string s = "about " + seconds_text(e.seconds()) + " of CPU";
  if (e.cap_seconds() > 1.5 * e.seconds()) {
    s += " (at most " + seconds_text(e.cap_seconds()) + " if every iteration runs to its cap)";
  }
  return s + " and " + bytes_text(e.bytes());
}

std::string judge(const Estimate& e, const Budget& b, const std::string& file) {
  const double cap = e.cap_seconds(), bytes = e.bytes();
  // Memory first: a run over it cannot finish however long one waits.
  if (!(bytes <= b.bytes)) {
    const CostTerm* t = largest(e.terms(), &CostTerm::bytes);
    throw InputError(file + ": this run needs " + describe_estimate(e) + ", expected at most " +
                     bytes_text(b.bytes) + " of memory; the largest term is " + term_text(*t) +
                     ": " + bytes_text(t->bytes) + " (--max-memory " +
                     flag_value(bytes / (1024.0 * 1024)) + " allows it)");
  }
  if (!(cap <= b.seconds)) {
    const CostTerm* t = largest(e.terms(), &CostTerm::cap_seconds);
    throw InputError(file + ": this run needs " + describe_estimate(e) + ", expected at most " +
                     seconds_text(b.seconds) + "; the largest term is " + term_text(*t) + ": " +
                     seconds_text(t->cap_seconds) + " (--max-time " + flag_value(cap) +
                     " allows it)");
  }
  if (e.seconds() > kWarnSeconds || bytes > kWarnMemoryShare * b.bytes) {
    const CostTerm* t = largest(e.terms(), &CostTerm::seconds);
    if (bytes > kWarnMemoryShare * b.bytes) t = largest(e.terms(), &CostTerm::bytes);
    return file + ": this run takes " + describe_estimate(e) + " (docs/scenes.md, \"Cost\"); " +
           "the largest term is " + term_text(*t);
  }
  return "";
}

ordered_json estimate_json(const Estimate& e) {
  ordered_json j;
  j["status"] = "estimate";
  j["seconds"] = e.seconds();
  j["cap_seconds"] = e.cap_seconds();
  j["bytes"] = e.bytes();
  ordered_json terms = ordered_json::array();
  for (const CostTerm& t : e.terms()) {
    ordered_json k;
    k["what"] = t.what;
    k["key"] = t.key;
    k["seconds"] = t.seconds;
    k["cap_seconds"] = t.cap_seconds;
    k["bytes"] = t.bytes;
    terms.push_back(k);
  }
  j["terms"] = terms;
  return j;
}

WorkMeter::WorkMeter(std::string file, std::string what, double per_step, std::string why)
    : file_(std::move(file)), what_(std::move(what)), why_(std::move(why)), per_step_(per_step) {}

void WorkMeter::count(double units) {
  if (over(units)) {
    throw InputError(file_ + ": stopped at step " + std::to_string(step_) + ": it needs " +
                     count_text(done_ + units) + " " + what_ + ", more than " +
                     fmt(kOverrunFactor) + " times the " + count_text(per_step_) +
                     " per step the cost model estimated before the run (docs/scenes.md, "
                     "\"Cost\"); " +
                     why_);
  }
  done_ += units;
}

}  // namespace wb
