// crSin, crCos and crLog (include/simbob/cr_math.h): GNU MPFR at 53 bits of precision, rounded to
// nearest, which is the correctly rounded double. One set of MPFR numbers per thread, made on
// first use: no allocation per call.
#include <mpfr.h>

#include <cmath>

#include "simbob/cr_math.h"

namespace simbob {

namespace {

struct Mpfr53 {
  mpfr_t x, r;
  Mpfr53() {
    mpfr_init2(x, 53);
    mpfr_init2(r, 53);
  }
  ~Mpfr53() {  // at the thread's end: also MPFR's per-thread caches (the constants sin needs)
    mpfr_clear(x);
    mpfr_clear(r);
    mpfr_free_cache2(MPFR_FREE_LOCAL_CACHE);
  }
  Mpfr53(const Mpfr53&) = delete;
  Mpfr53& operator=(const Mpfr53&) = delete;
};

using Fn = int (*)(mpfr_ptr, mpfr_srcptr, mpfr_rnd_t);

double correctlyRounded(Fn fn, double v) {
  // MPFR's exponent range is far wider than a double's; a result is subnormal only for sin of a
  // subnormal x, which is x itself, so the conversion back never rounds a second time.
  thread_local Mpfr53 m;
  mpfr_set_d(m.x, v, MPFR_RNDN);  // exact: 53 bits hold any double
  fn(m.r, m.x, MPFR_RNDN);
  return mpfr_get_d(m.r, MPFR_RNDN);  // exact: r already has 53 bits
}

}  // namespace

// Zero (most Euler angles in a scene) is exact and needs no MPFR: sin(+-0) = +-0, cos(0) = 1.
double crSin(double x) { return std::isfinite(x) && x != 0 ? correctlyRounded(mpfr_sin, x) : std::sin(x); }
double crCos(double x) {
  if (x == 0) return 1.0;
  return std::isfinite(x) ? correctlyRounded(mpfr_cos, x) : std::cos(x);
}
double crLog(double x) { return std::isfinite(x) && x > 0 ? correctlyRounded(mpfr_log, x) : std::log(x); }

}  // namespace simbob
