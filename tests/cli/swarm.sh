#!/usr/bin/env bash
# scenes/swarm.xml: 20 robots with range sensors and RCObstacleAvoiders wander for 60 s in a
# 4 m arena and never touch each other or a wall. Checked from the trajectory CSV, sampled every
# 0.01 s. Seen from above, every robot lies within three rectangles of its chassis frame: the
# chassis (x in [-0.1, 0.1], z in [-0.07, 0.07]; the caster is under it) and one per wheel
# (x in [-0.01, 0.07], |z| in [0.05, 0.13]: a sphere of 0.04 m about (0.03, +-0.09)), all upright
# (the tilt is checked below 2 degrees). Two rectangles cannot touch while a separating axis (an
# edge normal of one of them) shows a gap: the largest such gap is a lower bound on their
# distance, and two robots are apart by at least the smallest of these over their 3 x 3 pairs of
# rectangles. A robot cannot touch a
# wall while its rectangle's corners stay inside the walls' inner faces (+-(2 - 0.02) m).
# Between samples a robot moves at most 0.1 m/s x 0.01 s = 1 mm (Speed) and its corners 2.5 rad/s
# (TurnRate) x 0.15 m x 0.01 s = 3.75 mm more: so every gap must exceed 2 x 5.5 mm = 11 mm between
# robots and 5.5 mm to a wall. That they wander (rather than stand still, which would pass trivially):
# every robot travels more than 3 m.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
cli_setup "$@"

check "20 robots for 60 s: no two footprints meet, none reaches a wall, all of them move"
expect_status 0 "$SIMBOB" run "$SCENES/swarm.xml" --duration 60 --sample-interval 0.01 --out swarm.csv
/usr/bin/python3 - swarm.csv <<'PY'
import collections, csv, math, sys
HALF = 2 - 0.02
RECTS = [(-0.1, 0.1, -0.07, 0.07), (-0.01, 0.07, -0.13, -0.05), (-0.01, 0.07, 0.05, 0.13)]
at = collections.defaultdict(dict)
tilt = 0.0
for r in csv.reader(open(sys.argv[1])):
    if len(r) > 8 and r[1].endswith(".Cart.Chassis"):
        x, z = float(r[2]), float(r[4])
        qw, qx, qy, qz = (float(v) for v in r[5:9])
        fx, fz = 1 - 2 * (qy * qy + qz * qz), 2 * (qx * qz - qw * qy)  # local +X in the world
        tilt = max(tilt, abs(math.degrees(math.asin(max(-1, min(1, 2 * (qx * qy + qw * qz)))))))
        h = math.atan2(-fz, fx)
        f = (math.cos(h), -math.sin(h))  # forward on the ground (x, z)
        s = (math.sin(h), math.cos(h))   # local +Z on the ground (the robot's right)
        rects = []
        for x0, x1, z0, z1 in RECTS:
            corners = [(x + a * f[0] + b * s[0], z + a * f[1] + b * s[1])
                       for a, b in ((x0, z0), (x0, z1), (x1, z1), (x1, z0))]
            rects.append((corners, (f, s)))
        at[r[0]][r[1]] = rects + [(x, z)]


def gap(A, B):
    """Largest gap between rectangles A and B along an edge normal of either (< 0: overlap)."""
    best = -1e9
    for corners, axes in (A, B):
        for ax in axes:
            pa = [c[0] * ax[0] + c[1] * ax[1] for c in A[0]]
            pb = [c[0] * ax[0] + c[1] * ax[1] for c in B[0]]
            best = max(best, min(pa) - max(pb), min(pb) - max(pa))
    return best


times = sorted(at, key=float)
robots = sorted(at[times[0]])
assert len(robots) == 20, robots
pair, wall = (1e9, None), (1e9, None)
travel = collections.Counter()
prev = None
for t in times:
    p = at[t]
    for i, a in enumerate(robots):
        w = HALF - max(max(abs(cx), abs(cz)) for rect in p[a][:3] for cx, cz in rect[0])
        if w < wall[0]:
            wall = (w, (t, a))
        for b in robots[i + 1:]:
            # Every corner is within 0.164 m of the chassis centre: centres farther apart than
            # 2 x 0.164 m + the smallest gap so far cannot lower it.
            if math.dist(p[a][3], p[b][3]) > 0.328 + min(pair[0], 0.05):
                continue
            g = min(gap(ra, rb) for ra in p[a][:3] for rb in p[b][:3])
            if g < pair[0]:
                pair = (g, (t, a, b))
        if prev:
            travel[a] += math.dist(p[a][3], prev[a][3])
    prev = p
print(f"check: {len(times)} samples; smallest gap between two robots {pair[0] * 1000:.1f} mm at {pair[1]}; "
      f"to a wall {wall[0] * 1000:.1f} mm at {wall[1]}; least travel {min(travel.values()):.2f} m; "
      f"largest tilt {tilt:.2f} deg")
assert float(times[-1]) >= 60 - 1e-9, times[-1]
assert tilt < 2, tilt
assert pair[0] > 0.011, pair
assert wall[0] > 0.0055, wall
assert min(travel.values()) > 3, travel
PY
