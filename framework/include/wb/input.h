// Reading scene files: every error names the file, the JSON path, the value
// and what was expected, and is reported by the run contract with exit status 2.
#pragma once
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "wb/types.h"

namespace wb {

using json = nlohmann::json;
using ordered_json = nlohmann::ordered_json;

// Limits on a JSON input file (docs/scenes.md, "Limits"): a file larger than
// this, or nested deeper, is refused before it is parsed any further.
constexpr std::size_t kMaxJsonFileBytes = std::size_t(16) << 20;  // 16 MiB
constexpr int kMaxJsonDepth = 64;  // objects and arrays inside each other
// A message is cut (in its middle, at a character boundary) to this length.
constexpr std::size_t kMaxMessageBytes = 1000;

// `s` as one line of valid UTF-8, at most `max_bytes` long: control characters
// and Unicode line breaks are escaped (\n, \t, \xNN, \u2028), bytes that are
// not UTF-8 become \xNN, and a long text keeps its head and tail around " ... ".
std::string one_line(const std::string& s, std::size_t max_bytes = kMaxMessageBytes);

// Bad input: the message is complete and meant for the user. It is stored as
// one_line(message): one line of valid UTF-8, whatever the file or key held.
struct InputError : std::runtime_error {
  explicit InputError(const std::string& message) : std::runtime_error(one_line(message)) {}
};

// ---- Numbers: one reader for scene files and flags (docs/scenes.md, "Numbers").

// What the text of a number is. The grammar is JSON's, the whole text and nothing
// else: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)? (no blanks, no "+" in front, no
// hex, no "inf" or "nan"). `value` is the double nearest the number the digits write
// (ties to even), for any number of digits and any exponent (std::from_chars); whether
// it is a whole number, and which, is decided from the digits exactly.
struct NumberText {
  bool valid = false;      // the whole text is one number in JSON's grammar
  double value = 0;        // correctly rounded; 0 when underflow, +-inf when overflow
  bool overflow = false;   // too large for a double (1e999)
  bool underflow = false;  // not 0, but reads as 0 (1e-400)
  bool nonzero = false;    // the digits are not all 0
  bool whole = false;      // exactly a whole number (5, 5.0, 1e3, -0)
  bool negative = false;   // a whole number below 0
  bool fits = false;       // a whole number whose magnitude fits 64 bits (below)
  std::uint64_t magnitude = 0;
};
NumberText read_number(const std::string& text);

// A whole number in [min, max] from `t` (a valid NumberText), or false.
bool whole_in(const NumberText& t, std::int64_t min, std::int64_t max, std::int64_t& out);

// Reads typed values from one JSON object at a known path in a known file.
//   JsonObject f(reader, doc["forces"][2], "forces[2]");
//   double k = f.number("k", {.min = 0});
struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;  // value must be > min rather than >= min
};

class JsonObject {
 public:
  JsonObject(std::string file, const json& j, std::string path);

  const json& raw() const { return j_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  bool has(const char* key) const { return j_.contains(key); }

  // Rejects keys outside `known`, naming the first unknown one and the known set.
  void only_keys(std::initializer_list<const char*> known) const;

  double number(const char* key, Range r = {}) const;
  double number_or(const char* key, double def, Range r = {}) const;
  Vec2 vec2(const char* key) const;
  Vec2 vec2_or(const char* key, const Vec2& def) const;
  std::string string(const char* key) const;
  std::string string_or(const char* key, const std::string& def) const;
  // A whole number in [min, max].
  std::int64_t integer(const char* key, std::int64_t min, std::int64_t max) const;
  std::int64_t integer_or(const char* key, std::int64_t def, std::int64_t min,
                          std::int64_t max) const;
  // Element i of the array at `key` as a whole number in [min, max] (same
  // rules as integer()); a message adds `note` after the range.
  std::int64_t integer_in(const char* key, std::size_t i, std::int64_t min, std::int64_t max,
                          const std::string& note = "") const;
  bool boolean_or(const char* key, bool def) const;
  // The object at `key` (which must be a JSON object).
  JsonObject object(const char* key) const;
  // The array at `key` (missing -> empty); element paths are key[i].
  const json& array_or_empty(const char* key) const;
  JsonObject element(const char* key, std::size_t i) const;

  [[noreturn]] void fail(const std::string& key, const json* value,
                         const std::string& expected) const;
  std::string key_path(const std::string& key) const;

 private:
  std::string file_;
  const json& j_;
  std::string path_;
};

// A short rendering of a JSON value for error messages: at most about 60
// bytes, whatever the value's size or depth (only what is shown is visited).
std::string describe(const json& value);

// Parses `text` as JSON, or throws InputError naming `file`, the JSON path
// where parsing stopped and what was expected: not JSON, a number that does
// not fit a double (1e999), a key given twice in one object, nesting deeper
// than kMaxJsonDepth.
json parse_json(const std::string& text, const std::string& file);

// Reads a regular file of at most kMaxJsonFileBytes and parses it as JSON
// (parse_json), or throws InputError naming the file.
json read_json_file(const std::string& file);

}  // namespace wb
