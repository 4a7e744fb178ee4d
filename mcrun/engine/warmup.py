"""The kernel's compilation: whether it is ready for a kind of ground, and its warm-up.

Numba compiles the batch kernel once for each kind of ground it runs on: the ``"plane"`` (no
terrain: each shot lands on its own plane of the slope model) and a ``"terrain"`` (a hole's
grid, ``ground.Terrain``). A compilation takes a minute or two, the first time after an
install or a change of the kernel's source; it is then cached on disk (``__pycache__``, or
``NUMBA_CACHE_DIR``) and loaded in about a second. The command line asks ``kernel_cached``
before a command (the plane's), and again once a command has read that it plays on a hole
(the terrain's: ``mcrun run`` of a hole, ``mcrun aim``); when the answer is no, it runs
``warm_up`` and says how long it took, so that the command's own time and rate are its own.

``warm_up_all`` (``mcrun warm-up``) compiles every kernel on every kind of ground ahead, one
spawned process per kind of ground where there are cores, their cache saves locked against
each other (``cache_lock``).
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


def dispatcher_cached(dispatcher, signature=None):
    """Whether the Numba ``dispatcher`` is compiled for ``signature`` (a tuple of Numba types;
    None: for any), in this process or in its on-disk cache for this source, this Numba and
    this CPU. Raises AttributeError where Numba's cache internals have moved."""
    compiled = dispatcher.overloads
    if bool(compiled) if signature is None else signature in compiled:
        return True
    # What the dispatcher looks up on disk before it compiles (numba.core.caching.Cache): the
    # index of its cache, for its source stamp, by signature, CPU and bytecode.
    cache = dispatcher._cache
    codegen = dispatcher.targetctx.codegen()
    files = cache._cache_file
    index = files._load_index()
    if signature is None:
        rest = cache._index_key((), codegen)[1:]
        names = [name for key, name in index.items() if key[1:] == rest]
    else:
        names = [index.get(cache._index_key(signature, codegen))]
    return any(name is not None and os.path.exists(os.path.join(files._cache_path, name))
               for name in names)  # fmt: skip


def _compiled(ground, kernel):
    """Whether ``kernel`` for ``ground`` is compiled, in this process or on disk."""
    dispatcher = _kernel(kernel)
    signature = tuple(dispatcher.typeof_pyval(a) for a in _kernel_arguments(ground, kernel))
    return dispatcher_cached(dispatcher, signature)


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


# --- every kernel, in parallel processes -------------------------------------------------------


class KernelWarmUp(NamedTuple):
    """What ``warm_up_all`` did for one kernel on one kind of ground."""

    ground: str  # of GROUNDS
    kernel: str  # of KERNELS
    seconds: float  # wall time of its compilation, or of loading it from the cache
    was_cached: bool | None  # ``kernel_cached`` before: False, it compiled; True, it loaded


class WarmUpReport(NamedTuple):
    """What ``warm_up_all`` did: each kernel in order, the processes and the wall time."""

    kernels: tuple  # of KernelWarmUp, by ground then kernel
    processes: int  # 1: in this process, one after the other
    wall_s: float


class WarmUpError(RuntimeError):
    """A warm-up job failed (in a child process or here); its message is one line."""


def choose(values, allowed, what):
    """``values`` without repeats, each of ``allowed`` (else ValueError, one line naming
    ``what`` it is), at least one."""
    values = tuple(dict.fromkeys(values))
    for value in values:
        if value not in allowed:
            raise ValueError(f"unknown {what} '{value}': choose one of {', '.join(allowed)}")
    if not values:
        raise ValueError(f"no {what} to warm up: choose among {', '.join(allowed)}")
    return values


def timed(ground, kernels, cached, run):
    """``run(kernel)`` for each of ``kernels`` on ``ground`` in turn, each timed on its own,
    ``cached(kernel)`` asked before: a list of ``KernelWarmUp``."""
    done = []
    for kernel in kernels:
        was_cached = cached(kernel)
        started = time.perf_counter()
        run(kernel)
        done.append(KernelWarmUp(ground, kernel, time.perf_counter() - started, was_cached))
    return done


def warm_pair(ground, kernels):
    """Compile (or load) each of ``kernels`` on ``ground`` in this process, in order, each timed
    on its own (``timed``): a list of ``KernelWarmUp``."""
    return timed(ground, kernels, lambda k: kernel_cached(ground, (k,)), lambda k: _run(ground, k))


def warm_up_job(*pairs):
    """One job of ``warm_up_all``: ``warm_pair`` of each (ground, kernels) pair in turn, its
    cache saves locked against the other jobs' (``cache_lock``). Returns a list of
    ``KernelWarmUp``."""
    from mcrun.engine import cache_lock

    with cache_lock.locked_saves():
        return [done for ground, kernels in pairs for done in warm_pair(ground, kernels)]


# The terrain's kernels that go with the plane's in a job of their own when there are two
# processes (``jobs``): measured on a 2-core AMD EPYC, all ten kernels compile in 79 s so
# against 96 s in one job per ground, whose plane's job ends some 40 s before the terrain's.
# (A kernel compiles what it shares with the kernels compiled before it in its process only
# once, so that the costs do not add up kernel by kernel: this split is measured, not summed.)
TERRAIN_WITH_PLANE = ("landed", "traced")


def jobs(grounds, kernels, processes):
    """``warm_up_all``'s jobs, each a tuple of (ground, kernels) pairs compiled in one process:
    one job per ground, but with two processes or more for both grounds, the terrain's kernels
    of ``TERRAIN_WITH_PLANE`` go with the plane's, so that the two jobs take about as long."""
    if processes < 2 or set(grounds) != set(GROUNDS):
        return [((g, kernels),) for g in grounds]
    apart = tuple(k for k in kernels if k not in TERRAIN_WITH_PLANE)
    along = tuple(k for k in kernels if k in TERRAIN_WITH_PLANE)
    if not apart or not along:
        return [((g, kernels),) for g in grounds]
    return [(("terrain", apart),), (("plane", kernels), ("terrain", along))]


def _one_line(err):
    return " ".join(f"{type(err).__name__}: {err}".split()) or type(err).__name__


def default_processes(jobs):
    """The processes for ``jobs`` jobs: one each, at most the cores this process may use."""
    try:
        cores = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cores = os.cpu_count() or 1
    return max(1, min(jobs, cores))


def run_jobs(job, arguments, processes):
    """``[job(*a) for a in arguments]``: here, one after the other, when ``processes`` is 1;
    otherwise in ``processes`` new (spawned) processes at once. A job that raises, or a process
    that dies, raises ``WarmUpError`` with one line naming the job's arguments."""
    if processes <= 1 or len(arguments) <= 1:
        results = []
        for args in arguments:
            try:
                results.append(job(*args))
            except Exception as err:
                raise WarmUpError(f"{_describe(args)}: {_one_line(err)}") from err
        return results
    import concurrent.futures
    import multiprocessing

    context = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(processes, mp_context=context) as pool:
        futures = [pool.submit(job, *args) for args in arguments]
        results = []
        try:
            for args, future in zip(arguments, futures, strict=True):
                try:
                    results.append(future.result())
                except Exception as err:
                    raise WarmUpError(f"{_describe(args)}: {_one_line(err)}") from None
        except BaseException:
            for future in futures:
                future.cancel()
            raise
    return results


def _describe(args):
    """What a job of ``warm_up_job``'s (ground, kernels) pairs ``args`` did, for its error."""
    if args and all(
        isinstance(a, tuple) and len(a) == 2 and isinstance(a[0], str) and isinstance(a[1], tuple)
        for a in args
    ):
        what = " and ".join(f"the {', '.join(kernels)} kernel(s) on the {ground}"
                            for ground, kernels in args)  # fmt: skip
        return f"warming up {what} failed"
    return f"warm-up job {args!r} failed"


def warm_up_all(grounds=GROUNDS, kernels=KERNELS, processes=None, also=(), job=warm_up_job):
    """Compile every kernel of ``kernels`` for every kind of ground of ``grounds`` (all of
    them by default), or load it from Numba's on-disk cache, as ``warm_up`` does: one job per
    ground (its kernels in order, which share their callees; with two processes, two of the
    terrain's go with the plane's: ``jobs``), the jobs in ``processes`` spawned processes at
    once (default: one per job, at most the cores; 1: in this process, one after the other).
    ``also``: more jobs, of kernels above the engine's (each a tuple of (ground, kernels)
    pairs), after the engine's, every job then run by ``job``, a function of such pairs that
    knows their grounds (``putting.warmup.warm_up_all``, the green's kernels); ``grounds``
    may then be empty. The jobs' saves to the cache are locked against each other
    (``cache_lock``: concurrent saves could otherwise lose index entries); where that lock is
    not available the jobs run one after the other. Returns a ``WarmUpReport``; raises
    ``WarmUpError`` (one line) when a job fails, ``ValueError`` for an unknown ground or
    kernel."""
    from mcrun.engine import cache_lock

    also = [tuple(pairs) for pairs in also]
    grounds = choose(grounds, GROUNDS, "ground") if grounds or not also else ()
    kernels = choose(kernels, KERNELS, "kernel") if grounds else ()
    count = len(grounds) + len(also)
    if processes is None:
        processes = default_processes(count)
    elif isinstance(processes, bool) or not isinstance(processes, int) or processes < 1:
        raise ValueError(f"processes must be a whole number >= 1, got {processes!r}")
    processes = min(processes, count)
    if not cache_lock.available():
        processes = 1
    started = time.perf_counter()
    planned = (jobs(grounds, kernels, processes) if grounds else []) + also
    results = run_jobs(job, planned, processes)
    pairs = [(g, k) for g in grounds for k in kernels]
    pairs += [(g, k) for extra in also for g, ks in extra for k in ks]
    order = {pair: i for i, pair in enumerate(pairs)}
    done = tuple(sorted((k for job in results for k in job),
                        key=lambda k: order[(k.ground, k.kernel)]))  # fmt: skip
    return WarmUpReport(done, processes, time.perf_counter() - started)


# What the compile of each ground's kernels is called on stderr (``announced``), by the command
# line and the Dask client alike.
KERNEL_NAMES = {
    "plane": ("the kernels", "first run after install"),
    "terrain": ("the kernel for a hole's ground", "first run on a hole after install"),
}


def compile_announced(ground, kernels=("batch",), say=print):
    """When the ``kernels`` for ``ground`` are not in Numba's on-disk cache, compile them here,
    saying so (``say``, a function of one line) before and after, with the time it took.
    Returns the seconds of the compilation (0.0 when none was needed)."""
    if kernel_cached(ground, kernels) is not False:
        return 0.0
    what, when = KERNEL_NAMES[ground]
    return announced(what, when, lambda: warm_up((ground,), kernels), say)


def announced(what, when, warm, say):
    """``warm()`` (a warm-up: its ``WarmUp``s or ``KernelWarmUp``s) said before and after
    (``say``, a function of one line): ``mcrun: compiling {what} ({when}; cached for the next
    runs)``, then ``mcrun: compiled {what} in N s``. Returns its seconds."""
    say(f"mcrun: compiling {what} ({when}; cached for the next runs)")
    seconds = sum(done.seconds for done in warm())
    say(f"mcrun: compiled {what} in {seconds:.0f} s")
    return seconds
