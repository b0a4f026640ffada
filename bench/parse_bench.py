#!/usr/bin/env python3
"""Loading at the parser's pace (issue 32, point 2): `simbob check` of an N-box scene against a
bare pugixml parse of the same file (build/bench/bare_parse), at 1,000, 5,000 and 20,000 boxes.

Usage: bench/parse_bench.py --simbob build/simbob --bare build/bench/bare_parse
                            [-n 1000,5000,20000] [-r 7] [--callgrind]

`simbob check FILE` reads the file, parses it, builds the component graph, resolves imports and
Refs, compiles the model and runs the checks (lint); bare_parse reads the file and parses it with
the same pugixml call (and counts the elements). Each program runs R times per size, in turn,
order reversed on every repetition: wall time and CPU time (user + system, getrusage of the
child), medians; peak RSS from 3 more runs under /usr/bin/time. Printed with simbob/bare ratios
(the goal: time within 3x, memory within 2x). --callgrind adds one instruction count per program
and size (independent of the machine's load).
"""
import argparse
import os
import platform
import re
import statistics
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True
HERE = os.path.dirname(os.path.abspath(__file__))


def timed(cmd):
    # getrusage of the child (os.wait4): CPU time in microseconds; /usr/bin/time rounds to 10 ms,
    # more than a bare parse of 1,000 bodies takes.
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    err = proc.stderr.read().decode()
    _, status, ru = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    proc.stderr.close()
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"parse_bench: {' '.join(cmd)} failed:\n{err}")
    return {"wall_s": wall, "cpu_s": ru.ru_utime + ru.ru_stime}


def peak_rss_mb(cmd):
    # Under /usr/bin/time: a child of Python would inherit Python's resident set as the floor of
    # its peak (Linux keeps the high-water mark across exec).
    out = subprocess.run(["/usr/bin/time", "-f", "@@ %M"] + cmd, capture_output=True, text=True)
    return int(re.search(r"@@ (\d+)", out.stderr)[1]) / 1024


def instructions(cmd):
    out = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null"] + cmd,
                         capture_output=True, text=True)
    m = re.search(r"refs:\s+([\d,]+)", out.stderr)
    return int(m[1].replace(",", "")) if m else None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--simbob", required=True)
    ap.add_argument("--bare", required=True)
    ap.add_argument("-n", default="1000,5000,20000", help="box counts, comma separated")
    ap.add_argument("-r", type=int, default=7, help="repetitions (default 7)")
    ap.add_argument("--callgrind", action="store_true", help="also count instructions (valgrind)")
    args = ap.parse_args()
    work = tempfile.mkdtemp(prefix="simbob-parse-")
    print(f"machine: {platform.node()}, {os.cpu_count()} CPUs; {args.r} runs each, medians; "
          f"load average {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    keys = ["wall_s", "cpu_s", "rss_mb"] + (["instructions"] if args.callgrind else [])
    print(f"{'boxes':>6} {'program':>7}" + "".join(f"{k:>15}" for k in keys))
    for n in (int(x) for x in args.n.split(",")):
        scene = os.path.join(work, f"boxes{n}.xml")
        subprocess.run([sys.executable, os.path.join(HERE, "gen_scene.py"), str(n), scene], check=True)
        progs = {"bare": [args.bare, scene], "simbob": [args.simbob, "check", scene, "-q"]}
        runs = {p: [] for p in progs}
        for rep in range(args.r):
            for p in progs if rep % 2 == 0 else reversed(list(progs)):
                runs[p].append(timed(progs[p]))
        med = {p: {k: statistics.median(r[k] for r in runs[p]) for k in runs[p][0]} for p in progs}
        for p in progs:
            med[p]["rss_mb"] = statistics.median(peak_rss_mb(progs[p]) for _ in range(3))
        if args.callgrind:
            for p in progs:
                med[p]["instructions"] = instructions(progs[p])
        for p in progs:
            print(f"{n:>6} {p:>7}" + "".join(f"{med[p][k]:>15.3f}" if isinstance(med[p][k], float)
                                             else f"{med[p][k]:>15,}" for k in keys))
        print(f"{n:>6} {'ratio':>7}" + "".join(f"{med['simbob'][k] / med['bare'][k]:>14.2f}x" if med['bare'][k]
                                             else f"{'-':>15}" for k in keys))
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
