"""The best aim: where to aim each club of a scenario on its hole to leave the fewest expected
strokes (``mcrun.strokes``), found with common random numbers.

An aim is a start line: the bearing from where the clubs are hit (the tee, or the scenario's
start on the hole) of an aim point, given as its offset (m, + to the right) at the pin's
distance from the line to the pin; how far the ball goes is the club's
(a scenario's groups are its clubs). Every aim of a club is flown with the same sampled shots,
the same swing turned by the aim (``sampling.sample``, its azimuths plus the bearing), so that
the difference between two aims is measured shot by shot: its standard error is that of the
paired differences, far smaller than either value's.

The search is coarse to fine: aims ``coarse_m`` apart over the region, then, around the best
so far, aims a third as far apart, until they are ``resolution_m`` apart; each round flies the
club's shots once per new aim, its aims the tasks of the executor (``mcrun.executor``: an aim's
shots on one thread, the round's aims on all of them).

Before the search, ``check`` refuses what it cannot do in one line naming the option (a value
that is not a finite number, fewer than two shots, more than ``MAX_AIMS`` aims of a club, a
search whose shots would not fit in the memory there is: ``memory_bytes``), and its plan
(``SearchPlan.line``) says what it will fly. After it, a search none of whose shots stayed on
the hole's map is refused (its "best" aim would be one of a row of equal penalties); the shots
of a best aim that left the map are counted (``ClubAims.off_map``) for the command line's
warning.

The table of every aim flown (``table``) is written as a run's files are (``write_table``):
atomically, with the provenance of a run of the scenario (``plan.provenance``: the scenario,
seed, N, versions, and the geometry: the hole's frame, tee, pin, the scenario's aim, each
club's target and the hole's map, ``mcrun.results.geometry``) and the baseline it was scored
by.
"""

import math
import os
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numba
import numpy as np
import pandas as pd

from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import COLUMN, FINAL_X, FINAL_Y, N_INPUT, N_OUTCOME
from mcrun.executor import Executor
from mcrun.putting.on_hole import map_of_hole
from mcrun.quantities import InputError
from mcrun.results import on_hole, output
from mcrun.run import plan, sampling
from mcrun.run import scenario as scenario_module
from mcrun.strokes import start_of, tour_baseline
from mcrun.units import shown

AZIMUTH = COLUMN["azimuth_rad"]
DEFAULT_HALF_WIDTH_M = 20.0
DEFAULT_COARSE_M = 5.0
DEFAULT_RESOLUTION_M = 1.0
TOUR_BASELINE = "PGA Tour (Broadie 2012)"
TABLE_SUFFIXES = (".parquet", ".pq")
# The most aims a club may have: its coarse aims, or the aims given. 4 km of region at the
# default step; a search over more is a mistake (``--half-width 1e9``: 4 x 10^8 aims).
MAX_AIMS = 801
# The finest spacing may be at most this many times finer than the coarse step.
MAX_REFINEMENT = 1e6
# The refinement after the coarse aims: rounds of at most this many new aims each.
NEW_AIMS_PER_ROUND = 6
# The rounds a search may go on past the edge of the aims flown where its best aim is there,
# at the step it had (each at most NEW_AIMS_PER_ROUND new aims).
WALK_ROUNDS = 4
# What a search holds per shot besides its inputs and outcomes: the azimuths, and the columns of
# the scoring of one aim (``strokes.score_shots``), 8 bytes each.
SCORING_COLUMNS = 24
# The names of ``search``'s arguments in messages (the command line gives its options').
ARGUMENT_NAMES = {
    "n": "n",
    "centre_m": "centre_m",
    "half_width_m": "half_width_m",
    "coarse_m": "coarse_m",
    "resolution_m": "resolution_m",
    "offsets_m": "offsets_m",
}


class AimError(InputError):
    """An aim search that cannot run; the message is one line."""


@dataclass
class ClubAims:
    """The aims flown for one club (a point of the scenario) and what they leave."""

    club: str
    offsets_m: list = field(default_factory=list)  # aim offsets flown, m right at the pin
    expected: list = field(default_factory=list)  # mean expected strokes after the shot
    expected_se: list = field(default_factory=list)
    difference: list = field(default_factory=list)  # minus that of the reference aim
    difference_se: list = field(default_factory=list)  # paired standard error
    scores: dict = field(default_factory=dict)  # offset -> per-shot expected strokes after
    reference_m: float = 0.0  # the aim the differences are to (the pin, or the scenario's)
    off_map: dict = field(default_factory=dict)  # offset -> shots that left the hole's map
    at_edge: bool = False  # its best aim the first or last flown, where the search stopped

    @property
    def best(self):
        """Index of the aim with the fewest expected strokes."""
        return int(np.nanargmin(self.expected))

    def best_between_m(self):
        """The best aim between those flown (m right at the pin): the vertex of the parabola
        through the best flown aim and its two neighbours, finer than the aims themselves; the
        best flown aim where it is the first or the last of them, a neighbour has no value, or
        the three do not curve upwards. NaN where no aim has a value."""
        order = np.argsort(self.offsets_m)
        offsets = np.asarray(self.offsets_m, dtype=float)[order]
        expected = np.asarray(self.expected, dtype=float)[order]
        if not np.isfinite(expected).any():
            return math.nan
        k = int(np.nanargmin(np.where(np.isfinite(expected), expected, np.nan)))
        three = slice(k - 1, k + 2)
        if k == 0 or k == len(offsets) - 1 or not np.isfinite(expected[three]).all():
            return float(offsets[k])
        a, b, _ = np.polyfit(offsets[three], expected[three], 2)
        return float(-b / (2.0 * a)) if a > 0.0 else float(offsets[k])

    def off_map_share(self, k):
        """The share of the shots aimed ``offsets_m[k]`` that left the hole's map."""
        return self.off_map.get(self.offsets_m[k], 0) / max(len(self.scores[self.offsets_m[k]]), 1)


@dataclass
class AimSearch:
    """An aim search: each club's aims, the shots per aim, and how long it took."""

    scenario: object
    clubs: list
    n: int
    pin_distance_m: float  # from the start
    expected_start: float  # expected strokes from the start
    seconds: float
    shots_flown: int
    start_xy_m: tuple = (0.0, 0.0)  # where the clubs are hit from (the tee unless it says)

    @property
    def line_rad(self):
        """The bearing (rad, + right of +x) of the line from the start to the pin."""
        return _line_rad(self.scenario.hole, self.start_xy_m)

    def bearing_rad(self, offset_m):
        """The bearing (rad, + right of +x) of the aim ``offset_m`` right of the pin."""
        return self.line_rad + _bearing(offset_m, self.pin_distance_m)

    @property
    def from_tee(self):
        return self.start_xy_m == (0.0, 0.0)

    def best(self):
        """(club, index) of the aim with the fewest expected strokes of all the clubs."""
        k = int(np.nanargmin([c.expected[c.best] for c in self.clubs]))
        return self.clubs[k], self.clubs[k].best


def load_scenario(scenario, seed=None, seed_name="seed"):
    """The scenario of an aim search: a file or a library name (``scenario.find``), with
    ``seed`` (default its own; checked first, named ``seed_name``); AimError when it has no
    hole."""
    seed = None if seed is None else plan.positive_int(seed, seed_name, minimum=0)
    loaded = scenario_module.load(scenario_module.find(scenario))
    if seed is not None:
        loaded = plan.with_seed(loaded, seed)
    if loaded.hole is None:
        raise AimError(f"{loaded.path}: an aim search needs a hole ([hole] in the scenario)")
    return loaded


def check_output(path, force=False, option="-o", suffixes=TABLE_SUFFIXES, what=".parquet"):
    """``path`` where an output will be written, checked before the search: the right suffix,
    not a folder, not there yet unless ``force``, and in a folder that exists or can be made
    (its nearest existing parent a folder one can write in)."""
    destination = Path(path)
    if destination.suffix.lower() not in suffixes:
        raise AimError(f"{option} {path}: the output must be a {what} file")
    if destination.is_dir():
        raise AimError(f"{option} {path}: is a folder; give a file name")
    if destination.exists() and not force:
        raise AimError(f"{option} {path}: already exists: use --force to replace it")
    parent = destination.absolute().parent
    while not parent.exists() and parent.parent != parent:
        parent = parent.parent
    if not parent.is_dir():
        raise AimError(f"{option} {path}: {parent} is not a folder")
    try:  # the only sure test of a folder one can write in (root, read-only mounts, /proc)
        with tempfile.TemporaryFile(dir=parent):
            pass
    except OSError as err:
        raise AimError(f"{option} {path}: cannot write in {parent}: {err.strerror}") from None
    return destination


def _finite(value, name, positive=False):
    """``value`` as a float: finite (and > 0 when ``positive``), else AimError naming it."""
    try:
        number = float(value)
    except (TypeError, ValueError):
        number = math.nan
    if not math.isfinite(number) or (positive and number <= 0.0):
        allowed = "a finite number of metres" + (" > 0" if positive else "")
        raise AimError(f"{name} {value}: must be {allowed}")
    return number


def coarse_count(half_width_m, coarse_m):
    """How many coarse aims ``coarse_offsets`` gives, counted as it counts them (a huge region
    is refused before they are made)."""
    k = math.floor(half_width_m / coarse_m + 1e-9)
    return 2 * k + 1 + 2 * (half_width_m - k * coarse_m > 1e-9)


def coarse_offsets(half_width_m, coarse_m):
    """The coarse aims about the centre: the centre, ``coarse_m`` apart to either side, and
    the region's two edges (from its left edge alone, a half width that is no whole number of
    steps left the right of the region unflown: 7 m at 5 m steps flew -7, -2, 3)."""
    k = math.floor(half_width_m / coarse_m + 1e-9)
    inner = list(coarse_m * np.arange(-k, k + 1))
    if half_width_m - k * coarse_m > 1e-9:
        return [-half_width_m, *inner, half_width_m]
    return inner


def aims_per_club(half_width_m, coarse_m, resolution_m, offsets_m=None):
    """The aims a club will fly at most: ``offsets_m``, or the coarse aims of the region and
    the refinement's rounds (each a third of the step before, down to the resolution, and up
    to ``WALK_ROUNDS`` past an edge)."""
    if offsets_m is not None:
        return len(offsets_m) + 1  # and the reference
    coarse = coarse_count(half_width_m, coarse_m)
    rounds = max(0, math.ceil(math.log(coarse_m / resolution_m, 3.0) - 1e-9)) + WALK_ROUNDS
    return coarse + 1 + NEW_AIMS_PER_ROUND * rounds


def memory_bytes(clubs, n, aims, threads=None):
    """The memory (bytes) an aim search of ``clubs`` clubs of ``n`` shots and ``aims`` aims each
    holds at most: one club's inputs, and the inputs, outcomes and scoring of an aim on each of
    ``threads`` threads (default ``numba.get_num_threads()``) at a time, and every aim's score
    of every shot, kept for the table's paired differences."""
    threads = numba.get_num_threads() if threads is None else int(threads)
    return (8 * n * N_INPUT + 8 * n * threads * (N_INPUT + N_OUTCOME + SCORING_COLUMNS)
            + 8 * n * clubs * aims)  # fmt: skip


def available_memory():
    """The memory (bytes) this machine has available now (Linux's MemAvailable, else its
    physical memory), or None when it cannot be told."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, OSError, ValueError):
        return None


@dataclass(frozen=True)
class SearchPlan:
    """What an aim search will fly: the checked arguments of ``search``, the aims per club (at
    most) and an estimate of its time (s) and memory (bytes)."""

    n: int
    centre_m: float | None
    half_width_m: float
    coarse_m: float
    resolution_m: float
    offsets_m: list | None
    clubs: int
    aims: int
    seconds: float
    bytes: int

    def line(self):
        """One line for the terminal, as a run's plan line."""
        clubs = f"{self.clubs} club" + ("s" if self.clubs != 1 else "")
        shots = self.clubs * self.aims * self.n
        return (
            f"mcrun: {clubs} x up to {self.aims:,} aims x {self.n:,} shots = up to {shots:,} "
            f"shots; {'under' if self.seconds < 0.05 else 'about'} "
            f"{plan.duration_text(self.seconds)} of simulation, about "
            f"{plan.size_text(self.bytes)} of memory"
        )


def check(
    scenario,
    n=10_000,
    half_width_m=DEFAULT_HALF_WIDTH_M,
    centre_m=None,
    coarse_m=DEFAULT_COARSE_M,
    resolution_m=DEFAULT_RESOLUTION_M,
    offsets_m=None,
    names=None,
    memory=None,
):
    """The ``SearchPlan`` of ``search``'s arguments, before anything is flown; AimError (one
    line naming the argument, ``names``: {argument: name}, default ``ARGUMENT_NAMES``) for a
    value that is not a finite number, fewer than 2 shots (a standard error needs two), more
    than ``MAX_AIMS`` aims per club, or a search that would not fit in ``memory`` (bytes,
    default ``available_memory()``)."""
    names = {**ARGUMENT_NAMES, **(names or {})}
    if scenario.hole is None:
        raise AimError(f"{scenario.path}: an aim search needs a hole ([hole] in the scenario)")
    starts = dict.fromkeys(p.play.start_m for p in scenario.points)
    if len(starts) > 1:
        raise AimError(
            f"{scenario.path}: an aim search compares its clubs from one place, but its groups "
            f"start at {', '.join(str(list(s)) for s in starts)}: search each start apart"
        )
    n = plan.positive_int(n, names["n"], minimum=2)
    if centre_m is not None:
        centre_m = _finite(centre_m, names["centre_m"])
    half_width_m = _finite(half_width_m, names["half_width_m"], positive=True)
    coarse_m = _finite(coarse_m, names["coarse_m"], positive=True)
    resolution_m = _finite(resolution_m, names["resolution_m"], positive=True)
    if offsets_m is not None:
        if isinstance(offsets_m, str | bytes) or not isinstance(offsets_m, list | tuple |
                                                                   np.ndarray):  # fmt: skip
            raise AimError(f"{names['offsets_m']} {shown(offsets_m)}: allowed: a list of aims, "
                           "m right of the pin")  # fmt: skip
        offsets_m = list(np.ravel(offsets_m)) if isinstance(offsets_m, np.ndarray) else offsets_m
        given = ",".join(str(o) for o in offsets_m)
        try:
            if any(isinstance(o, bool | np.bool_) for o in offsets_m):  # (True flew 1 m)
                raise AimError("")
            offsets_m = [_finite(o, "") for o in offsets_m]
        except AimError:
            raise AimError(
                f"{names['offsets_m']} {given}: every aim must be a finite number of metres "
                "right of the pin"
            ) from None
        if not offsets_m:
            raise AimError(f"{names['offsets_m']}: give at least one aim")
        if len(offsets_m) > MAX_AIMS:
            raise AimError(
                f"{names['offsets_m']}: {len(offsets_m):,} aims; at most {MAX_AIMS:,} per club"
            )
    elif not coarse_m / MAX_REFINEMENT <= resolution_m <= coarse_m:
        raise AimError(
            f"{names['resolution_m']} {resolution_m:g}: the finest spacing must be at most the "
            f"coarse step, {names['coarse_m']} {coarse_m:g}, and at least a "
            f"{MAX_REFINEMENT:,.0f}th of it"
        )
    else:
        coarse = coarse_count(half_width_m, coarse_m)
        if coarse > MAX_AIMS:
            raise AimError(
                f"{names['half_width_m']} {half_width_m:g} with {names['coarse_m']} "
                f"{coarse_m:g}: {coarse:,} aims per club; at most {MAX_AIMS:,} (the centre, a "
                "step apart to either side, and the region's edges): narrow the region or widen "
                "the step"
            )
    given = offsets_m if offsets_m is not None else [] if centre_m is None else [centre_m]
    x_lo, x_hi, y_lo, y_hi = scenario.hole.extent_m
    start = scenario.points[0].play.start_m
    points = [_aim_point(scenario.hole, start, o) for o in given]
    if given and all(not (x_lo <= x <= x_hi and y_lo <= y <= y_hi) for x, y in points):
        what = names["offsets_m"] if offsets_m is not None else names["centre_m"]
        where = _map_span(y_lo, y_hi, start)
        raise AimError(
            f"{what} {','.join(f'{o:g}' for o in given)}: every aim is off the hole's map, "
            f"{where}: aim where the map is"
        )
    clubs = len(scenario.points)
    aims = aims_per_club(half_width_m, coarse_m, resolution_m, offsets_m)
    size = memory_bytes(clubs, n, aims)
    memory = available_memory() if memory is None else memory
    if memory is not None and size >= memory:
        raise AimError(
            f"{names['n']} {n:,}: an aim search keeps every aim's score of every shot in "
            f"memory, about {plan.size_text(size)} for {clubs} club(s) x up to {aims:,} aims, "
            f"and {plan.size_text(memory)} is available: lower {names['n']}"
        )
    seconds = clubs * (aims + 1) * n / plan.SHOTS_PER_S
    return SearchPlan(
        n, centre_m, half_width_m, coarse_m, resolution_m, offsets_m, clubs, aims, seconds, size
    )


def _line_rad(hole, start_xy_m):
    """The bearing (rad, + right of +x) of the line from ``start_xy_m`` to the pin: from the
    tee, +x itself (the frame's axis is that line)."""
    if start_xy_m == (0.0, 0.0):
        return 0.0
    px, py = hole.pin_xy
    return math.atan2(py - start_xy_m[1], px - start_xy_m[0])


def _map_span(y_lo, y_hi, start_xy_m):
    """Where the hole's map lies, for a message about aims off it: its span across the line
    from the tee (the frame's y), or, from a start off the tee, about that start's line."""
    if start_xy_m == (0.0, 0.0):
        return f"which spans {y_lo:+.0f} to {y_hi:+.0f} m right of the line from the tee to the pin"
    return "about the line from the start to the pin"


def _aim_point(hole, start_xy_m, offset_m):
    """The aim point (x, y) m of the hole's frame ``offset_m`` right of the line from
    ``start_xy_m`` to the pin, at the pin's distance (where ``_bearing`` aims)."""
    line = _line_rad(hole, start_xy_m)
    px, py = hole.pin_xy
    return px - offset_m * math.sin(line), py + offset_m * math.cos(line)


def _bearing(offset_m, distance_m):
    """The bearing (rad, + right) of the aim point ``offset_m`` right of the line to the pin at
    ``distance_m`` from the tee."""
    return math.atan2(offset_m, distance_m)


def _scores(hole, terrain, strokes, job):
    """An aim (a task of the executor): per-shot expected strokes after the shots ``inputs``
    (sampled about ``play``'s aim) aimed on ``bearing``, and how many of them left the hole's
    map; ``job`` = (inputs, bearing, play)."""
    inputs, bearing, play = job
    inputs = inputs.copy(order="F")
    inputs[:, AZIMUTH] += bearing - play.aim_rad
    out = simulate_batch(inputs, terrain=terrain)
    scored = on_hole.scores(hole, out, strokes, start_xy_m=play.start_m)
    off_map = int((scored["outcome"] == "off_map").sum())
    return scored["expected_strokes_after"].to_numpy(), off_map


def _summary(values, reference):
    ok = np.isfinite(values) & np.isfinite(reference)
    n = int(ok.sum())
    if n < 2:
        return math.nan, math.nan, math.nan, math.nan
    v = values[ok]
    d = v - reference[ok]
    se = float(v.std(ddof=1) / math.sqrt(n))
    return float(v.mean()), se, float(d.mean()), float(d.std(ddof=1) / math.sqrt(n))


def search(
    scenario,
    n=10_000,
    half_width_m=DEFAULT_HALF_WIDTH_M,
    centre_m=None,
    coarse_m=DEFAULT_COARSE_M,
    resolution_m=DEFAULT_RESOLUTION_M,
    offsets_m=None,
    baseline=None,
    lie_of_zone=None,
    progress=None,
):
    """The aim search of a scenario on a hole (``AimSearch``), ``n`` shots per club.

    The aims lie ``centre_m`` +/- ``half_width_m`` (m right of the line to the pin, at its
    distance; default centre: the scenario's aim), coarse to fine; ``offsets_m``: fly exactly
    these aims instead (no refinement). ``baseline``, ``lie_of_zone``: as
    ``strokes.score_shots``. ``progress(text)``: called after each round. AimError (one line):
    arguments ``check`` refuses, before anything is flown; a search none of whose shots stayed
    on the hole's map, or none of whose shots could be scored, after.
    """
    checked = check(scenario, n, half_width_m, centre_m, coarse_m, resolution_m, offsets_m)
    n, centre_m, offsets_m = checked.n, checked.centre_m, checked.offsets_m
    half_width_m, coarse_m, resolution_m = (
        checked.half_width_m, checked.coarse_m, checked.resolution_m
    )  # fmt: skip
    hole = scenario.hole
    started = time.perf_counter()
    terrain = hole.terrain()
    start = scenario.points[0].play.start_m
    pin_x, pin_y = hole.pin_xy
    distance = math.hypot(pin_x - start[0], pin_y - start[1])
    line = _line_rad(hole, start)
    given_centre = centre_m
    strokes = {"baseline": baseline or tour_baseline(), "lie_of_zone": lie_of_zone,
               "putting": map_of_hole(hole)}  # fmt: skip
    executor = Executor()
    clubs = []
    flown = 0
    for point in scenario.points:
        inputs, _ = sampling.sample(scenario, point, 0, n)
        # Each club about its own aim (a club aimed 40 m left was searched about the first's).
        centre_m = (distance * math.tan(point.play.aim_rad - line) if given_centre is None
                    else given_centre)  # fmt: skip
        aims = ClubAims(point.label or point.group or "shot", reference_m=centre_m)

        def fly(offsets, aims=aims, inputs=inputs, play=point.play):
            """The aims of ``offsets`` not flown yet, each a task of the executor."""
            todo = [o for o in dict.fromkeys(round(o, 9) for o in offsets) if o not in aims.scores]
            jobs = [(inputs, line + _bearing(o, distance), play) for o in todo]
            for o, (scores, off_map) in zip(
                todo, executor.map(_scores, jobs, shared=(hole, terrain, strokes), name="aim"),
                strict=True,
            ):  # fmt: skip
                aims.scores[o], aims.off_map[o] = scores, off_map

        if offsets_m is not None:
            todo = [float(o) for o in offsets_m]
        else:
            todo = [centre_m + o for o in coarse_offsets(half_width_m, coarse_m)]
        fly([centre_m, *todo])
        reference = aims.scores[round(centre_m, 9)]
        step, walked = coarse_m, 0
        while True:
            fly(todo)
            if progress is not None:
                progress(f"{aims.club}: {len(aims.scores)} aims flown, {step:g} m apart")
            if offsets_m is not None:
                break
            best = min(aims.scores, key=lambda o: np.nanmean(aims.scores[o]))
            # The best at an edge of the aims flown: the search goes on that way at this step
            # (refined there, it stopped at the edge of the region, still falling: a "best"
            # worse than an aim it had not flown).
            edge = not (min(aims.scores) < best < max(aims.scores))
            if not edge:
                if step <= resolution_m + 1e-9:
                    break
                step = max(step / 3.0, resolution_m)
            elif walked == WALK_ROUNDS:
                aims.at_edge = True  # (said, where the search ends: a wider region tells more)
                break
            else:
                walked += 1
            todo = [best + k * step for k in range(-3, 4)]
            if all(round(o, 9) in aims.scores for o in todo):
                aims.at_edge = edge
                break  # (nothing left to fly there)
        for offset in sorted(aims.scores):
            mean, se, diff, diff_se = _summary(aims.scores[offset], reference)
            aims.offsets_m.append(offset)
            aims.expected.append(mean)
            aims.expected_se.append(se)
            aims.difference.append(diff)
            aims.difference_se.append(diff_se)
        flown += n * len(aims.scores)
        clubs.append(aims)
    aimed = [o for c in clubs for o in c.scores]
    if all(c.off_map[o] == n for c in clubs for o in c.scores):
        t = terrain
        reach = (t.y0_m, t.y0_m + (t.height_m.shape[0] - 1) * t.cell_m)
        where = _map_span(*reach, start)
        raise AimError(
            f"every shot of every aim ({min(aimed):+.1f} to {max(aimed):+.1f} m right of the pin) "
            f"left the hole's map, {where}: aim where the map is"
        )
    for c in clubs:
        if not np.isfinite(c.expected).any():
            raise AimError(
                f"{c.club}: no shot of any aim ({min(aimed):+.1f} to {max(aimed):+.1f} m right of "
                "the pin) could be scored (every shot failed): check the scenario's launch"
            )
    lie, start_m = start_of(hole, start)
    expected_start = float(strokes["baseline"].expected(lie, start_m))
    return AimSearch(
        scenario, clubs, n, distance, expected_start, time.perf_counter() - started, flown, start
    )


def table(result):
    """Every aim flown, one row per club and aim: a dict of columns (units in the names)."""
    names = ("club", "aim_offset_m", "aim_bearing_deg", "expected_strokes_after",
             "expected_strokes_after_se", "difference_strokes", "difference_se",
             "strokes_gained")  # fmt: skip
    rows = {name: [] for name in names}
    for club in result.clubs:
        for k, offset in enumerate(club.offsets_m):
            rows["club"].append(club.club)
            rows["aim_offset_m"].append(offset)
            rows["aim_bearing_deg"].append(math.degrees(result.bearing_rad(offset)))
            rows["expected_strokes_after"].append(club.expected[k])
            rows["expected_strokes_after_se"].append(club.expected_se[k])
            rows["difference_strokes"].append(club.difference[k])
            rows["difference_se"].append(club.difference_se[k])
            rows["strokes_gained"].append(result.expected_start - 1.0 - club.expected[k])
    return rows


def write_table(result, path, baseline=None, force=False):
    """Write ``table(result)`` to ``path`` (Parquet) atomically, with the provenance of a run of
    its scenario (``plan.provenance``, its geometry and its hole's map included: the file
    describes itself) and ``baseline``, the name of the table the shots were scored by
    (default the Tour's); return the path."""
    the_plan = plan.plan(result.scenario, n=result.n)
    provenance = plan.provenance(
        the_plan,
        "local",
        output.versions(),
        numba.get_num_threads(),
        baseline=TOUR_BASELINE if baseline is None else str(baseline),
        seconds=round(result.seconds, 3),
        shots_flown=result.shots_flown,
    )
    with output.AtomicFile(path, force=force) as target:
        output.write_table(
            target.tmp, pd.DataFrame(table(result)), plan.file_metadata(provenance, "aim")
        )
        target.commit()
    return Path(path)


def patterns(result):
    """The finishes (x, y) of the best club's shots (``AimSearch.best``) at its best aim and at
    the reference aim, as the search flew them: {"best": (x, y), "reference": (x, y)}."""
    club, k = result.best()
    c = result.clubs.index(club)
    return {
        "best": finishes(result, c, club.offsets_m[k]),
        "reference": finishes(result, c, club.reference_m),
    }


def finishes(result, club, offset_m):
    """(x, y) finish positions (hole frame, m) of the shots of ``club`` (an index of
    ``result.clubs``) aimed ``offset_m`` right of the pin: its shots flown again, as the
    search flew them."""
    scenario = result.scenario
    point = scenario.points[club]
    inputs, _ = sampling.sample(scenario, point, 0, result.n)
    inputs[:, AZIMUTH] += result.bearing_rad(offset_m) - point.play.aim_rad
    out = simulate_batch(inputs, terrain=scenario.hole.terrain())
    return out[:, FINAL_X], out[:, FINAL_Y]
