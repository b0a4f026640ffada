"""simbob.SimbobEnv: a scene as a Gymnasium-style environment (the gymnasium package is not needed).

It follows Gymnasium's Env interface: reset(seed=None, options=None) -> (obs, info),
step(action) -> (obs, reward, terminated, truncated, info), observation_space and action_space
with shape, dtype, low, high, sample() and contains(), render(), close(). The mapping between
the scene and the learning problem is the user's: observe(sim), reward(sim, action), act(sim,
action) and an optional terminate(sim).
"""

import math
import numbers
import os

import numpy as np

from . import _simbob

__all__ = ["Box", "SimbobEnv"]


def _usage(message):
    return _simbob.UsageError(message, "Usage")


class Box:
    """A box in R^shape, as gymnasium.spaces.Box: shape, dtype, low, high (arrays of shape,
    -inf/inf for unbounded), sample() and contains(x)."""

    def __init__(self, low, high, shape=None, dtype=np.float64):
        self.dtype = np.dtype(dtype)
        if shape is None:
            shape = np.broadcast(np.asarray(low), np.asarray(high)).shape
        self.shape = tuple(int(s) for s in (shape if isinstance(shape, (tuple, list)) else (shape,)))
        self.low = np.broadcast_to(np.asarray(low, dtype=self.dtype), self.shape).copy()
        self.high = np.broadcast_to(np.asarray(high, dtype=self.dtype), self.shape).copy()
        if np.any(self.low > self.high):
            raise _usage(f"Box: low {self.low} is above high {self.high}")
        self.np_random = np.random.default_rng(0)

    def seed(self, seed=None):
        """Reseeds sample()'s generator (numpy Generator, PCG64)."""
        self.np_random = np.random.default_rng(seed)
        return [seed]

    def sample(self, rng=None):
        """A uniform point of the box (bounded dimensions; unbounded ones: a standard normal
        deviate), from `rng` (a numpy Generator) or the box's own generator."""
        g = self.np_random if rng is None else rng
        bounded = np.isfinite(self.low) & np.isfinite(self.high)
        if bounded.all():  # then exactly g.uniform(low, high)
            return g.uniform(self.low, self.high).astype(self.dtype)
        x = np.where(bounded, g.uniform(np.where(bounded, self.low, 0), np.where(bounded, self.high, 1)),
                     g.standard_normal(self.shape))
        return x.astype(self.dtype)

    def contains(self, x):
        """Whether x has this shape and lies within [low, high]."""
        a = np.asarray(x)
        return a.shape == self.shape and bool(np.all((a >= self.low) & (a <= self.high)))

    def __contains__(self, x):
        return self.contains(x)

    def __repr__(self):
        return f"Box({self.low.min()}, {self.high.max()}, {self.shape}, {self.dtype})"


def _default_act(sim, action):
    for i, value in enumerate(np.asarray(action, dtype=np.float64).reshape(-1)):
        sim.set_command(i, float(value))


class SimbobEnv:
    """A scene as a Gymnasium-style environment: one Simulation, advanced `dt` per step().

    SimbobEnv(scene, observe, reward, act=None, action_shape=None, observation_shape=None,
              dt=None, horizon=1000, terminate=None, overrides=None, seed=0, physics_dt=None,
              action_low=-inf, action_high=inf)

    Args:
        scene (str | os.PathLike): the scene file.
        observe (fn(sim) -> array): the observation at the current instant.
        reward (fn(sim, action) -> float): the reward of the step just taken with `action`.
        act (fn(sim, action) | None): applies an action (sets commands) before the step; None
            sets actuator i to action[i] (action_shape defaults to (A,)).
        action_shape, observation_shape (tuple | None): the declared shapes; None: (A,) for the
            action, the shape of observe() at t = 0 for the observation.
        dt (float | None): simulated time per step() (s), a whole number of physics steps (at
            least one); None: one physics step.
        horizon (int | None): step() returns truncated=True at the horizon-th step of an
            episode; None: never.
        terminate (fn(sim) -> bool | None): terminated after a step when it returns True.
        overrides, physics_dt: as Simulation's overrides and dt.
        seed (int): the first episode's seed.
        action_low, action_high: action_space's bounds (scalars or arrays).

    reset(seed=None) starts an episode at t = 0: with `seed` when given, else with a seed drawn
    from the generator the last given seed started (Gymnasium's convention), so a sequence of
    episodes is fixed by the first seed. The world's seed is in info["seed"]. step() applies
    the action with act(), advances dt (the scene's controllers and the action's commands
    acting) and returns (observe(sim), reward(sim, action), terminate(sim), horizon reached,
    info) with info {"time", "steps", "seed"}. A run that diverges raises DivergedError.
    """

    metadata = {"render_modes": ["rgb_array"]}

    def __init__(self, scene, observe, reward, act=None, action_shape=None, observation_shape=None, dt=None,
                 horizon=1000, terminate=None, overrides=None, seed=0, physics_dt=None, action_low=-math.inf,
                 action_high=math.inf, render_mode=None):
        for name, fn in (("observe", observe), ("reward", reward), ("act", act), ("terminate", terminate)):
            if fn is not None and not callable(fn):
                raise _usage(f"SimbobEnv: {name} must be callable, got {fn!r}")
        if horizon is not None and (isinstance(horizon, bool) or not isinstance(horizon, numbers.Integral)
                                    or horizon < 1):
            raise _usage(f"SimbobEnv: horizon must be a positive integer or None, got {horizon!r}")
        self.sim = _simbob.Simulation(os.fspath(scene), overrides=overrides, seed=seed, dt=physics_dt)
        self._observe, self._reward, self._terminate = observe, reward, terminate
        self._act = act or _default_act
        if dt is None:
            self.frame_skip = 1
        else:
            k = round(float(dt) / self.sim.dt)
            if not math.isfinite(float(dt)) or k < 1 or abs(k * self.sim.dt - float(dt)) > 1e-9 * max(1.0, float(dt)):
                raise _usage(f"SimbobEnv: dt must be a whole number (>= 1) of physics steps of {self.sim.dt} s, "
                             f"got {dt!r}")
            self.frame_skip = int(k)
        self.dt = self.frame_skip * self.sim.dt
        self.horizon = None if horizon is None else int(horizon)
        self.render_mode = render_mode
        if action_shape is None:
            action_shape = (len(self.sim.actuator_keys),)
        self.action_space = Box(action_low, action_high, shape=action_shape)
        first = np.asarray(self._observe(self.sim), dtype=np.float64)
        if observation_shape is None:
            observation_shape = first.shape
        self.observation_space = Box(-math.inf, math.inf, shape=observation_shape)
        self._check_obs(first)
        self._seed = int(seed)
        self.np_random = np.random.default_rng(self._seed)
        self._episode_steps = 0
        self._started = False

    def _check_obs(self, obs):
        if obs.shape != self.observation_space.shape:
            raise _usage(f"SimbobEnv: observe() returned shape {obs.shape}, declared "
                         f"{self.observation_space.shape}")
        return obs

    def _info(self):
        return {"time": self.sim.time, "steps": self._episode_steps, "seed": self._seed}

    def reset(self, seed=None, options=None):
        """Starts an episode at t = 0 and returns (observation, info)."""
        if seed is not None:
            if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or not 0 <= seed <= 0xFFFFFFFF:
                raise _usage(f"reset: the seed is an integer from 0 to 2**32-1, got {seed!r}")
            self.np_random = np.random.default_rng(int(seed))
            self._seed = int(seed)
        elif self._started:
            self._seed = int(self.np_random.integers(0, 2**32))
        self._started = True
        self.sim.reset(self._seed)
        self._episode_steps = 0
        obs = self._check_obs(np.asarray(self._observe(self.sim), dtype=np.float64))
        return obs, self._info()

    def step(self, action):
        """Applies `action`, advances dt; returns (obs, reward, terminated, truncated, info)."""
        if not self._started:
            raise _usage("step: call reset() first")
        a = np.asarray(action, dtype=np.float64)
        if a.shape != self.action_space.shape:
            raise _usage(f"step: the action has shape {a.shape}, declared {self.action_space.shape}")
        self._act(self.sim, a)
        self.sim.step(self.frame_skip)
        self._episode_steps += 1
        obs = self._check_obs(np.asarray(self._observe(self.sim), dtype=np.float64))
        reward = float(self._reward(self.sim, a))
        terminated = bool(self._terminate(self.sim)) if self._terminate else False
        truncated = self.horizon is not None and self._episode_steps >= self.horizon
        return obs, reward, terminated, truncated, self._info()

    def render(self, camera=None, size=(640, 480)):
        """The scene now as uint8 (h, w, 3) (Simulation.render)."""
        return self.sim.render(camera=camera, size=size)

    def close(self):
        """Nothing to release beyond the Simulation (freed with the environment)."""

    @property
    def unwrapped(self):
        """This environment (Gymnasium's wrappers reach the base environment through it)."""
        return self

    def __repr__(self):
        return f"<simbob.SimbobEnv {self.sim.scene!r} dt={self.dt:g} horizon={self.horizon}>"
