"""The kernel's compilation: whether it is ready for a kind of ground, and its warm-up.

Numba compiles the batch kernel once for each kind of ground it runs on: the ``"plane"`` (no
terrain: each shot lands on its own plane of the slope model) and a ``"terrain"`` (a hole's
grid, ``ground.Terrain``). A compilation takes a minute or two, the first time after an
install or a change of the kernel's source; it is then cached on disk (``__pycache__``, or
``NUMBA_CACHE_DIR``) and loaded in about a second. The command line asks ``kernel_cached``
before a command (the plane's), and again once a command has read that it plays on a hole
(the terrain's: ``mcrun run`` of a hole, ``mcrun aim``); when the answer is no, it runs
``warm_up`` and says how long it took, so that the command's own time and rate are its own.
"""

import os
import time
from typing import NamedTuple

import numpy as np

from mcrun.engine.backend import simulate_batch, simulate_landed, simulate_traced
from mcrun.engine.schema import COLUMN, N_INPUT, N_OUTCOME
from mcrun.engine.tables import N_LANDING
from mcrun.ground import IN_PLAY, make_terrain
from mcrun.physics import aero
from mcrun.physics.aero import QUADRATIC_COEFFICIENTS
from mcrun.physics.turf import PRESETS

# The kinds of ground the kernel is compiled for.
GROUNDS = ("plane", "terrain")


class WarmUp(NamedTuple):
    """What ``warm_up`` did for one kind of ground."""

    ground: str  # "plane" or "terrain"
    seconds: float  # wall time of the compilation (or of loading it from the cache)
    was_cached: bool | None  # ``kernel_cached`` before: False, it compiled; True, it loaded


def _check(ground):
    if ground not in GROUNDS:
        raise ValueError(f"unknown ground '{ground}': choose one of {', '.join(GROUNDS)}")


def sample_terrain():
    """The smallest terrain: 2 x 2 nodes 1 m apart, level, one zone of fairway in play. Its
    type is that of every hole's terrain (``make_terrain`` builds them all), so that the kernel
    compiled for it is the one a hole runs."""
    return make_terrain(
        0.0, 0.0, 1.0, np.zeros((2, 2)), np.zeros((2, 2), np.int8),
        np.array([PRESETS["fairway"]], np.float64), np.array([IN_PLAY], np.int8),
    )  # fmt: skip


def _terrain(ground):
    return sample_terrain() if ground == "terrain" else None


# The kernels, each compiled on its own for each kind of ground: the batch (every run, and a
# single shot), the traced batch (a shot whose path is recorded: ``mcrun shot --trajectory``,
# a run's ``--trajectories``), each for shots of the quadratic flight kind and, apart, for
# batches that hold shots of the general kind too (``batch.needs_general``: a model that
# does not fly in the vectorised lanes, or a wind profile), and the run from a landing
# (``mcrun paper``'s bounce studies).
KERNELS = ("batch", "traced", "landed", "batch_general", "traced_general")


def general(kernels):
    """``kernels`` for shots of the general flight kind: each batch kernel's general kind."""
    return tuple(f"{k}_general" if f"{k}_general" in KERNELS else k for k in kernels)


def _kernel(kernel="batch"):
    """A kernel's Numba dispatcher: the one place that names them."""
    from mcrun.engine import batch

    return {
        "batch": batch._batch_task,
        "batch_general": batch._batch_task_general,
        "traced": batch._simulate_traced,
        "traced_general": batch._simulate_traced_general,
        "landed": batch._simulate_landed,
    }[kernel]


def _kernel_arguments(ground, kernel="batch"):
    """Arguments of the types a kernel gets from ``backend`` on ``ground``: inputs and outcomes
    float64 in Fortran order (at least two rows: ``batch._as_kernel_layout``), the task's
    number, the quadratic models' table, a path's buffer and the terrain (None on the
    plane)."""
    inputs = np.zeros((2, N_INPUT), order="F")
    out = np.empty((2, N_OUTCOME), order="F")
    traj = np.empty((1, 5))
    terrain = _terrain(ground)
    if kernel.startswith("traced"):
        return inputs, 0, QUADRATIC_COEFFICIENTS, out, traj, terrain
    if kernel == "landed":
        return inputs, np.zeros((2, N_LANDING)), out, traj, np.zeros(4), terrain
    return inputs, 0, QUADRATIC_COEFFICIENTS, out, terrain


def _compiled(ground, kernel):
    """Whether ``kernel`` for ``ground`` is compiled, in this process or on disk (None: cannot
    be told)."""
    dispatcher = _kernel(kernel)
    signature = tuple(dispatcher.typeof_pyval(a) for a in _kernel_arguments(ground, kernel))
    if signature in dispatcher.overloads:
        return True
    # What the dispatcher looks up on disk before it compiles (numba.core.caching.Cache): the
    # index of the kernel's cache, for its source stamp, by signature, CPU and bytecode.
    cache = dispatcher._cache
    key = cache._index_key(signature, dispatcher.targetctx.codegen())
    files = cache._cache_file
    name = files._load_index().get(key)
    return name is not None and os.path.exists(os.path.join(files._cache_path, name))


def kernel_cached(ground="plane", kernels=("batch",)):
    """Whether the ``kernels`` (of ``KERNELS``; the batch kernel by default) for ``ground``
    (``"plane"`` or ``"terrain"``) are compiled: in this process, or in Numba's on-disk cache
    for this source, this Numba and this CPU, so that running them compiles nothing. None when
    it cannot be told (Numba's cache internals have moved, or the JIT is disabled:
    ``NUMBA_DISABLE_JIT=1``)."""
    _check(ground)
    try:
        return all(_compiled(ground, kernel) for kernel in kernels)
    except AttributeError:
        return None


def _run(ground, kernel):
    """Run ``kernel`` once on ``ground``: a shot that ends at once (speed 0, invalid_input),
    of a model of the general flight kind for a general kernel."""
    terrain = _terrain(ground)
    inputs = np.zeros((1, N_INPUT))
    if kernel.endswith("_general"):
        inputs[:, COLUMN["aero_model"]] = aero.SMITS_SMITH1994
    if kernel.startswith("traced"):
        simulate_traced(inputs, terrain=terrain)
    elif kernel == "landed":
        simulate_landed(inputs, np.zeros((1, N_LANDING)), terrain=terrain)
    else:
        simulate_batch(inputs, terrain=terrain)


def warm_up(grounds=GROUNDS, kernels=("batch",)):
    """Compile the ``kernels`` (the batch kernel by default) for each kind of ground in
    ``grounds``, or load them from Numba's cache, by running each on a shot that ends at once
    (speed 0, ``invalid_input``) on the plane and on ``sample_terrain``. Returns a ``WarmUp``
    for each ground, in order: whether its kernels were cached before, and how long they took."""
    for ground in grounds:
        _check(ground)
    for kernel in kernels:
        if kernel not in KERNELS:
            raise ValueError(f"unknown kernel '{kernel}': choose one of {', '.join(KERNELS)}")
    done = []
    for ground in grounds:
        was_cached = kernel_cached(ground, kernels)
        started = time.perf_counter()
        for kernel in kernels:
            _run(ground, kernel)
        done.append(WarmUp(ground, time.perf_counter() - started, was_cached))
    return tuple(done)
