"""What the Python module costs over `simbob run` (issue #20's targets): python_bench.py [--repeats R]

1. A Python loop of sim.step() over bench/scenes/boxes100.xml (100 boxes, 1 ms steps), reading
   the poses every 10 steps as `run` samples them, against `build/simbob run` of the same scene
   and duration writing its CSV (target: the loop within 5 % of run).
2. The cost of one step() call above the physics, on a one-body scene: step() one step at a time
   against step(n) of the same n steps in one call (target: <= 2 us per call).
3. Batch throughput: simbob.Batch of W worlds of the 100-box scene stepped 1 s (in calls of
   step(100)) with 1 and 2 worker processes (and in-process, workers=0), in world-steps per
   second (target: 2 workers >= 1.8x 1 worker on 2 cores). --batch-only runs this part alone.
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


def process_cpu(pid):
    """User + system CPU seconds of a live process (/proc/PID/stat)."""
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def batch_throughput(a):
    """Part 3: world-steps per second of a Batch with 0 (in-process), 1 and 2 workers.

    Besides the wall time it reads each stepping process's CPU time (this one for workers=0,
    each worker's before close()). On a loaded machine the wall time says little: with the
    kernel's autogroup scheduling (kernel.sched_autogroup_enabled) the CPU is shared between
    sessions, and all the workers of a Batch are in the caller's session, so under contention
    two workers share one session's slice. The CPU times give the speedup the split allows
    when each worker has a core: (CPU of the 1-worker run) / (CPU of the busiest of 2 workers)."""
    steps = int(round(a.batch_duration / 0.001))
    rates, busiest = {}, {}
    for workers in (0, 1, 2):
        times, cpus = [], []
        for _ in range(a.repeats):
            with simbob.Batch(BOXES, a.worlds, workers=workers) as b:  # forking is not timed
                pids = b._pids or [os.getpid()]  # the workers, or this process (workers=0)
                before = [process_cpu(p) for p in pids]

                def run():
                    for _ in range(steps // 100):
                        b.step(100)
                        b.poses()
                times.append(timed(run))
                cpus.append(max(process_cpu(p) - c for p, c in zip(pids, before)))
        wall, cpu = statistics.median(times), statistics.median(cpus)
        rates[workers], busiest[workers] = a.worlds * steps / wall, cpu
        print(f"Batch of {a.worlds} x 100 boxes, {a.batch_duration:g} s each, workers={workers}: "
              f"median {wall:.3f} s (min {min(times):.3f}, max {max(times):.3f}); "
              f"{rates[workers]:.0f} world-steps/s; busiest stepping process {cpu:.3f} s CPU "
              f"({cpu / wall:.2f} of a core)")
    print(f"Batch: 2 workers / 1 worker = {rates[2] / rates[1]:.2f}x wall (target >= 1.8); "
          f"by CPU time, with a core per worker: {busiest[1] / busiest[2]:.2f}x; "
          f"1 worker / in-process = {rates[1] / rates[0]:.3f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--duration", type=float, default=5.0, help="s of simulated time for part 1 (default 5)")
    ap.add_argument("--steps", type=int, default=200000, help="steps for part 2 (default 200000)")
    ap.add_argument("--worlds", type=int, default=4, help="worlds in the Batch of part 3 (default 4)")
    ap.add_argument("--batch-duration", type=float, default=1.0, help="s of simulated time per world in part 3")
    ap.add_argument("--batch-only", action="store_true", help="run part 3 only")
    a = ap.parse_args()
    if a.batch_only:
        batch_throughput(a)
        return
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
    batch_throughput(a)


if __name__ == "__main__":
    main()
