"""simbob.Batch of a scene whose controller program simbob starts (docs/python.md "Scenes that
start controller programs"): scenes/socket_robot.xml's RCLocalSocketCommunicator starts
scripts/simbob_client.py, which drives the robot over the socket. With worker processes every
world runs with its own program, to the same numbers as with workers=0 and as a Simulation alone;
before, the caller's copies of the worlds ended the programs after the fork ("UnavailableError
... Broken pipe"). The programs are the workers' children and end with them."""

import os
import time
from pathlib import Path

import numpy as np
import pytest

import simbob

ROOT = Path(os.environ.get("SIMBOB_SOURCE_DIR", Path(__file__).resolve().parents[2]))
SOCKET_ROBOT = ROOT / "scenes" / "socket_robot.xml"


def children():
    """The pids of this process's child processes (from /proc)."""
    me = str(os.getpid())
    out = set()
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as f:
                    if f.read().rsplit(")", 1)[1].split()[1] == me:
                        out.add(int(entry))
            except (OSError, IndexError):
                pass
    return out


def drive(obj):
    obj.run_until(0.5)
    obj.step(137)
    obj.run_until(1.0)
    return obj


def test_a_simulation_lists_the_programs_it_started():
    sim = simbob.Simulation(SOCKET_ROBOT)
    assert sim.programs == ["Bot.Cart.Link"]
    assert simbob.Simulation(ROOT / "scenes" / "pendulum.xml").programs == []


@pytest.mark.parametrize("workers", [1, 2])
def test_worlds_with_controller_programs_run_in_workers_as_alone(workers):
    alone = simbob.Simulation(SOCKET_ROBOT, seed=0)
    start = alone.poses()
    want = drive(alone).poses()
    # The program drove the robot (without its commands the chassis stays where it starts).
    assert np.linalg.norm(want[0, :3] - start[0, :3]) > 0.05
    del alone
    before = children()
    with simbob.Batch(SOCKET_ROBOT, 2, seeds=[0, 0], workers=workers) as b:
        # The caller's own worlds (loaded to check the scene) ended with their programs; the
        # programs that run now are the workers' children, not the caller's.
        assert children() - before == set(b._pids)
        drive(b)
        assert list(b.time) == [1.0, 1.0]
        for i in range(2):
            assert b.poses()[i].tobytes() == want.tobytes()
        b.reset()
        drive(b)
        assert b.poses()[1].tobytes() == want.tobytes()
    deadline = time.monotonic() + 10
    while children() - before and time.monotonic() < deadline:
        time.sleep(0.05)
    assert children() - before == set()
