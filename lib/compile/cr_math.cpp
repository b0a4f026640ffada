// crSin, crCos and crLog (include/simbob/cr_math.h), and the GNU MPFR slow paths of all four
// functions (lib/compile/cr_detail.h).
//
// Each function is Ziv's strategy: a fast path in double-double arithmetic (lib/compile/cr_detail.h:
// IEEE + - * / only, no FMA, no libm transcendental) with a proven bound on its error, then Ziv's
// rounding test: if both ends of the error interval round to the same double, that double is the
// correctly rounded value. Otherwise (about one argument in 3,000; tests/compile/cr_math_test.cpp
// counts them) GNU MPFR at 53 bits decides, as every call did before. Both paths return the
// correctly rounded value, so the bits are those MPFR alone gave, on every CPU.
//
// The constants (pi/2 in four parts, sin and cos of j/128, log of the reciprocal table, log 2) are
// computed once per process by MPFR at 256 bits and split into doubles: nothing copied, nothing
// that depends on the CPU.
#include <mpfr.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "compile/cr_detail.h"
#include "simbob/cr_math.h"

namespace simbob {

namespace cr {

namespace {

thread_local std::uint64_t tFallbacks = 0;

struct Mpfr53 {
  mpfr_t x, y, r;
  Mpfr53() { mpfr_inits2(53, x, y, r, static_cast<mpfr_ptr>(nullptr)); }
  ~Mpfr53() {  // at the thread's end: also MPFR's per-thread caches (the constants sin needs)
    mpfr_clears(x, y, r, static_cast<mpfr_ptr>(nullptr));
    mpfr_free_cache2(MPFR_FREE_LOCAL_CACHE);
  }
  Mpfr53(const Mpfr53&) = delete;
  Mpfr53& operator=(const Mpfr53&) = delete;
};

Mpfr53& mpfr53() {
  thread_local Mpfr53 m;
  return m;
}

// r (53 bits, ternary value inex) to the double it rounds to, subnormals rounded once: in
// IEEE double's exponent range, mpfr_subnormalize rounds r again to the precision a subnormal
// has, using inex so that no value is rounded twice.
double toDouble(mpfr_ptr r, int inex) {
  const mpfr_exp_t emin = mpfr_get_emin(), emax = mpfr_get_emax();
  mpfr_set_emin(-1073);
  mpfr_set_emax(1024);
  inex = mpfr_check_range(r, inex, MPFR_RNDN);
  mpfr_subnormalize(r, inex, MPFR_RNDN);
  const double d = mpfr_get_d(r, MPFR_RNDN);  // exact: r is a double now
  mpfr_set_emin(emin);
  mpfr_set_emax(emax);
  return d;
}

using Fn = int (*)(mpfr_ptr, mpfr_srcptr, mpfr_rnd_t);

double slow(Fn fn, double v) {
  ++tFallbacks;
  Mpfr53& m = mpfr53();
  mpfr_set_d(m.x, v, MPFR_RNDN);  // exact: 53 bits hold any double
  return toDouble(m.r, fn(m.r, m.x, MPFR_RNDN));
}

}  // namespace

double sinMpfr(double x) { return slow(mpfr_sin, x); }
double cosMpfr(double x) { return slow(mpfr_cos, x); }
double logMpfr(double x) { return slow(mpfr_log, x); }
double atan2Mpfr(double y, double x) {
  ++tFallbacks;
  Mpfr53& m = mpfr53();
  mpfr_set_d(m.y, y, MPFR_RNDN);
  mpfr_set_d(m.x, x, MPFR_RNDN);
  return toDouble(m.r, mpfr_atan2(m.r, m.y, m.x, MPFR_RNDN));
}

std::uint64_t fallbacks() { return tFallbacks; }

}  // namespace cr

namespace {

using cr::DD;

// The tables, made once (a function-local static: thread-safe) by MPFR at 256 bits.
struct Tables {
  // pi/2 = P1 + P2 + P3 + P4 + d, P1 and P2 with 33 significant bits (so k * P1 and k * P2 are
  // exact for |k| < 2^20), P3 and P4 with 53: |d| < 2^-170.
  double p1, p2, p3, p4;
  // sin(j / 128) and cos(j / 128), j = 0..104 (|r| <= pi/4 + 2^-40 needs j <= 101), each to
  // 2^-106 relative.
  std::array<DD, 105> sin, cos;
  // For i = 181..363: rcp[i] = 256 / i rounded to double, and mlog[i] = -log(rcp[i]) to 2^-106.
  std::array<double, 364> rcp;
  std::array<DD, 364> mlog;
  // log 2 = ln2hi + ln2lo + d, ln2hi with 42 bits (e ln2hi is exact for |e| < 2^11), |d| < 2^-96.
  double ln2hi, ln2lo;

  Tables() {
    mpfr_t v, t;
    mpfr_inits2(256, v, t, static_cast<mpfr_ptr>(nullptr));
    const auto split = [&](mpfr_ptr a) {  // a to hi + lo; a itself is left unchanged
      DD d{mpfr_get_d(a, MPFR_RNDN), 0};
      mpfr_sub_d(t, a, d.hi, MPFR_RNDN);  // exact at 256 bits
      d.lo = mpfr_get_d(t, MPFR_RNDN);
      return d;
    };
    const auto take = [&](int bits) {  // v rounded to `bits` bits; v becomes the remainder
      mpfr_set(t, v, MPFR_RNDN);
      mpfr_prec_round(t, bits, MPFR_RNDN);
      const double p = mpfr_get_d(t, MPFR_RNDN);
      mpfr_set_prec(t, 256);
      mpfr_sub_d(v, v, p, MPFR_RNDN);  // exact
      return p;
    };
    mpfr_const_pi(v, MPFR_RNDN);
    mpfr_div_2ui(v, v, 1, MPFR_RNDN);
    p1 = take(33);
    p2 = take(33);
    p3 = take(53);
    p4 = take(53);
    for (std::size_t j = 0; j < sin.size(); ++j) {
      mpfr_set_d(v, static_cast<double>(j) / 128, MPFR_RNDN);
      mpfr_sin(t, v, MPFR_RNDN);
      mpfr_swap(t, v);
      sin[j] = split(v);
      mpfr_set_d(v, static_cast<double>(j) / 128, MPFR_RNDN);
      mpfr_cos(t, v, MPFR_RNDN);
      mpfr_swap(t, v);
      cos[j] = split(v);
    }
    for (std::size_t i = 181; i < rcp.size(); ++i) {
      rcp[i] = 256.0 / static_cast<double>(i);  // IEEE division: the same double everywhere
      mpfr_set_d(v, rcp[i], MPFR_RNDN);
      mpfr_log(t, v, MPFR_RNDN);
      mpfr_neg(v, t, MPFR_RNDN);
      mlog[i] = split(v);
    }
    mpfr_const_log2(v, MPFR_RNDN);
    ln2hi = take(42);
    ln2lo = take(53);
    mpfr_clears(v, t, static_cast<mpfr_ptr>(nullptr));
    mpfr_free_cache2(MPFR_FREE_LOCAL_CACHE);
  }
};

const Tables& tables() {
  static const Tables t;
  return t;
}

// The bound on the relative error of every fast path below, with a margin of 4 to 8 over each
// derivation (the comments at each function): a proven bound is all Ziv's test needs, and the
// margin costs only a slower average (about 1 argument in 3,000 falls back).
constexpr double kRelErr = 0x1p-66;

// sin(r) and cos(r) for a double-double r, |r| <= pi/4 + 2^-40, with absolute errors at most
// 2^-69 |sin r| and 2^-69 |cos r| (plus 2^-100 |r| from the table's splitting).
//
// r = a + t with a = j/128 the nearest table point, |t| <= 2^-8 (t = r.hi - a is exact: both are
// multiples of ulp(r.hi) and |t| < 2^53 ulp(r.hi)). Then sin r = S + (C sin t + S (cos t - 1)),
// cos r = C + (C (cos t - 1) - S sin t), S and C the table's sin a and cos a.
//   sin t = t + t^3 (-1/6 + t^2/120 - t^4/5040): the next term, t^9/9!, is below 2^-82 |t|. The
//     t^3 part is below 2^-18.5 |t| and computed in doubles from t.hi with at most 8 roundings
//     (relative 2^-53 each, the coefficients' own included): its error is below 2^-68.5 |t|;
//     added to t.lo in double, it errs by 2^-53 * 2^-18.4 |t| more: 2^-68.2 |t| in all.
//   cos t - 1 = -t^2/2 + t^4 (1/24 - t^2/720): -t^2/2 in double-double (Dekker's product of t.hi,
//     plus t.hi t.lo), error below 2^-100 t^2; the t^4 part is below 2^-36.5 and good to 2^-86
//     (added to the low part: 2^-89 more);
//     the next term, t^8/8!, is below 2^-79.
// For j = 0 the result is sin t (error 2^-68.2 |t|, |sin t| >= 0.99 |t|) or 1 + (cos t - 1)
// (error 2^-79). For j >= 1, |sin r| >= sin(2^-8) and the absolute errors above (2^-76.5) are
// below 2^-68 |sin r|; |cos r| >= 0.7 throughout. The double-double products and sums add below
// 2^-100 relative.
struct SinCosT {
  DD sinT, cosTm1;
  std::size_t j;
};

SinCosT kernelParts(DD r) {
  const auto j = static_cast<std::size_t>(cr::nearestInt(r.hi * 128));
  const double a = static_cast<double>(j) / 128;
  const DD t = cr::fastTwoSum(r.hi - a, r.lo);
  const double z = t.hi * t.hi;
  const double s3 = t.hi * z * (-1.0 / 6 + z * (1.0 / 120 + z * (-1.0 / 5040)));
  const DD sinT = cr::fastTwoSum(t.hi, t.lo + s3);
  const DD sq = cr::twoProduct(t.hi, t.hi);
  const double c4 = z * z * (1.0 / 24 + z * (-1.0 / 720));
  const DD cosTm1{-0.5 * sq.hi, (-0.5 * sq.lo - t.hi * t.lo) + c4};  // not normalised
  return {sinT, cosTm1, j};
}

// a * b as an unnormalised double-double (mul without its last FastTwoSum): the same error.
DD mulRaw(DD a, DD b) {
  const DD p = cr::twoProduct(a.hi, b.hi);
  return {p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi)};
}

// a + b + c, each an unnormalised double-double whose lo is below 2^-50 of its hi: the highs by
// TwoSum, exactly, the lows and the TwoSums' errors summed in doubles. With M = |a| + |b| + |c|,
// the error is below 5 * 2^-53 * 5 * 2^-52 M < 2^-100 M.
DD sum3(DD a, DD b, DD c) {
  const DD h1 = cr::twoSum(a.hi, b.hi), h2 = cr::twoSum(h1.hi, c.hi);
  return cr::fastTwoSum(h2.hi, ((h1.lo + h2.lo) + (a.lo + b.lo)) + c.lo);
}

// M <= 3 |sin r| (for j >= 1, |S| <= 2 |sin r| and |C sin t| <= 2^-8; for j = 0, S = 0) and
// M <= 3 |cos r|: sum3 adds below 2^-98 relative.
DD sinKernel(DD r) {  // r >= 0
  const Tables& tb = tables();
  const SinCosT p = kernelParts(r);
  const DD s = tb.sin[p.j], c = tb.cos[p.j];
  return sum3(s, mulRaw(c, p.sinT), mulRaw(s, p.cosTm1));
}

DD cosKernel(DD r) {  // r >= 0
  const Tables& tb = tables();
  const SinCosT p = kernelParts(r);
  const DD s = tb.sin[p.j], c = tb.cos[p.j];
  return sum3(c, mulRaw(c, p.cosTm1), cr::neg(mulRaw(s, p.sinT)));
}

// Cody and Waite's reduction, for 2^-27 <= |x| < 2^20: x = k pi/2 + r, r in double-double with
// |r| <= pi/4 + 2^-40, and an absolute error below 2^-102 |r| + 2^-140:
//   k = x * 2/pi rounded to an integer (|k| < 2^20);
//   x - k P1 is exact (k P1 has 53 bits; the difference is a multiple of 2^-53 below 1);
//   k P2 is exact, and its difference with the former is held exactly by TwoSum (s);
//   k P3 exactly by Dekker's product (p), and s.hi - p.hi exactly by TwoSum (h);
//   the lows, h.lo + s.lo - p.lo - k P4, in doubles: each is below 2^-52 (|s.hi| + |p.hi|), so
//     three roundings err by less than 2^-103 (|s.hi| + |p.hi|), which is below 2^-102 |r| where
//     s.hi and p.hi do not cancel, and below 2^-147 where they do (|p.hi| < 2^20 * 2^-65);
//   k P4 in double (error below 2^-150) and the remainder of pi/2 (k 2^-170) left out.
DD reduce(double x, std::int64_t* k) {
  const Tables& tb = tables();
  const double kd = cr::nearestInt(x * 0x1.45f306dc9c883p-1);  // 2/pi; any nearby value will do
  *k = static_cast<std::int64_t>(kd);
  const double r1 = x - kd * tb.p1;
  const DD s = cr::twoSum(r1, -(kd * tb.p2));
  const DD p = cr::twoProduct(kd, tb.p3);
  const DD h = cr::twoSum(s.hi, -p.hi);
  return cr::twoSum(h.hi, (h.lo + (s.lo - p.lo)) - kd * tb.p4);
}

enum class Which { kSin, kCos };

double sinCos(double x, Which which) {
  const double ax = std::fabs(x);
  // |x| < 2^-27: sin x = x (1 - x^2/6 + ...) lies within 2^-55.5 |x| of x, closer than the
  // nearest midpoint (2^-54 |x| away at least); cos x = 1 - x^2/2 + ... lies within 2^-55 of 1,
  // closer than the midpoint below 1 (1 - 2^-54).
  if (ax < 0x1p-27) return which == Which::kSin ? x : 1.0;
  if (ax >= 0x1p20) return which == Which::kSin ? cr::sinMpfr(x) : cr::cosMpfr(x);
  std::int64_t k = 0;
  DD r = ax < 0.78 ? DD{x, 0} : reduce(x, &k);  // below pi/4: k = 0, r = x exactly
  const bool negR = r.hi < 0;
  if (negR) r = cr::neg(r);
  // sin x = sin r, cos r, -sin r, -cos r for k = 0, 1, 2, 3 mod 4; cos x = sin(x + pi/2).
  const unsigned q = static_cast<unsigned>(k + (which == Which::kCos ? 1 : 0)) & 3U;
  DD v = (q & 1U) ? cosKernel(r) : sinKernel(r);
  // sin(-r) = -sin r, cos(-r) = cos r.
  if (((q & 1U) == 0 && negR) != ((q & 2U) != 0)) v = cr::neg(v);
  double out = 0;
  // Relative kRelErr of the kernel (|derivative| <= 1 carries the reduction's error, 2^-102 |r|
  // relative and 2^-140 absolute, into the result: |sin r| >= 0.63 |r|).
  if (cr::zivRound(v, kRelErr * std::fabs(v.hi) + 0x1p-139, &out)) return out;
  return which == Which::kSin ? cr::sinMpfr(x) : cr::cosMpfr(x);
}

}  // namespace

double crSin(double x) {
  if (!std::isfinite(x)) return std::sin(x);  // NaN
  if (x == 0) return x;                       // sin(+-0) = +-0
  return sinCos(x, Which::kSin);
}

double crCos(double x) {
  if (!std::isfinite(x)) return std::cos(x);  // NaN
  return sinCos(x, Which::kCos);
}

// log x for x > 0 finite: x = 2^e m with m in [sqrt(1/2), sqrt 2], i = m * 256 rounded
// (181..363), c = rcp[i] (256/i rounded), and log x = e log 2 - log c + log(1 + z) with
// z = m c - 1, |z| <= 2^-8.5 * 1.42 + 2^-52 < 2^-8.4. m c is exact as Dekker's product p + pl,
// p - 1 is exact (Sterbenz: p is within 2^-8 of 1), so z = (p - 1) + pl is exact.
//   log(1 + z) = z - z^2/2 + z^3 (1/3 - z/4 + ... + z^6/9): the next term, z^10/10, is below
//     2^-79 |z|; z^2/2 in double-double (error 2^-100 z^2); the z^3 part, below 2^-18.5 |z|,
//     in doubles from z.hi: z.hi^3 is good to 5 * 2^-53 (z.lo <= 2^-53 |z.hi|, two products),
//     the polynomial to 3 * 2^-53 (1/3 rounded, the sum; the rest is 2^-8 smaller), their
//     product to one more: error below 2^-50 * 2^-18.4 |z| = 2^-68.4 |z|.
//     z.hi - z.hi^2/2 is held exactly by FastTwoSum; the low part's terms are below 2^-51 |z|
//     but for t3, so its roundings err by less than 2^-53 (2^-18.4 + 2^-49) |z|: 2^-68.2 |z| in all.
//   e log 2: e ln2hi exact, e ln2lo to 2^-53 of it (2^-96 |e|), log 2 - ln2hi - ln2lo < 2^-96:
//     below 2^-94 |e| <= 2^-95 |log x| for e != 0. -log c: 2^-106 relative.
//   The sum (sum3): below 2^-100 of |e log 2| + |log c| + |log(1 + z)| <= 3 |log x|.
// The sum: for e != 0, |log x| >= 0.34 and every error above is below 2^-75 |log x|; for e = 0,
// either i = 256 (c = 1: the result is log(1 + z) itself, |log(1 + z)| >= 0.99 |z|) or
// |log x| >= log(256.5/256) >= |z|/2, so the error is below 2^-67.2 |log x| (kRelErr = 2^-66).
double crLog(double x) {
  if (!std::isfinite(x) || x <= 0) return std::log(x);  // NaN, +inf, -inf at 0, NaN below
  if (x == 1) return 0.0;
  const Tables& tb = tables();
  const double x0 = x;
  int e = 0;
  if (x < 0x1p-1022) {  // subnormal: scaled by 2^54, exactly
    x *= 0x1p54;
    e = -54;
  }
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  e += static_cast<int>(b >> 52) - 1023;
  b = (b & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL;  // m in [1, 2)
  double m = 0;
  std::memcpy(&m, &b, sizeof m);
  if (m > 0x1.6a09e667f3bcdp+0) {  // sqrt 2
    m *= 0.5;
    ++e;
  }
  const auto i = static_cast<std::size_t>(cr::nearestInt(m * 256));
  const DD p = cr::twoProduct(m, tb.rcp[i]);
  const DD z = cr::fastTwoSum(p.hi - 1, p.lo);  // exact: |p.hi - 1| >= ulp(p.hi) > |p.lo| or 0
  const double zh = z.hi;
  const double t3 =
      zh * zh * zh *
      (1.0 / 3 +
       zh * (-1.0 / 4 + zh * (1.0 / 5 + zh * (-1.0 / 6 + zh * (1.0 / 7 + zh * (-1.0 / 8 + zh * (1.0 / 9)))))));
  // log(1 + z): z.hi - z.hi^2/2 by FastTwoSum (|z.hi| > z.hi^2), the rest in the low part.
  const DD sq = cr::twoProduct(zh, zh);
  const DD h = cr::fastTwoSum(zh, -0.5 * sq.hi);
  const DD l1p{h.hi, ((h.lo + z.lo) - (0.5 * sq.lo + zh * z.lo)) + t3};
  // e log 2 (exact high part) - log c + log(1 + z).
  const double ed = static_cast<double>(e);
  const DD v = sum3({ed * tb.ln2hi, ed * tb.ln2lo}, tb.mlog[i], l1p);
  double out = 0;
  if (cr::zivRound(v, kRelErr * std::fabs(v.hi), &out)) return out;
  return cr::logMpfr(x0);
}

}  // namespace simbob
