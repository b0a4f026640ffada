"""simbob.Batch: n independent worlds of one scene stepped in parallel by forked worker processes.

Why processes: ODE's QuickStep draws from one process-wide random generator, so simbob steps
the worlds of one process one at a time (each World swaps its own generator state in and out
under a process-wide lock). Parallel worlds therefore live in separate processes. The Batch
loads every world in the calling process (so load errors are raised there, as by Simulation),
then forks `workers` processes; each keeps a contiguous share of the worlds and drops the rest.
Commands go to the workers over pipes (a few bytes per call); every worker writes the state of
its worlds into one shared anonymous memory map (mmap MAP_SHARED, inherited through fork), which
the caller reads as numpy arrays. The caller waits on the pipes with the GIL released.
"""

import math
import mmap
import numbers
import os
import pickle
import signal
import struct
import threading
import time
import weakref

import numpy as np

from . import _simbob

__all__ = ["Batch"]

# The parent's ends of the pipes of every live Batch in this process: a worker forked later
# closes them, so that closing a Batch's pipes is seen (EOF) by its workers.
_PARENT_FDS = set()


def _usage(message):
    return _simbob.UsageError(message, "Usage")


def _send(fd, obj):
    data = pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
    data = struct.pack("<I", len(data)) + data
    while data:
        data = data[os.write(fd, data):]


def _read_exactly(fd, n):
    chunks = []
    while n:
        b = os.read(fd, n)  # releases the GIL while waiting
        if not b:
            return None
        chunks.append(b)
        n -= len(b)
    return b"".join(chunks)


def _recv(fd):
    head = _read_exactly(fd, 4)
    if head is None:
        return None
    body = _read_exactly(fd, struct.unpack("<I", head)[0])
    return None if body is None else pickle.loads(body)


def _pack_exception(e):
    """An exception as plain data, rebuilt by _unpack_exception in the caller's process."""
    if isinstance(e, _simbob.Error):
        return ("simbob", type(e).__name__, e.message, e.kind, e.file, e.line, getattr(e, "errors", None))
    return ("python", type(e).__module__, type(e).__name__, str(e))


def _unpack_exception(p, world):
    if p[0] == "simbob":
        _, name, message, kind, file, line, errors = p
        e = getattr(_simbob, name, _simbob.InternalError)(message, kind, file, line)
        if errors is not None:
            e.errors = errors
    else:
        _, module, name, text = p
        import builtins

        cls = getattr(builtins, name, None) if module == "builtins" else None
        if isinstance(cls, type) and issubclass(cls, Exception):
            e = cls(text)
        else:
            e = _simbob.InternalError(f"world {world}: {module}.{name}: {text}", "Internal")
    e.world = world
    return e


class _State:
    """The stacked state arrays, views into one buffer (shared memory when there are workers)."""

    def __init__(self, n, bodies, joints, actuators, sensors, shared):
        shapes = [
            ("poses", (n, bodies, 7), np.float64),
            ("velocities", (n, bodies, 6), np.float64),
            ("joint_positions", (n, joints), np.float64),
            ("joint_velocities", (n, joints), np.float64),
            ("commands", (n, actuators), np.float64),
            ("commands_in", (n, actuators), np.float64),
            ("time", (n,), np.float64),
            ("steps", (n,), np.int64),
            ("touching", (n, sensors), np.bool_),
            ("running", (n,), np.bool_),
        ]
        sizes = [int(np.prod(s)) * np.dtype(t).itemsize for _, s, t in shapes]
        total = sum((z + 7) // 8 * 8 for z in sizes)
        self.buffer = mmap.mmap(-1, max(total, 8)) if shared else bytearray(max(total, 8))
        offset = 0
        for (name, shape, dtype), size in zip(shapes, sizes):
            count = int(np.prod(shape))
            setattr(self, name, np.frombuffer(self.buffer, dtype, count, offset).reshape(shape))
            offset += (size + 7) // 8 * 8

    def publish(self, i, sim):
        self.poses[i] = sim.poses()
        self.velocities[i] = sim.velocities()
        self.joint_positions[i] = sim.joint_positions()
        self.joint_velocities[i] = sim.joint_velocities()
        self.commands[i] = sim.commands()
        self.touching[i] = sim.touching()
        self.time[i] = sim.time
        self.steps[i] = sim.steps
        self.running[i] = sim.running


def _apply(sims, first, state, op, arg):
    """Runs one operation on worlds first, first+1, ...; publishes their state; returns the
    failures as [(world, packed exception)] in world order."""
    failures = []
    for j, sim in enumerate(sims):
        i = first + j
        try:
            if op == "step":
                sim.step(arg)
            elif op == "until":
                sim.run_until(arg)
            elif op == "commands":
                for a in range(state.commands_in.shape[1]):
                    sim.set_command(a, float(state.commands_in[i, a]))
            elif op == "reset":
                sim.reset(arg[j])
        except Exception as e:  # noqa: BLE001 - every error goes back to the caller
            failures.append((i, _pack_exception(e)))
        state.publish(i, sim)
    return failures


def _serve(sims, first, state, rfd, wfd):
    """A worker's loop: one reply per command until the pipe closes or "close" arrives."""
    while True:
        msg = _recv(rfd)
        if msg is None or msg[0] == "close":
            return
        try:
            reply = ("done", _apply(sims, first, state, msg[0], msg[1]))
        except BaseException as e:  # noqa: BLE001 - reported, then the worker goes on
            reply = ("done", [(first, _pack_exception(e))])
        _send(wfd, reply)


def _worker_terminated(signum, frame):
    """A worker's SIGTERM handler: the caller ends a worker in the middle of a call (Ctrl-C) with
    SIGTERM; the worker leaves the call at its next slice (Simulation.step checks for signals
    every few ms), ends its worlds (and the programs they started) and exits."""
    raise SystemExit(70)


def _shutdown(creator, pids, fds, terminate=False):
    """Closes a Batch's pipes and reaps its workers: they end when they see their pipe close
    (with terminate=True they are sent SIGTERM first: they are inside a call); one that has not
    ended within 2 s is killed."""
    for fd in fds:
        _PARENT_FDS.discard(fd)
        try:
            os.close(fd)
        except OSError:
            pass
    if os.getpid() != creator:  # a copy inherited by another Batch's worker: not its children
        return
    if terminate:
        for pid in pids:
            try:
                os.kill(pid, signal.SIGTERM)
            except ProcessLookupError:
                pass
    deadline = time.monotonic() + 2.0
    for pid in pids:
        while True:
            try:
                done, _ = os.waitpid(pid, os.WNOHANG)
            except ChildProcessError:
                break
            if done:
                break
            if time.monotonic() > deadline:
                os.kill(pid, signal.SIGKILL)
                os.waitpid(pid, 0)
                break
            time.sleep(0.001)


def _per_world_overrides(overrides, n):
    """None, one dict / list of "KEY.PARAM=VALUE" for every world, or a list of n of those."""
    if overrides is None or isinstance(overrides, dict):
        return [overrides] * n
    items = list(overrides)
    if all(isinstance(o, str) for o in items):
        return [items] * n
    if len(items) != n or not all(o is None or isinstance(o, (dict, list, tuple)) for o in items):
        raise _usage(f"overrides: expected a dict, a list of \"KEY.PARAM=VALUE\" strings, or one of those "
                     f"per world ({n}), got {overrides!r}")
    return [None if o is None else (o if isinstance(o, dict) else list(o)) for o in items]


def _seeds(seeds, n, what):
    if seeds is None:
        return list(range(n))
    items = list(seeds)
    if len(items) != n:
        raise _usage(f"{what}: expected {n} seeds (one per world), got {len(items)}")
    for s in items:
        if isinstance(s, bool) or not isinstance(s, numbers.Integral) or not 0 <= s <= 0xFFFFFFFF:
            raise _usage(f"{what}: a seed is an integer from 0 to 2**32-1, got {s!r}")
    return [int(s) for s in items]


class Batch:
    """n independent worlds of one scene, stepped in parallel, with their state as stacked
    numpy arrays.

    Batch(scene, n, overrides=None, seeds=None, dt=None, workers=None)

    Args:
        scene (str | os.PathLike): the scene file, as for Simulation.
        n (int): the number of worlds (at least 1).
        overrides: None; one dict or list of "KEY.PARAM=VALUE" strings for every world; or a
            list of n of those (None for none), world i taking the i-th.
        seeds (list[int] | None): world i's seed (0 to 2**32-1); None: world i gets seed i.
        dt (float | None): the step (s) of every world; None takes the scene's MaxTimeStep.
        workers (int | None): worker processes; None: as many as CPUs this process may use,
            at most n; 0 steps every world in this process, one after the other (no fork).

    World i gives the same numbers, bit for bit, as Simulation(scene, overrides[i], seeds[i], dt)
    stepped alone, whatever `workers` is. The worlds are loaded here (load errors are raised as
    by Simulation), then `workers` processes are forked, each stepping a contiguous share of
    the worlds; the state comes back through shared memory. Calls wait with the GIL released.

    After every call the state of all worlds is read with poses(), velocities(),
    joint_positions(), joint_velocities(), commands(), touching() (fresh copies, world first),
    and the per-world arrays time, steps and running. A world whose run stops (diverged, a
    failed controller) raises its error from the call, as Simulation does, with `e.world` set
    to its index (the lowest one when several fail); the other worlds have completed the call.
    A stopped world raises again at every later call until reset().

    A scene whose controller programs simbob starts (Simulation.programs) runs them in the
    workers: each worker loads its worlds again (their programs become its children) after the
    worlds loaded here have checked the scene and ended. Ctrl-C (KeyboardInterrupt) during a call
    raises KeyboardInterrupt, ends the workers and closes the Batch: its worlds had not all
    finished the call.

    Close it with close() (or use `with simbob.Batch(...) as b:`); it is also closed when
    garbage-collected. Use it from one thread at a time (another thread's call meanwhile raises
    UsageError), and create it while no other thread of this process is inside simbob.
    """

    def __init__(self, scene, n, overrides=None, seeds=None, dt=None, workers=None):
        if isinstance(n, bool) or not isinstance(n, numbers.Integral) or n < 1:
            raise _usage(f"Batch: n must be a positive integer, got {n!r}")
        n = int(n)
        per_world = _per_world_overrides(overrides, n)
        self._seeds = _seeds(seeds, n, "Batch")
        if workers is None:
            try:
                cpus = len(os.sched_getaffinity(0))
            except AttributeError:
                cpus = os.cpu_count() or 1
            workers = min(n, cpus)
        if isinstance(workers, bool) or not isinstance(workers, numbers.Integral) or workers < 0:
            raise _usage(f"Batch: workers must be an integer >= 0, got {workers!r}")
        workers = min(int(workers), n)
        sims = [_simbob.Simulation(scene, overrides=o, seed=s, dt=dt) for o, s in zip(per_world, self._seeds)]
        first = sims[0]
        for i, s in enumerate(sims[1:], 1):
            if (s.body_keys, s.joint_keys, s.actuator_keys, s.sensor_keys) != (
                    first.body_keys, first.joint_keys, first.actuator_keys, first.sensor_keys):
                raise _usage(f"Batch: world {i}'s overrides change the scene's bodies, joints, actuators "
                             f"or sensors; every world must have the same ones")
        self._closed_why = "this Batch is closed"
        self.n = n
        self._lock = threading.Lock()
        self.scene = first.scene
        self.body_keys = first.body_keys
        self.joint_keys = first.joint_keys
        self.actuator_keys = first.actuator_keys
        self.sensor_keys = first.sensor_keys
        self.dt = np.array([s.dt for s in sims])
        self.workers = workers
        self._state = _State(n, len(self.body_keys), len(self.joint_keys), len(self.actuator_keys),
                             len(self.sensor_keys), shared=workers > 0)
        for i, s in enumerate(sims):
            self._state.publish(i, s)
        self._bounds = [(w * n // max(workers, 1), (w + 1) * n // max(workers, 1)) for w in range(max(workers, 1))]
        self._pipes = []  # (to worker, from worker) per worker
        self._pids = []
        self._sims = None
        if workers == 0:
            self._sims = sims
            self._finalizer = None
            return
        # A world whose scene starts controller programs cannot move to a worker: its programs are
        # this process's children, talking to this process's sockets, and end with its objects.
        # Such worlds are ended here (they were loaded to check the scene and the overrides) and
        # each worker loads its own again, so that their programs are the worker's.
        reload = None
        if any(s.programs for s in sims):
            reload = (scene, per_world, self._seeds, dt)
            s = first = None
            sims.clear()  # ends them and their programs, before the workers start their own
        try:
            for lo, hi in self._bounds:
                self._fork(sims, lo, hi, reload)
        finally:
            fds = [fd for p in self._pipes for fd in p]
            self._finalizer = weakref.finalize(self, _shutdown, os.getpid(), list(self._pids), fds)
        del sims
        if reload is not None:  # each worker replies once it has loaded its worlds (or failed to)
            self._run_locked("loaded", self._same_for_all(None))

    def _fork(self, sims, lo, hi, reload):
        down_r, down_w = os.pipe()
        up_r, up_w = os.pipe()
        pid = os.fork()
        if pid == 0:  # the worker: never returns into the caller's code
            status = 0
            mine = []
            try:
                signal.signal(signal.SIGINT, signal.SIG_IGN)  # the caller handles Ctrl-C
                signal.signal(signal.SIGTERM, _worker_terminated)
                for fd in list(_PARENT_FDS) + [down_w, up_r]:
                    os.close(fd)
                if reload is None:
                    mine = sims[lo:hi]
                    del sims[:]  # the other workers' worlds
                else:  # its own worlds, loaded here: their programs are this worker's children
                    scene, per_world, seeds, dt = reload
                    try:
                        mine = [_simbob.Simulation(scene, overrides=per_world[i], seed=seeds[i], dt=dt)
                                for i in range(lo, hi)]
                        for j, sim in enumerate(mine):
                            self._state.publish(lo + j, sim)
                        reply = ("done", [])
                    except Exception as e:  # noqa: BLE001 - raised by the caller
                        reply = ("done", [(lo + len(mine), _pack_exception(e))])
                    _send(up_w, reply)
                _serve(mine, lo, self._state, down_r, up_w)
            except BaseException:  # noqa: BLE001
                status = 70
            finally:
                try:
                    del mine[:]  # its worlds end, and with them the programs they started
                finally:
                    os._exit(status)
        os.close(down_r)
        os.close(up_w)
        self._pids.append(pid)
        self._pipes.append((down_w, up_r))
        _PARENT_FDS.update((down_w, up_r))

    def _run(self, op, args):
        """Runs op on every world (args: one per worker, or one for all), raises the first failure."""
        if not self._lock.acquire(blocking=False):
            raise _usage("this Batch is in use by another thread: use one Batch from one thread at a time")
        try:
            self._run_locked(op, args)
        finally:
            self._lock.release()

    def _run_locked(self, op, args):
        if self._sims is None and not self._pipes:
            raise _usage(self._closed_why)
        try:
            failures = self._call(op, args)
        except KeyboardInterrupt:
            # Ctrl-C in the middle of a call: some worlds have finished it, others not (a worker's
            # reply may still be on its way). The worlds can no longer be stepped together: the
            # workers are ended (SIGTERM: they leave the call within moments) and the Batch closed.
            name = {"step": "step", "until": "run_until", "commands": "set_commands", "reset": "reset",
                    "loaded": "Batch"}[op]
            self._closed_why = (f"this Batch was closed by KeyboardInterrupt during {name}(): its worlds had "
                                f"not all finished the call; make a new Batch")
            self._close(terminate=True)
            raise
        if failures:
            world, packed = min(failures, key=lambda f: f[0])
            if op == "loaded":
                self.close()
            raise _unpack_exception(packed, world)

    def _call(self, op, args):
        """Sends op to the workers (or runs it here) and returns the failures."""
        if self._sims is not None:
            return _apply(self._sims, 0, self._state, op, args[0])
        if op != "loaded":  # "loaded": the workers' first reply, sent once they have loaded their worlds
            for (down, _), a in zip(self._pipes, args):
                try:
                    _send(down, (op, a))
                except OSError:  # a worker that has ended: its reply below is the end of its pipe
                    pass
        failures = []
        for w, (_, up) in enumerate(self._pipes):
            reply = _recv(up)
            if reply is None:
                lo, hi = self._bounds[w]
                self.close()
                raise _simbob.InternalError(
                    f"Batch: worker {w} (worlds {lo} to {hi - 1}) ended unexpectedly; the Batch is closed",
                    "Internal")
            failures.extend(reply[1])
        return failures

    def _same_for_all(self, arg):
        return [arg] * len(self._bounds)

    def step(self, k=1):
        """Takes k whole steps (dt) in every world, serving its parties as Simulation.step does."""
        if isinstance(k, bool) or not isinstance(k, numbers.Integral) or k < 0:
            raise _usage(f"step: k must be an integer >= 0, got {k!r}")
        self._run("step", self._same_for_all(int(k)))

    def run_until(self, t):
        """Steps every world to its first grid instant at or after t (s), as Simulation.run_until."""
        t = float(t)
        if not math.isfinite(t):
            raise _usage(f"run_until: the time must be finite, got {t!r}")
        self._run("until", self._same_for_all(t))

    def set_commands(self, commands):
        """Commands every actuator of every world from its current instant on: `commands` is
        float64-convertible of shape (n, A) (A = len(actuator_keys)), or (A,) for all worlds
        alike; entries are clamped as Simulation.set_command clamps them, and must be finite."""
        a = np.asarray(commands, dtype=np.float64)
        want = (self.n, len(self.actuator_keys))
        if a.shape not in (want, want[1:]):
            raise _usage(f"set_commands: expected an array of shape {want} (worlds, actuators) or {want[1:]}, "
                         f"got {a.shape}")
        if not np.all(np.isfinite(a)):
            raise _usage("set_commands: every command must be finite")
        self._state.commands_in[...] = a
        self._run("commands", self._same_for_all(None))

    def reset(self, seeds=None):
        """Every world back to t = 0, world i seeded with seeds[i] (None: the seeds given to Batch)."""
        s = self._seeds if seeds is None else _seeds(seeds, self.n, "reset")
        self._run("reset", [s[lo:hi] for lo, hi in self._bounds])

    def poses(self):
        """Body poses, float64 (n, N, 7): per world, Simulation.poses()."""
        return self._state.poses.copy()

    def velocities(self):
        """Body velocities, float64 (n, N, 6): per world, Simulation.velocities()."""
        return self._state.velocities.copy()

    def joint_positions(self):
        """Joint positions, float64 (n, J): per world, Simulation.joint_positions()."""
        return self._state.joint_positions.copy()

    def joint_velocities(self):
        """Joint velocities, float64 (n, J): per world, Simulation.joint_velocities()."""
        return self._state.joint_velocities.copy()

    def commands(self):
        """Actuator commands, float64 (n, A): per world, Simulation.commands()."""
        return self._state.commands.copy()

    def touching(self):
        """Proximity sensors, bool (n, S): per world, Simulation.touching()."""
        return self._state.touching.copy()

    @property
    def time(self):
        """Each world's simulated time (s), float64 (n,)."""
        return self._state.time.copy()

    @property
    def steps(self):
        """Each world's whole steps since t = 0, int64 (n,)."""
        return self._state.steps.copy()

    @property
    def running(self):
        """Each world's Simulation.running, bool (n,)."""
        return self._state.running.copy()

    def close(self):
        """Ends the workers (idempotent); the last state stays readable."""
        self._close()

    def _close(self, terminate=False):
        if self._finalizer is not None:
            if terminate and self._finalizer.alive:
                self._finalizer.detach()
                fds = [fd for p in self._pipes for fd in p]
                _shutdown(os.getpid(), list(self._pids), fds, terminate=True)
            else:
                self._finalizer()
        self._pipes = []
        self._sims = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        return (f"<simbob.Batch {self.scene!r} n={self.n} workers={self.workers} "
                f"t={float(self._state.time.min()):g}..{float(self._state.time.max()):g}>")
