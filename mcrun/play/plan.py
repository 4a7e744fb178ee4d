"""A solve before it runs: ``plan_play`` checks a player and a hole for ``play_hole`` and says
what the solve will do (``PlayPlan``: its states, actions and rows, shots, time and memory),
or refuses in one line (``PlayerError``) what it cannot do, before a shot is flown on the hole:

- an argument that is not one (``n`` under 2, ``plays`` under 1, a spacing that is not a
  positive number of metres), named as the caller names it (``names``: ``mcrun play``'s
  options);
- a hole whose pin is not on a green (a hole is played to a pin on its green);
- a bag that cannot play the hole: no club that flies (every club's mean carry on the level
  under ``MIN_CARRY_M``: putters), or whose shots cannot reach the green from the tee in
  ``MAX_STROKES`` strokes (the most a play of the policy counts): ``MAX_STROKES`` times
  ``REACH_MARGIN`` times the longest shot of the bag on the level (of the first
  ``PROBE_SHOTS`` shots of each club at full power, on the plane's ground with the club's own
  turf and weather) is short of the green's nearest point from the tee. The margin (an
  ESTIMATE) stands for what the hole's ground can add to a shot (a downhill lie, firmer turf),
  so that the criterion refuses only a bag that needs half as many strokes again as a play can
  count; a bag it lets through that still cannot hole out from somewhere is refused after the
  solve, whose values then do not settle;
- a solve that would not fit in the memory there is (``memory_bytes``, against
  ``mcrun.run.aim.available_memory``): first on the rows the ``PROBE_SHOTS`` shots of each
  option give (before n shots of each are sampled: ``-n 1e9``), then on the exact rows.

The plan holds what it computed (the lattice, each club's n shots and what they do on the
level, the actions and their jobs): ``mcrun.play.solve_planned`` flies and solves them, bit for
bit what ``play_hole`` gives.
"""

import math
import time
from dataclasses import dataclass, replace

import numba
import numpy as np

from mcrun.engine.schema import N_INPUT, N_OUTCOME
from mcrun.hole.zones import ZONE_KINDS, contains
from mcrun.play.episodes import MAX_STROKES
from mcrun.play.lattice import DEFAULT_COARSE_M, DEFAULT_FINE_M, DEFAULT_FINE_WITHIN_M, lattice
from mcrun.play.player import PlayerError, on_hole
from mcrun.play.transitions import options_of, plan_actions
from mcrun.putting.on_hole import check_putting
from mcrun.run import plan as run_plan
from mcrun.run.distributed import WORKER_BYTES
from mcrun.strokes.baseline import tour_baseline
from mcrun.units import float_or_nan, is_number, shown

__all__ = [
    "ARGUMENT_NAMES",
    "MIN_CARRY_M",
    "REACH_MARGIN",
    "PlayPlan",
    "memory_bytes",
    "plan_play",
]

# The names of ``plan_play``'s arguments in its messages (``mcrun play`` gives its options').
ARGUMENT_NAMES = {
    "n": "n",
    "plays": "plays",
    "coarse_m": "coarse_m",
    "fine_m": "fine_m",
    "fine_within_m": "fine_within_m",
    "seed": "seed",
}
# A club that flies: its mean carry on the level (full power) at least this. A putt skids and
# rolls from the face (a 4 m/s putt carries about 0.1 m); a pitch carries tens of metres.
MIN_CARRY_M = 1.0
# What the hole's ground may add to the longest shot of the bag on the level (an ESTIMATE: a
# downhill lie, firmer turf than the club's own).
REACH_MARGIN = 1.5
# Memory (bytes), by what a solve holds (``memory_bytes``), from the arrays it makes:
# - per shot kept: its kind and lie (int8), where it rests and its putts (3 float64) = 26 B,
#   each put in its place as its job finishes, and a margin (the order of the rows, the
#   solve's arrays);
SHOT_BYTES = 72
# - per shot of a job being flown (``chunk_rows`` states x n shots, one a thread or one on each
#   Dask worker): the kernel's inputs and outcomes (float64) and the classification's arrays
#   (about a dozen more a shot);
BATCH_SHOT_BYTES = 8 * (N_INPUT + N_OUTCOME) + 112
# - per row (a state and an action): its indices, Q and its standard error for the best and the
#   fairway's policy, and the row of -o's table (a dozen columns, strings among them);
ROW_BYTES = 512
# - per play of the policy: its state, strokes and the arrays of a stroke (a dozen);
PLAY_BYTES = 128
# - per shot of an option (a club at a power): its inputs, kept for every option; and the
#   copies made while one option is sampled and flown on the level;
OPTION_SHOT_BYTES = 8 * N_INPUT
SAMPLING_SHOT_BYTES = 8 * (3 * N_INPUT + N_OUTCOME)
# - per local Dask worker: a process (``distributed.WORKER_BYTES``), and per task the shots'
#   inputs it carries (the client's and the worker's copies).
CHUNK_ROWS = 256
# The plays of the policy a second (measured: 10^8 plays of a par 3 in about 200 s on 2 cores;
# the shots go at ``mcrun.run.plan.SHOTS_PER_S``).
PLAYS_PER_S = 5e5
# The shots of each option flown on the level before the n are sampled: the bag's reach, and
# the rows to expect (the mean totals of 64 shots decide which clubs fit a state as the n's do
# but within a few metres).
PROBE_SHOTS = 64


def memory_bytes(n_options, n, rows, plays, workers=0, chunk_rows=CHUNK_ROWS, threads=None):
    """The memory (bytes) a solve of ``n_options`` options (clubs and powers) of ``n`` shots
    each over ``rows`` rows (states x the actions that fit them) holds at most, its policy
    played ``plays`` times, its jobs flown on ``threads`` threads of this process (default
    ``numba.get_num_threads()``) or on ``workers`` local Dask workers (0: threads, or a cluster
    elsewhere). Checked once: Riverside 2 at -n 5000
    --coarse 20m --fine 10m --plays 1e8 (30 million shots), estimated 16 GB, peaked at 12.6 GB
    resident."""
    sampling = n * (n_options * OPTION_SHOT_BYTES + SAMPLING_SHOT_BYTES)
    batch = min(chunk_rows, max(rows, 1)) * n * BATCH_SHOT_BYTES
    dask = 0
    if workers:
        tasks = math.ceil(rows / chunk_rows)
        dask = workers * (WORKER_BYTES + batch) + tasks * n * 2 * OPTION_SHOT_BYTES
    threads = numba.get_num_threads() if threads is None else int(threads)
    return int(sampling + (0 if workers else threads * batch) + dask + rows * n * SHOT_BYTES
               + rows * ROW_BYTES + plays * PLAY_BYTES)  # fmt: skip


@dataclass
class PlayPlan:
    """A solve planned by ``plan_play``: what it will fly (``states``, ``rows``, ``shots``) and
    its estimated ``seconds`` and ``bytes``; ``mcrun.play.solve_planned`` runs it."""

    player: object
    hole: object
    scenario: object  # the player's on the hole, with the seed
    n: int
    plays: int
    lattice: object
    baseline: object
    options: list
    actions: list
    jobs: list
    workers: int
    seconds: float  # estimated: the shots on the hole and the plays
    bytes: int  # estimated, at most
    planned_s: float  # what planning took

    @property
    def states(self):
        return self.lattice.size

    @property
    def rows(self):
        return sum(len(job[0]) for job in self.jobs)

    @property
    def shots(self):
        return self.rows * self.n

    def line(self):
        """One line for the terminal, as ``mcrun aim``'s and a run's plan lines."""
        return (
            f"mcrun: {self.player.name}: {self.states:,} states x {len(self.actions)} actions "
            f"({self.rows:,} that fit) x {self.n:,} shots = {self.shots:,} shots; "
            f"{'under' if self.seconds < 0.05 else 'about'} "
            f"{run_plan.duration_text(self.seconds)} of simulation and plays, up to about "
            f"{run_plan.size_text(self.bytes)} of memory"
        )


def _names(names):
    return {**ARGUMENT_NAMES, **(names or {})}


def _spacing(value, name):
    """A spacing of the lattice: a finite number of metres, at least 1 m (``mcrun play``'s
    range: finer would hold millions of states)."""
    number = float_or_nan(value)  # (text is not a number: "20" was read as 20 m)
    if not (math.isfinite(number) and number >= 1.0):
        raise PlayerError(f"{name} {value!r}: allowed: a number of metres, at least 1")
    return number


def _count(value, name, least):
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < least:
        raise PlayerError(f"{name} {value!r}: allowed: a whole number of at least {least}")
    return int(value)


def _edge_distance_m(polygon, x, y):
    """The distance (m) from (x, y) to the nearest edge of ``polygon`` (a list of rings)."""
    best = math.inf
    for ring in polygon:
        a = np.asarray(ring, dtype=float)
        d = np.roll(a, -1, axis=0) - a
        length2 = np.maximum((d * d).sum(axis=1), 1e-12)
        t = np.clip(((x - a[:, 0]) * d[:, 0] + (y - a[:, 1]) * d[:, 1]) / length2, 0.0, 1.0)
        best = min(
            best, float(np.hypot(a[:, 0] + t * d[:, 0] - x, a[:, 1] + t * d[:, 1] - y).min())
        )
    return best


def green_distance_m(hole):
    """The distance (m) from the tee to the pin's green: the green that holds the pin (else the
    nearest green to it); 0 where the tee is on it; the distance to the pin without a green."""
    px, py = hole.pin_xy
    greens = [polygon for kind, polygon in hole.zones if kind == "green"]
    if not greens:
        return math.hypot(px, py)

    def off_pin(polygon):
        return 0.0 if contains(polygon, px, py) else _edge_distance_m(polygon, px, py)

    green = min(greens, key=off_pin)
    return 0.0 if contains(green, 0.0, 0.0) else _edge_distance_m(green, 0.0, 0.0)


def check_pin(hole):
    """PlayerError when the hole's pin is not on a green."""
    px, py = hole.pin_xy
    code = int(hole.zone_at(np.array([px]), np.array([py]))[0])
    if code != ZONE_KINDS.index("green"):
        where = "off the hole's map" if code < 0 else f"on {ZONE_KINDS[code]}"
        raise PlayerError(
            f"{hole.source}: the pin ({px:.1f}, {py:.1f}) m is {where}, not on a green: a hole "
            "is played to a pin on its green; allowed is a hole of a map with its greens"
        )


def check_reach(player, hole, options):
    """PlayerError when the bag has no club that flies, or cannot reach the green from the tee
    in ``MAX_STROKES`` strokes (see the module's notes)."""
    full = [o for o in options if o.power == 1.0]
    carry = max((o.carry_m for o in full if math.isfinite(o.carry_m)), default=0.0)
    if carry < MIN_CARRY_M:
        raise PlayerError(
            f"{player.source}: no club of {player.name} flies: every club's mean carry on the "
            f"level is under {MIN_CARRY_M:g} m (the longest: {carry:.2f} m), as a putt's: "
            "mcrun play needs clubs that carry the ball (a green is putted as the hole's "
            "putting says; mcrun putt putts alone)"
        )
    longest = max((o.longest_m for o in full if math.isfinite(o.longest_m)), default=0.0)
    reach = MAX_STROKES * REACH_MARGIN * longest
    distance = green_distance_m(hole)
    if reach < distance:
        club = max(full, key=lambda o: o.longest_m if math.isfinite(o.longest_m) else -1.0)
        raise PlayerError(
            f"{player.source}: {player.name} cannot reach the green of {hole.source}: it is "
            f"{distance:.0f} m from the tee, and the bag's longest shot on the level "
            f"({player.clubs[club.club]}) goes {longest:.1f} m: {MAX_STROKES} strokes (the "
            f"most a play counts) of {REACH_MARGIN:g} times that reach {reach:.0f} m; allowed "
            "is a bag whose longest shot goes at least "
            f"{distance / (MAX_STROKES * REACH_MARGIN):.1f} m on the level"
        )


def _too_big(size, memory, n, plays, rows, options, workers, names, exact):
    """The PlayerError of a solve of ``size`` bytes where ``memory`` is available: it names
    the argument to lower and the most it may be here."""
    have = run_plan.size_text(memory)
    about = "about" if exact else "an estimated"
    rows_are = f"{rows:,}" if exact else f"about {rows:,}"
    play_part = plays * PLAY_BYTES
    if play_part >= memory / 2:
        most = max(int(memory / 2 / PLAY_BYTES), 0)
        return PlayerError(
            f"{names['plays']} {plays:,}: the plays of the policy take about "
            f"{run_plan.size_text(play_part)} of memory, and {have} is available: allowed "
            f"here: {names['plays']} up to about {most:,}"
        )
    fixed = memory_bytes(options, 0, rows, plays, workers)
    per_shot = memory_bytes(options, 1, rows, plays, workers) - fixed
    most = int((memory - fixed) / per_shot) if per_shot > 0 else 0
    if most >= 2:
        allowed = f"allowed here: {names['n']} up to about {most:,}"
    else:
        allowed = (f"allowed here: fewer states, a wider {names['coarse_m']} and "
                   f"{names['fine_m']}")  # fmt: skip
    return PlayerError(
        f"{names['n']} {n:,}: a solve keeps every shot of every action from every state in "
        f"memory, {about} {run_plan.size_text(size)} for {rows_are} rows (states x "
        f"actions) x {n:,} shots, and {have} is available: {allowed}"
    )


def plan_play(player, hole, n=100, seed=None, coarse_m=DEFAULT_COARSE_M, fine_m=DEFAULT_FINE_M,
              fine_within_m=DEFAULT_FINE_WITHIN_M, plays=4000, workers=0, memory=None,
              names=None, chunk_rows=CHUNK_ROWS):  # fmt: skip
    """The ``PlayPlan`` of ``play_hole``'s arguments (``workers``: the local Dask workers that
    will fly it, 0 for threads or a cluster elsewhere), or PlayerError (one line naming the
    argument, ``names``: {argument: name}, default ``ARGUMENT_NAMES``) for what it cannot do
    (the module's notes); ``memory``: bytes available (default ``available_memory()``)."""
    from mcrun.run.aim import available_memory

    started = time.perf_counter()
    names = _names(names)
    n = _count(n, names["n"], 2)
    plays = _count(plays, names["plays"], 1)
    coarse_m = _spacing(coarse_m, names["coarse_m"])
    fine_m = _spacing(fine_m, names["fine_m"])
    fine_within_m = _spacing(fine_within_m, names["fine_within_m"])
    if fine_m > coarse_m:  # ("near the pin" coarser than elsewhere, without a word)
        raise PlayerError(f"{names['fine_m']} {fine_m:g} m: allowed: at most {names['coarse_m']} "
                          f"({coarse_m:g} m), the lattice's spacing away from the pin")  # fmt: skip
    workers = _count(workers, "workers", 0)
    if seed is not None:  # (1.7 was 1, True 1, 2**70 solved; a text a ValueError)
        seed = run_plan.positive_int(seed, names["seed"], minimum=0)
    check_pin(hole)
    check_putting(hole, green=True, putter=player.putter)  # its green, where a map values it
    if memory is not None and not (is_number(memory) and memory > 0):  # (True was 1 byte)
        raise PlayerError(f"memory {shown(memory)}: allowed: the bytes available, > 0")
    memory = available_memory() if memory is None else memory
    base = tour_baseline()
    lat = lattice(hole, base, coarse_m, fine_m, fine_within_m)
    scenario = on_hole(player, hole)
    if seed is not None:
        scenario = replace(scenario, seed=seed)
    # The first PROBE_SHOTS shots of each option first: what the bag reaches, and the rows
    # (states x the actions that fit them; exact when n is no more), before n are sampled.
    flown = options_of(scenario, min(n, PROBE_SHOTS), player)
    check_reach(player, hole, flown)
    options = len(flown)
    exact = n <= PROBE_SHOTS
    for _ in range(2):
        actions, jobs = plan_actions(hole, lat, flown, chunk_rows)
        rows = sum(len(job[0]) for job in jobs)
        size = memory_bytes(options, n, rows, plays, workers, chunk_rows)
        if memory is not None and size >= memory:
            raise _too_big(size, memory, n, plays, rows, options, workers, names, exact)
        if exact:
            break
        flown = options_of(scenario, n, player)
        exact = True
    seconds = rows * n / run_plan.SHOTS_PER_S + plays / PLAYS_PER_S
    return PlayPlan(player, hole, scenario, n, plays, lat, base, flown, actions, jobs, workers,
                    seconds, size, time.perf_counter() - started)  # fmt: skip
