#!/usr/bin/env python3
"""Runs the side-by-side benchmark: bare ODE (bench/bare_ode), simbob, MuJoCo (mujoco-testspeed).

Usage: bench/run_bench.py --simbob build/simbob --bare build/bench/bare_ode
                          [--mujoco /usr/bin/mujoco-testspeed] [--quick] [--results bench/results]

scripts/bench.sh builds the programs and calls this. For every N the three programs run in
turn (the order reversed every repetition), each on the same scene (bench/gen_scene.py,
bench/gen_mjcf.py) for the same number of 1 ms steps. Each run is a child process; its wall time
comes from time.perf_counter around it, its CPU time and peak RSS from wait4() (what GNU time's
%U %S %M report). Medians are printed and written to RESULTS/<date>-<machine>.csv, every single
run to RESULTS/<date>-<machine>-runs.csv.

Three rates per run:
  wall  = steps / wall time of the whole process (start-up, scene load, stepping, output);
  loop  = steps / the program's own timer: simbob's wall_seconds (JSON summary) and bare_ode's
          loop_seconds both cover world creation, stepping, sampling and CSV formatting;
          mujoco-testspeed times mj_step alone and writes no trajectory;
  cpu   = steps / (user + system CPU time) of the process; least disturbed by other load.
"""
import argparse
import datetime
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))

# N, simulated seconds (1 ms steps), repetitions. Durations give runs of about 2 s (quick:
# 0.5 s) of bare ODE on the 2-core AMD EPYC VM of docs/performance.md; the boxes land after 14 ms.
FULL = [(10, 40.0, 5), (100, 3.0, 5), (1000, 0.5, 5), (5000, 0.15, 3)]
QUICK = [(10, 10.0, 3), (100, 0.8, 3), (1000, 0.1, 3), (5000, 0.05, 1)]
# CSV writing: LOAD_BODIES falling boxes for CSV_STEPS steps (all before they land, so the steps
# are cheap), sampled every step versus at the start and the end only.
CSV_STEPS = 13
LOAD_BODIES = 10000


def log(msg):
    print(msg, file=sys.stderr, flush=True)


GNU_TIME = "/usr/bin/time"


def run(cmd, stdout_path):
    """Runs cmd under GNU time; returns (returncode, wall s, cpu s, peak RSS KiB, stdout text).

    The peak RSS is GNU time's %M: the program's own, measured by the small `time` process that
    forks it. (wait4() on a child forked by Python would report at least Python's RSS, which
    the forked child starts with.) CPU time is user + system from wait4() on the `time` process,
    which includes the program it waited for; wall time is perf_counter around it all.
    """
    rss_path = stdout_path + ".rss"
    with open(stdout_path, "w") as out:
        t0 = time.perf_counter()
        p = subprocess.Popen([GNU_TIME, "-f", "%M", "-o", rss_path, "--"] + cmd, stdout=out,
                             stderr=subprocess.STDOUT)
        _, status, ru = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    with open(stdout_path) as f:
        text = f.read()
    rss = float("nan")
    try:
        with open(rss_path) as f:
            rss = float(f.read().split()[-1])
    except (OSError, ValueError, IndexError):
        pass
    return p.returncode, wall, ru.ru_utime + ru.ru_stime, rss, text


def last_json(text):
    """The JSON object printed on stdout (simbob --json prints several lines, bare_ode one)."""
    start = text.find("{")
    end = text.rfind("}")
    return json.loads(text[start:end + 1]) if start >= 0 and end > start else None


def machine_info():
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    nproc = os.cpu_count() or 1
    slug = re.sub(r"[^a-z0-9]+", "-", cpu.lower()).strip("-") or "cpu"
    return cpu, nproc, f"{slug}-{nproc}cpu"


def loadavg():
    try:
        return os.getloadavg()[0]
    except OSError:
        return float("nan")


class Bench:
    def __init__(self, args, work):
        self.a = args
        self.work = work
        self.runs = []  # dicts, one per run

    def scene(self, n):
        path = os.path.join(self.work, f"boxes{n}.xml")
        if not os.path.exists(path):
            subprocess.check_call([sys.executable, os.path.join(HERE, "gen_scene.py"), str(n), path])
        return path

    def mjcf(self, n):
        path = os.path.join(self.work, f"boxes{n}.mjcf.xml")
        if not os.path.exists(path):
            subprocess.check_call([sys.executable, os.path.join(HERE, "gen_mjcf.py"), str(n), path])
        return path

    def one(self, prog, n, duration, rep, sample_interval=None, tag="steps"):
        steps = int(round(duration * 1000))
        out_csv = os.path.join(self.work, f"{prog}{n}.csv")
        stdout_path = os.path.join(self.work, f"{prog}{n}.out")
        if prog == "bare":
            cmd = [self.a.bare, str(n), repr(duration), out_csv]
            if sample_interval:
                cmd.append(repr(sample_interval))
        elif prog == "simbob":
            cmd = [self.a.simbob, "run", self.scene(n), "--duration", repr(duration), "--out", out_csv,
                   "--json", "-q"]
            if sample_interval:
                cmd += ["--sample-interval", repr(sample_interval)]
        elif prog == "mujoco":
            cmd = [self.a.mujoco, self.mjcf(n), str(steps), "1", "0"]
        elif prog == "load":
            cmd = [self.a.simbob, "check", self.scene(n), "-q"]
        else:
            raise ValueError(prog)
        rc, wall, cpu, rss, text = run(cmd, stdout_path)
        rec = {"tag": tag, "program": prog, "n": n, "rep": rep, "sim_seconds": duration,
               "steps": steps if prog != "load" else 0, "wall_s": wall, "cpu_s": cpu,
               "loop_s": float("nan"), "rss_mb": rss / 1024.0, "csv_bytes": 0, "ok": rc == 0,
               "sample_s": float("nan"), "note": "", "load1": loadavg()}
        err = [l.strip() for l in text.splitlines() if l.strip().lower().startswith(("error", "simbob: error"))]
        if rc != 0 or err:
            rec["ok"] = False
            rec["note"] = (err or text.strip().splitlines() or [f"exit {rc}"])[-1][:120]
            if prog == "mujoco" and "mjData" in rec["note"]:
                rec["note"] += " (MuJoCo 2.2 allocates constraint memory growing with njmax^2)"
        elif prog in ("bare", "simbob"):
            j = last_json(text)
            rec["steps"] = j["steps"]
            rec["loop_s"] = j["loop_seconds"] if prog == "bare" else j["wall_seconds"]
            rec["csv_bytes"] = j["csv_bytes"]
            rec["sample_s"] = j.get("sample_seconds", float("nan"))
        elif prog == "mujoco":
            m = re.search(r"Steps per second\s*:\s*([0-9.]+)", text)
            if m and float(m.group(1)) > 0:
                rec["loop_s"] = steps / float(m.group(1))
            else:
                rec["ok"] = False
                rec["note"] = "no 'Steps per second' in the output"
        if os.path.exists(out_csv):
            os.remove(out_csv)
        self.runs.append(rec)
        return rec

    def med(self, tag, prog, n, key, how=statistics.median):
        vals = [r[key] for r in self.runs if r["tag"] == tag and r["program"] == prog and r["n"] == n and r["ok"]]
        return how(vals) if vals else float("nan")

    def fails(self, tag, prog, n):
        return [r for r in self.runs if r["tag"] == tag and r["program"] == prog and r["n"] == n and not r["ok"]]


def fmt(x, digits=0):
    if x != x:  # NaN
        return "n/a"
    return f"{x:,.{digits}f}"


def ratio(a, b):
    return a / b if a == a and b == b and b > 0 else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--simbob", required=True)
    ap.add_argument("--bare", required=True)
    ap.add_argument("--mujoco", default=shutil.which("mujoco-testspeed"))
    ap.add_argument("--quick", action="store_true", help="about a minute instead of several")
    ap.add_argument("--results", default=os.path.join(HERE, "results"), help="folder for the CSV files")
    ap.add_argument("--no-save", action="store_true", help="print only")
    a = ap.parse_args()
    plan = QUICK if a.quick else FULL
    programs = ["bare", "simbob"] + (["mujoco"] if a.mujoco else [])
    if not a.mujoco:
        log("bench: mujoco-testspeed not found; MuJoCo columns stay empty")

    cpu, nproc, machine = machine_info()
    stamp = datetime.datetime.now()
    started = time.perf_counter()
    load_start = loadavg()
    work = tempfile.mkdtemp(prefix="simbob-bench-")
    b = Bench(a, work)
    try:
        # Warm-up (page cache, dynamic loader) -- not recorded.
        for prog in programs:
            b.one(prog, 10, 0.1, -1, tag="warmup")
        for n, duration, reps in plan:
            log(f"bench: N={n}: {reps} x {len(programs)} runs of {int(round(duration * 1000))} steps")
            for rep in range(reps):
                order = programs if rep % 2 == 0 else list(reversed(programs))
                for prog in order:
                    r = b.one(prog, n, duration, rep)
                    if not r["ok"]:
                        log(f"bench:   {prog} N={n} failed: {r['note']}")

        # simbob's scene load (parse, build the graph, compile) for 10,000 bodies: `simbob check`.
        load_reps = 1 if a.quick else 3
        log(f"bench: scene load of {LOAD_BODIES} bodies: {load_reps} x simbob check")
        for rep in range(load_reps):
            b.one("load", LOAD_BODIES, 0.0, rep, tag="load")
        scene_mb = os.path.getsize(b.scene(LOAD_BODIES)) / 1e6

        # CSV throughput: the extra loop time (and CPU time) per extra byte of sampling every
        # step instead of at the ends only is the cost of taking, formatting and writing samples.
        # Fastest of the repetitions: the difference is small next to the noise of a busy machine.
        csv_reps = 2 if a.quick else 5
        log(f"bench: CSV writing: {csv_reps} x 2 x 2 runs of {CSV_STEPS} steps of {LOAD_BODIES} bodies")
        for rep in range(csv_reps):
            for prog in ("bare", "simbob"):
                b.one(prog, LOAD_BODIES, CSV_STEPS / 1000, rep, sample_interval=0.001, tag="csv-every-step")
                b.one(prog, LOAD_BODIES, CSV_STEPS / 1000, rep, sample_interval=1.0, tag="csv-ends-only")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    total = time.perf_counter() - started
    load_end = loadavg()

    # ---- tables ----
    rows = []
    for n, duration, reps in plan:
        row = {"n": n, "steps": int(round(duration * 1000)), "reps": reps}
        for prog in ("bare", "simbob", "mujoco"):
            wall = b.med("steps", prog, n, "wall_s")
            loop = b.med("steps", prog, n, "loop_s")
            cpu_s = b.med("steps", prog, n, "cpu_s")
            row[f"{prog}_wall_sps"] = row["steps"] / wall if wall == wall else float("nan")
            row[f"{prog}_loop_sps"] = row["steps"] / loop if loop == loop else float("nan")
            row[f"{prog}_cpu_sps"] = row["steps"] / cpu_s if cpu_s == cpu_s else float("nan")
            row[f"{prog}_rss_mb"] = b.med("steps", prog, n, "rss_mb")
            f = b.fails("steps", prog, n)
            row[f"{prog}_note"] = f[0]["note"] if f else ""
        rows.append(row)

    def table(kind, title):
        print(title)
        head = (f"{'N':>5} {'steps':>6} | {'bare st/s':>10} {'simbob st/s':>11} {'mujoco st/s':>11} | "
                f"{'simbob/bare':>11} {'simbob/mujoco':>13} | {'RSS MB bare':>11} {'simbob':>7} {'mujoco':>7}")
        print(head)
        print("-" * len(head))
        for r in rows:
            print(f"{r['n']:>5} {r['steps']:>6} | {fmt(r[f'bare_{kind}_sps']):>10} {fmt(r[f'simbob_{kind}_sps']):>11} "
                  f"{fmt(r[f'mujoco_{kind}_sps']):>11} | "
                  f"{fmt(ratio(r[f'simbob_{kind}_sps'], r[f'bare_{kind}_sps']), 3):>11} "
                  f"{fmt(ratio(r[f'simbob_{kind}_sps'], r[f'mujoco_{kind}_sps']), 2):>13} | "
                  f"{fmt(r['bare_rss_mb'], 1):>11} {fmt(r['simbob_rss_mb'], 1):>7} {fmt(r['mujoco_rss_mb'], 1):>7}")
        print()

    print()
    print(f"simbob benchmark, {stamp:%Y-%m-%d %H:%M}, {cpu}, {nproc} CPUs, "
          f"load average {load_start:.2f} at start, {load_end:.2f} at end, {total:.0f} s"
          + (" (--quick)" if a.quick else ""))
    print(f"Scene: N boxes of 0.2 m resting on a plane, ODE QuickStep 20 iterations, dt 1 ms, "
          f"samples every 0.01 s (MuJoCo: Newton, no output). Medians.")
    print()
    table("wall", "Steps per second of wall time (whole process: start-up, load, stepping, output):")
    table("loop", "Steps per second of each program's own timer (simbob/bare: world + stepping + sampling "
                  "+ CSV; mujoco: mj_step only):")
    table("cpu", "Steps per second of CPU time (user + system) of the process:")
    notes = sorted({(r["n"], r["program"], r["note"]) for r in b.runs if not r["ok"] and r["tag"] == "steps"})
    for n, prog, note in notes:
        print(f"note: {prog} N={n}: {note}")
    if notes:
        print()

    load_wall = b.med("load", "load", LOAD_BODIES, "wall_s")
    load_rss = b.med("load", "load", LOAD_BODIES, "rss_mb")
    print(f"simbob scene load, {LOAD_BODIES} bodies ({scene_mb:.1f} MB of XML): `simbob check` "
          f"{fmt(load_wall, 3)} s wall ({fmt(scene_mb / load_wall if load_wall else float('nan'), 1)} MB/s), "
          f"peak RSS {fmt(load_rss, 1)} MB")
    csv_rates = {}
    for prog in ("bare", "simbob"):
        lo_e = b.med("csv-every-step", prog, LOAD_BODIES, "loop_s", min)
        lo_n = b.med("csv-ends-only", prog, LOAD_BODIES, "loop_s", min)
        by_e = b.med("csv-every-step", prog, LOAD_BODIES, "csv_bytes")
        by_n = b.med("csv-ends-only", prog, LOAD_BODIES, "csv_bytes")
        cpu_e = b.med("csv-every-step", prog, LOAD_BODIES, "cpu_s", min)
        cpu_n = b.med("csv-ends-only", prog, LOAD_BODIES, "cpu_s", min)
        mb = (by_e - by_n) / 1e6
        rate = mb / (lo_e - lo_n) if lo_e == lo_e and lo_n == lo_n and lo_e > lo_n else float("nan")
        cpu_rate = mb / (cpu_e - cpu_n) if cpu_e == cpu_e and cpu_n == cpu_n and cpu_e > cpu_n else float("nan")
        csv_rates[prog] = rate
        csv_rates[prog + "_cpu"] = cpu_rate
        print(f"CSV writing, {prog:>6}: {fmt(mb, 1)} MB more in {fmt(lo_e - lo_n, 3)} s more loop time "
              f"= {fmt(rate, 0)} MB/s; {fmt(cpu_e - cpu_n, 3)} s more CPU = {fmt(cpu_rate, 0)} MB/s of CPU "
              f"(sampling + formatting + write)")
    smp = b.med("csv-every-step", "bare", LOAD_BODIES, "sample_s", min)
    by_e = b.med("csv-every-step", "bare", LOAD_BODIES, "csv_bytes")
    csv_rates["bare_timer"] = by_e / 1e6 / smp if smp == smp and smp > 0 else float("nan")
    print(f"CSV writing, bare_ode's own timer around its samples: {fmt(by_e / 1e6, 1)} MB in {fmt(smp, 3)} s "
          f"= {fmt(csv_rates['bare_timer'], 0)} MB/s")
    print()

    if a.no_save:
        return 0
    os.makedirs(a.results, exist_ok=True)
    base = os.path.join(a.results, f"{stamp:%Y-%m-%d}-{machine}{'-quick' if a.quick else ''}")
    cols = ["n", "steps", "reps"] + [f"{p}_{k}" for p in ("bare", "simbob", "mujoco")
                                      for k in ("wall_sps", "loop_sps", "cpu_sps", "rss_mb")]
    with open(base + ".csv", "w") as f:
        f.write(f"# simbob benchmark {stamp:%Y-%m-%d %H:%M}; cpu={cpu}; nproc={nproc}; "
                f"loadavg_start={load_start:.2f}; loadavg_end={load_end:.2f}; medians\n")
        f.write(",".join(cols + ["simbob_over_bare_wall", "simbob_over_mujoco_wall", "simbob_over_bare_loop",
                                 "simbob_over_mujoco_loop", "mujoco_note"]) + "\n")
        for r in rows:
            vals = [f"{r[c]:.6g}" if isinstance(r[c], float) else str(r[c]) for c in cols]
            vals += [f"{ratio(r['simbob_wall_sps'], r['bare_wall_sps']):.4f}",
                     f"{ratio(r['simbob_wall_sps'], r['mujoco_wall_sps']):.4f}",
                     f"{ratio(r['simbob_loop_sps'], r['bare_loop_sps']):.4f}",
                     f"{ratio(r['simbob_loop_sps'], r['mujoco_loop_sps']):.4f}",
                     '"' + r["mujoco_note"].replace('"', "'") + '"']
            f.write(",".join(vals) + "\n")
        f.write(f"# scene_load_{LOAD_BODIES}_bodies_wall_s={load_wall:.4f}; scene_mb={scene_mb:.2f}; "
                f"load_rss_mb={load_rss:.1f}; csv_mb_per_s_simbob={csv_rates['simbob']:.1f}; "
                f"csv_mb_per_s_bare={csv_rates['bare']:.1f}; csv_mb_per_cpu_s_simbob={csv_rates['simbob_cpu']:.1f}; "
                f"csv_mb_per_cpu_s_bare={csv_rates['bare_cpu']:.1f}; "
                f"csv_mb_per_s_bare_own_timer={csv_rates['bare_timer']:.1f}\n")
    keys = ["tag", "program", "n", "rep", "sim_seconds", "steps", "wall_s", "cpu_s", "loop_s", "rss_mb",
            "csv_bytes", "sample_s", "ok", "load1", "note"]
    with open(base + "-runs.csv", "w") as f:
        f.write(",".join(keys) + "\n")
        for r in b.runs:
            f.write(",".join('"' + str(r[k]).replace('"', "'") + '"' if k == "note" else
                             (f"{r[k]:.6g}" if isinstance(r[k], float) else str(r[k])) for k in keys) + "\n")
    print(f"wrote {base}.csv and {base}-runs.csv")
    return 0


if __name__ == "__main__":
    sys.exit(main())
