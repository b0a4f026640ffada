#!/usr/bin/env python3
"""A random policy on the two-wheeled robot for 1,000 steps through simbob.SimbobEnv (nothing is
trained): each step commands the two wheel speeds (rad/s, uniform in [-10, 10] from a seeded numpy
Generator) for 0.01 s; the reward is the chassis' speed along +X (m/s) times 0.01 s, so the return
is about the distance made good along X. The scene's own schedule is emptied (Bot.Plan.Commands).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/random_policy.py [--seed S] [--steps N]

prints the return, the chassis' final pose and the simulated time.
"""
import argparse
import math
import os

import numpy as np

import simbob

SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes", "two_wheel_robot.xml")


def observe(sim):
    """Chassis x, z (m), heading (rad, about +Y), forward speed vx, vz (m/s), yaw rate (rad/s)."""
    x, _, z, qw, _, qy, _ = sim.poses()[0]
    v = sim.velocities()[0]
    return np.array([x, z, 2 * math.atan2(qy, qw), v[0], v[2], v[4]])


def make_env(steps):
    return simbob.SimbobEnv(
        SCENE,
        observe=observe,
        reward=lambda sim, action: float(sim.velocities()[0, 0]) * 0.01,
        overrides={"Bot.Plan.Commands": "0 0 0"},
        action_low=-10.0,
        action_high=10.0,  # actuator i gets action[i]: LeftDrive, RightDrive
        dt=0.01,
        horizon=steps,
    )


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seed", type=int, default=0, help="the policy's and the world's seed (default 0)")
    ap.add_argument("--steps", type=int, default=1000, help="steps (default 1000)")
    a = ap.parse_args()
    env = make_env(a.steps)
    rng = np.random.default_rng(a.seed)
    obs, info = env.reset(seed=a.seed)
    total, steps = 0.0, 0
    while True:
        obs, reward, terminated, truncated, info = env.step(env.action_space.sample(rng))
        total += reward
        steps += 1
        if terminated or truncated:
            break
    print(f"steps {steps}  return {total!r}")
    print(f"t={info['time']:.2f} s  chassis at x={obs[0]:.3f} z={obs[1]:.3f} m, heading {math.degrees(obs[2]):.1f} deg")


if __name__ == "__main__":
    main()
