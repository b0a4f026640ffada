"""Tests of `import simbob` (python/simbob_module.cpp), run by ctest as python.pytest:

    PYTHONPATH=build/python /usr/bin/python3 -m pytest -q python/tests

Physics is checked against analytic answers; stepping from Python is checked against the
bytes `simbob run` writes.
"""

import csv
import math
import os
import subprocess
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import simbob

ROOT = Path(os.environ.get("SIMBOB_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BINARY = Path(os.environ.get("SIMBOB_BINARY", ROOT / "build" / "simbob"))
SCENES = ROOT / "scenes"
G = 9.81


def ball_scene(y0=10.0, vy0=0.0, extra=""):
    """A 1 kg ball at height y0 with vertical speed vy0, no ground: nothing but gravity."""
    return f"""<?xml version="1.0" encoding="UTF-8"?>
<Simulation>
  <SceneSettings><MaxTimeStep Value="0.001"/>{extra}</SceneSettings>
  <ComponentList>
    <RCMobileRigidBody Key="Ball">
      <Pose><RCGlobalCoordinates><Pose Value="0 {y0!r} 0 0 0 0"/></RCGlobalCoordinates></Pose>
      <Motion><RCGlobalMotion><LinVelocity Value="0 {vy0!r} 0"/></RCGlobalMotion></Motion>
      <Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom>
      <Inertia><RCInertiaByGeom><Mass Value="1"/></RCInertiaByGeom></Inertia>
    </RCMobileRigidBody>
  </ComponentList>
</Simulation>
"""


def cli_samples(tmp_path, scene, *args):
    """`simbob run SCENE --duration 2 ARGS` -> [(time, {body: [x y z qw qx qy qz]})], floats
    parsed from the CSV's shortest round-trip decimals (so exactly the doubles written)."""
    out = tmp_path / (Path(scene).stem + "_" + str(abs(hash(args))) + ".csv")
    subprocess.run([str(BINARY), "run", str(scene), "--duration", "2", "--out", str(out), "--quiet", *args],
                   check=True)
    samples = []
    with open(out, newline="") as f:
        rows = csv.reader(f)
        assert next(rows) == ["time", "body", "x", "y", "z", "qw", "qx", "qy", "qz"]
        for row in rows:
            t = float(row[0])
            if not samples or samples[-1][0] != t:
                samples.append((t, {}))
            samples[-1][1][row[1]] = [float(v) for v in row[2:]]
    return samples


def step_to(sim, t):
    """Steps one step at a time until sim.time reaches t (a CSV sample time)."""
    while sim.time < t:
        sim.step()
    assert sim.time == t


# ---- analytic physics ----

def test_free_fall_is_semi_implicit_euler_to_1e_12():
    # ODE integrates v_{n+1} = v_n - g h, then y_{n+1} = y_n + h v_{n+1} (semi-implicit Euler),
    # so y_n = y0 - g h^2 (1 + 2 + ... + n) = y0 - g h^2 n (n + 1) / 2 exactly, up to rounding.
    sim = simbob.Simulation.from_text(ball_scene(), "fall.xml")
    h = sim.dt
    assert h == 0.001
    assert sim.body_keys == ["Ball"]
    worst = 0.0
    for n in range(1, 1001):
        sim.step()
        assert sim.steps == n
        y = sim.poses()[0, 1]
        worst = max(worst, abs(y - (10.0 - G * h * h * n * (n + 1) / 2)))
        assert abs(sim.velocities()[0, 1] - (-G * h * n)) < 1e-12
    assert worst < 1e-12, worst
    assert sim.time == 1.0
    # x, z and the orientation never move.
    np.testing.assert_array_equal(sim.poses()[0, [0, 2, 3, 4, 5, 6]], [0, 0, 1, 0, 0, 0])


def complete_elliptic_k(k):
    """K(k) by the arithmetic-geometric mean: K = pi / (2 AGM(1, sqrt(1 - k^2)))."""
    a, b = 1.0, math.sqrt(1 - k * k)
    for _ in range(40):
        a, b = (a + b) / 2, math.sqrt(a * b)
    return math.pi / (2 * a)


def pendulum_periods(dt):
    """Periods between upward zero crossings of the bob's x in scenes/pendulum.xml (it starts
    at x > 0, so first it swings to x < 0), each crossing interpolated inside its step."""
    sim = simbob.Simulation(SCENES / "pendulum.xml", dt=dt)
    assert sim.joint_keys == ["Pendulum.Hinge"] and sim.dt == dt
    crossings = []
    x_prev, t_prev = sim.poses()[0, 0], sim.time
    while len(crossings) < 4:
        sim.step()
        x, t = sim.poses()[0, 0], sim.time
        if x_prev < 0 <= x:
            crossings.append(t_prev + (t - t_prev) * (-x_prev) / (x - x_prev))
        x_prev, t_prev = x, t
    return np.diff(crossings)


def test_pendulum_period_matches_the_exact_large_angle_period():
    # scenes/pendulum.xml: a 1 kg bob 1 m below the pivot with I = 0.001 kg m^2 about its
    # centre, released at 30 degrees. A compound pendulum: I_pivot = 0.001 + 1 * 1^2, and the
    # exact period at amplitude a is 4 sqrt(I_pivot / (m g L)) K(sin(a / 2)) = 2.0420 s
    # (the small-angle formula is 1.7 % shorter).
    expected = 4 * math.sqrt(1.001 / (1 * G * 1)) * complete_elliptic_k(math.sin(math.radians(30) / 2))
    assert abs(expected / (2 * math.pi * math.sqrt(1.001 / G)) - 1) > 0.015
    # The step's error in the period is second order in h (measured: 5.7e-4, 1.3e-4, 3.5e-5,
    # 9e-6 relative at h = 2, 1, 0.5, 0.25 ms; ODE solves the hinge at velocity level with ERP
    # pulling the bob back onto its circle, so this is not the symplectic (w h)^2/24 alone).
    # Tolerance 3e-4 at 1 ms, and halving h must cut the error about four times: a wrong model
    # (0.1 % off in I or L, the small-angle period) would not converge to `expected`.
    err_1ms = [abs(p / expected - 1) for p in pendulum_periods(0.001)]
    err_half = [abs(p / expected - 1) for p in pendulum_periods(0.0005)]
    assert max(err_1ms) < 3e-4, err_1ms
    for a, b in zip(err_1ms, err_half):
        assert 3 < a / b < 5, (a, b)


# ---- the same bytes as `simbob run` ----

@pytest.mark.parametrize("scene", ["chain.xml", "two_wheel_robot.xml"])
def test_step_loop_equals_simbob_run_csv_bit_for_bit(tmp_path, scene):
    samples = cli_samples(tmp_path, SCENES / scene)
    assert len(samples) == 201
    sim = simbob.Simulation(SCENES / scene)
    for t, bodies in samples:
        step_to(sim, t)
        assert list(bodies) == sim.body_keys
        poses = sim.poses()
        for i, key in enumerate(sim.body_keys):
            assert poses[i].tolist() == bodies[key], (t, key)


def test_seed_and_overrides_reach_the_run_as_on_the_command_line(tmp_path):
    # --seed and --set against seed= and overrides= on a QuickStep scene whose constraint
    # order the seed shuffles.
    samples = cli_samples(tmp_path, SCENES / "chain.xml", "--seed", "7", "--set", "SceneSettings.Gravity=0 -5 0")
    sim = simbob.Simulation(SCENES / "chain.xml", seed=7, overrides={"SceneSettings.Gravity": (0, -5, 0)})
    for t, bodies in samples[::10]:
        step_to(sim, t)
        assert sim.poses().tolist() == list(bodies.values()), t


# ---- overrides ----

def test_overrides_change_gravity_and_start_velocity_as_expected():
    # y_n = y0 + n h v0 - g h^2 n (n + 1) / 2 with g = 3 and v0 = 2 set by overrides, as a dict
    # and as a list of KEY.PARAM=VALUE strings.
    for overrides in ({"SceneSettings.Gravity": [0, -3, 0], "Ball.Motion.LinVelocity": "0 2 0"},
                      ["SceneSettings.Gravity=0 -3 0", "Ball.Motion.LinVelocity=0 2 0"]):
        sim = simbob.Simulation.from_text(ball_scene(), "fall.xml", overrides=overrides)
        sim.step(500)
        n, h = 500, 0.001
        assert abs(sim.poses()[0, 1] - (10 + n * h * 2 - 3 * h * h * n * (n + 1) / 2)) < 1e-12


def test_override_of_the_robots_schedule_doubles_its_speed():
    # The schedule drives forward at 0.2 m/s for 2 s; overridden to 0.4 m/s the chassis runs
    # twice as fast once the drives have spun the wheels up (well before t = 1.5 s).
    def speed(overrides):
        sim = simbob.Simulation(SCENES / "two_wheel_robot.xml", overrides=overrides)
        sim.run_until(1.5)
        return sim.velocities()[0, 0]

    assert abs(speed(None) - 0.2) < 0.002
    assert abs(speed({"Bot.Plan.Commands": "0 0.4 0; 2 0 0.5; 4 0 0"}) - 0.4) < 0.004


def test_dt_option_sets_the_step():
    sim = simbob.Simulation.from_text(ball_scene(), "fall.xml", dt=0.002)
    sim.step(5)
    assert sim.dt == 0.002 and sim.steps == 5 and sim.time == 0.01


def test_physics_messages_count_what_ode_reported_while_stepping():
    # The box stack under Solver Step without constraint force mixing: ODE's LCP solver reports
    # contacts it cannot meet exactly ("LCP internal error"); as shipped (QuickStep) it says nothing.
    step = {"SceneSettings.Solver": "Step", "SceneSettings.CFM": "0"}
    sim = simbob.Simulation(SCENES / "box_stack.xml", overrides=step)
    sim.step(1000)
    m = sim.physics_messages
    assert m["count"] > 1
    assert m["first"].startswith("ODE message 3: LCP internal error")
    assert 0 < m["first_time"] <= sim.time
    quiet = simbob.Simulation(SCENES / "box_stack.xml")
    quiet.step(1000)
    assert quiet.physics_messages == {"count": 0, "first": "", "first_time": 0.0}


# ---- reset and seeds ----

def trajectory(sim, steps=1500, every=50):
    out = []
    for _ in range(steps // every):
        sim.step(every)
        out.append(sim.poses().tobytes())
    return out


def test_reset_with_a_seed_equals_a_fresh_simulation_with_that_seed():
    scene = SCENES / "chain.xml"
    fresh7 = trajectory(simbob.Simulation(scene, seed=7))
    fresh0 = trajectory(simbob.Simulation(scene, seed=0))
    assert fresh7 != fresh0  # the seed reaches QuickStep: the test below can fail
    sim = simbob.Simulation(scene, seed=0)
    assert trajectory(sim) == fresh0
    sim.reset(7)
    assert sim.time == 0 and sim.steps == 0
    assert trajectory(sim) == fresh7
    sim.reset(0)
    assert trajectory(sim) == fresh0


# ---- many Simulations in one process ----

def test_three_simulations_stepped_interleaved_equal_three_separate_runs():
    scene = SCENES / "chain.xml"
    cases = [dict(seed=1), dict(seed=2), dict(seed=3, overrides={"SceneSettings.Gravity": "0 -4 0"})]
    alone = [trajectory(simbob.Simulation(scene, **c), 1000, 10) for c in cases]
    sims = [simbob.Simulation(scene, **c) for c in cases]
    got = [[], [], []]
    for k in range(100):
        # A different order each round.
        for i in ([0, 1, 2], [2, 0, 1], [1, 2, 0])[k % 3]:
            sims[i].step(4)
            sims[i].step(6)
            got[i].append(sims[i].poses().tobytes())
    for i in range(3):
        assert got[i] == alone[i], i
    assert alone[0] != alone[1]


# ---- errors ----

def test_a_bad_scene_file_raises_scene_error_with_file_and_line(tmp_path):
    bad = tmp_path / "bad.xml"
    text = ball_scene().replace('<Mass Value="1"/>', '<Mas Value="1"/>')
    bad.write_text(text)
    line = text.splitlines().index(next(l for l in text.splitlines() if "<Mas " in l)) + 1
    with pytest.raises(simbob.SceneError) as info:
        simbob.Simulation(bad)
    e = info.value
    assert isinstance(e, simbob.Error)
    assert (e.kind, e.file, e.line, e.exit_status) == ("InvalidInput", str(bad), line, 65)
    assert "Mas" in e.message
    assert str(e) == f"{bad}:{line}: error: {e.message}"
    assert e.errors[0] == str(e)


def test_a_missing_scene_raises_missing_input_error(tmp_path):
    with pytest.raises(simbob.MissingInputError) as info:
        simbob.Simulation(tmp_path / "nope.xml")
    assert info.value.file == str(tmp_path / "nope.xml")
    assert info.value.exit_status == 66
    assert str(info.value).startswith(str(tmp_path / "nope.xml") + ": error: ")


def test_bad_overrides():
    with pytest.raises(simbob.UsageError) as info:
        simbob.Simulation.from_text(ball_scene(), "fall.xml", overrides=["Ball.Mass"])
    assert "KEY.PARAM=VALUE" in info.value.message and info.value.exit_status == 64
    with pytest.raises(simbob.SceneError) as info:
        simbob.Simulation.from_text(ball_scene(), "fall.xml", overrides={"Bal.Motion.LinVelocity": "0 1 0"})
    assert info.value.file == "override Bal.Motion.LinVelocity=0 1 0"
    assert "did you mean 'Ball.Motion'" in info.value.message
    with pytest.raises(simbob.UsageError):
        simbob.Simulation.from_text(ball_scene(), "fall.xml", dt=0)


def test_an_unknown_actuator_raises_usage_error():
    sim = simbob.Simulation(SCENES / "two_wheel_robot.xml")
    with pytest.raises(simbob.UsageError) as info:
        sim.set_command("Bot.Cart.MiddleDrive", 1.0)
    assert "Bot.Cart.LeftDrive" in info.value.message  # names the actuators there are
    assert info.value.kind == "Usage" and info.value.file is None
    with pytest.raises(simbob.UsageError):
        sim.set_command(2, 1.0)
    with pytest.raises(simbob.UsageError):
        sim.set_command(0, float("nan"))


def test_a_diverging_run_raises_diverged_error_with_the_body_and_its_line():
    # 1e7 m/s upwards passes the runaway limit of 1e6 m/s at once.
    text = ball_scene(vy0=1e7)
    sim = simbob.Simulation.from_text(text, "rocket.xml")
    assert any("warning" in w for w in sim.warnings) or sim.warnings == []
    with pytest.raises(simbob.DivergedError) as info:
        sim.step(10)
    e = info.value
    assert (e.kind, e.file, e.exit_status) == ("Diverged", "rocket.xml", 1)
    assert e.line == text.splitlines().index(next(l for l in text.splitlines() if "RCMobileRigidBody Key" in l)) + 1
    assert "body 'Ball' diverged at t=0.001 s" in e.message
    assert not sim.running
    with pytest.raises(simbob.DivergedError):  # a stopped run stays stopped
        sim.step()
    sim.reset(0)  # ... until reset
    assert sim.running and sim.time == 0


def test_an_ode_error_raises_internal_error_and_the_interpreter_goes_on(monkeypatch):
    # SIMBOB_TEST_ODE_FAULT_AT_STEP (lib/physics/world.cpp, tests only) makes ODE's integrator fail
    # its own check inside the third step: ODE's error used to end the process (exit 70).
    monkeypatch.setenv("SIMBOB_TEST_ODE_FAULT_AT_STEP", "3")
    sim = simbob.Simulation.from_text(ball_scene(), "ball.xml")
    sim.step(2)
    with pytest.raises(simbob.InternalError) as info:
        sim.step(1)
    e = info.value
    assert (e.kind, e.exit_status) == ("Internal", 70)
    assert e.message.startswith("internal error: ODE internal error 1: assertion")
    assert "in the step to t=0.003 s" in e.message and "this world is not stepped again" in e.message
    assert not sim.running and sim.time == pytest.approx(0.002)
    with pytest.raises(simbob.InternalError):  # the World that hit it refuses further steps
        sim.step()
    # The interpreter goes on: a new world (reset) steps as any does.
    monkeypatch.delenv("SIMBOB_TEST_ODE_FAULT_AT_STEP")
    sim.reset(0)
    sim.step(1000)
    assert sim.time == 1.0
    # Free fall as in test_free_fall: ODE's semi-implicit Euler, exactly (rounding only).
    h, n = sim.dt, 1000
    assert abs(sim.poses()[0, 1] - (10.0 - G * h * h * n * (n + 1) / 2)) < 1e-12


def test_exception_classes():
    classes = {simbob.SceneError: 65, simbob.MissingInputError: 66, simbob.UsageError: 64,
               simbob.DivergedError: 1, simbob.UnavailableError: 69, simbob.OutputError: 74,
               simbob.ProtocolError: 76, simbob.InternalError: 70}
    for cls, status in classes.items():
        assert issubclass(cls, simbob.Error) and issubclass(cls, Exception)
        assert cls.exit_status == status and cls.__doc__
        e = cls("m", "Usage", "f.xml", 3)
        assert str(e) == "f.xml:3: error: m"
    assert str(simbob.Error("m")) == "simbob: error: m"


# ---- Python controllers ----

def run_poses(sim, until, every=1):
    out = []
    while sim.time < until:
        sim.step(every)
        out.append(sim.poses().tobytes())
    return out


def test_python_controller_follows_the_schedule_to_the_same_bytes():
    # two_wheel_robot.xml: RCCommandSchedule "0 0.2 0; 2 0 0.5; 4 0 0" drives an
    # RCTwoWheelMotionControl (track 0.38 m, wheel radius 0.1 m). Here the schedule is emptied
    # ("0 0 0": it commands zero at t = 0, as the motion control starts) and a Python controller
    # at period 2 s does the same arithmetic on the same rows at the same instants.
    scene = SCENES / "two_wheel_robot.xml"
    builtin = run_poses(simbob.Simulation(scene), 5.0)

    rows = {0: (0.2, 0.0), 2: (0.0, 0.5), 4: (0.0, 0.0)}
    half_track, radius = 0.38 / 2, 0.1
    granted = []

    def schedule(sim):
        granted.append(sim.time)
        v, w = rows.get(round(sim.time), (0.0, 0.0))
        sim.set_command("Bot.Cart.LeftDrive", (v - w * half_track) / radius)
        sim.set_command("Bot.Cart.RightDrive", (v + w * half_track) / radius)

    sim = simbob.Simulation(scene, overrides={"Bot.Plan.Commands": "0 0 0"})
    sim.add_controller(2.0, schedule)
    assert run_poses(sim, 5.0) == builtin
    assert granted == [0.0, 2.0, 4.0]
    # Without the controller the robot stays put: the test above can fail.
    idle = run_poses(simbob.Simulation(scene, overrides={"Bot.Plan.Commands": "0 0 0"}), 5.0)
    assert idle != builtin


def test_controller_at_a_period_equals_the_same_commands_from_a_step_loop():
    scene = SCENES / "two_wheel_robot.xml"
    overrides = {"Bot.Plan.Commands": "0 0 0"}

    def command(sim):
        k = round(sim.time / 0.1)
        sim.set_command(0, 3 * math.sin(0.7 * k))
        sim.set_command(1, 3 * math.cos(0.3 * k))

    with_controller = simbob.Simulation(scene, overrides=overrides)
    with_controller.add_controller(0.1, command)
    a = run_poses(with_controller, 3.0, 100)

    loop = simbob.Simulation(scene, overrides=overrides)
    b = []
    while loop.time < 3.0:
        command(loop)  # at t = 0, 0.1, ...: after the scene's controllers there, as a controller
        loop.step(100)
        b.append(loop.poses().tobytes())
    assert a == b
    command(loop)  # the controller was also granted at t = 3, where the loop stopped
    np.testing.assert_array_equal(with_controller.commands(), loop.commands())
    # After reset the controller runs again from t = 0.
    with_controller.reset(0)
    assert run_poses(with_controller, 3.0, 100) == a


def test_controller_exception_is_raised_from_step():
    sim = simbob.Simulation(SCENES / "two_wheel_robot.xml")

    class Stop(Exception):
        pass

    def fail(s):
        if s.time >= 0.3:
            raise Stop("at %g" % s.time)

    sim.add_controller(0.1, fail)
    with pytest.raises(Stop, match="at 0.3"):
        sim.run_until(1.0)
    assert abs(sim.time - 0.3) < 1e-12
    assert not sim.running
    # The run stopped because a controller failed, not because anything diverged.
    with pytest.raises(simbob.ControllerError, match="Python controller") as e:
        sim.step()
    assert e.value.kind == "ControllerFailed" and e.value.exit_status == 2


def test_controller_may_not_step_the_simulation():
    sim = simbob.Simulation(SCENES / "pendulum.xml")
    sim.add_controller(0.5, lambda s: s.step())
    with pytest.raises(simbob.UsageError, match="not step"):
        sim.step()


def test_a_slow_controller_raises_unavailable_error_with_its_place():
    sim = simbob.Simulation(SCENES / "pendulum.xml", overrides={"SceneSettings.MaxAccessTime": 0.05})
    sim.add_controller(0.5, lambda s: time.sleep(0.2))
    line = test_a_slow_controller_raises_unavailable_error_with_its_place.__code__.co_firstlineno + 2
    with pytest.raises(simbob.UnavailableError) as info:
        sim.step()
    assert info.value.file == __file__ and info.value.line == line
    assert info.value.exit_status == 69


# ---- threads and the GIL ----

def test_step_releases_the_gil_without_python_controllers():
    sim = simbob.Simulation(SCENES / "chain.xml")
    stamps, done = [], threading.Event()

    def tick():
        while not done.is_set():
            stamps.append(time.monotonic())
            time.sleep(0.001)

    t = threading.Thread(target=tick)
    t.start()
    time.sleep(0.01)
    t0 = time.monotonic()
    sim.step(60000)
    t1 = time.monotonic()
    done.set()
    t.join()
    assert t1 - t0 > 0.2, "the step was too short to tell"
    inside = [s for s in stamps if t0 + 0.05 < s < t1 - 0.05]
    assert len(inside) > 10


def test_a_simulation_used_from_two_threads_is_refused():
    sim = simbob.Simulation(SCENES / "chain.xml")
    worker = threading.Thread(target=lambda: sim.step(30000))
    refused = 0
    worker.start()
    while worker.is_alive():
        try:
            sim.poses()
        except simbob.UsageError as e:
            assert "another thread" in e.message
            refused += 1
        time.sleep(0.001)
    worker.join()
    assert refused > 0
    assert sim.steps == 30000


# ---- the reference ----

def test_docstrings_everywhere():
    assert simbob.__doc__ and simbob.Simulation.__doc__
    for name in dir(simbob.Simulation):
        if not name.startswith("_"):
            assert getattr(simbob.Simulation, name).__doc__, name
    text = simbob.Simulation.step.__doc__
    assert "n whole steps" in text


# ---- rendering ----

def read_png_rgb(path):
    """An 8-bit RGB PNG (as simbob writes them) as numpy uint8 (h, w, 3); standard library only."""
    import struct
    import zlib
    data = Path(path).read_bytes()
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and color == 2
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride = zlib.decompress(idat), width * 3
    out, prev = np.zeros((height, width, 3), np.uint8), bytearray(stride)
    for y in range(height):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - 3] if i >= 3 else 0
            b, c = prev[i], prev[i - 3] if i >= 3 else 0
            p = a + b - c
            pred = [0, a, b, (a + b) // 2,
                    a if abs(p - a) <= abs(p - b) and abs(p - a) <= abs(p - c) else b if abs(p - b) <= abs(p - c) else c][f]
            line[i] = (line[i] + pred) & 0xFF
        out[y] = np.frombuffer(bytes(line), np.uint8).reshape(width, 3)
        prev = line
    return out


@pytest.mark.parametrize("camera", ["Overview", "OnBall"])
def test_render_equals_simbob_render_of_that_camera_at_that_time(tmp_path, camera):
    """render() draws through the renderer of `simbob render`: the same pixels, byte for byte,
    for a static and a mounted camera at t = 1 s of the gallery (both draw each frame from the
    poses alone, so no earlier frame matters)."""
    still = tmp_path / "still.png"
    subprocess.run([str(BINARY), "render", str(SCENES / "gallery.xml"), "--at", "1", "--camera", camera,
                    "--size", "96x72", "--out", str(still), "--quiet"], check=True)
    sim = simbob.Simulation(str(SCENES / "gallery.xml"))
    sim.run_until(1.0)
    img = sim.render(camera=camera, size=(96, 72))
    assert img.shape == (72, 96, 3) and img.dtype == np.uint8
    assert np.array_equal(img, read_png_rgb(still))
    # A different instant is a different picture (the ball rolls), so the check can fail.
    sim.run_until(2.0)
    assert not np.array_equal(sim.render(camera=camera, size=(96, 72)), img)


CAMERA_SENSOR_SCENE = """<Simulation>
  <SceneSettings><MaxTimeStep Value="0.001"/></SceneSettings>
  <ComponentList>
    <RCGround Key="Ground"/>
    <RCStaticRigidBody Key="Wall">
      <Pose><RCGlobalCoordinates><Pose Value="0 0.5 -3 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCCuboidGeom><Width Value="2"/><Height Value="1"/><Depth Value="0.2"/></RCCuboidGeom></Geom>
    </RCStaticRigidBody>
    <RCConstruction Key="Bot">
      <Body><RCMobileRigidBody Key="Chassis">
        <Pose><RCGlobalCoordinates><Pose Value="0 1 0 0 0 0"/></RCGlobalCoordinates></Pose>
        <Geom><RCCuboidGeom><Width Value="0.2"/><Height Value="0.1"/><Depth Value="0.2"/></RCCuboidGeom></Geom>
      </RCMobileRigidBody></Body>
      <ChildList>
        <RCCameraSensor Key="Eye">
          <Pose><RCLocalCoordinates><Pose Value="0 0.1 0 -10 0 0"/></RCLocalCoordinates></Pose>
          <Width Value="64"/><Height Value="48"/><Period Value="0.1"/>
        </RCCameraSensor>
      </ChildList>
    </RCConstruction>
  </ComponentList>
</Simulation>
"""


def test_camera_sensor_image_equals_simbob_render_of_that_camera_at_that_time(tmp_path):
    """An RCCameraSensor's image at t is `simbob render --camera KEY --at t --size WxH`, byte for
    byte; it is held between Period instants (a box with the camera falls onto the ground)."""
    scene = tmp_path / "eye.xml"
    scene.write_text(CAMERA_SENSOR_SCENE)
    still = tmp_path / "still.png"
    subprocess.run([str(BINARY), "render", str(scene), "--at", "0.3", "--camera", "Bot.Eye", "--size", "64x48",
                    "--out", str(still), "--quiet"], check=True)
    sim = simbob.Simulation(str(scene))
    assert sim.camera_image("Bot.Eye").shape == (0, 0, 3)  # nothing served yet
    sim.run_until(0.3)
    img = sim.camera_image("Bot.Eye")
    assert img.shape == (48, 64, 3) and img.dtype == np.uint8
    assert np.array_equal(img, read_png_rgb(still))
    sim.run_until(0.35)  # held until the next Period instant
    assert np.array_equal(sim.camera_image("Bot.Eye"), img)
    sim.run_until(0.4)  # the box has fallen on: another picture, so the check can fail
    assert not np.array_equal(sim.camera_image("Bot.Eye"), img)
    with pytest.raises(simbob.UsageError, match="no camera sensor 'Bot.Nose'.*its camera sensors: Bot.Eye"):
        sim.camera_image("Bot.Nose")


def test_a_controller_at_t_reads_the_camera_image_of_t(tmp_path):
    """Camera sensors are served before the controllers of an instant: a Python controller at
    the camera's Period instants reads the picture of that instant (the box is falling, so every
    instant's picture differs), the one sim.render() draws through that camera there."""
    scene = tmp_path / "eye.xml"
    scene.write_text(CAMERA_SENSOR_SCENE)
    seen = []
    sim = simbob.Simulation(str(scene))
    sim.add_controller(0.1, lambda s: seen.append((s.time, s.camera_image("Bot.Eye").copy())))
    sim.run_until(0.3)
    assert [t for t, _ in seen] == pytest.approx([0.0, 0.1, 0.2, 0.3])
    direct = simbob.Simulation(str(scene))
    for t, img in seen:
        direct.run_until(t)
        assert np.array_equal(img, direct.render(camera="Bot.Eye", size=(64, 48))), t
    assert not np.array_equal(seen[1][1], seen[2][1])


def test_render_errors():
    sim = simbob.Simulation(str(SCENES / "gallery.xml"))
    with pytest.raises(simbob.SceneError):
        sim.render(camera="NoSuchCamera")
    with pytest.raises(simbob.UsageError):
        sim.render(size=(0, 10))
    with pytest.raises(simbob.UsageError):
        sim.render(quality="shiny")


def rss_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_ten_thousand_create_step_destroy_cycles_keep_memory_flat():
    """Each cycle loads and compiles a scene, builds its ODE world, steps it and drops it. After a
    warm-up of 1,000 cycles (allocator pools, Python's own caches), 10,000 more may grow the
    resident set by less than 2 MiB: about 200 bytes a cycle, less than any one leaked world,
    body or scene graph (each several KiB)."""
    scene = ball_scene()

    def cycle():
        sim = simbob.Simulation.from_text(scene, "ball.xml")
        sim.step(3)
        sim.poses()
        del sim

    for _ in range(1000):
        cycle()
    before = rss_bytes()
    for _ in range(10000):
        cycle()
    grown = rss_bytes() - before
    assert grown < 2 * 1024 * 1024, f"resident memory grew {grown} bytes over 10,000 cycles"


def sensed_scene():
    """A body at rest without gravity carrying a range sensor that looks along +X at a wall whose
    face is at x = 2, and an IMU."""
    return """<?xml version="1.0" encoding="UTF-8"?>
<Simulation>
  <SceneSettings><MaxTimeStep Value="0.001"/><Gravity Value="0 0 0"/></SceneSettings>
  <ComponentList>
    <RCStaticRigidBody Key="Wall">
      <Pose><RCGlobalCoordinates><Pose Value="2.5 0 0 0 0 0"/></RCGlobalCoordinates></Pose>
      <Geom><RCCuboidGeom><Width Value="1"/><Height Value="1"/><Depth Value="10"/></RCCuboidGeom></Geom>
    </RCStaticRigidBody>
    <RCConstruction Key="Bot">
      <Body><RCMobileRigidBody Key="Chassis">
        <Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom>
      </RCMobileRigidBody></Body>
      <ChildList>
        <RCRangeSensor Key="Front">
          <Pose><RCLocalCoordinates><Pose Value="0 0 0 0 -90 0"/></RCLocalCoordinates></Pose>
        </RCRangeSensor>
        <RCImuSensor Key="Imu"/>
      </ChildList>
    </RCConstruction>
  </ComponentList>
</Simulation>
"""


def test_sensor_readings_by_key():
    sim = simbob.Simulation.from_text(sensed_scene(), "sensed.xml")
    assert sim.sensor_keys == ["Bot.Front", "Bot.Imu"]
    assert sim.sensor_quantities("Bot.Front") == ["distance"]
    assert sim.sensor_quantities("Bot.Imu") == ["ax", "ay", "az", "gx", "gy", "gz"]
    d = sim.sensor("Bot.Front")
    assert d.dtype == np.float64 and d.shape == (1,)
    assert abs(d[0] - 2.0) < 1e-9
    assert sim.sensor("Bot.Imu").shape == (6,)
    assert list(sim.touching()) == [False, False]  # neither is a proximity sensor
    with pytest.raises(simbob.UsageError) as info:
        sim.sensor("Bot.Back")
    assert "Bot.Front" in info.value.message  # names the sensors there are


PENDULUM_URDF = """<robot name="pend">
  <link name="world"/>
  <joint name="pivot" type="continuous">
    <parent link="world"/><child link="bob"/><origin xyz="0 0 2"/><axis xyz="0 1 0"/>
  </joint>
  <link name="bob">
    <inertial><origin xyz="1 0 0"/><mass value="1"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
  </link>
</robot>
"""


def test_a_urdf_file_is_a_scene_of_its_own(tmp_path):
    """simbob.Simulation("robot.urdf") reads a URDF as simbob run does (docs/urdf.md)."""
    path = tmp_path / "pend.urdf"
    path.write_text(PENDULUM_URDF)
    sim = simbob.Simulation(path)
    assert sim.body_keys == ["pend.bob"]
    assert sim.joint_keys == ["pend.pivot"]
    # The row is the link frame, at the pivot (URDF z = 2 is the scene's y = 2), while the mass
    # 1 m away along URDF x starts to fall: after 0.1 s it has turned by about g t^2 / 2 / 1 m.
    sim.run_until(0.1)
    p = sim.poses()[0]
    assert abs(p[0]) < 1e-3 and abs(p[1] - 2) < 1e-3 and abs(p[2]) < 1e-3
    assert abs(abs(sim.joint_positions()[0]) - G * 0.01 / 2) < 2e-3
    with pytest.raises(simbob.SceneError) as info:
        simbob.Simulation.from_text(PENDULUM_URDF.replace('<mass value="1"/>', '<mass value="0"/>'), "bad.urdf")
    assert info.value.line == 7
