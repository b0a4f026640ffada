// The machinery of include/simbob/cr_math.h's functions, shared by lib/compile/cr_math.cpp and
// cr_atan2.cpp, and open to their test and microbenchmark: double-double arithmetic from IEEE
// operations alone, Ziv's rounding test, and the GNU MPFR paths the fast ones fall back to.
//
// Every function here computes with + - * / on doubles, each correctly rounded to nearest by
// IEEE 754; simbob compiles with -ffp-contract=off, so none is fused into an FMA and the same
// operations give the same bits on every x86-64 CPU.
#pragma once

#include <cmath>
#include <cstdint>

namespace simbob::cr {

/// A double-double: the value hi + lo, |lo| <= ulp(hi) / 2 once normalised.
struct DD {
  double hi, lo;
};

/// Knuth's TwoSum: a + b exactly as s + e, whatever their magnitudes.
inline DD twoSum(double a, double b) {
  const double s = a + b, bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}

/// Dekker's FastTwoSum: exact when the exponent of a is at least that of b (or a == 0).
inline DD fastTwoSum(double a, double b) {
  const double s = a + b;
  return {s, b - (s - a)};
}

/// Dekker's product with Veltkamp's split (no FMA): a * b exactly as hi + lo, for |a|, |b| below
/// 2^995 and a product that does not underflow.
inline DD twoProduct(double a, double b) {
  constexpr double kSplit = 134217729.0;  // 2^27 + 1
  const double ta = kSplit * a, ah = ta - (ta - a), al = a - ah;
  const double tb = kSplit * b, bh = tb - (tb - b), bl = b - bh;
  const double p = a * b;
  return {p, ((ah * bh - p) + ah * bl + al * bh) + al * bl};
}

/// Accurate double-double sum (Joldes, Muller, Popescu 2017, "AccurateDWPlusDW"): relative error
/// at most 3 * 2^-106 of the exact sum.
inline DD add(DD a, DD b) {
  DD s = twoSum(a.hi, b.hi);
  const DD t = twoSum(a.lo, b.lo);
  s = fastTwoSum(s.hi, s.lo + t.hi);
  return fastTwoSum(s.hi, s.lo + t.lo);
}

/// Double-double product, a.lo * b.lo dropped: relative error below 7 * 2^-106 (ibid., "DWTimesDW1").
inline DD mul(DD a, DD b) {
  const DD p = twoProduct(a.hi, b.hi);
  return fastTwoSum(p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi));
}

/// a / b: the quotient of the high parts and one correction from the exact remainder (a.hi - p.hi
/// is exact: p.hi is within a few ulps of a.hi). Relative error below 2^-100.
inline DD div(DD a, DD b) {
  const double q1 = a.hi / b.hi;
  const DD p = twoProduct(q1, b.hi);
  const double r = (((a.hi - p.hi) - p.lo) + a.lo) - q1 * b.lo;
  return fastTwoSum(q1, r / b.hi);
}

/// v rounded to the nearest integer (ties to even), for |v| < 2^51: adding and subtracting
/// 1.5 * 2^52 leaves no fraction bits. Exact, no libm call, the same on every CPU.
inline double nearestInt(double v) {
  constexpr double kRound = 0x1.8p52;
  return (v + kRound) - kRound;
}

inline DD neg(DD a) { return {-a.hi, -a.lo}; }

/// Ziv's rounding test. v.hi + v.lo approximates an exact value y with |y - (v.hi + v.lo)| <= err
/// (err >= 0, |v.lo| <= 2^-50 |v.hi|, err <= 2^-60 |v.hi|). If the two ends of the interval,
/// v.hi + v.lo -+ 2 err, round to the same double, that double is the correctly rounded y: rounding
/// to nearest is monotone, and y lies between the two ends. (The factor 2 covers the rounding of
/// v.lo -+ 2 err, which is below 2^-53 |v.lo -+ 2 err| <= 2^-102 |v.hi|: far below err itself, as
/// long as err is at least 2^-100 |v.hi|, which every caller's bound is.) Returns false where they
/// differ: then the slow path decides.
inline bool zivRound(DD v, double err, double* out) {
  const double e = 2 * err;
  const double a = v.hi + (v.lo - e), b = v.hi + (v.lo + e);
  if (a != b) return false;
  *out = a;
  return true;
}

/// The slow paths: GNU MPFR at 53 bits, rounded to nearest (correct rounding by MPFR's own
/// contract), with subnormal results rounded once (mpfr_subnormalize). Each call counts in
/// fallbacks().
double sinMpfr(double x);
double cosMpfr(double x);
double logMpfr(double x);
double atan2Mpfr(double y, double x);

/// How many times this thread's fast paths fell back to MPFR (the tests and the benchmark report
/// the rate).
std::uint64_t fallbacks();

}  // namespace simbob::cr
