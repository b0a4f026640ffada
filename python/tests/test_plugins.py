"""Plug-ins from Python (docs/plugins.md): simbob.load_plugin loads the example BeamSensor
(examples/plugins/beam_sensor.c, built by CMake into build/plugins/), and Simulation.sensor reads
it like a built-in sensor: the distance to the wall of examples/plugins/beam_robot.xml, 1.8 m at
t = 0, shrinking as RCObstacleAvoider drives the robot towards it. A second load is refused (its
type name is taken), and so is a file that is not there."""
import os

import pytest

import simbob

SOURCE = os.environ.get("SIMBOB_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
BINARY = os.environ.get("SIMBOB_BINARY", "")
BEAM = os.path.join(os.path.dirname(BINARY), "plugins", "beam_sensor.so")
SCENE = os.path.join(SOURCE, "examples", "plugins", "beam_robot.xml")


@pytest.mark.skipif(not os.path.isfile(BEAM), reason="build/plugins/beam_sensor.so is not built")
def test_plugin_sensor_reads_like_a_built_in():
    with pytest.raises(simbob.SceneError, match="unknown component type 'BeamSensor'"):
        simbob.Simulation(SCENE)
    simbob.load_plugin(BEAM)
    sim = simbob.Simulation(SCENE)
    assert "Bot.Cart.Beam" in sim.sensor_keys
    assert list(sim.sensor_quantities("Bot.Cart.Beam")) == ["distance"]
    assert sim.sensor("Bot.Cart.Beam")[0] == pytest.approx(1.8, abs=1e-12)
    sim.run_until(5.0)
    x = sim.poses()[0][0]  # the chassis, body 0
    d = sim.sensor("Bot.Cart.Beam")[0]
    assert d == pytest.approx(2.0 - 0.2 - x, abs=5e-5)  # the wall's face at x = 2 m
    assert 0.3 < d < 1.0
    with pytest.raises(simbob.SceneError, match="the name 'BeamSensor' is already registered"):
        simbob.load_plugin(BEAM)
    with pytest.raises(simbob.MissingInputError, match="cannot load the plug-in"):
        simbob.load_plugin("nowhere.so")


ACT_FAILS = os.path.join(os.path.dirname(BINARY), "plugins", "bad_act_fails.so")
SQUARE_SCENE = os.path.join(SOURCE, "examples", "plugins", "square_robot.xml")


@pytest.mark.skipif(not os.path.isfile(ACT_FAILS), reason="build/plugins/bad_act_fails.so is not built")
def test_a_failing_plugin_controller_raises_controller_error(tmp_path):
    """The test plug-in's BadController returns an error from act() at t >= 0.5 s: the run stops
    there with ControllerError (not DivergedError: nothing diverged), exit status 2 as the CLI's,
    from Simulation and from simbob.run, which keeps the partial trajectory up to 0.5 s."""
    text = open(SQUARE_SCENE).read()
    start, end = text.index("<SquareDriver"), text.index("</SquareDriver>") + len("</SquareDriver>")
    scene = tmp_path / "bad_robot.xml"
    scene.write_text(text[:start] + '<BadController Key="Bad"/>' + text[end:])
    line = text[:start].count("\n") + 1
    simbob.load_plugin(ACT_FAILS)
    sim = simbob.Simulation(scene)
    with pytest.raises(simbob.ControllerError) as e:
        sim.run_until(1.0)
    assert type(e.value) is simbob.ControllerError
    assert e.value.kind == "ControllerFailed" and e.value.exit_status == 2
    assert (e.value.file, e.value.line) == (str(scene), line)
    assert e.value.message == ("controller 'Bot.Bad' (plug-in 'bad', type 'BadController'): "
                               "act() failed: act failed on purpose at t=0.5")
    out = tmp_path / "b.csv"
    with pytest.raises(simbob.ControllerError):
        simbob.run(scene, duration=1, out=out)
    assert not out.exists()
    rows = (tmp_path / "b.partial.csv").read_text().splitlines()
    assert rows[-1].split(",")[0] == "0.5"
