// Typed, path-aware reading of JSON scene files.
#include "wb/input.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

namespace wb {

static const json kEmptyArray = json::array();

namespace {

// Length of the valid UTF-8 sequence at s[i] (1 to 4), or 0 if none starts there.
std::size_t utf8_length(const std::string& s, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = b(i);
  if (c < 0x80) return 1;
  std::size_t n;
  unsigned char lo = 0x80, hi = 0xBF;  // allowed range of the second byte
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    if (c == 0xE0) lo = 0xA0;  // no overlong forms
    if (c == 0xED) hi = 0x9F;  // no surrogates
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    if (c == 0xF0) lo = 0x90;
    if (c == 0xF4) hi = 0x8F;  // at most U+10FFFF
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  if (b(i + 1) < lo || b(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < n; ++k) {
    if (b(i + k) < 0x80 || b(i + k) > 0xBF) return 0;
  }
  return n;
}

void append_hex_byte(std::string& out, unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "\\x%02X", static_cast<unsigned>(c));
  out += buf;
}

// The escaped text (no length limit): every character printable on one line.
std::string escape_one_line(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const std::size_t n = utf8_length(s, i);
    if (n == 0) {
      append_hex_byte(out, c);  // not UTF-8
      ++i;
    } else if (n == 1) {
      if (c == '\n') {
        out += "\\n";
      } else if (c == '\r') {
        out += "\\r";
      } else if (c == '\t') {
        out += "\\t";
      } else if (c < 0x20 || c == 0x7F) {
        append_hex_byte(out, c);
      } else {
        out += static_cast<char>(c);
      }
      ++i;
    } else {
      const unsigned char c1 = static_cast<unsigned char>(s[i + 1]);
      const unsigned char c2 = n > 2 ? static_cast<unsigned char>(s[i + 2]) : 0;
      if (c == 0xC2 && c1 < 0xA0) {  // C1 controls U+0080..U+009F (NEL among them)
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\u%04X", static_cast<unsigned>(c1));
        out += buf;
      } else if (c == 0xE2 && c1 == 0x80 && (c2 == 0xA8 || c2 == 0xA9)) {
        out += c2 == 0xA8 ? "\\u2028" : "\\u2029";  // line and paragraph separators
      } else {
        out.append(s, i, n);
      }
      i += n;
    }
  }
  return out;
}

// The longest prefix of valid UTF-8 `s` of at most `max` bytes that ends on a
// character boundary.
std::size_t utf8_cut(const std::string& s, std::size_t max) {
  if (max >= s.size()) return s.size();
  std::size_t k = max;
  while (k > 0 && (static_cast<unsigned char>(s[k]) & 0xC0) == 0x80) --k;
  return k;
}

}  // namespace

std::string one_line(const std::string& s, std::size_t max_bytes) {
  std::string e = escape_one_line(s);
  if (e.size() <= max_bytes) return e;
  const std::string mid = " ... ";
  const std::size_t keep = max_bytes > mid.size() ? (max_bytes - mid.size()) / 2 : 0;
  const std::size_t head = utf8_cut(e, keep);
  std::size_t tail = e.size() - keep;  // move right to a character boundary
  while (tail < e.size() && (static_cast<unsigned char>(e[tail]) & 0xC0) == 0x80) ++tail;
  return e.substr(0, head) + mid + e.substr(tail);
}

namespace {
// The text of a number whose double hides it (below, at the number reader).
const std::string* remembered_text(const std::string& file, const std::string& path);
}  // namespace

JsonObject::JsonObject(std::string file, const json& j, std::string path)
    : file_(std::move(file)), j_(j), path_(std::move(path)) {
  if (!j_.is_object()) {
    throw InputError(file_ + ": " + (path_.empty() ? "(top level)" : path_) + ": got " +
                     describe(j_) + ", expected a JSON object");
  }
}

std::string JsonObject::key_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void JsonObject::fail(const std::string& key, const json* value,
                      const std::string& expected) const {
  std::string where = key.empty() ? (path_.empty() ? "(top level)" : path_) : key_path(key);
  std::string got = value ? "got " + describe(*value) : "missing";
  if (value && value->is_number_float()) {  // its text, where its double would mislead
    if (const std::string* text = remembered_text(file_, where)) got = "got " + *text;
  }
  throw InputError(file_ + ": " + where + ": " + got + ", expected " + expected);
}

void JsonObject::only_keys(std::initializer_list<const char*> known) const {
  for (auto it = j_.begin(); it != j_.end(); ++it) {
    bool ok = false;
    for (const char* k : known) ok = ok || it.key() == k;
    if (!ok) {
      std::string list;
      for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
      throw InputError(file_ + ": " + key_path(it.key()) +
                       ": unknown key, expected one of: " + list);
    }
  }
}

static std::string range_text(const Range& r) {
  std::ostringstream s;
  bool lo = std::isfinite(r.min), hi = std::isfinite(r.max);
  s << "a finite number";
  if (lo) s << (r.min_exclusive ? " > " : " >= ") << r.min;
  if (lo && hi) s << " and";
  if (hi) s << " <= " << r.max;
  return s.str();
}

static bool in_range(double x, const Range& r) {
  if (!std::isfinite(x)) return false;
  if (r.min_exclusive ? !(x > r.min) : !(x >= r.min)) return false;
  return x <= r.max;
}

double JsonObject::number(const char* key, Range r) const {
  if (!j_.contains(key)) fail(key, nullptr, range_text(r));
  const json& v = j_.at(key);
  if (!v.is_number()) fail(key, &v, range_text(r));
  double x = v.get<double>();
  if (!in_range(x, r)) fail(key, &v, range_text(r));
  return x;
}

double JsonObject::number_or(const char* key, double def, Range r) const {
  return j_.contains(key) ? number(key, r) : def;
}

Vec2 JsonObject::vec2(const char* key) const {
  const char* expected = "an array of 2 finite numbers";
  if (!j_.contains(key)) fail(key, nullptr, expected);
  const json& v = j_.at(key);
  if (!v.is_array() || v.size() != 2) fail(key, &v, expected);
  Vec2 out;
  for (int i = 0; i < 2; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>())) {
      fail(std::string(key) + "[" + std::to_string(i) + "]", &v[i], "a finite number");
    }
    out[i] = v[i].get<double>();
  }
  return out;
}

Vec2 JsonObject::vec2_or(const char* key, const Vec2& def) const {
  return j_.contains(key) ? vec2(key) : def;
}

std::string JsonObject::string(const char* key) const {
  if (!j_.contains(key)) fail(key, nullptr, "a string");
  const json& v = j_.at(key);
  if (!v.is_string()) fail(key, &v, "a string");
  return v.get<std::string>();
}

std::string JsonObject::string_or(const char* key, const std::string& def) const {
  return j_.contains(key) ? string(key) : def;
}

namespace {

// A whole number in [min, max] from `v`, or nothing. Every number whose text is
// exactly a whole number that fits 64 bits (5, 5.0, 1e3, 9007199254740993.0) was
// stored as an integer by the parser (parse_json), exactly as written: a number
// still stored as a double is not whole (0.5, 1e-400) or does not fit (1e300).
std::optional<std::int64_t> whole_number(const json& v, std::int64_t min, std::int64_t max) {
  if (v.is_number_unsigned()) {
    const std::uint64_t u = v.get<std::uint64_t>();
    if (max < 0 || u > static_cast<std::uint64_t>(max) ||
        (min > 0 && u < static_cast<std::uint64_t>(min))) {
      return std::nullopt;
    }
    return static_cast<std::int64_t>(u);
  }
  if (v.is_number_integer()) {
    const std::int64_t i = v.get<std::int64_t>();
    if (i < min || i > max) return std::nullopt;
    return i;
  }
  return std::nullopt;
}

std::string whole_expected(std::int64_t min, std::int64_t max) {
  return "a whole number from " + std::to_string(min) + " to " + std::to_string(max);
}

}  // namespace

std::int64_t JsonObject::integer(const char* key, std::int64_t min, std::int64_t max) const {
  if (!j_.contains(key)) fail(key, nullptr, whole_expected(min, max));
  const json& v = j_.at(key);
  const std::optional<std::int64_t> i = whole_number(v, min, max);
  if (!i) fail(key, &v, whole_expected(min, max));
  return *i;
}

std::int64_t JsonObject::integer_in(const char* key, std::size_t i, std::int64_t min,
                                    std::int64_t max, const std::string& note) const {
  const json& a = array_or_empty(key);
  const std::string at = std::string(key) + "[" + std::to_string(i) + "]";
  if (i >= a.size()) fail(at, nullptr, whole_expected(min, max) + note);
  const std::optional<std::int64_t> w = whole_number(a[i], min, max);
  if (!w) fail(at, &a[i], whole_expected(min, max) + note);
  return *w;
}

std::int64_t JsonObject::integer_or(const char* key, std::int64_t def, std::int64_t min,
                                    std::int64_t max) const {
  return j_.contains(key) ? integer(key, min, max) : def;
}

bool JsonObject::boolean_or(const char* key, bool def) const {
  if (!j_.contains(key)) return def;
  const json& v = j_.at(key);
  if (!v.is_boolean()) fail(key, &v, "true or false");
  return v.get<bool>();
}

JsonObject JsonObject::object(const char* key) const {
  if (!j_.contains(key)) fail(key, nullptr, "a JSON object");
  const json& v = j_.at(key);
  if (!v.is_object()) fail(key, &v, "a JSON object");
  return JsonObject(file_, v, key_path(key));
}

const json& JsonObject::array_or_empty(const char* key) const {
  if (!j_.contains(key)) return kEmptyArray;
  const json& v = j_.at(key);
  if (!v.is_array()) fail(key, &v, "an array");
  return v;
}

JsonObject JsonObject::element(const char* key, std::size_t i) const {
  const json& a = array_or_empty(key);
  std::string p = key_path(key) + "[" + std::to_string(i) + "]";
  if (i >= a.size()) {
    throw InputError(file_ + ": " + p + ": missing, expected " + key + " to have at least " +
                     std::to_string(i + 1) + " entries");
  }
  if (!a[i].is_object()) {
    throw InputError(file_ + ": " + p + ": got " + describe(a[i]) + ", expected a JSON object");
  }
  return JsonObject(file_, a[i], p);
}

namespace {

constexpr std::size_t kDescribeBytes = 60;
constexpr int kDescribeDepth = 3;

// A JSON string, quoted, at most about kDescribeBytes of it.
void render_string(const std::string& s, std::string& out) {
  const std::size_t n = utf8_cut(s, kDescribeBytes);
  std::string body;
  for (std::size_t i = 0; i < n; ++i) {
    if (s[i] == '"' || s[i] == '\\') body += '\\';
    body += s[i];
  }
  out += '"' + escape_one_line(body) + (n < s.size() ? "..." : "") + '"';
}

// Renders `v` until `out` is longer than kDescribeBytes: a huge or deep value
// costs no more than a small one.
void render(const json& v, std::string& out, int depth) {
  if (v.is_object() || v.is_array()) {
    const bool obj = v.is_object();
    if (v.empty()) {
      out += obj ? "{}" : "[]";
      return;
    }
    if (depth >= kDescribeDepth) {
      out += obj ? "{...}" : "[...]";
      return;
    }
    out += obj ? '{' : '[';
    bool first = true;
    for (auto it = v.begin(); it != v.end(); ++it) {
      if (out.size() > kDescribeBytes) {
        out += "...";
        return;
      }
      if (!first) out += ',';
      first = false;
      if (obj) {
        render_string(it.key(), out);
        out += ':';
      }
      render(it.value(), out, depth + 1);
    }
    out += obj ? '}' : ']';
  } else if (v.is_string()) {
    render_string(v.get_ref<const std::string&>(), out);
  } else {
    out += v.dump();  // a number, true, false or null: short
  }
}

}  // namespace

// ---- The one number reader (wb/input.h).

namespace {

// The texts of numbers a message may need that their double does not show (a fraction
// refused as a whole number), by file and JSON path; at most kMaxTexts of them.
constexpr std::size_t kMaxTexts = 10000;
std::map<std::string, std::map<std::string, std::string>>& number_texts() {
  static std::map<std::string, std::map<std::string, std::string>> texts;
  return texts;
}
std::size_t g_texts = 0;

void remember_text(const std::string& file, const std::string& path, const std::string& text) {
  if (g_texts >= kMaxTexts) return;
  ++g_texts;
  number_texts()[file][path] = text.size() > 80 ? text.substr(0, 77) + "..." : text;
}

const std::string* remembered_text(const std::string& file, const std::string& path) {
  const auto f = number_texts().find(file);
  if (f == number_texts().end()) return nullptr;
  const auto p = f->second.find(path);
  return p == f->second.end() ? nullptr : &p->second;
}

bool digit(char c) { return c >= '0' && c <= '9'; }

}  // namespace

NumberText read_number(const std::string& text) {
  NumberText r;
  const std::size_t n = text.size();
  std::size_t i = 0;
  // The grammar, and where its parts are.
  const bool minus = i < n && text[i] == '-';
  if (minus) ++i;
  const std::size_t int_begin = i;
  if (i < n && text[i] == '0') {
    ++i;
  } else if (i < n && text[i] >= '1' && text[i] <= '9') {
    while (i < n && digit(text[i])) ++i;
  } else {
    return r;
  }
  const std::size_t int_end = i;
  std::size_t frac_begin = i, frac_end = i;
  if (i < n && text[i] == '.') {
    frac_begin = ++i;
    while (i < n && digit(text[i])) ++i;
    frac_end = i;
    if (frac_end == frac_begin) return r;
  }
  // The written exponent, saturated far beyond any double (and any 16 MiB of digits).
  constexpr std::int64_t kExpCap = std::int64_t(1) << 50;
  std::int64_t exp = 0;
  if (i < n && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    bool exp_minus = false;
    if (i < n && (text[i] == '+' || text[i] == '-')) exp_minus = text[i++] == '-';
    const std::size_t exp_begin = i;
    while (i < n && digit(text[i])) {
      exp = std::min(kExpCap, exp * 10 + (text[i] - '0'));
      ++i;
    }
    if (i == exp_begin) return r;
    if (exp_minus) exp = -exp;
  }
  if (i != n) return r;
  r.valid = true;

  // The value is D x 10^e: D the significant digits (no leading or trailing zeros).
  auto at = [&](std::size_t k) {  // k-th digit of the integer part, then of the fraction
    const std::size_t ni = int_end - int_begin;
    return k < ni ? text[int_begin + k] : text[frac_begin + (k - ni)];
  };
  const std::size_t total = (int_end - int_begin) + (frac_end - frac_begin);
  std::size_t first = 0, last = total;  // [first, last): significant
  while (first < total && at(first) == '0') ++first;
  if (first == total) {  // 0, -0.0, 0e5: zero, and whole
    r.whole = r.fits = true;
    r.value = minus ? -0.0 : 0.0;
    return r;
  }
  while (at(last - 1) == '0') --last;
  r.nonzero = true;
  const std::int64_t frac_digits = std::int64_t(frac_end - frac_begin);
  // e: the exponent of the last significant digit.
  const std::int64_t e = exp - frac_digits + std::int64_t(total - last);
  const std::int64_t k = std::int64_t(last - first);
  r.whole = e >= 0;
  r.negative = minus;
  if (r.whole && k + e <= 20) {
    std::uint64_t m = 0;
    bool ok = true;
    for (std::int64_t q = 0; q < k + e && ok; ++q) {
      const std::uint64_t d = q < k ? std::uint64_t(at(first + std::size_t(q)) - '0') : 0;
      ok = m <= (UINT64_MAX - d) / 10;
      m = m * 10 + d;
    }
    r.fits = ok;
    r.magnitude = ok ? m : 0;
  }

  // The double: correctly rounded (std::from_chars where the library has it for doubles;
  // strtod, also correctly rounded in glibc and musl, elsewhere: the text is already
  // known to be a plain decimal, so the locale and hex forms cannot enter).
  // The magnitude of the number is 10^(k + e - 1) to 10^(k + e).
  const std::int64_t order = k + e;
  if (order > 400) {
    r.overflow = true;
    r.value = minus ? -HUGE_VAL : HUGE_VAL;
    return r;
  }
  if (order < -400) {
    r.underflow = true;
    r.value = minus ? -0.0 : 0.0;
    return r;
  }
  double v = 0;
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  const auto res = std::from_chars(text.data(), text.data() + n, v);
  if (res.ec == std::errc::result_out_of_range) {
    v = order > 0 ? HUGE_VAL : 0.0;
    if (minus) v = -v;
  }
#else
  v = std::strtod(text.c_str(), nullptr);
#endif
  r.value = v;
  r.overflow = std::isinf(v);
  r.underflow = v == 0.0;
  return r;
}

bool whole_in(const NumberText& t, std::int64_t min, std::int64_t max, std::int64_t& out) {
  if (!t.valid || !t.whole || !t.fits) return false;
  if (!t.negative) {
    if (max < 0 || t.magnitude > std::uint64_t(max)) return false;
    if (min > 0 && t.magnitude < std::uint64_t(min)) return false;
    out = std::int64_t(t.magnitude);
    return true;
  }
  // -magnitude >= min
  if (t.magnitude > std::uint64_t(INT64_MAX) + 1) return false;
  const std::int64_t v =
      t.magnitude == std::uint64_t(INT64_MAX) + 1 ? INT64_MIN : -std::int64_t(t.magnitude);
  if (v < min || v > max) return false;
  out = v;
  return true;
}

namespace {

// Builds the document as the parser reads it (nlohmann's SAX interface),
// keeping the JSON path of the value being read for messages, refusing a key
// given twice in one object and nesting deeper than kMaxJsonDepth. Every event
// costs O(1) plus the key lookup in its own object, so parsing is linear in
// the file's size. (nlohmann 3.11's parser callback is not: when an object or
// array closes it rescans its parent array, so an array of n objects costs
// O(n^2), hours for a 16 MiB file.)
class DomBuilder {
 public:
  DomBuilder(const std::string& file, json& root) : file_(file), root_(root) {}

  bool null() { return value(json(nullptr)); }
  bool boolean(bool b) { return value(json(b)); }
  bool number_integer(json::number_integer_t i) { return value(json(i)); }
  bool number_unsigned(json::number_unsigned_t u) { return value(json(u)); }
  // A number written with a fraction or an exponent: read again from its text by the
  // one reader (read_number, the value nlohmann's strtod found is not used) and stored
  // as the integer it exactly is when its text is a whole number that fits 64 bits (so
  // 5.0 and 9007199254740993.0 are whole numbers, read exactly), else as the double; a
  // number whose text is not 0 but that reads as 0 (1e-400) is refused.
  bool number_float(json::number_float_t, const std::string& text) {
    const NumberText e = read_number(text);
    if (e.underflow) {
      throw InputError(file_ + ": " + path() + ": got " + text +
                       ", a number too small for a double (it reads as 0), expected 0 or a "
                       "number of at least 4.9e-324 in size (the smallest double)");
    }
    if (e.overflow || !e.valid) {  // the parser refuses these before; kept for its message
      throw InputError(file_ + ": " + path() + ": got " + text +
                       ", a number too large for a double, expected a finite number");
    }
    std::int64_t i = 0;
    if (whole_in(e, INT64_MIN, INT64_MAX, i)) return value(json(i));
    if (e.whole && e.fits && !e.negative) return value(json(e.magnitude));
    // A fraction that rounds to a whole double (1000.0000000000000000001) would be shown
    // as "1000.0" by a message refusing it as a whole number: its text is kept for that.
    if (!e.whole && e.value == std::floor(e.value)) remember_text(file_, path(), text);
    return value(json(e.value));
  }
  bool string(std::string& s) { return value(json(std::move(s))); }
  bool binary(json::binary_t& b) { return value(json(std::move(b))); }
  bool start_object(std::size_t) { return open(json::value_t::object); }
  bool start_array(std::size_t) { return open(json::value_t::array); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(std::string& k) {
    Frame& f = stack_.back();
    f.key = k;
    f.has_key = true;
    if (f.node->contains(k)) {
      throw InputError(file_ + ": " + path() +
                       ": key given twice in one object, expected each key at most once");
    }
    slot_ = &(*f.node)[k];
    return true;
  }

  // A syntax error or a number too large for a double: thrown as the
  // library's exception, caught by parse_json with path() still in place.
  template <class Exception>
  bool parse_error(std::size_t, const std::string&, const Exception& e) {
    throw e;
  }

  // Where the parser is: "forces[2].k", or "(top level)".
  std::string path() const {
    std::string p;
    for (const Frame& f : stack_) {
      if (f.array) {
        p += "[" + std::to_string(f.index) + "]";
      } else if (f.has_key) {
        p += (p.empty() ? "" : ".") + f.key;
      }
    }
    return p.empty() ? "(top level)" : p;
  }

 private:
  struct Frame {
    json* node;         // the array or object being filled
    bool array;         // an array (else an object)
    std::size_t index;  // array: elements read so far
    std::string key;    // object: the key being read
    bool has_key;
  };

  // Stores v where the parser is (the root, the next array element or the
  // value of the last key) and returns where it went.
  json* place(json&& v) {
    if (stack_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Frame& f = stack_.back();
    if (f.array) {
      f.node->get_ref<json::array_t&>().push_back(std::move(v));
      return &f.node->get_ref<json::array_t&>().back();
    }
    *slot_ = std::move(v);
    return slot_;
  }
  bool value(json&& v) {
    place(std::move(v));
    value_done();
    return true;
  }
  bool open(json::value_t type) {
    if (stack_.size() >= std::size_t(kMaxJsonDepth)) {
      throw InputError(file_ + ": " + path() + ": nested deeper than " +
                       std::to_string(kMaxJsonDepth) + " arrays and objects, expected at most " +
                       std::to_string(kMaxJsonDepth) + " levels");
    }
    json* node = place(json(type));
    stack_.push_back(Frame{node, type == json::value_t::array, 0, {}, false});
    return true;
  }
  bool close() {
    stack_.pop_back();
    value_done();
    return true;
  }
  void value_done() {
    if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
  }

  const std::string& file_;
  json& root_;
  std::vector<Frame> stack_;
  json* slot_ = nullptr;  // the value of the last key read
};

// The library's message without its "[json.exception...]" prefix.
std::string library_message(const std::string& what, const char* from) {
  const auto p = what.find(from);
  return p == std::string::npos ? what : what.substr(p);
}

}  // namespace

std::string describe(const json& value) {
  std::string s;
  render(value, s, 0);
  if (s.size() > kDescribeBytes) s = s.substr(0, utf8_cut(s, kDescribeBytes - 3)) + "...";
  return s;
}

json parse_json(const std::string& text, const std::string& file) {
  // The texts kept from this file's last parse are of another document.
  if (number_texts().count(file)) {
    g_texts -= number_texts()[file].size();
    number_texts().erase(file);
  }
  json doc;
  DomBuilder where(file, doc);
  try {
    json::sax_parse(text, &where);
    return doc;
  } catch (const json::out_of_range& e) {
    // A number too large for a double (1e999) is refused by the parser.
    const std::string what = e.what();
    const std::string marker = "number overflow parsing '";
    const auto p = what.find(marker);
    std::string got = "a number";
    if (p != std::string::npos) {
      const std::size_t b = p + marker.size(), q = what.find('\'', b);
      got = what.substr(b, q == std::string::npos ? std::string::npos : q - b);
    }
    throw InputError(file + ": " + where.path() + ": got " + got +
                     ", a number too large for a double, expected a finite number");
  } catch (const json::exception& e) {
    // e.what() carries the line and column; drop the library's prefix.
    throw InputError(file + ": not valid JSON at " + where.path() + ": " +
                     library_message(e.what(), "parse error"));
  }
}

json read_json_file(const std::string& file) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);
  if (fs::is_directory(st)) throw InputError(file + ": a folder, expected a JSON file");
  if (fs::exists(st) && !fs::is_regular_file(st)) {
    throw InputError(file + ": not a regular file (a device, a pipe or a socket), expected a " +
                     "JSON file");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file + ": cannot open the file for reading");
  // Read at most one byte past the limit: a file that grows while it is read
  // (or that reports no size) still costs bounded time and memory.
  std::string text;
  char buf[1 << 16];
  while (text.size() <= kMaxJsonFileBytes) {
    in.read(buf, sizeof buf);
    if (in.gcount() <= 0) break;
    text.append(buf, std::size_t(in.gcount()));
  }
  if (text.size() > kMaxJsonFileBytes) {
    throw InputError(file + ": larger than " + std::to_string(kMaxJsonFileBytes) +
                     " bytes, expected a JSON file of at most 16 MiB");
  }
  if (in.bad()) throw InputError(file + ": cannot read the file");
  return parse_json(text, file);
}

}  // namespace wb
