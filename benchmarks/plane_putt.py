"""``python -m benchmarks.plane_putt [--threads 1,2] [--n N] [--repeats R]``: ``mcrun putt``'s
read of a putt on a plane green (``putting.putt``: twelve candidate reads, each struck n times
and every sample holed out from where its first putt stopped) by thread count.

The first putts (``stroke.strike_all``) and the samples' hole-outs (``putting.rest._hole_outs``)
run on every thread; the rest (the reads' centre lines, the strikes' speeds and lines, the
candidates' means) on one. Three putts of the Tour putter on an 11 ft green: 10 ft level, 10 ft
on 2 % falling left to right, 6 m uphill on 3 %; the best of ``--repeats`` after a warm-up
(compilation), the putts checked equal across thread counts. ``BEFORE_S``: the same putts before
the first putts ran on every thread (struck one lane group after another), on 2 threads,
measured on the same machine in the same hour as the table written here. Prints a Markdown table
and writes ``benchmarks/results/plane-putt.md``; asserts nothing.
"""

import argparse
import time
from pathlib import Path

import numba
import numpy as np

from benchmarks.common import publish
from mcrun.putting import putt
from mcrun.strokes.baseline import FOOT_M

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results" / "plane-putt.md"
STIMP_M = 11.0 * FOOT_M
# (label, distance m, slope tan, direction deg from the putt's line: 0 downhill, 180 uphill)
PUTTS = (
    ("10 ft, level", 10.0 * FOOT_M, 0.0, 0.0),
    ("10 ft, 2 % falling right", 10.0 * FOOT_M, 0.02, 90.0),
    ("6 m uphill, 3 %", 6.0, 0.03, 180.0),
)
# Before the first putts ran on every thread: this script on the tree before, 2,000 putts, 2
# threads, the best of two runs alternating with the tree after (2026-11-28, 2-core AMD EPYC;
# 4.73, 4.72 and 7.94 s on 1 thread).
BEFORE_S = {"10 ft, level": 2.88, "10 ft, 2 % falling right": 3.23, "6 m uphill, 3 %": 5.21}


def timed(distance_m, slope_tan, direction_deg, n, threads, repeats):
    """(best wall time s, putts) of the putt's read on ``threads`` threads."""
    numba.set_num_threads(threads)
    best, putts = float("inf"), None
    for _ in range(repeats):
        started = time.perf_counter()
        result = putt(distance_m, STIMP_M, slope_tan, direction_deg, n=n)
        best = min(best, time.perf_counter() - started)
        putts = result.putts
    return best, putts


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--threads", default="1,2")
    parser.add_argument("--n", type=int, default=2000)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    counts = [int(t) for t in args.threads.split(",")]
    previous = numba.get_num_threads()
    putt(3.0, STIMP_M, 0.01, 45.0, n=20)  # compiles
    lines = [
        "# A plane green's putt by thread count",
        "",
        f"`python -m benchmarks.plane_putt --threads {args.threads} --n {args.n} --repeats "
        f"{args.repeats}`: the read of {args.n:,} putts (the Tour putter, Stimp 11 ft), the "
        f"best of {args.repeats}.",
        "",
        "| putt | threads | wall | vs 1 thread | before (2 threads) |",
        "|---|---|---|---|---|",
    ]
    same = True
    try:
        for label, distance_m, slope_tan, direction_deg in PUTTS:
            walls, first = {}, None
            for threads in counts:
                wall, putts = timed(distance_m, slope_tan, direction_deg, args.n, threads,
                                    args.repeats)  # fmt: skip
                walls[threads] = wall
                first = putts if first is None else first
                same &= bool(np.array_equal(putts, first))
                scaling = f"{walls[1] / wall:.2f}x" if threads > 1 and 1 in walls else ""
                before = BEFORE_S.get(label) if threads == 2 and args.n == 2000 else None
                shown = "" if before is None else f"{before:.2f} s ({before / wall:.2f}x)"
                lines.append(f"| {label} | {threads} | {wall:.2f} s | {scaling} | {shown} |")
    finally:
        numba.set_num_threads(previous)
    lines += ["", "The putts on every thread count: " + ("the same." if same else "DIFFER.")]
    publish(RESULTS, lines)


if __name__ == "__main__":
    main()
