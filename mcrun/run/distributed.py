"""The same run on a Dask cluster: the local engine's shots and summary, bit for bit.

``run_scenario`` (``mcrun run SCENARIO --dask local``, ``--scheduler tcp://HOST:8786`` or
``--scheduler-file PATH``) runs a scenario as ``mcrun.run.local.run_scenario`` does, with the chunks
of sample indices as Dask tasks. Dask is an optional extra (``pip install 'mcrun[dask]'``);
this module imports it only when a run asks for it.

Tasks. Every point's N shots are cut into chunks of ``chunk_size`` sample indices, one task
each, numbered point by point (chunk c), as the local engine cuts them (``plan.Plan.chunks``).
The default size is fixed, not measured: it is the local engine's ``plan.DEFAULT_CHUNK_SIZE``
(65,536 shots), so that a default Dask run and a default local run cut the same chunks (see
Statistics). On the pga-driver scenario that is about 0.7 s of work per task for one thread on
the development machine (0.55 s of simulation at ~120,000 shots/s, then the sampling, the
statistics and the part's write), against a few milliseconds of Dask overhead per task; slower
scenarios give longer tasks. A task (``run_chunk``) rebuilds the scenario from its text (parsed
once per worker process), draws its chunk with ``sampling.sample`` (the draws of sample i
depend only on the scenario, the seed and i, so whichever worker runs it, and however often,
gives the same numbers), runs ``batch.simulate_batch`` with one Numba thread, writes its part
of the dataset and returns its ``stats.PointStats`` (counts by status, means and co-moments) to
the client. The chunks are the tasks of the executor (``mcrun.executor``, as every batch of
tasks is); the scenario text travels once, in the run's job, as the result of a small task the
chunks depend on (so a lost copy is recomputed, not lost); a scenario that resamples a
measured-shots file needs the scenario file and that file at the same path on every worker.

Layout. A Dask run folder holds:

- ``shots/part-NNNNN.parquet``: one file per chunk (NNNNN = c, zero-padded to 5 digits), one
  row group each, the columns and types of the local engine's ``shots.parquet``. When the
  scenario has groups the dataset is hive-partitioned by group:
  ``shots/group=<name>/part-NNNNN.parquet`` (the name percent-encoded, e.g. ``7%20iron``), and
  the ``group`` column lives in the folder names, not in the files (readers add it back).
- ``summary.parquet`` (the local engine's, row for row), optional
  ``trajectories/part-NNNNN.parquet`` (the paths of the chunk's every k-th shots, when it has
  some), and ``_SUCCESS``, a JSON note written last: a folder without it is incomplete.

The local engine writes one ``shots.parquet`` file instead (one writer, row groups in order);
here every task writes its own part, in parallel, on any machine. Both read the same way:
``pd.read_parquet(run / "shots")``, ``pl.scan_parquet(run / "shots" / "**/*.parquet",
hive_partitioning=True)``, DuckDB's ``read_parquet('run/shots/**/*.parquet',
hive_partitioning = true)``; rows come in file order, so sort by (point, shot) to compare with
the local file. ``mcrun.results.reader`` reads either layout: ``read_shots`` returns exactly the
DataFrame the local engine's file reads as, and ``mcrun plot`` and ``mcrun report`` read a Dask
run as they read a local one.

Statistics. Moments: from the tasks' partial ``PointStats``, merged on the client in chunk
order (not in order of completion), each chunk's sums folded into the running total with
Chan's pairwise update exactly as the local engine folds its chunks: with the same chunk size
the floating-point sums, and so the means, standard deviations, covariances, ellipses and
regression coefficients, are identical bit for bit. Percentiles and the distance radii: exact,
computed afterwards from the dataset by ``stats.summarise`` (sort, or histogram-then-select
when a column exceeds the memory budget), reading one column of one point at a time part by
part in chunk order. Not mergeable sketches (t-digest, KLL): those are approximate, and the
summary must equal the local engine's and a pandas computation on the shots; the extra pass
reads a few columns of the dataset, a fraction of the simulation's cost. (With another chunk
size the percentiles stay identical and the moments agree to rounding.) Bit for bit assumes
the workers run the client's software (mcrun, Numba, NumPy and its BLAS, which computes the
co-moments) on the same kind of CPU; a mixed cluster may differ in the last bits.

Failures. Every task may be retried twice (``retries``) when it raises; a task whose worker
dies is rescheduled by Dask on another worker (``distributed.scheduler.allowed-failures``,
default 3). Part names depend only on the chunk, and each part is written under a hidden
temporary name and renamed, so a retried or re-run chunk replaces its part: no shot is lost or
written twice. A run whose chunks still fail raises ``RunFailed`` (exit code 2), naming the
failed chunks in one line, and removes everything it wrote. A local (or shared, mounted) folder
is written under a temporary name beside the destination and renamed when complete, as the
local engine does. An fsspec URL (``s3://...`` with s3fs, or any fsspec protocol, ``file://``
included) has no atomic rename: the run is written in place, ``summary.parquet`` and then
``_SUCCESS`` last, and the folder is removed on failure; with ``force`` an earlier run there is
removed when the new one starts.

Workers. A local cluster has worker processes of one Dask thread each, started with
``NUMBA_NUM_THREADS=1``; on any cluster a task sets one Numba thread for itself
(``numba.set_num_threads`` is per calling thread), so the machine runs one Numba thread per
Dask thread and is not oversubscribed.

Kernels. Before it submits the chunks, the run makes sure that every worker has the kernels it
needs (``prepare_kernels``): on a local cluster the client compiles them once, in its own
process, into Numba's on-disk cache when they are not there (saying so on stderr, with the
time it took), and the workers, which share its cache folder (``__pycache__`` beside the
sources, or ``NUMBA_CACHE_DIR``, which they inherit), load them. Then each worker of any
cluster loads them or, when its cache lacks them (a remote cluster whose workers have no
shared cache folder, or another kind of CPU), compiles them at once, each worker saying on
stderr how long it took, instead of compiling silently in its first task. A remote cluster
compiles once for all its workers when ``NUMBA_CACHE_DIR`` points at a folder on storage that
all of them mount (Numba keys the cache by the source file's path and modification time, and
the CPU; workers that compile at once lock the cache's index files against each other:
``engine.cache_lock``). A worker that joins after the start compiles or loads in its first
task.

The client and every worker must reach the output (the client merges the statistics and
computes the percentiles). The run's elapsed time starts once the cluster is up and has its
kernels: starting a local cluster (about a second) is recorded apart, as ``cluster_start_s``
in the provenance, and making sure of the kernels as ``kernels_prepare_s``.
"""

import contextlib
import functools
import importlib
import json
import logging
import math
import os
import secrets
import signal
import sys
import time
import urllib.parse
from dataclasses import dataclass
from multiprocessing import resource_tracker
from pathlib import Path
from typing import NamedTuple

import numba
import numpy as np
import pyarrow as pa
import pyarrow.fs as pafs
import pyarrow.parquet as pq

from mcrun import exits
from mcrun import status as status_codes
from mcrun.engine import warmup
from mcrun.executor import NUMBA_THREADS_PER_TASK, Executor
from mcrun.quantities import InputError
from mcrun.results import location, output, stats
from mcrun.results.output import SHOTS_DIR, SUCCESS_FILE, TRAJECTORIES_DIR
from mcrun.results.reader import read_shots  # a Dask run's shots, as the local file reads
from mcrun.run import plan
from mcrun.run import scenario as scenario_module
from mcrun.units import is_number, path_of, shown

DEFAULT_CHUNK_SIZE = plan.DEFAULT_CHUNK_SIZE
RETRIES = 2
CONNECT_TIMEOUT_S = 30
_SHOWN_FAILURES = 10
# A local cluster's worker: a process with mcrun, Numba, Dask and a hole's kernel loaded
# (measured: 270 MB resident).
WORKER_BYTES = 300_000_000

__all__ = [
    "DEFAULT_CHUNK_SIZE",
    "ChunkResult",
    "DaskRunResult",
    "RunFailed",
    "local_cluster",
    "read_shots",
    "run_chunk",
    "run_scenario",
    "warm_workers",
]


class RunFailed(output.OutputError):
    """A Dask run could not finish; nothing it wrote is left. ``failed``: (chunk, point, start,
    stop, error) of each chunk that failed."""

    def __init__(self, message, failed=()):
        super().__init__(message)
        self.failed = list(failed)


def _dask():
    try:
        distributed = importlib.import_module("dask.distributed")
    except ImportError:
        raise InputError(
            "the Dask backend needs dask.distributed: pip install 'mcrun[dask]'"
        ) from None
    return distributed


# --- where the run is written ------------------------------------------------------------------


class _FolderDestination:
    """A local or shared folder: written under a temporary name beside it, renamed when done."""

    url = None

    def __init__(self, path, force):
        self._folder = output.AtomicFolder(Path(path).absolute(), force=force)
        self.fs = location.filesystem(None)
        self.root = None

    def __enter__(self):
        self._folder.__enter__()
        self.root = str(self._folder.tmp)
        return self

    def begin(self):
        """Nothing to do: the folder is written under a temporary name."""

    def commit(self):
        self._folder.commit()

    def __exit__(self, *exc):
        return self._folder.__exit__(*exc)


class _UrlDestination:
    """An fsspec URL: written in place, the summary and ``_SUCCESS`` last; removed on failure.
    Checked on entering, replaced (``--force``) only by ``begin``, once the cluster is reached:
    a run that could not start (its scheduler unreachable) deleted the run it was to replace."""

    def __init__(self, url, force):
        self.url = url.rstrip("/")
        self.force = force
        try:
            self.fs = location.filesystem(self.url)
            self.root = location.url_path(self.url)
        except (ImportError, ValueError) as err:
            raise output.OutputError(f"cannot use the output {url}: {err}") from None
        self._committed = False
        self._began = False

    def __enter__(self):
        info = self.fs.get_file_info(self.root)
        if info.type == pafs.FileType.File:
            raise output.OutputError(f"the output {self.url} exists and is not a folder")
        if info.type == pafs.FileType.Directory:
            names = {e.base_name for e in self.fs.get_file_info(pafs.FileSelector(self.root))}
            if names:
                problem = output.not_a_run(self.url, names, self._metadata, self._plots)
                if problem is not None:
                    raise output.OutputError(problem)
                if not self.force:
                    raise output.OutputError(
                        f"the output folder {self.url} already holds a run: use --force "
                        "(force=True) to replace it, or choose another with -o (out_dir)"
                    )
        return self

    def begin(self):
        """Replace what the output held (checked on entering) and make the folder."""
        info = self.fs.get_file_info(self.root)
        if info.type == pafs.FileType.Directory:
            self.fs.delete_dir_contents(self.root)
        self._began = True
        self.fs.create_dir(self.root)

    def _plots(self):
        """The names in the folder's plots/."""
        selector = pafs.FileSelector(f"{self.root}/{output.PLOTS_FOLDER}", allow_not_found=True)
        return [e.base_name for e in self.fs.get_file_info(selector)]

    def _metadata(self, name):
        with self.fs.open_input_file(f"{self.root}/{name}") as f:
            return pq.read_metadata(f).metadata

    def commit(self):
        self._committed = True

    def __exit__(self, *exc):
        if self._began and not self._committed:
            with contextlib.suppress(OSError):
                self.fs.delete_dir(self.root)
        return False


def _write_parquet(fs, path, table, local, use_dictionary=True):
    """Write ``table`` as one row group; on a local filesystem under a hidden temporary name
    renamed into place, so that a part is either complete or absent."""
    kwargs = {
        "compression": output.column_compression(table),
        "write_batch_size": output.WRITE_BATCH_SIZE,
        "row_group_size": max(table.num_rows, 1),
        "use_dictionary": use_dictionary,
    }
    if not local:
        pq.write_table(table, path, filesystem=fs, **kwargs)
        return
    parent, _, name = path.rpartition("/")
    tmp = f"{parent}/.{name}.{secrets.token_hex(4)}.tmp"
    try:
        pq.write_table(table, tmp, filesystem=fs, **kwargs)
        fs.move(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            fs.delete_file(tmp)
        raise


def _group_dir(group):
    return f"group={urllib.parse.quote(group, safe='')}"


# --- the task ----------------------------------------------------------------------------------


class ChunkResult(NamedTuple):
    """What a task returns: where its part is and its statistics."""

    chunk: int
    point: int
    start: int
    stop: int
    shots_path: str
    trajectories_path: str | None
    stats: stats.PointStats


@functools.lru_cache(maxsize=4)
def _scenario(text, path, seed):
    """The scenario of a job, parsed from its text once per worker process (a resampled shots
    file is found relative to ``path``, so it must be at the same place on every worker)."""
    return plan.with_seed(scenario_module.loads(text, path), seed)


def scenario_on_worker(text, path, seed):
    """The scenario of ``text`` (read from ``path``) with ``seed``, read once per worker
    process: how a task of another kind (``run.starts``) gets its scenario."""
    return _scenario(text, path, seed)


_BUILDERS = {}


def _shots_builder(job):
    """The job's table builder (an ``output.ShotsWriter`` without a file), once per worker."""
    builder = _BUILDERS.get(job["id"])
    if builder is None:
        _BUILDERS.clear()
        scenario = _scenario(job["scenario_text"], job["scenario_path"], job["seed"])
        builder = _BUILDERS[job["id"]] = output.ShotsWriter(
            None,
            job["input_names"],
            job["groups"],
            job["labels"],
            job["shots_metadata"],
            {name: pa.type_for_alias(kind) for name, kind in job["input_types"].items()},
            hole=scenario.hole,
            starts_xy_m=plan.starts_of(scenario.points),
            putting=plan.putting_of(scenario),
        )
    return builder


class _Paths(list):
    """Collects the trajectories ``plan.add_trajectories`` adds."""

    def add(self, point, shot, traj):
        self.append((point, shot, np.array(traj, dtype=float)))


def run_chunk(chunk, point, start, stop, job):
    """One task: sample, simulate and write shots ``start .. stop - 1`` of ``point``.

    ``job``: the run's description (plain data: the scenario text and path, the seed, the
    output's URL and folder, the columns). Returns a ``ChunkResult``.
    """
    numba.set_num_threads(NUMBA_THREADS_PER_TASK)
    scenario = _scenario(job["scenario_text"], job["scenario_path"], job["seed"])
    terrain = plan.terrain_of(scenario)
    inputs, point_stats, table = plan.made_chunk(
        scenario, _shots_builder(job), job["drivers"][point], job["input_names"], point, start,
        stop, terrain,
    )  # fmt: skip
    fs = location.filesystem(job["url"])
    local = job["url"] is None
    if job["partitioned"]:
        table = table.drop_columns("group")
    shots_path = f"{job['root']}/{job['shot_dirs'][point]}/{output.part_name(chunk)}"
    # Encoded as the local engine's shots.parquet: dictionaries for the text columns only.
    _write_parquet(fs, shots_path, table, local, output.dictionary_columns(table.schema))
    traj_path = None
    every = job["trajectories_every"]
    if every and plan.trajectory_shots(start, stop, every):
        paths = _Paths()
        plan.add_trajectories(paths, inputs, point, start, stop, every, terrain)
        schema = output.TRAJECTORY_SCHEMA.with_metadata(job["trajectories_metadata"])
        traj_path = f"{job['root']}/{TRAJECTORIES_DIR}/{output.part_name(chunk)}"
        _write_parquet(fs, traj_path, output.trajectory_table(paths, schema), local)
    return ChunkResult(chunk, point, start, stop, shots_path, traj_path, point_stats)


# --- the cluster -------------------------------------------------------------------------------


# A local Dask cluster's workers (``--dask local --workers N``) are processes of one thread
# each: more than a few a core only share the cores.
WORKERS_PER_CORE = 4


def local_cores():
    """The cores a local Dask cluster counts (its default workers): Dask's count where Dask is
    installed, else this process's CPUs."""
    try:
        from dask.system import CPU_COUNT

        return int(CPU_COUNT)
    except ImportError:
        cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else None
        return cores or os.cpu_count() or 1


def most_local_workers():
    """(the most workers of a local Dask cluster here, why): ``WORKERS_PER_CORE`` a core, and
    no more than the memory available holds at ``mcrun.run.distributed.WORKER_BYTES`` each
    (a process with mcrun, Numba, Dask and a kernel loaded)."""
    cores = local_cores()
    from mcrun.run.aim import available_memory

    most = WORKERS_PER_CORE * cores
    why = f"{WORKERS_PER_CORE} a core, {cores} core{'s' if cores != 1 else ''} here"
    memory = available_memory()
    if memory is not None:
        most = max(1, min(most, memory // WORKER_BYTES))
        why += (f"; each worker process takes about {plan.size_text(WORKER_BYTES)}, "
                f"{plan.size_text(memory)} is available")  # fmt: skip
    return int(most), why


def check_local_workers(workers, shown_as=None):
    """``workers`` (an int, or a float of a whole value) as an int from 1 to
    ``most_local_workers()``; InputError (``shown_as``: how the message names it, default
    "workers N") otherwise: a million workers were started one by one, without a word."""
    most, why = most_local_workers()
    shown_as = f"workers {shown(workers)}" if shown_as is None else shown_as
    ok = is_number(workers) and math.isfinite(workers) and workers == int(workers)
    if not (ok and 1 <= workers <= most):
        raise InputError(f"{shown_as}: allowed: a whole number of worker processes from 1 to "
                         f"{most} ({why})")  # fmt: skip
    return int(workers)


def local_cluster(workers=None, **kwargs):
    """A Dask ``LocalCluster`` as ``--dask local`` starts it: ``workers`` processes (default:
    the cores) of one Dask thread each, with ``NUMBA_NUM_THREADS=1``, no dashboard.

    Numba reads the variable when a process first imports it, which a worker does with its
    first task. Each task also runs one Numba thread whatever the variable says.
    """
    distributed = _dask()
    import dask

    workers = dask.system.CPU_COUNT if workers is None else check_local_workers(workers)
    options = {
        "n_workers": workers,
        "threads_per_worker": 1,
        "processes": True,
        "dashboard_address": None,
        # The scheduler serves its HTTP routes even without a dashboard, on port 8787 unless
        # told otherwise, and warns on stderr when another cluster has that port: any free one.
        "scheduler_kwargs": {"dashboard": False, "dashboard_address": ":0"},
    }
    # Set in each worker process as it starts (before it first imports Numba), not through
    # Dask's pre-spawn-environ: the nannies live in this process and would set it in this
    # process's environment, where Numba, which rereads it at every compilation, would then
    # refuse to compile once its own threads have started.
    env = {"NUMBA_NUM_THREADS": str(NUMBA_THREADS_PER_TASK)}
    options = {**options, "env": env, **kwargs}
    if not hasattr(signal, "pthread_sigmask"):  # (Windows: no signal masks)
        return distributed.LocalCluster(**options)
    # Ctrl-C reaches the whole process group: a worker process that was still importing printed
    # its traceback. The workers are started with SIGINT blocked (a process inherits the mask of
    # the thread that starts it), and so is Ctrl-C here until the cluster is up (or Dask gives
    # up starting it); then it comes, and this process stops the cluster and its workers.
    held = signal.pthread_sigmask(signal.SIG_BLOCK, [])  # (the mask as it is, to restore)
    try:
        resource_tracker.ensure_running()  # (its first start unblocks SIGINT in the thread)
        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
        cluster = distributed.LocalCluster(**options)
    except BaseException:
        signal.pthread_sigmask(signal.SIG_SETMASK, held)
        raise
    try:
        signal.pthread_sigmask(signal.SIG_SETMASK, held)  # (a Ctrl-C held meanwhile comes here)
    except KeyboardInterrupt:
        cluster.close()
        raise
    return cluster


def check_port(address):
    """InputError for an address whose port is no TCP port (tcp://host:99999 was tried for
    the connection's 30 s); what else is wrong with it, Dask says."""
    port = urllib.parse.urlsplit(address if "://" in address else f"tcp://{address}")
    try:
        number = port.port
    except ValueError:  # (out of 0-65535, or not digits)
        number = -1
    if number is not None and not 1 <= number <= 65535:
        raise InputError(f"--scheduler {address}: its port is not one: allowed: 1 to 65535, as "
                         "in tcp://HOST:8786")  # fmt: skip


def scheduler_address(path):
    """The address in a Dask scheduler file (``dask scheduler --scheduler-file``: JSON with
    an "address"); InputError, one line, where there is none (Dask's own reading was an
    AssertionError or a TypeError)."""
    path = Path(path)
    if not path.is_file():
        why = "a folder" if path.is_dir() else "no such file"
        raise InputError(f"--scheduler-file {path}: {why}")
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError):
        data = None
    if not (isinstance(data, dict) and isinstance(data.get("address"), str) and data["address"]):
        raise InputError(f"--scheduler-file {path}: not a Dask scheduler file (JSON with an "
                         '"address", as dask scheduler --scheduler-file writes)')  # fmt: skip
    return data["address"]


@contextlib.contextmanager
def _connect(client, scheduler, scheduler_file, workers):
    """The client of the cluster asked for (a local cluster is started and closed here)."""
    distributed = _dask()
    if sum(x is not None for x in (client, scheduler, scheduler_file)) > 1:
        raise InputError("give one of a client, a scheduler address or a scheduler file")
    existing = client is not None or scheduler_file is not None or scheduler not in (None, "local")
    if workers is not None and existing:  # (ignored: the cluster has its workers)
        raise InputError("workers: is for a local cluster (an existing cluster has its workers)")
    if scheduler is not None and not isinstance(scheduler, str):  # (a TypeError of Dask's)
        raise InputError(f"scheduler {shown(scheduler)}: allowed: an address such as "
                         "'tcp://host:8786', or 'local'")  # fmt: skip
    if client is not None:
        yield client
        return
    if scheduler_file is not None:
        target = {"address": scheduler_address(scheduler_file)}
        where = f"the Dask scheduler of {scheduler_file}"
    elif scheduler not in (None, "local"):
        check_port(scheduler)
        target = {"address": scheduler}
        where = f"the Dask scheduler {scheduler}"
    else:
        cluster = None
        try:
            # Interrupted while it starts, a cluster can be neither used nor closed.
            # Its logs are silenced, the critical too: the run reports its failed chunks
            # itself, and after Ctrl-C or SIGTERM (sent to the whole process group, workers
            # included) the scheduler logs errors about the workers it lost ("Couldn't gather
            # keys"; at CRITICAL, "Closed comm <BatchedSend: closed> while trying to write"),
            # which raced the run's own one line on stderr.
            with exits.interrupts_deferred():
                cluster = local_cluster(workers, silence_logs=logging.CRITICAL + 10)
            with distributed.Client(cluster) as own:
                yield own
        finally:
            if cluster is not None:
                cluster.close()
        return
    try:
        own = distributed.Client(**target, timeout=f"{CONNECT_TIMEOUT_S}s")
    except (OSError, TimeoutError, ValueError) as err:
        reason = " ".join(str(err).split()) or type(err).__name__
        raise InputError(f"cannot reach {where}: {reason}") from None
    with own:
        yield own


def _cluster_size(client):
    """(scheduler address, workers, Dask threads of each worker), once a worker is there."""
    try:
        client.wait_for_workers(1, timeout=CONNECT_TIMEOUT_S)
    except TimeoutError:
        raise InputError(
            f"the Dask cluster at {client.scheduler.address} has no worker "
            f"(waited {CONNECT_TIMEOUT_S} s)"
        ) from None
    info = client.scheduler_info(n_workers=-1)
    threads = [w["nthreads"] for w in info["workers"].values()]
    return info["address"], len(threads), threads


# --- the kernels on the workers ----------------------------------------------------------------


def _say(line):
    print(line, file=sys.stderr, flush=True)


def _is_local(client):
    """Whether the client's cluster is a local one (its workers share this machine's cache)."""
    cluster = getattr(client, "cluster", None)
    return cluster is not None and isinstance(cluster, _dask().LocalCluster)


def _worker_kernels_cached(ground, kernels):
    """On a worker: ``warmup.kernel_cached`` there (None: cannot be told)."""
    return warmup.kernel_cached(ground, kernels)


def _worker_warm_up(ground, kernels):
    """On a worker: compile or load the kernels (cache saves locked against the other
    workers'); the seconds it took."""
    return sum(done.seconds for done in warmup.warm_up_job((ground, kernels)))


def warm_workers(client, ground, kernels, say=_say):
    """Have every worker of the client's cluster load the ``kernels`` for ``ground`` or, where
    its cache lacks them, compile them, all at once: a line (``say``, default stderr) before,
    when any worker compiles, and one for each worker that compiled, with the time it took.
    Returns {worker address: seconds}; raises ``RunFailed`` (one line) when a worker fails."""
    cached = client.run(_worker_kernels_cached, ground, kernels)
    cold = sorted(address for address, is_cached in cached.items() if is_cached is not True)
    if cold:
        say(
            f"mcrun: compiling the kernels on {len(cold)} of {len(cached)} Dask workers (their "
            "cache lacks them; cached for the next runs)"
        )
    try:
        seconds = client.run(_worker_warm_up, ground, kernels)
    except Exception as err:
        raise RunFailed(
            f"a Dask worker could not compile the kernels: {_error_text(err)}"
        ) from None
    for address in cold:
        if address in seconds:
            say(f"mcrun: Dask worker {address} compiled the kernels in {seconds[address]:.0f} s")
    return seconds


# --- the run -----------------------------------------------------------------------------------


@dataclass
class DaskRunResult(plan.RunResult):
    """A ``plan.RunResult`` of a Dask run: ``shots_path`` is the shots/ dataset folder."""

    scheduler: str = ""
    workers: int = 0

    @property
    def where(self):
        """How it ran, for the line ``mcrun run`` prints: "2 Dask workers, 2 threads"."""
        return (f"{self.workers} Dask worker{'s' * (self.workers != 1)}, {self.threads} "
                f"thread{'s' * (self.threads != 1)}")  # fmt: skip


def run_scenario(
    path_or_scenario,
    n=None,
    seed=None,
    out_dir=None,
    *,
    client=None,
    scheduler=None,
    scheduler_file=None,
    workers=None,
    chunk_size=DEFAULT_CHUNK_SIZE,
    trajectories_every=None,
    progress=True,
    force=False,
    budget_bytes=stats.DEFAULT_BUDGET_BYTES,
    retries=RETRIES,
    chunk_task=run_chunk,
    ignore_disk_space=False,
    announce=None,
    prepare_kernels=True,
):
    """Run a scenario on a Dask cluster and write its folder; return a DaskRunResult.

    The same shots and summary as ``mcrun.run.local.run_scenario`` with the same ``n``, ``seed``
    and ``chunk_size``, bit for bit.

    Parameters
    ----------
    path_or_scenario, n, seed, chunk_size, trajectories_every, progress, force, budget_bytes
        As ``mcrun.run.local.run_scenario``; ``chunk_size`` is also the shots per task.
    ignore_disk_space, announce
        As ``mcrun.run.local.run_scenario``; the free space is checked for a folder, not for a URL.
    out_dir : str or Path, optional
        A folder that the client and every worker reach (local, or shared and mounted at the
        same path), or an fsspec URL (``s3://bucket/run``). Default ``runs/<name>-<seed>``.
    client : dask.distributed.Client, optional
        Use this client's cluster.
    scheduler : str, optional
        ``"local"`` (a ``local_cluster`` of ``workers`` processes, the default when no client,
        scheduler or scheduler file is given) or a scheduler address ``tcp://host:8786``.
    scheduler_file : str or Path, optional
        The scheduler file of an existing cluster (``dask scheduler --scheduler-file``).
    workers : int, optional
        Worker processes of the local cluster (default: the cores).
    retries : int
        Retries of a task that raises.
    chunk_task : callable
        The function a task runs, with ``run_chunk``'s signature (tests wrap it).
    prepare_kernels : bool
        Compile the kernels the run needs before its chunks (see Kernels in the module's
        notes); False: each worker compiles or loads them in its first task.

    Raises
    ------
    InputError
        (ScenarioError, OutputError) a bad scenario, argument or output, or an unreachable
        cluster, before anything is written; ``RunFailed`` when chunks still fail after their
        retries, after removing what was written. KeyboardInterrupt is re-raised after the
        tasks are cancelled and the output removed.
    """
    the_plan = plan.plan(path_or_scenario, n, seed, chunk_size, trajectories_every)
    plan.check_run_switches(announce, force=force, progress=progress,
                            ignore_disk_space=ignore_disk_space,
                            prepare_kernels=prepare_kernels)  # fmt: skip
    if workers is not None:
        workers = check_local_workers(plan.positive_int(workers, "workers"))
    retries = plan.positive_int(retries, "retries", minimum=0)
    scenario, points, n, seed = the_plan.scenario, the_plan.points, the_plan.n, the_plan.seed
    if out_dir is None:
        out_dir = plan.default_out_dir(scenario, seed)
    path_of(out_dir, "out_dir", "a folder's path or a URL")
    url = str(out_dir).rstrip("/") if location.is_url(str(out_dir)) else None
    if not (ignore_disk_space or url):
        plan.check_disk_space(the_plan, out_dir)
    partitioned = any(p.group for p in points)
    chunks = list(the_plan.chunks())

    destination = _UrlDestination(url, force) if url else _FolderDestination(out_dir, force)
    connecting = time.perf_counter()
    with destination, _connect(client, scheduler, scheduler_file, workers) as dask_client:
        address, n_workers, threads = _cluster_size(dask_client)
        ground, kernels = plan.kernels_of(scenario, the_plan.trajectories_every is not None)
        preparing = time.perf_counter()
        if prepare_kernels:
            if _is_local(dask_client):
                warmup.compile_announced(ground, kernels, _say)
            warm_workers(dask_client, ground, kernels, _say)
        prepared = time.perf_counter()
        destination.begin()  # (the cluster reached and ready: the output replaced now)
        if announce is not None:
            announce(the_plan.line())
        # The run's time starts once the cluster is up (a local cluster takes seconds to
        # start: recorded apart, as cluster_start_s).
        started = time.perf_counter()
        import dask
        import distributed

        provenance = plan.provenance(
            the_plan,
            "dask",
            {**output.versions(), "dask": dask.__version__, "distributed": distributed.__version__},
            sum(threads),
            layout="dataset",
            scheduler=address,
            workers=n_workers,
            threads_per_worker=sorted(set(threads)),
            cluster_start_s=round(preparing - connecting, 3),
            kernels_prepare_s=round(prepared - preparing, 3),
            numba_threads_per_task=NUMBA_THREADS_PER_TASK,
            chunks=len(chunks),
            retries=retries,
        )
        fs, root = destination.fs, destination.root
        shot_dirs = [
            f"{SHOTS_DIR}/{_group_dir(p.group)}" if partitioned else SHOTS_DIR for p in points
        ]
        # Tasks write into existing folders and never create one: a task still running after
        # an interrupted run has removed its folder fails instead of leaving files behind.
        for folder in dict.fromkeys(shot_dirs):
            fs.create_dir(f"{root}/{folder}")
        if the_plan.trajectories_every is not None:
            fs.create_dir(f"{root}/{TRAJECTORIES_DIR}")
        job = {
            "id": secrets.token_hex(8),
            "scenario_text": scenario.text,
            "scenario_path": str(Path(scenario.path).absolute()),
            "seed": seed,
            "url": destination.url,
            "root": root,
            "shot_dirs": shot_dirs,
            "partitioned": partitioned,
            "input_names": the_plan.input_names,
            "input_types": dict.fromkeys(the_plan.integer_columns, "int64"),
            "groups": [p.group for p in points],
            "labels": [p.label for p in points],
            "drivers": the_plan.drivers,
            "trajectories_every": the_plan.trajectories_every,
            "shots_metadata": plan.file_metadata(provenance, "shots"),
            "trajectories_metadata": plan.file_metadata(provenance, "trajectories"),
        }
        point_stats, results = _execute(
            dask_client,
            chunk_task,
            job,
            chunks,
            lambda: [plan.point_stats(the_plan.scenario, d) for d in the_plan.drivers],
            the_plan.shots,
            retries,
            progress,
        )
        _remove_strays(fs, root, results, the_plan.trajectories_every is not None)
        parts = {p.index: [] for p in points}
        for result in results:
            parts[result.point].append(result.shots_path)
        rows = plan.summary_rows(
            points,
            point_stats,
            lambda point: _PartsColumns(fs, parts[point]),
            budget_bytes,
            on_hole=the_plan.scenario.hole,
        )
        with fs.open_output_stream(f"{root}/{output.SUMMARY_FILE}") as f:
            output.write_table(
                f, plan.summary_table(rows), plan.summary_metadata(provenance, started)
            )
        elapsed = time.perf_counter() - started
        note = {
            "backend": "dask",
            "n": n,
            "seed": seed,
            "points": len(points),
            "chunks": len(chunks),
            "shot_parts": [r.shots_path[len(root) + 1 :] for r in results],
            "elapsed_s": round(elapsed, 3),
        }
        with fs.open_output_stream(f"{root}/{SUCCESS_FILE}") as f:
            f.write(json.dumps(note).encode())
        destination.commit()

    if url:
        folder = url
        join = "{}/{}".format
    else:
        folder = Path(out_dir)
        join = Path.joinpath
    return DaskRunResult(
        out_dir=folder,
        shots_path=join(folder, SHOTS_DIR),
        summary_path=join(folder, output.SUMMARY_FILE),
        trajectories_path=None
        if the_plan.trajectories_every is None
        else join(folder, TRAJECTORIES_DIR),
        n=n,
        seed=seed,
        points=len(points),
        elapsed_s=elapsed,
        threads=sum(threads),
        scheduler=address,
        workers=n_workers,
    )


def _describe_chunk(chunk):
    return f"chunk {chunk.index} (point {chunk.point}, shots {chunk.start}-{chunk.stop - 1})"


def _error_text(err):
    return " ".join(f"{type(err).__name__}: {err}".split())


def _job_of(job):
    """The job itself: a task the chunks depend on, so its data is recomputed if lost."""
    return job


def _chunk_of(chunk_task, job, chunk):
    """A chunk as a task of the executor: ``chunk_task`` (``run_chunk``) of its shots."""
    return chunk_task(chunk.index, chunk.point, chunk.start, chunk.stop, job)


def _execute(client, chunk_task, job, chunks, stats_of, total, retries, progress):
    """The chunks as the tasks of the executor on the client's workers (``mcrun.executor``),
    their statistics merged in chunk order as they finish into ``stats_of()`` (a PointStats
    per point); return (PointStats per point, ChunkResult per chunk without its
    statistics)."""
    from tqdm import tqdm

    merged = stats_of()
    pending = {}  # chunk -> PointStats, finished ahead of an earlier chunk
    following = [0]  # the next chunk to merge
    results = [None] * len(chunks)
    failed = []
    show = bool(progress) and sys.stderr.isatty()
    with tqdm(total=total, unit="shot", unit_scale=True, disable=not show, smoothing=0.1) as bar:
        bar.set_description(f"dask: {len(chunks)} tasks")

        def done(k, result):
            results[k] = result._replace(stats=None)
            if not failed:  # the run fails anyway: keep no statistics
                pending[k] = result.stats
                while following[0] in pending:
                    merged[chunks[following[0]].point].merge(pending.pop(following[0]))
                    following[0] += 1
            bar.update(chunks[k].stop - chunks[k].start)

        def failure(k, err):
            failed.append((chunks[k], err))
            pending.clear()

        # The job travels once, as the result of a task the chunks depend on (recomputed if
        # lost), released once the chunks are done or cancelled.
        job_future = client.submit(_job_of, job, key=f"mcrun-job-{job['id']}")
        try:
            Executor(client=client, retries=retries).map(
                functools.partial(_chunk_of, chunk_task), chunks, shared=(job_future,),
                done=done, failed=failure, name="chunk", key=f"mcrun-chunk-{job['id']}",
            )  # fmt: skip
        finally:
            job_future.release()
    if failed:
        failed.sort(key=lambda item: item[0].index)
        shown = "; ".join(f"{_describe_chunk(c)}: {_error_text(e)}" for c, e in failed[:3])
        listed = ", ".join(str(c.index) for c, _ in failed[:_SHOWN_FAILURES])
        if len(failed) > _SHOWN_FAILURES:
            listed += f" and {len(failed) - _SHOWN_FAILURES} more"
        raise RunFailed(
            f"the run could not finish: {len(failed)} of {len(chunks)} chunks failed after "
            f"{retries} retries (chunks {listed}): {shown}; nothing was written",
            [(c.index, c.point, c.start, c.stop, _error_text(e)) for c, e in failed],
        )
    return merged, results


def _remove_strays(fs, root, results, trajectories):
    """Remove what is not a finished part (the temporary file of a task whose worker died)."""
    keep = {r.shots_path for r in results} | {r.trajectories_path for r in results}
    folders = [SHOTS_DIR, TRAJECTORIES_DIR] if trajectories else [SHOTS_DIR]
    for folder in folders:
        selector = pafs.FileSelector(f"{root}/{folder}", recursive=True)
        for info in fs.get_file_info(selector):
            if info.type == pafs.FileType.File and info.path not in keep:
                fs.delete_file(info.path)
    missing = [
        r.shots_path
        for r in results
        if fs.get_file_info(r.shots_path).type == pafs.FileType.NotFound
    ]
    if missing:
        raise RunFailed(f"the run could not finish: parts missing: {', '.join(missing[:3])}")


class _PartsColumns(stats.ShotsColumns):
    """``stats.ShotsColumns`` over a point's parts, in chunk order (one row group each)."""

    def __init__(self, fs, paths):
        self.fs = fs
        self.paths = list(paths)

    def chunks(self, columns):
        for path in self.paths:
            with self.fs.open_input_file(path) as f:
                table = pq.ParquetFile(f).read(columns=[*columns, "status"])
            ok = table.column("status").to_numpy() == status_codes.OK
            yield {c: table.column(c).to_numpy()[ok] for c in columns}

    def tables(self, columns):
        for path in self.paths:
            with self.fs.open_input_file(path) as f:
                yield pq.ParquetFile(f).read(columns=list(columns))


# --- command line ------------------------------------------------------------------------------
