#!/usr/bin/env python3
"""20 KR5 arms (issue 28): collisions as convex hulls of their STL meshes against the same arms
with boxes (each mesh's bounding box), against real time.

Usage: bench/urdf_arms.py --simbob build/simbob [-n 20] [-d 5] [-r 5]

Both variants are the dart-doc KR5 sixx R650 (/usr/share/doc/dart/data/urdf/KR5) with position
drives (MaxForce 500 N m) on a 5 m grid; every arm swings its shoulder and elbow by a command
schedule, so the links move and their shapes are tested against each other and the ground.
Each variant runs R times, in turn, under /usr/bin/time; medians of wall and CPU time are
printed with the real-time factor (simulated seconds per wall second) and the hull/box ratio.
"""
import argparse
import os
import re
import statistics
import struct
import subprocess
import sys
import tempfile

KR5 = "/usr/share/doc/dart/data/urdf/KR5"


def stl_bounds(path):
    data = open(path, "rb").read()
    pts = []
    if len(data) >= 84 and 84 + 50 * struct.unpack("<I", data[80:84])[0] == len(data):
        n = struct.unpack("<I", data[80:84])[0]
        for i in range(n):
            v = struct.unpack("<12f", data[84 + 50 * i:84 + 50 * i + 48])
            pts += [v[3:6], v[6:9], v[9:12]]
    else:
        for m in re.finditer(rb"vertex\s+(\S+)\s+(\S+)\s+(\S+)", data):
            pts.append(tuple(float(x) for x in m.groups()))
    lo = [min(p[k] for p in pts) for k in range(3)]
    hi = [max(p[k] for p in pts) for k in range(3)]
    return lo, hi


def box_variant(out):
    text = open(os.path.join(KR5, "KR5 sixx R650.urdf")).read()

    def collision(m):
        mesh = re.search(r'filename="([^"]+)"', m.group(0)).group(1)
        lo, hi = stl_bounds(os.path.join(KR5, mesh))
        c = " ".join(f"{(a + b) / 2:.6g}" for a, b in zip(lo, hi))
        s = " ".join(f"{max(b - a, 1e-3):.6g}" for a, b in zip(lo, hi))
        return f'<collision><origin xyz="{c}" rpy="0 0 0"/><geometry><box size="{s}"/></geometry></collision>'

    text = re.sub(r"<collision>.*?</collision>", collision, text, flags=re.S)
    text = text.replace('filename="meshes/', f'filename="{KR5}/meshes/')
    open(out, "w").write(text)


def scene(urdf, n, out):
    arms = []
    for i in range(n):
        x, z = 5 * (i % 5), 5 * (i // 5)
        arms.append(f"""  <RCRobot Key="R{i}">
    <Construction><RCImportURDF Key="kr5"><File Value="{urdf}"/>
      <Pose><RCGlobalCoordinates><Pose Value="{x} 0.5 {z} 90 0 0"/></RCGlobalCoordinates></Pose>
      <Drives Value="position"/><MaxForce Value="500"/></RCImportURDF></Construction>
    <ControllerList>
      <RCCommandSchedule Key="Shoulder"><Target Ref="R{i}.kr5.shoulder_pitch"/><Commands Value="0 0 1 0.8 3 -0.4"/></RCCommandSchedule>
      <RCCommandSchedule Key="Elbow"><Target Ref="R{i}.kr5.elbow_pitch"/><Commands Value="0 0 1.5 -1.2 3.5 0.5"/></RCCommandSchedule>
      <RCCommandSchedule Key="Yaw"><Target Ref="R{i}.kr5.shoulder_yaw"/><Commands Value="0 0 2 1.5"/></RCCommandSchedule>
    </ControllerList>
  </RCRobot>""")
    open(out, "w").write("<Simulation><ComponentList>\n  <RCGround Key=\"Ground\"/>\n" + "\n".join(arms) +
                         "\n</ComponentList></Simulation>\n")


def timed(cmd):
    out = subprocess.run(["/usr/bin/time", "-f", "@@ %e %U %S"] + cmd, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"urdf_arms: {' '.join(cmd)} failed:\n{out.stderr}")
    m = re.search(r"@@ ([\d.]+) ([\d.]+) ([\d.]+)", out.stderr)
    return float(m[1]), float(m[2]) + float(m[3])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--simbob", required=True)
    ap.add_argument("-n", type=int, default=20, help="arms (default 20)")
    ap.add_argument("-d", type=float, default=5.0, help="simulated seconds (default 5)")
    ap.add_argument("-r", type=int, default=5, help="repetitions (default 5)")
    args = ap.parse_args()
    work = tempfile.mkdtemp(prefix="simbob-arms-")
    box = os.path.join(work, "kr5_boxes.urdf")
    box_variant(box)
    variants = {"hulls": os.path.join(work, "hulls.xml"), "boxes": os.path.join(work, "boxes.xml")}
    scene(os.path.join(KR5, "KR5 sixx R650.urdf"), args.n, variants["hulls"])
    scene(box, args.n, variants["boxes"])
    times = {k: [] for k in variants}
    for r in range(args.r):
        for k in (list(variants) if r % 2 == 0 else list(reversed(list(variants)))):
            times[k].append(timed([args.simbob, "run", variants[k], "--duration", str(args.d), "-q",
                                   "--out", os.path.join(work, k + ".csv")]))
    print(f"{args.n} KR5 arms, {args.d} s simulated, {args.r} runs each (medians); uptime: "
          f"{open('/proc/loadavg').read().split()[:3]}")
    med = {}
    for k, v in times.items():
        wall = statistics.median(t[0] for t in v)
        cpu = statistics.median(t[1] for t in v)
        med[k] = wall
        print(f"  {k:6s} wall {wall:7.2f} s  cpu {cpu:7.2f} s  real-time factor {args.d / wall:6.2f}x (by cpu "
              f"{args.d / cpu:6.2f}x)")
    print(f"  hulls / boxes wall time: {med['hulls'] / med['boxes']:.2f}")


if __name__ == "__main__":
    main()
