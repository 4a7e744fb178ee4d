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

The pattern is centred (the club's mean distance, the aim's line): a player who chooses the
club for the distance and aims at the pin; the errors of choosing and aiming are in the
spread. The proximity and the lateral spread grow in proportion to the spread (tested), so one
step of the ratio finds it, and a second checks it. ``calibrate(player, n)`` returns the
spreads; ``mcrun.play.player.TOUR_SPREAD`` holds those of the Tour bag, and
``tests/test_play.py`` checks them.
"""

from statistics import NormalDist

import numpy as np

from mcrun.engine.backend import simulate_batch
from mcrun.engine.schema import COLUMN, OUTCOME_FIELDS
from mcrun.run import sampling
from mcrun.strokes.baseline import FOOT_M, YARD_M

__all__ = ["FAIRWAY_HALF_WIDTH_M", "FAIRWAY_SHARE", "calibrate", "pattern", "proximity_target_ft"]

WOOD_YD = 235.0
# The Tour's approach proximity from the fairway (ft) at the middle of its distance bands (yd):
# 100-125, 150-175 and over 200 (its middle an ESTIMATE, see above).
PROXIMITY_FT = ((112.5, 20.0), (162.5, 27.5), (225.0, 50.25))
FAIRWAY_HALF_WIDTH_M = 15.0
FAIRWAY_SHARE = 0.60
SPREAD_COLUMNS = ("ball_speed_mps", "launch_angle_rad", "spin_radps", "spin_axis_rad",
                  "azimuth_rad")  # fmt: skip
_OUT = {name: k for k, name in enumerate(OUTCOME_FIELDS)}


def spread_inputs(inputs, factor):
    """``inputs`` with each ``SPREAD_COLUMNS`` deviation from its mean times ``factor``."""
    out = np.asfortranarray(inputs.copy())
    for name in SPREAD_COLUMNS:
        j = COLUMN[name]
        centre = out[:, j].mean()
        out[:, j] = centre + (out[:, j] - centre) * factor
    return out


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


def calibrate(player, n=4000):
    """Each club's spread (a tuple in the bag's order) and what it gives: rows (club, total_yd,
    spread, proximity_ft, target_ft or None, fairway share, target share or None)."""
    spreads, rows = [], []
    for club, name in enumerate(player.clubs):
        total, proximity, share, _ = pattern(player.scenario, club, n, 1.0)
        if total < WOOD_YD:
            target = proximity_target_ft(total)
            factor = target / proximity
        else:
            # A normal lateral spread puts a share 2 Phi(w / sd) - 1 within w of its centre:
            # the spread scales sd by the ratio of the two quantiles.
            factor = _quantile(share) / _quantile(FAIRWAY_SHARE)
        factor = round(factor, 3)
        total, proximity, share, _ = pattern(player.scenario, club, n, factor)
        spreads.append(factor)
        rows.append((name, total, factor, proximity,
                     proximity_target_ft(total) if total < WOOD_YD else None, share,
                     FAIRWAY_SHARE if total >= WOOD_YD else None))  # fmt: skip
    return tuple(spreads), rows


def _quantile(share):
    """w / sd of a normal spread that puts ``share`` within w of its centre."""
    return NormalDist().inv_cdf((1.0 + share) / 2.0)
