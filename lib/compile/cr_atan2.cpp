// crAtan2 (include/simbob/cr_math.h): atan2 correctly rounded, by Ziv's strategy (as crSin,
// crCos and crLog in lib/compile/cr_math.cpp): a fast path in double-double arithmetic
// (lib/compile/cr_detail.h) with a proven error bound, Ziv's rounding test, and GNU MPFR's
// mpfr_atan2 for the arguments the test cannot decide (about one in 3,000).
//
// The fast path. With num = min(|y|, |x|), den = max(|y|, |x|) and q = num / den in [0, 1]:
//   atan2(y, x) = s (pi - (w pi/2 + (1 - 2w) atan q)) or s (w pi/2 + (1 - 2w) atan q)
// (x < 0 or not; s the sign of y, w = 1 where |y| > |x|). Then atan q = atan c + atan u with
// c = k/256 the table point nearest q and u = (num - c den) / (den + c num), |u| <= 2^-9.
//   num - c den: Dekker's product c den = p + pl exactly, TwoSum of num - p exactly, then minus
//     pl in double-double: relative error 3 * 2^-106. den + c num likewise, all terms positive.
//   u = their quotient in double-double: relative error below 2^-99 in all.
//   atan u = u + u^3 (-1/3 + u^2/5 - u^4/7 + u^6/9); the next term, u^11/11, is below 2^-93 |u|.
//     The u^3 part is below 2^-19.5 |u|, computed in doubles from u.hi to 2^-50 relative (as
//     log's in cr_math.cpp): error below 2^-69.5 |u|.
//   atan c from the table (MPFR at 256 bits, split into two doubles): 2^-106 relative.
//   For k = 0 the sum is atan u itself; for k >= 1, q c >= 2^-17 makes |u| < 2^-9 (1 - 2^-17)
//   while atan c >= 2^-8 (1 - 2^-17), so the sum, atan q >= atan c - |u|, is at least |u| and
//   at least atan c / 3: the errors above are below 2^-68.5 of it. Adding or subtracting
//   from pi/2 or pi (double-double, 2^-106) only grows the result: below 2^-68 relative in all.
// Ziv's test is run with 2^-66 (kRelErr): a margin of 4.
//
// When q < 2^-60, atan q = q (1 - t), 0 < t < 2^-120, and q = num / den is held as a
// double-double from the exact remainder (Dekker's product), relative error 2^-104: the fast path
// above without the table, the same bound. Results below 2^-900 (subnormal or nearly) go to MPFR
// directly, where Ziv's relative bound and Dekker's product would underflow.
#include <mpfr.h>

#include <array>
#include <cmath>

#include "compile/cr_detail.h"
#include "simbob/cr_math.h"

namespace simbob {

namespace {

using cr::DD;

struct AtanTables {
  std::array<DD, 257> atan;  // atan(k / 256), k = 0..256
  DD halfPi, pi;
  AtanTables() {
    mpfr_t v, t;
    mpfr_inits2(256, v, t, static_cast<mpfr_ptr>(nullptr));
    const auto split = [&]() {  // v to hi + lo
      DD d{mpfr_get_d(v, MPFR_RNDN), 0};
      mpfr_sub_d(t, v, d.hi, MPFR_RNDN);  // exact at 256 bits
      d.lo = mpfr_get_d(t, MPFR_RNDN);
      return d;
    };
    for (std::size_t k = 0; k < atan.size(); ++k) {
      mpfr_set_d(t, static_cast<double>(k) / 256, MPFR_RNDN);
      mpfr_atan(v, t, MPFR_RNDN);
      atan[k] = split();
    }
    mpfr_const_pi(v, MPFR_RNDN);
    pi = split();
    mpfr_div_2ui(v, v, 1, MPFR_RNDN);
    halfPi = split();
    mpfr_clears(v, t, static_cast<mpfr_ptr>(nullptr));
    mpfr_free_cache2(MPFR_FREE_LOCAL_CACHE);
  }
};

const AtanTables& atanTables() {
  static const AtanTables t;
  return t;
}

constexpr double kRelErr = 0x1p-66;

}  // namespace

double crAtan2(double y, double x) {
  // Zeros, infinities and NaN have exact answers (multiples of pi/4 rounded, or NaN) that every
  // libm gives alike.
  if (!std::isfinite(x) || !std::isfinite(y) || x == 0 || y == 0) return std::atan2(y, x);
  const AtanTables& tb = atanTables();
  const double ax = std::fabs(x), ay = std::fabs(y);
  const bool swapped = ay > ax;  // atan(y/x) = pi/2 - atan(x/y)
  double num = swapped ? ax : ay, den = swapped ? ay : ax;
  DD r;
  if (num < den * 0x1p-60) {
    // The quotient alone; where it is the result and below 2^-900, MPFR (see the top).
    if (!swapped && x > 0 && num < den * 0x1p-900) return cr::atan2Mpfr(y, x);
    // Both scaled by the same power of 2, den to [1/2, 1): exact where q is the result (num stays
    // above 2^-902, so Dekker's product in div neither overflows nor underflows); otherwise num
    // may lose bits or vanish, an absolute error below 2^-1000, lost beside pi/2 or pi.
    int e = 0;
    std::frexp(den, &e);
    num = std::ldexp(num, -e);
    den = std::ldexp(den, -e);
    r = cr::div({num, 0}, {den, 0});
  } else {
    if (den > 0x1p+500 || den < 0x1p-500) {
      int e = 0;
      std::frexp(den, &e);  // scale both by the same power of 2 (exact: num >= 2^-60 den)
      num = std::ldexp(num, -e);
      den = std::ldexp(den, -e);
    }
    const auto k = static_cast<std::size_t>(cr::nearestInt(num / den * 256));
    const double c = static_cast<double>(k) / 256;
    const DD cd = cr::twoProduct(c, den), cn = cr::twoProduct(c, num);
    const DD n = cr::add(cr::twoSum(num, -cd.hi), {-cd.lo, 0});
    const DD d = cr::add(cr::twoSum(den, cn.hi), {cn.lo, 0});
    const DD u = cr::div(n, d);
    const double z = u.hi * u.hi;
    const double u3 = u.hi * z * (-1.0 / 3 + z * (1.0 / 5 + z * (-1.0 / 7 + z * (1.0 / 9))));
    r = cr::add(u, {u3, 0});
    if (k != 0) r = cr::add(tb.atan[k], r);
  }
  if (swapped) r = cr::add(tb.halfPi, cr::neg(r));
  if (x < 0) r = cr::add(tb.pi, cr::neg(r));
  if (y < 0) r = cr::neg(r);
  double out = 0;
  if (cr::zivRound(r, kRelErr * std::fabs(r.hi), &out)) return out;
  return cr::atan2Mpfr(y, x);
}

}  // namespace simbob
