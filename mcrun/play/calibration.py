"""The Tour player's dispersion, calibrated: each club's spread (``Player.spread``, the factor
on the deviations of its ball speed, launch angle, spin, spin axis and azimuth from their
means) set to the Tour's published outcomes (the strokes-gained reference, "A strategy's
checks"):

- approach clubs (a mean total under ``WOOD_YD``, 235 yd): the mean distance of the finishes
  from the centre of the club's pattern, on the level, equal to the Tour's approach proximity at the
  club's distance from the fairway: 20 ft 0 in from 100-125 yd, 27 ft 6 in from 150-175 yd and
  50 ft 3 in from over 200 yd (ShotLink season averages, as the Tour publishes them: the
  strokes-gained reference, and GolfTEC's summary of the same for the 200-plus band), linear in
  the distance between the bands' middles and beyond the last; the 200-plus band's middle is
  taken at 225 yd (an ESTIMATE: most of the Tour's long approaches are from 200-250 yd);
- the driver and the woods (longer): the share of drives within 15 m either side of the pattern's
  centre line (a fairway 30 m, 33 yd, wide, centred) equal to the Tour's 60 % of fairways hit.

Off the ground (``calibrate_ground``: ``Player.ground``, the factor on a club's spread from any
lie but the tee): 1 for the approach clubs (calibrated from the fairway) and for the clubs
struck from the tee only (``player.tee_only``: the driver); for the other woods (calibrated off
the tee) the factor that puts their expected strokes on the plane (``short_game_cost``: the
pattern centred on the pin of a round green) as far from Table 9's at their distance as the
approach clubs' are on average. No proximity beyond the "over 200 yd" band is published: Table
9 is the target there.

From the rough (``calibrate_rough``: the factor on the pattern that ``player.lie_launch``
applies there, besides the flyer's speed and spin), against the fairway's (off the ground)
at the distance the rough's shot goes:

- every full club, and the wedge's part powers of ``SHORT_GAME_YD`` (50 yd) or more: the mean
  distance of the finishes from the pattern's centre equal to the fairway's times the Tour's
  ratio of the two at the club's distance (``ROUGH_RATIO``: 30 ft 3 in against 20 ft 0 in from
  100-125 yd, 41 ft 5 in against 27 ft 6 in from 150-175 yd, 72 ft 9 in against 50 ft 3 in from
  over 200 yd; the same ShotLink averages as GolfTEC summarises them), linear between the bands'
  middles and held beyond them (below 100 yd an ESTIMATE: no proximity is published there);
- the wedge's pitches shorter than that, around the green: the cost of the rough over
  the fairway at the pitch's distance equal to Table 9's (``strokes.tour_baseline``), each
  pattern centred on the pin of a round green (``GREEN_RADIUS_M``), its finishes worth the
  baseline's putts on it and its strokes from the rough off it.

The pattern is centred (the club's mean distance, the aim's line): a player who chooses the
club for the distance and aims at the pin; the errors of choosing and aiming are in the
spread. The proximity and the lateral spread grow nearly in proportion to the spread (tested),
so one step of the ratio finds it (the Tour bag's; a few for the amateurs' wider patterns),
and a further pattern checks it. ``calibrate(player, n)`` returns the
spreads, ``calibrate_ground`` and then ``calibrate_rough`` (on the player with those) the
others, by bisection; ``mcrun.play.player`` holds those of the Tour bag (``TOUR_SPREAD``,
``TOUR_GROUND``, ``TOUR_ROUGH``, ``PITCH_ROUGH``), and ``tests/test_play.py`` checks them.
"""

import dataclasses
from statistics import NormalDist

import numpy as np

from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import COLUMN, OUTCOME_FIELDS
from mcrun.play.player import (
    LIE_LAUNCH,
    PART_POWERS,
    club_shots,
    lie_launch,
    spread_inputs,
    tee_only,
)
from mcrun.run import sampling
from mcrun.strokes import tour_baseline
from mcrun.strokes.baseline import FOOT_M, LIES, YARD_M

__all__ = [
    "AMATEUR_TARGETS",
    "FAIRWAY_HALF_WIDTH_M",
    "FAIRWAY_SHARE",
    "GREEN_RADIUS_M",
    "ROUGH_RATIO",
    "SHORT_GAME_YD",
    "calibrate",
    "calibrate_ground",
    "calibrate_rough",
    "lie_pattern",
    "longer",
    "pattern",
    "proximity_target_ft",
    "rough_ratio",
    "short_game_cost",
]

WOOD_YD = 235.0
# The Tour's approach proximity from the fairway (ft) at the middle of its distance bands (yd):
# 100-125, 150-175 and over 200 (its middle an ESTIMATE, see above).
PROXIMITY_FT = ((112.5, 20.0), (162.5, 27.5), (225.0, 50.25))
# The Tour's approach proximity from the rough over that from the fairway (GolfTEC's summary of
# ShotLink: 30'3" / 20'0", 41'5" / 27'6", 72'9" / 50'3"), at the middles of the same bands (yd).
ROUGH_RATIO = ((112.5, 30.25 / 20.0), (162.5, (41.0 + 5.0 / 12.0) / 27.5), (225.0, 72.75 / 50.25))
SHORT_GAME_YD = 50.0
# A Tour green's radius (m): round, about 6,000 sq ft (560 m^2), the pin in its middle
# (ESTIMATE).
GREEN_RADIUS_M = 13.3
FAIRWAY_HALF_WIDTH_M = 15.0
FAIRWAY_SHARE = 0.60
# The model amateurs' targets: (their approach proximity over the Tour's, their fairways hit).
# The ratios FITTED (``benchmarks/rating.py``'s check, a flat open par 4 of 400 yd, n = 50) so
# that scratch plays it 0.30 strokes worse than the Tour (Table 9's 3.99 + 0.30 = 4.29: rounds
# to a 0 handicap are 5.45 strokes a round worse than the Tour's on courses of the same
# difficulty, ShotByShot) and bogey 1.17 worse than scratch (5.46: the USGA's bogey golfer 21
# strokes a round behind scratch at Slope 113), with the greens' maps putted as the players'
# own putters read (the maps' default): 1.28 and 3.09 (4.290 and 5.459 there; with the best
# of 12 reads a point, the maps' earlier default, it was 1.33 and 3.21). The amateurs reference's
# proximity gives 1.43-1.82 for scratch (31 ft from 100 yd, Shot Scope; 36 ft 8 in from 150 yd,
# Arccos; 30 ft farther than the Tour from 175-200 yd, Shot Scope) and 3.59 for a Handicap
# Index of 20 (65 ft from 100 yd, Shot Scope): the fit is a little closer, as the amateurs'
# short game and putting are the Tour's scaled. Fairways: scratch 50 % (Arccos 51, Shot Scope
# 50), bogey 43 % (Arccos 41, Shot Scope 45).
AMATEUR_TARGETS = {"scratch": (1.28, 0.50), "bogey": (3.09, 0.43)}
AMATEUR_STEPS = 4
_OUT = {name: k for k, name in enumerate(OUTCOME_FIELDS)}


def pattern(scenario, club, n, factor, speed=1.0):
    """(total_yd, proximity_ft about the centre, share within the fairway, lateral standard
    deviation m) of ``club``'s first n shots on the level at spread ``factor``, ball speed
    times ``speed``."""
    inputs, _ = sampling.sample(scenario, scenario.points[club], 0, n)
    shots = spread_inputs(inputs, factor)
    shots[:, COLUMN["ball_speed_mps"]] *= speed
    out = simulate_batch(shots)
    x, y = out[:, _OUT["final_x_m"]], out[:, _OUT["final_y_m"]]
    ok = np.isfinite(x) & np.isfinite(y)
    x, y = x[ok], y[ok]
    proximity = float(np.hypot(x - x.mean(), y - y.mean()).mean()) / FOOT_M
    share = float((np.abs(y - y.mean()) <= FAIRWAY_HALF_WIDTH_M).mean())
    return float(x.mean()) / YARD_M, proximity, share, float(y.std())


def proximity_target_ft(distance_yd):
    """The Tour's approach proximity (ft) at ``distance_yd``: piecewise linear through
    ``PROXIMITY_FT``, its first and last pieces carried on beyond its ends."""
    k = 0
    while k < len(PROXIMITY_FT) - 2 and distance_yd > PROXIMITY_FT[k + 1][0]:
        k += 1
    (d0, p0), (d1, p1) = PROXIMITY_FT[k], PROXIMITY_FT[k + 1]
    return p0 + (p1 - p0) * (distance_yd - d0) / (d1 - d0)


def calibrate(player, n=4000, ratio=1.0, share=FAIRWAY_SHARE, steps=1):
    """Each club's spread (a tuple in the bag's order) and what it gives: rows (club, total_yd,
    spread, proximity_ft, target_ft or None, fairway share, target share or None). The clubs
    at the player's ball speeds (``Player.speed``); the approach clubs and the woods told apart
    at full speed (``WOOD_YD``). ``ratio``: the approach proximity targets times this (a
    player's against the Tour's); ``share``: the fairways' target (the Tour's 60 %); ``steps``:
    of the ratio (the Tour bag's one; the amateurs', whose spreads are wider and further from
    proportional, four)."""
    spreads, rows = [], []
    for club, name in enumerate(player.clubs):
        wood = pattern(player.scenario, club, n, 1.0)[0] >= WOOD_YD
        speed = player.speed_of(club)
        factor = 1.0
        for _ in range(steps):
            total, proximity, got, _ = pattern(player.scenario, club, n, factor, speed)
            if not wood:
                factor *= ratio * proximity_target_ft(total) / proximity
            else:
                # A normal lateral spread puts a share 2 Phi(w / sd) - 1 within w of its
                # centre: the spread scales sd by the ratio of the two quantiles.
                factor *= _quantile(got) / _quantile(share)
        factor = round(factor, 3)
        total, proximity, got, _ = pattern(player.scenario, club, n, factor, speed)
        spreads.append(factor)
        rows.append((name, total, factor, proximity,
                     None if wood else ratio * proximity_target_ft(total), got,
                     share if wood else None))  # fmt: skip
    return tuple(spreads), rows


def _quantile(share):
    """w / sd of a normal spread that puts ``share`` within w of its centre."""
    return NormalDist().inv_cdf((1.0 + share) / 2.0)


def rough_ratio(distance_yd):
    """The Tour's proximity from the rough over that from the fairway at ``distance_yd``:
    piecewise linear through ``ROUGH_RATIO``, held beyond its ends."""
    d = min(max(distance_yd, ROUGH_RATIO[0][0]), ROUGH_RATIO[-1][0])
    k = 0
    while k < len(ROUGH_RATIO) - 2 and d > ROUGH_RATIO[k + 1][0]:
        k += 1
    (d0, r0), (d1, r1) = ROUGH_RATIO[k], ROUGH_RATIO[k + 1]
    return r0 + (r1 - r0) * (d - d0) / (d1 - d0)


def lie_pattern(player, club, n, lie, rough, power=1.0, ground=None):
    """The finishes (x_m, y_m) on the level of ``player``'s first n shots of ``club`` at
    ``power`` (its spread and speed; off the ground its spread times ``ground``, default
    ``Player.ground_of``) struck from ``lie``, the rough's pattern factor ``rough``."""
    ground = player.ground_of(club) if ground is None else ground
    spread = player.spread[club] * (1.0 if lie == "tee" else ground)
    inputs = club_shots(player.scenario, club, n, power, spread, player.speed_of(club))
    lie_launch(inputs, [LIES.index(lie)], n, rough)
    out = simulate_batch(np.asfortranarray(inputs))
    x, y = out[:, _OUT["final_x_m"]], out[:, _OUT["final_y_m"]]
    ok = np.isfinite(x) & np.isfinite(y)
    return x[ok], y[ok]


def _proximity_ft(x, y):
    return float(np.hypot(x - x.mean(), y - y.mean()).mean()) / FOOT_M


def short_game_cost(x, y, base):
    """A pitch's expected strokes, its finishes (x, y) centred on the pin of a round green of
    ``GREEN_RADIUS_M``: 1 + the mean of the baseline's (``base``, a ``strokes.Baseline``) putts
    from those on it and its rough's strokes from those off it."""
    d = np.hypot(x - x.mean(), y - y.mean())
    on = d <= GREEN_RADIUS_M
    return 1.0 + float(np.where(on, base.expected("green", d), base.expected("rough", d)).mean())


def calibrate_rough(player, n=4000, fit=True):
    """The rough's pattern factor of each full club of ``player`` and of each part power of its
    wedge (``player.PART_POWERS``' order), as the module says, and what they give: rows (club,
    power, total_yd from the rough, what is matched, its target, what the factor gives, the
    factor). A shot from the rough is set against the fairway's at the distance the rough's
    goes (the player takes the club or power that reaches the pin from there): the fairway's
    proximity and cost interpolated between the bag's own (off the ground at its
    ``Player.ground``: ``calibrate_ground`` first). ``fit=False``: the player's own factors
    (``Player.rough_of``), what they give."""
    base = tour_baseline()
    last = len(player.clubs) - 1
    shots = [(c, 1.0) for c in range(last + 1)] + [(last, p) for p in PART_POWERS]
    fairway = [lie_pattern(player, club, n, "fairway", 1.0, power) for club, power in shots]
    yd = np.array([float(x.mean()) / YARD_M for x, _ in fairway])
    # the fairway's own: a club struck from the tee only is not
    order = np.array([k for k in np.argsort(yd) if not tee_only(player.clubs[shots[k][0]])])
    proximity = np.array([_proximity_ft(x, y) for x, y in fairway])
    cost = np.array([short_game_cost(x, y, base) for x, y in fairway])

    def at(values, d_yd):
        return float(np.interp(d_yd, yd[order], values[order]))

    clubs, pitches, rows = [], [], []
    for k, (club, power) in enumerate(shots):
        if tee_only(player.clubs[club]) and power == 1.0:  # never from the rough
            clubs.append(LIE_LAUNCH["rough"][2])
            rows.append((player.clubs[club], power, yd[k], "struck from the tee only", None,
                         None, clubs[-1]))  # fmt: skip
            continue
        if yd[k] >= SHORT_GAME_YD:

            def gap(f, club=club, power=power):
                x, y = lie_pattern(player, club, n, "rough", f, power)
                d = float(x.mean()) / YARD_M
                return _proximity_ft(x, y), rough_ratio(d) * at(proximity, d), d

            what = "rough proximity ft"
        else:

            def gap(f, club=club, power=power):
                x, y = lie_pattern(player, club, n, "rough", f, power)
                d = float(x.mean()) / YARD_M
                table = base.expected("rough", d * YARD_M) - base.expected("fairway", d * YARD_M)
                return short_game_cost(x, y, base) - at(cost, d), float(table), d

            what = "rough's cost, strokes"
        factor = _bisect(lambda f: (lambda g: g[0] - g[1])(gap(f)), 0.5, 8.0) if fit else (
            player.rough_of(club, power))  # fmt: skip
        got, target, d = gap(factor)
        (clubs if power == 1.0 else pitches).append(factor)
        rows.append((player.clubs[club], power, d, what, target, got, factor))
    return tuple(clubs), tuple(pitches), rows


def calibrate_ground(player, n=4000, fit=True):
    """Each club's factor on its spread off the ground (``Player.ground``; a tuple in the bag's
    order), as the module says, and what it gives: rows (club, total_yd, the plane's cost less
    Table 9's, its target or None, the factor). ``fit=False``: the player's own factors
    (``Player.ground_of``), what they give."""
    base = tour_baseline()

    def gap(club, factor):
        x, y = lie_pattern(player, club, n, "fairway", 1.0, ground=factor)
        d_m = float(x.mean())
        return short_game_cost(x, y, base) - float(base.expected("fairway", d_m)), d_m / YARD_M

    gaps = [gap(club, 1.0) for club in range(len(player.clubs))]
    approach = [g for g, d in gaps if d < WOOD_YD]
    target = float(np.mean(approach))
    factors, rows = [], []
    for club, (g, d) in enumerate(gaps):
        if d < WOOD_YD or tee_only(player.clubs[club]):
            factors.append(1.0)
            rows.append((player.clubs[club], d, g, None, 1.0))
            continue
        factor = (_bisect(lambda f, club=club: gap(club, f)[0] - target, 0.5, 4.0) if fit
                  else player.ground_of(club))  # fmt: skip
        g, d = gap(club, factor)
        factors.append(factor)
        rows.append((player.clubs[club], d, g, target, factor))
    return tuple(factors), rows


def _bisect(excess, lo, hi, steps=16):
    """The factor in [lo, hi], to 3 decimals, where ``excess`` (growing with it) crosses 0."""
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if excess(mid) < 0.0 else (lo, mid)
    return round(0.5 * (lo + hi), 3)


def longer(player, club, yards, n=2000):
    """``player`` whose ``club`` (an index) goes ``yards`` further on the level (its mean total):
    its ball speed factor found by bisection (its other launch values kept)."""
    base = player.speed_of(club)
    target = pattern(player.scenario, club, n, player.spread[club], base)[0] + yards
    lo, hi = 0.5 * base, 1.5 * base
    for _ in range(30):
        mid = 0.5 * (lo + hi)
        if pattern(player.scenario, club, n, player.spread[club], mid)[0] < target:
            lo = mid
        else:
            hi = mid
    speed = list(player.speed or (1.0,) * len(player.clubs))
    speed[club] = 0.5 * (lo + hi)
    name = f"{player.name} ({player.clubs[club]} {yards:+g} yd)"
    return dataclasses.replace(player, name=name, speed=tuple(speed))
