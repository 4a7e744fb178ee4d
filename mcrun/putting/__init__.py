"""Putting: the roll (``roll``), the cup (``cup``), the putter (``putter``), a putt struck with
its read, errors and the green's drift (``stroke``), the read's search (``read``), what a ball
at rest is worth (``rest``), holing out on plane greens (``holeout``), Tour-like greens and a
green's drift (``greens``) and the Tour putter's calibration (``calibration``); a hole's green
(``green``), its expected-putts map (``green_map``) and the map a hole's scores ask for
(``on_hole``).

``putt`` is the entry point from Python: a putt of a given length on a plane green, read and
holed out n times; ``mcrun putt`` prints its result.
"""

import math
from dataclasses import dataclass

import numpy as np

from mcrun.hole.hole import PUTTING_N_RANGE
from mcrun.physics.turf import rho_g_from_stimp
from mcrun.putting.cup import HOLE_RADIUS_M
from mcrun.putting.greens import (
    DRIFT_MM_PER_M_BENTGRASS,
    DRIFT_RANGE_MM_PER_M,
    STIMP_RANGE_FT,
    STIMP_RANGE_M,
    drift_sd,
    stopping_slope,
)
from mcrun.putting.putter import PUTTERS, Putter, putter_errors
from mcrun.putting.read import (
    AIM_STEPS_DEG,
    PACES_M,
    READ_NODES,
    Read,
    read_lines,
    search,
    value_read,
)
from mcrun.putting.rest import hole_out_values
from mcrun.putting.roll import DT_S
from mcrun.putting.stroke import (
    MAX_PUTTS,
    centre_line,
    pace_speed_mps,
    plane_putt_green,
    stroke_of,
)
from mcrun.quantities import InputError
from mcrun.strokes.baseline import FOOT_M
from mcrun.units import is_number, shown

__all__ = [
    "MAX_PUTTS",
    "PUTTERS",
    "PuttResult",
    "Putter",
    "Read",
    "check_putt",
    "check_stimp",
    "putt",
]

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

    @property
    def unfinished_share(self):
        """The share of holings-out that reached ``MAX_PUTTS`` and were counted so: a ball
        still rolling at the roll's cap (``roll.MAX_TIME_S``), on a slope near the green's
        stopping slope, where a plane green has no edge to roll off."""
        return float(np.mean(self.putts >= MAX_PUTTS))


def finite(value):
    """``value`` (a number) as a float; inf for an int beyond a float (10**400: an
    OverflowError where a message formatted it)."""
    try:
        return float(value)
    except OverflowError:
        return math.inf


def _rate(flags):
    n = flags.size
    p = float(flags.mean())
    return p, math.sqrt(p * (1.0 - p) / n)


def check_stimp(stimp_m, what=None):
    """``stimp_m`` (m), a Stimp reading within ``greens.STIMP_RANGE_M``; InputError (one line,
    beginning with ``what``, default "Stimp <reading> ft") otherwise."""
    lo, hi = STIMP_RANGE_M
    if not is_number(stimp_m):  # (a text, None or an array was a TypeError of a comparison)
        raise InputError(f"{what or 'stimp_m'} {shown(stimp_m)}: allowed: a number (m)")
    if not lo <= finite(stimp_m) <= hi:
        raise InputError(
            f"{what or f'Stimp {finite(stimp_m) / FOOT_M:g} ft'}: allowed: "
            f"{STIMP_RANGE_FT[0]:g} ft to {STIMP_RANGE_FT[1]:g} ft (a green's Stimpmeter "
            "reading; real greens run at about 5 to 16 ft)"
        )
    return stimp_m


def check_putt(distance_m, stimp_m, slope_tan, direction_deg, putter="tour", n=2000,
               drift_mm_per_m=DRIFT_MM_PER_M_BENTGRASS, said=None):  # fmt: skip
    """Check the inputs of ``putt`` (the seed apart, which it checks as it draws the errors):
    InputError (one line) for one out of range. Returns the ``Putter``.

    ``said``: what a message calls a field, where the user gave it otherwise than by its name and
    value (a command's option and the text typed, ``{"slope_tan": "--slope 2"}``); by default
    the field's name and its value."""
    said = said or {}

    def refuse(name, value, why):
        raise InputError(f"{said.get(name, value)}: {why}")

    given = {"distance_m": distance_m, "stimp_m": stimp_m, "slope_tan": slope_tan,
             "direction_deg": direction_deg, "n": n, "drift_mm_per_m": drift_mm_per_m}  # fmt: skip
    for name, value in given.items():  # (a string or None was a TypeError of a comparison)
        if not is_number(value):
            refuse(name, f"{name} {value!r}", "allowed: a number")
        if not math.isfinite(finite(value)) and name != "n":  # (n's range says it)
            refuse(name, f"{name} {shown(value, 40)}", "allowed: a finite number")
    if isinstance(putter, str):
        if putter not in PUTTERS:
            refuse("putter", f"putter {putter!r}", f"allowed: {', '.join(PUTTERS)}")
        putter = PUTTERS[putter]
    elif not isinstance(putter, Putter):
        refuse("putter", f"putter {putter!r}", f"allowed: {', '.join(PUTTERS)} or a Putter")
    if not HOLE_RADIUS_M < distance_m <= MAX_DISTANCE_M:
        refuse("distance_m", f"distance {distance_m:g} m", "allowed: beyond the hole's radius "
               f"({HOLE_RADIUS_M * 1000:.0f} mm) up to {MAX_DISTANCE_M:g} m")  # fmt: skip
    check_stimp(stimp_m, said.get("stimp_m"))
    if not 0.0 <= slope_tan <= MAX_SLOPE_TAN:
        refuse("slope_tan", f"slope {100 * slope_tan:g} %",
               f"allowed: 0 to {100 * MAX_SLOPE_TAN:g} %")  # fmt: skip
    rest = stopping_slope(stimp_m)
    if slope_tan > rest:
        refuse("slope_tan", f"slope {100 * slope_tan:g} %",
               f"steeper than the stopping slope of a Stimp {stimp_m / FOOT_M:g} ft green "
               f"({100 * rest:.1f} %): a ball cannot rest there")  # fmt: skip
    if not abs(direction_deg) <= 360.0:  # (NaN and inf fail too)
        refuse("direction_deg", f"direction {direction_deg:g} deg", "allowed: -360 to 360 deg")
    lo, hi = DRIFT_RANGE_MM_PER_M
    if not lo <= drift_mm_per_m <= hi:
        bentgrass = f"{DRIFT_MM_PER_M_BENTGRASS:g}: pure bentgrass"
        refuse("drift_mm_per_m", f"drift {drift_mm_per_m:g} mm/m",
               f"allowed: {lo:g} to {hi:g} mm/m ({bentgrass})")  # fmt: skip
    lo, hi = PUTTING_N_RANGE
    if not lo <= n <= hi or int(n) != n:  # (the range first: NaN and inf are out of it)
        refuse("n", f"n {shown(n, 40)}", f"allowed: a whole number from {lo} to {hi}")
    return putter


def putt(distance_m, stimp_m, slope_tan, direction_deg, putter="tour", n=2000, seed=0,
         read=True, drift_mm_per_m=DRIFT_MM_PER_M_BENTGRASS):  # fmt: skip
    """Hole out a putt of ``distance_m`` (m) on a plane green of Stimp ``stimp_m`` (m), slope
    ``slope_tan`` (rise over run) falling towards ``direction_deg`` (degrees from the putt's line,
    counter-clockwise: 0 downhill, 90 falls to the left, 180 uphill), drift ``drift_mm_per_m``
    (``greens``: 4.9 pure bentgrass, 0 a perfect green), ``n`` times, struck by ``putter`` (a
    name of ``PUTTERS`` or a ``Putter``) with errors seeded by ``seed``.

    With ``read`` the first putt's pace and start line are the ones that minimise the expected
    putts (``mcrun.putting.read``, on the same errors); without, the putter's own read (its pace
    on the centre line it perceives). Raises InputError for inputs out of range.
    """
    putter = check_putt(distance_m, stimp_m, slope_tan, direction_deg, putter, n, drift_mm_per_m)
    if not isinstance(read, bool | np.bool_):  # ("yes" or "no" would be true)
        raise InputError(f"read {read!r}: allowed: True or False")
    n = int(n)
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer) or not 0 <= seed < 2**63:
        raise InputError(f"seed {seed!r}: allowed: a whole number from 0 to 2**63 - 1")
    z, keys = putter_errors(n, seed)
    d = math.radians(direction_deg)
    green = plane_putt_green(slope_tan, math.cos(d), math.sin(d),
                             float(rho_g_from_stimp(stimp_m)), drift_sd(drift_mm_per_m),
                             DT_S)  # fmt: skip
    stroke = stroke_of(putter)
    rest_values = hole_out_values(z, keys)
    putts = np.zeros(n)
    hx = float(distance_m)
    if read:
        tried = np.zeros((len(PACES_M) + len(AIM_STEPS_DEG), 3))
        lines = np.zeros(len(READ_NODES))
        offset, pace, mean = search(0.0, 0.0, hx, 0.0, green, stroke, z, keys, rest_values,
                                    np.array(PACES_M), np.radians(AIM_STEPS_DEG), tried, putts,
                                    lines)[:3]  # fmt: skip
        centre = {p: _line(hx, p, green, stroke) for p in PACES_M}
        tried = tuple((math.degrees(o + centre[p]), float(p), float(m))
                      for o, p, m in tried)  # fmt: skip
    else:
        offset, pace = 0.0, putter.pace_m
        lines = read_lines(0.0, 0.0, hx, 0.0, pace, green, stroke)
        mean = value_read(0.0, 0.0, hx, 0.0, pace, offset, lines, green, stroke, z, keys,
                          rest_values, putts)[0]  # fmt: skip
        tried = ()
    chosen = Read(math.degrees(offset + lines[0]), float(pace),
                  float(mean), tried, math.degrees(offset))  # fmt: skip
    putts = np.rint(putts).astype(np.int64)
    make = _rate(putts == 1)
    three = _rate(putts >= 3)
    mean = float(putts.mean())
    mean_se = float(putts.std(ddof=1)) / math.sqrt(n)
    return PuttResult(distance_m, n, *make, *three, mean, mean_se, chosen, putts)


def _line(hx, pace, green, stroke):
    """The centre line (rad) the putter perceives without error at ``pace`` (``lines[0]`` of
    ``read.read_lines``)."""
    speed = pace_speed_mps(0.0, 0.0, hx, 0.0, pace, stroke.pace_slope_share, green, 0.0, 0.0)
    return float(centre_line(0.0, 0.0, hx, 0.0, speed, green, 0.0, 0.0))
