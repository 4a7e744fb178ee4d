"""The plan of a run: what it will be, decided once, whichever executor runs it.

A run of a scenario is the same whether its chunks run on local threads (``mcrun.run.local``)
or as Dask tasks (``mcrun.run.distributed``); the executors differ only in how they execute the
chunks and write them. What they share is here, written once:

- the arguments checked and the scenario loaded with its seed (``plan``, which returns a
  ``Plan``: the sampled columns, the variance drivers of each point, and an estimate of the
  run's time and size, said in one line before it starts; ``check_disk_space`` refuses a run
  that would not fit);
- the chunks: every point's N sample indices cut into ranges of ``chunk_size`` (``Plan.chunks``),
  numbered point by point, and the shots of a chunk whose paths are recorded
  (``add_trajectories``);
- the provenance every file of the run records (``provenance``, ``file_metadata``), with the
  run's geometry (``mcrun.results.geometry``: the frame, tee, pin, aim and targets in every
  file, the hole's map in summary.parquet);
- the summary rows, from each point's streamed statistics and its shots wherever they were
  written (``summary_rows``, ``summary_metadata``);
- what a run wrote (``RunResult``).
"""

import copy
import dataclasses
import math
import os
import shutil
import time
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import NamedTuple

import numpy as np
import pandas as pd
import pyarrow as pa

from mcrun.engine.backend import simulate_batch, simulate_traced
from mcrun.engine.batch import general_flight as general_flight_of
from mcrun.engine.schema import HOLE_FIELDS, PLANE_FIELDS
from mcrun.engine.warmup import general, warm_up
from mcrun.putting.on_hole import map_of_hole
from mcrun.quantities import DRIVER_COLUMNS, InputError
from mcrun.results import geometry, output, reader, stats
from mcrun.results import on_hole as on_hole_results
from mcrun.run import sampling
from mcrun.run import scenario as scenario_module
from mcrun.run.scenario.specs import DEFAULT_BLOCK_SIZE
from mcrun.units import INEXACT, shown, whole_number, whole_numbers_allowed

DEFAULT_CHUNK_SIZE = 65536
# The paths a chunk traces at most where the chunk size is left at its default: a path takes
# some 180 kB in memory until it is written (``--trajectories 1`` held 3.6 GB for 20,000
# shots, all in one chunk). The shots do not depend on the chunk size.
MAX_PATHS_PER_CHUNK = 512
RUNS_FOLDER = Path("runs")

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
    "target": "the scenario's target, else on a hole its pin, else the point's mean final position",
    "drivers": "standardised regression coefficients (src) on the sampled inputs that vary, "
    "share = src^2; run_m: correlation with each landing quantity, share = corr^2",
}


# --- the arguments and the scenario ------------------------------------------------------------


def positive_int(value, name, minimum=1):
    """An integer from ``minimum`` to 2**63 - 1 (an int64) from an int, a float with an
    integral value (up to 2**53, beyond which a float is not one integer) or a text: digits,
    read exactly, or a number such as "1e6" (``units.whole_number``)."""
    wrong = InputError(f"{name} must be an integer >= {minimum}, got {shown(value)}")
    number, why = whole_number(value.strip() if isinstance(value, str) else value)
    if why == INEXACT:
        allowed = whole_numbers_allowed(minimum, inexact=True)
        raise InputError(f"{name} {shown(value)}: allowed: {allowed}")
    if why:
        raise InputError(f"{name} {shown(value)}: {why}")
    if number is None or number < minimum:
        raise wrong
    if number > 2**63 - 1:
        raise InputError(f"{name} must be an integer up to 2**63 - 1, got {shown(value)}")
    return number


def check_run_switches(announce=None, **switches):
    """Refuse a run's switch (``force``, ``progress``, ``ignore_disk_space``) that is not a
    bool (``force="no"`` replaced the run: any text is true) and an ``announce`` that cannot
    be called, before anything is written."""
    for name, value in switches.items():
        if not isinstance(value, bool | np.bool_):
            raise InputError(f"{name} {shown(value)}: allowed: True or False")
    if announce is not None and not callable(announce):
        raise InputError(f"announce {shown(announce)}: allowed: a function of the plan's line")


def with_seed(scenario, seed):
    """The scenario with another seed (the sampler reads ``scenario.seed``)."""
    if scenario.seed == seed:
        return scenario
    if dataclasses.is_dataclass(scenario):
        return dataclasses.replace(scenario, seed=seed)
    other = copy.copy(scenario)
    other.seed = seed
    return other


def default_out_dir(scenario, seed):
    """``runs/<scenario name>-<seed>``, relative to the current folder."""
    return RUNS_FOLDER / f"{scenario.name}-{seed}"


def run_columns(scenario):
    """The sampled columns of a run (the same for every point), and those that hold integers.

    Found once from the scenario's points, without sampling: ``sampling.sampled_columns``
    looks at every point, so it is not asked again per point or per chunk.
    """
    names = list(sampling.sampled_columns(scenario))
    integers = [n for n in names if np.issubdtype(sampling.column_dtype(n), np.integer)]
    return names, integers


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


# --- the plan: what a run will be, said before it starts ---------------------------------------

# Bytes of Parquet per shot, an upper bound: shots.parquet of pga-driver (every launch input
# drawn) measured 175 B a shot at 1e6 shots in chunks of 65,536 (LZ4); a scenario that draws more
# inputs (wind, temperature, turf) writes up to about 250 B. The bound takes every column as a
# drawn float64 that the codec cannot compress: 8 B per column and shot.
BYTES_PER_COLUMN_SHOT = 8
# Each row group adds its column chunks' page headers and footer entries: about 365 B per
# column (measured: a 100 x 100 sweep of 10 shots a point, one row group a point, wrote
# 179 MB, 17.9 kB a row group of 49 columns), bounded at 500. Every row group but the last
# holds output.ROW_GROUP_ROWS shots or more (``output.ShotsWriter``).
BYTES_PER_ROW_GROUP_COLUMN = 500
# A trajectory is recorded every 10 ms to rest (a drive: about 1,500 rows of 7 columns, 35 kB
# in Parquet; with the fairway's roll-out of the flight's calibration, about 15 kB); the bound
# is that of a 15 s shot, 1,500 rows at 40 B (a tour drive comes to rest on a fairway in 14-15 s).
BYTES_PER_TRAJECTORY = 60_000
# summary.parquet: about 60 kB for one point (its metadata holds the scenario and the schema
# of about 120 columns) and 1.5 kB per further point (measured on 4 and 100 points).
BYTES_SUMMARY = 100_000
BYTES_SUMMARY_POINT = 2_000
# Time: end to end about 4e5 shots/s on two cores (docs/performance.md: 451,000 for 1e7
# pga-driver shots), and per point about 1.7 ms of Python (sampling its block, building its
# table and its summary row: a 100 x 100 sweep of 10 shots a point ran in 17 s).
SHOTS_PER_S = 4e5
SECONDS_PER_POINT = 2e-3
# A chunk draws every block of ``scenario.block_size`` samples that it touches whole: a chunk
# smaller than a block, or a point of fewer shots, draws more samples than it flies, each about
# 0.15 us (2-core AMD EPYC, one thread, 2026-11-28: 40 chunks of one shot in blocks of
# 1,048,576 took 5.7 s with three normal inputs, 2.3 s with every input constant).
SECONDS_PER_DRAWN_SAMPLE = 1.5e-7
# The columns of shots.parquet besides the sampled inputs: point, group, label, shot, the
# outcome fields and status_name; and those a run on a hole adds.
_FIXED_COLUMNS = 5 + len(PLANE_FIELDS)
_HOLE_COLUMNS = len(HOLE_FIELDS) + len(on_hole_results.COLUMNS)


class Chunk(NamedTuple):
    """Shots ``start .. stop - 1`` of point ``point``: chunk ``index`` of the run."""

    index: int
    point: int
    start: int
    stop: int


def starts_of(points):
    """Where each of ``points`` is struck ((x, y) m in the hole's frame): its start on a hole,
    the tee (the frame's origin) on a plane."""
    return [on_hole_results.TEE if p.play is None else p.play.start_m for p in points]


def general_flight(scenario):
    """Whether a point of ``scenario`` flies in the general lanes (``batch.general_flight``: an
    aerodynamic model that does not fly in the vectorised lanes, or a wind profile)."""
    return any(
        general_flight_of(p.params["models.aero"], p.params["weather.wind_profile"])
        for p in scenario.points
    )


def kernels_of(scenario, traced=False):
    """(ground, kernels) the scenario's shots run (``engine.warmup``): on the plane or a hole's
    terrain, the batch (and the traced batch where paths are recorded), of the general flight
    kind where a point flies in the general lanes."""
    ground = "plane" if scenario.hole is None else "terrain"
    kernels = ("batch", "traced") if traced else ("batch",)
    return ground, general(kernels) if general_flight(scenario) else kernels


def compile_kernel(scenario):
    """Compile the batch kernel the scenario's shots run (or load it from the cache), so that
    a run's clock starts after it: on its ground, of its flight kinds."""
    ground, kernels = kernels_of(scenario)
    warm_up((ground,), kernels)


def terrain_of(scenario):
    """The ground the kernel plays the scenario's shots on: its hole's Terrain, or None (each
    shot's own plane)."""
    return None if scenario.hole is None else scenario.hole.terrain()


def point_stats(scenario, drivers):
    """The streaming statistics of a point of the scenario's run (``stats.PointStats``, with
    its ``on_hole.HoleTally`` on a hole), ``drivers`` its variance drivers' inputs."""
    hole = scenario.hole
    tally = None
    if hole is not None:
        tally = on_hole_results.HoleTally(hole.putting["model"] == "physics")
    return stats.PointStats(drivers, tally)


def made_chunk(scenario, writer, drivers, input_names, point, start, stop, terrain):
    """Shots ``start .. stop - 1`` of ``point`` as both drivers make a chunk: sampled
    (``input_names``), flown on ``terrain``, the hole's columns made once
    (``writer.hole_columns``, an ``output.ShotsWriter``), tallied into the chunk's own
    streaming statistics (``point_stats`` of the point's ``drivers``) and made into its table
    (``writer.table``). Returns (inputs, PointStats, table)."""
    inputs, sampled = sampling.sample(scenario, scenario.points[point], start, stop, input_names)
    out = simulate_batch(inputs, terrain=terrain)
    hole_columns = writer.hole_columns(point, out)
    chunk_stats = point_stats(scenario, drivers)
    chunk_stats.update(out, sampled, hole_columns)
    return inputs, chunk_stats, writer.table(point, start, sampled, out, hole_columns)


def putting_of(scenario):
    """The expected-putts map the shots on the scenario's hole are scored with where its green
    is valued by one (``[hole.putting] model = "physics"``), built or read from its cache here,
    before a shot is scored (``putting.on_hole.map_of_hole``); None on a plane or where the
    baseline's table values the green."""
    return None if scenario.hole is None else map_of_hole(scenario.hole)


@dataclass(frozen=True)
class Plan:
    """What a run will be: the scenario (with the run's seed), its shots per point ``n``, the
    chunk size, every how many shots a path is recorded (None: none), the sampled columns
    (``input_names``; ``integer_columns`` those that hold integers) and the variance drivers
    of each point; and an estimate of its time (s) and of the Parquet it writes (bytes, an
    upper bound)."""

    scenario: scenario_module.Scenario
    n: int
    chunk_size: int
    trajectories_every: int | None
    input_names: list
    integer_columns: list
    drivers: list
    seconds: float
    bytes: int

    @property
    def seed(self):
        return self.scenario.seed

    @property
    def points(self):
        return self.scenario.points

    @property
    def shots(self):
        return len(self.points) * self.n

    def chunks(self):
        """The chunks one after the other, point by point, never as a list: n may be huge."""
        index = 0
        for point in self.points:
            for start in range(0, self.n, self.chunk_size):
                yield Chunk(index, point.index, start, min(start + self.chunk_size, self.n))
                index += 1

    def line(self):
        """One line for the terminal, e.g. ``mcrun: 4 points x 10 shots = 40 shots; ...``."""
        points = f"{len(self.points):,} point" + ("s" if len(self.points) != 1 else "")
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


def plan(
    path_or_scenario, n=None, seed=None, chunk_size=DEFAULT_CHUNK_SIZE, trajectories_every=None
):
    """The ``Plan`` of a run of ``n`` shots per point (default: the scenario's) with ``seed``
    (default: the scenario's) of a scenario file, a library scenario's name or a loaded
    scenario; InputError on a bad scenario or argument.

    The size is an upper bound (constants above); the time assumes the 2-core machine of the
    benchmarks.
    """
    scenario = path_or_scenario
    if isinstance(path_or_scenario, str | os.PathLike):
        scenario = scenario_module.load(path_or_scenario)
    elif not (hasattr(scenario, "points") and hasattr(scenario, "seed")):  # (AttributeError)
        raise InputError(f"scenario {shown(path_or_scenario)}: allowed: a scenario file, a "
                         "library scenario's name or a loaded scenario")  # fmt: skip
    n = positive_int(scenario.shots if n is None else n, "n")
    seed = positive_int(scenario.seed if seed is None else seed, "seed", minimum=0)
    chunk_size = positive_int(chunk_size, "chunk_size")
    if trajectories_every is not None:
        trajectories_every = positive_int(trajectories_every, "trajectories_every")
        if chunk_size == DEFAULT_CHUNK_SIZE:  # (a size the user chose is kept)
            chunk_size = min(chunk_size, MAX_PATHS_PER_CHUNK * trajectories_every)
    scenario = with_seed(scenario, seed)
    points = len(scenario.points)
    shots = points * n
    input_names, integer_columns = run_columns(scenario)
    drivers = [driver_inputs(point, input_names) for point in scenario.points]
    width = len(input_names) + _FIXED_COLUMNS + (0 if scenario.hole is None else _HOLE_COLUMNS)
    row_groups = shots // output.ROW_GROUP_ROWS + 1
    size = shots * width * BYTES_PER_COLUMN_SHOT + row_groups * width * BYTES_PER_ROW_GROUP_COLUMN
    size += BYTES_SUMMARY + points * BYTES_SUMMARY_POINT
    if trajectories_every is not None:
        size += points * -(-n // trajectories_every) * BYTES_PER_TRAJECTORY
    # (SECONDS_PER_POINT holds one block of the default size)
    extra = max(drawn_samples(n, chunk_size, scenario.block_size) - max(n, DEFAULT_BLOCK_SIZE), 0)
    seconds = shots / SHOTS_PER_S + points * (SECONDS_PER_POINT + extra * SECONDS_PER_DRAWN_SAMPLE)
    return Plan(
        scenario,
        n,
        chunk_size,
        trajectories_every,
        input_names,
        integer_columns,
        drivers,
        seconds,
        size,
    )


def drawn_samples(n, chunk_size, block_size):
    """The samples a point of ``n`` shots draws in chunks of ``chunk_size``: each chunk draws
    every block of ``block_size`` it touches, whole (``sampling.sample``). A chunk touches one
    block more for each block boundary inside it: the boundaries that are not also a chunk's."""
    chunks = -(-n // chunk_size)
    blocks = -(-n // block_size)
    shared = math.lcm(chunk_size, block_size) // block_size  # every shared-th boundary is a chunk's
    return (chunks + (blocks - 1) - (blocks - 1) // shared) * block_size


def free_space(out_dir):
    """(folder, free bytes) of the nearest existing folder of ``out_dir`` (itself or a parent),
    where the run will be written."""
    folder = Path(out_dir).absolute()
    while not folder.exists() and folder.parent != folder:
        folder = folder.parent
    return folder, shutil.disk_usage(folder).free


def check_disk_space(the_plan, out_dir):
    """Refuse (OutputError) a run whose estimated size, with its summary's temporary spill
    (``stats.Spill``: 8 bytes a shot for each of ``stats.SPILLED``), is not under the free
    space."""
    folder, free = free_space(out_dir)
    spill = the_plan.shots * 8 * len(stats.SPILLED)
    if the_plan.bytes + spill >= free:
        raise output.OutputError(
            f"the run would write about {size_text(the_plan.bytes)} of Parquet "
            f"({the_plan.shots:,} shots) and {size_text(spill)} of temporary values for its "
            f"summary, but {folder} has {size_text(free)} free: lower -n, "
            "choose another folder with -o, or pass --ignore-disk-space to run anyway"
        )


# --- a chunk's paths ---------------------------------------------------------------------------


def trajectory_shots(start, stop, every):
    """The shots start <= i < stop whose path is recorded: i % every == 0."""
    return range(-(-start // every) * every, stop, every)


def add_trajectories(writer, inputs, point, start, stop, every, terrain=None):
    """Compute the paths of a chunk's ``trajectory_shots`` (rows of ``inputs``: each shot
    alone again, its path recorded, on ``terrain``) and give each to ``writer.add(point, shot,
    path)``."""
    for i in trajectory_shots(start, stop, every):
        _, path = simulate_traced(inputs[i - start : i - start + 1], terrain=terrain)
        writer.add(point, i, path)


# --- provenance --------------------------------------------------------------------------------


def _model_names(points):
    """Names of the aerodynamic models and wind profiles used: choices, so the same for every
    sample of a point, read from its parameters (no sampling)."""
    models = sorted({p.params["models.aero"] for p in points})
    profiles = sorted({p.params["weather.wind_profile"] for p in points})
    return {"aero": models, "bounce": ["penner2002"], "wind_profile": profiles}


def provenance(the_plan, backend, versions, threads, **facts):
    """The provenance every file of a run records: the scenario, its question, seed, size,
    points and models, its launch files (their digests) and fits, its geometry
    (``geometry.record``) and on a hole its map (``geometry.record_map``, which
    ``file_metadata`` keeps for summary.parquet), the software
    ``versions``, the ``backend`` that ran it on how many ``threads`` and that backend's own
    ``facts``, the chunk size and the start time."""
    scenario, points = the_plan.scenario, the_plan.points
    recorded = {
        geometry.GEOMETRY_KEY: geometry.record(
            scenario.hole,
            [None if p.play is None else p.play.aim_rad for p in points],
            [p.target_m for p in points],
            starts_of(points),
        )
    }
    if scenario.hole is not None:
        recorded[geometry.MAP_KEY] = geometry.record_map(scenario.hole)
    return {
        "format_version": output.FORMAT_VERSION,
        "backend": backend,
        "scenario_name": scenario.name,
        "scenario_path": str(scenario.path),
        "scenario_text": scenario.text,
        "question": scenario.question,
        "seed": the_plan.seed,
        "n": the_plan.n,
        "block_size": scenario.block_size,
        "points": [p.label for p in points],
        "groups": [p.group for p in points],
        "models": _model_names(points),
        "launch_files": scenario_module.launch_files(points),
        "launch_fits": scenario_module.launch_fits(points),
        **recorded,
        "versions": versions,
        "threads": threads,
        **facts,
        "chunk_size": the_plan.chunk_size,
        "trajectories_every": the_plan.trajectories_every,
        "start_time_utc": datetime.now(UTC).isoformat(timespec="seconds"),
    }


# The files that hold the hole's map (``geometry.MAP_KEY``): one a run, not every part of it.
MAP_FILES = ("summary", "aim")


def file_metadata(run_provenance, file, started=None):
    """The Parquet key-value metadata of the run's ``file`` (shots, summary, trajectories,
    aim): the run's provenance (the hole's map only in ``MAP_FILES``) and, once the file is
    complete, the seconds since ``started`` (``time.perf_counter``) as ``elapsed_s``."""
    fields = {
        **{k: v for k, v in run_provenance.items() if k != geometry.MAP_KEY or file in MAP_FILES},
        "file": file,
    }
    if started is not None:
        fields["elapsed_s"] = round(time.perf_counter() - started, 3)
    return output.encode_provenance(fields)


# --- the summary -------------------------------------------------------------------------------


def _sweep_columns(points):
    """{key path: [value per point]}: numbers as floats, anything else as text."""
    keys = list(dict.fromkeys(k for p in points for k in (p.sweep or {})))
    columns = {}
    for key in keys:
        values = [(p.sweep or {}).get(key) for p in points]
        numeric = all(isinstance(v, int | float) and not isinstance(v, bool) for v in values)
        columns[key] = [float(v) for v in values] if numeric else [str(v) for v in values]
    return columns


def summary_rows(points, point_stats, shots_of, budget_bytes, on_hole=False):
    """summary.parquet's rows, one per point: its index, group, label and sweep values, then
    ``stats.summarise`` of its streamed ``PointStats`` and of its ok shots, which
    ``shots_of(point index)`` reads (a ``stats.ShotsColumns``) from wherever they were
    written; ``on_hole``: whether the run is on a hole, whose streamed tally
    (``on_hole.HoleTally``) gives the shares of its zones, its expected strokes and, where its
    green is valued by its map, its putting shares."""
    on_hole = on_hole is not None and on_hole is not False
    rows = []
    sweep = _sweep_columns(points)
    for point, one in zip(points, point_stats, strict=True):
        row = {"point": point.index, "group": point.group, "label": point.label}
        for key, values in sweep.items():
            row[key] = values[point.index]
        columns = shots_of(point.index)
        row.update(
            stats.summarise(
                one, columns, target_m=point.target_m, budget_bytes=budget_bytes, on_hole=on_hole
            )
        )
        if on_hole:
            row.update(one.on_hole.row())
        rows.append(row)
    return pd.DataFrame(rows)


def summary_table(rows):
    """summary.parquet's table of ``summary_rows``: its point, group and label of the shots'
    types (int32, and text as a dictionary), so that a join of the two on them needs no cast
    (polars refused to join its categorical with text, and before 2 int32 with int64)."""
    table = pa.Table.from_pandas(rows, preserve_index=False)
    text = pa.dictionary(pa.int32(), pa.string())
    for name, kind in (("point", pa.int32()), ("group", text), ("label", text)):
        i = table.schema.get_field_index(name)
        table = table.set_column(i, name, table.column(name).cast(kind))
    return table


def summary_metadata(run_provenance, started):
    """summary.parquet's metadata: the run's provenance, its elapsed time and how the summary
    is computed (``SUMMARY_CONVENTIONS``)."""
    return {
        **file_metadata(run_provenance, "summary", started),
        **output.encode_provenance(SUMMARY_CONVENTIONS),
    }


# --- what a run wrote --------------------------------------------------------------------------


@dataclass
class RunResult:
    """What a run wrote: the folder (a path, or for a Dask run possibly a URL), its files (or,
    for a Dask run, the dataset folders), and how it was run."""

    out_dir: Path | str
    shots_path: Path | str
    summary_path: Path | str
    trajectories_path: Path | str | None
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
        """The shots as a pandas DataFrame, as the local shots.parquet reads (``columns``: a
        subset to read)."""
        return reader.read_shots(self.out_dir, columns)

    def summary(self):
        """summary.parquet as a pandas DataFrame, one row per point."""
        return pd.read_parquet(self.summary_path)

    def trajectories(self):
        """The trajectories as a pandas DataFrame (None when not asked for)."""
        return None if self.trajectories_path is None else reader.read_trajectories(self.out_dir)
