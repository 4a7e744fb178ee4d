"""``python -m benchmarks.putting [--resolution R] [--n N] [--library-n N] [--library-best-n N]
[--aim-n N] [--aim-putts N] [--aim-seeds K]``: the expected-putts map of a 600 m^2 green.

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

Then the aim check: a wedge into a side-sloped green (``side_slope_wedge``: the library's
``wedge-two-tier-firm`` scenario, Riverside 18 from 110 m, its ground a plane tilted 2 %
falling right, Stimp 11 ft), its best aim (``ClubAims.best_between_m``: five aims 0.25 m apart,
``--aim-n`` shots each) valued by the green's map with the putter's own read (``--aim-putts``
putts a read, 1 m; and the others of ``AIM_MAPS``: the test's and the default's putts), built
on the way, and by the distance-only table, for ``--aim-seeds`` seeds of the shots and the
maps, and where the pattern then finishes across the slope.

Prints Markdown tables and writes ``benchmarks/results/putting.md``; asserts nothing.
"""

import argparse
import json
import math
import os
import re
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
# The aim check: the slope across the wedge's line (falling right), the green's speed, the aims.
SIDE_SLOPE = 0.02
SIDE_STIMP_FT = 11.0
AIM_OFFSETS_M = (-1.0, -0.75, -0.5, -0.25, 0.0)
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
    parser.add_argument("--aim-n", type=int, default=20_000)
    parser.add_argument("--aim-putts", type=int, default=2000)
    parser.add_argument("--aim-seeds", type=int, default=8)
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
    lines += aim_table(args.aim_n, args.aim_putts, args.aim_seeds)
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
              f"{m.sweep_change:.4f} at most. Map data (c) OpenStreetMap contributors, ODbL.",
              ""]  # fmt: skip
    return lines


def side_slope_wedge(folder, putting=None, seed=0):
    """The aim check's scenario file, written in ``folder``: the library's
    ``wedge-two-tier-firm`` (Riverside 18, a wedge from 110 m) with its ground a plane tilted
    ``SIDE_SLOPE`` falling right (across the line of play), Stimp ``SIDE_STIMP_FT``, the shots'
    seed ``seed``, and ``putting`` (a TOML inline table's text) for its hole's putting (None:
    the distance-only table)."""
    from mcrun.run import scenario as sc

    library = sc.library_folder()
    text = (library / "wedge-two-tier-firm.toml").read_text()
    header = ("# The aim check of benchmarks/putting.py (side_slope_wedge). Riverside Golf, "
              "Zagreb, hole 18:\n# map data (c) OpenStreetMap contributors, ODbL.\n")  # fmt: skip
    text = header + re.sub(r"\A(#[^\n]*\n)+", "", text)
    hole = (library / "holes" / "riverside-18-wedge.toml").as_posix()
    slope_deg = math.degrees(math.atan(SIDE_SLOPE))
    rho_g = float(rho_g_from_stimp(SIDE_STIMP_FT * FOOT_M))
    shape = f'shape = {{ kind = "tilted_plane", slope_deg = {slope_deg!r}, fall_line_deg = 90.0 }}'
    replacements = (
        (r"^name = .*$", 'name = "wedge-side-slope"'),
        (
            r"^question = .*$",
            'question = "Where should a 110 m wedge aim at a green sloping across its line?"',
        ),
        (r"^seed = .*$", f"seed = {seed}"),
        (r"^file = .*$", f"file = {json.dumps(hole)}"),
        (r"^shape = .*$", shape + ("" if putting is None else f"\nputting = {putting}")),
        (r'^preset = "firm_green"$', f'preset = "firm_green"\nrho_g = {rho_g!r}'),
    )
    for pattern, replacement in replacements:
        text, count = re.subn(pattern, lambda _, r=replacement: r, text, count=1, flags=re.M)
        if count != 1:
            raise ValueError(f"wedge-two-tier-firm.toml: no line matches {pattern}")
    path = Path(folder) / f"side-slope-{seed}-{'table' if putting is None else 'map'}.toml"
    path.write_text(text)
    return path


def own_read_map(n, seed, resolution_m=1.0):
    """The aim check's green map: the putter's own read, ``n`` putts a read, at
    ``resolution_m``."""
    return (f'{{ model = "physics", resolution_m = {resolution_m!r}, n = {n}, read = "own", '
            f"seed = {seed} }}")  # fmt: skip


# The aim check's maps, (putts a read, resolution m): the benchmark's, the test's (cheaper) and
# the default's number of putts.
AIM_MAPS = ((2000, 1.0), (2000, 1.5), (200, 1.0))


def aim_table(n, putts, seeds):
    """The aim check as Markdown lines: for each seed, the best aim valued by the own read's
    map of ``putts`` putts a read at 1 m, by the other maps of ``AIM_MAPS``, and by the table,
    and the pattern's centre across the slope at the first and the last; the maps built (in a
    cache folder of their own), and timed with them."""
    import tempfile
    from unittest import mock

    from mcrun.run import aim

    maps = ((putts, 1.0), *(m for m in AIM_MAPS[1:] if m != (putts, 1.0)))
    others = " | ".join(f"map of {k:,} putts at {r:g} m - table" for k, r in maps[1:])
    lines = [
        f"## The aim check: a wedge into a green sloping 2 % across its line ({n:,} shots an aim)",
        "",
        f"| seed | best aim: map of {putts:,} putts a read at 1 m | table | map - table | "
        f"{others} | the pattern's centre below the pin: map | table | seconds |",
        "|---" * (7 + len(maps) - 1) + "|",
    ]
    margins = {m: [] for m in maps}
    with (
        tempfile.TemporaryDirectory() as folder,
        mock.patch.dict(os.environ, {"MCRUN_CACHE_DIR": str(Path(folder) / "cache")}),
    ):
        for seed in range(seeds):
            started = time.perf_counter()
            best, below = [], []
            valuations = (*(own_read_map(k, seed, r) for k, r in maps), None)
            for k, putting in enumerate(valuations):
                path = side_slope_wedge(folder, putting, seed)
                result = aim.search(aim.load_scenario(path), n=n, offsets_m=AIM_OFFSETS_M)
                best.append(result.clubs[0].best_between_m())
                if k in (0, len(valuations) - 1):  # the pattern: the first map's, the table's
                    _, y = aim.finishes(result, 0, best[-1])
                    below.append(float(np.mean(y)) - result.scenario.hole.pin_xy[1])  # right
            for m, value in zip(maps, best, strict=False):
                margins[m].append(value - best[-1])
            seconds = time.perf_counter() - started
            cells = [f"{seed}", f"{best[0]:+.3f} m", f"{best[-1]:+.3f} m",
                     *(f"{margins[m][-1]:+.3f} m" for m in maps),
                     f"{below[0]:+.2f} m", f"{below[-1]:+.2f} m", f"{seconds:.0f}"]  # fmt: skip
            lines.append("| " + " | ".join(cells) + " |")
    lines += ["", "Aims in m right of the pin (+: below it, the slope falls right). How far each "
              "map moves the best aim towards below the pin, against the table:", ""]  # fmt: skip
    for (k, r), values in margins.items():
        sd = f"SD {100 * np.std(values, ddof=1):.1f}; " if len(values) > 1 else ""
        lines.append(f"- {k:,} putts a read at {r:g} m: {100 * np.mean(values):.1f} cm on average "
                     f"({sd}{100 * min(values):.1f} to {100 * max(values):.1f})")  # fmt: skip
    lines += ["", "The aim itself stays above the pin, as the pattern rolls down the slope after "
              "it lands.", "", "Map data (c) OpenStreetMap contributors, ODbL.", ""]  # fmt: skip
    return lines


if __name__ == "__main__":
    main()
