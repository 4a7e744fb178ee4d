"""The engine's warm-up and cache check (``mcrun.engine.warmup``), which the command line asks
before a command: the kernel for a kind of ground is "cached" exactly when running it would
compile nothing.

A cold compilation takes a minute or two per kind of ground, too long for every run of the
suite: the cold case is checked in a child process whose Numba cache is an empty folder (where
nothing is cached, and the check itself compiles nothing), the warm case in this process after
a warm-up, and on disk in a child process that has compiled nothing itself.
"""

import os
import subprocess
import sys
from pathlib import Path

import numba
import pytest

from mcrun.engine import warmup
from mcrun.run import scenario

ROOT = Path(__file__).resolve().parents[1]
CHECK = "from mcrun.engine import warmup; print(*(warmup.kernel_cached(g) for g in warmup.GROUNDS))"


@pytest.fixture(scope="module")
def warmed():
    return warmup.warm_up()


def child(env=None):
    done = subprocess.run(
        [sys.executable, "-c", CHECK],
        capture_output=True,
        text=True,
        env={**os.environ, **(env or {})},
        check=True,
    )
    return done.stdout.split()


def test_warm_up_says_what_it_compiled_and_how_long(warmed):
    assert [w.ground for w in warmed] == ["plane", "terrain"]
    for w in warmed:
        assert w.seconds >= 0.0
        assert w.was_cached in (True, False)


def test_cached_after_the_warm_up(warmed):
    """In this process: the signature the check builds is one the warm-up compiled (or
    loaded), i.e. the one ``backend.simulate_batch`` dispatches to."""
    assert warmup.kernel_cached("plane") is True
    assert warmup.kernel_cached("terrain") is True


def test_not_cached_in_an_empty_cache(tmp_path):
    """A Numba cache folder with nothing in it: neither kernel is cached (and the check
    compiles nothing: the folder stays empty)."""
    assert child({"NUMBA_CACHE_DIR": str(tmp_path)}) == ["False", "False"]
    assert not any(p.suffix in (".nbi", ".nbc") for p in tmp_path.rglob("*"))


def test_cached_on_disk_after_the_warm_up(warmed):
    """A new process, which has compiled nothing, finds both kernels in the on-disk cache the
    warm-up filled (or loaded from)."""
    assert child() == ["True", "True"]


def test_a_hole_runs_the_kernel_compiled_for_the_sample_terrain():
    """Every hole's terrain has the type of ``sample_terrain``: the kernel warmed for the
    terrain is the one a hole runs."""
    hole = scenario.load(ROOT / "scenarios" / "par3-over-water.toml").hole
    assert numba.typeof(hole.terrain()) == numba.typeof(warmup.sample_terrain())


def test_an_unknown_ground_is_refused():
    with pytest.raises(ValueError, match="unknown ground 'green'"):
        warmup.kernel_cached("green")
    with pytest.raises(ValueError, match="unknown ground 'green'"):
        warmup.warm_up(("plane", "green"))


def test_every_kernel_is_cached_after_its_warm_up():
    """The traced batch (a recorded path) and the run from a landing (the paper's figures) are
    kernels of their own, which a command that uses them compiles, and says so, before its
    work: the signature the check builds for each is the one its warm-up, which runs it as the
    backend does, compiled."""
    warmed = warmup.warm_up(kernels=warmup.KERNELS)
    assert [w.ground for w in warmed] == list(warmup.GROUNDS)
    for kernel in warmup.KERNELS:
        for ground in warmup.GROUNDS:
            assert warmup.kernel_cached(ground, (kernel,)) is True, (kernel, ground)
    with pytest.raises(ValueError, match="unknown kernel 'fast'"):
        warmup.warm_up(("plane",), ("fast",))
