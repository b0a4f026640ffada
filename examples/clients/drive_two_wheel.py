#!/usr/bin/python3
"""The example peer of scenes/socket_robot.xml through python/simbob_client.py (protocol version 3):
the control law of scripts/simbob_client.py, so it drives the robot to the same trajectory bytes.

    simbob run scenes/socket_robot.xml --duration 10 \\
        --controller "Bot.Cart.Link=/usr/bin/python3 examples/clients/drive_two_wheel.py"

`drive_two_wheel.py probe` prints what the conformance test (tests/cli/clients.sh) compares
between clients.
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from simbob_client import Client, SimbobError  # noqa: E402


def heading(q):
    """Rotation about +Y (rad, counter-clockwise seen from above) of a body whose forward is +X."""
    w, x, y, z = q
    fx = 1 - 2 * (y * y + z * z)
    fz = 2 * (x * z - w * y)
    return math.atan2(-fz, fx)


def probe(c):
    print(f"version {c.version}\nkey {c.key}")
    for m in c.motions:
        print("motion", m)
    for b in c.bodies:
        print("body", b)
    for key, (kind, n) in c.sensors.items():
        print("sensor", key, kind, n)
    c.state()
    c.reply(sets=[(c.motions[0], 0.5, 0.0)], subscribe={"bodies": [c.bodies[0]], "joints": []})
    s = c.state()
    print(f"t {s.t:.3f}")
    for key, v in s.bodies.items():
        print(f"state body {key} {len(v)} moving {int(v[7] > 0.01)}")
    for key in s.joints:
        print("state joint", key)
    c.reply(done=True)
    print("end")


def main():
    try:
        c = Client.connect()
        if sys.argv[1:] == ["probe"]:
            return probe(c)
        motion, body, steps = c.motions[0], c.bodies[0], 0
        while (s := c.state()) is not None:
            if s.t < 2.0:
                linear, angular = 0.2, 0.0
            else:
                linear, angular = 0.0, max(-1.0, min(1.0, 2.0 * (math.pi / 2 - heading(s.bodies[body][3:7]))))
            c.reply(sets=[(motion, linear, angular)])
            steps += 1
    except SimbobError as e:
        sys.exit(f"drive_two_wheel.py: {e}")
    print(f"drive_two_wheel.py: the run ended at t={c.ended:g} s after {steps} exchanges", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
