// Tests of the basic value conversions (user guide 4.3) and Error::str().
#include <catch2/catch.hpp>

#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "simbob/error.h"
#include "simbob/values.h"

using namespace simbob;

namespace {

const double kInf = std::numeric_limits<double>::infinity();

// The cuboid model's SideMask table from the brief, aliases listed after the canonical key.
const EnumTable kSideMask{"SideMask",
                          {{"Left", 1},
                           {"MinX", 1},
                           {"Right", 2},
                           {"MaxX", 2},
                           {"Bottom", 4},
                           {"MinY", 4},
                           {"Top", 8},
                           {"MaxY", 8},
                           {"Back", 16},
                           {"MinZ", 16},
                           {"Front", 32},
                           {"MaxZ", 32},
                           {"X", 3},
                           {"Y", 12},
                           {"Z", 48},
                           {"All", 63}}};

const EnumTable kDriveMode{"DriveMode", {{"Velocity", 0}, {"Vel", 0}, {"Position", 1}, {"Torque", 2}}};

uint64_t bitsOf(double d) {
  uint64_t u = 0;
  std::memcpy(&u, &d, sizeof u);
  return u;
}

Value parseOk(ValueType t, std::string_view text, const EnumTable* table = nullptr, ParseOptions opts = {}) {
  ParseResult r = parseValue(t, text, table, opts);
  INFO("parsing '" << std::string(text) << "' as " << valueTypeName(t) << ": " << r.error);
  REQUIRE(r);
  CHECK(r.error.empty());
  return *r.value;
}

std::string parseErr(ValueType t, std::string_view text, const EnumTable* table = nullptr, ParseOptions opts = {}) {
  ParseResult r = parseValue(t, text, table, opts);
  INFO("parsing '" << std::string(text) << "' as " << valueTypeName(t));
  REQUIRE_FALSE(r);
  REQUIRE_FALSE(r.error.empty());
  return r.error;
}

template <class T>
T parseAs(ValueType t, std::string_view text, const EnumTable* table = nullptr, ParseOptions opts = {}) {
  Value v = parseOk(t, text, table, opts);
  REQUIRE(std::holds_alternative<T>(v));
  return std::get<T>(v);
}

// parse(write(v)) must give v back bit for bit (checked through the doubles' bits).
template <class T>
void checkRoundTrip(ValueType t, const T& value, const EnumTable* table = nullptr) {
  const std::string text = formatValue(t, Value{value}, table);
  INFO("written as '" << text << "'");
  const T back = parseAs<T>(t, text, table, ParseOptions{true});
  CHECK(back == value);
}

template <size_t N>
bool sameBits(const std::array<double, N>& a, const std::array<double, N>& b) {
  for (size_t i = 0; i < N; ++i) {
    if (bitsOf(a[i]) != bitsOf(b[i])) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("valueTypeName names every type", "[values]") {
  CHECK(std::string(valueTypeName(ValueType::Bool)) == "Bool");
  CHECK(std::string(valueTypeName(ValueType::Int)) == "Int");
  CHECK(std::string(valueTypeName(ValueType::Number)) == "Number");
  CHECK(std::string(valueTypeName(ValueType::String)) == "String");
  CHECK(std::string(valueTypeName(ValueType::Triple)) == "Triple");
  CHECK(std::string(valueTypeName(ValueType::Vector)) == "Vector");
  CHECK(std::string(valueTypeName(ValueType::Quaternion)) == "Quaternion");
  CHECK(std::string(valueTypeName(ValueType::Pose)) == "Pose");
  CHECK(std::string(valueTypeName(ValueType::Matrix)) == "Matrix");
  CHECK(std::string(valueTypeName(ValueType::Cuboid)) == "Cuboid");
  CHECK(std::string(valueTypeName(ValueType::Color)) == "Color");
  CHECK(std::string(valueTypeName(ValueType::Enum)) == "Enum");
  CHECK(std::string(valueTypeName(ValueType::Bitmask)) == "Bitmask");
}

TEST_CASE("equalsIgnoreCase is ASCII case-insensitive", "[values]") {
  CHECK(equalsIgnoreCase("True", "tRUE"));
  CHECK(equalsIgnoreCase("", ""));
  CHECK_FALSE(equalsIgnoreCase("True", "Tru"));
  CHECK_FALSE(equalsIgnoreCase("a", "b"));
}

TEST_CASE("Bool parses every documented spelling", "[values][bool]") {
  for (const char* s : {"True", "true", "TRUE", "1", "On", "on", "Enable", "ENABLE", "  true\t"}) {
    CHECK(parseAs<bool>(ValueType::Bool, s) == true);
  }
  for (const char* s : {"False", "false", "0", "Off", "OFF", "Disable", "disable", "\t0 "}) {
    CHECK(parseAs<bool>(ValueType::Bool, s) == false);
  }
}

TEST_CASE("Bool writes True/False and rejects other text", "[values][bool]") {
  CHECK(formatValue(ValueType::Bool, Value{true}) == "True");
  CHECK(formatValue(ValueType::Bool, Value{false}) == "False");
  CHECK(parseErr(ValueType::Bool, "maybe") == "expected a boolean (True/False/1/0/On/Off/Enable/Disable), got 'maybe'");
  CHECK(parseErr(ValueType::Bool, "") == "expected a boolean (True/False/1/0/On/Off/Enable/Disable), got ''");
  parseErr(ValueType::Bool, "2");
  parseErr(ValueType::Bool, "yes");
  parseErr(ValueType::Bool, "Tru e");
  checkRoundTrip(ValueType::Bool, true);
  checkRoundTrip(ValueType::Bool, false);
}

TEST_CASE("parseNumber accepts the documented forms", "[values][number]") {
  CHECK(parseNumber("0") == 0.0);
  CHECK(parseNumber("42") == 42.0);
  CHECK(parseNumber("+42") == 42.0);
  CHECK(parseNumber("-42") == -42.0);
  CHECK(parseNumber(".5") == 0.5);
  CHECK(parseNumber("-.5") == -0.5);
  CHECK(parseNumber("+.5") == 0.5);
  CHECK(parseNumber("1.") == 1.0);
  CHECK(parseNumber("1.5e3") == 1500.0);
  CHECK(parseNumber("1.5E3") == 1500.0);
  CHECK(parseNumber("1e-3") == 0.001);
  CHECK(parseNumber("1e+3") == 1000.0);
  CHECK(parseNumber("0.1") == 0.1);
  CHECK(parseNumber("  3.25\t") == 3.25);
  CHECK(parseNumber("007") == 7.0);
  CHECK(parseNumber("1.7976931348623157e308") == std::numeric_limits<double>::max());
  CHECK(parseNumber("5e-324") == std::numeric_limits<double>::denorm_min());
  auto neg_zero = parseNumber("-0");
  REQUIRE(neg_zero);
  CHECK(bitsOf(*neg_zero) == bitsOf(-0.0));
}

TEST_CASE("parseNumber rejects everything else", "[values][number]") {
  for (const char* s : {"",    " ",   "nan", "NaN", "-nan", "inf",   "-inf", "infinity", "Infinite", "0x10",
                        "1e",  "1e+", "e5",  ".",   "-",    "+",     "+-1",  "-+1",      "--1",      "1.5.2",
                        "1 2", "1,5", "abc", "1x",  "x1",   "1_000", "\n1",  "1\n",      "(1)",      "1f"}) {
    INFO("text '" << s << "'");
    CHECK_FALSE(parseNumber(s).has_value());
  }
  // from_chars reports both overflow and underflow to zero as out of range.
  CHECK_FALSE(parseNumber("1e309").has_value());
  CHECK_FALSE(parseNumber("-1e309").has_value());
  CHECK_FALSE(parseNumber("1.7976931348623159e308").has_value());
  CHECK_FALSE(parseNumber("1e-400").has_value());
}

TEST_CASE("Infinite is accepted only when allowed", "[values][number]") {
  CHECK(parseNumber("Infinite", true) == kInf);
  CHECK(parseNumber("+infinite", true) == kInf);
  CHECK(parseNumber(" -INFINITE ", true) == -kInf);
  CHECK_FALSE(parseNumber("Infinite", false).has_value());
  CHECK_FALSE(parseNumber("inf", true).has_value());
  CHECK_FALSE(parseNumber("Infinity", true).has_value());
  CHECK_FALSE(parseNumber("nan", true).has_value());
  CHECK(std::get<double>(parseOk(ValueType::Number, "-Infinite", nullptr, {true})) == -kInf);
  CHECK(parseErr(ValueType::Number, "Infinite") == "infinite value not allowed here: 'Infinite'");
}

TEST_CASE("Number parse errors say what is wrong", "[values][number]") {
  CHECK(parseErr(ValueType::Number, "abc") == "expected a number, got 'abc'");
  CHECK(parseErr(ValueType::Number, " 1x ") == "expected a number, got '1x'");
  CHECK(parseErr(ValueType::Number, "") == "expected a number, got ''");
  CHECK(parseErr(ValueType::Number, "inf") == "expected a number, got 'inf'");
  CHECK(parseErr(ValueType::Number, "0x1p3") == "expected a number, got '0x1p3'");
  CHECK(parseErr(ValueType::Number, "NaN") == "NaN is not allowed: 'NaN'");
  CHECK(parseErr(ValueType::Number, "-nan", nullptr, {true}) == "NaN is not allowed: '-nan'");
  CHECK(parseErr(ValueType::Number, "1e999") == "number out of range: '1e999'");
  CHECK(parseErr(ValueType::Number, "1e999", nullptr, {true}) == "number out of range: '1e999'");
}

TEST_CASE("formatApprox writes three significant digits like %.3g", "[values][number]") {
  CHECK(formatApprox(0.0) == "0");
  CHECK(formatApprox(1.0) == "1");
  CHECK(formatApprox(100.0) == "100");
  CHECK(formatApprox(1234.5) == "1.23e+03");
  CHECK(formatApprox(0.0012345) == "0.00123");
  CHECK(formatApprox(-2.0 / 3.0) == "-0.667");
  CHECK(formatApprox(1e-7) == "1e-07");
  CHECK(formatApprox(9.996) == "10");
  CHECK(formatApprox(kInf) == "inf");
}

TEST_CASE("numbers people read never show -0; the CSV writer keeps it", "[values][number]") {
  CHECK(formatReadable(-0.0) == "0");
  CHECK(formatReadable(0.0) == "0");
  CHECK(formatReadable(-0.5) == "-0.5");
  CHECK(formatApprox(-0.0) == "0");
  // formatNumber writes values back to scene files: it round-trips the sign bit.
  CHECK(formatNumber(-0.0) == "-0");
  CHECK(formatApprox(-1e-300 * 1e-300) == "0");  // underflows to -0
  // The trajectory CSVs' bytes are fixed (golden files hold "-0").
  std::string csv;
  appendNumber(csv, -0.0);
  CHECK(csv == "-0");
}

TEST_CASE("countOf says 1 body, 2 bodies", "[values]") {
  CHECK(countOf(0, "body", "bodies") == "0 bodies");
  CHECK(countOf(1, "body", "bodies") == "1 body");
  CHECK(countOf(2, "worker", "workers") == "2 workers");
}

TEST_CASE("editDistance and didYouMean: one rule for every suggestion", "[values][suggest]") {
  CHECK(editDistance("", "") == 0);
  CHECK(editDistance("abc", "") == 3);
  CHECK(editDistance("Hinge", "hinge") == 0);  // ASCII case does not count
  CHECK(editDistance("kitten", "sitting") == 3);
  CHECK(editDistance("POSITOIN", "Position") == 1);  // a swap of neighbours is one edit
  CHECK(editDistance("ab", "ba") == 1);
  CHECK(editDistance("abc", "ca") == 3);  // restricted: no edits inside a swapped pair
  // Within 2 edits for short words, |word| / 3 for long ones (body keys, type names).
  CHECK(didYouMean("Pendulm.Hinge.Bob", {"Pendulum.Hinge.Bob"}) == "Pendulum.Hinge.Bob");
  CHECK(didYouMean("Pendlm.Hing.Bob", {"Pendulum.Hinge.Bob"}) == "Pendulum.Hinge.Bob");  // 3 edits, limit 5
  CHECK(didYouMean("Pndlm.Hng.Bob", {"Pendulum.Hinge.Bob"}) == "");                      // 5 edits, limit 4
  CHECK(didYouMean("Hnge", {"Hinge"}) == "Hinge");
  CHECK(didYouMean("Hi", {"Hinge"}) == "");
  // Never "corrects" a text into a short candidate it shares nothing with.
  CHECK(didYouMean("xy", {"ab"}) == "");
  CHECK(didYouMean("7", {"Vel"}) == "");
  CHECK(didYouMean("", {"a", "ab"}) == "");
  // The nearest wins; ties go to the first.
  CHECK(didYouMean("Bx", {"Ba", "Bb", "B"}) == "Ba");
  CHECK(didYouMean("Radius", {"RadiusX", "Radius"}) == "Radius");
}

TEST_CASE("formatNumber writes the shortest round-trip form", "[values][number]") {
  CHECK(formatNumber(0.0) == "0");
  CHECK(formatNumber(-0.0) == "-0");
  CHECK(formatNumber(1.0) == "1");
  CHECK(formatNumber(-2.5) == "-2.5");
  CHECK(formatNumber(0.1) == "0.1");
  CHECK(formatNumber(0.1 + 0.2) == "0.30000000000000004");
  CHECK(formatNumber(1e300) == "1e+300");
  CHECK(formatNumber(1e-7) == "1e-07");
  CHECK(formatNumber(123456789012.0) == "123456789012");
  CHECK(formatNumber(std::numeric_limits<double>::max()) == "1.7976931348623157e+308");
  CHECK(formatNumber(std::numeric_limits<double>::denorm_min()) == "5e-324");
  CHECK(formatNumber(kInf) == "Infinite");
  CHECK(formatNumber(-kInf) == "-Infinite");
  CHECK(formatNumber(std::numeric_limits<double>::quiet_NaN()) == "NaN");
}

TEST_CASE("appendNumber appends to existing text", "[values][number]") {
  std::string s = "x=";
  appendNumber(s, 0.25);
  s += ' ';
  appendNumber(s, -kInf);
  s += ' ';
  appendNumber(s, -2.2250738585072014e-308);
  CHECK(s == "x=0.25 -Infinite -2.2250738585072014e-308");
}

TEST_CASE("random doubles round-trip bit for bit", "[values][number]") {
  std::mt19937_64 rng(0x5eedb0b);
  std::uniform_real_distribution<double> human(-1000.0, 1000.0);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    // Alternate raw bit patterns (all exponents, subnormals) with everyday magnitudes.
    double d = 0;
    if (i % 2 == 0) {
      const uint64_t bits = rng();
      std::memcpy(&d, &bits, sizeof d);
      if (!std::isfinite(d)) continue;
    } else {
      d = human(rng);
    }
    const std::string text = formatNumber(d);
    auto back = parseNumber(text);
    INFO("value written as " << text);
    REQUIRE(back.has_value());
    REQUIRE(bitsOf(*back) == bitsOf(d));
    ++checked;
  }
  CHECK(checked > 19900);
  for (double d : {kInf, -kInf}) {
    auto back = parseNumber(formatNumber(d), true);
    REQUIRE(back.has_value());
    CHECK(bitsOf(*back) == bitsOf(d));
  }
  for (double d : {0.0, -0.0, 5e-324, -5e-324, 2.2250738585072014e-308, 1.7976931348623157e308}) {
    const double back = parseAs<double>(ValueType::Number, formatValue(ValueType::Number, d));
    CHECK(bitsOf(back) == bitsOf(d));
  }
}

TEST_CASE("short decimals read as from_chars reads them, bit for bit", "[values][number]") {
  // Plain decimals of up to 15 digits take a quicker path than std::from_chars (one division
  // of exact doubles); both round correctly, so the bits must agree for every such text,
  // whatever the digits, the place of the '.' and the sign. Longer ones, exponents and a bare
  // '.' at either end go to from_chars itself and are checked here too.
  std::mt19937_64 rng(0xdec1a1);
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    const size_t digits = 1 + rng() % 17;  // 16 and 17 digits go to from_chars
    std::string text;
    if (rng() % 2) text += '-';
    for (size_t d = 0; d < digits; ++d) text += static_cast<char>('0' + rng() % 10);
    const size_t point = rng() % (digits + 2);  // digits + 1: no point
    if (point <= digits) text.insert(text.size() - digits + point, 1, '.');
    if (rng() % 16 == 0) text += "e" + std::to_string(static_cast<int>(rng() % 40) - 20);
    const std::string_view unsigned_text = std::string_view(text).substr(text[0] == '-' ? 1 : 0);
    double want = 0;
    const auto [end, ec] = std::from_chars(unsigned_text.data(), unsigned_text.data() + unsigned_text.size(), want);
    double got = 1;
    INFO("'" << text << "'");
    if (ec != std::errc() || end != unsigned_text.data() + unsigned_text.size()) {
      CHECK_FALSE(parseNumberValue(text, false, &got));
      continue;
    }
    REQUIRE(parseNumberValue(text, false, &got));
    REQUIRE(bitsOf(got) == bitsOf(text[0] == '-' ? -want : want));
    ++checked;
  }
  CHECK(checked > 150000);
  // Rounding cases: halfway and near-halfway fractions, the largest 15-digit integer, zeros.
  for (const char* text : {"0.1", "0.3", "0.7", "2.675", "1.005", "999999999999999", "0.000000000000001",
                           "123456789.012345", "0", "-0", "0.0", "00000.5"}) {
    double want = 0, got = 1;
    const std::string_view t(text[0] == '-' ? text + 1 : text);
    std::from_chars(t.data(), t.data() + t.size(), want);
    REQUIRE(parseNumberValue(text, false, &got));
    CHECK(bitsOf(got) == bitsOf(text[0] == '-' ? -want : want));
  }
}

TEST_CASE("Int parses integral numbers into int64", "[values][int]") {
  CHECK(parseAs<int64_t>(ValueType::Int, "42") == 42);
  CHECK(parseAs<int64_t>(ValueType::Int, "+7") == 7);
  CHECK(parseAs<int64_t>(ValueType::Int, "-0") == 0);
  CHECK(parseAs<int64_t>(ValueType::Int, "1e3") == 1000);
  CHECK(parseAs<int64_t>(ValueType::Int, "2.0") == 2);
  CHECK(parseAs<int64_t>(ValueType::Int, "9223372036854775807") == std::numeric_limits<int64_t>::max());
  CHECK(parseAs<int64_t>(ValueType::Int, "-9223372036854775808") == std::numeric_limits<int64_t>::min());
  // Integer literals are exact even beyond 2^53, where a double would round.
  CHECK(parseAs<int64_t>(ValueType::Int, "9007199254740993") == 9007199254740993LL);
  CHECK(formatValue(ValueType::Int, Value{int64_t{-12}}) == "-12");
  CHECK(formatValue(ValueType::Int, Value{int64_t{1000000000000}}) == "1000000000000");
  CHECK(formatValue(ValueType::Int, Value{std::numeric_limits<int64_t>::min()}) == "-9223372036854775808");
}

TEST_CASE("Int rejects fractions, junk and out-of-range values", "[values][int]") {
  CHECK(parseErr(ValueType::Int, "1.5") == "expected an integer, got '1.5'");
  CHECK(parseErr(ValueType::Int, "ten") == "expected an integer, got 'ten'");
  CHECK(parseErr(ValueType::Int, "+-5") == "expected an integer, got '+-5'");
  CHECK(parseErr(ValueType::Int, "9223372036854775808") == "integer out of range: '9223372036854775808'");
  CHECK(parseErr(ValueType::Int, "-1e19") == "integer out of range: '-1e19'");
  CHECK(parseErr(ValueType::Int, "1e999") == "number out of range: '1e999'");
  CHECK(parseErr(ValueType::Int, "nan") == "NaN is not allowed: 'nan'");
  CHECK(parseErr(ValueType::Int, "Infinite") == "infinite value not allowed here: 'Infinite'");
  parseErr(ValueType::Int, "Infinite", nullptr, {true});
}

TEST_CASE("Number and Int values start with a sign, a digit or '.' (guide 4.3)", "[values][number][int]") {
  // Before: the text was trimmed first, so " 7" (and "7 ") were accepted as 7. Guide 4.3: "The
  // first character needs to be a plus or minus sign, a digit or a '.'".
  CHECK(parseErr(ValueType::Number, " 7") ==
        "expected a number without blanks around it, got ' 7' (guide 4.3: a number starts with a sign, a digit or "
        "'.')");
  CHECK(parseErr(ValueType::Number, "7 ") ==
        "expected a number without blanks around it, got '7 ' (guide 4.3: a number starts with a sign, a digit or "
        "'.')");
  CHECK(parseErr(ValueType::Int, " -7 ") ==
        "expected an integer without blanks around it, got ' -7 ' (guide 4.3: a number starts with a sign, a digit "
        "or '.')");
  for (const char* s : {" 7", "\t7", "7\t", "  -1.5", "+2 ", " .5", " 1e3"}) {
    INFO("text '" << s << "'");
    parseErr(ValueType::Number, s);
    parseErr(ValueType::Int, s);
  }
  // Infinite drive limits too; a text that is no number at all keeps its plain message.
  parseErr(ValueType::Number, " Infinite", nullptr, {true});
  parseErr(ValueType::Number, "-Infinite\t", nullptr, {true});
  CHECK(parseAs<double>(ValueType::Number, "-Infinite", nullptr, {true}) == -kInf);
  CHECK(parseErr(ValueType::Number, " x") == "expected a number, got 'x'");
  CHECK(parseErr(ValueType::Int, " 1.5") == "expected an integer, got '1.5'");
  // What 4.3 allows.
  for (const char* s : {"7", "+7", "-7", ".5", "-.5", "+.5", "7.", "1e3", "1E+3"}) {
    INFO("text '" << s << "'");
    parseOk(ValueType::Number, s);
  }
  CHECK(parseAs<int64_t>(ValueType::Int, "-7") == -7);
  CHECK(parseAs<int64_t>(ValueType::Int, "+7") == 7);
  // Compound values are numerical value lists: separators (blanks among them) may stand
  // before, between and after the elements, and each element is a number as above.
  CHECK(parseAs<Triple>(ValueType::Triple, " 1 2 3 ") == Triple{1, 2, 3});
  CHECK(parseAs<Pose>(ValueType::Pose, "  (1, 2, 3) (0; 90; 0)  ").pos == std::array<double, 3>{1, 2, 3});
  CHECK(parseAs<Cuboid>(ValueType::Cuboid, "\t-1 -1 -1 1 1 1\t").b == std::array<double, 3>{1, 1, 1});
  for (const char* s : {"1 2\n3", "1 \r2 3", "1 2 3\v", "1 x2 3", "1 e2 3", "1 2 --3"}) {
    INFO("text '" << s << "'");
    parseErr(ValueType::Triple, s);
  }
}

TEST_CASE("random int64 values round-trip", "[values][int]") {
  std::mt19937_64 rng(42);
  for (int i = 0; i < 2000; ++i) {
    checkRoundTrip(ValueType::Int, static_cast<int64_t>(rng()));
  }
  checkRoundTrip(ValueType::Int, std::numeric_limits<int64_t>::min());
  checkRoundTrip(ValueType::Int, std::numeric_limits<int64_t>::max());
  checkRoundTrip(ValueType::Int, int64_t{0});
}

TEST_CASE("String escapes of 4.3", "[values][string]") {
  CHECK(unescapeString("a\\tb") == "a\tb");
  CHECK(unescapeString("a\\nb") == "a\nb");
  CHECK(unescapeString("a\\\\b") == "a\\b");
  CHECK(unescapeString("\\x\\\"") == "x\"");
  CHECK(unescapeString("\\T") == "T");
  CHECK(unescapeString("end\\") == "end\\");
  CHECK(unescapeString("") == "");
  CHECK(unescapeString("  spaces kept  ") == "  spaces kept  ");
  CHECK(escapeString("a\tb\nc\\d") == "a\\tb\\nc\\\\d");
  CHECK(escapeString("plain") == "plain");
  CHECK(escapeString("\\") == "\\\\");
  CHECK(std::get<std::string>(parseOk(ValueType::String, "C:\\\\dir\\tx")) == "C:\\dir\tx");
  CHECK(formatValue(ValueType::String, Value{std::string("a\\b\n")}) == "a\\\\b\\n");
  for (const char* s :
       {"", "x", "\\", "\\\\", "\t\n", "a\\tb", "end\\", " lead", "\\n literal", "mixed \\ \t \n stuff\\"}) {
    checkRoundTrip(ValueType::String, std::string(s));
  }
}

TEST_CASE("numerical value lists accept every separator", "[values][list]") {
  std::string err;
  auto l = parseNumberList(" ( 1, 2;3\\4\t(5) ) ,;", &err);
  REQUIRE(l);
  CHECK(*l == std::vector<double>{1, 2, 3, 4, 5});
  auto empty = parseNumberList(" ,;() ", &err);
  REQUIRE(empty);
  CHECK(empty->empty());
  auto exp = parseNumberList("1e-3,-2E+2", &err);
  REQUIRE(exp);
  CHECK(*exp == std::vector<double>{0.001, -200});
}

TEST_CASE("numerical value list errors name the bad element", "[values][list]") {
  std::string err;
  CHECK_FALSE(parseNumberList("1, 1x, 3", &err));
  CHECK(err == "'1x' is not a number");
  CHECK_FALSE(parseNumberList("(1 nan)", &err));
  CHECK(err == "NaN is not allowed: 'nan'");
  CHECK_FALSE(parseNumberList("1e400", &err));
  CHECK(err == "number out of range: '1e400'");
  CHECK_FALSE(parseNumberList("1 Infinite", &err));
  CHECK(err == "infinite value not allowed here: 'Infinite'");
  auto inf = parseNumberList("1 -Infinite", &err, true);
  REQUIRE(inf);
  CHECK(*inf == std::vector<double>{1, -kInf});
  CHECK_FALSE(parseNumberList("1 2 x", nullptr));  // a null error pointer is allowed
  CHECK(parseErr(ValueType::Triple, "(1, two, 3)") == "'two' is not a number");
}

TEST_CASE("Triple parsing fills missing trailing values with zero", "[values][triple]") {
  CHECK(parseAs<Triple>(ValueType::Triple, "0") == Triple{0, 0, 0});
  CHECK(parseAs<Triple>(ValueType::Triple, "(1, 2)") == Triple{1, 2, 0});
  CHECK(parseAs<Triple>(ValueType::Triple, "5") == Triple{5, 0, 0});
  CHECK(parseAs<Triple>(ValueType::Triple, "1 2 3") == Triple{1, 2, 3});
  CHECK(parseAs<Triple>(ValueType::Triple, "(1;2;3)") == Triple{1, 2, 3});
  CHECK(parseErr(ValueType::Triple, "") == "expected 1 to 3 numbers for a Triple, got 0");
  CHECK(parseErr(ValueType::Triple, "1 2 3 4") == "expected 1 to 3 numbers for a Triple, got 4");
}

TEST_CASE("Triple writing: '0', parentheses, dropped trailing zero", "[values][triple]") {
  auto w = [](Triple t) { return formatValue(ValueType::Triple, Value{t}); };
  CHECK(w({0, 0, 0}) == "0");
  CHECK(w({1, 2, 3}) == "(1, 2, 3)");
  CHECK(w({1, 2, 0}) == "(1, 2)");
  CHECK(w({1, 0, 0}) == "(1, 0)");  // only the last zero is dropped
  CHECK(w({0, 1, 0}) == "(0, 1)");
  CHECK(w({0, 0, 1}) == "(0, 0, 1)");
  CHECK(w({0.1, -2.5, 1e300}) == "(0.1, -2.5, 1e+300)");
  // -0 is kept so the sign survives the round trip.
  CHECK(w({-0.0, 0, 0}) == "(-0, 0)");
  CHECK(w({1, 2, -0.0}) == "(1, 2, -0)");
  for (Triple t : {Triple{0, 0, 0}, Triple{1, 0, 0}, Triple{0, 1, 0}, Triple{0, 0, 1}, Triple{-0.0, 0, 0},
                   Triple{0, -0.0, -0.0}, Triple{kInf, -kInf, 0}}) {
    const Triple back = parseAs<Triple>(ValueType::Triple, w(t), nullptr, ParseOptions{true});
    CHECK(sameBits(back, t));
  }
}

TEST_CASE("Vector parses 3 or 4 values and writes them normalised", "[values][vector]") {
  CHECK(parseAs<Vector4>(ValueType::Vector, "1 2 3") == Vector4{{1, 2, 3, 1}});
  // Parsing keeps the scale as written; only writing normalises.
  CHECK(parseAs<Vector4>(ValueType::Vector, "(2, 4, 6, 2)") == Vector4{{2, 4, 6, 2}});
  CHECK(parseErr(ValueType::Vector, "1 2") == "expected 3 or 4 numbers for a Vector, got 2");
  CHECK(parseErr(ValueType::Vector, "1 2 3 4 5") == "expected 3 or 4 numbers for a Vector, got 5");
  auto w = [](Vector4 v) { return formatValue(ValueType::Vector, Value{v}); };
  CHECK(w(Vector4{{1, 2, 3, 1}}) == "(1, 2, 3, 1)");
  CHECK(w(Vector4{{2, 4, 6, 2}}) == "(1, 2, 3, 1)");
  CHECK(w(Vector4{{1, 2, 3, 0}}) == "(1, 2, 3, 0)");
  CHECK(w(Vector4{{1, 2, 3, -0.0}}) == "(1, 2, 3, 0)");
  CHECK(w(Vector4{{1, 0, 0, -4}}) == "(-0.25, -0, -0, 1)");
}

TEST_CASE("Vector round-trip gives the normalised vector", "[values][vector]") {
  // Documented behaviour: parse(write(v)) == normalise(v), not v, whenever w is not 0 or 1.
  const Vector4 v{{2, 4, 6, 2}};
  const Vector4 back = parseAs<Vector4>(ValueType::Vector, formatValue(ValueType::Vector, v));
  CHECK(back == Vector4{{1, 2, 3, 1}});
  CHECK_FALSE(back == v);
  // Already normalised vectors and directions come back unchanged.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-100, 100);
  for (int i = 0; i < 500; ++i) {
    checkRoundTrip(ValueType::Vector, Vector4{{u(rng), u(rng), u(rng), 1}});
    checkRoundTrip(ValueType::Vector, Vector4{{u(rng), u(rng), u(rng), 0}});
  }
  // Writing the normalised form again changes nothing.
  const Vector4 odd{{1, 1, 1, 3}};
  const std::string once = formatValue(ValueType::Vector, odd);
  CHECK(formatValue(ValueType::Vector, parseAs<Vector4>(ValueType::Vector, once)) == once);
}

TEST_CASE("Quaternion needs exactly four non-degenerate values", "[values][quaternion]") {
  CHECK(parseAs<Quaternion>(ValueType::Quaternion, "(1, 0, 0, 0)") == Quaternion{{1, 0, 0, 0}});
  // Not normalised on parse.
  CHECK(parseAs<Quaternion>(ValueType::Quaternion, "2 0 0 0") == Quaternion{{2, 0, 0, 0}});
  CHECK(formatValue(ValueType::Quaternion, Quaternion{{0.5, -0.5, 0.25, 1e-9}}) == "(0.5, -0.5, 0.25, 1e-09)");
  CHECK(parseErr(ValueType::Quaternion, "1 0 0") == "expected 4 numbers for a Quaternion, got 3");
  CHECK(parseErr(ValueType::Quaternion, "1 0 0 0 0") == "expected 4 numbers for a Quaternion, got 5");
  CHECK(parseErr(ValueType::Quaternion, "(0, 0, 0, 0)") ==
        "a Quaternion must not be all zero (it describes no orientation)");
  CHECK(parseErr(ValueType::Quaternion, "0 -0 0 0") ==
        "a Quaternion must not be all zero (it describes no orientation)");
}

TEST_CASE("Pose is six numbers written space-separated", "[values][pose]") {
  const Pose p = parseAs<Pose>(ValueType::Pose, "(1, 2, 3, 90, -45, 0.5)");
  CHECK(p.pos == Triple{1, 2, 3});
  CHECK(p.euler_deg == Triple{90, -45, 0.5});
  CHECK(formatValue(ValueType::Pose, p) == "1 2 3 90 -45 0.5");
  CHECK(formatValue(ValueType::Pose, Pose{}) == "0 0 0 0 0 0");
  CHECK(parseErr(ValueType::Pose, "1 2 3 4 5") == "expected 6 numbers for a Pose, got 5");
  CHECK(parseErr(ValueType::Pose, "1 2 3 4 5 6 7") == "expected 6 numbers for a Pose, got 7");
}

TEST_CASE("Matrix parses the four documented forms", "[values][matrix]") {
  CHECK(parseAs<Matrix4>(ValueType::Matrix, "2 3 4") == Matrix4{{2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 0, 0, 0, 1}});
  CHECK(parseAs<Matrix4>(ValueType::Matrix, "1 2 3 4 5 6 7 8 9") ==
        Matrix4{{1, 2, 3, 0, 4, 5, 6, 0, 7, 8, 9, 0, 0, 0, 0, 1}});
  CHECK(parseAs<Matrix4>(ValueType::Matrix, "1 2 3 4 5 6 7 8 9 10 11 12") ==
        Matrix4{{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 0, 0, 0, 1}});
  CHECK(parseAs<Matrix4>(ValueType::Matrix, "1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16") ==
        Matrix4{{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16}});
  for (const char* s : {"", "1", "1 2", "1 2 3 4", "1 2 3 4 5 6 7 8", "1 2 3 4 5 6 7 8 9 10",
                        "1 2 3 4 5 6 7 8 9 10 11 12 13", "1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17"}) {
    INFO(s);
    const std::string err = parseErr(ValueType::Matrix, s);
    CHECK(err.rfind("matrix needs 3, 9, 12 or 16 numbers, got ", 0) == 0);
  }
  CHECK(parseErr(ValueType::Matrix, "1 2 3 4") == "matrix needs 3, 9, 12 or 16 numbers, got 4");
}

TEST_CASE("Matrix writes the shortest exact form", "[values][matrix]") {
  auto w = [](std::array<double, 16> m) { return formatValue(ValueType::Matrix, Matrix4{m}); };
  CHECK(w({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}) == "1 1 1");
  CHECK(w({2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 0, 0, 0, 1}) == "2 3 4");
  CHECK(w({1, 2, 3, 0, 4, 5, 6, 0, 7, 8, 9, 0, 0, 0, 0, 1}) == "1 2 3 4 5 6 7 8 9");
  CHECK(w({1, 0, 0, 0, 0, 1, 0, 0, 0, 0.5, 1, 0, 0, 0, 0, 1}) == "1 0 0 0 1 0 0 0.5 1");
  CHECK(w({1, 0, 0, 5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}) == "1 0 0 5 0 1 0 0 0 0 1 0");
  CHECK(w({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 0, 0, 0, 1}) == "1 2 3 4 5 6 7 8 9 10 11 12");
  CHECK(w({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 2}) == "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 2");
  CHECK(w({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1}) == "1 0 0 0 0 1 0 0 0 0 1 0 1 0 0 1");
  // -0 is not the implied +0, so it forces the longer form.
  CHECK(w({1, -0.0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}) == "1 -0 0 0 1 0 0 0 1");
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int i = 0; i < 200; ++i) {
    Matrix4 m;
    for (double& x : m.m) x = u(rng);
    checkRoundTrip(ValueType::Matrix, m);
    for (int k : {12, 13, 14}) m.m[k] = 0;
    m.m[15] = 1;
    checkRoundTrip(ValueType::Matrix, m);
    for (int k : {3, 7, 11}) m.m[k] = 0;
    checkRoundTrip(ValueType::Matrix, m);
    for (int k : {1, 2, 4, 6, 8, 9}) m.m[k] = 0;
    checkRoundTrip(ValueType::Matrix, m);
  }
}

TEST_CASE("Cuboid is two corners of six numbers", "[values][cuboid]") {
  const Cuboid c = parseAs<Cuboid>(ValueType::Cuboid, "(-1, -2, -3) (1, 2, 3.5)");
  CHECK(c.a == Triple{-1, -2, -3});
  CHECK(c.b == Triple{1, 2, 3.5});
  CHECK(formatValue(ValueType::Cuboid, c) == "-1 -2 -3 1 2 3.5");
  CHECK(parseErr(ValueType::Cuboid, "1 2 3") == "expected 6 numbers for a Cuboid, got 3");
  checkRoundTrip(ValueType::Cuboid, Cuboid{{0.1, 0.2, 0.3}, {-0.0, 1e-300, 7}});
}

TEST_CASE("Color: invalid, 3 or 4 components in [0, 1]", "[values][color]") {
  const Color invalid = parseAs<Color>(ValueType::Color, " INVALID ");
  CHECK_FALSE(invalid.valid);
  CHECK(formatValue(ValueType::Color, invalid) == "invalid");
  const Color rgb = parseAs<Color>(ValueType::Color, "1 0.5 0");
  CHECK(rgb.valid);
  CHECK(rgb.rgba == std::array<double, 4>{1, 0.5, 0, 1});
  const Color rgba = parseAs<Color>(ValueType::Color, "(0, 0.25, 1, 0)");
  CHECK(rgba.rgba == std::array<double, 4>{0, 0.25, 1, 0});
  CHECK(formatValue(ValueType::Color, rgb) == "1 0.5 0 1");
  CHECK(formatValue(ValueType::Color, rgba) == "0 0.25 1 0");
  CHECK(parseErr(ValueType::Color, "1 0.5 1.5") == "color component 1.5 is outside [0, 1]");
  CHECK(parseErr(ValueType::Color, "-0.1 0 0") == "color component -0.1 is outside [0, 1]");
  CHECK(parseErr(ValueType::Color, "1 1 1 Infinite", nullptr, {true}) == "color component Infinite is outside [0, 1]");
  CHECK(parseErr(ValueType::Color, "1 1") == "expected 3 or 4 numbers (or 'invalid') for a Color, got 2");
  CHECK(parseErr(ValueType::Color, "red") == "'red' is not a number");
  checkRoundTrip(ValueType::Color, Color{{0.1, 0.2, 0.3, 0.4}, true});
  checkRoundTrip(ValueType::Color, Color{{0, 0, 0, 1}, false});
}

TEST_CASE("Enum keys are case-insensitive; the first alias is written", "[values][enum]") {
  CHECK(parseAs<EnumValue>(ValueType::Enum, "Position", &kDriveMode).value == 1);
  CHECK(parseAs<EnumValue>(ValueType::Enum, " torque ", &kDriveMode).value == 2);
  CHECK(parseAs<EnumValue>(ValueType::Enum, "VEL", &kDriveMode).value == 0);
  CHECK(parseAs<EnumValue>(ValueType::Enum, "2", &kDriveMode).value == 2);
  CHECK(formatValue(ValueType::Enum, EnumValue{0}, &kDriveMode) == "Velocity");
  CHECK(formatValue(ValueType::Enum, EnumValue{2}, &kDriveMode) == "Torque");
  CHECK(formatValue(ValueType::Enum, EnumValue{7}, &kDriveMode) == "7");
  for (uint32_t v : {0u, 1u, 2u}) checkRoundTrip(ValueType::Enum, EnumValue{v}, &kDriveMode);
}

TEST_CASE("Enum errors list the keys and suggest a close one", "[values][enum]") {
  CHECK(parseErr(ValueType::Enum, "Torqe", &kDriveMode) ==
        "unknown DriveMode 'Torqe', did you mean 'Torque'? (valid: Velocity, Vel, Position, "
        "Torque)");
  CHECK(parseErr(ValueType::Enum, "POSITOIN", &kDriveMode) ==
        "unknown DriveMode 'POSITOIN', did you mean 'Position'? (valid: Velocity, Vel, "
        "Position, Torque)");
  CHECK(parseErr(ValueType::Enum, "Speed", &kDriveMode) ==
        "unknown DriveMode 'Speed' (valid: Velocity, Vel, Position, Torque)");
  CHECK(parseErr(ValueType::Enum, "", &kDriveMode) == "unknown DriveMode '' (valid: Velocity, Vel, Position, Torque)");
  // A number is accepted only if some key has that value.
  CHECK(parseErr(ValueType::Enum, "7", &kDriveMode) ==
        "unknown DriveMode '7' (valid: Velocity, Vel, Position, Torque)");
  CHECK(parseErr(ValueType::Enum, "Torque", nullptr) == "internal error: no key table for an Enum");
}

TEST_CASE("Bitmask parses keys, hex and decimal joined by '|'", "[values][bitmask]") {
  auto p = [](const char* s) { return parseAs<BitmaskValue>(ValueType::Bitmask, s, &kSideMask).bits; };
  CHECK(p("All") == 63);
  CHECK(p("left") == 1);
  CHECK(p("Left|Right") == 3);
  CHECK(p(" minx | MAXY |back ") == 1 + 8 + 16);
  CHECK(p("Left|0x40") == 65);
  CHECK(p("0X1F") == 31);
  CHECK(p("0xffffffff") == 0xffffffffu);
  CHECK(p("12") == 12);
  CHECK(p("0") == 0);
  CHECK(p("X|X|Left") == 3);
  CHECK(parseErr(ValueType::Bitmask, "Left||Right", &kSideMask) == "empty part in bitmask 'Left||Right'");
  CHECK(parseErr(ValueType::Bitmask, "Left|", &kSideMask) == "empty part in bitmask 'Left|'");
  CHECK(parseErr(ValueType::Bitmask, "", &kSideMask) == "expected a SideMask bitmask, got ''");
  CHECK(parseErr(ValueType::Bitmask, "0xg", &kSideMask) == "'0xg' is not a hexadecimal number");
  CHECK(parseErr(ValueType::Bitmask, "0x", &kSideMask) == "'0x' is not a hexadecimal number");
  CHECK(parseErr(ValueType::Bitmask, "0x100000000", &kSideMask) == "bitmask out of range (32 bits): '0x100000000'");
  CHECK(parseErr(ValueType::Bitmask, "4294967296", &kSideMask) == "bitmask out of range (32 bits): '4294967296'");
  CHECK(parseErr(ValueType::Bitmask, "Left|Rigth", &kSideMask) ==
        "unknown SideMask 'Rigth', did you mean 'Right'? (valid: Left, MinX, Right, MaxX, "
        "Bottom, MinY, Top, MaxY, Back, MinZ, Front, MaxZ, X, Y, Z, All)");
  // One letter away from the one-letter key 'X' is no evidence of a typo.
  CHECK(parseErr(ValueType::Bitmask, "Q", &kSideMask).find("did you mean") == std::string::npos);
}

TEST_CASE("Bitmask writes the minimal key combination plus a hex remainder", "[values][bitmask]") {
  auto w = [](uint32_t bits) { return formatValue(ValueType::Bitmask, BitmaskValue{bits}, &kSideMask); };
  CHECK(w(63) == "All");
  CHECK(w(3) == "X");
  CHECK(w(1) == "Left");
  CHECK(w(7) == "Bottom|X");  // keys are written in table order
  CHECK(w(15) == "X|Y");
  CHECK(w(1 + 4 + 16) == "Left|Bottom|Back");
  CHECK(w(2 + 12) == "Right|Y");
  CHECK(w(60) == "Y|Z");
  CHECK(w(62) == "Right|Y|Z");
  CHECK(w(64 | 1) == "Left|0x40");
  CHECK(w(64) == "0x40");
  CHECK(w(0xff) == "All|0xc0");
  CHECK(w(0) == "0");
  const EnumTable with_none{"Flags", {{"A", 1}, {"B", 2}, {"None", 0}, {"Nothing", 0}}};
  CHECK(formatValue(ValueType::Bitmask, BitmaskValue{0}, &with_none) == "None");
  CHECK(formatValue(ValueType::Bitmask, BitmaskValue{3}, &with_none) == "A|B");
  CHECK(formatValue(ValueType::Bitmask, BitmaskValue{0x13}, nullptr) == "0x13");
  // Fewest keys wins over single bits; among pairs A|BC precedes AB|C in table order.
  const EnumTable overlap{"O", {{"A", 1}, {"B", 2}, {"C", 4}, {"AB", 3}, {"BC", 6}}};
  CHECK(formatValue(ValueType::Bitmask, BitmaskValue{7}, &overlap) == "A|BC");
  CHECK(formatValue(ValueType::Bitmask, BitmaskValue{3}, &overlap) == "AB");
  for (uint32_t bits = 0; bits < 256; ++bits) {
    checkRoundTrip(ValueType::Bitmask, BitmaskValue{bits}, &kSideMask);
  }
  checkRoundTrip(ValueType::Bitmask, BitmaskValue{0xffffffffu}, &kSideMask);
}

TEST_CASE("Bitmask search stays correct on a large table", "[values][bitmask]") {
  EnumTable big{"Big", {}};
  static const char* names[] = {"b0",  "b1",  "b2",  "b3",  "b4",  "b5",  "b6",  "b7",  "b8",  "b9",  "b10", "b11",
                                "b12", "b13", "b14", "b15", "b16", "b17", "b18", "b19", "b20", "b21", "b22", "b23"};
  for (uint32_t i = 0; i < 24; ++i) big.keys.push_back({names[i], 1u << i});
  // 24 candidate keys exceed the exhaustive limit; the greedy fallback must still be exact.
  CHECK(formatValue(ValueType::Bitmask, BitmaskValue{0xffffff}, &big).find("0x") == std::string::npos);
  checkRoundTrip(ValueType::Bitmask, BitmaskValue{0xffffff}, &big);
  checkRoundTrip(ValueType::Bitmask, BitmaskValue{0xff00ffffu}, &big);
}

TEST_CASE("formatValue with the wrong alternative returns an empty string", "[values]") {
  CHECK(formatValue(ValueType::Bool, Value{1.0}) == "");
  CHECK(formatValue(ValueType::Number, Value{true}) == "");
  CHECK(formatValue(ValueType::Int, Value{2.0}) == "");
  CHECK(formatValue(ValueType::Triple, Value{Vector4{}}) == "");
  CHECK(formatValue(ValueType::Enum, Value{BitmaskValue{1}}, &kSideMask) == "");
  CHECK(formatValue(ValueType::Bitmask, Value{EnumValue{1}}, &kSideMask) == "");
  CHECK(formatValue(ValueType::String, Value{int64_t{3}}) == "");
}

TEST_CASE("random structured values round-trip", "[values]") {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  std::uniform_real_distribution<double> unit(0, 1);
  auto pick = [&]() {
    // Mix in zeros so the short Triple forms are exercised.
    const uint64_t r = rng() % 4;
    return r == 0 ? 0.0 : u(rng);
  };
  for (int i = 0; i < 1000; ++i) {
    checkRoundTrip(ValueType::Triple, Triple{pick(), pick(), pick()});
    checkRoundTrip(ValueType::Quaternion, Quaternion{{u(rng), pick(), pick(), pick()}});
    checkRoundTrip(ValueType::Pose, Pose{{pick(), pick(), pick()}, {pick(), pick(), pick()}});
    checkRoundTrip(ValueType::Cuboid, Cuboid{{pick(), pick(), pick()}, {pick(), pick(), pick()}});
    checkRoundTrip(ValueType::Color, Color{{unit(rng), unit(rng), unit(rng), unit(rng)}, true});
    checkRoundTrip(ValueType::Number, u(rng));
  }
}

TEST_CASE("Error::str formats file, line and message", "[error]") {
  Error e;
  e.message = "parameter 'mass': expected a number, got 'x'";
  CHECK(e.str() == "parameter 'mass': expected a number, got 'x'");
  e.loc.line = 7;
  CHECK(e.str() == "parameter 'mass': expected a number, got 'x'");
  e.loc.file = "scene.xml";
  CHECK(e.str() == "scene.xml:7: parameter 'mass': expected a number, got 'x'");
  e.loc.line = 0;
  CHECK(e.str() == "scene.xml: parameter 'mass': expected a number, got 'x'");
}

TEST_CASE("FileName: one interned name per text, the empty one as made by default", "[error]") {
  const FileName none, empty(""), empty_string{std::string()};
  CHECK(none == empty);
  CHECK(none == empty_string);
  CHECK(none.empty());
  CHECK(none.size() == 0);
  CHECK(none.str().empty());
  CHECK(std::string(none.c_str()).empty());
  CHECK(none == std::string());
  CHECK(none + "x" == "x");
  const FileName a("scene.xml"), b(std::string("scene.xml")), c("other.xml");
  CHECK(a == b);
  CHECK(&a.str() == &b.str());  // one interned string
  CHECK(a != c);
  CHECK(a != none);
  CHECK_FALSE(a.empty());
  CHECK(a.size() == 9);
  CHECK(a == "scene.xml");
  CHECK(std::string(a.c_str()) == "scene.xml");
  CHECK("dir/" + a == "dir/scene.xml");
}
