#!/usr/bin/python3
"""bench/peers (issue 42): the same URDFs in simbob and in MuJoCo 2.2.2 (Debian's libmujoco-dev):
load time and steps per CPU-second, medians of several runs, with the ratios.

Usage: /usr/bin/python3 bench/peers/run.py [--build build] [-r 5] [--steps 10000] [--results DIR]
       [--profile]

The robots (written to a temporary folder; see bench/README.md, "Peers"):
  pendulum     one link (1 kg, a 5 cm sphere 0.5 m from a continuous hinge), starting horizontal
  chain10      10 links (0.2 m boxes, 0.5 kg) on continuous hinges about alternating axes (each
               joint frame turned 0.3 rad about the chain, damping 0.02 N m s/rad), starting
               straight out, folding in 3-D
  kr5_passive  dart-doc's KR5 sixx R650 (/usr/share/doc/dart/data/urdf/KR5), base 2 m above the
               ground and upright, no drives: it falls onto its joint stops
  kr5_driven   the same URDF with a position drive on each of its 6 joints (simbob: an
               RCImportURDF scene with Drives position, MaxForce 500, Smooth 0.05 and command
               schedules; MuJoCo: the same velocity law as a torque each step, mujoco_urdf.cpp)
  kr5_drv_step the same driven scene with SceneSettings Solver Step (what simbob chooses for a
               bare URDF run of the KR5); MuJoCo's side is kr5_driven's again

Every process loads its robot K times (the median is the load) and then steps it STEPS times at
1 ms; both programs read their own process CPU time (CLOCK_PROCESS_CPUTIME_ID), so the load of a
shared machine moves the figures less than it moves wall time. Runs alternate between the engines.
The table and the raw JSON lines go to stdout and to bench/results/<date>-<machine>-peers.txt.
--profile adds callgrind's count of simbob's instructions inside and outside ODE on the KR5,
and the same split by time from perf's cpu-clock samples where perf can sample.

Exit 69 when build/bench/peers_mujoco is missing (libmujoco-dev not installed); 1 when a run fails.
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

KR5 = "/usr/share/doc/dart/data/urdf/KR5"
KR5_FILE = os.path.join(KR5, "KR5 sixx R650.urdf")
# MuJoCo reads URDF options from a <mujoco> element inside <robot>: keep the collision meshes'
# folder (its URDF reader takes the file name alone and looks in meshdir),
# drop visuals (the default for URDF; written out so the reader sees it).
MJ_EXT = '<mujoco><compiler meshdir="{meshdir}" discardvisual="true" fusestatic="true" strippath="true"/></mujoco>'

# KR5 drives: the URDF's velocity limits (rad/s), and the commands (joint, time s, target rad).
KR5_JOINTS = {"shoulder_yaw": 6.545, "shoulder_pitch": 5.236, "elbow_pitch": 6.545, "elbow_roll": 7.1558,
              "wrist_pitch": 7.1558, "wrist_roll": 11.5191731}
KR5_COMMANDS = [("shoulder_yaw", 0.5, 0.8), ("shoulder_pitch", 0.5, 0.5), ("elbow_pitch", 0.5, -0.6)]
SMOOTH, MAXFORCE = 0.05, 500.0


def inertial(mass, xyz, ixx, iyy, izz):
    return (f'<inertial><origin xyz="{xyz}" rpy="0 0 0"/><mass value="{mass}"/>'
            f'<inertia ixx="{ixx:.9g}" ixy="0" ixz="0" iyy="{iyy:.9g}" iyz="0" izz="{izz:.9g}"/></inertial>')


def base_link():
    # A fixed block the chain hangs from (fixed to the world: no mass that moves).
    return ('<link name="world"/>\n<joint name="to_world" type="fixed"><parent link="world"/><child link="base"/>'
            '<origin xyz="0 0 {z}" rpy="0 0 0"/></joint>\n<link name="base">' + inertial(1, "0 0 0", 1e-3, 1e-3, 1e-3) +
            '<collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision></link>\n')


def pendulum_urdf(meshdir):
    i = 0.4 * 1.0 * 0.05 ** 2  # solid sphere, 1 kg, r 5 cm
    return (f'<robot name="pendulum">{MJ_EXT.format(meshdir=meshdir)}\n' + base_link().format(z=2.0) +
            '<joint name="hinge" type="continuous"><parent link="base"/><child link="bob"/>'
            '<origin xyz="0 0 0" rpy="0 0 0"/><axis xyz="0 1 0"/></joint>\n'
            '<link name="bob">' + inertial(1.0, "0.5 0 0", i, i, i) +
            '<collision><origin xyz="0.5 0 0" rpy="0 0 0"/><geometry><sphere radius="0.05"/></geometry></collision>'
            '</link>\n</robot>\n')


# The chain's joints are damped a little (N m s/rad; simbob applies -damping * velocity each step,
# MuJoCo implicitly in its Euler step): undamped, the free end whips up until MuJoCo's Euler
# step blows up ("Nan, Inf or huge value in QACC", and MuJoCo silently resets the state) at 8 s.
CHAIN_DAMPING = 0.02


def chain_urdf(meshdir, n=10):
    length, side, mass = 0.2, 0.04, 0.5
    ia = mass * (2 * side ** 2) / 12  # about the long axis
    ib = mass * (length ** 2 + side ** 2) / 12
    out = [f'<robot name="chain{n}">{MJ_EXT.format(meshdir=meshdir)}\n', base_link().format(z=3.0)]
    parent = "base"
    for k in range(n):
        axis = "0 1 0" if k % 2 == 0 else "0 0 1"
        # each joint frame turned 0.3 rad about the chain: the z hinges feel gravity too (3-D)
        origin = "0 0 0" if k == 0 else f"{length} 0 0"
        out.append(f'<joint name="j{k}" type="continuous"><parent link="{parent}"/><child link="l{k}"/>'
                   f'<origin xyz="{origin}" rpy="{0 if k == 0 else 0.3} 0 0"/><axis xyz="{axis}"/>'
                   f'<dynamics damping="{CHAIN_DAMPING}"/></joint>\n')
        out.append(f'<link name="l{k}">' + inertial(mass, f"{length / 2} 0 0", ia, ib, ib) +
                   f'<collision><origin xyz="{length / 2} 0 0" rpy="0 0 0"/><geometry><box size="{length * 0.9} '
                   f'{side} {side}"/></geometry></collision></link>\n')
        parent = f"l{k}"
    out.append("</robot>\n")
    return "".join(out)


def kr5_urdf():
    # dart-doc's file lays the arm on its side (its fixed joint turns it by -1.57 about x) at the
    # world's origin: stood upright with its base 2 m up, so that no link reaches the ground (in
    # either engine: both have a ground plane). Collision meshes only (both engines use their
    # convex hulls).
    text = open(KR5_FILE).read()
    text = re.sub(r'(<joint\s+name="arm_to_world_fixed".*?<origin\s+)xyz="[^"]*"\s+rpy="[^"]*"',
                  r'\1xyz="0 0 2" rpy="0 0 0"', text, flags=re.S)
    text = re.sub(r"<visual>.*?</visual>", "", text, flags=re.S)
    text = text.replace('filename="meshes/', f'filename="{KR5}/meshes/')
    text = re.sub(r"(<robot[^>]*>)", r"\1" + MJ_EXT.format(meshdir=KR5 + "/meshes/"), text, count=1)
    return text


def kr5_driven_scene(urdf, solver=""):
    schedules = "\n".join(
        f'      <RCCommandSchedule Key="S{k}"><Target Ref="Bot.kr5.{j}"/><Commands Value="0 0 {t} {q}"/>'
        f'</RCCommandSchedule>' for k, (j, t, q) in enumerate(KR5_COMMANDS))
    return f"""<Simulation>
  <SceneSettings><MaxTimeStep Value="0.001"/>{solver}</SceneSettings>
  <ComponentList>
    <RCGround Key="Ground"/>
    <RCRobot Key="Bot">
      <Construction>
        <RCImportURDF Key="kr5"><File Value="{urdf}"/>
          <Drives Value="position"/><MaxForce Value="{MAXFORCE}"/><Smooth Value="{SMOOTH}"/></RCImportURDF>
      </Construction>
      <ControllerList>
{schedules}
      </ControllerList>
    </RCRobot>
  </ComponentList>
</Simulation>
"""


def run_json(cmd, cwd):
    # In the work folder: MuJoCo writes its warnings to MUJOCO_LOG.TXT in the current folder.
    out = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd)
    if out.returncode != 0:
        sys.exit(f"peers: {' '.join(cmd)} failed ({out.returncode}):\n{out.stderr}{out.stdout}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def machine():
    model = "unknown"
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            model = line.split(":", 1)[1].strip()
            break
    short = re.sub(r"\(R\)|\(TM\)|CPU|Processor|@.*", "", model).split()
    return model, "-".join(w.lower() for w in short[:2]) + f"-{os.cpu_count()}cpu"


def callgrind_shares(exe, args, work, label):
    """simbob's instructions in its steps (Runner::step: what each step does after the world was
    built, controllers and drives included), split into ODE's and simbob's own. By object file:
    libode is ODE; the program is simbob (its callbacks from ODE included); a shared library's
    function (libc's memset, libm's) counts for whoever called it, in proportion to the calls'
    cost (callgrind_annotate --tree=caller)."""
    out = os.path.join(work, f"cg.{label}")
    subprocess.run(["valgrind", "--tool=callgrind", "--collect-atstart=no", "--toggle-collect=simbob::Runner::step*",
                    f"--callgrind-out-file={out}", exe] + args, capture_output=True, text=True, check=True)
    ann = subprocess.run(["callgrind_annotate", "--tree=caller", "--threshold=100", out], capture_output=True,
                         text=True, check=True).stdout
    line_re = re.compile(r"\s*([\d,]+)\s+\(\s*[\d.]+%\)\s+([<*])\s+(.*?)(?:\s+\((\d[\d,]*)x\))?\s*"
                         r"(?:\[([^\[\]]+)\])?\s*$")
    total, ode, own, rows, callers, last_obj, ode_rows = 0, 0, 0, [], [], {}, []
    for line in ann.splitlines():
        m2 = re.match(r"\s*([\d,]+)\s+(?:\(100\.0%\)\s+)?PROGRAM TOTALS", line)
        if m2:
            total = int(m2[1].replace(",", ""))
            continue
        m = line_re.match(line)
        if not m:
            if not line.strip():
                callers = []
            continue
        ir, kind, fn, obj = int(m[1].replace(",", "")), m[2], m[3], m[5]
        if obj:
            last_obj[fn] = os.path.basename(obj)
        obj = last_obj.get(fn, "?")
        if kind == "<":
            callers.append((ir, obj))
            continue
        if obj.startswith("libode"):
            ode += ir
            ode_rows.append((ir, fn))
        elif not obj.startswith("lib"):
            own += ir
            rows.append((ir, fn, obj))
        else:  # a shared library's function: split by its callers
            c_ode = sum(c for c, o in callers if o.startswith("libode"))
            c_all = sum(c for c, o in callers) or 1
            ode += ir * c_ode / c_all
            own += ir * (1 - c_ode / c_all)
            if c_ode < c_all:
                rows.append((ir * (1 - c_ode / c_all), fn, obj))
        callers = []
    inc = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", out], capture_output=True,
                         text=True, check=True).stdout
    entries = {}
    for line in inc.splitlines():
        m = re.match(r"\s*([\d,]+)\s+\(\s*[\d.]+%\)\s+\?\?\?:"
                     r"(dWorldStep|dWorldQuickStep|dSpaceCollide2|dSpaceCollide|dCollide)\s", line)
        if m:
            entries[m[2]] = entries.get(m[2], 0) + int(m[1].replace(",", ""))
    return total, ode, own, rows, entries, ode_rows


def perf_shares(exe, args, work, label):
    """The same split by time: perf's cpu-clock samples of a whole run (its load, about 1 % of it,
    included), by shared object: libode is ODE; the program, libm and libstdc++ count as simbob's
    (libm's calls are simbob's); libc (memset/memcpy, mostly ODE's, 0.3-1.5 %), the kernel and
    the load's libraries (qhull, assimp, the dynamic loader) are left out. None if perf cannot
    sample here."""
    if not shutil.which("perf"):
        return None
    data = os.path.join(work, f"perf.{label}")
    rec = subprocess.run(["perf", "record", "-q", "-e", "cpu-clock", "-F", "10000", "-o", data, exe] + args,
                         capture_output=True, text=True)
    if rec.returncode != 0:
        return None
    rep = subprocess.run(["perf", "report", "-i", data, "--sort", "dso,sym", "--stdio"], capture_output=True,
                         text=True).stdout
    ode = own = 0.0
    syms = []
    for line in rep.splitlines():
        m = re.match(r"\s*([\d.]+)%\s+(\S+)\s+\[.\]\s+(.*)$", line)
        if not m:
            continue
        share, dso, sym = float(m[1]), m[2], m[3].strip()
        if dso.startswith("libode"):
            ode += share
        elif dso == os.path.basename(exe) or dso.startswith(("libm.", "libstdc++")):
            own += share
            syms.append((share, sym))
    if ode + own == 0:
        return None
    return ode, own, syms


GROUPS = [("hinge angles (crAtan2, hingeAngle, joint totals)",
           r"crAtan2|twoProduct|\badd\(|::add\b|\bDD\b|hingeAngle|wrappedJointState|updateJointTotals"
           r"|__remainder|lround"),
          ("broad phase (HashSpacePairs, mayTouch, near callback)", r"HashSpacePairs|meets<|mayTouch|near|collide"),
          ("run checks (firstBadBody, jointSeparation)", r"firstBadBody|jointSeparation|firstBrokenJoint"),
          ("drives, controllers, clock", r"Actuator|actuator|Schedule|Runner|Party|Clock|serve|Servo|drive")]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("-r", type=int, default=5, help="runs of each engine and robot (default 5)")
    ap.add_argument("--steps", type=int, default=10000, help="steps of 1 ms per run (default 10000)")
    ap.add_argument("--loads", type=int, default=5, help="loads per run, median taken (default 5)")
    ap.add_argument("--results", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "results"))
    ap.add_argument("--profile", action="store_true",
                    help="simbob's own share of a KR5 step: callgrind (instructions), perf (time)")
    ap.add_argument("--only", default="", help="comma-separated robots (default all)")
    args = ap.parse_args()

    simbob_exe = os.path.abspath(os.path.join(args.build, "bench", "peers_simbob"))
    mujoco_exe = os.path.abspath(os.path.join(args.build, "bench", "peers_mujoco"))
    if not os.access(simbob_exe, os.X_OK):
        sys.exit(f"peers: {simbob_exe} missing: build first (bash scripts/build.sh)")
    if not os.access(mujoco_exe, os.X_OK):
        print(f"peers: {mujoco_exe} missing: it is built only where MuJoCo 2.2.2 is installed "
              "(sudo apt-get install libmujoco-dev, then bash scripts/build.sh)", file=sys.stderr)
        sys.exit(69)
    if not os.path.exists(KR5_FILE):
        print(f"peers: {KR5_FILE} missing (sudo apt-get install dart-doc)", file=sys.stderr)
        sys.exit(69)

    work = tempfile.mkdtemp(prefix="simbob-peers-")
    files = {}
    for name, text in (("pendulum", pendulum_urdf(KR5 + "/meshes/")), ("chain10", chain_urdf(KR5 + "/meshes/")),
                       ("kr5", kr5_urdf())):
        files[name] = os.path.join(work, name + ".urdf")
        open(files[name], "w").write(text)
    driven_xml = os.path.join(work, "kr5_driven.xml")
    open(driven_xml, "w").write(kr5_driven_scene(files["kr5"]))
    driven_step_xml = os.path.join(work, "kr5_driven_step.xml")
    open(driven_step_xml, "w").write(kr5_driven_scene(files["kr5"], '<Solver Value="Step"/>'))
    drive_args = ["--smooth", str(SMOOTH), "--maxforce", str(MAXFORCE)]
    for j, v in KR5_JOINTS.items():
        drive_args += ["--drive", j, str(v)]
    for j, t, q in KR5_COMMANDS:
        drive_args += ["--command", j, str(t), str(q)]
    cases = {  # name: (simbob file, mujoco file, mujoco's extra arguments)
        "pendulum": (files["pendulum"], files["pendulum"], ["--floor"]),
        "chain10": (files["chain10"], files["chain10"], ["--floor"]),
        "kr5_passive": (files["kr5"], files["kr5"], ["--floor"]),
        "kr5_driven": (driven_xml, files["kr5"], ["--floor"] + drive_args),
        # the same scene with the solver a bare URDF run of the KR5 gets (simbob's side only differs)
        "kr5_drv_step": (driven_step_xml, files["kr5"], ["--floor"] + drive_args),
    }
    if args.only:
        cases = {k: v for k, v in cases.items() if k in args.only.split(",")}

    model, tag = machine()
    start = datetime.datetime.now(datetime.timezone.utc)
    load0 = open("/proc/loadavg").read().split()[:3]
    raw = {k: {"simbob": [], "mujoco": []} for k in cases}
    common = [str(args.steps), "--loads", str(args.loads)]
    for r in range(args.r):
        for name, (sfile, mfile, margs) in cases.items():
            order = ["simbob", "mujoco"] if r % 2 == 0 else ["mujoco", "simbob"]
            for eng in order:
                cmd = [simbob_exe, sfile] + common if eng == "simbob" else [mujoco_exe, mfile] + common + margs
                raw[name][eng].append(run_json(cmd, work))
    load1 = open("/proc/loadavg").read().split()[:3]

    lines = []
    p = lines.append
    p(f"bench/peers/run.py, {start:%Y-%m-%d %H:%M} UTC, {model}, {os.cpu_count()} CPUs, "
      f"{platform.platform()}")
    p(f"load average before {' '.join(load0)}, after {' '.join(load1)}; {args.r} runs each, alternating; "
      f"{args.steps} steps of 1 ms per run; load = median of {args.loads} loads in a process")
    p(f"simbob: {simbob_exe}; MuJoCo: {mujoco_exe} (libmujoco {raw[next(iter(cases))]['mujoco'][0]['version']})")
    p("process CPU time (medians); steps/CPU-s = steps / CPU seconds of the steps alone")
    p("")
    p("load ms: the first load in a process (what a run pays), then the median of the process's loads")
    p(f"{'robot':12s} {'simbob load ms':>16s} {'MuJoCo load ms':>16s} {'ratio':>11s} "
      f"{'simbob st/CPU-s':>15s} {'MuJoCo st/CPU-s':>15s} {'MuJoCo/simbob':>13s}")
    summary = {}
    for name in cases:
        s, m = raw[name]["simbob"], raw[name]["mujoco"]
        sl = statistics.median(x["load_cpu_s"] for x in s) * 1e3
        ml = statistics.median(x["load_cpu_s"] for x in m) * 1e3
        sf = statistics.median(x["load_first_cpu_s"] for x in s) * 1e3
        mf = statistics.median(x["load_first_cpu_s"] for x in m) * 1e3
        ss = statistics.median(x["steps"] / x["step_cpu_s"] for x in s)
        ms = statistics.median(x["steps"] / x["step_cpu_s"] for x in m)
        summary[name] = (sl, ml, ss, ms)
        p(f"{name:12s} {sf:7.2f} / {sl:6.2f} {mf:7.2f} / {ml:6.2f} {sf / mf:5.2f} / {sl / ml:4.2f} {ss:15.0f} "
          f"{ms:15.0f} {ms / ss:13.2f}")
    for name in cases:
        bad = sum(x.get("unstable", 0) for x in raw[name]["mujoco"])
        if bad:
            p(f"WARNING: {name}: MuJoCo's step went unstable {bad} times (it resets the state and goes on): "
              "its figure is not of the same motion")
    p("")
    p("joint angles at the end (rad), first run of each engine:")
    for name in cases:
        s, m = raw[name]["simbob"][0]["qpos"], raw[name]["mujoco"][0]["qpos"]
        common_keys = [k for k in m if any(sk.endswith("." + k) or sk == k for sk in s)]
        pairs = []
        for k in common_keys:
            sv = next(v for sk, v in s.items() if sk.endswith("." + k) or sk == k)
            pairs.append(f"{k} {sv:+.3f}/{m[k]:+.3f}")
        p(f"  {name} (simbob/MuJoCo): " + ", ".join(pairs))

    if args.profile:
        p("")
        p("callgrind: instructions of 2,000 steps after the world was built (Runner::step), ODE's and simbob's own")
        p("(libc/libm functions counted for their callers):")
        for name in ("kr5_passive", "kr5_driven"):
            if name not in cases:
                continue
            total, ode, own, rows, entries, ode_rows = callgrind_shares(
                simbob_exe, [cases[name][0], "2000", "--loads", "1"], work, name)
            p(f"  {name}: {total:,} instructions ({total / 2000:,.0f} a step); ODE {ode / total:.1%}, "
              f"simbob's own {own / total:.1%}")
            p("    ODE's entry points, inclusive: " + ", ".join(f"{k} {v / total:.1%}" for k, v in entries.items()))
            left = list(rows)
            for title, pat in GROUPS:
                hit = [r for r in left if re.search(pat, r[1])]
                left = [r for r in left if r not in hit]
                p(f"    {title:55s} {sum(r[0] for r in hit) / total:6.2%}")
            p(f"    {'the rest':55s} {sum(r[0] for r in left) / total:6.2%}")
            top = sorted(ode_rows, reverse=True)[:4]
            p("    ODE's largest (exclusive): " +
              ", ".join(f"{re.sub(r'^[?]+:', '', fn).split('(')[0]} {ir / total:.1%}" for ir, fn in top))
            pf = perf_shares(simbob_exe, [cases[name][0], "100000", "--loads", "1"], work, name)
            if pf:
                ode_t, own_t, syms = pf
                hinge = sum(x for x, sym in syms if re.search(GROUPS[0][1], sym))
                p(f"    by time (perf cpu-clock, 100,000 steps): ODE {ode_t / (ode_t + own_t):.1%}, simbob's own "
                  f"{own_t / (ode_t + own_t):.1%}, of which hinge angles {hinge / (ode_t + own_t):.1%}")
            p("    simbob's largest (exclusive):")
            for ir, fn, obj in sorted(rows, reverse=True)[:14]:
                p(f"      {ir / total:6.2%}  {re.sub(r'^.*?:', '', fn)[:100]}")
    p("")
    p("raw:")
    for name in cases:
        for eng in ("simbob", "mujoco"):
            for x in raw[name][eng]:
                p("  " + json.dumps({"robot": name, **x}))
    text = "\n".join(lines) + "\n"
    print(text, end="")
    os.makedirs(args.results, exist_ok=True)
    out = os.path.join(args.results, f"{start:%Y-%m-%d}-{tag}-peers.txt")
    open(out, "w").write(text)
    print(f"peers: written {os.path.relpath(out)}", file=sys.stderr)
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
