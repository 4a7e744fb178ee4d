"""The putter: the player who strikes the putt, as a pace and three error sizes.

A putter reads the green (``stroke``: it perceives the green tilted by a plane it misreads, each
component of that plane's fall vector a normal error of ``read_sd_pct`` % of slope), chooses a
pace, ``pace_m`` past the hole (default 0.43 m, 17 in: the rule of thumb for a makeable putt,
Pelz, Putting Bible (2000), as quoted in the strokes-gained reference; ``pace_slope_share`` of
the slope beyond the hole allowed for) and the start line that rolls over the hole's centre on
the green it perceives, then misses the start line by a normal error of ``line_sd_deg`` and its
speed by a relative normal error of ``speed_sd_pct``, independently per putt. The green adds its
drift while the ball rolls (``greens``).

Presets (``PUTTERS``):

- "tour": CALIBRATED (``calibration``; the table in docs/putting.md, checked by
  tests/test_putting.py) to the PGA Tour's make rates and average putts on Tour-like greens and
  to the Tour's putts on slopes (uphill against downhill at 8 ft, the leaves of a 10-footer
  uphill and downhill, the share left short), all at once (``calibration.refit``): start line
  1.0 deg, speed 3.3 %, read 0.4 % of slope, pace slope share 0.4. Where the Tour putter had
  no read error (1.5 deg and 4.7 %), a downhill 8-footer was holed 10 points more often than an
  uphill one, against the Tour's 2.5-5 points fewer. Karlsen and Nilsson (2008) put green
  reading at 60 % of a good player's distance variance, technique 34 %; here the read's share
  of a 10-footer's speed variance depends on the slope.
- "scratch", "15-handicap": ESTIMATES scaled from the Tour's. Broadie (Every Shot Counts, 2014;
  the strokes-gained reference): amateurs of 0-9 handicap make half their putts from about 6 ft
  where the Tour does from 8 ft. A make rate of short putts is set by the start line's error
  against the hole's angular width, which falls as 1/distance: so the 50 % distance scales as
  1/line_sd, and a scratch player's line error is the Tour's times 8/6. The 15-handicap's is the
  Tour's times 8/4.5 (50 % from about 4.5 ft: an extrapolation, no published figure). Their
  speed and read errors are scaled by the same factors (the one published comparison is of make
  rates; this is an estimate).
"""

from dataclasses import dataclass

import numpy as np

from mcrun.errors import InputError
from mcrun.putting.stroke import MAX_PUTTS
from mcrun.units import is_number, shown

__all__ = ["DEFAULT_PACE_M", "PUTTERS", "Putter", "putter_errors"]

DEFAULT_PACE_M = 0.43  # 17 in past the hole


@dataclass(frozen=True)
class Putter:
    """Pace (m past the hole) and the standard deviations of start line (deg), speed (%) and
    the read of the slope (%: each component of the fall vector of the tilt the putter
    misreads, ``stroke``)."""

    name: str
    line_sd_deg: float
    speed_sd_pct: float
    read_sd_pct: float = 0.0
    pace_m: float = DEFAULT_PACE_M
    pace_slope_share: float = 1.0

    def __post_init__(self):
        """InputError, one line, for a field out of ``PUTTER_RANGES`` (NaN errors struck every
        putt to the 10-putt cap; a negative pace was a SystemError from the compiled read)."""
        if not isinstance(self.name, str):
            raise InputError(f"Putter name {self.name!r}: allowed: text")
        for field, (lo, hi, unit) in PUTTER_RANGES.items():
            value = getattr(self, field)
            if not is_number(value) or not lo <= value <= hi:
                raise InputError(f"Putter {field} {shown(value)}: allowed: a number from {lo:g} "
                                 f"to {hi:g}{unit}")  # fmt: skip


# What a putter's fields may be: errors of none to several times the 15-handicap's (1.8 deg,
# 5.9 %, 0.7 % of slope), a pace up to 3 m past the hole, a share of the slope from 0 to 1.
PUTTER_RANGES = {
    "line_sd_deg": (0.0, 10.0, " deg"),
    "speed_sd_pct": (0.0, 50.0, " %"),
    "read_sd_pct": (0.0, 50.0, " % of slope"),
    "pace_m": (0.0, 3.0, " m"),
    "pace_slope_share": (0.0, 1.0, ""),
}


# CALIBRATED (docs/putting.md): tests/test_putting.py checks the table.
TOUR_LINE_SD_DEG = 1.0
TOUR_SPEED_SD_PCT = 3.3
TOUR_READ_SD_PCT = 0.4
TOUR_PACE_SLOPE_SHARE = 0.4
SCRATCH_FACTOR = 8.0 / 6.0
HIGH_HANDICAP_FACTOR = 8.0 / 4.5


def scaled(name, factor):
    """The Tour putter with every error ``factor`` times larger."""
    return Putter(name, TOUR_LINE_SD_DEG * factor, TOUR_SPEED_SD_PCT * factor,
                  TOUR_READ_SD_PCT * factor, DEFAULT_PACE_M, TOUR_PACE_SLOPE_SHARE)  # fmt: skip


PUTTERS = {
    "tour": scaled("tour", 1.0),
    "scratch": scaled("scratch", SCRATCH_FACTOR),
    "15-handicap": scaled("15-handicap", HIGH_HANDICAP_FACTOR),
}


def putter_errors(n, seed):
    """The errors of n holings-out, from ``numpy.random.SeedSequence(seed)``: standard normals
    (n, MAX_PUTTS, 4) of each putt's start line, speed and read (x, y), and the keys (n, MAX_PUTTS)
    uint64 of its drift on the green (``roll.drift_step``). The same seed, the same errors
    (common random numbers for every read a search tries). The normals come in antithetic
    pairs (holing-out n // 2 + i has the errors of i negated): every error's mean is 0 exactly,
    so a sample does not lean to one side of the hole or one pace."""
    rng = np.random.Generator(np.random.PCG64(np.random.SeedSequence(seed)))
    z = rng.standard_normal((n, MAX_PUTTS, 4))
    half = n // 2
    z[half : 2 * half] = -z[:half]
    keys = rng.integers(0, 2**64, size=(n, MAX_PUTTS), dtype=np.uint64, endpoint=False)
    return z, keys
