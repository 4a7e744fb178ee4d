"""Running a scenario: sample, simulate, reduce and write, chunk by chunk.

``run_scenario`` streams every point of a scenario through fixed-size chunks of sample indices:
``sampling.sample`` draws the chunk's inputs (which depend only on the scenario, the seed and
the sample index, so neither the chunk size nor the thread count changes a number),
``batch.simulate_batch`` runs them in parallel into a preallocated buffer, ``stats.PointStats``
folds them into its streaming sums, and ``output.ShotsWriter`` appends them to shots.parquet as
one row group. Memory is one chunk, whatever the number of shots. After the last chunk the
percentiles are computed exactly from shots.parquet (``stats.summarise``), summary.parquet is
written, and the temporary folder is renamed into place.

The default output folder is ``runs/<scenario name>-<seed>`` under the current folder. The
command line over it, ``mcrun run``, is ``mcrun.cli.run``.
"""

import copy
import dataclasses
import math
import shutil
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path

import numba
import numpy as np
import pandas as pd
import pyarrow as pa
import pyarrow.parquet as pq

from mcrun.api import InputError
from mcrun.engine.backend import simulate_batch, simulate_traced
from mcrun.engine.schema import N_INPUT, N_OUTCOME, OUTCOME_FIELDS
from mcrun.results import output, stats
from mcrun.run import sampling
from mcrun.run import scenario as scenario_module
from mcrun.units import shown

DEFAULT_CHUNK_SIZE = 65536
RUNS_FOLDER = Path("runs")

# The sampled column of each parameter a user can give a distribution (scenario.PARAMETERS key
# paths): the candidate drivers of the variance. Derived columns (the ball launch of a club
# delivery, the air density, the wind components) are not candidates: their parameters are.
DRIVER_COLUMNS = {
    "launch.ball_speed": "ball_speed_mps",
    "launch.launch_angle": "launch_angle_deg",
    "launch.spin": "spin_radps",
    "launch.azimuth": "azimuth_deg",
    "launch.spin_axis": "spin_axis_deg",
    "club.speed": "club_speed_mps",
    "club.mass": "club_mass_kg",
    "club.loft": "loft_deg",
    "club.azimuth": "azimuth_deg",
    "club.spin_axis": "spin_axis_deg",
    "turf.mu": "mu",
    "turf.softness": "softness",
    "turf.restitution": "restitution",
    "turf.rho_g": "rho_g",
    "turf.stimp": "stimp_m",
    "turf.critical_height": "critical_height_m",
    "turf.slope": "slope_deg",
    "turf.fall_line": "fall_line_deg",
    "weather.wind_speed": "wind_speed_mps",
    "weather.wind_direction": "wind_direction_deg",
    "weather.temperature": "temperature_c",
    "weather.altitude": "altitude_m",
    "weather.pressure": "pressure_pa",
    "weather.humidity": "relative_humidity",
    "models.cd_scale": "cd_scale",
    "models.cl_scale": "cl_scale",
}
# A resampled launch-monitor file varies the launch quantities it holds or jitters.
_FILE_DRIVERS = {
    "ball_speed": "ball_speed_mps",
    "launch_angle": "launch_angle_deg",
    "spin": "spin_radps",
    "spin_axis": "spin_axis_deg",
    "azimuth": "azimuth_deg",
}

# How the summary is computed, recorded in summary.parquet's metadata.
SUMMARY_CONVENTIONS = {
    "statistics_over": "shots with status ok; the others are counted in n_<status>",
    "ddof": stats.DDOF,
    "percentile_method": "linear interpolation between order statistics (pandas' default)",
    "ellipse": "semi-axes sqrt(eigenvalue * -2 ln(1 - p)) of the final position's covariance; "
    "angle of the major axis from the target line towards the right, in [0, 180) deg",
    "target": "the scenario's target, else the point's mean final position",
    "drivers": "standardised regression coefficients (src) on the sampled inputs that vary, "
    "share = src^2; run_m: correlation with each landing quantity, share = corr^2",
}


@dataclass
class RunResult:
    """What a run wrote: the folder, its files, and how it was run."""

    out_dir: Path
    shots_path: Path
    summary_path: Path
    trajectories_path: Path | None
    n: int
    seed: int
    points: int
    elapsed_s: float
    threads: int

    @property
    def paths(self):
        """The files (or, for a Dask run, the folders) the run wrote."""
        optional = [] if self.trajectories_path is None else [self.trajectories_path]
        return [self.shots_path, self.summary_path, *optional]

    def shots(self, columns=None):
        """shots.parquet as a pandas DataFrame (``columns``: a subset to read)."""
        return pd.read_parquet(self.shots_path, columns=columns)

    def summary(self):
        """summary.parquet as a pandas DataFrame, one row per point."""
        return pd.read_parquet(self.summary_path)

    def trajectories(self):
        """trajectories.parquet as a pandas DataFrame (None when not asked for)."""
        return None if self.trajectories_path is None else pd.read_parquet(self.trajectories_path)


# --- checks ------------------------------------------------------------------------------------


def _positive_int(value, name, minimum=1):
    """An integer >= minimum from an int, a float with an integral value or a text ("1e6")."""
    wrong = InputError(f"{name} must be an integer >= {minimum}, got {shown(value)}")
    if isinstance(value, bool):
        raise wrong
    try:
        number = float(value.strip().replace("_", "") if isinstance(value, str) else value)
    except (TypeError, ValueError):
        raise wrong from None
    if not (math.isfinite(number) and number == int(number) and number >= minimum):
        raise wrong
    return int(number)


def _check_threads(threads):
    if threads is None:
        return None
    most = numba.config.NUMBA_NUM_THREADS
    threads = _positive_int(threads, "threads")
    if threads > most:
        raise InputError(f"threads must be within [1, {most}] on this machine, got {threads}")
    return threads


def _load(path_or_scenario):
    if isinstance(path_or_scenario, str | Path):
        return scenario_module.load(path_or_scenario)
    return path_or_scenario


def _with_seed(scenario, seed):
    """The scenario with another seed (the sampler reads ``scenario.seed``)."""
    if dataclasses.is_dataclass(scenario):
        return dataclasses.replace(scenario, seed=seed)
    other = copy.copy(scenario)
    other.seed = seed
    return other


def default_out_dir(scenario, seed):
    """``runs/<scenario name>-<seed>``, relative to the current folder."""
    return RUNS_FOLDER / f"{scenario.name}-{seed}"


def driver_inputs(point, columns):
    """The sampled columns of ``point`` that a distribution varies (the variance drivers)."""
    names = []
    for key, spec in point.params.items():
        if key == "launch.file":
            names += [_FILE_DRIVERS[q] for q in (*spec.columns, *spec.jitter)]
        elif key in DRIVER_COLUMNS and not getattr(spec, "is_constant", True):
            names.append(DRIVER_COLUMNS[key])
    names = set(names)
    return [name for name in columns if name in names]


def _model_names(points):
    """Names of the aerodynamic models and wind profiles used: choices, so the same for every
    sample of a point, read from its parameters (no sampling)."""
    models = sorted({p.params["models.aero"] for p in points})
    profiles = sorted({p.params["weather.wind_profile"] for p in points})
    return {"aero": models, "bounce": ["penner2002"], "wind_profile": profiles}


def _sweep_columns(points):
    """{key path: [value per point]}: numbers as floats, anything else as text."""
    keys = list(dict.fromkeys(k for p in points for k in (p.sweep or {})))
    columns = {}
    for key in keys:
        values = [(p.sweep or {}).get(key) for p in points]
        numeric = all(isinstance(v, int | float) and not isinstance(v, bool) for v in values)
        columns[key] = [float(v) for v in values] if numeric else [str(v) for v in values]
    return columns


# --- the plan: what a run will be, said before it starts ---------------------------------------

# Bytes of Parquet per shot, an upper bound: shots.parquet of pga-driver (every launch input
# drawn) measured 150 B a shot at 1e6 shots in chunks of 65,536; a scenario that draws more
# inputs (wind, temperature, turf) writes up to about 250 B. The bound takes every column as a
# drawn float64 that zstd cannot compress: 8 B per column and shot.
BYTES_PER_COLUMN_SHOT = 8
# Each row group adds its column chunks' page headers and footer entries: about 365 B per
# column (measured: a 100 x 100 sweep of 10 shots a point, one row group a point, wrote
# 179 MB, 17.9 kB a row group of 49 columns), bounded at 500. Every row group but the last
# holds output.ROW_GROUP_ROWS shots or more (``output.ShotsWriter``).
BYTES_PER_ROW_GROUP_COLUMN = 500
# A trajectory is recorded every 10 ms to rest (a drive: about 1,500 rows of 7 columns, 35 kB
# in Parquet); the bound is that of a 30 s shot, 3,000 rows at 40 B.
BYTES_PER_TRAJECTORY = 120_000
# summary.parquet: about 60 kB for one point (its metadata holds the scenario and the schema
# of about 120 columns) and 1.5 kB per further point (measured on 4 and 100 points).
BYTES_SUMMARY = 100_000
BYTES_SUMMARY_POINT = 2_000
# Time: end to end about 4e5 shots/s on two cores (README, Performance: 451,000 for 1e7
# pga-driver shots), and per point about 1.7 ms of Python (sampling its block, building its
# table and its summary row: a 100 x 100 sweep of 10 shots a point ran in 17 s).
SHOTS_PER_S = 4e5
SECONDS_PER_POINT = 2e-3
# The columns of shots.parquet besides the sampled inputs: point, group, label, shot, the
# outcome fields and status_name.
_FIXED_COLUMNS = 5 + len(OUTCOME_FIELDS)


@dataclass(frozen=True)
class Plan:
    """What a run will be: its points, shots per point, total shots, an estimate of its time
    (s) and of the Parquet it writes (bytes, an upper bound)."""

    points: int
    n: int
    shots: int
    seconds: float
    bytes: int

    def line(self):
        """One line for the terminal, e.g. ``mcrun: 4 points x 10 shots = 40 shots; ...``."""
        points = f"{self.points:,} point" + ("s" if self.points != 1 else "")
        return (
            f"mcrun: {points} x {self.n:,} shots = {self.shots:,} shots; "
            f"{'under' if self.seconds < 0.05 else 'about'} {duration_text(self.seconds)} of "
            f"simulation, about {size_text(self.bytes)} of Parquet"
        )


def size_text(n_bytes):
    """A size in B, kB, MB, GB, TB or PB (powers of 1000), two or three digits."""
    value = float(n_bytes)
    for unit in ("B", "kB", "MB", "GB", "TB"):
        if value < 999.5:
            return f"{value:.0f} {unit}" if unit == "B" or value >= 9.95 else f"{value:.1f} {unit}"
        value /= 1000.0
    return f"{value:,.0f} PB"


def duration_text(seconds):
    """A duration in s, min, h or days."""
    for unit, size in (("days", 86400.0), ("h", 3600.0), ("min", 60.0)):
        if seconds >= 2 * size:
            return f"{seconds / size:,.0f} {unit}"
    if seconds < 0.05:
        return "0.1 s"
    return f"{seconds:.1f} s" if seconds < 10 else f"{seconds:.0f} s"


def plan(scenario, n, chunk_size=DEFAULT_CHUNK_SIZE, trajectories_every=None, columns=None):
    """The ``Plan`` of a run of ``n`` shots per point of a loaded scenario.

    ``columns``: the run's sampled columns, when known (``run_columns``). The size is an upper
    bound (constants above); the time assumes the 2-core machine of the benchmarks.
    """
    points = len(scenario.points)
    shots = points * n
    if columns is None:
        columns, _ = run_columns(scenario)
    width = len(columns) + _FIXED_COLUMNS
    row_groups = shots // output.ROW_GROUP_ROWS + 1
    size = shots * width * BYTES_PER_COLUMN_SHOT + row_groups * width * BYTES_PER_ROW_GROUP_COLUMN
    size += BYTES_SUMMARY + points * BYTES_SUMMARY_POINT
    if trajectories_every is not None:
        size += points * -(-n // trajectories_every) * BYTES_PER_TRAJECTORY
    seconds = shots / SHOTS_PER_S + points * SECONDS_PER_POINT
    return Plan(points, n, shots, seconds, size)


def free_space(out_dir):
    """(folder, free bytes) of the nearest existing folder of ``out_dir`` (itself or a parent),
    where the run will be written."""
    folder = Path(out_dir).absolute()
    while not folder.exists() and folder.parent != folder:
        folder = folder.parent
    return folder, shutil.disk_usage(folder).free


def check_disk_space(the_plan, out_dir):
    """Refuse (OutputError) a run whose estimated size is not under the free space."""
    folder, free = free_space(out_dir)
    if the_plan.bytes >= free:
        raise output.OutputError(
            f"the run would write about {size_text(the_plan.bytes)} of Parquet "
            f"({the_plan.shots:,} shots) but {folder} has {size_text(free)} free: lower -n, "
            "choose another folder with -o, or pass --ignore-disk-space to run anyway"
        )


# --- the run -----------------------------------------------------------------------------------


def _trajectories(writer, inputs, point, start, stop, every, buffer):
    """Paths of the shots start <= i < stop with i % every == 0 (rows of ``inputs``)."""
    first = -(-start // every) * every
    for i in range(first, stop, every):
        _, path = simulate_traced(inputs[i - start : i - start + 1])
        writer.add(point, i, path)
    return buffer


def describe_run(scenario, seed, n, points):
    """The provenance every backend records: the scenario, its seed and size, its points and
    their models."""
    return {
        "scenario_name": scenario.name,
        "scenario_path": str(scenario.path),
        "scenario_text": scenario.text,
        "seed": seed,
        "n": n,
        "block_size": scenario.block_size,
        "points": [p.label for p in points],
        "groups": [p.group for p in points],
        "models": _model_names(points),
    }


def run_columns(scenario):
    """The sampled columns of a run (the same for every point), and those that hold integers.

    Found once from the scenario's points, without sampling: ``sampling.sampled_columns``
    looks at every point, so it is not asked again per point or per chunk.
    """
    names = list(sampling.sampled_columns(scenario))
    integers = [n for n in names if np.issubdtype(sampling.column_dtype(n), np.integer)]
    return names, integers


def run_scenario(
    path_or_scenario,
    n=None,
    seed=None,
    out_dir=None,
    threads=None,
    chunk_size=DEFAULT_CHUNK_SIZE,
    trajectories_every=None,
    progress=True,
    force=False,
    budget_bytes=stats.DEFAULT_BUDGET_BYTES,
    ignore_disk_space=False,
    announce=None,
):
    """Run a scenario and write its folder; return a RunResult.

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
        Run even when the estimated size (``plan``) is not under the free space of the output's
        disk.
    announce : callable, optional
        Called with the plan's line (``Plan.line``) before the run starts.

    Raises
    ------
    InputError
        (ScenarioError, OutputError) on a bad scenario, argument or output folder, or a run
        that would not fit on the disk, before anything is written. KeyboardInterrupt is
        re-raised after the temporary files are removed.
    """
    scenario = _load(path_or_scenario)
    n = _positive_int(scenario.shots if n is None else n, "n")
    seed = _positive_int(scenario.seed if seed is None else seed, "seed", minimum=0)
    chunk_size = _positive_int(chunk_size, "chunk_size")
    if trajectories_every is not None:
        trajectories_every = _positive_int(trajectories_every, "trajectories_every")
    threads = _check_threads(threads)
    if seed != scenario.seed:
        scenario = _with_seed(scenario, seed)
    points = list(scenario.points)
    out_dir = Path(default_out_dir(scenario, seed) if out_dir is None else out_dir)

    input_names, integer_columns = run_columns(scenario)
    the_plan = plan(scenario, n, chunk_size, trajectories_every, input_names)
    if not ignore_disk_space:
        check_disk_space(the_plan, out_dir)
    input_types = dict.fromkeys(integer_columns, pa.int64())
    drivers_per_point = [driver_inputs(point, input_names) for point in points]

    previous_threads = numba.get_num_threads()
    if threads is not None:
        numba.set_num_threads(threads)
    # Compile (or load from the cache) before the clock starts: the rate is the run's.
    simulate_batch(np.empty((0, N_INPUT), order="F"))
    started = time.perf_counter()
    base = {
        "format_version": 1,
        "backend": "local",
        **describe_run(scenario, seed, n, points),
        "versions": output.versions(),
        "threads": numba.get_num_threads(),
        "chunk_size": chunk_size,
        "trajectories_every": trajectories_every,
        "start_time_utc": datetime.now(UTC).isoformat(timespec="seconds"),
    }

    def metadata(file):
        return output.encode_provenance(
            {**base, "file": file, "elapsed_s": round(time.perf_counter() - started, 3)}
        )

    try:
        with output.AtomicFolder(out_dir, force=force) as folder:
            if announce is not None:  # once the output folder is accepted
                announce(the_plan.line())
            shots_writer = output.ShotsWriter(
                folder.file(output.SHOTS_FILE),
                input_names,
                [p.group for p in points],
                [p.label for p in points],
                output.encode_provenance({**base, "file": "shots"}),
                input_types,
            )
            traj_writer = None
            if trajectories_every is not None:
                traj_writer = output.TrajectoryWriter(
                    folder.file(output.TRAJECTORIES_FILE),
                    output.encode_provenance({**base, "file": "trajectories"}),
                )
            try:
                point_stats = _stream(
                    scenario,
                    points,
                    input_names,
                    drivers_per_point,
                    n,
                    chunk_size,
                    shots_writer,
                    traj_writer,
                    trajectories_every,
                    progress,
                )
            except BaseException:
                shots_writer.abort()
                if traj_writer is not None:
                    traj_writer.abort()
                raise
            shots_writer.close(metadata("shots"))
            rows = _summary_rows(
                points,
                point_stats,
                folder.file(output.SHOTS_FILE),
                shots_writer.row_groups,
                chunk_size,
                budget_bytes,
            )
            output.write_table(
                folder.file(output.SUMMARY_FILE),
                rows,
                {**metadata("summary"), **output.encode_provenance(SUMMARY_CONVENTIONS)},
            )
            if traj_writer is not None:
                traj_writer.close(metadata("trajectories"))
            folder.commit()
    finally:
        numba.set_num_threads(previous_threads)
    elapsed = time.perf_counter() - started
    return RunResult(
        out_dir=out_dir,
        shots_path=out_dir / output.SHOTS_FILE,
        summary_path=out_dir / output.SUMMARY_FILE,
        trajectories_path=None
        if trajectories_every is None
        else out_dir / output.TRAJECTORIES_FILE,
        n=n,
        seed=seed,
        points=len(points),
        elapsed_s=elapsed,
        threads=base["threads"],
    )


def _stream(
    scenario,
    points,
    input_names,
    drivers_per_point,
    n,
    chunk_size,
    shots_writer,
    traj_writer,
    every,
    progress,
):
    """The chunked loop; returns the PointStats of every point."""
    from tqdm import tqdm

    show = bool(progress) and sys.stderr.isatty()
    # A pipeline of three threads: while the kernel simulates a chunk (on every core, without
    # the GIL), one thread samples the next chunk and another adds the chunk before to the
    # statistics and writes it to Parquet (numpy and pyarrow release the GIL too). The
    # statistics take the chunks in order, so they do not depend on the timing. Two output
    # buffers, taken in turn by the full chunks (the last chunk of a point gets its own).
    full = n >= chunk_size
    buffers = [np.empty((chunk_size, N_OUTCOME), order="F") if full else None for _ in range(2)]
    traj_buffer = np.empty((4096, 5))
    all_stats = [stats.PointStats(drivers) for drivers in drivers_per_point]
    # The chunks one after the other, never as a list: n may be huge.
    chunks = (
        (j, point, start, min(start + chunk_size, n))
        for j, point in enumerate(points)
        for start in range(0, n, chunk_size)
    )

    def finish(point_stats, point, start, sampled, out):
        point_stats.update(out, sampled)
        shots_writer.write(point.index, start, sampled, out)

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
            return chunk, sampler.submit(sampling.sample, scenario, *chunk[1:], input_names)

        following, sampling_next = sample_next()
        k = 0
        while following is not None:
            j, point, start, stop = following
            if len(points) > 1 and start == 0:
                bar.set_description(point.label or f"point {point.index}")
            inputs, sampled = sampling_next.result()
            following, sampling_next = sample_next()
            out = buffers[k % 2] if stop - start == chunk_size else None
            out = simulate_batch(inputs, out)
            if writing is not None:
                writing.result()  # frees the other buffer; raises what the write raised
            writing = writer.submit(finish, all_stats[j], point, start, sampled, out)
            if traj_writer is not None:
                traj_buffer = _trajectories(
                    traj_writer, inputs, point.index, start, stop, every, traj_buffer
                )
                traj_writer.flush()
            bar.update(stop - start)
            k += 1
        if writing is not None:
            writing.result()
    return all_stats


def _summary_rows(points, point_stats, shots_path, row_groups, chunk_size, budget_bytes):
    rows = []
    sweep = _sweep_columns(points)
    # One open file for every point: its footer lists every row group of the run; and one
    # cache, for the points that share a row group.
    cache = {}
    with pq.ParquetFile(shots_path) as shots_file:
        for point, one in zip(points, point_stats, strict=True):
            row = {"point": point.index, "group": point.group, "label": point.label}
            for key, values in sweep.items():
                row[key] = values[point.index]
            groups = row_groups.get(point.index, [])
            columns = stats.ShotsColumns(shots_file, groups, point.index, cache, chunk_size)
            row.update(
                stats.summarise(one, columns, target_m=point.target_m, budget_bytes=budget_bytes)
            )
            rows.append(row)
    return pd.DataFrame(rows)


def run_dataframes(path_or_scenario, n=None, seed=None, **kwargs):
    """Run a scenario into a temporary folder and return (shots, summary) DataFrames."""
    import tempfile

    kwargs.setdefault("progress", False)
    with tempfile.TemporaryDirectory(prefix="mcrun-") as tmp:
        result = run_scenario(path_or_scenario, n=n, seed=seed, out_dir=Path(tmp) / "run", **kwargs)
        return result.shots(), result.summary()
