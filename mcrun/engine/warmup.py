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

from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import N_INPUT, N_OUTCOME
from mcrun.ground import IN_PLAY, make_terrain
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


def _kernel():
    """The batch kernel's Numba dispatcher: the one place that names it."""
    from mcrun.engine.batch import _simulate_batch

    return _simulate_batch


def _kernel_arguments(ground):
    """Arguments of the types the batch kernel gets from ``backend.simulate_batch`` on
    ``ground``: inputs and outcomes float64 in Fortran order (at least two rows), the
    quadratic models' table and the terrain (None on the plane)."""
    inputs = np.zeros((2, N_INPUT), order="F")
    out = np.empty((2, N_OUTCOME), order="F")
    return inputs, QUADRATIC_COEFFICIENTS, out, _terrain(ground)


def kernel_cached(ground="plane"):
    """Whether the batch kernel for ``ground`` (``"plane"`` or ``"terrain"``) is compiled: in
    this process, or in Numba's on-disk cache for this source, this Numba and this CPU, so that
    running it compiles nothing. None when it cannot be told (Numba's cache internals have
    moved, or the JIT is disabled: ``NUMBA_DISABLE_JIT=1``)."""
    _check(ground)
    kernel = _kernel()
    try:
        signature = tuple(kernel.typeof_pyval(a) for a in _kernel_arguments(ground))
        if signature in kernel.overloads:
            return True
        # What the dispatcher looks up on disk before it compiles (numba.core.caching.Cache):
        # the index of the kernel's cache, for its source stamp, by signature, CPU and bytecode.
        cache = kernel._cache
        key = cache._index_key(signature, kernel.targetctx.codegen())
        files = cache._cache_file
        name = files._load_index().get(key)
        return name is not None and os.path.exists(os.path.join(files._cache_path, name))
    except AttributeError:
        return None


def warm_up(grounds=GROUNDS):
    """Compile the batch kernel for each kind of ground in ``grounds``, or load it from Numba's
    cache: a batch of two shots that end at once (speed 0, ``invalid_input``) on the plane,
    and on ``sample_terrain``. Returns a ``WarmUp`` for each, in order: whether it was
    cached before, and how long it took."""
    for ground in grounds:
        _check(ground)
    done = []
    for ground in grounds:
        was_cached = kernel_cached(ground)
        started = time.perf_counter()
        simulate_batch(np.zeros((0, N_INPUT)), terrain=_terrain(ground))
        done.append(WarmUp(ground, time.perf_counter() - started, was_cached))
    return tuple(done)
