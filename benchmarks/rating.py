"""``python -m benchmarks.rating``: courses rated by simulating the handicap system's model
players (``mcrun.play.rating``), against the system's length rule, and a real course from its
map, timed. Options: ``--n N``, ``--skip-length``, ``--skip-course``, ``--skip-men``,
``--skip-women``, ``--output MD``.

- The length rule: made-up open courses (``hole.synthetic.open_course``: 18 straight, flat holes,
  fairways 40 m wide, round greens of 560 m^2, no hazards; four par 3s, ten par 4s and four par
  5s) of 5,500, 6,000, 6,500 and 7,000 yd for the men, 4,500, 5,000, 5,500 and 6,000 yd for the
  women. Their holes of one par are alike, so each course's par 3, par 4 and par 5 are solved
  once for each player and the 18-hole ratings put together from them (each hole's plays drawn
  apart). The targets (the issue, for the men): the scratch rating rises one stroke per 220 yd
  within 15 % and the bogey rating one per 160 yd within 20 % (the slopes of a straight line
  fitted through the four), and the scratch rating within 2 strokes of length / 220 + 40.9 at
  every length (in both readings: the expected score and the better half). Each model player's
  day form (``rating.DAY_FORM``) fitted again on these courses, beside the one in use. The
  women's against their rules (``rating.LENGTH_RATING``: 180 and 120 yd a
  stroke) at the same tolerances (ours: the issue sets none for them).
- The model players on a flat open par 4 of 400 yd (the women's of 336 yd, as much shorter as
  their scratch player's drive), against the scores the men's approach proximity was fitted to
  (``calibration.AMATEUR_TARGETS``); the women's bogey - scratch against 26.6 / 18 = 1.48 a hole
  (a Slope of 113 at the women's 4.24 a stroke).
- The library's course map (Riverside, Zagreb: 18 holes, par by length), rated for the men from
  each hole line's first point (the back tees) and for the women from each hole's front tee
  box in the map (``--tees forward``): its ratings and the time, against the target of an
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
from mcrun.play.rating import (
    BETTER_HALF,
    DAY_FORM,
    EXPECTED,
    KNUTH_GAP,
    LENGTH_RATING,
    MODEL_PLAYERS,
    SLOPE_FACTOR,
    CourseRating,
    better_half_gap,
    fit_day_form,
    length_rating,
    rate,
)
from mcrun.strokes.baseline import YARD_M

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results" / "rating.md"
COURSE = ROOT / "scenarios" / "holes" / "riverside-zagreb.osm.geojson"
LENGTHS_YD = {"men": (5500, 6000, 6500, 7000), "women": (4500, 5000, 5500, 6000)}
TOLERANCE = (0.15, 0.20)  # of the scratch and the bogey player's yards a stroke
WITHIN_STROKES = 2.0
FIT_HOLE_YD = {"men": 400, "women": 336}
COURSE_TEES = {"men": None, "women": "forward"}
TARGET_S = 15 * 60.0


def open_rating(length_yd, n, sex="men"):
    """The CourseRating of an open course of ``length_yd`` for ``sex``'s model players: its
    distinct holes (one of each par) solved, each of the 18 holes given its par's solve, and
    the seconds it took."""
    pars = pars_for(18)
    first = {par: pars.index(par) for par in sorted(set(pars))}
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"open-{length_yd}.geojson"
        path.write_text(json.dumps(open_course(length_yd)))
        _, holes, *_ = course_holes(path)
        started = time.perf_counter()
        distinct = rate([holes[k] for k in first.values()], n=n, women=sex == "women")
        seconds = time.perf_counter() - started
    scores = {}
    for player in distinct.players:
        of_par = dict(zip(first, distinct.scores[player], strict=True))
        scores[player] = [dataclasses.replace(of_par[par], hole=k + 1)
                          for k, par in enumerate(pars)]  # fmt: skip
    return CourseRating(holes, distinct.players, scores, distinct.seed, sex == "women"), seconds


def _rule(player):
    yd, strokes = LENGTH_RATING[player]
    return f"length / {yd:.0f} + {strokes}"


def length_rule(n, sex="men"):
    """Report lines of the length rule's table and targets for ``sex``'s model players."""
    players = MODEL_PLAYERS[sex]
    scratch, bogey = players
    lengths = LENGTHS_YD[sex]
    rows, ratings, halves = [], {p: [] for p in players}, []
    courses = {p: [] for p in players}
    for length in lengths:
        rating, seconds = open_rating(length, n, sex)
        for player in players:
            ratings[player].append(rating.rating(player))
            courses[player].append(rating.scores[player])
        halves.append(rating.rating(scratch, BETTER_HALF) - length_rating(scratch, length))
        rows.append("| " + " | ".join([f"{length:,}", *(
            f"{rating.rating(p):.1f} | {rating.rating(p, BETTER_HALF):.1f} | "
            f"{length_rating(p, length):.1f}" for p in players),
            f"{rating.slope():d}", f"{seconds:.0f}"]) + " |")  # fmt: skip
    lines = [f"## The length rule: open courses, the {sex}'s model players", "",
             "| length (yd) | " + " | ".join(f"{p}: expected | better half | {_rule(p)}"
                                           for p in players)
             + " | Slope (expected) | solves (s) |", "|---" * 9 + "|", *rows, ""]  # fmt: skip
    for player, tolerance in zip(players, TOLERANCE, strict=True):
        yd = LENGTH_RATING[player][0]
        slope = float(np.polyfit(lengths, ratings[player], 1)[0])
        per = 1.0 / slope if slope > 0 else float("inf")
        met = abs(per / yd - 1.0) <= tolerance
        lines.append(f"- {player}: one stroke per {per:.0f} yd of length (the system's {yd:.0f}, "
                     f"within {100 * tolerance:.0f} %: {'met' if met else 'NOT met'})")  # fmt: skip
    off = [r - length_rating(scratch, length)
           for r, length in zip(ratings[scratch], lengths, strict=True)]  # fmt: skip
    worst = max(abs(v) for v in off)
    lines += [f"- {scratch} within {WITHIN_STROKES:g} strokes of {_rule(scratch)} at every "
              f"length: {min(off):+.1f} to {max(off):+.1f} "
              f"({'met' if worst <= WITHIN_STROKES else 'NOT met'})"]  # fmt: skip
    lines.append(
        f"- {scratch}'s better half against the same: {min(halves):+.1f} to "
        f"{max(halves):+.1f} "
        f"({'met' if max(map(abs, halves)) <= WITHIN_STROKES else 'NOT met'})"
    )
    for player in players:
        fitted = fit_day_form(courses[player], rating.seed)
        alone = np.mean([better_half_gap(c, rating.seed) for c in courses[player]])
        lines.append(
            f"- {player}'s day form fitted to a better half {KNUTH_GAP:g} strokes below "
            f"the average over these courses: {fitted:.3f} (in use "
            f"{DAY_FORM[player]:.3f}; with independent holes the gap is {alone:.2f})"
        )
    return lines + [""]


def course_rating(n, sex="men", path=COURSE):
    """Report lines of a real course rated from its map for ``sex``'s model players (the men
    from the back tees, the women from each hole's front tee box: ``COURSE_TEES``)."""
    women = sex == "women"
    tees = COURSE_TEES[sex]
    _, holes, *_ = course_holes(path, women=women, tees=tees)
    started = time.perf_counter()
    rating = rate(holes, n=n, women=women)
    seconds = time.perf_counter() - started
    length = rating.length_yd
    scratch, bogey = rating.players
    title = holes[0].name.split(",")[0] if holes[0].name else path.name
    lines = [f"## {title}, the {sex}'s model players: {len(holes)} holes, {length:,.0f} yd from "
             f"{'the back tees' if tees is None else 'the front tee boxes'} (par "
             f"{sum(h.par for h in holes)}, by length)", "",
             f"| hole | par | yd | {scratch} | {bogey} | {bogey} - {scratch} |",
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
        plays = ", ".join(f"{p} {rating.plays_as_yd(p, reading):,.0f}" for p in rating.players)
        lines.append(f"- {reading}: Course Rating {cr:.1f}, Bogey Rating {br:.1f}, Slope Rating "
                     f"{rating.slope(reading)}; plays as (yd) {plays}")  # fmt: skip
    rule = ", ".join(f"{p} {length_rating(p, length):.1f}" for p in rating.players)
    lines += [f"- the length rule: {rule}",
              f"- {seconds / 60:.1f} minutes in all (the greens' maps for the scratch and the "
              f"15-handicap putters built on the way where not cached); target under "
              f"{TARGET_S / 60:.0f}: {'met' if seconds < TARGET_S else 'NOT met'}", "",
              "Map data (c) OpenStreetMap contributors, ODbL.", ""]  # fmt: skip
    return lines


def fit_check(n=50, sex="men"):
    """Report lines of ``sex``'s model players on a flat open par 4 (``FIT_HOLE_YD``), against
    the scores the men's approach proximity was fitted to (``calibration.AMATEUR_TARGETS``)."""
    yd = FIT_HOLE_YD[sex]
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"open-{yd}.geojson"
        path.write_text(json.dumps(open_course(yd, pars=(4,))))
        _, holes, *_ = course_holes(path)
        rating = rate(holes, n=n, women=sex == "women")
    (first, scratch), (second, bogey) = ((p, rating.rating(p)) for p in rating.players)
    standard = 113 / SLOPE_FACTOR[sex] / 18
    targets = ("fitted to 4.29: Table 9's 3.99 + 0.30", "fitted to 5.46: scratch + 1.17")
    if sex == "women":
        targets = ("the men's scratch on 400 yd: 4.29", "a Slope of 113: scratch + "
                   f"{standard:.2f}")  # fmt: skip
    return [f"## The {sex}'s model players on a flat open par 4 of {yd} yd", "",
            f"n = {n}: {first} {scratch:.3f} ({targets[0]}), {second} {bogey:.3f} "
            f"({targets[1]}), {bogey - scratch:+.3f} apart (at a Slope of 113: "
            f"{standard:+.3f}).", ""]  # fmt: skip


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=100)
    parser.add_argument("--skip-length", action="store_true")
    parser.add_argument("--skip-course", action="store_true")
    parser.add_argument("--skip-men", action="store_true")
    parser.add_argument("--skip-women", action="store_true")
    parser.add_argument("--output", type=Path, default=RESULTS, help="the report (%(default)s)")
    args = parser.parse_args(argv)
    threads = len(os.sched_getaffinity(0))
    sexes = [s for s in ("men", "women") if not getattr(args, f"skip_{s}")]
    lines = ["# Courses rated by simulating the model players", "",
             f"`python -m benchmarks.rating --n {args.n}` on {threads} threads.", ""]  # fmt: skip
    for sex in [] if args.skip_length else sexes:
        lines += length_rule(args.n, sex)
    if not args.skip_course:
        for sex in sexes:
            lines += course_rating(args.n, sex)
    for sex in sexes:
        lines += fit_check(sex=sex)
    publish(args.output, lines)


if __name__ == "__main__":
    main()
