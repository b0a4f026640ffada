#!/usr/bin/env python3
"""Thread scaling of one world (`simbob run --threads N`, issue 32): the 100-robot scanner scene
and a 1,000-box pile, side by side at 1, 2, ... threads.

Usage: bench/threads_bench.py --simbob build/simbob [--threads 1,2] [-r 5] [--duration 3]
                              [--profile] [--out results/FILE.txt]

The scenes:
  robots   bench/gen_robots.py scanners --robots 100: 100 two-wheeled wall followers with a
           36-ray laser scanner read at 10 Hz, each in its own lane (800 geoms).
  pile     1,000 boxes of 0.2 m dropped in 10 layers of 10 x 10 onto the ground, each a little
           turned and shifted, so that they land on one another: box-box contacts from the
           first layer's landing on (gen_pile below).

Every run writes its trajectory; the bytes of every thread count must equal those of one thread
(checked, or the benchmark stops). Runs alternate between thread counts, order reversed on every
repetition; for each it takes the wall time and the CPU time (user + system, getrusage of the
child). Medians and the speed-up against one thread are printed, with the load average before
and after: on a shared machine the wall-clock scaling means little while others run.

--profile adds, per scene, callgrind's instruction counts of a run on 2 threads: the share of
the instructions spent in the jobs that run in parallel (the broad phase's sweep, the narrow
phase's and the rays' chunk jobs: lib/physics/broadphase.cpp, contacts.cpp and rays.cpp) is p;
1 - p is the serial fraction, and 1 / (1 - p + p / N) the most N threads can give (Amdahl).
"""
import argparse
import os
import platform
import random
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))


def gen_pile(path, n=1000, side=10):
    """n boxes of 0.2 m in layers of side x side, 0.205 m apart, each layer 0.25 m above the last,
    turned and shifted a little (seeded), over a ground plane: they land on one another."""
    rnd = random.Random(32)
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           f"<!-- {n} boxes dropped into a pile (bench/threads_bench.py) -->",
           "<Simulation>", "  <SceneSettings><MaxTimeStep Value=\"0.001\"/></SceneSettings>", "  <ComponentList>",
           '    <RCGround Key="Ground"><Material><RCGenericMaterial Key="Mat"><Friction Value="0.8"/>'
           '<Bounceness Value="0.1"/><MinBounceVel Value="0.1"/></RCGenericMaterial></Material></RCGround>']
    for i in range(n):
        layer, k = divmod(i, side * side)
        row, col = divmod(k, side)
        x = (col - side / 2) * 0.205 + rnd.uniform(-0.05, 0.05)
        z = (row - side / 2) * 0.205 + rnd.uniform(-0.05, 0.05)
        y = 0.11 + layer * 0.25
        a, b, c = (rnd.uniform(-20, 20) for _ in range(3))
        out.append(f'    <RCMobileRigidBody Key="Box{i}"><Pose><RCGlobalCoordinates><Pose Value="{x:.4f} {y:.4f} '
                   f'{z:.4f} {a:.2f} {b:.2f} {c:.2f}"/></RCGlobalCoordinates></Pose>'
                   '<Geom><RCCuboidGeom><Width Value="0.2"/><Height Value="0.2"/><Depth Value="0.2"/></RCCuboidGeom>'
                   '</Geom><Inertia><RCInertiaByGeom><Density Value="500.0"/></RCInertiaByGeom></Inertia>'
                   '<Material Ref="Ground.Mat"/></RCMobileRigidBody>')
    out += ["  </ComponentList>", "</Simulation>", ""]
    with open(path, "w") as f:
        f.write("\n".join(out))


def timed(cmd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    out = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode != 0:
        sys.exit(f"threads_bench: {' '.join(cmd)} failed:\n{out.stderr}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def parallel_share(simbob, scene, duration, work):
    """Instructions of a run on 2 threads, and the share in the parallel chunk jobs (callgrind)."""
    prof = os.path.join(work, f"callgrind.{os.path.splitext(os.path.basename(scene))[0]}.out")
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={prof}", simbob, "run", scene,
                    "--duration", str(duration), "--threads", "2", "--out", os.path.join(work, "prof.csv"), "-q"],
                   capture_output=True, check=True)
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", prof], capture_output=True,
                          text=True, check=True).stdout
    total = int(re.search(r"([\d,]+)\s+\(100\.0%\)\s+PROGRAM TOTALS", text)[1].replace(",", ""))
    jobs = 0
    for line in text.splitlines():
        # The chunk jobs WorkerPool::run runs (never inlined; broadphase.cpp, contacts.cpp,
        # rays.cpp), every file:function fragment of them (code inlined from headers is listed
        # apart).
        if re.search(r"^\s*[\d,]+ \([ \d.]+%\)\s+\S*:simbob::(\(anonymous namespace\)::(collideChunk|readSensorChunk)"
                     r"|HashSpacePairs::sweep)\(", line):
            jobs += int(line.split()[0].replace(",", ""))
    return total, jobs / total


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--simbob", required=True)
    ap.add_argument("--threads", default="1,2", help="thread counts, comma separated (default 1,2)")
    ap.add_argument("-r", type=int, default=5, help="repetitions (default 5)")
    ap.add_argument("--duration", type=float, default=3.0, help="simulated seconds per run (default 3)")
    ap.add_argument("--scenes", default="robots,pile")
    ap.add_argument("--profile", action="store_true", help="also the serial fraction from callgrind")
    ap.add_argument("--profile-duration", type=float, default=0.5)
    args = ap.parse_args()
    counts = [int(t) for t in args.threads.split(",")]
    work = tempfile.mkdtemp(prefix="simbob-threads-")
    scenes = {}
    if "robots" in args.scenes:
        scenes["robots"] = os.path.join(work, "robots100.xml")
        subprocess.run([sys.executable, os.path.join(HERE, "gen_robots.py"), "scanners", scenes["robots"],
                        "--robots", "100"], check=True)
    if "pile" in args.scenes:
        scenes["pile"] = os.path.join(work, "pile1000.xml")
        gen_pile(scenes["pile"])

    cpu_name = "?"
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            cpu_name = line.split(":", 1)[1].strip()
            break
    print(f"machine: {platform.node()}, {os.cpu_count()} CPUs, {cpu_name}")
    print(f"simbob run --duration {args.duration}, {args.r} runs per thread count, medians")
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    for name, scene in scenes.items():
        runs = {t: [] for t in counts}
        outs = {t: os.path.join(work, f"{name}.t{t}.csv") for t in counts}
        for rep in range(args.r):
            for t in counts if rep % 2 == 0 else list(reversed(counts)):
                runs[t].append(timed([args.simbob, "run", scene, "--duration", str(args.duration), "--threads",
                                      str(t), "--out", outs[t], "-q"]))
        base = open(outs[counts[0]], "rb").read()
        for t in counts[1:]:
            if open(outs[t], "rb").read() != base:
                sys.exit(f"threads_bench: {name}: {t} threads wrote other bytes than {counts[0]}")
        wall1 = statistics.median(w for w, _ in runs[counts[0]])
        print(f"\n{name}: {scene}  (identical bytes at every thread count)")
        print(f"{'threads':>8} {'wall s':>9} {'cpu s':>9} {'speed-up':>9} {'real time':>10}")
        for t in counts:
            wall = statistics.median(w for w, _ in runs[t])
            cpu = statistics.median(c for _, c in runs[t])
            print(f"{t:>8} {wall:>9.3f} {cpu:>9.3f} {wall1 / wall:>8.2f}x {args.duration / wall:>9.2f}x")
        if args.profile:
            total, p = parallel_share(args.simbob, scene, args.profile_duration, work)
            bound = " ".join(f"{n} threads <= {1 / (1 - p + p / n):.3f}x" for n in (2, 4, 16))
            print(f"  profile ({args.profile_duration} s on 2 threads, {total:,} instructions): parallel share "
                  f"p = {p:.4f}, serial fraction {1 - p:.4f}; Amdahl: {bound}")
    print(f"\nload average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
