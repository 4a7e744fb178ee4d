"""Runs lost or left behind: the output folder checked before a run, a finished run kept when
the final rename fails, names too long, SIGTERM, and the temporary folders of killed runs.

A busy or immutable destination cannot be made without root: ``os.rename`` and ``os.replace``
are patched to fail as they would (EBUSY) for that destination only.
"""

import errno
import math
import os
import shutil
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numba
import numpy as np
import pandas as pd
import pytest

from mcrun import cli, exits
from mcrun.results import output

SCENARIO = """\
[scenario]
name = "lost-runs"
shots = 200
seed = 3

[launch]
ball_speed = { dist = "normal", mean = "70 m/s", sd = "1 m/s" }
launch_angle = "11 deg"
spin = "280 rad/s"
"""

LONG = "x" * 300  # a name over the 255 bytes of ext4, XFS, btrfs, APFS


def write_scenario(folder, name="scenario.toml"):
    path = Path(folder) / name
    path.write_text(SCENARIO, encoding="utf-8")
    return path


def listing(folder):
    return sorted(str(p.relative_to(folder)) for p in Path(folder).rglob("*"))


def mcrun(capsys, *argv):
    code = cli.main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def one_line(err):
    return err.count("\n") == 1 and err.startswith("mcrun: ")


def busy(monkeypatch, place, inside=True):
    """Make a rename of or onto ``place`` (and, with ``inside``, into it) fail with EBUSY, as
    of a mount point or an immutable folder."""
    place = str(place)

    def refuses(dst):
        dst = str(dst)
        return dst == place or (inside and dst.startswith(place + os.sep))

    for name in ("rename", "replace"):
        real = getattr(os, name)

        def fake(src, dst, *args, _real=real, **kwargs):
            if refuses(src) or refuses(dst):
                raise OSError(errno.EBUSY, os.strerror(errno.EBUSY), str(dst))
            return _real(src, dst, *args, **kwargs)

        monkeypatch.setattr(os, name, fake)


# --- before the run ----------------------------------------------------------------------------


def test_a_destination_the_rename_cannot_replace_is_refused_before_the_run(
    tmp_path, capsys, monkeypatch
):
    """An empty mount point, or an immutable folder: one line naming it and why, exit 2,
    nothing written (not even a temporary folder)."""
    scenario = write_scenario(tmp_path)
    mount = tmp_path / "mnt"
    mount.mkdir()
    frozen = tmp_path / "frozen"
    frozen.mkdir()
    real_ismount = os.path.ismount
    monkeypatch.setattr(os.path, "ismount", lambda p: Path(p) == mount or real_ismount(p))
    monkeypatch.setattr(output, "_immutable", lambda p: Path(p) == frozen)
    before = listing(tmp_path)
    for folder, reason in ((mount, "is a mount point"), (frozen, "is immutable")):
        code, out, err = mcrun(capsys, "run", scenario, "-o", folder, "--quiet")
        assert (code, out) == (2, ""), err
        assert one_line(err) and f"the output {folder} {reason}" in err, err
        assert listing(tmp_path) == before


@pytest.mark.parametrize(
    "argv",
    [
        ["run", "{scenario}", "-o", f"{{tmp}}/{LONG}", "--quiet"],
        ["run", "{scenario}", "-o", f"{{tmp}}/{LONG}/run", "--quiet"],
        ["run", f"{{tmp}}/{LONG}.toml"],
        ["validate", f"{{tmp}}/{LONG}.toml"],
        ["run", "{launch_file}", "--quiet", "-o", "{tmp}/run"],
        ["replay", f"{{tmp}}/{LONG}.csv", "-o", "{tmp}/replayed.parquet"],
        ["replay", "{session}", "-o", f"{{tmp}}/{LONG}.parquet"],
        ["plot", f"{{tmp}}/{LONG}"],
        ["plot", "{tmp}/done", "-o", f"{{tmp}}/{LONG}"],
        ["report", "{tmp}/done", "-o", f"{{tmp}}/{LONG}.html"],
    ],
)
def test_a_name_too_long_is_one_line_and_exit_2(tmp_path, capsys, argv, done_run):
    scenario = write_scenario(tmp_path)
    launch_file = tmp_path / "launch-file.toml"
    launch_file.write_text(
        SCENARIO.split("[launch]")[0] + f'[launch]\nfile = "{LONG}.csv"\n', encoding="utf-8"
    )
    shutil.copytree(done_run, tmp_path / "done")
    session = Path(__file__).parent / "data" / "launch_monitor_session.csv"
    names = {"scenario": scenario, "tmp": tmp_path, "launch_file": launch_file}
    argv = [a.format(session=session, **names) for a in argv]
    before = listing(tmp_path)
    code, out, err = mcrun(capsys, *argv)
    assert (code, out) == (2, ""), err
    assert one_line(err) and "is too long (30" in err, err
    assert "..." in err and len(err) < 250, err  # the path, shortened
    assert listing(tmp_path) == before


@pytest.fixture(scope="module")
def done_run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("done")
    scenario = write_scenario(folder)
    assert cli.main(["run", str(scenario), "-o", str(folder / "run"), "--quiet"]) == 0
    return folder / "run"


# --- the final rename --------------------------------------------------------------------------


def test_a_busy_empty_folder_gets_the_run_file_by_file(tmp_path, capsys, monkeypatch):
    """The rename onto an existing empty folder fails: the files are moved into it, the run
    is where it was asked for, exit 0, nothing left beside it."""
    scenario = write_scenario(tmp_path)
    target = tmp_path / "target"
    target.mkdir()
    busy(monkeypatch, target, inside=False)
    code, out, err = mcrun(capsys, "run", scenario, "-o", target, "--quiet")
    assert code == 0, err
    assert sorted(os.listdir(target)) == ["shots.parquet", "summary.parquet"]
    assert len(pd.read_parquet(target / "shots.parquet")) == 200
    assert listing(tmp_path) == sorted(
        ["scenario.toml", "target", "target/shots.parquet", "target/summary.parquet"]
    )


def test_a_finished_run_that_cannot_be_moved_is_kept_beside_it(tmp_path, capsys, monkeypatch):
    """Neither the rename nor a move into the destination works: the complete run is kept as
    NAME.complete-<time>, one line says where, exit 2; with --force the earlier run stays."""
    scenario = write_scenario(tmp_path)
    target = tmp_path / "target"
    busy(monkeypatch, target)
    code, out, err = mcrun(capsys, "run", scenario, "-o", target, "--quiet")
    assert (code, out) == (2, "")
    kept = [p for p in tmp_path.iterdir() if p.name.startswith("target.complete-")]
    assert len(kept) == 1 and not target.exists()
    assert one_line(err) and f"could not be moved to {target}" in err and str(kept[0]) in err
    assert len(pd.read_parquet(kept[0] / "shots.parquet")) == 200
    assert output.read_provenance(kept[0] / "summary.parquet")["n"] == 200
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]

    monkeypatch.undo()
    assert mcrun(capsys, "run", scenario, "-o", target, "--quiet", "-n", "100")[0] == 0
    busy(monkeypatch, target)
    code, _, err = mcrun(capsys, "run", scenario, "-o", target, "--quiet", "--force")
    assert code == 2 and one_line(err)
    assert output.read_provenance(target / "shots.parquet")["n"] == 100  # the earlier run
    assert len([p for p in tmp_path.iterdir() if p.name.startswith("target.complete-")]) == 2
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]


def test_a_run_that_another_finished_beside_is_kept_without_force(tmp_path, capsys, monkeypatch):
    """Two runs to one new folder at once, neither with --force: the second to finish replaced
    the first's run (both said they wrote it). Now the destination is checked again as the
    run is moved into place: the other run stays, this one is kept beside it, one line, 2."""
    scenario = write_scenario(tmp_path)
    target = tmp_path / "target"
    assert mcrun(capsys, "run", scenario, "-o", tmp_path / "other", "-n", "100", "--quiet")[0] == 0
    commit = output.AtomicFolder.commit

    def another_run_first(self):  # the other process's run, moved into place meanwhile
        shutil.copytree(tmp_path / "other", self.path)
        return commit(self)

    monkeypatch.setattr(output.AtomicFolder, "commit", another_run_first)
    code, out, err = mcrun(capsys, "run", scenario, "-o", target, "--quiet")
    assert (code, out) == (2, "") and one_line(err)
    assert "another run was written there meanwhile" in err
    assert output.read_provenance(target / "summary.parquet")["n"] == 100  # the other's
    kept = [p for p in tmp_path.iterdir() if p.name.startswith("target.complete-")]
    assert len(kept) == 1 and str(kept[0]) in err
    assert output.read_provenance(kept[0] / "summary.parquet")["n"] == 200


@pytest.mark.skipif(sys.platform == "win32", reason="no file-size limit on Windows")
def test_a_file_size_limit_reached_mid_run_is_one_line_and_leaves_nothing(tmp_path):
    """A file-size limit (``ulimit -f``; a full disk or quota ends the same way) reached as
    the shots are written: a traceback and exit 1 before; one line, exit 2, and nothing left,
    an earlier run kept."""
    import resource

    out = tmp_path / "run"
    command = [sys.executable, "-c", "from mcrun.cli import main; raise SystemExit(main())",
               "run", "pga-driver", "-o", str(out), "--quiet"]  # fmt: skip
    env = {**os.environ, "NUMBA_NUM_THREADS": "1"}
    earlier = subprocess.run([*command, "-n", "100"], env=env, capture_output=True, timeout=300)
    assert earlier.returncode == 0, earlier.stderr
    argv = [*command, "-n", "50000"]
    limit = 1 << 20  # 1 MiB: 50,000 shots write some 9 MB

    def limited():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    done = subprocess.run([*argv, "--force"], env=env, capture_output=True, text=True,
                          timeout=300, preexec_fn=limited)  # fmt: skip
    assert done.returncode == 2 and done.stderr.count("\n") == 1, done.stderr
    assert done.stderr.startswith("mcrun: error: ") and "File too large" in done.stderr
    assert output.read_provenance(out / "summary.parquet")["n"] == 100  # the earlier run
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run"]


def test_a_replayed_file_that_cannot_be_moved_is_kept_beside_it(tmp_path, capsys, monkeypatch):
    session = Path(__file__).parent / "data" / "launch_monitor_session.csv"
    target = tmp_path / "replayed.parquet"
    busy(monkeypatch, target)
    code, out, err = mcrun(capsys, "replay", session, "-o", target)
    assert (code, out) == (2, "")
    (kept,) = [p for p in tmp_path.iterdir() if p.name.startswith("replayed.complete-")]
    assert kept.suffix == ".parquet" and str(kept) in err and one_line(err)
    assert len(pd.read_parquet(kept)) == len(pd.read_csv(session, comment="#"))


# --- what killed runs leave --------------------------------------------------------------------


def dead_pid():
    """The id of a process that has ended."""
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    return child.pid


def test_stale_temporary_folders_of_dead_processes_are_removed(tmp_path, capsys):
    """At the next run into the folder: the temporary folder and file of a process that is gone
    are removed; those of a live process, of another host, and anything not of the pattern
    are kept."""
    scenario = write_scenario(tmp_path)
    runs = tmp_path / "runs"
    runs.mkdir()
    host = output._HOST
    dead = dead_pid()
    stale = [
        runs / f".other.partial-{host}-{dead}-0123abcd",  # another run, same folder
        runs / f".run.partial-{host}-{dead}-89abcdef",
    ]
    kept = [
        runs / f".run.partial-{host}-{os.getpid()}-0123abcd",  # alive
        runs / f".run.partial-another-host-{dead}-0123abcd",  # not ours to judge
        runs / ".run.partial-0123abcd",  # no process id
        runs / f"run.partial-{host}-{dead}-0123abcd",  # not hidden: not ours
        runs / f".run.old-{host}-{dead}-0123abcd",  # the earlier run's only copy
    ]
    for folder in stale + kept:
        folder.mkdir()
        (folder / "shots.parquet").write_bytes(b"partial")
    stale_file = runs / f".replayed.parquet.partial-{host}-{dead}-0123abcd"
    stale_file.write_bytes(b"partial")
    code, _, err = mcrun(capsys, "run", scenario, "-o", runs / "run", "--quiet")
    assert code == 0, err
    assert sorted(p.name for p in runs.iterdir()) == sorted(["run", *(p.name for p in kept)])
    # Once the run it replaced is in place, a left-over .old copy goes too.
    assert output.remove_stale(runs) == [runs / f".run.old-{host}-{dead}-0123abcd"]


def test_sigterm_stops_a_run_as_ctrl_c_does(tmp_path):
    """SIGTERM in the middle of a run (the installed console script): exit 143, one line on
    stderr, no folder and no temporary folder left."""
    scenario = write_scenario(tmp_path)
    script = shutil.which("mcrun") or str(Path(sys.executable).parent / "mcrun")
    process = subprocess.Popen(
        [script, "run", str(scenario), "-n", "1e8", "-o", str(tmp_path / "run"), "--quiet"],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    deadline = time.monotonic() + 120
    while not list(tmp_path.glob(".run.partial-*/shots.parquet")):
        assert process.poll() is None and time.monotonic() < deadline, process.communicate()
        time.sleep(0.05)
    process.send_signal(signal.SIGTERM)
    out, err = process.communicate(timeout=60)
    assert process.returncode == exits.EXIT_TERMINATED == 143, err
    assert out == "" and one_line(err) and "interrupted" in err, err
    assert listing(tmp_path) == ["scenario.toml"]


@pytest.mark.skipif(not hasattr(signal, "SIGHUP"), reason="no SIGHUP on Windows")
def test_sighup_stops_a_run_as_sigterm_does(tmp_path, capsys):
    """SIGHUP (the terminal closed, an ssh connection lost) in the middle of a run: exit 129,
    one line on stderr, no folder and no temporary folder left (it ended the run with no word,
    its temporary folder left for a later run to remove)."""
    scenario = write_scenario(tmp_path)

    def hang_up():
        deadline = time.monotonic() + 120
        while not list(tmp_path.glob(".run.partial-*/shots.parquet")):
            if time.monotonic() > deadline:
                return
            time.sleep(0.05)
        os.kill(os.getpid(), signal.SIGHUP)

    threading.Thread(target=hang_up, daemon=True).start()
    code, out, err = mcrun(capsys, "run", scenario, "-n", "1e8", "-o", tmp_path / "run",
                           "--quiet")  # fmt: skip
    assert code == exits.exit_code(signal.SIGHUP) == 129, err
    assert out == "" and one_line(err) and "interrupted" in err, err
    assert listing(tmp_path) == ["scenario.toml"]


@pytest.mark.skipif(not hasattr(signal, "SIGHUP"), reason="no SIGHUP on Windows")
def test_a_run_started_with_nohup_goes_on_when_the_terminal_closes():
    """A process started to ignore SIGHUP (``nohup mcrun run ...``) still ignores it."""
    previous = signal.signal(signal.SIGHUP, signal.SIG_IGN)
    try:
        with exits.sigterm_interrupts() as received:
            os.kill(os.getpid(), signal.SIGHUP)
            time.sleep(0.05)  # (a signal is handled between two bytecodes: there were many)
        assert received == []
        assert signal.getsignal(signal.SIGHUP) is signal.SIG_IGN
    finally:
        signal.signal(signal.SIGHUP, previous)


# SIGTERM arrives while the main thread waits in ``Thread.start`` for a kernel thread of the
# pool: the new thread sends it before it starts, and starts 0.5 s later.
STARTING_THREAD_SIGTERM = """\
import os, signal, threading, time
from mcrun import exits
from mcrun import executor

bootstrap = threading.Thread._bootstrap_inner
sent = []
def late_bootstrap(self):
    if not sent:
        sent.append(True)
        os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(0.5)
    bootstrap(self)
threading.Thread._bootstrap_inner = late_bootstrap
try:
    with exits.sigterm_interrupts():
        executor.on_threads(lambda k: time.sleep(0.01), 4, threads=2)
except exits.Terminated:
    print("terminated", flush=True)
time.sleep(1)  # every thread has started by now: the interpreter would wait for one left out
"""


def test_ctrl_c_while_a_command_s_modules_import_is_one_line(monkeypatch, capsys):
    """A command's modules take seconds to import (NumPy, Numba, pandas): Ctrl-C then was a
    traceback through the imports; now ``mcrun: interrupted`` and exit code 130."""

    def interrupted(*args):
        raise KeyboardInterrupt

    monkeypatch.setattr(cli, "build_parser", interrupted)
    assert cli.main(["run", "pga-driver"]) == exits.EXIT_INTERRUPTED
    assert capsys.readouterr().err == "mcrun: interrupted\n"


@pytest.mark.skipif(sys.platform == "win32", reason="no SIGTERM handler on Windows")
def test_sigterm_while_a_kernel_thread_starts_leaves_no_thread_behind():
    """A signal that lands while the kernels' pool starts a thread: the command stops, and the
    process exits (a thread left out of the pool's list would make the interpreter wait for it
    forever at exit)."""
    process = subprocess.run(
        [sys.executable, "-c", STARTING_THREAD_SIGTERM],
        capture_output=True,
        text=True,
        timeout=30,
    )
    assert (process.returncode, process.stdout) == (0, "terminated\n"), process.stderr


def test_sigterm_stops_a_dask_run_and_its_cluster(tmp_path):
    """The same on a local Dask cluster (SIGTERM to the whole process group, as Slurm sends
    it): exit 143, one line, no folder, no warning of leaked resources."""
    pytest.importorskip("dask.distributed")
    scenario = write_scenario(tmp_path)
    script = shutil.which("mcrun") or str(Path(sys.executable).parent / "mcrun")
    argv = [script, "run", str(scenario), "-n", "1e8", "-o", str(tmp_path / "run"), "--quiet"]
    process = subprocess.Popen(
        [*argv, "--dask", "local", "--workers", "1"],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    deadline = time.monotonic() + 120
    while not list(tmp_path.glob(".run.partial-*/shots/part-*.parquet")):
        assert process.poll() is None and time.monotonic() < deadline, process.communicate()
        time.sleep(0.05)
    os.killpg(process.pid, signal.SIGTERM)
    out, err = process.communicate(timeout=60)
    assert process.returncode == 143, err
    assert out == "" and one_line(err) and "interrupted" in err, err
    assert listing(tmp_path) == ["scenario.toml"]


@pytest.mark.parametrize("interrupt", [signal.SIGTERM, signal.SIGINT])
def test_an_interrupt_dropped_in_a_garbage_collector_s_callback_comes_again(
    interrupt, ctrl_c_raises, capsys
):
    """An interrupt whose exception Python drops (raised within a garbage collector's callback,
    as Dask's client registers one: "Exception ignored in ... GCDiagnosis._gc_callback", the
    command ran on and a Dask run did not stop) comes again, ``REDELIVER_S`` later, in the
    code that runs; nothing is printed."""
    import gc

    expected = exits.Terminated if interrupt == signal.SIGTERM else KeyboardInterrupt
    raised_inside = []

    def callback(phase, info):
        if phase == "start" and not raised_inside:
            try:
                signal.raise_signal(interrupt)  # its handler runs here, within the callback
            except BaseException as err:
                raised_inside.append(type(err))
                raise  # and the collector drops it

    with exits.sigterm_interrupts() as received, pytest.raises(expected) as caught:
        gc.callbacks.append(callback)
        try:
            gc.collect()
            time.sleep(1.0)  # (it comes again within REDELIVER_S, 0.02 s: here or in collect)
        finally:
            gc.callbacks.remove(callback)
    assert raised_inside == [expected] and caught.type is expected
    # (each SIGTERM handled is received: the dropped one, and the one that stopped the block;
    # one may be dropped again if it too comes within a collection)
    if interrupt == signal.SIGTERM:
        assert len(received) >= 2 and set(received) == {signal.SIGTERM}
    else:
        assert received == []
    assert "Exception ignored" not in capsys.readouterr().err


@numba.njit(cache=True, nogil=True)
def _spin(stop):
    """Compiled work that runs until ``stop[0]`` is set (as a long kernel runs), or for 10-20 s
    of 2026's CPUs."""
    x, k = 0.0, 0
    while stop[0] == 0.0 and k < 1_000_000_000:
        x = math.sin(x) + 1.0
        k += 1
    return x, k


def test_sigterm_stops_a_long_kernel_call_at_once():
    """``exits.interruptible``: a call into compiled code that would hold the main thread (and
    SIGTERM's handler with it) for as long as it runs is waited for on a thread of its own, so
    that SIGTERM stops the command at once; the call is left to finish."""
    stop = np.zeros(1)
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGTERM))
    started = time.monotonic()
    try:
        with exits.sigterm_interrupts() as received, pytest.raises(exits.Terminated):
            timer.start()
            exits.interruptible(_spin, stop)
        waited = time.monotonic() - started
    finally:
        stop[0] = 1.0  # the call ends
    assert received == [signal.SIGTERM] and waited < 2.0
    assert exits.interruptible(_spin, np.ones(1)) == (0.0, 0)  # and returns what the call does


def test_an_interrupt_waits_for_a_step_that_cannot_be_undone():
    """Within ``interrupts_deferred`` SIGTERM waits; it stops the command as the step ends."""
    with exits.sigterm_interrupts() as received, pytest.raises(exits.Terminated):
        with exits.interrupts_deferred():
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(0.05)  # a signal is handled between two bytecodes: there were many
            finished = True
    assert finished and received == [signal.SIGTERM]
