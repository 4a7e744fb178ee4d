"""The local driver: a run's chunks on this machine's threads, into one shots.parquet.

``run_scenario`` runs the chunks of the run's ``plan.Plan`` (every point's sample indices in
fixed-size chunks) as the tasks of the executor (``mcrun.executor``), each on a thread of its
own: ``sampling.sample`` draws the chunk's inputs (which depend only on the scenario, the seed
and the sample index, so neither the chunk size nor the thread count changes a number),
``simulate_batch`` flies them (on the task's thread), the hole's columns are made
(``ShotsWriter.hole_columns``), a ``stats.PointStats`` of the chunk holds its streaming sums
and its Parquet table is built. One thread beside them (``executor.in_background``) takes the
chunks in order: it merges their statistics into the point's (in chunk order, so that they do
not depend on the timing) and appends their tables to shots.parquet, a row group each. The
tasks run at most ``AHEAD_PER_THREAD`` chunks a thread ahead of it: the memory is a few chunks,
whatever the number of shots. After the last chunk the percentiles are computed exactly from
shots.parquet (``plan.summary_rows``), summary.parquet is written, and the temporary folder is
renamed into place.

The command line: ``mcrun run``, ``mcrun validate``, ``mcrun scenarios`` (``register``) and
``mcrun replay`` (``mcrun.run.replay``). The default output folder of ``mcrun run`` is
``runs/<scenario name>-<seed>`` under the current folder.
"""

import concurrent.futures
import sys
import threading
import time
from pathlib import Path

import numba
import pyarrow as pa

from mcrun import executor
from mcrun.executor import on_threads
from mcrun.quantities import InputError
from mcrun.results import location, output, stats
from mcrun.results.output import OutputError
from mcrun.run import plan
from mcrun.units import path_of, shown, whole_number

# The chunks a thread's tasks may run ahead of the writer (each holds its table until written).
AHEAD_PER_THREAD = 2


def _check_threads(threads):
    if threads is None:
        return None
    most = numba.config.NUMBA_NUM_THREADS
    number, why = whole_number(threads.strip() if isinstance(threads, str) else threads)
    if not why and number is not None and number > most:  # (1e400 was "up to 2**63 - 1")
        raise InputError(
            f"threads must be within [1, {most}] on this machine, got {shown(threads)}"
        )
    return plan.positive_int(threads, "threads")


def run_scenario(
    path_or_scenario,
    n=None,
    seed=None,
    out_dir=None,
    threads=None,
    chunk_size=plan.DEFAULT_CHUNK_SIZE,
    trajectories_every=None,
    progress=True,
    force=False,
    budget_bytes=stats.DEFAULT_BUDGET_BYTES,
    ignore_disk_space=False,
    announce=None,
):
    """Run a scenario and write its folder; return a ``plan.RunResult``.

    Parameters
    ----------
    path_or_scenario : str, Path or scenario.Scenario
        A scenario file, a library scenario's name, or a loaded scenario.
    n : int, optional
        Shots per point (default: the scenario's ``shots``).
    seed : int, optional
        Default: the scenario's ``seed``.
    out_dir : str or Path, optional
        The run folder (default ``runs/<scenario name>-<seed>``). It must not exist, be empty,
        or (with ``force``) hold an earlier run, which is replaced once this one is complete.
    threads : int, optional
        Numba threads for the batch kernel (default: Numba's, all cores); restored after.
    chunk_size : int
        Shots per chunk (one row group each); results do not depend on it.
    trajectories_every : int, optional
        Write trajectories.parquet with the path of every k-th shot of each point.
    progress : bool
        A tqdm bar on stderr (only when stderr is a terminal).
    force : bool
        Replace an existing run folder.
    budget_bytes : int
        Memory for the exact percentiles per column (``stats.exact_quantiles``).
    ignore_disk_space : bool
        Run even when the estimated size (``plan.plan``) is not under the free space of the
        output's disk.
    announce : callable, optional
        Called with the plan's line (``plan.Plan.line``) before the run starts.

    Raises
    ------
    InputError
        (ScenarioError, OutputError) on a bad scenario, argument or output folder, or a run
        that would not fit on the disk, before anything is written. KeyboardInterrupt is
        re-raised after the temporary files are removed.
    """
    the_plan = plan.plan(path_or_scenario, n, seed, chunk_size, trajectories_every)
    threads = _check_threads(threads)
    plan.check_run_switches(announce, force=force, progress=progress,
                            ignore_disk_space=ignore_disk_space)  # fmt: skip
    budget_bytes = plan.positive_int(budget_bytes, "budget_bytes")
    if out_dir is None:
        out_dir = plan.default_out_dir(the_plan.scenario, the_plan.seed)
    if location.is_url(out_dir):  # (a path of that name was a traceback, or one made here)
        raise OutputError(f"the output {out_dir} is a URL: the local executor writes to a "
                          "folder's path; a URL output needs the Dask backend (--dask local, "
                          "--scheduler)")  # fmt: skip
    out_dir = path_of(out_dir, "out_dir", "a folder's path")
    if not ignore_disk_space:
        plan.check_disk_space(the_plan, out_dir)
    points = the_plan.points

    previous_threads = numba.get_num_threads()
    if threads is not None:
        numba.set_num_threads(threads)
    # Compile (or load from the cache) before the clock starts: the rate is the run's.
    plan.compile_kernel(the_plan.scenario)
    started = time.perf_counter()
    provenance = plan.provenance(the_plan, "local", output.versions(), numba.get_num_threads())
    try:
        with output.AtomicFolder(out_dir, force=force) as folder:
            if announce is not None:  # once the output folder is accepted
                announce(the_plan.line())
            shots_writer = output.ShotsWriter(
                folder.file(output.SHOTS_FILE),
                the_plan.input_names,
                [p.group for p in points],
                [p.label for p in points],
                plan.file_metadata(provenance, "shots"),
                dict.fromkeys(the_plan.integer_columns, pa.int64()),
                hole=the_plan.scenario.hole,
                starts_xy_m=plan.starts_of(points),
                putting=plan.putting_of(the_plan.scenario),
            )
            traj_writer = None
            if the_plan.trajectories_every is not None:
                traj_writer = output.TrajectoryWriter(
                    folder.file(output.TRAJECTORIES_FILE),
                    plan.file_metadata(provenance, "trajectories"),
                )
            # The summary's values of the ok shots, as written (``stats.Spill``): read back
            # from there rather than decoded from the Parquet again.
            spill = stats.Spill(folder.tmp)
            try:
                try:
                    point_stats = _stream(the_plan, shots_writer, traj_writer, progress, spill)
                except BaseException:
                    shots_writer.abort()
                    if traj_writer is not None:
                        traj_writer.abort()
                    raise
                shots_writer.close(plan.file_metadata(provenance, "shots", started))
                rows = plan.summary_rows(
                    points, point_stats, spill.columns, budget_bytes,
                    on_hole=the_plan.scenario.hole,
                )  # fmt: skip
            finally:
                spill.close()
            output.write_table(
                folder.file(output.SUMMARY_FILE),
                plan.summary_table(rows),
                plan.summary_metadata(provenance, started),
            )
            if traj_writer is not None:
                traj_writer.close(plan.file_metadata(provenance, "trajectories", started))
            folder.commit()
    finally:
        numba.set_num_threads(previous_threads)
    elapsed = time.perf_counter() - started
    return plan.RunResult(
        out_dir=out_dir,
        shots_path=out_dir / output.SHOTS_FILE,
        summary_path=out_dir / output.SUMMARY_FILE,
        trajectories_path=None
        if the_plan.trajectories_every is None
        else out_dir / output.TRAJECTORIES_FILE,
        n=the_plan.n,
        seed=the_plan.seed,
        points=len(points),
        elapsed_s=elapsed,
        threads=provenance["threads"],
    )


class _Stopped(Exception):
    """A chunk's task stops: another task or the writer failed."""


def _stream(the_plan, shots_writer, traj_writer, progress, spill):
    """The chunks as the executor's tasks, written in order beside them (and their summary's
    values to ``spill``, a ``stats.Spill``); returns the PointStats of every point."""
    from tqdm import tqdm

    show = bool(progress) and sys.stderr.isatty()
    scenario, points, n = the_plan.scenario, the_plan.points, the_plan.n
    every = the_plan.trajectories_every
    chunks = list(the_plan.chunks())
    all_stats = [plan.point_stats(scenario, drivers) for drivers in the_plan.drivers]
    terrain = plan.terrain_of(scenario)
    ahead = AHEAD_PER_THREAD * max(numba.get_num_threads(), 1)
    done = {}  # chunk index -> (its PointStats, its table, its spill, its inputs for the paths)
    turn = threading.Condition()
    state = {"written": 0, "failed": None}

    def fail(err):
        with turn:
            if state["failed"] is None:
                state["failed"] = err
            turn.notify_all()

    def task(k):
        """Chunk k: sampled, flown, its columns, statistics and table made."""
        chunk = chunks[k]
        try:
            with turn:
                while k >= state["written"] + ahead and state["failed"] is None:
                    turn.wait()
                if state["failed"] is not None:
                    raise _Stopped
            inputs, part, table = plan.made_chunk(
                scenario, shots_writer, the_plan.drivers[chunk.point], the_plan.input_names,
                chunk.point, chunk.start, chunk.stop, terrain,
            )  # fmt: skip
            block = spill.block(table)
            with turn:
                done[k] = (part, table, block, inputs if traj_writer is not None else None)
                turn.notify_all()
        except _Stopped:
            raise
        except BaseException as err:
            fail(err)
            raise

    def write(bar):
        """The chunks in order: their statistics merged, their tables and paths written."""
        try:
            for k, chunk in enumerate(chunks):
                with turn:
                    while k not in done and state["failed"] is None:
                        turn.wait()
                    if state["failed"] is not None:
                        return
                    part, table, block, inputs = done.pop(k)
                all_stats[chunk.point].merge(part)
                shots_writer.append(chunk.point, table)
                spill.append(chunk.point, block)
                if traj_writer is not None:
                    plan.add_trajectories(traj_writer, inputs, chunk.point, chunk.start,
                                          chunk.stop, every, terrain)  # fmt: skip
                    traj_writer.flush()
                if len(points) > 1 and chunk.start == 0:
                    bar.set_description(points[chunk.point].label or f"point {chunk.point}")
                bar.update(chunk.stop - chunk.start)
                with turn:
                    state["written"] = k + 1
                    turn.notify_all()
        except BaseException as err:
            fail(err)
            raise

    with tqdm(
        total=n * len(points), unit="shot", unit_scale=True, disable=not show, smoothing=0.1
    ) as bar:
        writing = executor.in_background(write, bar)
        try:
            on_threads(task, len(chunks))
        except _Stopped:
            pass  # the writer failed: its error is raised below
        except BaseException as err:
            fail(err)
            raise
        finally:
            if state["failed"] is not None:
                concurrent.futures.wait([writing])
        writing.result()  # raises what the writer raised
    return all_stats


def run_dataframes(path_or_scenario, n=None, seed=None, **kwargs):
    """Run a scenario into a temporary folder and return (shots, summary) DataFrames."""
    import tempfile

    kwargs.setdefault("progress", False)
    with tempfile.TemporaryDirectory(prefix="mcrun-") as tmp:
        result = run_scenario(path_or_scenario, n=n, seed=seed, out_dir=Path(tmp) / "run", **kwargs)
        return result.shots(), result.summary()


# --- printing ----------------------------------------------------------------------------------
