"""simbob.run(): a whole run through the library's Run, the object `simbob run` goes through.

The promise (docs/python.md): the same files as `simbob run`, byte for byte, wall-clock fields of
the summary aside. Checked for every scene in scenes/, with the run log of every kind, in fresh
folders, against the real binary.
"""

import json
import os
import subprocess
from pathlib import Path

import pytest

import simbob
from conftest import child_env

ROOT = Path(os.environ.get("SIMBOB_SOURCE_DIR", Path(__file__).resolve().parents[2]))
BINARY = Path(os.environ.get("SIMBOB_BINARY", ROOT / "build" / "simbob"))
SCENES = sorted((ROOT / "scenes").glob("*.xml"))
# Summary fields that measure the machine, not the run.
WALL_CLOCK = {"wall_seconds", "steps_per_second"}
DURATION = 0.3  # s: every scene's peers, controllers and sensors act in that time


def summary_without_clock(path):
    s = json.loads(Path(path).read_text())
    return {k: v for k, v in s.items() if k not in WALL_CLOCK}


@pytest.mark.parametrize("scene", SCENES, ids=[s.stem for s in SCENES])
def test_run_writes_the_cli_bytes(scene, tmp_path):
    cli, py = tmp_path / "cli", tmp_path / "py"
    cli.mkdir()
    py.mkdir()
    # Relative paths, as a user types them: both runs in their own folder, the scene absolute.
    # os.environ, not child_env(): a sanitizer build's simbob has its own ASan runtime, and the
    # one child_env() preloads for a Python child would clash with it.
    subprocess.run([str(BINARY), "run", str(scene), "--duration", str(DURATION), "--out", "t.csv",
                    "--log", "joints,sensors,commands", "--quiet"], cwd=cli, check=True)
    here = os.getcwd()
    os.chdir(py)
    try:
        summary = simbob.run(str(scene), duration=DURATION, out="t.csv", log="joints,sensors,commands")
    finally:
        os.chdir(here)
    for name in ("t.csv", "t.log.csv"):
        assert (py / name).read_bytes() == (cli / name).read_bytes(), name
    assert summary_without_clock(py / "t.json") == summary_without_clock(cli / "t.json")
    assert {k: v for k, v in summary.items() if k not in WALL_CLOCK} == summary_without_clock(py / "t.json")
    assert sorted(p.name for p in py.iterdir()) == sorted(p.name for p in cli.iterdir())


def test_run_default_output_is_the_scenes_name(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    simbob.run(ROOT / "scenes" / "pendulum.xml", duration=0.05)
    assert (tmp_path / "pendulum.csv").read_text().startswith("time,body,x,y,z,qw,qx,qy,qz\n")
    assert json.loads((tmp_path / "pendulum.json").read_text())["status"] == "completed"


def test_run_refuses_before_writing(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(simbob.UsageError) as e:
        simbob.run(ROOT / "scenes" / "pendulum.xml", duration=0)
    assert e.value.message == "--duration must be between 1e-9 and 1e9 s, got 0"
    (tmp_path / "bad.xml").write_text("<Simulation><Bogus/></Simulation>\n")
    with pytest.raises(simbob.SceneError) as e:
        simbob.run("bad.xml", duration=1)
    assert e.value.file == "bad.xml" and e.value.line == 1
    assert e.value.errors == [str(e.value)]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.xml"]


def test_run_keeps_a_diverged_runs_partials(tmp_path, monkeypatch):
    """A ball thrown at 2e6 m/s is beyond the runaway limit (1e6 m/s) at the first step: DivergedError,
    and the partial trajectory and summary are kept as `simbob run` keeps them."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "fast.xml").write_text("""<Simulation><ComponentList>
  <RCMobileRigidBody Key="Ball">
    <Motion><RCGlobalMotion><LinVelocity Value="2e6 0 0"/></RCGlobalMotion></Motion>
    <Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom>
    <Inertia><RCInertiaByGeom><Mass Value="1"/></RCInertiaByGeom></Inertia>
  </RCMobileRigidBody></ComponentList></Simulation>
""")
    with pytest.raises(simbob.DivergedError) as e:
        simbob.run("fast.xml", duration=1)
    assert e.value.message.startswith("body 'Ball' diverged at t=0.001 s")
    kept = json.loads((tmp_path / "fast.partial.json").read_text())
    assert kept["status"] == "diverged"
    assert kept["partial_trajectory"] == "fast.partial.csv"
    assert (tmp_path / "fast.partial.csv").exists() and not (tmp_path / "fast.csv").exists()


def test_ctrl_c_stops_a_long_run_and_keeps_its_partials(tmp_path):
    """SIGINT during simbob.run(): the run stops at the next step, raises RunInterrupted -- a
    KeyboardInterrupt -- and keeps the trajectory so far, as `simbob run` does on Ctrl-C."""
    import signal
    import sys
    import time
    script = tmp_path / "long.py"
    script.write_text(
        "import sys, simbob\n"
        "try:\n"
        f"    simbob.run({str(ROOT / 'scenes' / 'pendulum.xml')!r}, duration=1e6, out='long.csv')\n"
        "except simbob.RunInterrupted as e:\n"
        "    assert isinstance(e, KeyboardInterrupt)\n"
        "    print('interrupted:', e.message, flush=True)\n"
        "    sys.exit(3)\n")
    child = subprocess.Popen([sys.executable, str(script)], cwd=tmp_path, env=child_env(), stdout=subprocess.PIPE,
                             text=True)
    deadline = time.monotonic() + 30
    while not list(tmp_path.glob("long.csv.tmp*")) and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(1.0)  # a second of running: the progress callback has been asked a few times
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=30)
    assert child.returncode == 3, out
    assert out.startswith("interrupted: interrupted at t=")
    kept = json.loads((tmp_path / "long.partial.json").read_text())
    assert kept["status"] == "interrupted"
    assert (tmp_path / "long.partial.csv").read_text().startswith("time,body,x,y,z,qw,qx,qy,qz\n")
    assert not (tmp_path / "long.csv").exists()
