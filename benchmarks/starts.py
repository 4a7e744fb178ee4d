"""``python -m benchmarks.starts [--starts M] [--shots N] [--dask W]``: shots from many start
points of a hole against the same number of shots from the tee.

The issue's target: 10,000 start points x 200 shots on a library hole at 80 % or more of the
rate of 2,000,000 shots from the tee. The hole is par4-tee-shot's, its scenario's one point (a
Tour drive); the starts are places in play within 75 m of the tee (a seeded draw from a 1 m
grid), so that their shots fly as far over the same hole as the tee's do and stay on its map
as often: starts anywhere on the hole would send drives off the map, which ends them sooner and
would flatter the rate. Each start aims at the pin.

Measured on 2 threads, after a warm-up (compilation, the hole's grid) that is not timed, best
of ``--rounds``:

- the kernel: the tee's shots in the chunks a run cuts (65,536 shots, ``simulate_batch``),
  against the starts' batches as ``run.starts`` builds them (``tile``: 256 starts x 200 shots,
  their inputs copied per start);
- the whole: the same, each chunk scored in expected strokes (``results.on_hole.scores``), and
  the starts reduced to per-start means (``run.starts.play_from``);
- with ``--dask W``, ``play_from`` on a local cluster of W single-threaded workers, checked bit
  for bit against the local result.

Prints a Markdown table and writes ``benchmarks/results/starts.md``; asserts nothing.
"""

import argparse
import time
from pathlib import Path

import numba
import numpy as np

from mcrun.engine.backend import simulate_batch
from mcrun.results import on_hole
from mcrun.run import plan, sampling, starts
from mcrun.run import scenario as sc

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results" / "starts.md"
SCENARIO = "par4-tee-shot"
TARGET_SHARE = 0.8
NEAR_TEE_M = 75.0


def start_points(hole, m, seed=0):
    """``m`` places in play within NEAR_TEE_M of the tee: a seeded draw from a 1 m grid."""
    grid = starts.starts_grid(hole, 1.0)
    near = grid[np.hypot(grid[:, 0], grid[:, 1]) <= NEAR_TEE_M]
    if len(near) < m:
        raise SystemExit(f"only {len(near)} places in play within {NEAR_TEE_M:g} m of the tee")
    pick = np.random.default_rng(seed).choice(len(near), size=m, replace=False)
    return near[np.sort(pick)]


def _best(rounds, work):
    best = np.inf
    for _ in range(rounds):
        t = time.perf_counter()
        work()
        best = min(best, time.perf_counter() - t)
    return best


def tee_seconds(scenario, total, scored, rounds):
    """Seconds for ``total`` shots from the tee in a run's chunks (scored or not)."""
    hole, point = scenario.hole, scenario.points[0]
    terrain = hole.terrain()
    chunk = plan.DEFAULT_CHUNK_SIZE
    batches = [sampling.sample(scenario, point, c, min(c + chunk, total))[0]
               for c in range(0, total, chunk)]  # fmt: skip

    def work():
        for inputs in batches:
            out = simulate_batch(inputs, terrain=terrain)
            if scored:
                on_hole.scores(hole, out)

    return _best(rounds, work)


def starts_kernel_seconds(scenario, points, n, rounds):
    """Seconds for the kernel alone on the starts' batches, their tiling included."""
    hole, point = scenario.hole, scenario.points[0]
    terrain = hole.terrain()
    inputs, _ = sampling.sample(scenario, point, 0, n)
    k = starts.DEFAULT_CHUNK_STARTS

    def work():
        for c in range(0, len(points), k):
            batch = starts.tile(inputs, point.play, points[c : c + k], hole.pin_xy)
            simulate_batch(batch, terrain=terrain)

    return _best(rounds, work)


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m benchmarks.starts", description=__doc__)
    p.add_argument("--starts", type=int, default=10_000, help="start points")
    p.add_argument("--shots", type=int, default=200, help="shots per start point")
    p.add_argument("--rounds", type=int, default=3, help="rounds, the best counted")
    p.add_argument("--dask", type=int, default=0, help="workers of a local Dask cluster (0: none)")
    args = p.parse_args(argv)
    scenario = sc.load(ROOT / "scenarios" / f"{SCENARIO}.toml")
    points = start_points(scenario.hole, args.starts)
    total = args.starts * args.shots
    previous = numba.get_num_threads()
    numba.set_num_threads(min(2, numba.config.NUMBA_NUM_THREADS))
    try:
        starts.play_from(scenario, points[:4], n=args.shots)  # warm: compiled, grid built
        tee_kernel = tee_seconds(scenario, total, False, args.rounds)
        many_kernel = starts_kernel_seconds(scenario, points, args.shots, args.rounds)
        tee_whole = tee_seconds(scenario, total, True, args.rounds)
        result = None

        def whole():
            nonlocal result
            result = starts.play_from(scenario, points, n=args.shots)

        many_whole = _best(args.rounds, whole)
    finally:
        numba.set_num_threads(previous)
    lines = [
        "## Shots from many start points",
        "",
        f"{SCENARIO}: {args.starts:,} start points within {NEAR_TEE_M:g} m of the tee x "
        f"{args.shots} shots ({total:,} shots), each start aimed at the pin, against "
        f"{total:,} shots from the tee; 2 threads, best of {args.rounds} "
        f"(target: the starts at {TARGET_SHARE:.0%} or more of the tee's rate).",
        "",
        "| what | from the tee (shots/s) | from the start points (shots/s) | share | target |",
        "|---|---|---|---|---|",
    ]
    for what, tee, many in (
        ("kernel", tee_kernel, many_kernel),
        ("kernel + expected strokes", tee_whole, many_whole),
    ):
        share = tee / many
        met = "met" if share >= TARGET_SHARE else "NOT met"
        lines.append(f"| {what} | {total / tee:,.0f} | {total / many:,.0f} | {share:.0%} | {met} |")
        print(lines[-1], flush=True)
    if args.dask:
        from mcrun.run import distributed

        with distributed.local_cluster(args.dask) as cluster, _client(cluster) as client:
            starts.play_from(scenario, points[:4], n=args.shots, client=client)  # warm workers
            t = time.perf_counter()
            on_dask = starts.play_from(scenario, points, n=args.shots, client=client)
            seconds = time.perf_counter() - t
        same = all(
            np.array_equal(a, b, equal_nan=True)
            for a, b in zip(_arrays(result), _arrays(on_dask), strict=True)
        )
        lines += [
            "",
            f"On a local Dask cluster of {args.dask} single-threaded workers: "
            f"{total / seconds:,.0f} shots/s (the chunks of {starts.DEFAULT_CHUNK_STARTS} starts "
            f"are the tasks); the same as the local result bit for bit: {same}.",
        ]
        print(lines[-1])
    RESULTS.write_text("\n".join(lines) + "\n")
    print(f"wrote {RESULTS}")
    return 0


def _client(cluster):
    from distributed import Client

    return Client(cluster)


def _arrays(result):
    frame = result.frame()
    return [frame[c].to_numpy() for c in frame.columns if c != "lie"]


if __name__ == "__main__":
    raise SystemExit(main())
