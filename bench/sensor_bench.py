#!/usr/bin/env python3
"""Sensor benchmarks of issue #21: cost per ray, and 100 robots with scanners against real time.

Usage: bench/sensor_bench.py [--simbob build/simbob] [--ray-bench build/bench/ray_bench]
                             [--repeats 3] [--seconds 10] [--results bench/results]

1. build/bench/ray_bench (bench/ray_bench.cpp): ns per ray of a 360-ray scanner read every step
   against 10, 100 and 1,000 static boxes (median of its own repeats).
2. `simbob run` on bench/gen_robots.py scanners: 100 robots, each with a 36-ray 360-degree laser
   scanner read at 10 Hz by an RCWallFollower, for --seconds of simulated time; the real-time
   factor is simulated seconds / wall_seconds of the JSON summary, and / the process's CPU time
   (user + system, least disturbed by other load); medians of --repeats runs.
   The baseline is the same scene with the scanners and followers read once (Period 1000 s: one
   scan at t = 0): what the 100 robots cost without sensing.
Prints the figures and writes them to RESULTS/<date>-<machine>-sensors.txt. Never a test:
wall-clock times depend on the machine and its load.
"""
import argparse
import datetime
import json
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def machine():
    cpu = "cpu"
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    return cpu, f"{re.sub(r'[^a-z0-9]+', '-', cpu.lower()).strip('-')}-{os.cpu_count()}cpu"


def realtime(simbob, scene, seconds, repeats, work):
    """Real-time factors (simulated s per wall s of the run's own timer, and per CPU s of the
    process: the latter is least disturbed by other load) and the wall times."""
    walls, cpus = [], []
    for r in range(repeats):
        out = os.path.join(work, f"run{r}.csv")
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.check_call([simbob, "run", scene, "--duration", str(seconds), "--out", out, "--quiet"])
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
        with open(out[:-4] + ".json") as f:
            walls.append(json.load(f)["wall_seconds"])
    return seconds / statistics.median(walls), seconds / statistics.median(cpus), walls


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--simbob", default=os.path.join(ROOT, "build", "simbob"))
    ap.add_argument("--ray-bench", default=os.path.join(ROOT, "build", "bench", "ray_bench"))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--seconds", type=float, default=10)
    ap.add_argument("--results", default=os.path.join(HERE, "results"))
    a = ap.parse_args()
    cpu, slug = machine()
    lines = [f"{datetime.date.today()} on {cpu} ({os.cpu_count()} CPUs), load {os.getloadavg()[0]:.2f} at start"]
    lines.append("cost per ray (bench/ray_bench, median of 5):")
    lines += ["  " + l for l in subprocess.check_output([a.ray_bench], text=True).strip().splitlines()]
    with tempfile.TemporaryDirectory(prefix="simbob-sensors-") as work:
        scene = os.path.join(work, "scanners.xml")
        base = os.path.join(work, "baseline.xml")
        gen = [sys.executable, os.path.join(HERE, "gen_robots.py")]
        subprocess.check_call(gen + ["scanners", scene, "--robots", "100", "--rays", "36", "--period", "0.1"])
        subprocess.check_call(gen + ["scanners", base, "--robots", "100", "--rays", "36", "--period", "1000"])
        f_scan, c_scan, w_scan = realtime(a.simbob, scene, a.seconds, a.repeats, work)
        f_base, c_base, w_base = realtime(a.simbob, base, a.seconds, a.repeats, work)
    lines.append(f"100 robots, 36-ray scanners at 10 Hz, {a.seconds:g} s simulated: {f_scan:.2f}x real time by "
                 f"wall clock, {c_scan:.2f}x by CPU time (median of {a.repeats}: wall s "
                 f"{', '.join(f'{w:.2f}' for w in w_scan)}; target >= 1)")
    lines.append(f"the same 100 robots scanning once (baseline): {f_base:.2f}x by wall clock, {c_base:.2f}x by CPU "
                 f"time (wall s {', '.join(f'{w:.2f}' for w in w_base)})")
    text = "\n".join(lines) + "\n"
    sys.stdout.write(text)
    os.makedirs(a.results, exist_ok=True)
    with open(os.path.join(a.results, f"{datetime.date.today()}-{slug}-sensors.txt"), "w") as f:
        f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
