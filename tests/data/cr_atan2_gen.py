#!/usr/bin/env python3
"""Writes tests/data/cr_atan2.txt: arguments of atan2 and their correctly rounded values, computed
with mpmath at 300 bits (Debian's python3-mpmath; a maintainer's tool, not run by the tests).
tests/compile/cr_math_test.cpp checks simbob's crAtan2 against every line.

Each line: y x atan2(y, x), as C99 hexadecimal floats. The arguments: the two of docs/ci.md where
glibc's FMA and generic atan2 differ, points on circles of every quadrant (a hinge's quaternion
gives atan2(|v|, w) with |v|, w <= 1), wide exponents, quotients next to the table points
k / 64 of the reduction, tiny angles, and both axes' neighbourhoods."""
import math
import random
import sys

import mpmath

mpmath.mp.prec = 300
rnd = random.Random(2811)
args = [(float.fromhex('0x1.fb234d8f2130ap-3'), float.fromhex('0x1.f00ddb41c101fp-1')),
        (float.fromhex('0x1.5d05d01551edbp-1'), float.fromhex('-0x1.769a47b6aa066p-1'))]
for _ in range(1200):
    t, r = rnd.uniform(-math.pi, math.pi), rnd.uniform(0.05, 1)
    args.append((r * math.sin(t), r * math.cos(t)))
for _ in range(600):
    args.append((rnd.choice([-1, 1]) * 2 ** rnd.uniform(-80, 80), rnd.choice([-1, 1]) * 2 ** rnd.uniform(-80, 80)))
for _ in range(600):
    k, x = rnd.randrange(65), rnd.uniform(0.5, 1)
    args.append((x * k / 64 * (1 + rnd.uniform(-1e-9, 1e-9)), rnd.choice([-1, 1]) * x))
for _ in range(300):
    args.append((rnd.uniform(0, 1e-5), rnd.uniform(0.999, 1)))
for _ in range(300):
    args.append((rnd.uniform(0.999, 1), rnd.uniform(-1e-5, 1e-5)))
args += [(1e-300, 1e300), (-1e-300, -1e300), (1e300, 1e-300), (5e-324, 1.0), (1.0, 1.0), (-1.0, -1.0),
         (1.0, -1.0), (3.0, 4.0), (-0.5, 0.8660254037844386)]
out = sys.stdout if len(sys.argv) < 2 else open(sys.argv[1], 'w')
out.write('# y x atan2(y,x) correctly rounded (mpmath, 300 bits): tests/data/cr_atan2_gen.py\n')
for y, x in args:
    out.write(f'{y.hex()} {x.hex()} {float(mpmath.atan2(mpmath.mpf(y), mpmath.mpf(x))).hex()}\n')
