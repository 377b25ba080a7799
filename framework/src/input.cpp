// Typed, path-aware reading of JSON scene files.
#include "wb/input.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace wb {

static const json kEmptyArray = json::array();

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

std::int64_t JsonObject::integer(const char* key, std::int64_t min, std::int64_t max) const {
  std::string expected =
      "a whole number from " + std::to_string(min) + " to " + std::to_string(max);
  if (!j_.contains(key)) fail(key, nullptr, expected);
  const json& v = j_.at(key);
  if (!v.is_number()) fail(key, &v, expected);
  double d = v.get<double>();
  if (!std::isfinite(d) || d != std::floor(d) || d < double(min) || d > double(max)) {
    fail(key, &v, expected);
  }
  return static_cast<std::int64_t>(d);
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
  if (!a.at(i).is_object()) {
    throw InputError(file_ + ": " + p + ": got " + describe(a.at(i)) +
                     ", expected a JSON object");
  }
  return JsonObject(file_, a.at(i), p);
}

std::string describe(const json& value) {
  std::string s = value.dump();
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

json read_json_file(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file + ": cannot open the file for reading");
  std::stringstream buf;
  buf << in.rdbuf();
  try {
    return json::parse(buf.str());
  } catch (const json::out_of_range& e) {
    // A number too large for a double (1e999) is refused by the parser.
    std::string what = e.what();
    auto p = what.find("number overflow");
    throw InputError(
        file + ": not a usable JSON number: " + (p == std::string::npos ? what : what.substr(p)) +
        ", expected a finite number");
  } catch (const json::parse_error& e) {
    // e.what() carries the byte position; drop the library's prefix.
    std::string what = e.what();
    auto p = what.find("parse error");
    throw InputError(file +
                     ": not valid JSON: " + (p == std::string::npos ? what : what.substr(p)));
  }
}

}  // namespace wb
