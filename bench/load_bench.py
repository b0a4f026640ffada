#!/usr/bin/env python3
"""Load time and peak RSS: simbob against bare ODE building the same N-box world (issue #9).

Usage: bench/load_bench.py --simbob build/simbob --bare build/bench/bare_ode [-n 5000] [-r 7]
                           [--callgrind] [--csv OUT.csv] [--label after] [--machine NAME]

Both programs build the world of bench/gen_scene.py and take a single 1 ms step (neither
accepts a zero duration), sampling t = 0 and t = 0.001: `bare_ode N 0.001 OUT` and
`simbob run scene.xml --duration 0.001 --out OUT -q`. So the figures are start-up + scene load +
compile + world creation + writing 2 x N CSV rows, the same rows for both (checked with cmp).
Each program runs R times, in turn, order reversed on every repetition, under /usr/bin/time;
medians of wall time, CPU time (user + system) and peak RSS are printed, with simbob/bare
ratios. --callgrind adds one valgrind instruction count per program (independent of load).
"""
import argparse
import csv
import datetime
import filecmp
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))


def timed(cmd):
    out = subprocess.run(["/usr/bin/time", "-f", "@@ %e %U %S %M"] + cmd, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"load_bench: {' '.join(cmd)} failed:\n{out.stderr}")
    m = re.search(r"@@ ([\d.]+) ([\d.]+) ([\d.]+) (\d+)", out.stderr)
    wall, user, sys_, rss_kb = float(m[1]), float(m[2]), float(m[3]), int(m[4])
    return {"wall_s": wall, "cpu_s": user + sys_, "rss_mb": rss_kb / 1024}


def instructions(cmd):
    out = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null"] + cmd,
                         capture_output=True, text=True)
    m = re.search(r"refs:\s+([\d,]+)", out.stderr)
    return int(m[1].replace(",", "")) if m else None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--simbob", required=True)
    ap.add_argument("--bare", required=True)
    ap.add_argument("-n", type=int, default=5000, help="boxes (default 5000)")
    ap.add_argument("-r", type=int, default=7, help="repetitions (default 7)")
    ap.add_argument("--callgrind", action="store_true", help="also count instructions (valgrind)")
    ap.add_argument("--csv", help="append the medians to this CSV")
    ap.add_argument("--label", default="", help="a name for this build in the CSV (before, after...)")
    ap.add_argument("--machine", default=platform.node() or "?", help="machine name for the CSV")
    args = ap.parse_args()

    work = tempfile.mkdtemp(prefix="simbob-load-")
    scene = os.path.join(work, f"boxes{args.n}.xml")
    subprocess.run([sys.executable, os.path.join(HERE, "gen_scene.py"), str(args.n), scene], check=True)
    progs = {
        "bare": [args.bare, str(args.n), "0.001", os.path.join(work, "bare.csv")],
        "simbob": [args.simbob, "run", scene, "--duration", "0.001", "--out", os.path.join(work, "simbob.csv"), "-q"],
    }
    runs = {p: [] for p in progs}
    order = list(progs)
    for rep in range(args.r):
        for p in order if rep % 2 == 0 else reversed(order):
            runs[p].append(timed(progs[p]))
    if not filecmp.cmp(os.path.join(work, "bare.csv"), os.path.join(work, "simbob.csv"), shallow=False):
        sys.exit("load_bench: the two CSV files differ")
    med = {p: {k: statistics.median(r[k] for r in runs[p]) for k in runs[p][0]} for p in progs}
    if args.callgrind:
        for p in progs:
            med[p]["instructions"] = instructions(progs[p])

    print(f"{args.n} boxes, {args.r} runs each, medians (load average {os.getloadavg()[0]:.1f})")
    keys = list(med["bare"])
    print(f"{'':8}" + "".join(f"{k:>16}" for k in keys))
    for p in progs:
        print(f"{p:8}" + "".join(f"{med[p][k]:>16.3f}" if isinstance(med[p][k], float) else f"{med[p][k]:>16,}"
                                 for k in keys))
    print(f"{'ratio':8}" + "".join(f"{med['simbob'][k] / med['bare'][k]:>16.2f}" for k in keys))

    if args.csv:
        new = not os.path.exists(args.csv)
        with open(args.csv, "a", newline="") as f:
            w = csv.writer(f)
            if new:
                w.writerow(["date", "machine", "label", "program", "n", "runs"] + keys + ["ratio_" + k for k in keys])
            date = datetime.date.today().isoformat()
            for p in progs:
                w.writerow([date, args.machine, args.label, p, args.n, args.r] +
                           [f"{med[p][k]:.4f}" if isinstance(med[p][k], float) else med[p][k] for k in keys] +
                           [f"{med[p][k] / med['bare'][k]:.3f}" for k in keys])
    return 0


if __name__ == "__main__":
    sys.exit(main())
