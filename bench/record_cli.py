#!/usr/bin/env python3
"""Times `simbob run --video/--record` end to end on the recording benchmark's scene (issue #12).

Usage: bench/record_cli.py --simbob build/simbob [--scene bench/scenes/boxes100.xml]
                           [--frames 120] [--fps 30] [--size 640x480] [--format avi|mp4|png]
                           [--repeats 5]

Each repetition runs the CLI twice, in alternating order: once recording (`--video F.avi|F.mp4`
or `--record DIR` for png) for frames / fps simulated seconds less one frame (so that it records
exactly `--frames` frames, at t = 0 ... (frames - 1) / fps), and once without recording, the
same run otherwise (the trajectory CSV and its summary are written both times). Per run it prints
the process's wall time (perf_counter around it: start-up, loading, GL context, run, output) and
the run loop's own `wall_seconds` from the JSON summary, and at the end their medians and the
frames per second they give. Compare the `loop` rate with record_bench's `sequential` and
`pipelined` lines (same scene, same frames; record_bench writes no trajectory).
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def run_once(args, out_dir, record):
    duration = (args.frames - 1) / args.fps
    cmd = [args.simbob, "run", "-q", args.scene, "--duration", repr(duration + 1e-7),
           "--out", os.path.join(out_dir, "traj.csv"), "--json"]
    if record:
        cmd += ["--fps", repr(args.fps), "--size", args.size]
        if args.format == "png":
            frames = os.path.join(out_dir, "frames")
            shutil.rmtree(frames, ignore_errors=True)
            cmd += ["--record", frames]
        else:
            cmd += ["--video", os.path.join(out_dir, "video." + args.format)]
    start = time.perf_counter()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, check=False)
    wall = time.perf_counter() - start
    if p.returncode != 0:
        sys.stderr.write(f"record_cli: {' '.join(cmd)} failed ({p.returncode}):\n{p.stderr}")
        sys.exit(1)
    summary = json.loads(p.stdout)
    frames = summary.get("frames", 0)
    if record and frames != args.frames:
        sys.stderr.write(f"record_cli: recorded {frames} frames, expected {args.frames}\n")
        sys.exit(1)
    return wall, summary["wall_seconds"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--simbob", required=True)
    ap.add_argument("--scene", default=os.path.join(HERE, "scenes", "boxes100.xml"))
    ap.add_argument("--frames", type=int, default=120)
    ap.add_argument("--fps", type=float, default=30.0)
    ap.add_argument("--size", default="640x480")
    ap.add_argument("--format", choices=["avi", "mp4", "png"], default="mp4")
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    results = {True: ([], []), False: ([], [])}
    with tempfile.TemporaryDirectory(prefix="simbob_record_cli_") as out_dir:
        for rep in range(args.repeats):
            for record in ((True, False) if rep % 2 == 0 else (False, True)):
                wall, loop = run_once(args, out_dir, record)
                results[record][0].append(wall)
                results[record][1].append(loop)
                what = f"--{'record' if args.format == 'png' else 'video'} {args.format}" if record else "no recording"
                print(f"run {rep} {what:<16} process {wall:6.3f} s, run loop {loop:6.3f} s", flush=True)
    f = args.frames
    for record in (True, False):
        wall, loop = (statistics.median(v) for v in results[record])
        what = f"recording {args.format}" if record else "no recording"
        rate = f", {f / wall:5.1f} / {f / loop:5.1f} fps (process / loop)" if record else ""
        print(f"median {what:<14} process {wall:6.3f} s, run loop {loop:6.3f} s{rate}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
