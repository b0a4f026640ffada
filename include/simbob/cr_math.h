// Correctly rounded mathematical functions: the same bits on every x86-64 CPU and libm.
//
// glibc's atan2, sin, cos and log are not correctly rounded, and their CPU-specific variants (FMA
// and generic) round a few arguments in a thousand differently. Wherever such a result reaches a
// trajectory -- a hinge angle read by a servo law or held by a stop, a rotation built from a
// scene's Euler angles, a scanner ray's direction, sensor noise -- simbob calls these instead
// (docs/ci.md, "Hinge angles and libm's atan2"). A correctly rounded result depends on nothing
// but the argument.
//
// crAtan2 is simbob's own double-double arithmetic from IEEE additions, multiplications and
// divisions alone (simbob compiles with -ffp-contract=off): about 0.2 microseconds, cheap enough
// for every hinge at every step. crSin, crCos and crLog are GNU MPFR's at 53 bits, rounded to
// nearest (a few microseconds each): for set-up work and per-reading noise, not for inner loops.
// tests/compile/cr_math_test.cpp checks crAtan2 against MPFR and against values computed at 300
// bits.
#pragma once

namespace simbob {

/// atan2(y, x) rounded once to the nearest double; zeros, infinities and NaN as C's atan2.
double crAtan2(double y, double x);
/// sin(x), cos(x), log(x) rounded once to the nearest double (MPFR); NaN, infinities and
/// log's domain as C's.
double crSin(double x);
double crCos(double x);
double crLog(double x);

}  // namespace simbob
