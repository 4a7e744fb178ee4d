"""``python -m benchmarks.holes [--shots N] [--aims K]``: the kernel on a hole, an aim search,
and the memory of a whole course's grid.

The issues' targets: the kernel on a hole with terrain and zones at 500,000 complete shots/s
or more on two threads, beside the flat pga-driver, which must stay where it is; an aim search
of 200 aims x 10,000 shots on a hole with terrain in under 10 s on two cores; a whole course's
grid at 0.5 m under 200 MB. Each kernel rate is the best of three rounds of ``--shots`` shots of
the scenario's first point on 2 threads, after a warm-up (Numba's compilation) that is not
timed; the plane's rate is measured in the same run, as the machine's load moves both. Prints
a Markdown table and writes ``benchmarks/results/holes.md``; asserts nothing.
"""

import argparse
import time
from pathlib import Path

import numba
import numpy as np

from mcrun.engine.backend import simulate_batch
from mcrun.hole.hole import load_hole
from mcrun.run import aim, sampling
from mcrun.run import scenario as sc

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results" / "holes.md"
KERNEL_TARGET = 500_000
AIM_TARGET_S = 10.0
GRID_TARGET_B = 200e6
SCENARIOS = (
    ("pga-driver", "the plane (reference)"),
    ("par3-over-water", "mapped hole, flat"),
    ("par4-tee-shot", "mapped hole, flat"),
    ("wedge-two-tier-firm", "mapped hole, two-tier ground"),
    ("drive-real-ground", "USGS 3DEP ground (every cell curved)"),
)


def kernel_rate(name, n, threads=2):
    s = sc.load(ROOT / "scenarios" / f"{name}.toml")
    terrain = None if s.hole is None else s.hole.terrain()
    inputs, _ = sampling.sample(s, s.points[0], 0, n)
    simulate_batch(inputs[:16], terrain=terrain)
    previous = numba.get_num_threads()
    numba.set_num_threads(threads)
    try:
        best = np.inf
        for _ in range(3):
            t = time.perf_counter()
            simulate_batch(inputs, terrain=terrain)
            best = min(best, time.perf_counter() - t)
    finally:
        numba.set_num_threads(previous)
    return n / best


def aim_seconds(name, aims, n):
    s = sc.load(ROOT / "scenarios" / f"{name}.toml")
    aim.search(s, n=100, offsets_m=[0.0])  # compiled, the hole's grid built
    offsets = np.linspace(-20.0, 20.0, aims)
    t = time.perf_counter()
    result = aim.search(s, n=n, offsets_m=offsets)
    return time.perf_counter() - t, result.shots_flown


def course_grid_bytes():
    hole = load_hole(ROOT / "scenarios" / "holes" / "riverside-9.toml")
    t = hole.terrain_over(hole.course_extent_m())
    arrays = (t.height_m, t.zone, t.turf, t.penalty, t.calm)
    return sum(a.nbytes for a in arrays), t.height_m.shape


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m benchmarks.holes", description=__doc__)
    p.add_argument("--shots", type=int, default=100_000, help="shots per kernel round")
    p.add_argument("--aims", type=int, default=200, help="aims of the aim search")
    p.add_argument("--aim-shots", type=int, default=10_000, help="shots per aim")
    args = p.parse_args(argv)
    lines = [
        "## Holes",
        "",
        f"The kernel on 2 threads ({args.shots:,} shots of each scenario, best of 3, "
        "compilation excluded), beside the plane in the same run:",
        "",
        "| scenario | ground | shots/s | target |",
        "|---|---|---|---|",
    ]
    for name, ground in SCENARIOS:
        rate = kernel_rate(name, args.shots)
        target = "(reference)" if name == "pga-driver" else (
            f">= {KERNEL_TARGET:,}: {'met' if rate >= KERNEL_TARGET else 'NOT met'}"
        )  # fmt: skip
        lines.append(f"| {name} | {ground} | {rate:,.0f} | {target} |")
        print(lines[-1], flush=True)
    seconds, flown = aim_seconds("wedge-two-tier-firm", args.aims, args.aim_shots)
    met = "met" if seconds < AIM_TARGET_S else "NOT met"
    lines += [
        "",
        f"Aim search on wedge-two-tier-firm (two-tier ground, zones): {args.aims} aims x "
        f"{args.aim_shots:,} shots ({flown:,} shots, each scored by expected strokes): "
        f"{seconds:.1f} s (target < {AIM_TARGET_S:g} s: {met}).",
    ]
    print(lines[-1], flush=True)
    size, shape = course_grid_bytes()
    lines += [
        "",
        f"The whole Riverside course at 0.5 m: {shape[1]} x {shape[0]} nodes, {size / 1e6:.1f} MB "
        f"of grid (target < {GRID_TARGET_B / 1e6:.0f} MB: "
        f"{'met' if size < GRID_TARGET_B else 'NOT met'}).",
    ]
    print(lines[-1])
    RESULTS.write_text("\n".join(lines) + "\n")
    print(f"wrote {RESULTS}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
