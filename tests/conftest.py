"""Fixtures, options and the session's set-up shared by several test files.

The suite runs in parallel on every core (``pytest -n auto``, pytest-xdist), each test file in
one worker (``--dist loadfile``, so that a module's fixtures are built once). Before the workers
start, the main process compiles every kernel of the engine, one process per kind of ground
(``mcrun warm-up``), or loads them from Numba's cache when nothing changed, so that the workers
load them instead of each compiling the same kernels at once; every process saves to Numba's
cache under its lock (``cache_lock``), so that workers compiling other functions at once lose
no entry.
"""

import signal

import pytest


def pytest_addoption(parser):
    parser.addoption(
        "--bit-for-bit", action="store_true",
        help="compare the golden file bit for bit (for a refactoring, on the machine that wrote "
        "it); by default floats are compared at a tolerance that holds on any CPU",
    )  # fmt: skip


def pytest_configure(config):
    from mcrun.engine import cache_lock

    config._mcrun_locked_saves = cache_lock.locked_saves()
    config._mcrun_locked_saves.__enter__()
    workers = getattr(config.option, "numprocesses", None)
    if workers and not hasattr(config, "workerinput"):  # the main process of a parallel run
        from mcrun.engine.warmup import warm_up_all

        # (Said as it starts: from a fresh clone this takes minutes, and pytest -q prints
        # nothing meanwhile.)
        say("compiling the engine's kernels for the tests, or loading them from Numba's cache")
        report = warm_up_all()
        compiled = sum(1 for kernel in report.kernels if kernel.was_cached is False)
        loaded = len(report.kernels) - compiled
        say(f"kernels ready in {report.wall_s:.0f} s ({compiled} compiled, {loaded} loaded)")


def say(line):
    """``line`` on the terminal at once, through pytest's capture."""
    import sys

    print(f"mcrun tests: {line}", file=sys.__stderr__, flush=True)


def pytest_unconfigure(config):
    locked = getattr(config, "_mcrun_locked_saves", None)
    if locked is not None:
        locked.__exit__(None, None, None)


@pytest.fixture
def ctrl_c_raises():
    """SIGINT raises KeyboardInterrupt during the test, as in a terminal, even where the suite
    was started with SIGINT ignored (a job put in the background by a non-interactive shell
    inherits it ignored, and Python then installs no handler of its own)."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)
