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


# --- every kernel at once: `mcrun warm-up` and warmup.warm_up_all ------------------------------

TINY = """\
from numba import njit


@njit(cache=True)
def add_one(x):
    return x + 1
"""

COMPILE_TINY = """\
import sys
sys.path.insert(0, sys.argv[1])
from mcrun.engine import cache_lock
with cache_lock.locked_saves():
    import tiny
    tiny.add_one(1 if sys.argv[2] == "int" else 1.0)
"""

LOAD_TINY = """\
import sys
sys.path.insert(0, sys.argv[1])
import tiny
tiny.add_one(1)
tiny.add_one(1.0)
print(tiny.add_one.stats.cache_hits and sum(tiny.add_one.stats.cache_hits.values()),
      sum(tiny.add_one.stats.cache_misses.values()))
"""


def test_warm_up_all_over_a_warm_cache_finds_every_kernel_cached(warmed):
    """Both grounds at once in two spawned processes (the suite's cache is warm: they load)."""
    report = warmup.warm_up_all(kernels=("batch",), processes=2)
    assert report.processes == 2
    assert [(k.ground, k.kernel) for k in report.kernels] == [
        ("plane", "batch"),
        ("terrain", "batch"),
    ]
    assert all(k.was_cached is True and k.seconds >= 0.0 for k in report.kernels)
    assert report.wall_s > 0.0


def test_jobs_run_in_processes_and_a_failure_is_one_line():
    import operator

    assert warmup.run_jobs(operator.add, [(1, 2), (3, 4)], 2) == [3, 7]
    assert warmup.run_jobs(operator.add, [(1, 2), (3, 4)], 1) == [3, 7]
    for processes in (1, 2):
        with pytest.raises(warmup.WarmUpError) as err:
            warmup.run_jobs(operator.truediv, [(1, 1), (1, 0)], processes)
        assert str(err.value) == "warm-up job (1, 0) failed: ZeroDivisionError: division by zero"


def test_warm_up_all_refuses_unknown_grounds_kernels_and_processes():
    with pytest.raises(ValueError, match="unknown ground 'green'"):
        warmup.warm_up_all(("green",))
    with pytest.raises(ValueError, match="unknown kernel 'fast'"):
        warmup.warm_up_all(kernels=("fast",))
    with pytest.raises(ValueError, match="processes"):
        warmup.warm_up_all(processes=0)


def test_cli_warm_up_says_what_it_found_cached(warmed, capsys):
    from mcrun.cli import main

    assert main(["warm-up", "--kernel", "batch", "--processes", "1"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].split() == ["ground", "kernel", "state", "time"]
    assert [line.split()[:3] for line in out[1:3]] == [
        ["plane", "batch", "cached"],
        ["terrain", "batch", "cached"],
    ]
    assert out[3].startswith("2 kernels (0 compiled, 2 cached) in ")
    assert out[3].endswith(" s wall time on 1 process")


@pytest.mark.parametrize(
    "argv, message",
    [
        (["--ground", "fairway"], "argument --ground: invalid choice: 'fairway'"),
        (
            ["--ground", "green", "--kernel", "batch"],
            "--kernel batch: the green has no kernel 'batch': choose one of putt, map",
        ),
        (
            ["--ground", "terrain", "--kernel", "map"],
            "--kernel map: the terrain has no kernel "
            "'map': choose one of batch, traced, landed, batch_general, traced_general",
        ),
        (["--kernel", "fast"], "argument --kernel: invalid choice: 'fast'"),
        (["--processes", "two"], "--processes 'two': allowed: a whole number from 1 to 2**63 - 1"),
        (["--processes", "0"], "--processes '0': allowed: a whole number from 1 to 2**63 - 1"),
        # (as every whole number: argparse's int() read "١٢" as 12 and refused "1e0")
        (["--processes", "١٢"], "--processes '١٢': only ASCII digits (0-9) are accepted"),
    ],
)
def test_cli_warm_up_refuses_a_bad_option_in_one_line(argv, message, capsys):
    from mcrun.cli import main

    assert main(["warm-up", *argv]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mcrun: error: ") and message in err
    assert err.count("\n") == 1


def test_locked_saves_restores_numba(tmp_path, monkeypatch):
    from numba.core.caching import IndexDataCacheFile

    from mcrun.engine import cache_lock

    # Numba's own save (the suite's processes save under the lock: conftest.py).
    save = getattr(IndexDataCacheFile.save, "__wrapped__", IndexDataCacheFile.save)
    monkeypatch.setattr(IndexDataCacheFile, "save", save)
    with cache_lock.locked_saves() as locked:
        assert locked is cache_lock.available()
        if locked:
            assert IndexDataCacheFile.save is not save
            with cache_lock.locked_saves():  # nested: the same lock
                pass
    assert IndexDataCacheFile.save is save


@pytest.mark.skipif(os.name != "posix", reason="the cache lock is POSIX flock")
def test_processes_compiling_one_function_at_once_keep_every_signature(tmp_path):
    """Two processes compile one cached function for two signatures at once, each saving to
    the one index file under the lock: a third process then loads both from the cache."""
    (tmp_path / "tiny.py").write_text(TINY)
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    children = [
        subprocess.Popen([sys.executable, "-c", COMPILE_TINY, str(tmp_path), kind], env=env)
        for kind in ("int", "float")
    ]
    assert [child.wait() for child in children] == [0, 0]
    done = subprocess.run(
        [sys.executable, "-c", LOAD_TINY, str(tmp_path)],
        env=env,
        capture_output=True,
        text=True,
        check=True,
    )
    assert done.stdout.split() == ["2", "0"]


def test_cli_warm_up_reports_a_failed_job_in_one_line(monkeypatch, capsys):
    from mcrun.cli import main

    def failing(*args):
        raise warmup.WarmUpError("warming up the batch kernel(s) on the terrain failed: boom")

    monkeypatch.setattr(warmup, "warm_up_all", failing)
    assert main(["warm-up"]) == 2
    assert capsys.readouterr().err == (
        "mcrun: error: warming up the batch kernel(s) on the terrain failed: boom\n"
    )


def test_the_general_lanes_kernels_are_compiled_where_a_command_needs_them(tmp_path):
    """The kernels of the general flight lanes (another aerodynamic model, a wind profile) are
    their own, compiled only where a batch holds such a shot, and named among what a command
    compiles (and says) before its work: by its options, or by its scenario's points."""
    from mcrun.cli import build_parser, kernels_of
    from mcrun.engine.batch import general_flight
    from mcrun.run import plan

    assert not general_flight("ferguson2022", "uniform")
    assert not general_flight("trackman2019_lyu", "uniform")  # a Reynolds model, in the lanes
    assert general_flight("lyu2018", "uniform") and general_flight("ferguson2022", "log")
    parser = build_parser("shot")
    shot = ["shot", "--ball-speed", "60", "--launch", "12", "--spin", "300"]
    assert kernels_of(parser.parse_args(shot)) == ("batch",)
    assert kernels_of(parser.parse_args([*shot, "--aero", "lyu2018"])) == ("batch_general",)
    traced = parser.parse_args([*shot, "--wind-profile", "log", "--trajectory", "path.csv"])
    # One shot's path needs the traced kernel alone (the batch's carries no recording).
    assert kernels_of(traced) == ("traced_general",)
    assert not plan.general_flight(scenario.load(ROOT / "scenarios" / "pga-driver.toml"))
    path = tmp_path / "s.toml"
    path.write_text(
        "[launch]\nball_speed = 60\nlaunch_angle = 12\nspin = 300\n\n"
        '[[group]]\nname = "a"\n\n[[group]]\nname = "b"\nmodels.aero = "lyu2018"\n'
    )
    assert plan.general_flight(scenario.load(path))


def test_the_jobs_compile_every_kernel_once_the_terrain_s_batch_apart():
    """Each kernel on each ground is in exactly one job; with two processes for both grounds
    the terrain's batch kernels (the costliest) have a process of their own and its traced
    ones go with the plane's; with one process, or one ground, one job per ground."""
    for grounds, processes in ((warmup.GROUNDS, 1), (warmup.GROUNDS, 2), (("terrain",), 2)):
        planned = warmup.jobs(grounds, warmup.KERNELS, processes)
        pairs = [(g, k) for job in planned for g, ks in job for k in ks]
        assert sorted(pairs) == sorted((g, k) for g in grounds for k in warmup.KERNELS)
    two = warmup.jobs(warmup.GROUNDS, warmup.KERNELS, 2)
    assert two[0] == (("terrain", ("batch", "batch_general", "traced_general")),)
    assert two[1] == (("plane", warmup.KERNELS), ("terrain", ("traced", "landed")))
    assert warmup.jobs(warmup.GROUNDS, ("batch",), 2) == [
        (("plane", ("batch",)),),
        (("terrain", ("batch",)),),
    ]
    # a failure names every kernel of its job, the terrain's that went with the plane's too
    assert warmup._describe(two[1]) == (
        "warming up the batch, traced, landed, batch_general, traced_general kernel(s) on the "
        "plane and the traced, landed kernel(s) on the terrain failed"
    )


# --- the green's kernels (putting.warmup) --------------------------------------------------------


def test_the_green_s_kernels_are_those_the_putting_commands_run(tmp_path, capsys):
    """After the green's warm-up, ``mcrun putt`` on a plane green and the map of a hole's green
    (the library's, not the warm-up's tiny one) compile no other signature of any kernel the
    check asks: the warm-up compiled (or loaded) the very ones the commands run."""
    from mcrun.cli import main
    from mcrun.putting import warmup as green

    done = green.warm_up()
    assert [(k.ground, k.kernel) for k in done] == [("green", "putt"), ("green", "map")]
    assert green.kernel_cached() is True
    kernels = {d: len(d.signatures) for k in green.KERNELS for d in green._dispatchers(k)}
    assert all(count == 1 for count in kernels.values()), kernels
    argv = ["putt", "--distance", "7ft", "--stimp", "10ft", "--slope", "1%", "-n", "20"]
    assert main(argv) == 0 and main([*argv, "--direction", "180"]) == 0
    out = tmp_path / "map.parquet"
    hole = ROOT / "scenarios" / "holes" / "riverside-18-green.toml"
    assert main(["putt", "--hole", str(hole), "-n", "4", "--resolution", "2m", "-o", str(out)]) == 0
    assert {d: len(d.signatures) for d in kernels} == kernels
    capsys.readouterr()


def test_the_green_s_kernels_are_not_cached_in_an_empty_cache(tmp_path):
    check = "from mcrun.putting import warmup; print(warmup.kernel_cached())"
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path)}
    done = subprocess.run([sys.executable, "-c", check], capture_output=True, text=True, env=env)
    assert done.stdout.split() == ["False"]
    assert not any(p.suffix in (".nbi", ".nbc") for p in tmp_path.rglob("*"))


def test_warm_up_all_plans_the_green_in_a_job_of_its_own(monkeypatch):
    """Every ground at once: the engine's jobs as ``engine.warmup.jobs`` plans them, then the
    green's, each job run by the green's job function (which passes the engine's pairs on)."""
    from mcrun.putting import warmup as green

    ran = []

    def run_jobs(job, planned, processes):
        ran.append((job, planned, processes))
        return [[warmup.KernelWarmUp(g, k, 0.0, True) for g, ks in pairs for k in ks]
                for pairs in planned]  # fmt: skip

    monkeypatch.setattr(warmup, "run_jobs", run_jobs)
    report = green.warm_up_all(processes=2)
    job, planned, processes = ran[-1]
    assert job is green.warm_up_job and processes == 2
    assert planned == [*warmup.jobs(warmup.GROUNDS, warmup.KERNELS, 2), (("green", green.KERNELS),)]
    assert [(k.ground, k.kernel) for k in report.kernels] == [
        *((g, k) for g in warmup.GROUNDS for k in warmup.KERNELS),
        ("green", "putt"),
        ("green", "map"),
    ]
    green.warm_up_all(kernels=("batch", "map"), processes=1)
    assert ran[-1][1] == [(("plane", ("batch",)),), (("terrain", ("batch",)),),
                          (("green", ("map",)),)]  # fmt: skip
    green.warm_up_all(("green",))
    assert ran[-1][1] == [(("green", green.KERNELS),)] and ran[-1][2] == 1
    with pytest.raises(ValueError, match="the plane or the terrain has no kernel 'putt'"):
        green.warm_up_all(("plane", "terrain"), ("putt",))
    with pytest.raises(ValueError, match="unknown ground 'fairway'"):
        green.warm_up_all(("fairway",))


def test_a_putt_says_the_green_s_compile_apart(capsys, monkeypatch):
    """A putt whose kernels are not in Numba's cache: the compile is said on stderr, with its
    time, before the putt; a bad input is refused before any compile."""
    from mcrun.cli import main
    from mcrun.putting import warmup as green

    compiled = []
    monkeypatch.setattr(green, "kernel_cached", lambda kernels=green.KERNELS: False)

    def warm_up(kernels):
        compiled.append(kernels)
        return [warmup.KernelWarmUp("green", k, 31.6, False) for k in kernels]

    monkeypatch.setattr(green, "warm_up", warm_up)
    assert main(["putt", "--distance", "1000ft"]) == 2
    assert compiled == [] and capsys.readouterr().err.startswith("mcrun: error: --distance ")
    assert main(["putt", "--distance", "6ft", "-n", "100"]) == 0
    assert compiled == [("putt",)]
    assert capsys.readouterr().err.splitlines() == [
        "mcrun: compiling the green's kernels (first putts after install; cached for the next "
        "runs)",
        "mcrun: compiled the green's kernels in 32 s",
    ]
