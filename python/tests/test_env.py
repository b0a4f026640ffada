"""Tests of simbob.SimbobEnv (python/simbob/env.py) and examples/python/random_policy.py."""

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import simbob
from conftest import child_env

ROOT = Path(os.environ.get("SIMBOB_SOURCE_DIR", Path(__file__).resolve().parents[2]))
ROBOT = ROOT / "scenes" / "two_wheel_robot.xml"
NO_PLAN = {"Bot.Plan.Commands": "0 0 0"}
G = 9.81
BALL = """<Simulation>
  <SceneSettings><MaxTimeStep Value="0.001"/></SceneSettings>
  <ComponentList>
  <RCMobileRigidBody Key="Ball">
    <Pose><RCGlobalCoordinates><Pose Value="0 10 0 0 0 0"/></RCGlobalCoordinates></Pose>
    <Geom><RCSphereGeom><Radius Value="0.1"/></RCSphereGeom></Geom>
  </RCMobileRigidBody>
</ComponentList></Simulation>
"""


def robot_env(**kw):
    args = dict(observe=lambda s: s.poses()[0, :3], reward=lambda s, a: float(s.poses()[0, 0]),
                overrides=NO_PLAN, dt=0.01, horizon=5, action_low=-10, action_high=10)
    args.update(kw)
    return simbob.SimbobEnv(ROBOT, **args)


def test_free_fall_through_the_env_is_semi_implicit_euler(tmp_path):
    # Each env step is 10 physics steps of h = 1 ms; after n physics steps from rest the ball
    # has fallen g h^2 n (n + 1) / 2 (semi-implicit Euler: velocity first, then position).
    scene = tmp_path / "ball.xml"
    scene.write_text(BALL)
    env = simbob.SimbobEnv(scene, observe=lambda s: s.poses()[0, 1:2], reward=lambda s, a: -s.poses()[0, 1],
                           act=lambda s, a: None, action_shape=(0,), dt=0.01, horizon=None)
    obs, info = env.reset(seed=0)
    assert obs.tolist() == [10.0] and info == {"time": 0.0, "steps": 0, "seed": 0}
    h = 0.001
    for m in range(1, 51):
        obs, reward, terminated, truncated, info = env.step(np.zeros(0))
        n = 10 * m
        assert obs[0] == pytest.approx(10 - G * h * h * n * (n + 1) / 2, abs=1e-12)
        assert reward == -obs[0] and not terminated and not truncated
        assert info["steps"] == m and info["time"] == pytest.approx(n * h, abs=1e-12)


def test_step_reward_termination_truncation_and_shapes():
    env = robot_env(terminate=lambda s: s.time >= 0.03)
    assert env.action_space.shape == (2,) and env.observation_space.shape == (3,)
    assert (env.action_space.low == -10).all() and (env.action_space.high == 10).all()
    assert env.dt == pytest.approx(0.01) and env.frame_skip == 10
    obs, info = env.reset(seed=3)
    assert obs.shape == (3,) and info["seed"] == 3
    results = [env.step(np.array([4.0, 4.0])) for _ in range(3)]
    assert [r[2] for r in results] == [False, False, True]  # terminated at t = 0.03
    assert all(not r[3] for r in results)
    assert results[-1][1] == float(env.sim.poses()[0, 0])  # the reward is reward(sim) after the step
    assert env.sim.commands().tolist() == [4.0, 4.0]  # the default act: actuator i <- action[i]
    env = robot_env()
    env.reset(seed=0)
    flags = [env.step(np.zeros(2))[3] for _ in range(5)]
    assert flags == [False] * 4 + [True]  # truncated at the horizon (5)
    with pytest.raises(simbob.UsageError):
        env.step(np.zeros(3))
    with pytest.raises(simbob.UsageError):
        robot_env(dt=0.0105)  # not a whole number of 1 ms steps
    with pytest.raises(simbob.UsageError):
        robot_env(observation_shape=(4,))
    with pytest.raises(simbob.UsageError):
        robot_env().step(np.zeros(2))  # before reset()


def test_reset_seeds_make_episodes_repeatable():
    def episode(env, seed):
        obs, info = env.reset(seed=seed)
        rng = np.random.default_rng(5)
        out = [obs.tobytes()]
        for _ in range(5):
            out.append(env.step(env.action_space.sample(rng))[0].tobytes())
        return info["seed"], out

    env = robot_env()
    first = episode(env, 11)
    assert episode(env, 11) == first
    # Without a seed, the next episode's seed comes from the generator the last seed started.
    env.reset(seed=11)
    a = env.reset()[1]["seed"]
    env2 = robot_env()
    env2.reset(seed=11)
    assert env2.reset()[1]["seed"] == a and a != 11


def test_box_sample_and_contains():
    box = simbob.Box(-1.0, 2.0, shape=(3,))
    x = box.sample(np.random.default_rng(1))
    assert x.shape == (3,) and box.contains(x) and x in box
    assert (x == np.random.default_rng(1).uniform([-1.0] * 3, [2.0] * 3)).all()
    assert not box.contains(np.array([0.0, 0.0, 3.0])) and not box.contains(np.zeros(2))


def test_random_policy_example_prints_the_return_of_the_same_loop_by_hand():
    """The example runs 1,000 steps; its return equals the same random actions applied with
    Simulation.set_command and step(10), summed by hand, to the last bit."""
    script = ROOT / "examples" / "python" / "random_policy.py"
    env = child_env()
    out = subprocess.run([sys.executable, str(script), "--seed", "4"], check=True, capture_output=True, text=True,
                         env=env).stdout
    first = out.splitlines()[0].split()
    assert first[:3] == ["steps", "1000", "return"]
    printed = float(first[3])
    rng = np.random.default_rng(4)
    sim = simbob.Simulation(ROBOT, overrides=NO_PLAN, seed=4)
    total = 0.0
    for _ in range(1000):
        action = rng.uniform([-10.0, -10.0], [10.0, 10.0])
        for i in range(2):
            sim.set_command(i, float(action[i]))
        sim.step(10)
        total += float(sim.velocities()[0, 0]) * 0.01
    assert printed == total
    assert sim.time == pytest.approx(10.0)
    assert f"t={sim.time:.2f} s  chassis at x={sim.poses()[0, 0]:.3f}" in out
    again = subprocess.run([sys.executable, str(script), "--seed", "4"], check=True, capture_output=True, text=True,
                           env=env).stdout
    assert again == out
    other = subprocess.run([sys.executable, str(script), "--seed", "5"], check=True, capture_output=True,
                           text=True, env=env).stdout
    assert other != out
    assert math.isfinite(printed)
