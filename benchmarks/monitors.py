"""``python -m benchmarks.monitors [--rows N]``: reading and replaying a launch-monitor export.

The issue's target: reading a 100,000-row session and replaying it in under 2 s plus the
simulation. A TrackMan Normalized export of N rows (``sep=`` line, unit row, the 7-iron and
driver of ``tests/data/monitors/trackman-normalized.csv`` repeated, launches varied row by
row) is written to a temporary folder; then, best of three rounds after a warm-up (Numba's
compilation) that is not timed: the read (``monitors.read_session``), the whole replay
(``replay.replay``, the per-club summary and the comparison with the device) and the kernel
alone on the same inputs. Reading + replaying - kernel is what the target bounds. Prints a
Markdown table and writes ``benchmarks/results/monitors.md``; asserts nothing.
"""

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from mcrun.api import conditions_inputs
from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import pack
from mcrun.run import clubs, replay
from mcrun.run.monitors import read_session

ROOT = Path(__file__).resolve().parents[1]
FIXTURE = ROOT / "tests" / "data" / "monitors" / "trackman-normalized.csv"
RESULTS = ROOT / "benchmarks" / "results" / "monitors.md"
TARGET_S = 2.0


def write_session(path, rows, seed=1):
    """A TrackMan Normalized export of ``rows`` shots, the fixture's two shots varied."""
    lines = FIXTURE.read_text(encoding="utf-8").splitlines()
    head, shots = lines[:3], lines[3:]
    header = head[1].split(",")
    speed = header.index("Ball Speed")
    rng = np.random.default_rng(seed)
    body = []
    for k in range(rows):
        fields = shots[k % 2].split(",")
        fields[speed] = f"{float(fields[speed]) + rng.normal(0.0, 2.0):.1f}"
        body.append(",".join(fields))
    path.write_text("\n".join(head + body) + "\n", encoding="utf-8")


def best(function, rounds=3):
    times = []
    for _ in range(rounds):
        started = time.perf_counter()
        function()
        times.append(time.perf_counter() - started)
    return min(times)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m benchmarks.monitors")
    parser.add_argument("--rows", type=int, default=100_000)
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "session.csv"
        write_session(path, args.rows)
        session = read_session(path)
        replay.replay(session)  # warm-up: compiles or loads the kernel
        values, valid = replay.launches(session)
        names = ("ball_speed_mps", "launch_angle_rad", "spin_radps", "spin_axis_rad")
        quantities = ("ball_speed", "launch_angle", "spin", "spin_axis")
        inputs = dict(zip(names, (values[q] for q in quantities), strict=True))
        inputs["azimuth_rad"] = values["azimuth"]
        packed = pack({**conditions_inputs(), **inputs}, args.rows, invalid=~valid)

        def whole():
            frame = replay.replay(read_session(path))
            clubs.club_summary(frame)
            clubs.device_comparison(frame)

        read_s = best(lambda: read_session(path))
        whole_s = best(whole)
        kernel_s = best(lambda: simulate_batch(packed))
    overhead = whole_s - kernel_s
    met = "yes" if overhead < TARGET_S else "no"
    table = "\n".join(
        [
            f"Reading and replaying a {args.rows:,}-row TrackMan Normalized export "
            "(best of 3, compilation excluded).",
            "",
            "| step | time (s) |",
            "|---|---|",
            f"| read (monitors.read_session) | {read_s:.3f} |",
            f"| read + replay + per-club summary + comparison | {whole_s:.3f} |",
            f"| of which the kernel (simulate_batch) | {kernel_s:.3f} |",
            f"| read + replay without the kernel (target < {TARGET_S:g} s, met: {met}) "
            f"| {overhead:.3f} |",
        ]
    )
    print(table)
    RESULTS.write_text("## Launch-monitor sessions\n\n" + table + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
