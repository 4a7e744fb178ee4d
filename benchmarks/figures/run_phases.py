"""A run at the kernel's pace: ``mcrun run``'s phases, each timed alone per shot, and the run end
to end against the kernel alone, on 1 and 2 threads, for pga-driver (the plane) and
par3-over-water (a hole: zones, lon/lat, expected strokes).

The phases of a chunk (``run.local``'s task and writer, one after the other here so that each
is timed alone): the sampling; the kernel (on the threads); the hole's columns (zones, lon/lat,
expected strokes: ``ShotsWriter.hole_columns``); the streaming statistics (the moments and the
hole's tally, and the chunk's values for the summary kept in its ``stats.Spill``); the Parquet
table and its write; then, once, the summary (its exact percentiles read back from the
spill). The run end to end: ``run.local.run_scenario`` in this
process (its chunks the executor's tasks, written in order beside them), after a warm-up; the
kernel alone: the same chunks, already sampled, through ``simulate_batch``.
"""

import tempfile
import time
from pathlib import Path

import numba
import pyarrow as pa

from benchmarks.common import rate, target
from mcrun.engine.backend import simulate_batch
from mcrun.results import output, stats
from mcrun.run import local, plan, sampling

SCENARIOS = ("pga-driver", "par3-over-water")
PHASES = ("sample", "kernel", "hole columns", "statistics", "parquet", "summary")
# The targets (recorded, never asserted): the run on 2 threads at least this share of
# the kernel's rate, and at least this many times the run on 1 thread.
TARGET_SHARE = 0.60
TARGET_SCALING = 1.7


def _phases(name, n):
    """{phase: seconds} of a run of ``n`` shots of the scenario, each phase timed alone."""
    the_plan = plan.plan(name, n, None, plan.DEFAULT_CHUNK_SIZE, None)
    plan.compile_kernel(the_plan.scenario)
    scenario, points = the_plan.scenario, the_plan.points
    terrain = plan.terrain_of(scenario)
    seconds = dict.fromkeys(PHASES, 0.0)
    with tempfile.TemporaryDirectory(prefix="mcrun-bench-") as tmp:
        path = Path(tmp) / "shots.parquet"
        provenance = plan.provenance(the_plan, "local", output.versions(), 1)
        writer = output.ShotsWriter(
            path, the_plan.input_names, [p.group for p in points], [p.label for p in points],
            plan.file_metadata(provenance, "shots"),
            dict.fromkeys(the_plan.integer_columns, pa.int64()), hole=scenario.hole,
            starts_xy_m=plan.starts_of(points), putting=plan.putting_of(scenario),
        )  # fmt: skip
        point_stats = [plan.point_stats(scenario, d) for d in the_plan.drivers]
        spill = stats.Spill(tmp)
        for _, point, start, stop in the_plan.chunks():
            t0 = time.perf_counter()
            inputs, sampled = sampling.sample(scenario, points[point], start, stop,
                                              the_plan.input_names)  # fmt: skip
            t1 = time.perf_counter()
            out = simulate_batch(inputs, terrain=terrain)
            t2 = time.perf_counter()
            hole_columns = writer.hole_columns(point, out)
            t3 = time.perf_counter()
            point_stats[point].update(out, sampled, hole_columns)
            t4 = time.perf_counter()
            table = writer.table(point, start, sampled, out, hole_columns)
            writer.append(point, table)
            t5 = time.perf_counter()
            spill.append(point, spill.block(table))
            t6 = time.perf_counter()
            for phase, s in zip(PHASES, (t1 - t0, t2 - t1, t3 - t2, t4 - t3 + t6 - t5, t5 - t4),
                                strict=False):  # fmt: skip
                seconds[phase] += s
        t5 = time.perf_counter()
        writer.close()  # (the row groups still kept: the Parquet's)
        seconds["parquet"] += time.perf_counter() - t5
        t6 = time.perf_counter()
        plan.summary_rows(points, point_stats, spill.columns, stats.DEFAULT_BUDGET_BYTES,
                          on_hole=scenario.hole)  # fmt: skip
        seconds["summary"] = time.perf_counter() - t6
        spill.close()
    return seconds


def _kernel_alone(name, n):
    """Seconds of the kernel alone on the run's chunks (sampled before the clock starts)."""
    the_plan = plan.plan(name, n, None, plan.DEFAULT_CHUNK_SIZE, None)
    scenario, points = the_plan.scenario, the_plan.points
    terrain = plan.terrain_of(scenario)
    batches = [sampling.sample(scenario, points[p], a, b, the_plan.input_names)[0]
               for _, p, a, b in the_plan.chunks()]  # fmt: skip
    started = time.perf_counter()
    for inputs in batches:
        simulate_batch(inputs, terrain=terrain)
    return time.perf_counter() - started


def _end_to_end(name, n):
    """Seconds of ``mcrun run`` of n shots in this process (the run's own clock)."""
    with tempfile.TemporaryDirectory(prefix="mcrun-bench-") as tmp:
        result = local.run_scenario(name, n=n, out_dir=Path(tmp) / "run", progress=False)
        return result.elapsed_s


def measure(config, inputs):
    previous = numba.get_num_threads()
    rows = []
    try:
        for name in SCENARIOS:
            with tempfile.TemporaryDirectory(prefix="mcrun-bench-") as tmp:
                local.run_scenario(name, n=20_000, out_dir=Path(tmp) / "warm", progress=False)
            for threads in config.threads:
                numba.set_num_threads(threads)
                n = config.phases_n
                phases = _phases(name, n)
                kernel_s = min(_kernel_alone(name, n) for _ in range(2))
                run_s = min(_end_to_end(name, n) for _ in range(2))
                rows.append({
                    "scenario": name, "threads": threads, "n": n,
                    "phases_us_per_shot": {k: 1e6 * v / n for k, v in phases.items()},
                    "kernel_shots_per_s": n / kernel_s, "run_shots_per_s": n / run_s,
                })  # fmt: skip
    finally:
        numba.set_num_threads(previous)
    return {"rows": rows}


def _row(r, scenario, threads):
    return next((x for x in r.get("rows", []) if x["scenario"] == scenario
                 and x["threads"] == threads), None)  # fmt: skip


def targets(r):
    out = []
    for name in SCENARIOS:
        two, one = _row(r, name, 2), _row(r, name, 1)
        if two is not None:
            share = two["run_shots_per_s"] / two["kernel_shots_per_s"]
            out.append(target(f"a run at the kernel's pace: {name}, mcrun run on 2 threads >= "
                              f"{100 * TARGET_SHARE:.0f} % of the kernel's rate", share,
                              share >= TARGET_SHARE, f"{100 * share:.0f} %"))  # fmt: skip
        if two is not None and one is not None:
            scaling = two["run_shots_per_s"] / one["run_shots_per_s"]
            out.append(target(f"a run at the kernel's pace: {name}, mcrun run on 2 threads >= "
                              f"{TARGET_SCALING}x on 1", scaling, scaling >= TARGET_SCALING,
                              f"{scaling:.2f}x"))  # fmt: skip
    return out


def markdown(r):
    lines = [
        "### A run at the kernel's pace: its phases, and the run against the kernel",
        "",
        "Each phase timed alone, in microseconds a shot (the kernel's on the threads, the "
        "others on one); the run end to end (`run.local.run_scenario`: the chunks as the "
        "executor's tasks, written in order beside them) against the kernel alone on the same "
        "chunks.",
        "",
        "| scenario | threads | N | " + " | ".join(PHASES) + " | kernel shots/s | run shots/s "
        "| run / kernel |",
        "|---|---|---|" + "---|" * len(PHASES) + "---|---|---|",
    ]
    for row in r.get("rows", []):
        phases = " | ".join(f"{row['phases_us_per_shot'][p]:.2f}" for p in PHASES)
        share = row["run_shots_per_s"] / row["kernel_shots_per_s"]
        lines.append(
            f"| {row['scenario']} | {row['threads']} | {row['n']:,} | {phases} | "
            f"{rate(row['kernel_shots_per_s'])} | {rate(row['run_shots_per_s'])} | "
            f"{100 * share:.0f} % |"
        )
    return lines
