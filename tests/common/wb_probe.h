// Diagnosis probes: fixed, public inputs on which the grader calls a task's functions to tell
// mistakes apart (docs/grading.md, "Diagnosis").
//
// A probe is not a test: it carries no points and checks nothing. It records the inputs it
// gives and the outputs it gets; tools/mutants records the same probes' outputs for the
// solution, the skeleton and every catalogued mistake (tests/mutants/<lab>/signatures.json,
// numbers only), and tools/diagnosis/hints.py compares a submission's outputs with them: the
// first probe whose output differs is the counterexample the student reads, and the outputs
// that go wrong point at the part of the computation the mistake is in.
//
//   WB_PROBE("F3", "pull", "a particle of mass 2 at distance 5 from the centre, a massless one")
//   {
//     ...
//     P.call("add_attractor");
//     P.in("x", x), P.in("m", m), P.in("center", c), P.in("GM", GM), P.in("f", f);
//     add_attractor(x, m, c, GM, f);
//     P.out("f", f);
//   }
//
// How to write them (docs/grading.md, "Writing probes"):
// - Details first, marked P.simple(): the simplest cases and those that isolate one factor (unit
//   masses, one axis, one situation such as "just touching"). The counterexample is the first
//   probe, in the order written, whose output is wrong: a detail reads best.
// - Then one probe per part of the computation (a '# kind:' of the catalogue: the spring term,
//   the damper, the particle loop), with generic values (no 1, no 0, no symmetry, a centre off
//   the origin), so that every mistake in that part shows there and mistakes in other parts
//   show as little as possible: the damper at the rest length, the spring at rest. Where a
//   part's mistakes show in different situations (a contact test: just touching, receding, the
//   centre below the plane), put the situations in one probe and one output. Give a particle
//   that a correct function leaves alone the last place (massless, moving with the flow): a
//   loop that skips the last particle then shows only in the probe of the loop.
// - Record every input a student needs to redo the call (P.in), in the order of the
//   parameters; a callback is described in words (P.note).
// - Record outputs whole (P.out: a 2 x n matrix, not its first column): what comes back from
//   the student's code may have any size. P.out_each tells its columns apart (a particle that
//   goes wrong alone). Outputs whose order is unspecified (a list of pairs) are put in a
//   canonical order before recording. Outputs that separate parts (the new x from the new v)
//   are recorded apart; outputs that one part's mistakes change in turn (the fields of a
//   report) together.
// - P.tol(rel, abs): how close two outputs must be to count as the same (default 1e-7
//   relative, 1e-9 of the probe's largest expected output absolute): every alternative in
//   tests/mutants/<lab>/alternatives/ must agree with the solution to this tolerance.
//
// The binary (<lab>-probes, built by the grader with the stubs of the worker, or
// <lab>-probes-direct linked with the lab for tools/mutants) prints one JSON line per probe:
//   <lab>-probes --list          every probe's task, id and title, without calling anything
//   <lab>-probes ID...           runs these probes in order (ID is "<task>/<id>")
// An exception in a probe is recorded as its "error"; a non-finite number is written as the
// string "nan", "inf" or "-inf".
#pragma once
#include <cmath>
#include <cstdio>
#include <exception>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

namespace wbprobe {

struct Value {
  Value() = default;
  Value(std::string n, long r, long c, std::vector<double> d, bool whole)
      : name(std::move(n)), rows(r), cols(c), data(std::move(d)), integer(whole) {}
  std::string name;
  long rows = 1, cols = 1;   // a scalar is 1 x 1
  std::vector<double> data;  // column-major
  bool integer = false;      // shown without decimals
  bool each = false;         // its columns are told apart (Probe::out_each)
  std::string group;         // outputs of one group go wrong together (Probe::group)
};

class Probe {
 public:
  // Inputs, in the order of the parameters.
  template <class T>
  void in(const char* name, const T& v) {
    inputs_.push_back(value(name, v));
  }
  // Outputs, whole: the diagnosis tells parts apart by which outputs of which probes go wrong.
  template <class T>
  void out(const char* name, const T& v) {
    outputs_.push_back(value(name, v));
    outputs_.back().group = group_;
  }
  // Outputs recorded after P.group("body") go wrong together for the diagnosis (each is still
  // shown apart): one part's mistakes change some of them, another's others (P.group("") ends).
  void group(const char* name) { group_ = name; }
  // An output whose columns (particles, bodies) go wrong apart: a loop that misses one shows as
  // that column alone.
  template <class T>
  void out_each(const char* name, const T& v) {
    outputs_.push_back(value(name, v));
    outputs_.back().each = true;
    outputs_.back().group = group_;
  }
  // The function called (shown with the inputs: "add_attractor(x = ..., m = ...)").
  void call(const char* name) { call_ = name; }
  const std::string& called() const { return call_; }
  // Words for an input that is not a number (a callback: "a(x, v) = -x").
  void note(const std::string& words) { notes_.push_back(words); }
  void tol(double rel, double abs) { rel_ = rel, abs_ = abs; }
  // A detail: a simple case, or one that isolates one factor of a part (unit masses, one axis,
  // one situation), written for the counterexample a student reads. It explains a mistake but
  // does not say which part of the computation it is in: the diagnosis leaves it out when it
  // tells parts apart (docs/grading.md, "Writing probes").
  void simple() { simple_ = true; }
  bool is_simple() const { return simple_; }

  const std::vector<Value>& inputs() const { return inputs_; }
  const std::vector<Value>& outputs() const { return outputs_; }
  const std::vector<std::string>& notes() const { return notes_; }
  double rel() const { return rel_; }
  double abs() const { return abs_; }

 private:
  static Value value(const char* name, double v) { return {name, 1, 1, {v}, false}; }
  static Value value(const char* name, int v) { return {name, 1, 1, {double(v)}, true}; }
  static Value value(const char* name, long v) { return {name, 1, 1, {double(v)}, true}; }
  static Value value(const char* name, long long v) { return {name, 1, 1, {double(v)}, true}; }
  static Value value(const char* name, bool v) { return {name, 1, 1, {v ? 1.0 : 0.0}, true}; }
  template <class D>
  static Value value(const char* name, const Eigen::MatrixBase<D>& m) {
    Value out{name, long(m.rows()), long(m.cols()), {}, false};
    for (Eigen::Index j = 0; j < m.cols(); ++j)
      for (Eigen::Index i = 0; i < m.rows(); ++i) out.data.push_back(double(m(i, j)));
    return out;
  }
  static Value value(const char* name, const Eigen::Quaterniond& q) {
    return {name, 4, 1, {q.w(), q.x(), q.y(), q.z()}, false};  // (w, x, y, z)
  }
  static Value value(const char* name, const Eigen::SparseMatrix<double>& s) {
    return value(name, Eigen::MatrixXd(s));
  }
  static Value value(const char* name, const std::vector<std::pair<int, int>>& pairs) {
    Value out{name, long(pairs.size()), 2, {}, true};
    out.data.resize(2 * pairs.size());
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      out.data[k] = pairs[k].first;
      out.data[pairs.size() + k] = pairs[k].second;
    }
    return out;
  }

  std::vector<Value> inputs_, outputs_;
  std::vector<std::string> notes_;
  std::string call_, group_;
  double rel_ = 1e-7, abs_ = 1e-9;
  bool simple_ = false;
};

// Inputs written as lists: cols({{2, 0}, {0, 3}}) is the 2 x 2 matrix of columns (2, 0) and
// (0, 3); vec({1, 2}) the vector (1, 2).
inline Eigen::Matrix<double, 2, Eigen::Dynamic> cols(
    std::initializer_list<std::pair<double, double>> c) {
  Eigen::Matrix<double, 2, Eigen::Dynamic> m(2, Eigen::Index(c.size()));
  Eigen::Index j = 0;
  for (const auto& p : c) m(0, j) = p.first, m(1, j) = p.second, ++j;
  return m;
}
inline Eigen::VectorXd vec(std::initializer_list<double> c) {
  Eigen::VectorXd v(Eigen::Index(c.size()));
  Eigen::Index j = 0;
  for (double x : c) v[j++] = x;
  return v;
}

using Fn = void (*)(Probe&);
struct Entry {
  const char* task;
  const char* id;
  const char* title;
  Fn fn;
};

inline std::vector<Entry>& registry() {
  static std::vector<Entry> r;
  return r;
}

struct Register {
  Register(const char* task, const char* id, const char* title, Fn fn) {
    registry().push_back({task, id, title, fn});
  }
};

namespace detail {

inline std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += char(c);
    } else if (c < 0x20 || c >= 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;  // bytes outside ASCII as \u00XX: the reader decides what is printable
    } else {
      out += char(c);
    }
  }
  return out + "\"";
}

inline std::string number(double v) {
  if (std::isnan(v)) return "\"nan\"";
  if (std::isinf(v)) return v > 0 ? "\"inf\"" : "\"-inf\"";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

inline std::string values(const std::vector<Value>& vs) {
  std::string out = "[";
  for (std::size_t k = 0; k < vs.size(); ++k) {
    const Value& v = vs[k];
    out += (k ? ",{" : "{") + std::string("\"name\":") + quoted(v.name) + ",\"shape\":[" +
           std::to_string(v.rows) + "," + std::to_string(v.cols) + "]";
    if (v.integer) out += ",\"integer\":true";
    if (v.each) out += ",\"each\":true";
    if (!v.group.empty()) out += ",\"group\":" + quoted(v.group);
    out += ",\"v\":[";
    for (std::size_t i = 0; i < v.data.size(); ++i) out += (i ? "," : "") + number(v.data[i]);
    out += "]}";
  }
  return out + "]";
}

inline std::string head(const Entry& e) {
  return "{\"probe\":" + quoted(std::string(e.task) + "/" + e.id) +
         ",\"task\":" + quoted(e.task) + ",\"title\":" + quoted(e.title);
}

}  // namespace detail

inline int main(int argc, char** argv) {
  const std::vector<Entry>& all = registry();
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() == 1 && args[0] == "--list") {
    for (const Entry& e : all) std::printf("%s}\n", detail::head(e).c_str());
    return 0;
  }
  for (const std::string& id : args) {
    const Entry* e = nullptr;
    for (const Entry& c : all)
      if (std::string(c.task) + "/" + c.id == id) e = &c;
    if (!e) {
      std::fprintf(stderr, "no probe %s (--list lists them)\n", id.c_str());
      return 2;
    }
    Probe p;
    std::string error;
    try {
      e->fn(p);
    } catch (const std::exception& ex) {
      error = ex.what();
      if (error.empty()) error = "an exception with no message";
    } catch (...) {
      error = "an exception that is not a std::exception";
    }
    std::string line = detail::head(*e) + ",\"in\":" + detail::values(p.inputs()) +
                       ",\"out\":" + detail::values(p.outputs()) + ",\"notes\":[";
    for (std::size_t k = 0; k < p.notes().size(); ++k)
      line += (k ? "," : "") + detail::quoted(p.notes()[k]);
    line += "],\"tol\":[" + detail::number(p.rel()) + "," + detail::number(p.abs()) + "]";
    if (p.is_simple()) line += ",\"simple\":true";
    if (!p.called().empty()) line += ",\"call\":" + detail::quoted(p.called());
    if (!error.empty()) line += ",\"error\":" + detail::quoted(error.substr(0, 2000));
    std::printf("%s}\n", line.c_str());
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace wbprobe

#define WB_PROBE_CAT2(a, b) a##b
#define WB_PROBE_CAT(a, b) WB_PROBE_CAT2(a, b)
#define WB_PROBE_IMPL(task, id, title, n)                                                        \
  static void WB_PROBE_CAT(wb_probe_fn_, n)(wbprobe::Probe & P);                                 \
  static const wbprobe::Register WB_PROBE_CAT(wb_probe_reg_, n)(task, id, title,                 \
                                                                &WB_PROBE_CAT(wb_probe_fn_, n)); \
  static void WB_PROBE_CAT(wb_probe_fn_, n)(wbprobe::Probe & P)
// WB_PROBE(task, id, title) { ... uses P ... }: one probe (ids unique within the task).
#define WB_PROBE(task, id, title) WB_PROBE_IMPL(task, id, title, __COUNTER__)
