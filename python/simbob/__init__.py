"""simbob: headless robot simulation (Simulator Bob scenes on ODE) from Python.

The package: the compiled module (simbob._simbob: Simulation and the error classes), Batch
(simbob/batch.py: worlds stepped in parallel by worker processes) and SimbobEnv
(simbob/env.py: a Gymnasium-style environment). Everything is imported from `simbob`.
"""

from . import _simbob
from ._simbob import (  # noqa: F401
    ControllerError,
    DivergedError,
    Error,
    InternalError,
    MissingInputError,
    OutputError,
    ProtocolError,
    RunInterrupted,
    SceneError,
    Simulation,
    UnavailableError,
    UsageError,
    __version__,
    load_plugin,
    run,
)
from .batch import Batch  # noqa: E402,F401
from .env import Box, SimbobEnv  # noqa: E402,F401

__doc__ = _simbob.__doc__ + """

Many worlds at once: simbob.Batch(scene, n, overrides=..., seeds=...) steps n worlds in parallel
worker processes and returns their state as stacked arrays, each world the same numbers as it
alone. A scene as a Gymnasium-style environment: simbob.SimbobEnv(scene, observe, reward, ...)."""
for _cls in (Simulation, Batch, Box, SimbobEnv):
    _cls.__module__ = "simbob"

__all__ = [
    "Batch",
    "Box",
    "ControllerError",
    "DivergedError",
    "Error",
    "InternalError",
    "MissingInputError",
    "OutputError",
    "ProtocolError",
    "RunInterrupted",
    "SceneError",
    "SimbobEnv",
    "Simulation",
    "UnavailableError",
    "UsageError",
    "load_plugin",
    "run",
]
