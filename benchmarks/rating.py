"""``python -m benchmarks.rating [--n N] [--skip-course]``: courses rated by simulating the
handicap system's model players (``mcrun.play.rating``), against the system's length rule, and a
real course from its map, timed.

- The length rule: made-up open courses (``hole.synthetic.open_course``: 18 straight, flat holes,
  fairways 40 m wide, round greens of 560 m^2, no hazards; four par 3s, ten par 4s and four par
  5s) of 5,500, 6,000, 6,500 and 7,000 yd. Their holes of one par are alike, so each course's
  par 3, par 4 and par 5 are solved once for each player and the 18-hole ratings put together
  from them (each hole's plays drawn apart). The targets (the issue): the scratch rating rises
  one stroke per 220 yd within 15 % and the bogey rating one per 160 yd within 20 % (the
  slopes of a straight line fitted through the four), and the scratch rating within 2 strokes of
  length / 220 + 40.9 at every length.
- The model players on a flat open par 4 of 400 yd, against the scores their approach
  proximity was fitted to (``calibration.AMATEUR_TARGETS``).
- The library's course map (Riverside, Zagreb: 18 holes, each rated from its line's first point
  to its pin, par by length), both players: its ratings and the time, against the target of an
  18-hole course in under 15 minutes on two cores. The first rating of a course also builds its
  greens' expected-putts maps for the scratch and the 15-handicap putters (cached after): the
  time is given with them and without.

Prints a Markdown report and writes ``benchmarks/results/rating.md``; asserts nothing.
"""

import argparse
import dataclasses
import json
import os
import tempfile
import time
from pathlib import Path

import numpy as np

from benchmarks.common import publish
from mcrun.cli.rate import course_holes
from mcrun.hole.synthetic import open_course, pars_for
from mcrun.play.rating import BETTER_HALF, EXPECTED, CourseRating, rate
from mcrun.strokes.baseline import YARD_M

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results" / "rating.md"
COURSE = ROOT / "scenarios" / "holes" / "riverside-zagreb.osm.geojson"
LENGTHS_YD = (5500, 6000, 6500, 7000)
YD_PER_STROKE = {"scratch": (220.0, 0.15), "bogey": (160.0, 0.20)}
LENGTH_RATING = {"scratch": (220.0, 40.9), "bogey": (160.0, 50.7)}
WITHIN_STROKES = 2.0
TARGET_S = 15 * 60.0


def open_rating(length_yd, n):
    """The CourseRating of an open course of ``length_yd``: its distinct holes (one of each
    par) solved, each of the 18 holes given its par's solve, and the seconds it took."""
    pars = pars_for(18)
    first = {par: pars.index(par) for par in sorted(set(pars))}
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"open-{length_yd}.geojson"
        path.write_text(json.dumps(open_course(length_yd)))
        _, holes, _ = course_holes(path)
        started = time.perf_counter()
        distinct = rate([holes[k] for k in first.values()], n=n)
        seconds = time.perf_counter() - started
    scores = {}
    for player in distinct.players:
        of_par = dict(zip(first, distinct.scores[player], strict=True))
        scores[player] = [dataclasses.replace(of_par[par], hole=k + 1)
                          for k, par in enumerate(pars)]  # fmt: skip
    return CourseRating(holes, distinct.players, scores, distinct.seed), seconds


def length_rule(n):
    """Report lines of the length rule's table and targets."""
    rows, ratings = [], {p: [] for p in YD_PER_STROKE}
    for length in LENGTHS_YD:
        rating, seconds = open_rating(length, n)
        for player in YD_PER_STROKE:
            ratings[player].append(rating.rating(player))
        rule = length / 220.0 + 40.9
        rows.append(f"| {length:,} | {rating.rating('scratch'):.1f} | "
                    f"{rating.rating('scratch', BETTER_HALF):.1f} | {rule:.1f} | "
                    f"{rating.rating('bogey'):.1f} | {rating.rating('bogey', BETTER_HALF):.1f} | "
                    f"{length / 160.0 + 50.7:.1f} | {rating.slope():d} | "
                    f"{seconds:.0f} |")  # fmt: skip
    lines = ["## The length rule: open courses", "",
             "| length (yd) | scratch: expected | better half | length / 220 + 40.9 | bogey: "
             "expected | better half | length / 160 + 50.7 | Slope (expected) | solves (s) |",
             "|---|---|---|---|---|---|---|---|---|", *rows, ""]  # fmt: skip
    for player, (yd, tolerance) in YD_PER_STROKE.items():
        slope = float(np.polyfit(LENGTHS_YD, ratings[player], 1)[0])
        per = 1.0 / slope if slope > 0 else float("inf")
        met = abs(per / yd - 1.0) <= tolerance
        lines.append(f"- {player}: one stroke per {per:.0f} yd of length (the system's {yd:.0f}, "
                     f"within {100 * tolerance:.0f} %: {'met' if met else 'NOT met'})")  # fmt: skip
    worst = max(abs(r - (length / 220.0 + 40.9))
                for r, length in zip(ratings["scratch"], LENGTHS_YD, strict=True))  # fmt: skip
    lines += [f"- scratch within {WITHIN_STROKES:g} strokes of length / 220 + 40.9 at every "
              f"length: worst {worst:.1f} ({'met' if worst <= WITHIN_STROKES else 'NOT met'})",
              ""]  # fmt: skip
    return lines


def course_rating(n, path=COURSE):
    """Report lines of a real course rated from its map."""
    _, holes, _ = course_holes(path)
    started = time.perf_counter()
    rating = rate(holes, n=n)
    seconds = time.perf_counter() - started
    length = rating.length_yd
    title = holes[0].name.split(",")[0] if holes[0].name else path.name
    lines = [f"## {title}: {len(holes)} holes, {length:,.0f} yd (par "
             f"{sum(h.par for h in holes)}, by length)", "",
             "| hole | par | yd | scratch | bogey | bogey - scratch |",
             "|---|---|---|---|---|---|"]  # fmt: skip
    for k, hole in enumerate(holes):
        s, b = (rating.scores[p][k] for p in rating.players)
        lines.append(f"| {s.hole} | {hole.par} | {hole.length_m / YARD_M:.0f} | "
                     f"{s.expected_strokes:.3f} +- {s.expected_strokes_se:.3f} | "
                     f"{b.expected_strokes:.3f} +- {b.expected_strokes_se:.3f} | "
                     f"{b.expected_strokes - s.expected_strokes:+.3f} |")  # fmt: skip
    lines.append("")
    for reading in (EXPECTED, BETTER_HALF):
        cr, br = (rating.rating(p, reading) for p in rating.players)
        lines.append(f"- {reading}: Course Rating {cr:.1f}, Bogey Rating {br:.1f}, Slope Rating "
                     f"{rating.slope(reading)}")  # fmt: skip
    lines += [f"- the length rule: scratch {length / 220 + 40.9:.1f}, bogey "
              f"{length / 160 + 50.7:.1f}",
              f"- {seconds / 60:.1f} minutes in all (the greens' maps for the scratch and the "
              f"15-handicap putters built on the way where not cached); target under "
              f"{TARGET_S / 60:.0f}: {'met' if seconds < TARGET_S else 'NOT met'}", "",
              "Map data (c) OpenStreetMap contributors, ODbL.", ""]  # fmt: skip
    return lines


def fit_check(n=50):
    """Report lines of the model players on a flat open par 4 of 400 yd, against the scores
    their approach proximity was fitted to (``calibration.AMATEUR_TARGETS``)."""
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "open-400.geojson"
        path.write_text(json.dumps(open_course(400, pars=(4,))))
        _, holes, _ = course_holes(path)
        rating = rate(holes, n=n)
    scratch, bogey = (rating.rating(p) for p in rating.players)
    return ["## The model players on a flat open par 4 of 400 yd", "",
            f"n = {n}: scratch {scratch:.3f} (fitted to 4.29: Table 9's 3.99 + 0.30), bogey "
            f"{bogey:.3f} (fitted to 5.46: scratch + 1.17), {bogey - scratch:+.3f} apart.",
            ""]  # fmt: skip


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=100)
    parser.add_argument("--skip-course", action="store_true")
    args = parser.parse_args(argv)
    threads = len(os.sched_getaffinity(0))
    lines = ["# Courses rated by simulating the model players", "",
             f"`python -m benchmarks.rating --n {args.n}` on {threads} threads.", ""]  # fmt: skip
    lines += length_rule(args.n)
    if not args.skip_course:
        lines += course_rating(args.n)
    lines += fit_check()
    publish(RESULTS, lines)


if __name__ == "__main__":
    main()
