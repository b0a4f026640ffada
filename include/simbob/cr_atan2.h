// A correctly rounded atan2: the same bits on every x86-64 CPU and libm.
//
// glibc's atan2 is not correctly rounded, and its CPU-specific variants (FMA and generic) round a
// few arguments differently. A hinge angle is 2 atan2(|v|, w) of the joint's relative quaternion;
// where a servo law or a joint stop uses that angle in full precision, the differing last bit
// reaches the trajectory (docs/ci.md, "Hinge angles and libm's atan2"). simbob reads hinge angles
// through crAtan2 instead: double-double arithmetic built from IEEE additions, multiplications and
// divisions alone (simbob compiles with -ffp-contract=off), so the result depends on nothing but
// the arguments, and it is the correctly rounded value of atan2(y, x) (tests/compile/
// cr_atan2_test.cpp checks it against values computed at 300 bits).
#pragma once

namespace simbob {

/// atan2(y, x) rounded once to the nearest double; zeros, infinities and NaN as C's atan2.
double crAtan2(double y, double x);

}  // namespace simbob
