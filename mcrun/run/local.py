"""The local executor: a run's chunks on this machine's threads, into one shots.parquet.

``run_scenario`` streams the chunks of the run's ``plan.Plan`` (every point's sample indices
in fixed-size chunks) through a pipeline: ``sampling.sample`` draws the chunk's inputs (which
depend only on the scenario, the seed and the sample index, so neither the chunk size nor the
thread count changes a number), ``simulate_batch`` runs them in parallel into a preallocated
buffer, ``stats.PointStats`` folds them into its streaming sums, and ``output.ShotsWriter``
appends them to shots.parquet as one row group. Memory is one chunk, whatever the number of
shots. After the last chunk the percentiles are computed exactly from shots.parquet
(``plan.summary_rows``), summary.parquet is written, and the temporary folder is renamed into
place.

The command line: ``mcrun run``, ``mcrun validate``, ``mcrun scenarios`` (``register``) and
``mcrun replay`` (``mcrun.run.replay``). The default output folder of ``mcrun run`` is
``runs/<scenario name>-<seed>`` under the current folder.
"""

import argparse
import json
import math
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numba
import numpy as np
import pyarrow as pa
import pyarrow.parquet as pq

from mcrun.api import InputError
from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import N_INPUT, N_OUTCOME
from mcrun.results import output, stats
from mcrun.run import plan, sampling
from mcrun.run import scenario as scenario_module
from mcrun.units import UnitError

_INTERRUPTED = "mcrun: interrupted: the run was stopped and nothing was written"


def _check_threads(threads):
    if threads is None:
        return None
    most = numba.config.NUMBA_NUM_THREADS
    threads = plan.positive_int(threads, "threads")
    if threads > most:
        raise InputError(f"threads must be within [1, {most}] on this machine, got {threads}")
    return threads


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
    if out_dir is None:
        out_dir = plan.default_out_dir(the_plan.scenario, the_plan.seed)
    out_dir = Path(out_dir)
    if not ignore_disk_space:
        plan.check_disk_space(the_plan, out_dir)
    points = the_plan.points

    previous_threads = numba.get_num_threads()
    if threads is not None:
        numba.set_num_threads(threads)
    # Compile (or load from the cache) before the clock starts: the rate is the run's.
    simulate_batch(np.empty((0, N_INPUT), order="F"))
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
            )
            traj_writer = None
            if the_plan.trajectories_every is not None:
                traj_writer = output.TrajectoryWriter(
                    folder.file(output.TRAJECTORIES_FILE),
                    plan.file_metadata(provenance, "trajectories"),
                )
            try:
                point_stats = _stream(the_plan, shots_writer, traj_writer, progress)
            except BaseException:
                shots_writer.abort()
                if traj_writer is not None:
                    traj_writer.abort()
                raise
            shots_writer.close(plan.file_metadata(provenance, "shots", started))
            # One open file for every point: its footer lists every row group of the run; and
            # one cache, for the points that share a row group.
            cache = {}
            with pq.ParquetFile(folder.file(output.SHOTS_FILE)) as shots_file:
                rows = plan.summary_rows(
                    points,
                    point_stats,
                    lambda point: stats.ShotsColumns(
                        shots_file,
                        shots_writer.row_groups.get(point, []),
                        point,
                        cache,
                        the_plan.chunk_size,
                    ),
                    budget_bytes,
                )
            output.write_table(
                folder.file(output.SUMMARY_FILE),
                rows,
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


def _stream(the_plan, shots_writer, traj_writer, progress):
    """The chunked loop; returns the PointStats of every point."""
    from tqdm import tqdm

    show = bool(progress) and sys.stderr.isatty()
    scenario, points, n = the_plan.scenario, the_plan.points, the_plan.n
    chunk_size, every = the_plan.chunk_size, the_plan.trajectories_every
    # A pipeline of three threads: while the kernel simulates a chunk (on every core, without
    # the GIL), one thread samples the next chunk and another adds the chunk before to the
    # statistics and writes it to Parquet (numpy and pyarrow release the GIL too). The
    # statistics take the chunks in order, so they do not depend on the timing. Two output
    # buffers, taken in turn by the full chunks (the last chunk of a point gets its own).
    full = n >= chunk_size
    buffers = [np.empty((chunk_size, N_OUTCOME), order="F") if full else None for _ in range(2)]
    all_stats = [stats.PointStats(drivers) for drivers in the_plan.drivers]
    chunks = the_plan.chunks()

    def finish(point_stats, point, start, sampled, out):
        point_stats.update(out, sampled)
        shots_writer.write(point, start, sampled, out)

    writing = None  # the statistics and the write of the chunk before
    with (
        ThreadPoolExecutor(max_workers=1) as sampler,
        ThreadPoolExecutor(max_workers=1) as writer,
        tqdm(
            total=n * len(points), unit="shot", unit_scale=True, disable=not show, smoothing=0.1
        ) as bar,
    ):

        def sample_next():
            chunk = next(chunks, None)
            if chunk is None:
                return None, None
            point = points[chunk.point]
            args = (scenario, point, chunk.start, chunk.stop, the_plan.input_names)
            return chunk, sampler.submit(sampling.sample, *args)

        following, sampling_next = sample_next()
        k = 0
        while following is not None:
            _, point, start, stop = following
            if len(points) > 1 and start == 0:
                bar.set_description(points[point].label or f"point {point}")
            inputs, sampled = sampling_next.result()
            following, sampling_next = sample_next()
            out = buffers[k % 2] if stop - start == chunk_size else None
            out = simulate_batch(inputs, out)
            if writing is not None:
                writing.result()  # frees the other buffer; raises what the write raised
            writing = writer.submit(finish, all_stats[point], point, start, sampled, out)
            if traj_writer is not None:
                plan.add_trajectories(traj_writer, inputs, point, start, stop, every)
                traj_writer.flush()
            bar.update(stop - start)
            k += 1
        if writing is not None:
            writing.result()
    return all_stats


def run_dataframes(path_or_scenario, n=None, seed=None, **kwargs):
    """Run a scenario into a temporary folder and return (shots, summary) DataFrames."""
    import tempfile

    kwargs.setdefault("progress", False)
    with tempfile.TemporaryDirectory(prefix="mcrun-") as tmp:
        result = run_scenario(path_or_scenario, n=n, seed=seed, out_dir=Path(tmp) / "run", **kwargs)
        return result.shots(), result.summary()


# --- printing ----------------------------------------------------------------------------------


def _fmt(value, spec=".1f"):
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    return format(float(value) + 0.0, spec)


def _mean_sd(row, name, spec=".1f"):
    return f"{_fmt(row[f'{name}_mean'], spec)} ± {_fmt(row[f'{name}_std'], spec)}"


# The points a terminal shows of a run or a scenario; a larger sweep's are all in its files.
SHOWN_POINTS = 40


def _more_points(total, shown, where):
    """The line that says how many points were not shown, and where they are."""
    return f"... and {total - shown:,} more points ({where})"


def format_summary(summary, top=3):
    """The summary as an aligned text table, one line per point, then the variance drivers;
    the first SHOWN_POINTS points of a larger sweep."""
    total = len(summary)
    summary = summary.iloc[:SHOWN_POINTS]
    header = [
        "point",
        "label",
        "ok/shots",
        "carry_m",
        "total_m",
        "final_y_m",
        "ellipse95_m",
        "r50_m",
        "r95_m",
    ]
    lines = [header]
    for row in summary.to_dict("records"):
        lines.append(
            [
                str(row["point"]),
                row["label"] or "-",
                f"{row['n_ok']}/{row['n_shots']}",
                _mean_sd(row, "carry_m"),
                _mean_sd(row, "total_m"),
                _mean_sd(row, "final_y_m"),
                f"{_fmt(row['ellipse95_semi_major_m'])} x {_fmt(row['ellipse95_semi_minor_m'])}"
                f" @ {_fmt(row['ellipse95_angle_deg'], '.0f')} deg",
                _fmt(row["distance_r50_m"]),
                _fmt(row["distance_r95_m"]),
            ]
        )
    widths = [max(len(line[k]) for line in lines) for k in range(len(header))]
    text = [
        "  ".join(cell.ljust(w) for cell, w in zip(line, widths, strict=True)).rstrip()
        for line in lines
    ]
    for row in summary.to_dict("records"):
        for y in (*stats.DRIVEN, "run_m"):
            prefix = f"{y}_share_"
            shares = {
                k[len(prefix) :]: v
                for k, v in row.items()
                if k.startswith(prefix) and isinstance(v, float) and math.isfinite(v)
            }
            if not shares:
                continue
            best = sorted(shares.items(), key=lambda kv: -kv[1])[:top]
            parts = ", ".join(f"{k} {100 * v:.0f}%" for k, v in best)
            if y == "run_m":
                text.append(f"point {row['point']}: run_m explained alone by {parts}")
            else:
                text.append(
                    f"point {row['point']}: variance of {y} from {parts} "
                    f"(R^2 {_fmt(row[f'{y}_r2'], '.2f')})"
                )
    if total > len(summary):
        text.append(_more_points(total, len(summary), "every point is in summary.parquet"))
    return "\n".join(text)


def _json_safe(value):
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


# --- command line ------------------------------------------------------------------------------


def _error(err):
    print("mcrun: error: " + " ".join(str(err).split()), file=sys.stderr)
    return 2


def _say(line):
    print(line, file=sys.stderr, flush=True)


def _interrupted():
    print(_INTERRUPTED, file=sys.stderr)
    return 130


def _dask_backend(args):
    """Whether ``mcrun run`` was asked for the Dask backend (``mcrun.run.distributed``)."""
    names = ("dask", "scheduler", "scheduler_file", "workers")
    return any(getattr(args, name, None) is not None for name in names)


def _cmd_run(args):
    announce = None if args.quiet else _say
    try:
        if _dask_backend(args):
            from mcrun.run import distributed

            result = distributed.run_from_args(args, announce)
        else:
            result = run_scenario(
                args.scenario,
                n=args.n,
                seed=args.seed,
                out_dir=args.output,
                threads=args.threads,
                chunk_size=args.chunk_size,
                trajectories_every=args.trajectories,
                progress=not args.quiet,
                force=args.force,
                ignore_disk_space=args.ignore_disk_space,
                announce=announce,
            )
    except (InputError, UnitError) as err:
        return _error(err)
    except KeyboardInterrupt:
        return _interrupted()
    summary = result.summary()
    if args.json:
        records = [{k: _json_safe(v) for k, v in r.items()} for r in summary.to_dict("records")]
        print(
            json.dumps(
                {
                    "out_dir": str(result.out_dir),
                    "files": [str(p) for p in result.paths],
                    "n": result.n,
                    "seed": result.seed,
                    "threads": result.threads,
                    "elapsed_s": result.elapsed_s,
                    "summary": records,
                },
                allow_nan=False,
            )
        )
        return 0
    print(format_summary(summary))
    shots = result.n * result.points
    rate = shots / result.elapsed_s if result.elapsed_s > 0 else math.inf
    threads = f"{result.threads} thread" + ("s" if result.threads != 1 else "")
    where = getattr(result, "where", threads)
    print(f"{shots} shots in {result.elapsed_s:.1f} s ({rate:,.0f} shots/s on {where}); wrote:")
    for path in result.paths:
        print(f"  {path}")
    return 0


def describe(scenario):
    """A short description of a scenario's points (what ``mcrun validate`` prints)."""
    lines = [f"scenario {scenario.name} ({scenario.path})"]
    if scenario.question:
        lines.append(f"question: {scenario.question}")
    lines.append(
        f"{len(scenario.points)} point(s) x {scenario.shots} shots, seed {scenario.seed}, "
        f"block size {scenario.block_size}"
    )
    names = sampling.sampled_columns(scenario)
    for point in scenario.points[:SHOWN_POINTS]:
        varying = plan.driver_inputs(point, names)
        model = point.params["models.aero"]
        label = point.label or "(single point)"
        lines.append(
            f"  {point.index}: {label}: aero {model}; sampled: "
            + (", ".join(varying) if varying else "none (every input constant)")
        )
    if len(scenario.points) > SHOWN_POINTS:
        lines.append("  " + _more_points(len(scenario.points), SHOWN_POINTS, "in the sweep"))
    return "\n".join(lines)


def _cmd_validate(args):
    try:
        scenario = scenario_module.load(args.scenario)
        text = describe(scenario)
    except (InputError, UnitError) as err:
        return _error(err)
    print(text)
    return 0


def _cmd_scenarios(args):
    try:
        folder = Path(args.dir) if args.dir else scenario_module.library_folder()
        if not folder.is_dir():
            raise InputError(f"--dir {folder}: not a folder")
        entries = scenario_module.list_library(folder)
    except (InputError, UnitError) as err:
        return _error(err)
    if args.json:
        print(
            json.dumps(
                [{"name": name, "question": q, "path": str(path)} for name, path, q in entries]
            )
        )
        return 0
    if not entries:
        print(f"no scenarios in {folder}")
        return 0
    width = max(len(name) for name, _, _ in entries)
    for name, _, question in entries:
        print(f"{name:<{width}}  {question}".rstrip())
    return 0


def _add_dask_options(p):
    """The Dask backend's options of ``mcrun run`` (``mcrun.run.distributed``)."""
    group = p.add_argument_group(
        "Dask backend (pip install 'mcrun[dask]')",
        "Run the chunks as tasks on a Dask cluster: the same shots and summary as the local "
        "engine, bit for bit; shots are written as a dataset, shots/part-NNNNN.parquet, to a "
        "folder or fsspec URL (-o s3://...) that the client and every worker reach.",
    )
    where = group.add_mutually_exclusive_group()
    where.add_argument(
        "--dask",
        choices=["local"],
        help="a LocalCluster on this machine: --workers processes of one thread each",
    )
    where.add_argument(
        "--scheduler", metavar="ADDRESS", help="an existing cluster, e.g. tcp://HOST:8786"
    )
    where.add_argument(
        "--scheduler-file", metavar="PATH", help="an existing cluster's scheduler file"
    )
    group.add_argument(
        "--workers", metavar="N", help="worker processes of --dask local (default: the cores)"
    )


def register(subparsers):
    """Add ``run``, ``validate``, ``scenarios`` and ``replay`` to an argparse subparsers."""
    p = subparsers.add_parser(
        "run",
        help="run a Monte Carlo scenario and write shots, summary (and trajectories) Parquet",
        description="Run every point of a scenario (a TOML file, see 'mcrun scenarios') with "
        "N shots each, and write a folder with shots.parquet (one row per shot), "
        "summary.parquet (one row per point: dispersion statistics and what drives it) and "
        "optionally trajectories.parquet. The same seed gives the same shots, bit for bit, "
        "whatever the thread count and chunk size. Ctrl-C stops cleanly and writes nothing.",
        allow_abbrev=False,
    )
    p.add_argument(
        "scenario", metavar="SCENARIO", help="scenario file (.toml), or a library scenario's name"
    )
    p.add_argument("-n", metavar="N", help="shots per point (default: the scenario's); 1e6 works")
    p.add_argument("--seed", metavar="S", help="random seed (default: the scenario's)")
    p.add_argument(
        "-o",
        "--output",
        metavar="DIR",
        help="output folder (default runs/<scenario name>-<seed>); refused if it holds a run, "
        "unless --force",
    )
    p.add_argument("--force", action="store_true", help="replace an existing run folder")
    p.add_argument("--threads", metavar="T", help="Numba threads (default: all cores)")
    p.add_argument(
        "--trajectories", metavar="K", help="also write the path of every K-th shot of each point"
    )
    p.add_argument(
        "--chunk-size",
        metavar="C",
        default=plan.DEFAULT_CHUNK_SIZE,
        help=f"shots per chunk and row group (default {plan.DEFAULT_CHUNK_SIZE}); results do not "
        "depend on it",
    )
    p.add_argument(
        "--ignore-disk-space",
        action="store_true",
        help="run even when the estimated size of the output is not under the free space of "
        "its disk (by default such a run is refused before it starts)",
    )
    p.add_argument(
        "--quiet", action="store_true", help="no progress bar, and no line saying the run's size"
    )
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    _add_dask_options(p)
    p.set_defaults(func=_cmd_run)

    p = subparsers.add_parser(
        "validate",
        help="check a scenario file and describe its points",
        description="Load and check a scenario; print its points and what each samples. "
        "Exit 0 when valid, else one line naming the file, the key and what is allowed, exit 2.",
        allow_abbrev=False,
    )
    p.add_argument(
        "scenario", metavar="SCENARIO", help="scenario file (.toml), or a library scenario's name"
    )
    p.set_defaults(func=_cmd_validate)

    p = subparsers.add_parser(
        "scenarios",
        help="list the scenario library, with the question each one answers",
        allow_abbrev=False,
    )
    p.add_argument(
        "--dir",
        metavar="DIR",
        help=f"library folder (default: ${scenario_module.ENV_LIBRARY}, else the scenarios/ "
        "folder beside the package)",
    )
    p.add_argument("--json", action="store_true", help="print JSON instead")
    p.set_defaults(func=_cmd_scenarios)

    from mcrun.run import replay

    replay.register(subparsers)


def main(argv=None):
    """``run``, ``validate``, ``scenarios`` and ``replay`` alone (for testing without mcrun.cli)."""
    parser = argparse.ArgumentParser(prog="mcrun", allow_abbrev=False)
    register(parser.add_subparsers(dest="command", required=True))
    args = parser.parse_args(argv)
    return args.func(args)
