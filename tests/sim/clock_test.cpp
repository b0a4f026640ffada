// The clock without physics: time conversion and the order in which requests are granted.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "simbob/clock.h"

using namespace simbob;

TEST_CASE("clock: toSimTime rounds to the nearest nanosecond", "[sim][clock]") {
  CHECK(toSimTime(0.0) == SimTime{0});
  CHECK(toSimTime(1.5) == SimTime{1500000000});
  CHECK(toSimTime(0.001) == SimTime{1000000});
  CHECK(toSimTime(1e-9) == SimTime{1});
  CHECK(toSimTime(0.4e-9) == SimTime{0});
  CHECK(toSimTime(0.6e-9) == SimTime{1});
  CHECK(toSimTime(-0.25) == SimTime{-250000000});
  CHECK(toSimTime(1e9) == SimTime{1000000000000000000});  // the CLI's largest --duration
}

TEST_CASE("clock: toSimTime refuses what does not fit instead of wrapping", "[sim][clock]") {
  // SimTime holds +-2^63 ns = +-9.223372036854775808e9 s.
  CHECK(toSimTime(9.2e9) == SimTime{9200000000000000000});
  CHECK(toSimTime(-9.2e9) == SimTime{-9200000000000000000});
  CHECK_FALSE(toSimTime(9.223372036854775808e9).has_value());  // exactly 2^63 ns
  CHECK_FALSE(toSimTime(-9.223372036854775808e9).has_value());
  CHECK_FALSE(toSimTime(1e10).has_value());
  CHECK_FALSE(toSimTime(-1e300).has_value());
  CHECK_FALSE(toSimTime(std::numeric_limits<double>::infinity()).has_value());
  CHECK_FALSE(toSimTime(-std::numeric_limits<double>::infinity()).has_value());
  CHECK_FALSE(toSimTime(std::numeric_limits<double>::quiet_NaN()).has_value());
  // The largest double below 2^63 ns converts exactly.
  const double below = std::nextafter(9.223372036854775808e18, 0.0);
  REQUIRE(toSimTime(below / 1e9).has_value());
  CHECK(*toSimTime(below / 1e9) > SimTime{9223372036854770000});
}

TEST_CASE("clock: due requests are granted earliest first, ties to the first party", "[sim][clock]") {
  Clock c(1000, 10);  // a grid of 1000 ns; within 10 ns counts as reached
  const int a = c.addParty(5);
  const int b = c.addParty(0);
  const int d = c.addParty(0);
  const int never = c.addParty(kNever);
  CHECK(never == 3);
  CHECK(c.grantable() == b);  // 0 before 5; b before d (list order)
  c.granted(b, 2000);
  CHECK(c.grantable() == d);
  c.granted(d, 2000);
  CHECK(c.grantable() == a);  // 5 ns away: within MinTimeStep
  c.granted(a, 2000);
  CHECK(c.grantable() == -1);
  CHECK_FALSE(c.reached(2000));
  c.advance();
  CHECK(c.now() == 1000);
  CHECK(c.grantable() == -1);
  c.advance();
  CHECK(c.now() == 2000);
  CHECK(c.steps() == 2);
  CHECK(c.reached(2000));
  CHECK(c.grantable() == a);  // all three at 2000: list order
  c.granted(a, kNever);
  CHECK(c.grantable() == b);
  c.granted(b, kNever);
  CHECK(c.grantable() == d);
  c.granted(d, kNever);
  CHECK(c.grantable() == -1);
}

TEST_CASE("clock: a request between grid instants is granted at the next one, never splitting a step", "[sim][clock]") {
  Clock c(1000, 10);
  const int a = c.addParty(1500);  // between the 1000 and 2000 ns instants
  const int b = c.addParty(2995);  // 5 ns before the 3000 ns instant: granted there
  const int e = c.addParty(3995);  // within MinTimeStep of 4000 from below: granted at 4000
  CHECK(c.grantable() == -1);
  c.advance();
  CHECK(c.grantable() == -1);  // 1000 < 1500 - 10
  c.advance();
  CHECK(c.now() == 2000);
  CHECK(c.grantable() == a);
  c.granted(a, kNever);
  c.advance();
  CHECK(c.grantable() == b);
  c.granted(b, kNever);
  c.advance();
  CHECK(c.grantable() == e);
  c.granted(e, kNever);
  // gridInstant says the same without a clock.
  CHECK(gridInstant(1500, 1000, 10) == 2000);
  CHECK(gridInstant(2995, 1000, 10) == 3000);
  CHECK(gridInstant(3000, 1000, 10) == 3000);
  CHECK(gridInstant(3005, 1000, 10) == 3000);  // MinTimeStep after an instant still counts as it
  CHECK(gridInstant(3011, 1000, 10) == 4000);
  CHECK(gridInstant(0, 1000, 10) == 0);
  CHECK(gridInstant(kNever, 1000, 10) == kNever);
  CHECK(gridInstant(kNever - 1, 1000, 0) == kNever);  // the instant after does not fit
  // 30 fps on a 1 ms grid: frame 1 (33333333 ns) shows 34 ms, frame 3 (1e8 ns) 100 ms.
  CHECK(gridInstant(33333333, 1000000, 1000) == 34000000);
  CHECK(gridInstant(99999999, 1000000, 1000) == 100000000);
}

TEST_CASE("clock: a party asking again within MinTimeStep waits for the next step", "[sim][clock]") {
  Clock c(1000, 10);
  const int a = c.addParty(0);
  const int b = c.addParty(500);
  REQUIRE(c.grantable() == a);
  c.granted(a, 3);  // within 10 ns of now: not again at this instant
  CHECK(c.grantable() == -1);
  c.advance();
  CHECK(c.grantable() == a);  // 3 ns is past: a first (earliest), then b
  c.granted(a, kNever);
  CHECK(c.grantable() == b);
  // A request in the past is granted after the next step too, never twice at one instant.
  c.granted(b, 100);
  CHECK(c.grantable() == -1);
  c.advance();
  CHECK(c.now() == 2000);
  CHECK(c.grantable() == b);
}
