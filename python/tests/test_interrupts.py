"""Ctrl-C and the clock's range in the Python module (docs/python.md "Interrupting a call",
docs/testing.md): a real SIGINT, sent by this test to a child interpreter while it is inside a long
Simulation.step / run_until or Batch.step, raises KeyboardInterrupt there within moments; a
Simulation stays usable at the grid instant it reached, a Batch is closed and its workers are
gone. Steps and times beyond the clock's range (2**63 ns, about 292 years) are refused."""

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

import simbob
from conftest import child_env

ROOT = Path(os.environ.get("SIMBOB_SOURCE_DIR", Path(__file__).resolve().parents[2]))
PENDULUM = ROOT / "scenes" / "pendulum.xml"
CHAIN = ROOT / "scenes" / "chain.xml"
# A box at rest without gravity: nothing moves, so steps of 1e9 s do not diverge.
STILL = """<Simulation><SceneSettings><Gravity Value="0 0 0"/></SceneSettings><ComponentList>
  <RCMobileRigidBody Key="Box">
    <Geom><RCCuboidGeom><Width Value="1"/><Height Value="1"/><Depth Value="1"/></RCCuboidGeom></Geom>
  </RCMobileRigidBody>
</ComponentList></Simulation>
"""

# A generous bound on how long the child may take to answer Ctrl-C: not a timing assertion (a
# loaded machine may take seconds), a bound that tells an answer from none (before, the call ran
# to its end: hours of steps).
ANSWER_S = 60


def interrupted(body):
    """Runs `body` (Python source using `sim_scene`, `chain_scene`) in a child interpreter that
    prints "ready" before its long call; sends it SIGINT once it is ready (and a little later, so
    the call is under way); returns what the child printed after that."""
    script = "import os, sys, time, simbob\n" + f"sim_scene = {str(PENDULUM)!r}\nchain_scene = {str(CHAIN)!r}\n"
    script += textwrap.dedent(body)
    # A session of its own: SIGINT goes to the child alone (as Ctrl-C would reach a Batch's caller
    # and workers alike, which ignore it), and a child that does not answer is killed with
    # everything it started (a Batch's workers would hold the pipes open).
    child = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                             text=True, env=child_env(), start_new_session=True)
    try:
        assert child.stdout.readline().strip() == "ready", child.stderr.read()
        time.sleep(0.3)
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=ANSWER_S)
    except subprocess.TimeoutExpired:
        os.killpg(child.pid, signal.SIGKILL)
        child.communicate()
        pytest.fail(f"the child did not answer SIGINT within {ANSWER_S} s")
    assert child.returncode == 0, err
    return out


@pytest.mark.parametrize("call", ["sim.step(10**12)", "sim.run_until(9e9)"])
def test_ctrl_c_stops_a_long_call_and_the_simulation_goes_on(call):
    out = interrupted(f"""
        sim = simbob.Simulation(sim_scene)
        print("ready", flush=True)
        try:
            {call}
            print("finished")
        except KeyboardInterrupt:
            # stopped at a grid instant: time is steps * dt, and the run goes on from there
            assert sim.running
            assert abs(sim.time - sim.steps * sim.dt) <= 1e-9 * sim.time
            n = sim.steps
            sim.step(3)
            assert sim.steps == n + 3
            print("interrupted", n)
    """)
    assert out.startswith("interrupted "), out
    assert int(out.split()[1]) > 0


def test_ctrl_c_with_a_python_controller_raises_keyboard_interrupt_itself():
    out = interrupted("""
        sim = simbob.Simulation(sim_scene)
        sim.add_controller(0.001, lambda s: s.poses())
        print("ready", flush=True)
        try:
            sim.step(10**12)
            print("finished")
        except KeyboardInterrupt:
            print("KeyboardInterrupt")
        except BaseException as e:
            print(type(e).__name__, str(e).replace("\\n", "|"))
    """)
    assert out.strip() == "KeyboardInterrupt", out


def test_ctrl_c_in_a_batch_closes_it_and_ends_its_workers():
    out = interrupted("""
        b = simbob.Batch(chain_scene, 4, workers=2)
        pids = list(b._pids)
        print("ready", flush=True)
        try:
            b.step(3_000_000)
            print("finished")
        except KeyboardInterrupt:
            pass
        # The workers are gone (reaped): no world goes on stepping behind the caller's back.
        for pid in pids:
            try:
                os.kill(pid, 0)
                print("worker alive", pid)
            except ProcessLookupError:
                pass
        try:
            b.step(1)
            print("stepped", list(b.steps))
        except simbob.UsageError as e:
            print("closed:", e.message)
    """)
    assert out.splitlines() == [
        "closed: this Batch was closed by KeyboardInterrupt during step(): its worlds had not all finished "
        "the call; make a new Batch"], out


def test_ctrl_c_in_a_batch_without_workers_closes_it_too():
    out = interrupted("""
        b = simbob.Batch(chain_scene, 2, workers=0)
        print("ready", flush=True)
        try:
            b.run_until(9e9)
            print("finished")
        except KeyboardInterrupt:
            pass
        try:
            b.step(1)
            print("stepped", list(b.steps))
        except simbob.UsageError as e:
            print("closed:", e.message)
    """)
    assert out.splitlines() == [
        "closed: this Batch was closed by KeyboardInterrupt during run_until(): its worlds had not all finished "
        "the call; make a new Batch"], out


def test_keyboard_interrupt_inside_a_controller_is_itself_then_one_line():
    sim = simbob.Simulation(PENDULUM)

    def ctl(s):
        if s.time >= 0.05:
            raise KeyboardInterrupt

    sim.add_controller(0.01, ctl)
    with pytest.raises(KeyboardInterrupt):
        sim.step(1000)
    # The run stopped there; later calls say why in one line (no traceback), as for any failure:
    # a controller failed (not a divergence).
    with pytest.raises(simbob.ControllerError) as e:
        sim.step(1)
    assert "\n" not in str(e.value)
    assert e.value.message == "Python controller 'test_keyboard_interrupt_inside_a_controller_is_itself_then_one_line.<locals>.ctl' raised KeyboardInterrupt"


def test_a_controller_exception_is_one_line_when_raised_again():
    sim = simbob.Simulation(PENDULUM)

    def ctl(s):
        raise ValueError("bad\nworse")

    sim.add_controller(0.01, ctl)
    with pytest.raises(ValueError):
        sim.step(10)
    with pytest.raises(simbob.ControllerError) as e:
        sim.step(1)
    assert e.value.message.endswith("raised ValueError: bad"), e.value.message


def test_steps_beyond_the_clock_are_refused():
    sim = simbob.Simulation.from_text(STILL, dt=1e9)
    sim.step(9)  # 9e18 ns: within 2**63 - 1
    assert sim.time == 9e9
    with pytest.raises(simbob.UsageError) as e:
        sim.step(1)
    assert e.value.message == ("step(1): the time would pass 9.223372036854775807e9 s (2**63 ns), the end of "
                               "simbob's clock: at most 0 more steps of 1e+09 s from t=9e+09 s")
    assert sim.time == 9e9 and sim.running  # refused before anything moved
    with pytest.raises(simbob.UsageError) as e:
        simbob.Simulation(PENDULUM).run_until(1e10)
    assert e.value.message == "run_until: t=1e+10 s is beyond the end of simbob's clock (9.223372036854775807e9 s: 2**63 ns)"


def test_batch_refuses_steps_beyond_the_clock(tmp_path):
    (tmp_path / "still.xml").write_text(STILL)
    with simbob.Batch(tmp_path / "still.xml", 2, dt=1e9, workers=1) as b:
        b.step(9)
        with pytest.raises(simbob.UsageError, match="the end of simbob's clock"):
            b.step(1)
        with pytest.raises(simbob.UsageError, match="the end of simbob's clock"):
            b.run_until(1e10)
        assert list(b.time) == [9e9, 9e9]
