"""The putter: the player who strikes the putt, as a pace and two error sizes.

A putter aims to finish ``pace_m`` past the hole (default 0.43 m, 17 in: the rule of thumb for a
makeable putt, Pelz, Putting Bible (2000), as quoted in the strokes-gained reference) and misses
the start line it chose by a normal error of ``line_sd_deg`` and its speed by a relative normal
error of ``speed_sd_pct``, independently per putt.

Presets (``PUTTERS``):

- "tour": CALIBRATED to the PGA Tour's make rates and average putts (docs/putting.md) on
  Tour-like greens (``mcrun.putting.greens.tour_greens``): start line 1.5 deg, speed 4.7 %. The
  start line's error agrees with the one of A. Gelman and D. Nolan's geometric model fitted to
  professionals' make rates ("A probability model for golf putting", Teaching Statistics 24, 93
  (2002): 1.5 deg).
- "scratch", "15-handicap": ESTIMATES scaled from the Tour's. Broadie (Every Shot Counts, 2014;
  the strokes-gained reference): amateurs of 0-9 handicap make half their putts from about 6 ft
  where the Tour does from 8 ft. A make rate of short putts is set by the start line's error
  against the hole's angular width, which falls as 1/distance: so the 50 % distance scales as
  1/line_sd, and a scratch player's line error is the Tour's times 8/6. The 15-handicap's is the
  Tour's times 8/4.5 (50 % from about 4.5 ft: an extrapolation, no published figure). Their
  speed errors are scaled by the same factors (the one published comparison is of make rates;
  this is an estimate).
"""

from dataclasses import dataclass

import numpy as np

from mcrun.putting.holeout import MAX_PUTTS

__all__ = ["DEFAULT_PACE_M", "PUTTERS", "Putter", "putter_errors"]

DEFAULT_PACE_M = 0.43  # 17 in past the hole


@dataclass(frozen=True)
class Putter:
    """Pace (m past the hole) and the standard deviations of start line (deg) and speed (%)."""

    name: str
    line_sd_deg: float
    speed_sd_pct: float
    pace_m: float = DEFAULT_PACE_M


# CALIBRATED (docs/putting.md): tests/test_putting.py checks the table.
TOUR_LINE_SD_DEG = 1.5
TOUR_SPEED_SD_PCT = 4.7
SCRATCH_FACTOR = 8.0 / 6.0
HIGH_HANDICAP_FACTOR = 8.0 / 4.5

PUTTERS = {
    "tour": Putter("tour", TOUR_LINE_SD_DEG, TOUR_SPEED_SD_PCT),
    "scratch": Putter(
        "scratch", TOUR_LINE_SD_DEG * SCRATCH_FACTOR, TOUR_SPEED_SD_PCT * SCRATCH_FACTOR
    ),
    "15-handicap": Putter(
        "15-handicap",
        TOUR_LINE_SD_DEG * HIGH_HANDICAP_FACTOR,
        TOUR_SPEED_SD_PCT * HIGH_HANDICAP_FACTOR,
    ),
}


def putter_errors(n, seed):
    """Standard normal errors (n, MAX_PUTTS, 2) of start line and speed for n holings-out, from
    ``numpy.random.SeedSequence(seed)``: the same seed, the same errors (common random numbers
    for every aim and pace a read tries)."""
    rng = np.random.Generator(np.random.PCG64(np.random.SeedSequence(seed)))
    return rng.standard_normal((n, MAX_PUTTS, 2))
