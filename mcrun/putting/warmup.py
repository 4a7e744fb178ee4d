"""The green's kernels: whether they are compiled, their warm-up, and every kernel's at once.

Putting has kernels of its own beside the engine's (``engine.warmup``), on a ground of its own,
``"green"``:

- ``"putt"``: a putt read and holed out on a plane green (``mcrun putt --distance``,
  ``putting.putt``): the read's search and its lines, the value of a read and the centre line,
  each compiled where Python calls it;
- ``"map"``: the solver of a green's expected-putts map and the lookup of its values
  (``green_map``: ``mcrun putt --hole``, and every hole putted with the physics, in ``mcrun
  run``, ``aim``, ``play`` and ``rate``).

Each compiles the first time it runs after an install or a change of its source (half a minute
or more on two cores) and is then cached on disk, as the engine's are. ``warm_up`` runs each on
a tiny case; ``warm_up_all`` (``mcrun warm-up``) compiles the engine's kernels and the green's
in parallel processes.
"""

import numpy as np

from mcrun.engine import warmup as engine

GROUND = "green"
KERNELS = ("putt", "map")
# Every kind of ground with kernels: the engine's, then the green.
GROUNDS = (*engine.GROUNDS, GROUND)


def _dispatchers(kernel):
    """The Numba dispatchers a kernel compiles where Python calls them."""
    from mcrun.putting import green_map, read, stroke

    return {
        "putt": (
            read.search,
            read.read_lines,
            read.value_read,
            stroke.pace_speed_mps,
            stroke.centre_line,
        ),  # fmt: skip
        "map": (green_map._solve_points, green_map._values),
    }[kernel]


def _check(kernels):
    for kernel in kernels:
        if kernel not in KERNELS:
            raise ValueError(f"unknown kernel '{kernel}' of the green: choose one of "
                             f"{', '.join(KERNELS)}")  # fmt: skip


def kernel_cached(kernels=KERNELS):
    """Whether the green's ``kernels`` (of ``KERNELS``) are compiled, in this process or in
    Numba's on-disk cache for this source, this Numba and this CPU (for any signature: each
    is called with one), so that running them compiles nothing. None when it cannot be told."""
    _check(kernels)
    try:
        return all(engine.dispatcher_cached(d) for k in kernels for d in _dispatchers(k))
    except AttributeError:
        return None


def tiny_green():
    """A green of 17 x 17 nodes 0.25 m apart, sloping 1 %, its nodes within 2 m of the pin at
    its centre the green's: its types are those of every hole's green."""
    from mcrun.putting.green import Green
    from mcrun.putting.roll import Surface

    x = np.arange(-8, 9) * 0.25
    xx, yy = np.meshgrid(x, x)
    surface = Surface(0.01 * xx, (np.hypot(xx, yy) <= 2.0).astype(np.uint8), float(x[0]),
                      float(x[0]), 0.25)  # fmt: skip
    return Green(surface, (0.0, 0.0), 0.1, "warm-up")


def _run(kernel):
    """Run ``kernel`` once, on a tiny case."""
    if kernel == "putt":
        from mcrun.putting import putt

        for read in (True, False):
            putt(2.0, 3.0, 0.01, 90.0, n=2, read=read)
    else:
        from mcrun.putting.green_map import expected_putts_map

        expected_putts_map(tiny_green(), n=2, resolution_m=1.0, threads=1).value_at(0.5, 0.5)


def warm_up(kernels=KERNELS):
    """Compile the green's ``kernels``, or load them from Numba's cache, each in turn on a tiny
    case: a list of ``engine.warmup.KernelWarmUp``, one per kernel, in order."""
    _check(kernels)
    return engine.timed(GROUND, kernels, lambda k: kernel_cached((k,)), _run)


def warm_up_job(*pairs):
    """A job of ``warm_up_all``: each (ground, kernels) pair in turn, the green's here, the
    engine's by ``engine.warmup.warm_pair``, its cache saves locked against the other jobs'."""
    from mcrun.engine import cache_lock

    done = []
    with cache_lock.locked_saves():
        for ground, kernels in pairs:
            done += warm_up(kernels) if ground == GROUND else engine.warm_pair(ground, kernels)
    return done


def warm_up_all(grounds=GROUNDS, kernels=None, processes=None):
    """Compile every kernel of mcrun, or load it from Numba's cache: the engine's (of
    ``engine.warmup.KERNELS``) on its grounds in ``grounds``, as ``engine.warmup.warm_up_all``
    does, and, where ``grounds`` holds ``"green"``, the green's (of ``KERNELS``) in a job of
    their own; ``kernels``: those of either kind to compile (None: all). Returns an
    ``engine.warmup.WarmUpReport``; raises ``ValueError`` (one line) for an unknown ground or
    kernel, or a ground none of whose kernels is asked for."""
    grounds = engine.choose(grounds, GROUNDS, "ground")
    both = engine.KERNELS + KERNELS
    asked = None if kernels is None else engine.choose(kernels, both, "kernel")

    def of(own):  # the kernels asked for of those ``own``
        return own if asked is None else tuple(k for k in asked if k in own)

    engine_kernels = of(engine.KERNELS)
    engine_grounds = tuple(g for g in grounds if g != GROUND) if engine_kernels else ()
    green = of(KERNELS) if GROUND in grounds else ()
    if not engine_grounds and not green:
        if len(grounds) == 1:
            own = KERNELS if grounds[0] == GROUND else engine.KERNELS
            raise ValueError(f"the {grounds[0]} has no kernel '{', '.join(asked)}': choose one "
                             f"of {', '.join(own)}")  # fmt: skip
        raise ValueError(f"the {' or the '.join(grounds)} has no kernel '{', '.join(asked)}'")
    also = [((GROUND, green),)] if green else []
    return engine.warm_up_all(engine_grounds, engine_kernels, processes, also, warm_up_job)


def compile_announced(kernels=KERNELS, say=print):
    """When the green's ``kernels`` are not in Numba's on-disk cache, compile them here, saying
    so (``say``, a function of one line) before and after, with the time it took, so that the
    work that follows is timed alone. Returns the seconds of the compilation (0.0 when none
    was needed)."""
    if kernel_cached(kernels) is not False:
        return 0.0
    return engine.announced("the green's kernels", "first putts after install",
                            lambda: warm_up(kernels), say)  # fmt: skip
