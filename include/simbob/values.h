// Basic value types of the scene format and their string conversions (user guide 4.3).
// Parsing and writing are exact inverses for every value a parser accepts:
// write(parse(s)) may normalise the spelling, but parse(write(v)) == v bit for bit.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace simbob {

using Triple = std::array<double, 3>;

/// Four elements; the 4th scales the others (0 = a direction that cannot be normalised).
struct Vector4 {
  std::array<double, 4> v{0, 0, 0, 1};
  bool operator==(const Vector4& o) const { return v == o.v; }
};

/// Orientation as a unit quaternion, element order w x y z (as ODE).
struct Quaternion {
  std::array<double, 4> q{1, 0, 0, 0};
  bool operator==(const Quaternion& o) const { return q == o.q; }
};

/// Position (m) and Euler angles (degrees). Kept as written so files round-trip exactly.
/// Convention: R = Rz(c) * Ry(b) * Rx(a): rotate about global X, then global Y, then global Z.
struct Pose {
  Triple pos{0, 0, 0};
  Triple euler_deg{0, 0, 0};
  bool operator==(const Pose& o) const { return pos == o.pos && euler_deg == o.euler_deg; }
};

/// The 16 numbers of a Matrix4, kept on the heap: every parameter slot holds a Value, and a
/// Value is as large as its largest alternative, so 128 bytes inline would cost every slot.
/// Behaves as a std::array<double, 16> (indexing, data, iteration, ==). A moved-from one reads
/// as the identity.
class Matrix4Elements {
 public:
  using Array = std::array<double, 16>;
  Matrix4Elements(std::initializer_list<double> v) : p_(std::make_unique<Array>()) {
    std::copy_n(v.begin(), std::min<size_t>(v.size(), 16), p_->begin());
  }
  Matrix4Elements(const Array& a) : p_(std::make_unique<Array>(a)) {}
  Matrix4Elements(const Matrix4Elements& o) : p_(std::make_unique<Array>(o.array())) {}
  Matrix4Elements(Matrix4Elements&& o) noexcept = default;
  Matrix4Elements& operator=(const Matrix4Elements& o) {
    if (this != &o) p_ = std::make_unique<Array>(o.array());
    return *this;
  }
  Matrix4Elements& operator=(Matrix4Elements&& o) noexcept = default;

  const Array& array() const { return p_ ? *p_ : identity(); }
  Array& array() {
    if (!p_) p_ = std::make_unique<Array>(identity());
    return *p_;
  }
  double operator[](size_t i) const { return array()[i]; }
  double& operator[](size_t i) { return array()[i]; }
  const double* data() const { return array().data(); }
  double* data() { return array().data(); }
  const double* begin() const { return data(); }
  const double* end() const { return data() + 16; }
  double* begin() { return data(); }
  double* end() { return data() + 16; }
  static constexpr size_t size() { return 16; }
  bool operator==(const Matrix4Elements& o) const { return array() == o.array(); }

 private:
  static const Array& identity() {
    static const Array i{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    return i;
  }
  std::unique_ptr<Array> p_;
};

/// Row-major 4x4 matrix.
struct Matrix4 {
  Matrix4Elements m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  bool operator==(const Matrix4& o) const { return m == o.m; }
};

/// Two opposite corners.
struct Cuboid {
  Triple a{0, 0, 0};
  Triple b{0, 0, 0};
  bool operator==(const Cuboid& o) const { return a == o.a && b == o.b; }
};

/// RGBA in [0,1]; valid == false is the guide's "invalid" (unspecified) colour.
struct Color {
  std::array<double, 4> rgba{0, 0, 0, 1};
  bool valid = true;
  bool operator==(const Color& o) const { return valid == o.valid && (!valid || rgba == o.rgba); }
};

/// One key of an enum or bitmask table. Several keys may share a value (aliases); the first
/// one listed is the spelling used when writing.
struct EnumKey {
  const char* name;
  uint32_t value;
};

struct EnumTable {
  const char* name;  ///< e.g. "ColorMode"
  std::vector<EnumKey> keys;
};

struct EnumValue {
  uint32_t value = 0;
  bool operator==(const EnumValue& o) const { return value == o.value; }
};

struct BitmaskValue {
  uint32_t bits = 0;
  bool operator==(const BitmaskValue& o) const { return bits == o.bits; }
};

enum class ValueType {
  Bool,
  Int,     ///< a number that must be integral (stored as int64)
  Number,  ///< double
  String,
  Triple,
  Vector,
  Quaternion,
  Pose,
  Matrix,
  Cuboid,
  Color,
  Enum,
  Bitmask,
};

using Value = std::variant<bool, int64_t, double, std::string, Triple, Vector4, Quaternion, Pose, Matrix4, Cuboid,
                           Color, EnumValue, BitmaskValue>;

/// Name used in messages and `simbob types`: "Bool", "Number", "Triple", ...
const char* valueTypeName(ValueType t);

/// Options that change what a parse accepts.
struct ParseOptions {
  bool allow_infinite = false;  ///< accept "Infinite" / "-Infinite" for numbers (drive limits)
};

/// Result of a parse: a value, or a message saying what is wrong (no file/line: the caller adds it).
struct ParseResult {
  std::optional<Value> value;
  std::string error;
  explicit operator bool() const { return value.has_value(); }
};

/// Parse `text` as a value of type `t`. `table` is required for Enum and Bitmask.
/// NaN is always rejected; infinities only with allow_infinite. A Number or Int is the number
/// alone (guide 4.3: it starts with a sign, a digit or '.'): " 7" and "7 " are errors.
ParseResult parseValue(ValueType t, std::string_view text, const EnumTable* table = nullptr, ParseOptions opts = {});

/// Write `v` (which must hold the alternative for `t`) in its canonical string form.
std::string formatValue(ValueType t, const Value& v, const EnumTable* table = nullptr);

// --- building blocks, exposed for tests and for other readers (CSV, INI) ---

/// Shortest round-trip decimal form of a double (std::to_chars), "Infinite"/"-Infinite" for
/// infinities. Never locale-dependent. Round-trips bit for bit, so negative zero is "-0": for
/// numbers in messages use formatApprox or formatReadable.
std::string formatNumber(double d);

/// Append the shortest round-trip form of d to out (no allocation beyond out's growth). Writes
/// negative zero as "-0": the trajectory and log CSVs use it, and their bytes are fixed.
void appendNumber(std::string& out, double d);

/// Three significant digits, as printf's "%.3g" writes them ("0.00123", "1.23e+06"), for
/// numbers people read in messages; negative zero is "0". Never locale-dependent.
std::string formatApprox(double d);

/// Text for an XML attribute value or element text (or HTML): & < > " written as entities.
std::string escapeXml(const std::string& s);

/// formatNumber for a number in a message: negative zero (-1e-320 * 1e-10, a rotated zero) is
/// written "0", a sign that means nothing to the reader.
std::string formatReadable(double d);

/// "1 body", "2 bodies": a count with the noun in singular or plural.
std::string countOf(size_t n, std::string_view one, std::string_view many);

/// Edit distance, ASCII case-insensitive; swapping two neighbours costs 1 (restricted
/// Damerau-Levenshtein).
size_t editDistance(std::string_view a, std::string_view b);

/// The "did you mean" of every message: the candidate closest to `word` if it is within
/// max(2, |word| / 3) edits and fewer edits than the candidate is long; otherwise "". Ties go to
/// the first candidate.
std::string didYouMean(std::string_view word, const std::vector<std::string>& candidates);

/// Strict number: optional sign, digits, '.', exponent. Whole text must be consumed; blanks
/// around it are ignored (for CSV fields and INI counts; scene values go through parseValue).
std::optional<double> parseNumber(std::string_view text, bool allow_infinite = false);

/// A Number value as parseValue reads it: the number alone, without blanks around it (guide
/// 4.3). False, leaving *out alone, wherever parseValue gives an error instead.
bool parseNumberValue(std::string_view text, bool allow_infinite, double* out);

/// A numerical value list: numbers separated by any of " \t,;\\()" (guide 4.3).
/// Returns std::nullopt and sets *error on a malformed element.
std::optional<std::vector<double>> parseNumberList(std::string_view text, std::string* error,
                                                   bool allow_infinite = false);

/// String escapes of 4.3: "\t" tab, "\n" newline, "\x" -> x for any other x.
std::string unescapeString(std::string_view text);
std::string escapeString(std::string_view text);

/// Case-insensitive ASCII comparison.
bool equalsIgnoreCase(std::string_view a, std::string_view b);

}  // namespace simbob
