"""Plane greens: one putt's green from its slope, fall direction and Stimp reading, and the
reproducible sample of "Tour-like greens" the Tour putter is calibrated on.

The fall direction is the direction in which the green falls, in degrees from the putt's line
(from the ball to the hole), counter-clockwise seen from above: 0 the putt is straight downhill,
180 straight uphill, 90 the green falls to the golfer's left (the putt breaks left), 270 (or -90)
it falls to the right.

Tour-like greens (``tour_greens``): Stimp uniform in 11-12 ft, slope uniform in 1-3 %, fall
direction uniform all round: the Tour's greens run at Stimp 10-14 ft and typical green slopes are
1-3 % (the strokes-gained reference, "Putting").
"""

import math

import numpy as np

from mcrun.physics.turf import rho_g_from_stimp
from mcrun.strokes.baseline import FOOT_M

__all__ = [
    "STIMP_RANGE_FT",
    "STIMP_RANGE_M",
    "TOUR_GREENS_SEED",
    "plane_green",
    "stopping_slope",
    "tour_greens",
]

TOUR_GREENS_SEED = 20020  # the calibration's greens
TOUR_STIMP_FT = (11.0, 12.0)
TOUR_SLOPE_PCT = (1.0, 3.0)
# The Stimp readings a green to putt on may have: real greens run at about 5 ft (slow, as the
# paper's 6 ft) to 16 ft (the fastest tournament greens), so 3 to 20 ft is a generous range.
# Outside it the putting model is asked about no green that exists: a Stimp of 1e6 ft is a green
# with no rolling resistance (a ball rolls off whatever the pace), of 0.1 ft one on which no putt
# reaches the hole.
STIMP_RANGE_FT = (3.0, 20.0)
STIMP_RANGE_M = (STIMP_RANGE_FT[0] * FOOT_M, STIMP_RANGE_FT[1] * FOOT_M)


def plane_green(slope_tan, direction_rad, stimp_m, n=1):
    """One plane green, repeated n times, as the arrays (slope_tan, fall_x, fall_y, rho_g) of
    ``mcrun.putting.holeout.hole_out``."""
    ones = np.ones(n)
    return (
        slope_tan * ones,
        math.cos(direction_rad) * ones,
        math.sin(direction_rad) * ones,
        float(rho_g_from_stimp(stimp_m)) * ones,
    )


def stopping_slope(stimp_m):
    """The steepest slope (as tan) on which a ball rests on a green of this Stimp: rho_g."""
    return float(rho_g_from_stimp(stimp_m))


def tour_greens(n, seed=TOUR_GREENS_SEED):
    """n Tour-like greens (arrays as ``plane_green``), seeded."""
    rng = np.random.Generator(np.random.PCG64(np.random.SeedSequence(seed)))
    stimp_m = rng.uniform(*TOUR_STIMP_FT, n) * FOOT_M
    slope_tan = rng.uniform(*TOUR_SLOPE_PCT, n) / 100.0
    direction = rng.uniform(0.0, 2.0 * math.pi, n)
    return slope_tan, np.cos(direction), np.sin(direction), rho_g_from_stimp(stimp_m)
