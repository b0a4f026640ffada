#!/usr/bin/env python3
"""Physical expectations of the shipped example scenes (used by tests/cli/scenes.sh).

    python3 scene_expectations.py SCENE_NAME TRAJECTORY.csv

Checks what each scene's header comment promises, with tolerances loose enough for the
iterative solver but tight enough to catch a wrong frame, axis, material rule or a diverging
solver. Prints one line per check; exits 1 on the first failure. Unknown scene names pass.
"""
import collections
import csv
import math
import sys


def load(path):
    rows = collections.OrderedDict()
    for r in csv.DictReader(open(path, newline="")):
        rows.setdefault(r["body"], []).append(
            (float(r["time"]), (float(r["x"]), float(r["y"]), float(r["z"])),
             (float(r["qw"]), float(r["qx"]), float(r["qy"]), float(r["qz"]))))
    return rows


def qmul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return (w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)


def conj(q):
    return (q[0], -q[1], -q[2], -q[3])


def rotate(q, v):
    return qmul(qmul(q, (0.0,) + tuple(v)), conj(q))[1:]


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def qdist(a, b):
    """Distance of two unit quaternions, sign-insensitive."""
    return min(math.dist(a, b), math.dist(a, tuple(-x for x in b)))


class Checker:
    def __init__(self, scene, rows):
        self.scene = scene
        self.rows = rows

    def body(self, key):
        if key not in self.rows:
            self.fail(f"no body {key!r} in the trajectory (bodies: {list(self.rows)})")
        return self.rows[key]

    def at(self, key, t):
        """The sample of body `key` nearest to time t."""
        return min(self.body(key), key=lambda r: abs(r[0] - t))

    def fail(self, msg):
        print(f"FAIL: {self.scene}: {msg}")
        sys.exit(1)

    def near(self, what, value, expected, tol):
        print(f"check: {self.scene}: {what} = {value:.6g} (expected {expected:.6g} +- {tol:g})")
        if not abs(value - expected) <= tol:
            self.fail(f"{what} is {value!r}, expected {expected!r} +- {tol!r}")

    def below(self, what, value, limit):
        print(f"check: {self.scene}: {what} = {value:.6g} (at most {limit:g})")
        if not value <= limit:
            self.fail(f"{what} is {value!r}, above {limit!r}")

    def above(self, what, value, limit):
        print(f"check: {self.scene}: {what} = {value:.6g} (at least {limit:g})")
        if not value >= limit:
            self.fail(f"{what} is {value!r}, below {limit!r}")


def pendulum(c):
    bob = c.body("Pendulum.Hinge.Bob")
    pivot = (0.0, 2.0, 0.0)
    c.below("largest deviation of the rod length from 1 m",
            max(abs(math.dist(p, pivot) - 1.0) for _, p, _ in bob), 2e-3)
    c.below("highest bob position (released at y = 1.134 m)", max(p[1] for _, p, _ in bob), 1.134 + 2e-3)
    # The bob is at its lowest point (x = 0, moving towards -X) a quarter period after release.
    crossing = next(t for (t, p, _), (_, q, _) in zip(bob, bob[1:]) if p[0] > 0 >= q[0])
    c.near("first swing through the bottom (quarter period, s)", crossing, 2.006 * 1.017 / 4, 0.02)


def box_stack(c):
    for k in range(5):
        key = f"Box{k}"
        for t in (2.0, 10.0):
            _, p, q = c.at(key, t)
            c.near(f"{key} height at t={t:g}", p[1], 0.1 + 0.2 * k, 3e-3)
            c.below(f"{key} horizontal drift at t={t:g}", math.hypot(p[0], p[2]), 5e-3)
            c.below(f"{key} rotation at t={t:g}", qdist(q, (1, 0, 0, 0)), 5e-3)
    ball = c.body("Ball")
    c.above("lowest ball centre (radius 0.1, on the ground)", min(p[1] for _, p, _ in ball), 0.099)
    c.near("ball x at t=0.5 (rolling at 2 m/s)", c.at("Ball", 0.5)[1][0], 0.0, 0.01)
    c.above("farthest ball x (touches the wall x = 2 at x = 1.9)", max(p[0] for _, p, _ in ball), 1.85)
    c.below("farthest ball x (cannot pass the wall)", max(p[0] for _, p, _ in ball), 1.9 + 5e-3)
    c.below("ball x at t=3 (rolled back from the wall)", c.at("Ball", 3.0)[1][0], 1.5)
    c.below("ball drift in z", max(abs(p[2] - 1.0) for _, p, _ in ball), 0.01)


def chain(c):
    keys = list(c.rows)
    c.near("links", len(keys), 5, 0)
    anchor = (0.0, 2.0, 0.0)
    gap = reach = 0.0
    for s in range(len(c.rows[keys[0]])):
        prev = anchor
        for k in keys:
            _, p, q = c.rows[k][s]
            gap = max(gap, math.dist(add(p, rotate(q, (-0.1, 0, 0))), prev))
            prev = add(p, rotate(q, (0.1, 0, 0)))
            reach = max(reach, math.dist(prev, anchor))
    c.below("largest gap at a hinge (m)", gap, 5e-3)
    c.below("farthest chain point from the anchor (m)", reach, 1.0 + 5e-3)
    mean_y = [sum(c.rows[k][s][1][1] for k in keys) / 5 for s in range(len(c.rows[keys[0]]))]
    c.below("highest mean link height (energy is not gained)", max(mean_y), 2.0 + 2e-3)
    c.below("lowest point of the last link centre (the chain swings down)",
            min(p[1] for _, p, _ in c.rows[keys[-1]]), 1.3)
    c.below("largest |z| of any link (swings in the X-Y plane)",
            max(abs(p[2]) for k in keys for _, p, _ in c.rows[k]), 1e-3)


def imported_bodies(c):
    c.near("Rolling.Wheel x at t=10 (1 m/s from x=-3)", c.at("Rolling.Wheel", 10)[1][0], 7.0, 0.05)
    c.near("Rolling.Wheel y at t=10", c.at("Rolling.Wheel", 10)[1][1], 0.2, 3e-3)
    v = (c.at("Spinning.Wheel", 10)[1][0] - c.at("Spinning.Wheel", 5)[1][0]) / 5
    c.near("Spinning.Wheel speed after the slip (w0 r / 3)", v, 1.0, 0.05)
    c.near("Spinning.Wheel z at t=10 (slight turn while slipping)", c.at("Spinning.Wheel", 10)[1][2], 1.5, 0.2)
    c.near("Spinning.Wheel y at t=10", c.at("Spinning.Wheel", 10)[1][1], 0.2, 3e-3)
    c.near("Lying.Wheel height at rest (half its width)", c.at("Lying.Wheel", 10)[1][1], 0.04, 3e-3)
    c.below("Lying.Wheel turning between t=5 and t=10",
            qdist(c.at("Lying.Wheel", 5)[2], c.at("Lying.Wheel", 10)[2]), 1e-3)
    c.near("Lying.Wheel x at rest", c.at("Lying.Wheel", 10)[1][0], 0.0, 0.01)


def mechanisms(c):
    axis = (math.cos(math.radians(30)), -math.sin(math.radians(30)), 0.0)
    car = c.body("Slide.Slider.Carriage")
    p0, q0 = car[0][1], car[0][2]
    off = max(math.dist(sub(p, p0), tuple(sum(a * b for a, b in zip(sub(p, p0), axis)) * x for x in axis))
              for _, p, _ in car)
    c.below("carriage distance from its rail axis", off, 1e-4)
    c.below("carriage rotation", max(qdist(q, q0) for _, _, q in car), 1e-4)
    along = lambda t: sum(a * b for a, b in zip(sub(c.at("Slide.Slider.Carriage", t)[1], p0), axis))
    c.near("carriage travel at t=0.5 (g sin30 t^2 / 2)", along(0.5), 0.5 * 9.81 * 0.5 * 0.25, 0.01)
    c.near("carriage travel at rest against the stop", along(10), 1.35, 0.01)
    bob = c.body("Conical.Socket.Bob")
    c.below("bob distance from the pivot - 1 m", max(abs(math.dist(p, (0, 2.5, -2)) - 1) for _, p, _ in bob), 2e-3)
    c.near("lowest bob height (conical: constant)", min(p[1] for _, p, _ in bob), 1.7, 0.01)
    c.near("highest bob height (conical: constant)", max(p[1] for _, p, _ in bob), 1.7, 0.01)
    c.near("bob x half a revolution later (t=0.9 s)", c.at("Conical.Socket.Bob", 0.9)[1][0], -0.6, 0.02)
    a, b = c.body("Bent.A"), c.body("Bent.Fix.B")

    def rel(i):
        qa = a[i][2]
        return rotate(conj(qa), sub(b[i][1], a[i][1])), qmul(conj(qa), b[i][2])

    rp0, rq0 = rel(0)
    c.near("initial angle between the fixed bars (deg)", math.degrees(2 * math.acos(min(1, abs(rq0[0])))), 45, 0.01)
    c.below("change of B's position relative to A (m)", max(math.dist(rel(i)[0], rp0) for i in range(len(a))), 1e-3)
    c.below("change of B's orientation relative to A", max(qdist(rel(i)[1], rq0) for i in range(len(a))), 1e-3)
    c.near("bar A height at rest (lying on its 0.1 m face)", c.at("Bent.A", 10)[1][1], 0.05, 3e-3)
    c.below("bent arm motion between t=5 and t=10", math.dist(c.at("Bent.A", 5)[1], c.at("Bent.A", 10)[1]), 1e-3)
    for key, x, z in (("Rod", None, 2.0), ("RodCopy", -0.5, 3.0)):
        _, p, q = c.at(key, 10)
        c.near(f"{key} height at rest (its radius)", p[1], 0.05, 3e-3)
        c.near(f"{key} z at rest", p[2], z, 0.01)
        if x is not None:
            c.near(f"{key} x at rest", p[0], x, 0.01)
        # Lying flat: the rod's local Z axis is horizontal.
        c.below(f"{key} axis tilt at rest", abs(rotate(q, (0, 0, 1))[1]), 1e-2)


def bounce(c):
    for key, e in (("Dull", 0.2), ("Medium", 0.5), ("Lively", 0.9)):
        rows = c.body(key)
        peak = max(p[1] for t, p, _ in rows if 0.46 < t < 0.46 + 2 * e * 0.4515 + 0.05)
        c.near(f"{key} first rebound height (e^2 of 1 m)", peak - 0.1, e * e, max(0.01, 0.05 * e * e))
        c.near(f"{key} height at rest", rows[-1][1][1], 0.1, 2e-3)
        c.below(f"{key} sideways motion", max(math.hypot(p[0] - rows[0][1][0], p[2]) for _, p, _ in rows), 1e-6)


def robot(c):
    for key in c.rows:
        _, p1, q1 = c.at(key, 1.0)
        moved = max(math.dist(p, p1) for t, p, _ in c.rows[key] if t >= 1.0)
        turned = max(qdist(q, q1) for t, _, q in c.rows[key] if t >= 1.0)
        c.below(f"{key} motion after settling (m)", moved, 1e-4)
        c.below(f"{key} rotation after settling", turned, 1e-3)
    _, p, q = c.at("Bot.Cart.Chassis", 10)
    c.near("chassis height", p[1], 0.12, 2e-3)
    c.below("chassis tilt", qdist(q, (1, 0, 0, 0)), 2e-3)
    for key in ("Bot.Cart.LeftAxle.LeftWheel", "Bot.Cart.RightAxle.RightWheel"):
        c.near(f"{key} height (its radius)", c.at(key, 10)[1][1], 0.1, 2e-3)
    c.near("caster ball height (its radius)", c.at("Bot.Cart.CasterSocket.CasterBall", 10)[1][1], 0.04, 2e-3)


def turned(q0, q, axis):
    """Angle (rad) of the rotation from q0 to q about a global axis (0: X, 1: Y, 2: Z), in (-pi, pi]."""
    r = qmul(q, conj(q0))
    return 2 * math.atan2(r[1 + axis], r[0])


def unwrap(angles):
    out, turns = [], 0.0
    for i, a in enumerate(angles):
        if i:
            d = a - angles[i - 1]
            if d > math.pi:
                turns -= 2 * math.pi
            elif d < -math.pi:
                turns += 2 * math.pi
        out.append(a + turns)
    return out


def flywheel(c):
    rows = c.body("Bot.Base.Axle.Wheel")
    q0 = rows[0][2]
    theta = unwrap([turned(q0, q, 1) for _, _, q in rows])
    # theta(t) = (P / I) / w * (t - sin(w t) / w), w = 2 pi Variation / 60 = pi, P = pi/2, I = 1.
    law = lambda t: 0.5 * (t - math.sin(math.pi * t) / math.pi)
    for t in (1.0, 2.0, 5.0, 10.0):
        i = min(range(len(rows)), key=lambda k: abs(rows[k][0] - t))
        c.near(f"flywheel angle at t={t:g} (integral of the sine torque)", theta[i], law(t), 0.01 * law(t))
    c.below("largest deviation from the law over the run (rad)",
            max(abs(a - law(t)) for (t, _, _), a in zip(rows, theta)), 0.03)
    c.below("axle drift (m)", max(math.dist(p, (0, 1, 0)) for _, p, _ in rows), 1e-6)


def servo_arm(c):
    rows = c.body("Bot.Base.Joint.Arm")
    q0 = rows[0][2]
    angle = [turned(q0, q, 2) for _, _, q in rows]
    c.below("largest arm angle (MaxPos 1 rad)", max(angle), 1.0 + 1e-3)
    c.above("smallest arm angle (MinPos -1 rad)", min(angle), -1.0 - 1e-3)

    def target(t):
        f = (t * 6 / 60) % 1.0
        return -1 + 2 * (2 * f if f < 0.5 else 2 - 2 * f)
    # After the start (the arm begins at 0, the target at MinPos) it follows the triangle about
    # speed x Smooth = 0.04 rad behind; near the turns the lag cuts the corner by as much.
    lag = max(abs(a - target(t)) for (t, _, _), a in zip(rows, angle) if t >= 2.0)
    c.below("largest distance from the target after 2 s (rad)", lag, 0.06)
    c.near("arm angle at t=5 (target turns at MaxPos)", angle[min(range(len(rows)), key=lambda k: abs(rows[k][0] - 5))],
           1.0, 0.05)
    c.below("pivot drift (m)", max(abs(math.dist(p, (0, 1, 0)) - 0.25) for _, p, _ in rows), 1e-3)


def two_wheel_robot(c):
    rows = c.body("Bot.Cart.Chassis")
    x = lambda t: c.at("Bot.Cart.Chassis", t)[1][0]
    c.near("forward between 1 s and 2 s (v = 0.2 m/s)", x(2) - x(1), 0.2, 2e-3)
    q0 = rows[0][2]
    yaw = lambda t: turned(q0, c.at("Bot.Cart.Chassis", t)[2], 1)
    c.near("heading gained between 3 s and 4 s (w = 0.5 rad/s)", yaw(4) - yaw(3), 0.5, 1e-3)
    c.below("motion after the stop (4.5 s to 10 s, m)", math.dist(c.at("Bot.Cart.Chassis", 4.5)[1],
                                                                   c.at("Bot.Cart.Chassis", 10)[1]), 1e-3)


def wall_stop_robot(c):
    rows = c.body("Bot.Cart.Chassis")
    front = max(p[0] for _, p, _ in rows) + 0.2
    c.near("chassis front's gap to the wall at x = 1.4 when stopped (m)", 1.4 - front, 0.095, 0.005)
    c.below("motion over the last 2 s (m)", math.dist(c.at("Bot.Cart.Chassis", 8)[1], rows[-1][1]), 1e-4)
    c.below("sideways drift (m)", max(abs(p[2]) for _, p, _ in rows), 1e-4)


def sliding_box(c):
    # v0 = 2 m/s, mu = 0.5: stops at v0^2 / (2 mu g) = 0.408 m after v0 / (mu g) = 0.41 s; the
    # stop comes within one 1 ms step (v0 h = 2 mm).
    want = 2.0**2 / (2 * 0.5 * 9.81)
    _, p, q = c.at("Crate", 10)
    c.near("stopping distance v0^2/(2 mu g)", p[0], want, 0.005 * want + 0.002)
    c.near("height (half its 0.1 m)", p[1], 0.05, 1e-3)
    c.below("sideways drift", abs(p[2]), 1e-4)
    _, p1, _ = c.at("Crate", 1.0)
    c.below("at rest after 0.41 s", math.dist(p, p1), 1e-4)


def socket_robot(c):
    # Driven by scripts/simbob_client.py: 0.2 m/s for 2 s, then a proportional turn on the spot
    # to a heading of pi/2 (counter-clockwise about +Y). The wheels' axle midpoint sits 0.1 m
    # ahead of the chassis centre, so the turn moves the centre to axle + R(pi/2) (-0.1, 0, 0).
    def heading(q):
        w, x, y, z = q
        return math.atan2(-2 * (x * z - w * y), 1 - 2 * (y * y + z * z))

    _, p2, q2 = c.at("Bot.Cart.Chassis", 2.0)
    c.near("chassis x after 2 s at 0.2 m/s (m)", p2[0], 0.4, 0.02)
    c.near("heading after the straight leg (rad)", heading(q2), 0.0, 0.01)
    _, p, q = c.at("Bot.Cart.Chassis", 10.0)
    c.near("heading at the end (rad)", heading(q), math.pi / 2, 0.02)
    axle = p2[0] + 0.1
    c.near("chassis x after the turn (m)", p[0], axle, 0.02)
    c.near("chassis z after the turn (m)", p[2], 0.1, 0.02)
    c.near("chassis height", p[1], 0.12, 2e-3)


def gallery(c):
    # The ball rolls without slipping (v = w r from the start, no rolling resistance): x = -3 + t
    # until it reaches the sandbox wall at x = 6 - 0.3 m (t = 8.7 s); the rod rests on the ground.
    for t in (2.0, 5.0):
        _, p, _ = c.at("Ball", t)
        c.near(f"ball x at t = {t} s (m)", p[0], -3 + t, 0.05)
        c.near(f"ball height at t = {t} s (m)", p[1], 0.3, 0.01)
    _, p, _ = c.at("Rod", 10)
    c.near("rod height at t = 10 s (m)", p[1], 0.1, 0.01)


def go_to_point_robot(c):
    # RCSimGoToPoint stops for good once the chassis centre is within Tolerance (0.05 m) of the
    # target (1, -1); the last command may be up to one Period (0.01 s) old at Speed 0.3 m/s.
    # The braking distance of the velocity drives (MaxPower 5 N m) is well below 1 mm.
    rows = c.body("Bot.Cart.Chassis")
    end = rows[-1][1]
    c.below("distance to the target (1, -1) at the end (m)", math.hypot(end[0] - 1, end[2] + 1), 0.05 + 0.3 * 0.01)
    c.below("motion over the last 4 s (m)", math.dist(c.at("Bot.Cart.Chassis", 6)[1], end), 1e-4)
    # It got there, rather than starting near: it covered most of the 1.41 m.
    c.below("distance to the target after 2 s, less than at the start (m)",
            math.hypot(c.at("Bot.Cart.Chassis", 2)[1][0] - 1, c.at("Bot.Cart.Chassis", 2)[1][2] + 1), 1.0)


KR5 = "Bot.kr5."
KR5_LINKS = ("shoulder", "bicep", "elbow", "forearm", "wrist", "palm")


def kr5(c):
    # Position drives hold every joint at 0 for 5 s: no link frame moves more than 1 mm.
    for link in KR5_LINKS:
        rows = c.body(KR5 + link)
        c.below(f"{link} frame's largest displacement over 0-5 s (m)",
                max(math.dist(p, rows[0][1]) for t, p, _ in rows if t <= 5.0), 1e-3)
    c.below("base_link frame (fixed to the world) displacement (m)",
            max(math.dist(p, c.body(KR5 + "base_link")[0][1]) for _, p, _ in c.body(KR5 + "base_link")), 0.0)
    # At 5 s shoulder_yaw is commanded 0.8 rad about the arm's vertical axis (the scene's +Y):
    # at 6.545 rad/s to within 0.33 rad, then as exp(-t / 0.05 s): there by 6 s, held to 10 s.
    q0 = c.body(KR5 + "shoulder")[0][2]
    for t in (6.0, 8.0, 10.0):
        c.near(f"shoulder turned about Y at t = {t} s (rad)", turned(q0, c.at(KR5 + "shoulder", t)[2], 1), 0.8, 2e-3)
    # Halfway through the fast phase it is still on its way: the law, not a jump.
    c.near("shoulder turned about Y at t = 5.05 s (rad)", turned(q0, c.at(KR5 + "shoulder", 5.05)[2], 1),
           6.545 * 0.05, 0.03)


def drchubo(c):
    # Dropped with passive joints: it lands and collapses; nothing sinks into the ground and,
    # by the end, everything has come to rest (the CSV check already refused NaN; a joint
    # coming apart would have failed the run).
    lowest = min(p[1] for rows in c.rows.values() for _, p, _ in rows)
    c.above("lowest link frame over the run (m)", lowest, -0.05)
    torso = c.body("drchubo.Body_Torso")
    c.below("torso height at the end, collapsed (m)", torso[-1][1][1], 0.6)
    c.below("torso motion over the last second (m)", math.dist(c.at("drchubo.Body_Torso", 9)[1], torso[-1][1]), 0.05)


def mesh_drop(c):
    # The slider slides down the 30 degree ramp (mu 0.3) at a = g (sin 30 - 0.3 cos 30) from rest:
    # s = a t^2 / 2 along the slope after t. It starts 0.5 mm above the slope (a 10 ms fall, 1 mm
    # less slid); ODE's friction pyramid and contact softness keep it within 5 mm of that.
    a = 9.81 * (0.5 - 0.3 * math.cos(math.radians(30)))
    _, p0, q0 = c.at("Slider", 0.0)
    _, p, q = c.at("Slider", 0.6)
    s = 0.5 * a * 0.6**2
    c.near("slider x after 0.6 s on the slope (m)", p[0] - p0[0], s * math.cos(math.radians(30)), 0.005)
    c.near("slider drop after 0.6 s on the slope (m)", p0[1] - p[1], s * math.sin(math.radians(30)), 0.005)
    c.below("slider turn on the slope (it slides flat)", qdist(q, q0), 0.005)
    # The cube (an STL hull), the crate (COLLADA, cm, Z up) and the pyramid land upright on their
    # feet: the cube's centre at half its 0.1 m, the others' origins (on their feet) at 0.
    for key, y in (("Cube", 0.05), ("Crate", 0.0), ("Pyramid", 0.0)):
        _, p, q = c.at(key, 10)
        c.near(f"{key} height at rest (m)", p[1], y, 1e-3)
        c.below(f"{key} tilt at rest", qdist(q, (1, 0, 0, 0)), 5e-3)


SCENES = {f.__name__: f for f in (mesh_drop, pendulum, box_stack, chain, imported_bodies, mechanisms, bounce, robot, flywheel,
                                  servo_arm, two_wheel_robot, wall_stop_robot, sliding_box, socket_robot, gallery,
                                  go_to_point_robot, kr5, drchubo)}

if __name__ == "__main__":
    name, path = sys.argv[1], sys.argv[2]
    if name not in SCENES:
        print(f"check: {name}: no physical expectations recorded")
        sys.exit(0)
    SCENES[name](Checker(name, load(path)))
