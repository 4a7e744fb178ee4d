"""``python -m benchmarks.putting [--resolution R] [--n N] [--library-n N] [--library-best-n N]``:
the expected-putts map of a 600 m^2 green.

The issue's target: the map of a 600 m^2 green at 0.5 m, 200 putts per read, in under 60 s on
two cores; timed with each of the map's reads (``green_map.READS``: the putter's own, the
default, and the best of a search). The green: an ellipse of 16 m x 12 m semi-axes
(603 m^2) on a grid of 0.25 m, falling from back to front at 2 % with a crown of 0.15 m
(cos^2 over 8 m) off the pin's left, Stimp 11 ft; the pin 3 m short of its centre and 2 m
left. Timed after a warm-up (compilation, a map of a small green) that is not; every point
read and valued by n putts of the Tour putter.

Then the library's sloped green (``scenarios/holes/riverside-18-green.toml``: 2 % back to
front, Stimp 11 ft) mapped at 1 m with ``--library-n`` putts a read with the own read (8,000:
at the hole's own 100 a point's sampling error, about 0.03 putts, is as large as the difference
below and above the hole) and ``--library-best-n`` with the best (800: its search costs 12
reads), and its expected putts straight below and straight above the pin at 2, 3, 5 and 8 m.

Prints Markdown tables and writes ``benchmarks/results/putting.md``; asserts nothing.
"""

import argparse
import os
import time
from pathlib import Path

import numpy as np

from benchmarks.common import publish
from mcrun.physics.turf import rho_g_from_stimp
from mcrun.putting.green import Green
from mcrun.putting.green_map import READS, expected_putts_map
from mcrun.putting.roll import Surface
from mcrun.strokes.baseline import FOOT_M

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results" / "putting.md"
TARGET_S = 60.0
SEMI_AXES_M = (16.0, 12.0)
PIN_XY_M = (-3.0, -2.0)


def bench_green(semi_axes_m=SEMI_AXES_M, cell_m=0.25, slope=0.02, stimp_ft=11.0):
    """The benchmark's green (a ``putting.green.Green``), x towards the back."""
    a, b = semi_axes_m
    xs = np.arange(-a - 1.0, a + 1.0 + cell_m / 2, cell_m)
    ys = np.arange(-b - 1.0, b + 1.0 + cell_m / 2, cell_m)
    x, y = np.meshgrid(xs, ys)
    r = np.hypot(x - 4.0, y - 5.0)
    crown = np.where(r < 8.0, 0.15 * np.cos(0.5 * np.pi * r / 8.0) ** 2, 0.0)
    height = slope * x + crown
    on = ((x / a) ** 2 + (y / b) ** 2 <= 1.0).astype(np.uint8)
    surface = Surface(height, on, float(xs[0]), float(ys[0]), cell_m)
    return Green(surface, PIN_XY_M, float(rho_g_from_stimp(stimp_ft * FOOT_M)), "benchmark")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--resolution", type=float, default=0.5)
    parser.add_argument("--n", type=int, default=200)
    parser.add_argument("--library-n", type=int, default=8000)
    parser.add_argument("--library-best-n", type=int, default=800)
    args = parser.parse_args(argv)
    threads = len(os.sched_getaffinity(0))
    for read in READS:  # compile
        expected_putts_map(bench_green((3.0, 3.0)), n=20, resolution_m=1.0, read=read)
    green = bench_green()
    lines = [
        "# The expected-putts map of a 600 m^2 green",
        "",
        f"`python -m benchmarks.putting --resolution {args.resolution:g} --n {args.n} "
        f"--library-n {args.library_n} --library-best-n {args.library_best_n}` on {threads} "
        f"threads: a green of {green.area_m2():.0f} m^2 (its grid 0.25 m), Stimp 11 ft, 2 % "
        "back to front with a crown; every point read and valued by the Tour putter.",
        "",
        "| map | read | points | putts per read | time | target | | sweeps after the first "
        "(last change) | 3 m below the pin | 3 m above |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for read in READS:
        started = time.perf_counter()
        m = expected_putts_map(green, n=args.n, resolution_m=args.resolution, read=read)
        elapsed = time.perf_counter() - started
        points = int(m.valid.sum())
        below = float(m.value_at(PIN_XY_M[0] - 3.0, PIN_XY_M[1])[0][0])
        above = float(m.value_at(PIN_XY_M[0] + 3.0, PIN_XY_M[1])[0][0])
        verdict = "met" if elapsed < TARGET_S else f"NOT met ({elapsed - TARGET_S:.1f} s over)"
        lines.append(
            f"| {args.resolution:g} m | {read} | {points:,} (+ {m.polar_expected.size} around "
            f"the hole) | {args.n} | {elapsed:.1f} s | < {TARGET_S:g} s | {verdict} | "
            f"{m.sweeps} ({m.sweep_change:.4f}) | {below:.3f} | {above:.3f} |"
        )
    lines.append("")
    lines += library_table(args.library_n, "own")
    lines += library_table(args.library_best_n, "best")
    publish(RESULTS, lines)


def library_table(n, read):
    """The library green's expected putts below and above the pin, as Markdown lines."""
    from mcrun.hole.hole import load_hole
    from mcrun.putting.green import green_of_hole
    from mcrun.run import scenario as sc

    hole = load_hole(sc.library_folder() / "holes" / "riverside-18-green.toml")
    started = time.perf_counter()
    m = expected_putts_map(green_of_hole(hole), n=n, resolution_m=1.0, read=read)
    elapsed = time.perf_counter() - started
    px, py = hole.pin_xy
    distances = (2.0, 3.0, 5.0, 8.0)
    rows = {name: [m.value_at(px + sign * d, py) for d in distances]
            for name, sign in (("below", -1.0), ("above", 1.0))}  # fmt: skip
    lines = [
        f"## The library's green: below and above the hole ({read} read, {n} putts a read, "
        f"1 m, {elapsed:.0f} s)",
        "",
        "| from the pin | " + " | ".join(f"{d:g} m" for d in distances) + " |",
        "|---|" + "---|" * len(distances),
    ]
    for name in ("below", "above"):
        lines.append(f"| expected putts, {name} | "
                     + " | ".join(f"{v[0][0]:.3f}" for v in rows[name]) + " |")  # fmt: skip
    lines.append("| above - below | " + " | ".join(
        f"{a[0][0] - b[0][0]:+.3f}" for a, b in zip(rows["above"], rows["below"], strict=True))
        + " |")  # fmt: skip
    for name in ("below", "above"):
        lines.append(f"| three or more, {name} | "
                     + " | ".join(f"{100 * v[2][0]:.1f} %" for v in rows[name]) + " |")  # fmt: skip
    lines += ["", f"Sweeps after the first: {m.sweeps}; the last changed a value by "
              f"{m.sweep_change:.4f} at most.", ""]  # fmt: skip
    return lines


if __name__ == "__main__":
    main()
