// Correctly rounded mathematical functions: the same bits on every x86-64 CPU and libm.
//
// glibc's atan2, sin, cos and log are not correctly rounded, and their CPU-specific variants (FMA
// and generic) round a few arguments in a thousand differently. Wherever such a result reaches a
// trajectory -- a hinge angle read by a servo law or held by a stop, a rotation built from a
// scene's Euler angles, a scanner ray's direction, sensor noise -- simbob calls these instead
// (docs/ci.md, "Hinge angles and libm's atan2"). A correctly rounded result depends on nothing
// but the argument.
//
// Each is Ziv's strategy (lib/compile/cr_math.cpp, cr_atan2.cpp): a fast path in double-double
// arithmetic from IEEE additions, multiplications and divisions alone (simbob compiles with
// -ffp-contract=off), with an error bound proven in the source's comments (below 2^-66 relative);
// if both ends of that error interval round to the same double, it is the correctly rounded
// value, and it is returned. Otherwise (about one argument in 3,000, and sin/cos of |x| >= 2^20)
// GNU MPFR at 53 bits, correctly rounded by its own contract, decides. Correct rounding is thus
// proven for every argument, given the bounds and MPFR. A call costs a few times libm's
// (bench/README.md, "Deterministic math"). tests/compile/cr_math_test.cpp checks all four against
// MPFR on random arguments, hard cases and special values.
#pragma once

namespace simbob {

/// atan2(y, x) rounded once to the nearest double; zeros, infinities and NaN as C's atan2.
double crAtan2(double y, double x);
/// sin(x), cos(x), log(x) rounded once to the nearest double; NaN, infinities and log's domain
/// as C's.
double crSin(double x);
double crCos(double x);
double crLog(double x);

}  // namespace simbob
