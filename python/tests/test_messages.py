"""The Python module's messages for bad arguments (docs/python.md "Errors"): every one a
simbob.UsageError (or the scene file's SceneError) with a one-line message in simbob's number
form, never a bare RuntimeError from pybind11, 300 digits or a rounded-away value; a path with a
NUL is refused, not cut short; scene text has a scene file's size limit."""

import os
from pathlib import Path

import pytest

import simbob

ROOT = Path(os.environ.get("SIMBOB_SOURCE_DIR", Path(__file__).resolve().parents[2]))
PENDULUM = ROOT / "scenes" / "pendulum.xml"
ROBOT = ROOT / "scenes" / "two_wheel_robot.xml"


@pytest.mark.parametrize("period, shown", [(1e300, "1e+300"), (1e-10, "1e-10"), (-1.0, "-1"), (1e10, "1e+10")])
def test_add_controller_periods_out_of_range_are_shown_as_simbob_writes_numbers(period, shown):
    sim = simbob.Simulation(PENDULUM)
    with pytest.raises(simbob.UsageError) as e:
        sim.add_controller(period, lambda s: None)
    assert e.value.message == ("add_controller: the period must be from 1e-9 s to 9.223372036854775807e9 s "
                               f"(the clock's range), got {shown}")


def test_an_actuator_index_beyond_64_bits_is_a_usage_error():
    sim = simbob.Simulation(ROBOT)
    n = len(sim.actuator_keys)
    for index in (2**70, -2**70, n):
        with pytest.raises(simbob.UsageError) as e:
            sim.set_command(index, 1)
        assert e.value.message == f"no actuator {index} (the scene has {n})"


@pytest.mark.parametrize("dt", ["x", "0.001", True, [0.001], 10**400, float("nan")],
                         ids=["str", "numeric-str", "bool", "list", "huge-int", "nan"])
def test_dt_that_is_not_a_number_in_range_is_a_usage_error(dt):
    with pytest.raises(simbob.UsageError) as e:
        simbob.Simulation(PENDULUM, dt=dt)
    assert e.value.message == f"dt must be a number of seconds from 1e-9 to 1e9, got {dt!r}"


def test_a_path_with_a_nul_is_refused_not_cut_short():
    cut = str(PENDULUM) + "\0.ini"  # the C call would open scenes/pendulum.xml
    with pytest.raises(simbob.UsageError) as e:
        simbob.Simulation(cut)
    assert e.value.message == f"the scene path {cut!r} holds a NUL character, which no file name can hold"
    with pytest.raises(simbob.UsageError, match="holds a NUL character"):
        simbob.Simulation(Path(str(PENDULUM) + "\0"))
    with pytest.raises(simbob.UsageError, match="from_text: the name 'a.xml\\\\x00.ini' holds a NUL"):
        simbob.Simulation.from_text(PENDULUM.read_text(), name="a.xml\0.ini")
    with pytest.raises(simbob.UsageError, match="load_plugin: the path 'x.so\\\\x00' holds a NUL"):
        simbob.load_plugin("x.so\0")


def test_scene_text_has_the_scene_file_limit():
    text = PENDULUM.read_text()
    big = text + " " * ((64 << 20) + 1 - len(text))  # trailing blanks: a well-formed scene, 64 MiB + 1 byte
    with pytest.raises(simbob.SceneError) as e:
        simbob.Simulation.from_text(big, name="big.xml")
    assert str(e.value) == "big.xml: error: cannot read scene: larger than 64 MiB"
    del big
    ok = text + " " * ((64 << 20) - len(text))  # exactly 64 MiB: loads
    assert simbob.Simulation.from_text(ok, name="ok.xml").body_keys
