// The one number reader of scene files and flags (wb::read_number, docs/scenes.md
// "Numbers"), against a reference reading: glibc's strtod for the double (correctly
// rounded, a different implementation from std::from_chars'), and for whole numbers the
// number written out in full, digit by digit. The edges of issue 45 by name, then
// random texts of JSON's grammar.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>

#include "wb/input.h"

namespace {

// The reference whole-number reading: the number's digits written out with the point
// moved by the exponent (only for texts whose exponent and digits are short enough to
// write out), then "is every digit after the point 0" and the integer part's value.
struct Whole {
  bool whole = false, fits = false;
  std::uint64_t magnitude = 0;
};

Whole written_out(const std::string& text) {
  std::string mant = text, digits;
  long exp = 0;
  const auto e = mant.find_first_of("eE");
  if (e != std::string::npos) {
    exp = std::stol(mant.substr(e + 1));
    mant = mant.substr(0, e);
  }
  if (!mant.empty() && mant[0] == '-') mant = mant.substr(1);
  long point = long(mant.size());
  const auto dot = mant.find('.');
  if (dot != std::string::npos) {
    point = long(dot);
    mant.erase(dot, 1);
  }
  point += exp;  // digits before the point
  std::string integer, fraction;
  for (long k = 0; k < std::max(point, long(mant.size())); ++k) {
    const char c = k >= 0 && k < long(mant.size()) ? mant[std::size_t(k)] : '0';
    (k < point ? integer : fraction) += c;
  }
  for (long k = point; k < 0; ++k) fraction.insert(fraction.begin(), '0');
  Whole w;
  w.whole = fraction.find_first_not_of('0') == std::string::npos;
  const auto first = integer.find_first_not_of('0');
  const std::string sig = first == std::string::npos ? "0" : integer.substr(first);
  w.fits = w.whole && (sig.size() < 20 || (sig.size() == 20 && sig <= "18446744073709551615"));
  if (w.fits) w.magnitude = std::stoull(sig);
  return w;
}

void check_against_reference(const std::string& text) {
  CAPTURE(text);
  const wb::NumberText t = wb::read_number(text);
  REQUIRE(t.valid);
  const double ref = std::strtod(text.c_str(), nullptr);
  if (std::isinf(ref)) {
    CHECK(t.overflow);
  } else if (ref == 0 && t.nonzero) {
    CHECK(t.underflow);
  } else {
    CHECK(t.value == ref);
    CHECK(std::signbit(t.value) == std::signbit(ref));
  }
  const Whole w = written_out(text);
  CHECK(t.whole == w.whole);
  CHECK(t.fits == w.fits);
  if (w.fits) CHECK(t.magnitude == w.magnitude);
}

}  // namespace

TEST_CASE("read_number: JSON's grammar, the whole text", "[numbers]") {
  for (const char* ok : {"0", "-0", "1", "-12.5", "1e3", "1E+3", "1e-3", "0.0e0", "10.00"}) {
    CAPTURE(ok);
    CHECK(wb::read_number(ok).valid);
  }
  // Issue 45: hex, blanks before or after, "+", a bare point, leading zeros, words.
  for (const char* bad : {"", "0x1p-7", "0x10", " 0.01", "0.01 ", "\t1", "+1", ".5", "1.", "01",
                          "1e", "1e+", "--1", "inf", "nan", "1_000", "1,5", "\xef\xbc\x91"}) {
    CAPTURE(bad);
    CHECK_FALSE(wb::read_number(bad).valid);
  }
}

TEST_CASE("read_number: correctly rounded for any length of digits and any exponent",
          "[numbers]") {
  // 1 followed by 100 001 zeros, e-100002: 0.1 (an exponent cap of 10^5 read it as 10).
  const std::string long_one = "1" + std::string(100001, '0') + "e-100002";
  CHECK(wb::read_number(long_one).value == 0.1);
  CHECK_FALSE(wb::read_number(long_one).whole);
  // The exponent's own digits: any count, leading zeros included.
  CHECK(wb::read_number("1e-" + std::string(500, '0') + "1").value == 0.1);
  CHECK(wb::read_number("1e" + std::string(40, '9')).overflow);
  CHECK(wb::read_number("1e-" + std::string(40, '9')).underflow);
  CHECK_FALSE(wb::read_number("0e" + std::string(40, '9')).underflow);  // 0 is 0
  // The smallest double, and exactly half of it (ties to even: 0, refused as too small).
  const std::string half =
      "2.47032822920623272088284396434110686182529901307162382212792841250337753635104375932649"
      "9181808179961898982823477228588654633283551779698981993873980053909390631503565951557022"
      "6392290858392449105184435931802849936536152500319370457678249219365623669863658480757001"
      "5857692699037063119282795585513329278343384093519780155312465972635795746227664652728272"
      "2005637400648549997709659947045402082816622623785739345073633900796776193057750674017632"
      "4673600968951340535537458516661134223766678604162159680461914467291840300530057530849048"
      "7653917113865916462395249126236538818796362393732804238910186723484976682350898633885879"
      "2562830275599565752445550725518931369083625477918694866799496832404970582102851318545139"
      "6213837722826145437693412532098591327667236328125e-324";
  CHECK(wb::read_number(half).underflow);
  const std::string above_half = half.substr(0, half.size() - 5) + "1e-324";
  CHECK(wb::read_number(above_half).value == 4.9406564584124654e-324);
  CHECK(wb::read_number("1.7976931348623157e308").value == 1.7976931348623157e308);
  CHECK(wb::read_number("1.7976931348623159e308").overflow);  // past the halfway to 2^1024
  // 1000.0000000000000000001: the double 1000, not a whole number.
  const wb::NumberText t = wb::read_number("1000.0000000000000000001");
  CHECK(t.value == 1000.0);
  CHECK_FALSE(t.whole);
}

TEST_CASE("read_number: whole numbers from their digits, exactly", "[numbers]") {
  std::int64_t v = 0;
  CHECK(wb::whole_in(wb::read_number("9007199254740993.0"), 0, INT64_MAX, v));
  CHECK(v == 9007199254740993);  // 2^53 + 1: not its nearest double
  CHECK(wb::whole_in(wb::read_number("1e3"), 0, 1000, v));
  CHECK(v == 1000);
  CHECK(wb::whole_in(wb::read_number("-0.0e5"), 0, 0, v));
  CHECK(wb::whole_in(wb::read_number("-9223372036854775808"), INT64_MIN, 0, v));
  CHECK(v == INT64_MIN);
  CHECK_FALSE(wb::whole_in(wb::read_number("9223372036854775808"), 0, INT64_MAX, v));
  CHECK_FALSE(wb::whole_in(wb::read_number("1.5"), 0, 10, v));
  CHECK_FALSE(wb::whole_in(wb::read_number("1e-400"), 0, 10, v));
  CHECK(wb::whole_in(wb::read_number("1" + std::string(400, '0') + "e-400"), 0, 10, v));
  CHECK(v == 1);
  CHECK(wb::whole_in(wb::read_number("2e" + std::string(500, '0') + "1"), 0, 100, v));
  CHECK(v == 20);
}

TEST_CASE("read_number: random texts of JSON's grammar against the reference", "[numbers]") {
  std::mt19937_64 rng(45);
  const auto pick = [&](int n) { return int(rng() % std::uint64_t(n)); };
  const auto digits = [&](int n, bool lead) {
    std::string d;
    for (int k = 0; k < n; ++k) d += char('0' + (k == 0 && lead ? 1 + pick(9) : pick(10)));
    return d;
  };
  for (int trial = 0; trial < 20000; ++trial) {
    std::string text = pick(2) ? "-" : "";
    // Integer part: 0, or up to 40 digits; often ending in zeros (whole numbers).
    if (pick(5) == 0) {
      text += "0";
    } else {
      text += digits(1 + pick(pick(4) == 0 ? 40 : 20), true);
      if (pick(3) == 0) text += std::string(std::size_t(pick(6)), '0');
    }
    if (pick(2)) {
      std::string frac = digits(1 + pick(25), false);
      if (pick(3) == 0) frac = std::string(std::size_t(1 + pick(5)), '0');
      text += "." + frac;
    }
    if (pick(2)) {
      text += pick(2) ? "e" : "E";
      const int s = pick(3);
      if (s == 1) text += "+";
      if (s == 2) text += "-";
      text += std::to_string(pick(pick(3) == 0 ? 340 : 25));
    }
    check_against_reference(text);
  }
}
