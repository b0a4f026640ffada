// String conversions of the basic scene value types (user guide 4.3).
#include "simbob/values.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <system_error>

namespace simbob {

namespace {

// Exhaustive bitmask search is 2^n; above this many candidate keys fall back to greedy.
constexpr size_t kMaxExhaustiveKeys = 20;

bool isBlank(char c) { return c == ' ' || c == '\t'; }

bool isDigit(char c) { return c >= '0' && c <= '9'; }

bool isHexDigit(char c) { return isDigit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'); }

// Separators of a numerical value list (guide 4.3): blank, tab, ',', ';', '\\', '(' and ')'.
// Asked of every character of every list value: a switch, not a search of a string of them.
bool isSeparator(char c) {
  switch (c) {
    case ' ':
    case '\t':
    case ',':
    case ';':
    case '\\':
    case '(':
    case ')':
      return true;
    default:
      return false;
  }
}

char lowerAscii(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && isBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
  return s;
}

bool allDigits(std::string_view s) { return !s.empty() && std::all_of(s.begin(), s.end(), isDigit); }

// Quote user text in messages so leading/trailing blanks and empty input stay visible.
std::string quoted(std::string_view s) {
  std::string out = "'";
  out.append(s.data(), s.size());
  out += '\'';
  return out;
}

// +0.0 only: -0.0 must be written explicitly so files round-trip bit for bit.
bool isPlusZero(double d) { return d == 0.0 && !std::signbit(d); }

bool isOne(double d) { return d == 1.0; }

enum class NumStatus { Ok, NotNumber, OutOfRange, InfiniteNotAllowed, NotANumberValue };

// "123" or "0.101": digits, at most one '.' with digits on both sides, no exponent. With at most
// 15 digits the integer m they make is below 2^53, so m and 10^k (k digits after the '.') are
// exact doubles and one IEEE division rounds m / 10^k correctly: the very double from_chars gives
// (it rounds correctly too), for a third of its instructions. Anything else returns false and
// goes to from_chars.
bool exactDecimal(std::string_view s, double* out) {
  constexpr size_t kMaxDigits = 15;  // 10^15 < 2^53
  static constexpr double kPow10[kMaxDigits + 1] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                                    1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  uint64_t m = 0;
  size_t i = 0, digits = 0, point = 0;
  bool seen_point = false;
  for (; i < s.size(); ++i) {
    const char c = s[i];
    if (isDigit(c)) {
      if (++digits > kMaxDigits) return false;
      m = m * 10 + static_cast<uint64_t>(c - '0');
    } else if (c == '.' && !seen_point && digits > 0) {
      seen_point = true;
      point = digits;
    } else {
      return false;
    }
  }
  if (digits == 0 || (seen_point && point == digits)) return false;
  const size_t k = seen_point ? digits - point : 0;
  *out = static_cast<double>(m) / kPow10[k];
  return true;
}

NumStatus parseNumberImpl(std::string_view text, bool allow_infinite, double& out) {
  std::string_view s = trim(text);
  bool negative = false;
  if (!s.empty() && (s.front() == '+' || s.front() == '-')) {
    negative = s.front() == '-';
    s.remove_prefix(1);
  }
  // Most numbers start with a digit: the words below need no look then.
  const bool word = !s.empty() && !isDigit(s.front()) && s.front() != '.';
  if (word && equalsIgnoreCase(s, "Infinite")) {
    if (!allow_infinite) return NumStatus::InfiniteNotAllowed;
    out = negative ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
    return NumStatus::Ok;
  }
  if (word && equalsIgnoreCase(s, "nan")) return NumStatus::NotANumberValue;
  // from_chars would also take "inf", "nan" and a second sign; the guide allows only digit or '.'.
  if (s.empty() || !(isDigit(s.front()) || s.front() == '.')) return NumStatus::NotNumber;
  double d = 0;
  if (exactDecimal(s, &d)) {
    out = negative ? -d : d;
    return NumStatus::Ok;
  }
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, d, std::chars_format::general);
  if (ec == std::errc::invalid_argument || ptr != end) return NumStatus::NotNumber;
  if (ec == std::errc::result_out_of_range || !std::isfinite(d)) return NumStatus::OutOfRange;
  if (ec != std::errc()) return NumStatus::NotNumber;
  out = negative ? -d : d;
  return NumStatus::Ok;
}

// Message for a bad number; `in_list` selects the wording that names a list element.
std::string numberError(NumStatus st, std::string_view text, bool in_list) {
  std::string_view s = trim(text);
  switch (st) {
    case NumStatus::OutOfRange:
      return "number out of range: " + quoted(s);
    case NumStatus::InfiniteNotAllowed:
      return "infinite value not allowed here: " + quoted(s);
    case NumStatus::NotANumberValue:
      return "NaN is not allowed: " + quoted(s);
    case NumStatus::NotNumber:
    case NumStatus::Ok:
      break;
  }
  return in_list ? quoted(s) + " is not a number" : "expected a number, got " + quoted(s);
}

// A Number or Int value whose text is fine but for blanks around it. Guide 4.3: "The first
// character needs to be a plus or minus sign, a digit or a '.'" (numerical value lists are
// different: separators, blanks among them, may stand before, between and after the elements).
std::string blanksError(const char* what, std::string_view text) {
  return std::string("expected ") + what + " without blanks around it, got " + quoted(text) +
         " (guide 4.3: a number starts with a sign, a digit or '.')";
}

const char* tableName(const EnumTable& table) { return table.name ? table.name : "key"; }

const EnumKey* findKey(const EnumTable& table, std::string_view s) {
  for (const EnumKey& k : table.keys) {
    if (k.name && equalsIgnoreCase(s, k.name)) return &k;
  }
  return nullptr;
}

// "unknown X 'y', did you mean 'z'? (valid: a, b, c)".
std::string unknownKeyError(const EnumTable& table, std::string_view s) {
  std::string msg = "unknown ";
  msg += tableName(table);
  msg += ' ';
  msg += quoted(s);
  std::vector<std::string> names;
  for (const EnumKey& k : table.keys)
    if (k.name) names.emplace_back(k.name);
  const std::string best = didYouMean(s, names);
  if (!best.empty()) msg += ", did you mean " + quoted(best) + "?";
  msg += " (valid: ";
  bool first = true;
  for (const EnumKey& k : table.keys) {
    if (!k.name) continue;
    if (!first) msg += ", ";
    msg += k.name;
    first = false;
  }
  msg += ')';
  return msg;
}

// Decimal or hex (without prefix) text to uint32; false on junk or overflow.
bool parseUint32(std::string_view s, int base, uint32_t& out) {
  if (s.empty()) return false;
  const char* end = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(s.data(), end, out, base);
  return ec == std::errc() && ptr == end;
}

std::string hexString(uint32_t v) {
  char buf[16];
  auto res = std::to_chars(buf, buf + sizeof buf, v, 16);
  return "0x" + std::string(buf, res.ptr);
}

std::string decimalString(uint64_t v) {
  char buf[24];
  auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

void appendList(std::string& out, const double* values, size_t n, const char* sep) {
  for (size_t i = 0; i < n; ++i) {
    if (i) out += sep;
    appendNumber(out, values[i]);
  }
}

std::string parenList(const double* values, size_t n) {
  std::string out = "(";
  appendList(out, values, n, ", ");
  out += ')';
  return out;
}

std::string spaceList(const double* values, size_t n) {
  std::string out;
  appendList(out, values, n, " ");
  return out;
}

ParseResult fail(std::string msg) { return ParseResult{std::nullopt, std::move(msg)}; }

ParseResult ok(Value v) { return ParseResult{std::move(v), {}}; }

std::string arityError(const char* expected, const char* type, size_t got) {
  return std::string("expected ") + expected + " numbers for a " + type + ", got " + decimalString(got);
}

ParseResult parseBool(std::string_view text) {
  std::string_view s = trim(text);
  for (const char* t : {"True", "1", "On", "Enable"}) {
    if (equalsIgnoreCase(s, t)) return ok(true);
  }
  for (const char* f : {"False", "0", "Off", "Disable"}) {
    if (equalsIgnoreCase(s, f)) return ok(false);
  }
  return fail("expected a boolean (True/False/1/0/On/Off/Enable/Disable), got " + quoted(s));
}

ParseResult parseInt(std::string_view text) {
  std::string_view s = trim(text);
  // Plain integer literals are read exactly so every int64 round-trips (doubles stop at 2^53).
  std::string_view digits = s;  // from_chars takes '-' but not '+'
  if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
  const bool has_sign = !s.empty() && (s.front() == '+' || s.front() == '-');
  if (allDigits(has_sign ? s.substr(1) : s)) {
    int64_t v = 0;
    const char* end = digits.data() + digits.size();
    auto [ptr, ec] = std::from_chars(digits.data(), end, v);
    if (ec == std::errc() && ptr == end) return ok(v);
  }
  double d = 0;
  NumStatus st = parseNumberImpl(s, false, d);
  if (st == NumStatus::NotNumber) return fail("expected an integer, got " + quoted(s));
  if (st != NumStatus::Ok) return fail(numberError(st, s, false));
  if (std::trunc(d) != d) return fail("expected an integer, got " + quoted(s));
  // int64 holds [-2^63, 2^63); both bounds are exact doubles.
  if (d < -9223372036854775808.0 || d >= 9223372036854775808.0) {
    return fail("integer out of range: " + quoted(s));
  }
  return ok(static_cast<int64_t>(d));
}

ParseResult parseEnum(std::string_view text, const EnumTable* table) {
  if (!table) return fail("internal error: no key table for an Enum");
  std::string_view s = trim(text);
  if (const EnumKey* k = findKey(*table, s)) return ok(EnumValue{k->value});
  uint32_t v = 0;
  if (allDigits(s) && parseUint32(s, 10, v)) {
    for (const EnumKey& k : table->keys) {
      if (k.value == v) return ok(EnumValue{v});
    }
  }
  return fail(unknownKeyError(*table, s));
}

ParseResult parseBitmask(std::string_view text, const EnumTable* table) {
  if (!table) return fail("internal error: no key table for a Bitmask");
  std::string_view all = trim(text);
  if (all.empty()) return fail(std::string("expected a ") + tableName(*table) + " bitmask, got ''");
  uint32_t bits = 0;
  std::string_view rest = all;
  while (true) {
    const size_t bar = rest.find('|');
    std::string_view part = trim(rest.substr(0, bar));
    if (part.empty()) return fail("empty part in bitmask " + quoted(all));
    if (const EnumKey* k = findKey(*table, part)) {
      bits |= k->value;
    } else if (part.size() >= 2 && part[0] == '0' && (part[1] == 'x' || part[1] == 'X')) {
      std::string_view hex = part.substr(2);
      uint32_t v = 0;
      if (hex.empty() || !std::all_of(hex.begin(), hex.end(), isHexDigit)) {
        return fail(quoted(part) + " is not a hexadecimal number");
      }
      if (!parseUint32(hex, 16, v)) return fail("bitmask out of range (32 bits): " + quoted(part));
      bits |= v;
    } else if (allDigits(part)) {
      uint32_t v = 0;
      if (!parseUint32(part, 10, v)) return fail("bitmask out of range (32 bits): " + quoted(part));
      bits |= v;
    } else {
      return fail(unknownKeyError(*table, part));
    }
    if (bar == std::string_view::npos) break;
    rest.remove_prefix(bar + 1);
  }
  return ok(BitmaskValue{bits});
}

int popCount(uint32_t v) {
  int n = 0;
  for (; v; v &= v - 1) ++n;
  return n;
}

// Lexicographically first (= table order) combination of exactly k candidates whose union is target.
bool findCombination(const std::vector<uint32_t>& values, size_t k, uint32_t target, std::vector<size_t>& picked,
                     size_t start, uint32_t acc) {
  if (picked.size() == k) return acc == target;
  for (size_t i = start; i + (k - picked.size()) <= values.size(); ++i) {
    picked.push_back(i);
    if (findCombination(values, k, target, picked, i + 1, acc | values[i])) return true;
    picked.pop_back();
  }
  return false;
}

std::string formatBitmask(uint32_t bits, const EnumTable* table) {
  if (!table) return bits == 0 ? "0" : hexString(bits);
  if (bits == 0) {
    for (const EnumKey& k : table->keys) {
      if (k.value == 0 && k.name) return k.name;
    }
    return "0";
  }
  // Candidates: canonical (first-listed) keys whose bits all lie inside the mask.
  std::vector<uint32_t> values;
  std::vector<const char*> names;
  uint32_t covered = 0;
  for (const EnumKey& k : table->keys) {
    if (!k.name || k.value == 0 || (k.value & ~bits) != 0) continue;
    if (std::find(values.begin(), values.end(), k.value) != values.end()) continue;
    values.push_back(k.value);
    names.push_back(k.name);
    covered |= k.value;
  }
  std::vector<size_t> chosen;
  if (covered != 0 && values.size() <= kMaxExhaustiveKeys) {
    for (size_t k = 1; k <= values.size(); ++k) {
      chosen.clear();
      if (findCombination(values, k, covered, chosen, 0, 0)) break;
    }
  } else if (covered != 0) {
    // Greedy fallback for oversized tables: most new bits first, table order on ties.
    uint32_t acc = 0;
    while (acc != covered) {
      size_t best = 0;
      int best_gain = -1;
      for (size_t i = 0; i < values.size(); ++i) {
        const int gain = popCount(values[i] & ~acc);
        if (gain > best_gain) {
          best = i;
          best_gain = gain;
        }
      }
      chosen.push_back(best);
      acc |= values[best];
    }
    std::sort(chosen.begin(), chosen.end());
  }
  std::string out;
  for (size_t i : chosen) {
    if (!out.empty()) out += '|';
    out += names[i];
  }
  const uint32_t remainder = bits & ~covered;
  if (remainder != 0) {
    if (!out.empty()) out += '|';
    out += hexString(remainder);
  }
  return out;
}

std::string formatEnum(uint32_t value, const EnumTable* table) {
  if (table) {
    for (const EnumKey& k : table->keys) {
      if (k.value == value && k.name) return k.name;
    }
  }
  return decimalString(value);
}

}  // namespace

const char* valueTypeName(ValueType t) {
  switch (t) {
    case ValueType::Bool:
      return "Bool";
    case ValueType::Int:
      return "Int";
    case ValueType::Number:
      return "Number";
    case ValueType::String:
      return "String";
    case ValueType::Triple:
      return "Triple";
    case ValueType::Vector:
      return "Vector";
    case ValueType::Quaternion:
      return "Quaternion";
    case ValueType::Pose:
      return "Pose";
    case ValueType::Matrix:
      return "Matrix";
    case ValueType::Cuboid:
      return "Cuboid";
    case ValueType::Color:
      return "Color";
    case ValueType::Enum:
      return "Enum";
    case ValueType::Bitmask:
      return "Bitmask";
  }
  return "Unknown";
}

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (lowerAscii(a[i]) != lowerAscii(b[i])) return false;
  }
  return true;
}

void appendNumber(std::string& out, double d) {
  if (std::isnan(d)) {
    out += "NaN";  // never parsed back; written only so a bug shows up readably
    return;
  }
  if (std::isinf(d)) {
    out += d < 0 ? "-Infinite" : "Infinite";
    return;
  }
  char buf[32];  // longest shortest-form double is 24 chars
  auto res = std::to_chars(buf, buf + sizeof buf, d);
  out.append(buf, res.ptr);
}

std::string formatNumber(double d) {
  std::string out;
  appendNumber(out, d);
  return out;
}

std::string formatReadable(double d) { return formatNumber(d == 0 ? 0.0 : d); }

std::string escapeXml(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char ch : s) {
    switch (ch) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += ch;
    }
  }
  return out;
}

std::string formatApprox(double d) {
  if (d == 0) d = 0.0;
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, d, std::chars_format::general, 3);
  return std::string(buf, res.ptr);
}

std::string countOf(size_t n, std::string_view one, std::string_view many) {
  return std::to_string(n) + " " + std::string(n == 1 ? one : many);
}

size_t editDistance(std::string_view a, std::string_view b) {
  // Three rows (i - 2, i - 1, i): memory stays O(|b|) however long a misspelt name in a file is.
  const size_t m = b.size();
  std::vector<size_t> before(m + 1), prev(m + 1), cur(m + 1);
  for (size_t j = 0; j <= m; ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= m; ++j) {
      const bool same = lowerAscii(a[i - 1]) == lowerAscii(b[j - 1]);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (same ? 0 : 1)});
      if (i > 1 && j > 1 && lowerAscii(a[i - 1]) == lowerAscii(b[j - 2]) &&
          lowerAscii(a[i - 2]) == lowerAscii(b[j - 1]))
        cur[j] = std::min(cur[j], before[j - 2] + 1);
    }
    std::swap(before, prev);
    std::swap(prev, cur);
  }
  return prev[m];
}

std::string didYouMean(std::string_view word, const std::vector<std::string>& candidates) {
  // Longer words tolerate more typos; a distance below the candidate's length keeps a text that
  // shares nothing with a short candidate from being "corrected" into it.
  const size_t limit = std::max<size_t>(2, word.size() / 3);
  const std::string* best = nullptr;
  size_t best_dist = limit + 1;
  for (const std::string& c : candidates) {
    const size_t d = editDistance(word, c);
    if (d < best_dist && d < c.size()) {
      best = &c;
      best_dist = d;
    }
  }
  return best ? *best : std::string();
}

std::optional<double> parseNumber(std::string_view text, bool allow_infinite) {
  double d = 0;
  if (parseNumberImpl(text, allow_infinite, d) != NumStatus::Ok) return std::nullopt;
  return d;
}

namespace {

// The elements of a numerical value list, in order, each checked as a number. The first
// `capacity` go to `out`; the count is of all of them (an arity message names it). False with
// the message of the first bad element. Every value type's list fits in 16 numbers: the scene's
// values are read without a heap allocation each.
bool scanNumberList(std::string_view text, bool allow_infinite, double* out, size_t capacity, size_t* count,
                    std::string* error) {
  size_t n = 0;
  size_t i = 0;
  while (i < text.size()) {
    if (isSeparator(text[i])) {
      ++i;
      continue;
    }
    size_t j = i;
    while (j < text.size() && !isSeparator(text[j])) ++j;
    std::string_view element = text.substr(i, j - i);
    double d = 0;
    NumStatus st = parseNumberImpl(element, allow_infinite, d);
    if (st != NumStatus::Ok) {
      if (error) *error = numberError(st, element, true);
      return false;
    }
    if (n < capacity) out[n] = d;
    ++n;
    i = j;
  }
  *count = n;
  return true;
}

}  // namespace

bool parseNumberValue(std::string_view text, bool allow_infinite, double* out) {
  if (text.empty() || isBlank(text.front()) || isBlank(text.back())) return false;
  double d = 0;
  if (parseNumberImpl(text, allow_infinite, d) != NumStatus::Ok) return false;
  *out = d;
  return true;
}

std::optional<std::vector<double>> parseNumberList(std::string_view text, std::string* error, bool allow_infinite) {
  size_t count = 0;
  if (!scanNumberList(text, allow_infinite, nullptr, 0, &count, error)) return std::nullopt;
  std::vector<double> out(count);
  scanNumberList(text, allow_infinite, out.data(), count, &count, nullptr);
  return out;
}

std::string unescapeString(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c != '\\' || i + 1 == text.size()) {
      out += c;  // a trailing lone backslash has nothing to escape and is kept
      continue;
    }
    const char next = text[++i];
    out += next == 't' ? '\t' : next == 'n' ? '\n' : next;
  }
  return out;
}

std::string escapeString(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '\t') {
      out += "\\t";
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\\') {
      out += "\\\\";
    } else {
      out += c;
    }
  }
  return out;
}

ParseResult parseValue(ValueType t, std::string_view text, const EnumTable* table, ParseOptions opts) {
  const bool inf = opts.allow_infinite;
  switch (t) {
    case ValueType::Bool:
      return parseBool(text);
    case ValueType::Int: {
      ParseResult r = parseInt(text);
      if (r && trim(text).size() != text.size()) return fail(blanksError("an integer", text));
      return r;
    }
    case ValueType::Number: {
      double d = 0;
      if (parseNumberValue(text, inf, &d)) return ok(d);
      NumStatus st = parseNumberImpl(text, inf, d);
      if (st != NumStatus::Ok) return fail(numberError(st, text, false));
      return fail(blanksError("a number", text));
    }
    case ValueType::String:
      return ok(unescapeString(text));
    case ValueType::Enum:
      return parseEnum(text, table);
    case ValueType::Bitmask:
      return parseBitmask(text, table);
    case ValueType::Color:
      if (equalsIgnoreCase(trim(text), "invalid")) {
        Color c;
        c.valid = false;
        return ok(c);
      }
      break;
    case ValueType::Triple:
    case ValueType::Vector:
    case ValueType::Quaternion:
    case ValueType::Pose:
    case ValueType::Matrix:
    case ValueType::Cuboid:
      break;
  }

  // Everything below is a numerical value list with a type-specific arity.
  constexpr size_t kMaxListNumbers = 16;  // a Matrix's; more is an arity error for every type
  std::array<double, kMaxListNumbers> n{};
  size_t count = 0;
  {
    std::string error;
    if (!scanNumberList(text, inf, n.data(), n.size(), &count, &error)) return fail(error);
  }

  switch (t) {
    case ValueType::Triple: {
      if (count < 1 || count > 3) return fail(arityError("1 to 3", "Triple", count));
      Triple v{0, 0, 0};
      std::copy(n.begin(), n.begin() + count, v.begin());
      return ok(v);
    }
    case ValueType::Vector: {
      if (count != 3 && count != 4) return fail(arityError("3 or 4", "Vector", count));
      Vector4 v;
      std::copy(n.begin(), n.begin() + count, v.v.begin());
      return ok(v);
    }
    case ValueType::Quaternion: {
      if (count != 4) return fail(arityError("4", "Quaternion", count));
      if (n[0] == 0 && n[1] == 0 && n[2] == 0 && n[3] == 0) {
        return fail("a Quaternion must not be all zero (it describes no orientation)");
      }
      Quaternion q;
      std::copy(n.begin(), n.begin() + count, q.q.begin());
      return ok(q);
    }
    case ValueType::Pose: {
      if (count != 6) return fail(arityError("6", "Pose", count));
      Pose p;
      std::copy(n.begin(), n.begin() + 3, p.pos.begin());
      std::copy(n.begin() + 3, n.begin() + count, p.euler_deg.begin());
      return ok(p);
    }
    case ValueType::Matrix: {
      Matrix4 m;  // identity; the short forms only overwrite part of it
      if (count == 3) {
        m.m[0] = n[0];
        m.m[5] = n[1];
        m.m[10] = n[2];
      } else if (count == 9) {
        for (size_t r = 0; r < 3; ++r) {
          for (size_t c = 0; c < 3; ++c) m.m[r * 4 + c] = n[r * 3 + c];
        }
      } else if (count == 12 || count == 16) {
        std::copy(n.begin(), n.begin() + count, m.m.begin());
      } else {
        return fail("matrix needs 3, 9, 12 or 16 numbers, got " + decimalString(count));
      }
      return ok(m);
    }
    case ValueType::Cuboid: {
      if (count != 6) return fail(arityError("6", "Cuboid", count));
      Cuboid c;
      std::copy(n.begin(), n.begin() + 3, c.a.begin());
      std::copy(n.begin() + 3, n.begin() + count, c.b.begin());
      return ok(c);
    }
    case ValueType::Color: {
      if (count != 3 && count != 4) {
        return fail("expected 3 or 4 numbers (or 'invalid') for a Color, got " + decimalString(count));
      }
      Color c;
      std::copy(n.begin(), n.begin() + count, c.rgba.begin());
      for (double x : c.rgba) {
        if (!(x >= 0.0 && x <= 1.0)) {
          return fail("color component " + formatNumber(x) + " is outside [0, 1]");
        }
      }
      return ok(c);
    }
    case ValueType::Bool:
    case ValueType::Int:
    case ValueType::Number:
    case ValueType::String:
    case ValueType::Enum:
    case ValueType::Bitmask:
      break;
  }
  return fail("internal error: unknown value type");
}

std::string formatValue(ValueType t, const Value& v, const EnumTable* table) {
  switch (t) {
    case ValueType::Bool:
      if (auto* b = std::get_if<bool>(&v)) return *b ? "True" : "False";
      break;
    case ValueType::Int:
      if (auto* i = std::get_if<int64_t>(&v)) {
        char buf[24];
        auto res = std::to_chars(buf, buf + sizeof buf, *i);
        return std::string(buf, res.ptr);
      }
      break;
    case ValueType::Number:
      if (auto* d = std::get_if<double>(&v)) return formatNumber(*d);
      break;
    case ValueType::String:
      if (auto* s = std::get_if<std::string>(&v)) return escapeString(*s);
      break;
    case ValueType::Triple:
      if (auto* tr = std::get_if<Triple>(&v)) {
        const Triple& x = *tr;
        if (isPlusZero(x[0]) && isPlusZero(x[1]) && isPlusZero(x[2])) return "0";
        return parenList(x.data(), isPlusZero(x[2]) ? 2 : 3);
      }
      break;
    case ValueType::Vector:
      if (auto* vec = std::get_if<Vector4>(&v)) {
        const auto& e = vec->v;
        if (e[3] == 0) {
          const double out[4] = {e[0], e[1], e[2], 0.0};  // -0 scale is still "a direction"
          return parenList(out, 4);
        }
        const double out[4] = {e[0] / e[3], e[1] / e[3], e[2] / e[3], 1.0};
        // Normalising can overflow (1e300 / 1e-300) or give NaN (inf / inf): such a text
        // would not read back, so write the four elements as they are.
        for (int i = 0; i < 3; ++i) {
          if (std::isnan(out[i]) || (std::isinf(out[i]) && !std::isinf(e[i]))) return parenList(e.data(), 4);
        }
        return parenList(out, 4);
      }
      break;
    case ValueType::Quaternion:
      if (auto* q = std::get_if<Quaternion>(&v)) return parenList(q->q.data(), 4);
      break;
    case ValueType::Pose:
      if (auto* p = std::get_if<Pose>(&v)) {
        const double out[6] = {p->pos[0], p->pos[1], p->pos[2], p->euler_deg[0], p->euler_deg[1], p->euler_deg[2]};
        return spaceList(out, 6);
      }
      break;
    case ValueType::Matrix:
      if (auto* mat = std::get_if<Matrix4>(&v)) {
        const auto& m = mat->m;
        const bool last_row = isPlusZero(m[12]) && isPlusZero(m[13]) && isPlusZero(m[14]) && isOne(m[15]);
        const bool last_col = isPlusZero(m[3]) && isPlusZero(m[7]) && isPlusZero(m[11]);
        const bool diagonal = isPlusZero(m[1]) && isPlusZero(m[2]) && isPlusZero(m[4]) && isPlusZero(m[6]) &&
                              isPlusZero(m[8]) && isPlusZero(m[9]);
        if (last_row && last_col && diagonal) {
          const double out[3] = {m[0], m[5], m[10]};
          return spaceList(out, 3);
        }
        if (last_row && last_col) {
          const double out[9] = {m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]};
          return spaceList(out, 9);
        }
        return spaceList(m.data(), last_row ? 12 : 16);
      }
      break;
    case ValueType::Cuboid:
      if (auto* c = std::get_if<Cuboid>(&v)) {
        const double out[6] = {c->a[0], c->a[1], c->a[2], c->b[0], c->b[1], c->b[2]};
        return spaceList(out, 6);
      }
      break;
    case ValueType::Color:
      if (auto* c = std::get_if<Color>(&v)) {
        if (!c->valid) return "invalid";
        return spaceList(c->rgba.data(), 4);
      }
      break;
    case ValueType::Enum:
      if (auto* e = std::get_if<EnumValue>(&v)) return formatEnum(e->value, table);
      break;
    case ValueType::Bitmask:
      if (auto* b = std::get_if<BitmaskValue>(&v)) return formatBitmask(b->bits, table);
      break;
  }
  return {};  // wrong alternative for t: a caller bug, answered without UB
}

}  // namespace simbob
