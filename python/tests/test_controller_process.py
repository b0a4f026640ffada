"""The controller program a Simulation starts (an RCLocalSocketCommunicator's Controller) lives
as long as the Simulation, whichever thread made it (issue 31, item 8): PR_SET_PDEATHSIG fires
when the *thread* that forked exits, so a controller tied to it died with a worker thread."""
import csv
import os
import threading
import time
from pathlib import Path

import simbob

ROOT = Path(os.environ.get("SIMBOB_SOURCE_DIR", Path(__file__).resolve().parents[2]))
SCENE = ROOT / "scenes" / "socket_robot.xml"
GOLDEN = ROOT / "golden" / "socket_robot.csv"


def golden_last_sample():
    """{body: [x y z qw qx qy qz]} of the golden file's last time (t = 10)."""
    rows = list(csv.reader(open(GOLDEN, newline="")))[1:]
    last = rows[-1][0]
    return {r[1]: [float(v) for v in r[2:]] for r in rows if r[0] == last}, float(last)


def test_a_simulation_made_in_a_thread_keeps_its_controller_after_the_thread_ends():
    made = {}

    def make():
        sim = simbob.Simulation(SCENE)
        sim.step()  # the controller has started (and connected) in this thread
        made["sim"] = sim

    worker = threading.Thread(target=make)
    worker.start()
    worker.join()
    time.sleep(0.5)  # a parent-death signal tied to the thread has arrived by now
    sim = made["sim"]
    want, end = golden_last_sample()
    sim.run_until(end)  # raises UnavailableError where the controller is gone
    got = dict(zip(sim.body_keys, sim.poses().tolist()))
    # The same bytes as `simbob run` (the golden file): the controller drove the whole run.
    assert got == want
