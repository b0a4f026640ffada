"""What the Python module costs over `simbob run` (issue #20's targets): python_bench.py [--repeats R]

1. A Python loop of sim.step() over bench/scenes/boxes100.xml (100 boxes, 1 ms steps), reading
   the poses every 10 steps as `run` samples them, against `build/simbob run` of the same scene
   and duration writing its CSV (target: the loop within 5 % of run).
2. The cost of one step() call above the physics, on a one-body scene: step() one step at a time
   against step(n) of the same n steps in one call (target: <= 2 us per call).
Medians of R repetitions (default 5); prints the ratios. Runs under Debian's /usr/bin/python3
with PYTHONPATH=build/python. Never a test: wall-clock times depend on the machine and its load.
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "build", "python"))
import simbob  # noqa: E402

BOXES = os.path.join(ROOT, "bench", "scenes", "boxes100.xml")
SIMBOB = os.path.join(ROOT, "build", "simbob")
ONE_BODY = """<Simulation><ComponentList>
  <RCMobileRigidBody Key="Ball">
    <Pose><RCGlobalCoordinates><Pose Value="0 1e3 0 0 0 0"/></RCGlobalCoordinates></Pose>
    <Geom><RCSphereGeom Key="G"><Radius Value="0.1"/></RCSphereGeom></Geom>
  </RCMobileRigidBody>
</ComponentList></Simulation>"""


def timed(fn):
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def python_loop(duration):
    sim = simbob.Simulation(BOXES)
    for _ in range(int(round(duration / 0.01))):
        sim.step(10)
        sim.poses()


def cli_run(duration, out):
    subprocess.run([SIMBOB, "run", BOXES, "--duration", str(duration), "--out", out, "-q"], check=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--duration", type=float, default=5.0, help="s of simulated time for part 1 (default 5)")
    ap.add_argument("--steps", type=int, default=200000, help="steps for part 2 (default 200000)")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "boxes.csv")
        loop = [timed(lambda: python_loop(a.duration)) for _ in range(a.repeats)]
        run = [timed(lambda: cli_run(a.duration, out)) for _ in range(a.repeats)]
    ml, mr = statistics.median(loop), statistics.median(run)
    print(f"100 boxes, {a.duration:g} s: python step loop {ml:.3f} s, simbob run {mr:.3f} s "
          f"(median of {a.repeats}); ratio {ml / mr:.3f} (target <= 1.05)")

    def single():
        sim = simbob.Simulation.from_text(ONE_BODY, "one.xml")
        for _ in range(a.steps):
            sim.step()

    def batched():
        sim = simbob.Simulation.from_text(ONE_BODY, "one.xml")
        sim.step(a.steps)

    s = [timed(single) for _ in range(a.repeats)]
    b = [timed(batched) for _ in range(a.repeats)]
    per_call = (statistics.median(s) - statistics.median(b)) / a.steps * 1e6
    print(f"one body, {a.steps} steps: step() each {statistics.median(s):.3f} s, step(n) "
          f"{statistics.median(b):.3f} s; {per_call:.2f} us per step() call above the physics (target <= 2)")


if __name__ == "__main__":
    main()
