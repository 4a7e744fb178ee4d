"""Putting on a plane green: the roll (``roll``), the cup (``cup``), the putter (``putter``),
holing out (``holeout``), the read (``read``), plane and Tour-like greens (``greens``) and the
Tour putter's calibration (``calibration``).

``putt`` is the entry point from Python: a putt of a given length on a plane green, read and
holed out n times; ``mcrun putt`` prints its result.
"""

import math
from dataclasses import dataclass

import numpy as np

from mcrun.putting.cup import HOLE_RADIUS_M
from mcrun.putting.greens import STIMP_RANGE_FT, STIMP_RANGE_M, plane_green, stopping_slope
from mcrun.putting.holeout import MAX_PUTTS, hole_out_batch
from mcrun.putting.putter import PUTTERS, Putter, putter_errors
from mcrun.putting.read import Read, centre_line_rad, read_putt
from mcrun.quantities import InputError
from mcrun.strokes.baseline import FOOT_M

__all__ = ["MAX_PUTTS", "PUTTERS", "PuttResult", "Putter", "Read", "check_stimp", "putt"]

MAX_DISTANCE_M = 100.0
MAX_SLOPE_TAN = 0.2


@dataclass(frozen=True)
class PuttResult:
    """A putt's outcome over n holings-out: make rate (one putt), three-putt rate (three or
    more) and average putts, each with its standard error; the read it was struck with."""

    distance_m: float
    n: int
    make_rate: float
    make_rate_se: float
    three_putt_rate: float
    three_putt_rate_se: float
    average_putts: float
    average_putts_se: float
    read: Read
    putts: np.ndarray  # putts of each holing-out (MAX_PUTTS where not holed by then)


def _rate(flags):
    n = flags.size
    p = float(flags.mean())
    return p, math.sqrt(p * (1.0 - p) / n)


def check_stimp(stimp_m, what=None):
    """``stimp_m`` (m), a Stimp reading within ``greens.STIMP_RANGE_M``; InputError (one line,
    beginning with ``what``, default "Stimp <reading> ft") otherwise."""
    lo, hi = STIMP_RANGE_M
    if not lo <= stimp_m <= hi:
        raise InputError(
            f"{what or f'Stimp {stimp_m / FOOT_M:g} ft'}: allowed: "
            f"{STIMP_RANGE_FT[0]:g} ft to {STIMP_RANGE_FT[1]:g} ft (a green's Stimpmeter "
            "reading; real greens run at about 5 to 16 ft)"
        )
    return stimp_m


def putt(distance_m, stimp_m, slope_tan, direction_deg, putter="tour", n=2000, seed=0,
         read=True):  # fmt: skip
    """Hole out a putt of ``distance_m`` (m) on a plane green of Stimp ``stimp_m`` (m), slope
    ``slope_tan`` (rise over run) falling towards ``direction_deg`` (degrees from the putt's line,
    counter-clockwise: 0 downhill, 90 falls to the left, 180 uphill), ``n`` times, struck by
    ``putter`` (a name of ``PUTTERS`` or a ``Putter``) with errors seeded by ``seed``.

    With ``read`` the first putt's start line and pace are the ones that minimise the expected
    putts (``mcrun.putting.read``, on the same errors); without, the putter's own read (over the
    hole's centre at its pace). Raises InputError for inputs out of range.
    """
    if isinstance(putter, str):
        if putter not in PUTTERS:
            raise InputError(f"putter {putter!r}: allowed: {', '.join(PUTTERS)}")
        putter = PUTTERS[putter]
    if not HOLE_RADIUS_M < distance_m <= MAX_DISTANCE_M:
        raise InputError(
            f"distance {distance_m:g} m: allowed: beyond the hole's radius "
            f"({HOLE_RADIUS_M * 1000:.0f} mm) up to {MAX_DISTANCE_M:g} m"
        )
    check_stimp(stimp_m)
    if not 0.0 <= slope_tan <= MAX_SLOPE_TAN:
        raise InputError(f"slope {100 * slope_tan:g} %: allowed: 0 to {100 * MAX_SLOPE_TAN:g} %")
    rest = stopping_slope(stimp_m)
    if slope_tan > rest:
        raise InputError(
            f"slope {100 * slope_tan:g} %: steeper than the stopping slope of a Stimp "
            f"{stimp_m / 0.3048:g} ft green ({100 * rest:.1f} %): a ball cannot rest there"
        )
    if not math.isfinite(direction_deg):
        raise InputError(f"direction {direction_deg}: allowed: a finite angle in degrees")
    if int(n) != n or n < 2:
        raise InputError(f"n {n}: allowed: a whole number of at least 2")
    n = int(n)
    green = plane_green(slope_tan, math.radians(direction_deg), stimp_m, n)
    try:
        z = putter_errors(n, seed)
    except (TypeError, ValueError):
        raise InputError(f"seed {seed!r}: allowed: a whole number 0 or more") from None
    if read:
        chosen = read_putt(distance_m, green, putter, z)
    else:
        aim = centre_line_rad(distance_m, green, putter.pace_m)
        chosen = Read(math.degrees(aim), putter.pace_m, float("nan"), ())
    putts, _ = hole_out_batch(
        distance_m, green, putter, z, first=(math.radians(chosen.aim_deg), chosen.pace_m)
    )
    make = _rate(putts == 1)
    three = _rate(putts >= 3)
    mean = float(putts.mean())
    mean_se = float(putts.std(ddof=1)) / math.sqrt(n)
    return PuttResult(distance_m, n, *make, *three, mean, mean_se, chosen, putts)
