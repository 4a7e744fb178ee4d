"""The Dask backend (mcrun.run.distributed) against the local engine (mcrun.run.local): the same
shots and the same summary, bit for bit, for the same seed and chunk size, with and without groups;
a worker killed mid-run loses and duplicates no shot; the dataset reads back in pandas, polars and
DuckDB with the local engine's rows; chunks that keep failing are reported in one line and leave
nothing that looks like a run; the command line's --scheduler path and its errors.

One LocalCluster of 2 worker processes x 1 thread serves the whole module (CI has 2 cores).
Runs are small (a few thousand shots) in chunks of 1,000-5,000 shots, so that every run has
several tasks; the grouped scenario uses a sampler block of 256 so that chunks cross blocks.
"""

import functools
import json
import os
import signal
import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq
import pytest

pytest.importorskip("dask.distributed")

import cloudpickle  # noqa: E402 (a dependency of dask.distributed)
from dask.distributed import Client  # noqa: E402

from mcrun.cli import main  # noqa: E402
from mcrun.quantities import InputError  # noqa: E402
from mcrun.results import output  # noqa: E402
from mcrun.run import distributed  # noqa: E402
from mcrun.run import local as run  # noqa: E402

# The wrapped tasks below are defined here and run on the workers, which cannot import this
# file: ship them by value.
cloudpickle.register_pickle_by_value(sys.modules[__name__])

DRIVER = "pga-driver"
N = 20_000
CHUNK = 5_000

# Two groups times a sweep over the friction (four points), a temperature distribution and a
# negative-spin group (some shots end invalid_input).
BAG = """\
# Question: do two clubs on two fairways scatter alike?
[scenario]
name = "dask-bag"
shots = 3000
seed = 11
block_size = 256
target = ["150 m", "0 m"]

[launch]
ball_speed = { dist = "normal", mean = "120 mph", sd = "1.5 mph" }
launch_angle = { dist = "normal", mean = "16 deg", sd = "1 deg" }
spin = { dist = "normal", mean = "7000 rpm", sd = "400 rpm" }
spin_axis = { dist = "normal", mean = "0 deg", sd = "3 deg" }

[turf]
preset = "fairway"

[weather]
temperature = { dist = "normal", mean = "20 C", sd = "4 C" }

[[group]]
name = "7 iron"

[[group]]
name = "wild"
launch.spin = { dist = "normal", mean = "100 rad/s", sd = "100 rad/s" }

[sweep]
"turf.mu" = [0.4, 0.25]
"""
BAG_N = 3000
BAG_CHUNK = 1000
BAG_TRAJECTORIES = 397


@pytest.fixture(scope="module")
def client():
    cluster = distributed.local_cluster(2)
    with Client(cluster) as c:
        yield c
    cluster.close()


@pytest.fixture(scope="module")
def driver(tmp_path_factory, client):
    """The pga-driver scenario run by both engines: (local result, Dask result)."""
    folder = tmp_path_factory.mktemp("driver")
    local = run.run_scenario(
        DRIVER, n=N, chunk_size=CHUNK, out_dir=folder / "local", progress=False
    )
    dask = distributed.run_scenario(
        DRIVER, n=N, chunk_size=CHUNK, out_dir=folder / "dask", client=client, progress=False
    )
    return local, dask


@pytest.fixture(scope="module")
def bag(tmp_path_factory, client):
    """The grouped scenario with trajectories, by both engines: (local result, Dask result)."""
    folder = tmp_path_factory.mktemp("bag")
    path = folder / "bag.toml"
    path.write_text(BAG, encoding="utf-8")
    kwargs = {
        "n": BAG_N,
        "chunk_size": BAG_CHUNK,
        "trajectories_every": BAG_TRAJECTORIES,
        "progress": False,
    }
    local = run.run_scenario(path, out_dir=folder / "local", **kwargs)
    dask = distributed.run_scenario(path, out_dir=folder / "dask", client=client, **kwargs)
    return local, dask


@pytest.fixture(scope="module")
def small(tmp_path_factory):
    """A small local pga-driver run (4 chunks) to compare the other Dask runs with."""
    folder = tmp_path_factory.mktemp("small")
    result = run.run_scenario(
        DRIVER, n=6000, chunk_size=1500, out_dir=folder / "local", progress=False
    )
    return result.shots(), result.summary()


def assert_same_run(local, dask):
    pd.testing.assert_frame_equal(local.shots(), dask.shots(), check_exact=True)
    pd.testing.assert_frame_equal(local.summary(), dask.summary(), check_exact=True)


# --- the same run, bit for bit -----------------------------------------------------------------


def test_same_shots_and_summary_as_the_local_engine(driver, client):
    """pga-driver, 20,000 shots in 4 tasks: every per-shot value and every summary statistic
    (moments merged in chunk order, percentiles from the dataset) equal the local engine's."""
    local, dask = driver
    assert_same_run(local, dask)
    shots = dask.shots()
    assert len(shots) == N and shots["shot"].is_unique
    parts = sorted(p.name for p in Path(dask.shots_path).iterdir())
    assert parts == [f"part-{c:05d}.parquet" for c in range(N // CHUNK)]
    assert all(pq.ParquetFile(Path(dask.shots_path) / p).num_row_groups == 1 for p in parts)
    # Provenance: backend and cluster size in every file; the summary's agrees with the local
    # engine's on everything but how and when it ran.
    summary = output.read_provenance(dask.summary_path)
    part = output.read_provenance(Path(dask.shots_path) / parts[0])
    assert summary["backend"] == part["backend"] == "dask"
    assert summary["scheduler"] == client.scheduler.address
    assert summary["workers"] == 2 and summary["threads"] == 2
    assert summary["threads_per_worker"] == [1] and summary["numba_threads_per_task"] == 1
    assert summary["chunks"] == N // CHUNK
    assert summary["scenario_text"] == output.read_provenance(local.summary_path)["scenario_text"]
    note = json.loads((Path(dask.out_dir) / distributed.SUCCESS_FILE).read_text())
    assert note["n"] == N and note["chunks"] == N // CHUNK


def test_percentiles_by_histogram_select_over_the_parts(small, client, tmp_path):
    """With a memory budget of 1,000 values per column the percentiles come from
    histogram-then-select passes over the parts: still the exact order statistics, so the
    summary equals the local engine's (which sorted each column whole)."""
    result = distributed.run_scenario(
        DRIVER,
        n=6000,
        chunk_size=1500,
        out_dir=tmp_path / "run",
        client=client,
        progress=False,
        budget_bytes=8 * 1000,
    )
    pd.testing.assert_frame_equal(small[1], result.summary(), check_exact=True)


def test_workers_run_one_numba_thread(client):
    """The local cluster's workers are spawned with NUMBA_NUM_THREADS=1 (one Dask thread)."""
    threads = client.run(lambda: __import__("numba").config.NUMBA_NUM_THREADS)
    nthreads = client.nthreads()
    assert threads and set(threads.values()) == {1} and set(nthreads.values()) == {1}


@pytest.mark.determinism
def test_groups_partition_the_dataset_and_match_the_local_engine(bag):
    """Two groups x two sweep values: shots/group=<name>/part-NNNNN.parquet (the name
    percent-encoded, no group column in the files); shots, summary and trajectories equal the
    local engine's bit for bit."""
    local, dask = bag
    assert_same_run(local, dask)
    pd.testing.assert_frame_equal(local.trajectories(), dask.trajectories(), check_exact=True)
    shots = Path(dask.shots_path)
    assert sorted(p.name for p in shots.iterdir()) == ["group=7%20iron", "group=wild"]
    parts = sorted(shots.glob("*/*.parquet"))
    assert len(parts) == 4 * BAG_N // BAG_CHUNK
    assert "group" not in pq.read_schema(parts[0]).names
    assert (dask.summary()["n_invalid_input"] > 0).any()  # the wild group's negative spins


def _local_order(frame, columns):
    """A frame's ``columns`` in the local file's row order, categoricals as text."""
    frame = frame.sort_values(["point", "shot"]).reset_index(drop=True)[columns]
    for name in ("group", "label", "status_name"):
        frame[name] = frame[name].astype(str)
    return frame


def test_dataset_reads_back_in_pandas_polars_and_duckdb(bag):
    """pd.read_parquet(folder), pl.scan_parquet(folder/**/*.parquet, hive_partitioning=True)
    and DuckDB's read_parquet(..., hive_partitioning = true) read the hive-partitioned dataset
    with the local shots.parquet's rows and values (group back from the folder names); each
    summary's point, group and label join its shots' with no cast."""
    pl = pytest.importorskip("polars")
    duckdb = pytest.importorskip("duckdb")
    local, dask = bag
    expected = pd.read_parquet(local.shots_path)
    columns = list(expected.columns)
    expected = _local_order(expected, columns)
    folder = Path(dask.shots_path)
    shots = {
        "local": pl.scan_parquet(local.shots_path),
        "dask": pl.scan_parquet(folder / "**" / "*.parquet", hive_partitioning=True),
    }
    readers = {
        "pandas": pd.read_parquet(folder),
        "polars": pl.scan_parquet(folder / "**" / "*.parquet", hive_partitioning=True)
        .collect()
        .to_pandas(),
        "duckdb": duckdb.sql(
            f"SELECT * FROM read_parquet('{folder}/**/*.parquet', hive_partitioning = true)"
        ).df(),
    }
    for name, frame in readers.items():
        assert sorted(frame.columns) == sorted(columns), name
        got = _local_order(frame, columns)
        assert len(got) == len(expected) == 4 * BAG_N, name
        for column in columns:
            a, b = expected[column], got[column]
            if a.dtype.kind == "f":
                np.testing.assert_array_equal(a.to_numpy(), b.to_numpy(float), err_msg=name)
            else:
                assert a.astype(str).tolist() == b.astype(str).tolist(), (name, column)
    # the summary's point, group and label are of the shots' types: a join on them needs no
    # cast (polars refused to join its categorical with text, and before 2 int64 with int32)
    for name, result in (("local", local), ("dask", dask)):
        summary = pq.read_schema(result.summary_path)
        assert summary.field("point").type == pa.int32(), name
        text = pa.dictionary(pa.int32(), pa.string())
        assert summary.field("group").type == summary.field("label").type == text, name
        # (a Dask dataset's group is read from its folders' names: text)
        keys = ["point", "group", "label"] if name == "local" else ["point", "label"]
        joined = shots[name].join(pl.read_parquet(result.summary_path).lazy(), on=keys)
        assert len(joined.collect()) == 4 * BAG_N, name


# --- failures ----------------------------------------------------------------------------------


def _kill_worker_once(chunk, point, start, stop, job, *, marker):
    """Run chunk 1, then, the first time, leave a half-written temporary part behind and kill
    this worker process before it returns: its part is written but not reported."""
    result = distributed.run_chunk(chunk, point, start, stop, job)
    if chunk == 1 and not os.path.exists(marker):
        Path(marker).write_text(str(os.getpid()))
        stray = Path(result.shots_path).with_name(".part-00001.parquet.dead.tmp")
        stray.write_bytes(b"PAR1 half written")
        os.kill(os.getpid(), signal.SIGKILL)
    return result


def test_worker_killed_mid_run_loses_and_duplicates_no_shot(small, client, tmp_path):
    """A worker dies after writing chunk 1's part and before reporting it: Dask reruns the task
    on another worker, which rewrites the same part; every shot is there exactly once, with
    the local engine's values, and the dead task's temporary file is gone."""
    marker = tmp_path / "killed"
    task = functools.partial(_kill_worker_once, marker=str(marker))
    result = distributed.run_scenario(
        DRIVER,
        n=6000,
        chunk_size=1500,
        out_dir=tmp_path / "run",
        client=client,
        progress=False,
        chunk_task=task,
    )
    assert marker.exists()  # a worker was killed
    shots = result.shots()
    assert shots["shot"].nunique() == len(shots) == 6000
    pd.testing.assert_frame_equal(small[0], shots, check_exact=True)
    pd.testing.assert_frame_equal(small[1], result.summary(), check_exact=True)
    files = sorted(p.name for p in Path(result.shots_path).iterdir())
    assert files == [f"part-{c:05d}.parquet" for c in range(4)]
    client.wait_for_workers(2, timeout=60)  # the nanny restarts the killed worker


def _fail_chunk_2(chunk, point, start, stop, job, *, attempts):
    if chunk == 2:
        Path(attempts, f"{os.getpid()}-{len(os.listdir(attempts))}").touch()
        raise RuntimeError("simulated failure")
    return distributed.run_chunk(chunk, point, start, stop, job)


def test_chunks_that_keep_failing_are_reported_and_nothing_is_left(client, tmp_path):
    """Chunk 2 raises every time: it is tried 1 + 2 retries times, then the run raises
    RunFailed naming it in one line, and neither the folder nor a temporary one is left."""
    attempts = tmp_path / "attempts"
    attempts.mkdir()
    out = tmp_path / "out"
    task = functools.partial(_fail_chunk_2, attempts=str(attempts))
    with pytest.raises(distributed.RunFailed) as info:
        distributed.run_scenario(
            DRIVER,
            n=6000,
            chunk_size=1500,
            out_dir=out / "run",
            client=client,
            progress=False,
            chunk_task=task,
        )
    message = str(info.value)
    assert "\n" not in message
    assert "1 of 4 chunks failed after 2 retries (chunks 2)" in message
    assert "point 0, shots 3000-4499" in message and "RuntimeError: simulated failure" in message
    assert [f[0] for f in info.value.failed] == [2]
    assert len(list(attempts.iterdir())) == 3
    assert not out.exists()


def test_an_fsspec_url_is_written_in_place_with_a_success_marker(small, client, tmp_path,
                                                                  monkeypatch):  # fmt: skip
    """-o file:///...: through fsspec (as s3:// would be), the same shots and summary, the
    _SUCCESS marker written; an existing run is refused without force, replaced with it, and
    kept where the run to replace it cannot start (it was deleted before the cluster was
    reached)."""
    url = f"file://{tmp_path}/run"
    kwargs = {"n": 6000, "chunk_size": 1500, "client": client, "progress": False}
    result = distributed.run_scenario(DRIVER, out_dir=url, **kwargs)
    assert result.out_dir == url and result.shots_path == f"{url}/shots"
    pd.testing.assert_frame_equal(small[0], result.shots(), check_exact=True)
    pd.testing.assert_frame_equal(small[1], result.summary(), check_exact=True)
    assert (tmp_path / "run" / distributed.SUCCESS_FILE).is_file()
    with pytest.raises(output.OutputError, match="already holds a run"):
        distributed.run_scenario(DRIVER, out_dir=url, **kwargs)
    monkeypatch.setattr(distributed, "CONNECT_TIMEOUT_S", 1)
    unreachable = {**kwargs, "client": None, "scheduler": "tcp://127.0.0.1:9"}
    with pytest.raises(InputError, match="cannot reach the Dask scheduler"):
        distributed.run_scenario(DRIVER, out_dir=url, force=True, **unreachable)
    assert (tmp_path / "run" / distributed.SUCCESS_FILE).is_file()
    pd.testing.assert_frame_equal(small[0], result.shots(), check_exact=True)
    again = distributed.run_scenario(DRIVER, out_dir=url, force=True, seed=5, **kwargs)
    assert again.shots()["ball_speed_mps"].iloc[0] != small[0]["ball_speed_mps"].iloc[0]


def test_an_incomplete_run_does_not_read_as_one(driver, tmp_path):
    _, dask = driver
    copy = tmp_path / "copy"
    (copy / "shots").mkdir(parents=True)
    for part in Path(dask.shots_path).iterdir():
        (copy / "shots" / part.name).write_bytes(part.read_bytes())
    (copy / "summary.parquet").write_bytes(Path(dask.summary_path).read_bytes())
    with pytest.raises(output.OutputError, match="not a complete Dask run"):
        distributed.read_shots(copy)


# --- command line ------------------------------------------------------------------------------


def test_cli_runs_on_a_scheduler(small, client, tmp_path, capsys):
    """mcrun run ... --scheduler ADDRESS: the summary table, the rate on the Dask workers and
    the paths; the shots equal the local engine's."""
    out = tmp_path / "run"
    argv = ["run", DRIVER, "-n", "6000", "--chunk-size", "1500", "-o", str(out), "--quiet"]
    assert main([*argv, "--scheduler", client.scheduler.address]) == 0
    printed = capsys.readouterr().out
    assert "shots/s on 2 Dask workers, 2 threads); wrote:" in printed
    assert str(out / "shots") in printed and str(out / "summary.parquet") in printed
    pd.testing.assert_frame_equal(small[0], distributed.read_shots(out), check_exact=True)


def test_cli_ctrl_c_leaves_nothing(client, tmp_path, capsys, monkeypatch):
    """Ctrl-C once the tasks are done (while the run checks its parts): exit 130, the
    temporary folder removed."""

    def interrupt(*args):
        raise KeyboardInterrupt

    monkeypatch.setattr(distributed, "_remove_strays", interrupt)
    argv = ["run", DRIVER, "-n", "3000", "--chunk-size", "1500", "-o", str(tmp_path / "run")]
    assert main([*argv, "--scheduler", client.scheduler.address]) == 130
    assert "interrupted" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def _sigint_blocked():
    return signal.SIGINT in signal.pthread_sigmask(signal.SIG_BLOCK, [])


def test_a_local_cluster_s_workers_leave_ctrl_c_to_the_run(client):
    """Ctrl-C reaches every process of the terminal's group: a worker still importing printed
    its traceback. The workers of ``local_cluster`` start with SIGINT blocked (this process
    stops them), and this process's own Ctrl-C is held only while they start."""
    blocked = client.run(_sigint_blocked)
    assert len(blocked) == 2 and all(blocked.values())
    assert not _sigint_blocked()


def test_a_local_cluster_says_nothing_when_another_holds_the_dashboard_port(tmp_path, capfd):
    """--dask local while another cluster (here a bare socket) holds the scheduler's default
    HTTP port, 8787: the run's output is its own, with no warning of the port on stderr, as
    happened when two clusters ran at once."""
    import socket
    import warnings

    holder = socket.socket()
    try:
        holder.bind(("127.0.0.1", 8787))
        holder.listen()
    except OSError:
        holder.close()
        pytest.skip("port 8787 is taken by something that cannot be told apart")
    try:
        out = tmp_path / "run"
        argv = ["run", DRIVER, "-n", "500", "-o", str(out), "--quiet"]
        with warnings.catch_warnings():  # (the command shows each warning on stderr, one line)
            warnings.simplefilter("always")
            assert main([*argv, "--dask", "local", "--workers", "1"]) == 0
    finally:
        holder.close()
    assert "8787" not in capfd.readouterr().err


def test_without_dask_the_backend_says_how_to_install_it(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "dask.distributed", None)  # import fails as if missing
    out = tmp_path / "run"
    assert main(["run", DRIVER, "-n", "100", "-o", str(out), "--dask", "local"]) == 2
    assert "pip install 'mcrun[dask]'" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    ("options", "message"),
    [
        (["--dask", "local", "--threads", "2"], "--threads is for the local engine"),
        (["--workers", "2"], "--workers is for --dask local"),
        # (read as every whole number is: float() read "١" as 1 and "0_1" as 1)
        (["--dask", "local", "--workers", "١"], "--workers '١': only ASCII digits (0-9) are"),
        (["--dask", "local", "--workers", "0_1"], "--workers '0_1': '_' is not read in a number"),
        (["--scheduler-file", "missing.json"], "--scheduler-file missing.json: no such file"),
        (["--scheduler", "tcp://127.0.0.1:9"], "cannot reach the Dask scheduler tcp://"),
        # (it started a local cluster, and --workers was refused as for an existing one)
        (["--scheduler", "local"], "--scheduler local: a local cluster is --dask local"),
        # (tried for the connection's 30 s)
        (["--scheduler", "tcp://127.0.0.1:99999"], "its port is not one: allowed: 1 to 65535"),
    ],
)
def test_cli_errors_exit_2_with_one_line_and_write_nothing(
    options, message, tmp_path, capsys, monkeypatch
):
    monkeypatch.setattr(distributed, "CONNECT_TIMEOUT_S", 1)
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "run"
    assert main(["run", DRIVER, "-n", "100", "-o", str(out), *options]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mcrun: error: ") and err.count("\n") == 1 and message in err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    ("text", "says"),
    [("garbage", "not a Dask scheduler file (JSON with an \"address\""),
     ("", "not a Dask scheduler file"), ("{}", "not a Dask scheduler file"),
     ("[1, 2]", "not a Dask scheduler file")],
)  # fmt: skip
def test_a_scheduler_file_without_an_address_is_one_line(tmp_path, capsys, text, says):
    """Dask's own reading of such a file was an AssertionError (or a TypeError), a traceback."""
    (tmp_path / "in").mkdir()
    (tmp_path / "in" / "scheduler.json").write_text(text)
    out = tmp_path / "run"
    argv = ["run", DRIVER, "-n", "100", "-o", str(out), "--scheduler-file"]
    assert main([*argv, str(tmp_path / "in" / "scheduler.json")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mcrun: error: --scheduler-file ") and says in err
    assert main([*argv, str(tmp_path / "in")]) == 2
    assert capsys.readouterr().err.endswith(f"--scheduler-file {tmp_path / 'in'}: a folder\n")
    assert not out.exists()


def test_the_api_holds_a_local_cluster_s_workers_as_the_command_line_does(tmp_path):
    """workers=1000 started worker processes one by one (69 after 40 s), without a word;
    workers beside an existing cluster's address were ignored; a scheduler given as a number
    was Dask's TypeError."""
    out = tmp_path / "run"
    with pytest.raises(InputError, match=r"^workers 1000: allowed: a whole number of worker "
                       r"processes from 1 to \d+ \(4 a core"):  # fmt: skip
        distributed.run_scenario(DRIVER, n=50, progress=False, out_dir=out, workers=1000)
    with pytest.raises(InputError, match=r"^workers 0: allowed"):
        distributed.local_cluster(0)
    with pytest.raises(InputError, match=r"^workers: is for a local cluster"):
        distributed.run_scenario(DRIVER, n=50, progress=False, out_dir=out, workers=2,
                                 scheduler="tcp://127.0.0.1:9")  # fmt: skip
    with pytest.raises(InputError, match=r"^scheduler 8799: allowed: an address such as"):
        distributed.run_scenario(DRIVER, n=50, progress=False, out_dir=out, scheduler=8799)
    assert not out.exists()


def test_shots_from_many_starts_on_dask_are_the_local_ones_bit_for_bit(client):
    """``run.starts.play_from`` with its chunks of starts as Dask tasks: every per-start number
    and every shot's outcome as the local batch gives them, bit for bit."""
    from mcrun.run import scenario as sc
    from mcrun.run import starts

    scenario = sc.load(sc.library_folder() / "par3-over-water.toml")
    points = starts.starts_grid(scenario.hole, 8.0, within_m=(120.0, 170.0))[:12]
    here = starts.play_from(scenario, points, n=30, keep_shots=True, chunk_starts=5)
    there = starts.play_from(scenario, points, n=30, keep_shots=True, chunk_starts=5,
                             client=client)  # fmt: skip
    assert np.array_equal(here.outcomes, there.outcomes, equal_nan=True)
    a, b = here.frame(), there.frame()
    assert a.columns.tolist() == b.columns.tolist()
    for column in a.columns:
        assert np.array_equal(a[column].to_numpy(), b[column].to_numpy(), equal_nan=column != "lie")


# --- the kernels on the workers ----------------------------------------------------------------


class _FakeClient:
    """A cluster of three workers, the first two without the kernels in their cache."""

    def __init__(self, fail=False):
        self.fail = fail
        self.calls = []

    def run(self, function, *args):
        self.calls.append((function.__name__, args))
        if function is distributed._worker_kernels_cached:
            return {"tcp://b:2": False, "tcp://a:1": None, "tcp://c:3": True}
        if self.fail:
            raise RuntimeError("no space left\non device")
        return {"tcp://a:1": 61.2, "tcp://b:2": 58.7, "tcp://c:3": 0.8}


def test_workers_that_lack_the_kernels_compile_them_at_the_start_and_say_so():
    said = []
    seconds = distributed.warm_workers(_FakeClient(), "terrain", ("batch",), said.append)
    assert seconds == {"tcp://a:1": 61.2, "tcp://b:2": 58.7, "tcp://c:3": 0.8}
    assert said == [
        "mcrun: compiling the kernels on 2 of 3 Dask workers (their cache lacks them; cached "
        "for the next runs)",
        "mcrun: Dask worker tcp://a:1 compiled the kernels in 61 s",
        "mcrun: Dask worker tcp://b:2 compiled the kernels in 59 s",
    ]


def test_a_worker_that_cannot_compile_fails_the_run_in_one_line():
    client = _FakeClient(fail=True)
    with pytest.raises(distributed.RunFailed) as err:
        distributed.warm_workers(client, "plane", ("batch",), lambda line: None)
    assert str(err.value) == (
        "a Dask worker could not compile the kernels: RuntimeError: no space left on device"
    )


def test_workers_of_a_warm_cache_load_the_kernels_and_say_nothing(client):
    said = []
    seconds = distributed.warm_workers(client, "plane", ("batch",), said.append)
    assert said == []
    assert sorted(seconds) == sorted(client.scheduler_info(n_workers=-1)["workers"])
    assert distributed._is_local(client)


def test_a_hole_solved_on_dask_is_the_local_solution(client):
    """``mcrun.play.play_hole`` with the shots flown by Dask workers: every value, every best
    action and the plays, bit for bit the local solution."""
    from mcrun.play import load_player, play_hole
    from mcrun.run import scenario as sc

    hole = sc.load(sc.library_folder() / "par3-over-water.toml").hole
    player = load_player("tour")
    options = dict(n=6, coarse_m=16.0, fine_m=8.0, plays=50)
    here = play_hole(player, hole, **options)
    there = play_hole(player, hole, client=client, **options)
    assert np.array_equal(here.solution.values, there.solution.values)
    assert np.array_equal(here.solution.best_row, there.solution.best_row)
    assert np.array_equal(here.scores, there.scores)
