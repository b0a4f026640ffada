// math_bench: per-call time of libm's sin, cos, log and atan2, of simbob's correctly rounded
// crSin, crCos, crLog and crAtan2 (include/simbob/cr_math.h), and of their GNU MPFR slow path
// alone (what every call cost before Ziv's fast path; issue 44, point 4). See bench/README.md,
// "Deterministic math".
//
// Each function runs over the same 4,096 arguments of its usual domain (angles in [-pi, pi],
// log of uniform (0, 1] as the noise generator's, atan2 on [-1, 1]^2 as a hinge's quaternion),
// 15 rounds (3 for MPFR); printed: the median ns per call and its ratio to libm.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "compile/cr_detail.h"
#include "simbob/cr_math.h"

namespace {

volatile double gSink = 0;

template <class F>
double nsPerCall(const std::vector<double>& a, const std::vector<double>& b, F f, int rounds) {
  std::vector<double> t;
  for (int r = 0; r < rounds; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    double s = 0;
    for (std::size_t i = 0; i < a.size(); ++i) s += f(a[i], b[i]);
    const auto t1 = std::chrono::steady_clock::now();
    gSink = gSink + s;
    t.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / static_cast<double>(a.size()));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main() {
  constexpr std::size_t kN = 4096;
  std::mt19937_64 rng(44);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), unit(0.0, 1.0), sym(-1.0, 1.0);
  std::vector<double> ang(kN), pos(kN), ys(kN), xs(kN);
  for (std::size_t i = 0; i < kN; ++i) {
    ang[i] = angle(rng);
    pos[i] = 1.0 - unit(rng);  // (0, 1]
    ys[i] = sym(rng);
    xs[i] = sym(rng);
  }
  (void)simbob::crSin(1.0);  // the tables, made once per process
  (void)simbob::crAtan2(1.0, 2.0);
  std::printf("%-6s %10s %10s %10s %12s %12s  %s\n", "fn", "libm ns", "cr ns", "MPFR ns", "cr/libm", "MPFR/libm",
              "fallbacks");
  const auto row = [](const char* name, double libm, double cr, double mp, double fb) {
    std::printf("%-6s %10.1f %10.1f %10.1f %11.1fx %11.1fx  %.4f%%\n", name, libm, cr, mp, cr / libm, mp / libm, fb);
  };
  const auto fallbackRate = [&](auto f, const std::vector<double>& a, const std::vector<double>& b) {
    const auto f0 = simbob::cr::fallbacks();
    for (std::size_t i = 0; i < a.size(); ++i) gSink = gSink + f(a[i], b[i]);
    return 100.0 * static_cast<double>(simbob::cr::fallbacks() - f0) / static_cast<double>(a.size());
  };
  const auto one = [&](const char* name, const std::vector<double>& a, auto libm, auto cr, auto mp) {
    const auto l = [&](double x, double) { return libm(x); };
    const auto c = [&](double x, double) { return cr(x); };
    const auto m = [&](double x, double) { return mp(x); };
    row(name, nsPerCall(a, a, l, 15), nsPerCall(a, a, c, 15), nsPerCall(a, a, m, 3), fallbackRate(c, a, a));
  };
  one(
      "sin", ang, [](double x) { return std::sin(x); }, simbob::crSin, simbob::cr::sinMpfr);
  one(
      "cos", ang, [](double x) { return std::cos(x); }, simbob::crCos, simbob::cr::cosMpfr);
  one(
      "log", pos, [](double x) { return std::log(x); }, simbob::crLog, simbob::cr::logMpfr);
  const auto l2 = [](double y, double x) { return std::atan2(y, x); };
  const auto c2 = [](double y, double x) { return simbob::crAtan2(y, x); };
  const auto m2 = [](double y, double x) { return simbob::cr::atan2Mpfr(y, x); };
  row("atan2", nsPerCall(ys, xs, l2, 15), nsPerCall(ys, xs, c2, 15), nsPerCall(ys, xs, m2, 3),
      fallbackRate(c2, ys, xs));
  return 0;
}
