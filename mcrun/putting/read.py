"""The read: the start line and pace of a putt that minimise its expected putts.

A small search with common random numbers: every candidate (start line, pace) is holed out by the
same n sampled putters' errors and greens, so that the differences between candidates are the
candidates', not the samples'. First the paces ``PACES_M`` past the hole, each on the start line
that rolls the error-free putt over the hole's centre at that pace; then, at the best pace, start
lines ``AIM_STEPS_DEG`` either side of it. Later putts of a holing-out are read as the putter
reads any putt (``mcrun.putting.holeout``).

The strategy is that of Broadie's putting simulations: an aim line and a speed chosen for the
least expected putts under the golfer's errors (M. Broadie, "A simulation model of putting",
2007; M. Broadie and D. Shin, "Golf analytics: a random putting model and its applications to
optimal targeting strategy and attribution analysis", 2014).
"""

import math
from dataclasses import dataclass

from mcrun.putting.holeout import hole_out_batch, line_through_centre, pace_speed_mps

__all__ = ["AIM_STEPS_DEG", "PACES_M", "Read", "centre_line_rad", "read_putt"]

PACES_M = (0.15, 0.3, 0.43, 0.6, 0.8, 1.0)
AIM_STEPS_DEG = (-1.0, -0.5, -0.25, 0.25, 0.5, 1.0)


@dataclass(frozen=True)
class Read:
    """The chosen start line (deg from the line to the hole, + left), pace (m past the hole),
    their mean putts, and every candidate tried: ((aim_deg, pace_m, mean_putts), ...)."""

    aim_deg: float
    pace_m: float
    mean_putts: float
    tried: tuple


def centre_line_rad(distance_m, green, pace_m):
    """The start line (rad, + left) on which the error-free putt at ``pace_m`` rolls over the
    hole's centre, on the first green of ``green``."""
    slope_tan, fall_x, fall_y, rho_g = (float(a[0]) for a in green)
    speed = pace_speed_mps(distance_m, pace_m, fall_x, slope_tan, rho_g)
    return line_through_centre(0.0, 0.0, distance_m, 0.0, speed, slope_tan, fall_x, fall_y, rho_g)


def read_putt(distance_m, green, putter, z):
    """The Read of a putt of ``distance_m`` on ``green`` (arrays of n, as ``hole_out``) by
    ``putter`` with the errors ``z`` (n, MAX_PUTTS, 2)."""
    tried = []

    def score(aim_rad, pace_m):
        putts, _ = hole_out_batch(distance_m, green, putter, z, first=(aim_rad, pace_m))
        mean = float(putts.mean())
        tried.append((math.degrees(aim_rad), pace_m, mean))
        return mean

    best = None
    for pace in PACES_M:
        aim = centre_line_rad(distance_m, green, pace)
        mean = score(aim, pace)
        if best is None or mean < best[2]:
            best = (aim, pace, mean)
    aim0, pace, _ = best
    for step in AIM_STEPS_DEG:
        aim = aim0 + math.radians(step)
        mean = score(aim, pace)
        if mean < best[2]:
            best = (aim, pace, mean)
    return Read(math.degrees(best[0]), best[1], best[2], tuple(tried))
