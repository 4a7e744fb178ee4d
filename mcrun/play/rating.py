"""A course rated by simulating the handicap system's model players: each hole solved for the
scratch and the bogey player (``mcrun.play``), and their Course Rating, Bogey Rating and Slope
Rating by the system's definitions (the course-rating reference):

- Course Rating (CR) and Bogey Rating (BR): the model player's score on the course, to one
  decimal, in two readings: the **expected** score (the sum of the holes' expected strokes from
  the tee; the WHS text's "expected score of a scratch player") and the **better half**, the
  mean of the better half of the player's 18-hole scores (what the rating measures in practice:
  a handicap takes the best 8 of 20 differentials). The rounds are drawn from each hole's plays
  of its policy (``PlayResult.scores``), each hole's by a seed of its own, and joined by the
  player's form on the day (``DAY_FORM``, below).
- Slope Rating: 5.381 x (BR - CR) for men, 4.24 x (BR - CR) for women, of the ratings at one
  decimal, rounded to a whole number and held within 55-155 (113: a course of standard relative
  difficulty).
- The plays-as yardage: the length whose length rating (``LENGTH_RATING``: for a scratch man
  length / 220 + 40.9 over 18 holes) is the player's rating, the course's effective playing
  length as the simulated player finds it.

The model players (``MODEL_PLAYERS``): men's scratch and bogey, women's scratch-woman and
bogey-woman (the presets of ``mcrun.play.player.PLAYERS``).

What a hole's obstacles cost a player (``rate(..., obstacles=True)``): its expected strokes
less those of the same hole without them (``without_obstacles``: its bunkers and penalty areas
taken off the map, the ground under them what surrounds them, and no out of bounds).

The day's form: a player's holes within a round are not independent of one another (a good day
is good on most holes), and a better half depends on how far rounds spread. A player's average
runs about 3 strokes above his handicap [Knuth, the amateurs reference]; read as the distance
from his average to his better half (the reading of a rating used here), that is 0.80 of the
rounds' standard deviation for rounds spread about normally: 3.75 strokes. Independent holes
spread the model players' rounds less (their better half 1.8-2.7 strokes below their average
on the open courses of ``benchmarks.rating``). So each round draws a form, and each hole's
score is its plays' quantile at a latent normal sqrt(rho) form + sqrt(1 - rho) noise, rho =
``DAY_FORM[player]``: the holes' latents correlated rho with one another (a Gaussian copula,
by ranks: each hole's drawn plays are dealt to the rounds in the order of their latents, so
that a hole's scores are the same draws as without it). ``DAY_FORM`` is fitted
(``fit_day_form``) so that, over those open courses, the model player's better half lies 3.0
strokes below his average: an ESTIMATE from one figure, the same for every model player (the
reference gives no spread by handicap). Were Knuth's handicap the best 8 of 20 (0.97 of the
spread below the average), the spread would be 3.1 strokes and the better half about 0.5
higher. The expected score does not depend on it; the better half does.

A hole's par, where its map does not give one, is taken from its length (``par_by_length``:
the USGA's guide for men, an ESTIMATE where its ranges overlap); a rating does not use it.
"""

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from mcrun.strokes.baseline import YARD_M
from mcrun.units import shown

__all__ = [
    "BETTER_HALF",
    "DAY_FORM",
    "EXPECTED",
    "LENGTH_RATING",
    "MODEL_PLAYERS",
    "SLOPE_FACTOR",
    "SLOPE_RANGE",
    "CourseRating",
    "HoleScore",
    "better_half_gap",
    "course_rounds",
    "fit_day_form",
    "length_rating",
    "par_by_length",
    "plan_rating",
    "plays_as_yd",
    "rate",
    "rate_planned",
    "slope_rating",
    "without_obstacles",
]

SLOPE_FACTOR = {"men": 5.381, "women": 4.24}
MODEL_PLAYERS = {"men": ("scratch", "bogey"), "women": ("scratch-woman", "bogey-woman")}
# A model player's length rating of an 18-hole course: length / YD + STROKES (yd per stroke,
# strokes): the manual's for the scratch man; for the others third-party implementations' (not
# confirmed from the manual's own text: the course-rating reference).
LENGTH_RATING = {"scratch": (220.0, 40.9), "bogey": (160.0, 50.7),
                 "scratch-woman": (180.0, 40.1), "bogey-woman": (120.0, 51.3)}  # fmt: skip
SLOPE_RANGE = (55, 155)
EXPECTED, BETTER_HALF = "expected", "better half"
ROUNDS = 10_000  # 18-hole rounds drawn from the holes' plays
# The fewest plays of a hole's policy a rating takes: its better half is dealt from each hole's
# plays, so a few of them make rounds of a few scores repeated (one play: every round the same,
# its better half its average, without a word).
MIN_PLAYS = 100
# The day's form: the correlation of a model player's holes' latents within a round (module
# docstring), fitted by ``fit_day_form`` to a better half 3.0 strokes below the average [Knuth]
# over the open courses of ``benchmarks.rating`` (which prints the fit beside these): an
# ESTIMATE. A player not named here plays independent holes.
DAY_FORM = {"scratch": 0.161, "bogey": 0.019, "scratch-woman": 0.165, "bogey-woman": 0.047}
KNUTH_GAP = 3.0  # strokes between a player's average and his handicap [Knuth]
# Par by length (yd): a hole up to the first is a par 3, up to the second a par 4 (the USGA's
# guide: for men par 3 up to 260 yd, par 4 240-490, par 5 450-710; for women par 3 up to 220,
# par 4 200-420, par 5 370-600; the overlaps split).
PAR_YD = {"men": (250.0, 470.0), "women": (210.0, 395.0)}
OBSTACLES = ("bunker", "water", "water_yellow")  # zone kinds taken off (and out of bounds)


@dataclass(frozen=True)
class HoleScore:
    """What a hole's solve for one player leaves (the solve itself is let go: it holds every
    shot): the expected strokes from the tee and their standard error, the best tee shot, the
    plays' strokes and the solve's size and time."""

    hole: int  # position in the course, from 1
    player: str
    expected_strokes: float
    expected_strokes_se: float
    best: str
    scores: np.ndarray
    shots: int
    seconds: float
    obstacles_strokes: float = math.nan  # less the hole without its obstacles (NaN: not asked)

    @classmethod
    def of(cls, hole, result):
        """The HoleScore of hole number ``hole``'s ``PlayResult``."""
        tr = result.transitions
        return cls(hole, result.player.name, result.tee_value, result.tee_se,
                   result.tee_rows()[0][1], np.asarray(result.scores), int(tr.shots_flown),
                   float(result.seconds))  # fmt: skip


@dataclass
class CourseRating:
    """The holes (``mcrun.hole.Hole``s, in the course's order) and each player's
    ``HoleScore``s; ``rounds``: the 18-hole (or however many holes) totals drawn from them,
    with each player's ``day_form`` (``DAY_FORM``; 0 for a player not named there)."""

    holes: list
    players: tuple
    scores: dict  # player -> [HoleScore, one per hole]
    seed: int
    women: bool = False
    rounds: dict = field(default_factory=dict)  # player -> totals
    day_form: dict = field(default_factory=dict)  # player -> the day form of his rounds

    def __post_init__(self):
        for player in self.players:
            self.day_form[player] = DAY_FORM.get(player, 0.0)
            self.rounds[player] = course_rounds(self.scores[player], ROUNDS, self.seed,
                                                self.day_form[player])  # fmt: skip

    @property
    def length_yd(self):
        return sum(h.length_m for h in self.holes) / YARD_M

    def rating(self, player, reading=EXPECTED):
        """The player's rating, unrounded: the expected score or the better half's mean."""
        if reading == EXPECTED:
            return float(sum(s.expected_strokes for s in self.scores[player]))
        totals = np.sort(self.rounds[player])
        return float(totals[: len(totals) // 2].mean())

    def plays_as_yd(self, player, reading=EXPECTED):
        """The course's plays-as yardage for ``player`` (a model player: ``LENGTH_RATING``):
        the length whose length rating is the player's rating (``plays_as_yd``)."""
        return plays_as_yd(player, self.rating(player, reading), len(self.holes))

    def rating_se(self, player):
        """The standard error of the expected score (the holes' added as independent)."""
        return math.sqrt(sum(s.expected_strokes_se**2 for s in self.scores[player]))

    def slope(self, reading=EXPECTED):
        """The Slope Rating of the first two players' ratings (scratch, bogey) in ``reading``."""
        scratch, bogey = self.players[:2]
        return slope_rating(round(self.rating(scratch, reading), 1),
                            round(self.rating(bogey, reading), 1), self.women)  # fmt: skip

    def frame(self):
        """One row per hole and player: hole, par, length_m, player, expected_strokes and its
        _se, best, the plays' mean and their share of each stroke count (``strokes_K``)."""
        import pandas as pd

        rows = []
        top = max(int(s.scores.max()) for p in self.players for s in self.scores[p])
        for player in self.players:
            for s, hole in zip(self.scores[player], self.holes, strict=True):
                counts = np.bincount(s.scores.astype(np.int64), minlength=top + 1)
                row = {"hole": s.hole, "par": hole.par, "length_m": hole.length_m,
                       "player": player, "expected_strokes": s.expected_strokes,
                       "expected_strokes_se": s.expected_strokes_se, "best": s.best,
                       "plays_mean_strokes": float(s.scores.mean()),
                       "obstacles_strokes": s.obstacles_strokes, "shots": s.shots,
                       "seconds": s.seconds}  # fmt: skip
                for k in range(1, top + 1):
                    row[f"strokes_{k}"] = counts[k] / len(s.scores)
                rows.append(row)
        return pd.DataFrame(rows)


def course_rounds(scores, rounds, seed, day_form=0.0):
    """``rounds`` totals over the holes of ``scores`` (HoleScores): each hole's plays drawn
    ``rounds`` times (seeded by ``seed`` and the hole's number) and dealt to the rounds in the
    order of a latent normal, sqrt(day_form) times the round's form plus sqrt(1 - day_form)
    times the hole's own noise, so that the holes' latents are correlated ``day_form`` with one
    another (a Gaussian copula by ranks; 0: in the order drawn, the holes independent)."""
    if not 0.0 <= day_form < 1.0:
        raise ValueError(f"day_form {day_form}: must be in [0, 1)")
    if day_form > 0.0:
        form = np.random.default_rng([seed, 0]).standard_normal(rounds)  # holes count from 1
    total = np.zeros(rounds)
    for s in scores:
        rng = np.random.default_rng([seed, s.hole])
        drawn = rng.choice(s.scores, size=rounds, replace=True)
        if day_form > 0.0:
            noise = rng.standard_normal(rounds)
            latent = math.sqrt(day_form) * form + math.sqrt(1.0 - day_form) * noise
            dealt = np.empty(rounds)
            dealt[np.argsort(latent, kind="stable")] = np.sort(drawn, kind="stable")
            drawn = dealt
        total += drawn
    return total


def better_half_gap(scores, seed, day_form=0.0, rounds=ROUNDS):
    """The mean of the rounds (``course_rounds``) of ``scores`` less the mean of their better
    half: how far a player's better half lies below his average."""
    totals = np.sort(course_rounds(scores, rounds, seed, day_form))
    return float(totals.mean() - totals[: rounds // 2].mean())


def fit_day_form(courses, seed, gap=KNUTH_GAP, steps=20):
    """The day form (``course_rounds``) whose better half lies ``gap`` strokes below the
    average, on the mean over ``courses`` (each a list of one player's HoleScores), by
    bisection in [0, 0.9]; 0 where the holes alone already spread the rounds that far;
    ValueError where even 0.9 does not."""

    def mean_gap(rho):
        return float(np.mean([better_half_gap(c, seed, rho) for c in courses]))

    lo, hi = 0.0, 0.9
    if mean_gap(lo) >= gap:
        return 0.0
    if mean_gap(hi) < gap:
        raise ValueError(f"no day form up to {hi} puts the better half {gap} strokes below")
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if mean_gap(mid) < gap else (lo, mid)
    return 0.5 * (lo + hi)


def slope_rating(course_rating, bogey_rating, women=False):
    """The Slope Rating of a Course and a Bogey Rating: 5.381 (men) or 4.24 (women) times
    their difference, rounded, within ``SLOPE_RANGE``."""
    value = round(SLOPE_FACTOR["women" if women else "men"] * (bogey_rating - course_rating))
    return int(min(max(value, SLOPE_RANGE[0]), SLOPE_RANGE[1]))


def length_rating(player, length_yd, holes=18):
    """The system's length rating of model ``player`` (``LENGTH_RATING``) for a course of
    ``holes`` holes and ``length_yd``: length / YD + STROKES x holes / 18."""
    yd, strokes = LENGTH_RATING[player]
    return length_yd / yd + strokes * holes / 18.0


def plays_as_yd(player, rating, holes=18):
    """The length (yd) of ``holes`` holes whose length rating for model ``player`` is
    ``rating``: ``length_rating`` turned round."""
    yd, strokes = LENGTH_RATING[player]
    return (rating - strokes * holes / 18.0) * yd


def without_obstacles(hole):
    """``hole`` without its bunkers and penalty areas (``OBSTACLES``: their polygons taken off
    the map, so that the ground under them is what surrounds them) and its out of bounds."""
    zones = [(kind, polygon) for kind, polygon in hole.zones if kind not in OBSTACLES]
    return dataclasses.replace(hole, zones=zones, boundary=[], _terrain=None)


def par_by_length(length_m, women=False):
    """A man's (a woman's) par of a hole ``length_m`` long (``PAR_YD``)."""
    yd = length_m / YARD_M
    three, four = PAR_YD["women" if women else "men"]
    return 3 if yd <= three else 4 if yd <= four else 5


def plan_rating(holes, players=MODEL_PLAYERS["men"], n=100, seed=None, coarse_m=None,
                fine_m=None, plays=4000, numbers=None, obstacles=False, workers=0,
                names=None):  # fmt: skip
    """The plans of ``rate``'s solves, every one checked (``play.plan_play``: PlayerError, one
    line, for one that cannot be; ``names`` as it takes them) before any is flown: {(player
    name, hole number): [the hole's PlayPlan, and the hole's without its obstacles' with
    ``obstacles``]}, in the order they are solved. ``workers``: the local Dask workers that
    will solve them, each a whole solve at once (each solve then fits in their share of the
    memory)."""
    from mcrun.play import DEFAULT_N, PlayerError, load_player, plan_play
    from mcrun.play.lattice import DEFAULT_COARSE_M, DEFAULT_FINE_M
    from mcrun.run.aim import available_memory

    label = (names or {}).get("plays", "plays")
    if isinstance(plays, bool) or not isinstance(plays, int | np.integer) or plays < MIN_PLAYS:
        raise PlayerError(
            f"{label} {plays!r}: allowed: a whole number of at least {MIN_PLAYS} for a rating "
            "(its better half is dealt from each hole's plays)"
        )
    if not isinstance(holes, list | tuple) or not holes:  # (a Hole alone, or none: TypeError)
        raise PlayerError(f"holes {shown(holes, 60)}: allowed: a list of the course's holes")
    loaded = [load_player(p) if isinstance(p, str) else p for p in players]
    numbers = list(range(1, len(holes) + 1) if numbers is None else numbers)
    # Keyed by player and number: one given twice was solved once, the other dropped.
    if not (len(numbers) == len(holes) and len(set(numbers)) == len(numbers)
            and all(isinstance(k, int | np.integer) and not isinstance(k, bool)
                    for k in numbers)):  # fmt: skip
        raise PlayerError(f"numbers {shown(numbers, 60)}: allowed: one whole number a hole "
                          f"({len(holes)}), each once")  # fmt: skip
    names_of = [p.name for p in loaded]
    if not names_of or len(set(names_of)) != len(names_of):
        raise PlayerError(f"players {shown(names_of, 60)}: allowed: one or more players, each "
                          "once")  # fmt: skip
    memory = available_memory()
    if workers and memory is not None:
        memory /= int(workers)
    # (None: the default; 0 was read as the default too, where plan_play refuses it)
    settings = dict(n=DEFAULT_N if n is None else n, seed=seed,
                    coarse_m=DEFAULT_COARSE_M if coarse_m is None else coarse_m,
                    fine_m=DEFAULT_FINE_M if fine_m is None else fine_m, plays=plays,
                    memory=memory, names=names)  # fmt: skip
    return {(player.name, number): [plan_play(player, h, **settings)
                                    for h in ((hole, without_obstacles(hole)) if obstacles
                                              else (hole,))]
            for player in loaded
            for number, hole in zip(numbers, holes, strict=True)}  # fmt: skip


def rate_planned(holes, plans, women=False, progress=None, client=None):
    """The ``CourseRating`` of ``holes`` from their ``plans`` (``plan_rating``): each player's
    solve of each hole (``play.solve_planned``; with its obstacles' plan, the hole without
    them solved after it) one task, the tasks one after another here (each on every thread),
    or on ``client``'s Dask workers at once (each task on one worker: split by hole and
    player), bit for bit the same. ``progress(player, hole_number)``: called as each task
    finishes."""
    from mcrun.executor import Executor

    items = list(plans.items())
    players = tuple(dict.fromkeys(player for player, _ in plans))
    solved = {}

    def done(k, result):
        solved[items[k][0]] = result
        if progress is not None:
            progress(*items[k][0])

    if client is None:
        for k, item in enumerate(items):
            done(k, _solved(item))
    else:
        Executor(client=client).map(_solved, items, done=done, name="hole")
    scores = {player: [solved[key][0] for key, _ in items if key[0] == player]
              for player in players}  # fmt: skip
    return CourseRating(list(holes), players, scores, solved[items[-1][0]][1], women)


def _solved(item):
    """A task of ``rate_planned``: ((player, hole number), plans) solved: the hole's
    HoleScore (with what its obstacles cost where the hole without them was planned) and the
    seed the solve used."""
    from mcrun.play import solve_planned

    (_, number), planned = item
    result = solve_planned(planned[0])
    score, seed = HoleScore.of(number, result), result.seed
    del result  # it holds every shot
    if len(planned) > 1:  # the hole without its obstacles
        clear = solve_planned(planned[1]).tee_value
        score = dataclasses.replace(score, obstacles_strokes=score.expected_strokes - clear)
    return score, seed


def rate(holes, players=None, n=100, seed=None, coarse_m=None, fine_m=None, plays=4000,
         women=False, progress=None, client=None, numbers=None, obstacles=False):  # fmt: skip
    """The ``CourseRating`` of ``holes`` (``mcrun.hole.Hole``s, in order) for ``players``
    (presets or Players; the first the scratch player, the second the bogey player; default
    ``MODEL_PLAYERS``' men's, or women's with ``women``, whose Slope is the women's): each hole
    solved for each player (``n`` shots an action, the states' spacings, ``plays`` plays of
    each policy), every solve planned before the first is flown (``plan_rating``), then one
    after another (``rate_planned``), or each player's solve of each hole on one of
    ``client``'s workers where given;
    ``numbers``: the holes' numbers in their course (default 1, 2, ...); ``obstacles``: each
    hole solved again without its obstacles (``without_obstacles``) for what they cost each
    player. ``progress(player, hole_number)``: called as each player's hole is solved."""
    players = MODEL_PLAYERS["women" if women else "men"] if players is None else players
    plans = plan_rating(holes, players, n=n, seed=seed, coarse_m=coarse_m, fine_m=fine_m,
                        plays=plays, numbers=numbers, obstacles=obstacles)  # fmt: skip
    return rate_planned(holes, plans, women=women, progress=progress, client=client)
