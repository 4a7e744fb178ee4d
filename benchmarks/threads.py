"""``python -m benchmarks.threads [--threads 1,2] [--n N] [--map-n N]``: a solve and a green's map
on 1 and 2 threads, their time split into the kernels and everything else.

The issue's targets, on two cores: the solve of Riverside 9 for the Tour player (as in
``benchmarks.play``: ``--n`` shots an action, default 100) and the map of the 603 m^2 green of
``benchmarks.putting`` (at 0.5 m, ``--map-n`` putts a read, default 200; every putt read at
its best, ``read="best"``, the work the map did before the executor: its default, the putter's
own read, is a twelfth of it), each with the part
outside the kernels at most 10 % of the wall time on 2 threads, 2 threads at least 1.8 times as
fast as one, and at least twice as fast as before the executor (``BEFORE_S``: measured on the
same machine, with the same split, on the tree before it).

The split. The kernels: the shot kernel (``engine.batch``'s batches: each task of the executor
runs its batch on its own thread, so their seconds are thread-seconds, divided by the threads),
the solve's sweeps (``play.solve``: a parallel kernel on every thread, its wall time) and the
map's points (``putting.green_map``'s reads and putts, thread-seconds divided by the threads).
Everything else: the wall time less those. Each is timed after a warm-up (compilation) that is
not; the results are checked equal across thread counts (the tee's value, the map's sum).

Prints a Markdown table and writes ``benchmarks/results/threads.md``; asserts nothing.
"""

import argparse
import threading
import time
from pathlib import Path

import numba
import numpy as np

from benchmarks.common import publish
from benchmarks.putting import bench_green
from mcrun import executor
from mcrun.engine import batch
from mcrun.play import load_player, play_hole
from mcrun.putting import green_map
from mcrun.run import scenario as sc

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results" / "threads.md"
# Measured before the executor (the tree of 2026-11-26 with today's Tour bag, this script's
# split, 2-core AMD EPYC, the same hour): {what: {threads: wall s}}.
BEFORE_S = {"solve": {1: 44.8, 2: 30.9}, "map": {1: 106.8, 2: 57.5}}
SHARE_TARGET = 0.10
SCALING_TARGET = 1.8


class _Clock:
    """Thread-seconds spent in a function, wherever it runs: wraps ``module.name``."""

    def __init__(self, module, name):
        self.module, self.name = module, name
        self.original = getattr(module, name)
        self.seconds = 0.0
        self._lock = threading.Lock()

    def __enter__(self):
        def timed(*args, **kwargs):
            started = time.perf_counter()
            try:
                return self.original(*args, **kwargs)
            finally:
                elapsed = time.perf_counter() - started
                # A batch that ran on every thread (not a task's own) held them all.
                held = 1 if executor.in_task() else numba.get_num_threads()
                with self._lock:
                    self.seconds += elapsed * held

        setattr(self.module, self.name, timed)
        return self

    def __exit__(self, *exc):
        setattr(self.module, self.name, self.original)


def solve_split(player, hole, n, threads):
    """(wall, shot kernel, sweeps, tee value) of the hole solved on ``threads`` threads."""
    numba.set_num_threads(threads)
    with _Clock(batch, "_run") as shots:
        started = time.perf_counter()
        result = play_hole(player, hole, n=n)
        wall = time.perf_counter() - started
    sweeps = result.solution.seconds + result.fairway_solution.seconds
    return wall, shots.seconds / threads, sweeps, result.tee_value


def map_split(green, n, threads):
    """(wall, kernel, sum of the expected putts) of the green's map on ``threads`` threads."""
    numba.set_num_threads(threads)
    with _Clock(green_map, "_solve_points") as points:
        started = time.perf_counter()
        found = green_map.expected_putts_map(green, n=n, resolution_m=0.5, threads=threads,
                                             read="best")  # fmt: skip
        wall = time.perf_counter() - started
    return wall, points.seconds / threads, float(np.nansum(found.expected_putts))


def _row(what, threads, wall, kernels, one_wall, before):
    rest = wall - kernels
    scaling = "" if one_wall is None else f"{one_wall / wall:.2f}x"
    faster = "" if before is None else f"{before:.1f} s ({before / wall:.2f}x)"
    return (f"| {what} | {threads} | {wall:.1f} s | {kernels:.1f} s | {rest:.1f} s "
            f"({100 * rest / wall:.1f} %) | {scaling} | {faster} |")  # fmt: skip


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--threads", default="1,2")
    parser.add_argument("--n", type=int, default=100)
    parser.add_argument("--map-n", type=int, default=200)
    args = parser.parse_args(argv)
    counts = [int(t) for t in args.threads.split(",")]
    previous = numba.get_num_threads()
    player = load_player("pga-tour-bag")
    hole = sc.load("par4-tee-shot").hole
    play_hole(player, hole, n=4, coarse_m=40.0, fine_m=20.0, plays=10)  # compiles
    green = bench_green()
    green_map.expected_putts_map(bench_green(semi_axes_m=(3.0, 2.5)), n=8, resolution_m=0.5,
                                 read="best")  # fmt: skip
    lines = ["# A solve and a green's map by thread count", "",
             f"`python -m benchmarks.threads --threads {args.threads} --n {args.n} --map-n "
             f"{args.map_n}`.", "",
             "| what | threads | wall | kernels | everything else | vs 1 thread | before |",
             "|---|---|---|---|---|---|---|"]  # fmt: skip
    notes = []
    try:
        walls, values = {}, set()
        for threads in counts:
            wall, shots, sweeps, tee = solve_split(player, hole, args.n, threads)
            walls[threads], _ = wall, values.add(tee)
            lines.append(_row(f"solve of {hole.name} (shots {shots:.1f} s, sweeps {sweeps:.1f} s)",
                              threads, wall, shots + sweeps, walls.get(1) if threads > 1 else None,
                              BEFORE_S["solve"].get(threads)))  # fmt: skip
        notes.append(f"The solve's tee value on every thread count: {sorted(values)}.")
        walls, sums = {}, set()
        for threads in counts:
            wall, kernel, total = map_split(green, args.map_n, threads)
            walls[threads], _ = wall, sums.add(total)
            lines.append(_row(f"map of a 603 m^2 green, {args.map_n} putts a read", threads,
                              wall, kernel, walls.get(1) if threads > 1 else None,
                              BEFORE_S["map"].get(threads)))  # fmt: skip
        notes.append(f"The map's sum of expected putts on every thread count: {sorted(sums)}.")
    finally:
        numba.set_num_threads(previous)
    lines += ["", *notes, "",
              f"Targets on 2 threads: everything else at most {100 * SHARE_TARGET:.0f} % of the "
              f"wall time; 2 threads at least {SCALING_TARGET}x one; at least 2x faster than "
              "before."]  # fmt: skip
    publish(RESULTS, lines)


if __name__ == "__main__":
    main()
