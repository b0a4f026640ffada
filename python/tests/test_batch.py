"""Tests of simbob.Batch (python/simbob/batch.py): n worlds stepped by worker processes, each
world bit for bit the same as the same case run alone by one Simulation."""

import os
import signal
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import simbob

ROOT = Path(os.environ.get("SIMBOB_SOURCE_DIR", Path(__file__).resolve().parents[2]))
SCENES = ROOT / "scenes"
CHAIN = SCENES / "chain.xml"  # QuickStep: its trajectory depends on the seed
ROBOT = SCENES / "two_wheel_robot.xml"
NO_PLAN = {"Bot.Plan.Commands": "0 0 0"}
BALL = """<Simulation><ComponentList>
  <RCMobileRigidBody Key="Ball">
    <Pose><RCGlobalCoordinates><Pose Value="0 10 0 0 0 0"/></RCGlobalCoordinates></Pose>
    <Motion><RCGlobalMotion><LinVelocity Value="0 0 0"/></RCGlobalMotion></Motion>
    <Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom>
  </RCMobileRigidBody>
</ComponentList></Simulation>
"""

CASES = [
    dict(seed=0),
    dict(seed=7),
    dict(seed=0, overrides={"SceneSettings.Gravity": "0 -4 0"}),
    dict(seed=3),
    dict(seed=7),
]


def state(obj, i=None):
    """The state arrays of a Simulation, or of world i of a Batch, as bytes."""
    parts = [obj.poses(), obj.velocities(), obj.joint_positions(), obj.joint_velocities(), obj.commands()]
    if i is not None:
        parts = [p[i] for p in parts]
    return b"".join(np.ascontiguousarray(p).tobytes() for p in parts)


def drive(obj, record):
    """The same calls on a Simulation or a Batch: steps of several sizes and run_until."""
    for k in (1, 5, 37):
        obj.step(k)
        record(obj)
    for t in (0.1, 0.25, 0.25, 0.4):
        obj.run_until(t)
        record(obj)


def alone(scene, case):
    sim = simbob.Simulation(scene, overrides=case.get("overrides"), seed=case["seed"])
    out = []
    drive(sim, lambda s: out.append((s.time, state(s))))
    return out


@pytest.mark.parametrize("workers", [0, 1, 2, 3])
def test_every_world_equals_the_same_case_run_alone(workers):
    expected = [alone(CHAIN, c) for c in CASES]
    assert expected[0] != expected[1]  # the seed reaches QuickStep: the comparison can fail
    assert expected[0] != expected[2]  # and so does the override
    assert expected[1] == expected[4]
    got = [[] for _ in CASES]

    def record(b):
        for i in range(len(CASES)):
            got[i].append((float(b.time[i]), state(b, i)))

    with simbob.Batch(CHAIN, len(CASES), overrides=[c.get("overrides") for c in CASES],
                      seeds=[c["seed"] for c in CASES], workers=workers) as b:
        assert b.workers == workers
        assert b.poses().shape == (5, len(b.body_keys), 7) and b.velocities().shape == (5, len(b.body_keys), 6)
        assert b.joint_positions().shape == (5, len(b.joint_keys))
        drive(b, record)
        assert list(b.steps) == [400] * 5 and b.running.all()
    for i in range(len(CASES)):
        assert got[i] == expected[i], f"world {i}"


def test_default_seeds_are_the_world_indices_and_one_override_set_applies_to_all():
    with simbob.Batch(CHAIN, 2, overrides={"SceneSettings.Gravity": "0 -4 0"}, workers=2) as b:
        b.step(100)
        got = [state(b, 0), state(b, 1)]
    for i in range(2):
        sim = simbob.Simulation(CHAIN, overrides=["SceneSettings.Gravity=0 -4 0"], seed=i)
        sim.step(100)
        assert got[i] == state(sim)


def test_set_commands_per_world_equals_set_command_on_single_runs():
    speeds = np.array([[2.0, 2.0], [1.0, -1.0], [-3.0, 4.0]])
    with simbob.Batch(ROBOT, 3, overrides=NO_PLAN, seeds=[0, 0, 0], workers=2) as b:
        assert b.actuator_keys == ["Bot.Cart.LeftDrive", "Bot.Cart.RightDrive"]
        b.set_commands(speeds)
        assert (b.commands() == speeds).all()
        b.step(500)
        poses = b.poses()
        b.set_commands(-speeds)
        b.step(500)
        got = [state(b, i) for i in range(3)]
    for i in range(3):
        sim = simbob.Simulation(ROBOT, overrides=NO_PLAN, seed=0)
        for sign in (1, -1):
            for a in range(2):
                sim.set_command(a, sign * speeds[i, a])
            sim.step(500)
        assert got[i] == state(sim), f"world {i}"
    # After 0.5 s: equal wheel speeds (2 rad/s, 0.1 m wheels) drove about 0.1 m ahead (+X);
    # opposite ones turned on the spot.
    assert 0.05 < poses[0, 0, 0] < 0.11 and abs(poses[1, 0, 0]) < 0.01
    with simbob.Batch(ROBOT, 2, overrides=NO_PLAN, workers=0) as b:
        b.set_commands([1.5, 2.5])  # one row for every world
        assert (b.commands() == [[1.5, 2.5], [1.5, 2.5]]).all()


def test_reset_with_seeds_equals_fresh_worlds():
    with simbob.Batch(CHAIN, 2, seeds=[1, 2], workers=2) as b:
        b.step(200)
        first = [state(b, i) for i in range(2)]
        b.reset([2, 1])
        assert list(b.time) == [0, 0] and list(b.steps) == [0, 0]
        b.step(200)
        assert [state(b, 0), state(b, 1)] == [first[1], first[0]]
        b.reset()  # the seeds given to Batch
        b.step(200)
        assert [state(b, 0), state(b, 1)] == first


def test_load_errors_are_raised_by_the_constructor_as_by_simulation(tmp_path):
    with pytest.raises(simbob.MissingInputError) as info:
        simbob.Batch(tmp_path / "nope.xml", 2)
    assert info.value.file == str(tmp_path / "nope.xml")
    with pytest.raises(simbob.SceneError) as info:
        simbob.Batch(CHAIN, 2, overrides=[None, {"Nope.Mass": 1}])
    assert info.value.file == "override Nope.Mass=1"


def test_a_diverging_world_raises_diverged_error_with_its_index_and_place(tmp_path):
    scene = tmp_path / "rocket.xml"
    scene.write_text(BALL)
    fast = {"Ball.Motion.LinVelocity": "0 1e7 0"}  # beyond the runaway limit of 1e6 m/s at once
    single = simbob.Simulation(scene, overrides=fast)
    with pytest.raises(simbob.DivergedError) as alone_info:
        single.step(10)
    for workers in (0, 2):
        with simbob.Batch(scene, 4, overrides=[None, None, fast, None], workers=workers) as b:
            with pytest.raises(simbob.DivergedError) as info:
                b.step(10)
            e = info.value
            assert e.world == 2
            assert (e.kind, e.file, e.line, e.message) == (alone_info.value.kind, alone_info.value.file,
                                                          alone_info.value.line, alone_info.value.message)
            assert str(e) == str(alone_info.value)
            assert list(b.running) == [True, True, False, True]
            assert list(b.steps) == [10, 10, single.steps, 10]  # the others completed the call
            with pytest.raises(simbob.DivergedError):  # stopped until reset
                b.step(1)
            b.reset()  # a fresh run: world 2 diverges again at its first step
            assert b.running.all() and list(b.steps) == [0] * 4
            with pytest.raises(simbob.DivergedError) as again:
                b.step(10)
            assert again.value.world == 2 and str(again.value) == str(e)


def test_usage_errors():
    with pytest.raises(simbob.UsageError):
        simbob.Batch(CHAIN, 0)
    with pytest.raises(simbob.UsageError):
        simbob.Batch(CHAIN, 2, seeds=[1])
    with pytest.raises(simbob.UsageError):
        simbob.Batch(CHAIN, 2, seeds=[1, -1])
    with pytest.raises(simbob.UsageError):
        simbob.Batch(CHAIN, 2, overrides=[{}, {}, {}])
    with simbob.Batch(ROBOT, 2, workers=1) as b:
        with pytest.raises(simbob.UsageError):
            b.set_commands(np.zeros((3, 2)))
        with pytest.raises(simbob.UsageError):
            b.set_commands([[0, float("nan")], [0, 0]])
        with pytest.raises(simbob.UsageError):
            b.step(-1)
        with pytest.raises(simbob.UsageError):
            b.run_until(float("inf"))
    with pytest.raises(simbob.UsageError):
        b.step()  # closed


def test_a_worker_that_dies_raises_internal_error():
    b = simbob.Batch(CHAIN, 4, workers=2)
    b.step(1)
    os.kill(b._pids[1], signal.SIGKILL)
    with pytest.raises(simbob.InternalError) as info:
        b.step(1)
    assert "worker 1 (worlds 2 to 3)" in info.value.message
    with pytest.raises(simbob.UsageError):
        b.step(1)


def test_workers_are_reaped_on_close_and_run_in_their_own_processes():
    b = simbob.Batch(CHAIN, 3, workers=3)
    pids = list(b._pids)
    assert len(set(pids)) == 3 and os.getpid() not in pids
    b.close()
    for pid in pids:
        with pytest.raises(ChildProcessError):
            os.waitpid(pid, os.WNOHANG)  # already reaped
    b.close()  # idempotent


def test_a_second_thread_is_refused_while_a_call_runs():
    with simbob.Batch(CHAIN, 2, workers=2) as b:
        done = threading.Event()

        def long_call():
            while True:
                try:
                    b.step(40000)
                    break
                except simbob.UsageError:  # the main thread's step(1) was running: again
                    time.sleep(0.001)
            done.set()

        t = threading.Thread(target=long_call)
        t.start()
        refused = []
        while not done.is_set():
            try:
                b.step(1)
            except simbob.UsageError as e:
                refused.append(str(e))
            time.sleep(0.001)
        t.join()
    assert refused and "in use by another thread" in refused[0]


def test_the_caller_waits_with_the_gil_released():
    with simbob.Batch(CHAIN, 2, workers=2) as b:
        stamps, done = [], threading.Event()

        def tick():
            while not done.is_set():
                stamps.append(time.monotonic())
                time.sleep(0.001)

        t = threading.Thread(target=tick)
        t.start()
        time.sleep(0.01)
        t0 = time.monotonic()
        b.step(40000)
        t1 = time.monotonic()
        done.set()
        t.join()
    assert t1 - t0 > 0.2, "the step was too short to tell"
    assert len([s for s in stamps if t0 + 0.05 < s < t1 - 0.05]) > 10


def test_docstrings():
    assert simbob.Batch.__doc__ and simbob.SimbobEnv.__doc__ and simbob.Box.__doc__
    for cls in (simbob.Batch, simbob.SimbobEnv, simbob.Box):
        for name in dir(cls):
            if not name.startswith("_"):
                assert getattr(cls, name).__doc__, f"{cls.__name__}.{name}"
