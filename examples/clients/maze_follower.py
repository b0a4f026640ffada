#!/usr/bin/python3
"""A left-wall follower for scenes/maze_socket.xml over socket protocol version 3, through
python/simbob_client.py; examples/clients/maze_follower.c is the same program in C.

    simbob run scenes/maze_socket.xml --duration 60      # simbob starts it (the Controller)

At each exchange it reads the laser scanner's N ranges (the hello's first `scanner` sensor: a
360-degree scan whose ray k has the bearing b_k = -180 + k 360 / N degrees from the robot's
forward axis, counter-clockwise seen from above, as the maze's scanner is mounted) and sets the
first motion control (linear m/s, angular rad/s) with the law of RCWallFollower (docs/sensors.md),
wall on the left at DISTANCE:
    side distance  d = min r_k over the rays with 45 <= b_k <= 170 degrees
    front distance g = min r_k cos b_k over the rays with |b_k| < 25 degrees
    e = d - DISTANCE, e' = clamp((e - e_last) / Period, -SPEED, SPEED) (0 at the first reading)
    a wall ahead (g < 1.5 DISTANCE): v = SPEED clamp((g - DISTANCE) / DISTANCE, 0, 1), w = -TURN
    else: v = SPEED, w = clamp(W^2 / SPEED e + 2 W / SPEED e', -TURN, TURN), W = 2 SPEED / DISTANCE
The rays are chosen with integer arithmetic and every number is computed with the same float64
operations in the same order as in maze_follower.c (cos from the C library in both), so both
send the same commands and the run gives the same trajectory bytes (tests/cli/clients.sh).
It subscribes to the scanner only (no bodies, no joints). It prints the number of exchanges at
the end (to the controller log).
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from simbob_client import Client, SimbobError  # noqa: E402

DISTANCE = 0.25  # m from the wall on the left
SPEED = 0.2  # m/s
TURN = 2.0  # rad/s


class Follower:
    def __init__(self, n, period):
        self.period = period
        # Bearing of ray k in degrees times n: k 360 - 180 n (integers, exact).
        self.side = [k for k in range(n) if 45 * n <= k * 360 - 180 * n <= 170 * n]
        self.front = [k for k in range(n) if abs(k * 360 - 180 * n) < 25 * n]
        self.front_cos = [math.cos(float(k * 360 - 180 * n) * math.pi / float(180 * n)) for k in self.front]
        self.last_e = 0.0
        self.first = True

    def command(self, r):
        d = math.inf
        for k in self.side:
            d = min(d, r[k])
        g = math.inf
        for k, c in zip(self.front, self.front_cos):
            g = min(g, r[k] * c)
        e = d - DISTANCE
        de = 0.0 if self.first else max(-SPEED, min(SPEED, (e - self.last_e) / self.period))
        self.first = False
        self.last_e = e
        if g < 1.5 * DISTANCE:
            return SPEED * max(0.0, min(1.0, (g - DISTANCE) / DISTANCE)), -TURN
        wn = 2.0 * SPEED / DISTANCE
        return SPEED, max(-TURN, min(TURN, wn * wn / SPEED * e + 2.0 * wn / SPEED * de))


def main():
    try:
        c = Client.connect()
        scanner = next(key for key, (kind, _) in c.sensors.items() if kind == "scanner")
        motion = c.motions[0]
        follower = Follower(c.sensors[scanner][1], c.period)
        subscribe = {"bodies": [], "joints": [], "sensors": [scanner]}
        steps = 0
        while (s := c.state()) is not None:
            linear, angular = follower.command(s.sensors[scanner])
            c.reply(sets=[(motion, linear, angular)], subscribe=subscribe)
            subscribe = None
            steps += 1
    except SimbobError as e:
        sys.exit(f"maze_follower.py: {e}")
    print(f"maze_follower.py: the run ended at t={c.ended:g} s after {steps} exchanges", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
