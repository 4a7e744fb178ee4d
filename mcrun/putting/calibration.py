"""The Tour putter's calibration: make rates and average putts on Tour-like greens against the
PGA Tour's (Broadie; the strokes-gained reference, "Putting", and the green row of its table),
and the Tour's putts on slopes (the reference's "Putting on slopes").

``calibration_table`` holes out n putts from each distance, each on its own Tour-like green
(``greens.tour_greens``, pure bentgrass drift), with the putter's own read, and returns the
simulated make rate and average putts beside the Tour's, with their standard errors.
``slope_checks`` measures what the Tour's putts show on slopes:

- uphill against downhill at 8 ft (Broadie, golf.com 2019, ShotLink): uphill putts holed about
  2.5-5 points more often. Uphill: the green falls within 45 deg of straight back towards the
  ball; downhill: within 45 deg of straight towards the hole (Tour-like greens otherwise);
- the leave of a 10-footer (Broadie, golf.com 2020): with a 3 % slope at the hole, the median
  distance from the hole of a missed putt 1.1 ft straight uphill, 2.1 ft straight downhill
  (Stimp 11-12 ft); 7 % of Tour players' 10-footers are left short (Tour-like greens).
"""

import math

import numpy as np

from mcrun.hole.hole import PUTTING_N_RANGE
from mcrun.putting.greens import (
    DRIFT_MM_PER_M_BENTGRASS,
    DRIFT_RANGE_MM_PER_M,
    TOUR_GREENS_SEED,
    drift_sd,
    tour_greens,
)
from mcrun.putting.holeout import hole_out_batch
from mcrun.putting.putter import PUTTER_RANGES, Putter, putter_errors
from mcrun.quantities import InputError
from mcrun.strokes.baseline import FOOT_M
from mcrun.units import is_number, shown

__all__ = [
    "SLOPE_TARGETS",
    "TOUR_AVERAGE_PUTTS",
    "TOUR_MAKE_PCT",
    "calibration_table",
    "slope_checks",
    "tour_holeouts",
]

# PGA Tour make rate (%) and average putts to hole out, by distance (ft).
TOUR_MAKE_PCT = {3: 96.0, 5: 77.0, 10: 40.0, 20: 15.0}
TOUR_AVERAGE_PUTTS = {5: 1.23, 10: 1.61, 20: 1.87, 30: 1.98, 40: 2.06}
DISTANCES_FT = tuple(sorted(set(TOUR_MAKE_PCT) | set(TOUR_AVERAGE_PUTTS)))
# The tolerances the Tour putter is held to.
MAKE_TOLERANCE_PCT = 3.0
PUTTS_TOLERANCE = 0.03
# The slope checks: (what, Tour's value, lowest allowed, highest allowed).
SLOPE_TARGETS = {
    "uphill_minus_downhill_make_pct_8ft": ("8 ft: uphill make rate minus downhill (points)",
                                           None, 2.5, 5.0),
    "leave_uphill_ft": ("10 ft, 3 % at the hole, uphill: median leave of a miss (ft)",
                        1.1, 0.8, 1.4),
    "leave_downhill_ft": ("10 ft, 3 % at the hole, downhill: median leave of a miss (ft)",
                          2.1, 1.8, 2.4),
    "short_pct_10ft": ("10 ft: share left short (%)", 7.0, 5.0, 10.0),
}  # fmt: skip
ERRORS_SEED = 7
SECTOR_DEG = 45.0


def check_calibration(putter, n, seed, greens_seed, drift_mm_per_m):
    """InputError (one line) for an argument of the calibration's functions that is not one
    (a putter's name, n under 2 or not whole, a NaN or negative drift: a perfect green's
    numbers, or a traceback)."""
    if not isinstance(putter, Putter):
        raise InputError(f"putter {shown(putter)}: allowed: a Putter (putting.PUTTERS's)")
    lo, hi = PUTTING_N_RANGE
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or not lo <= n <= hi:
        raise InputError(f"n {shown(n, 40)}: allowed: a whole number from {lo} to {hi}")
    for name, value in (("seed", seed), ("greens_seed", greens_seed)):
        if (isinstance(value, bool) or not isinstance(value, int | np.integer)
                or not 0 <= value < 2**63):  # fmt: skip
            raise InputError(f"{name} {shown(value, 40)}: allowed: a whole number from 0 to "
                             "2**63 - 1")  # fmt: skip
    lo, hi = DRIFT_RANGE_MM_PER_M
    if not (is_number(drift_mm_per_m) and lo <= drift_mm_per_m <= hi):
        raise InputError(f"drift_mm_per_m {shown(drift_mm_per_m, 40)}: allowed: {lo:g} to "
                         f"{hi:g} mm/m")  # fmt: skip


def tour_holeouts(putter, n, seed=ERRORS_SEED, greens_seed=TOUR_GREENS_SEED,
                  drift_mm_per_m=DRIFT_MM_PER_M_BENTGRASS):  # fmt: skip
    """{distance_ft: ``holeout.HoleOut``} of n putts from each of ``DISTANCES_FT`` on Tour-like
    greens, with the putter's own read."""
    check_calibration(putter, n, seed, greens_seed, drift_mm_per_m)
    greens = tour_greens(n, greens_seed)
    errors = putter_errors(n, seed)
    drift = drift_sd(drift_mm_per_m)
    return {ft: hole_out_batch(ft * FOOT_M, greens, putter, errors, drift) for ft in DISTANCES_FT}


def calibration_table(putter, n, seed=ERRORS_SEED, greens_seed=TOUR_GREENS_SEED,
                      drift_mm_per_m=DRIFT_MM_PER_M_BENTGRASS, holeouts=None):  # fmt: skip
    """Rows (distance_ft, make_pct, make_se_pct, tour_make_pct, putts, putts_se, tour_putts)
    for every distance of the Tour's two lists (None where the Tour's list has no value), from
    ``holeouts`` (``tour_holeouts``'s, made here where not given)."""
    check_calibration(putter, n, seed, greens_seed, drift_mm_per_m)
    if holeouts is None:
        holeouts = tour_holeouts(putter, n, seed, greens_seed, drift_mm_per_m)
    rows = []
    for ft in DISTANCES_FT:
        putts = holeouts[ft].putts
        made = putts == 1
        rows.append(
            (
                ft,
                100.0 * made.mean(),
                100.0 * made.std(ddof=1) / np.sqrt(n),
                TOUR_MAKE_PCT.get(ft),
                putts.mean(),
                putts.std(ddof=1) / np.sqrt(n),
                TOUR_AVERAGE_PUTTS.get(ft),
            )
        )
    return rows


def slope_checks(putter, n, seed=ERRORS_SEED, greens_seed=TOUR_GREENS_SEED,
                 drift_mm_per_m=DRIFT_MM_PER_M_BENTGRASS, ten_ft=None):  # fmt: skip
    """The measures of ``SLOPE_TARGETS`` for ``putter``, n putts each: {key: value}, with the
    uphill and downhill make rates at 8 ft ("make_uphill_pct_8ft", "make_downhill_pct_8ft") and
    the standard error of their difference ("..._se"). ``ten_ft``: ``tour_holeouts``'s 10 ft,
    where it was made already."""
    check_calibration(putter, n, seed, greens_seed, drift_mm_per_m)
    drift = drift_sd(drift_mm_per_m)
    errors = putter_errors(n, seed)
    out = {}
    made = {}
    for name, centre in (("uphill", 180.0), ("downhill", 0.0)):
        greens = tour_greens(n, greens_seed, (centre - SECTOR_DEG, centre + SECTOR_DEG))
        made[name] = hole_out_batch(8 * FOOT_M, greens, putter, errors, drift).putts == 1
        out[f"make_{name}_pct_8ft"] = 100.0 * made[name].mean()
    out["uphill_minus_downhill_make_pct_8ft"] = (
        out["make_uphill_pct_8ft"] - out["make_downhill_pct_8ft"]
    )
    out["uphill_minus_downhill_make_pct_8ft_se"] = 100.0 * math.sqrt(
        sum(m.mean() * (1 - m.mean()) for m in made.values()) / n
    )
    for name, centre in (("uphill", 180.0), ("downhill", 0.0)):
        greens = tour_greens(n, greens_seed, (centre, centre), (3.0, 3.0))
        result = hole_out_batch(10 * FOOT_M, greens, putter, errors, drift)
        missed = result.putts != 1
        out[f"leave_{name}_ft"] = float(np.median(result.leave_m()[missed])) / FOOT_M
    if ten_ft is None:
        ten_ft = hole_out_batch(10 * FOOT_M, tour_greens(n, greens_seed), putter, errors, drift)
    out["short_pct_10ft"] = 100.0 * ten_ft.short().mean()
    return out


# The refit: its holings-out per target (the calibration's seeds) and its steps.
FIT_N = 12000
FIT_STEPS = {"line_sd_deg": 0.05, "speed_sd_pct": 0.3, "read_sd_pct": 0.03,
             "pace_slope_share": 0.05}  # fmt: skip


def fit_errors(putter, n=FIT_N):
    """Each target's error over its tolerance (1: at its edge) for ``putter``, n putts each on
    the calibration's seeds: {name: (value, normalised error)}."""
    out = {}
    holeouts = tour_holeouts(putter, n)
    for ft, make, _, tour_make, putts, _, tour_putts in calibration_table(
        putter, n, holeouts=holeouts
    ):
        if tour_make is not None:
            out[f"make_pct_{ft}ft"] = (make, (make - tour_make) / MAKE_TOLERANCE_PCT)
        if tour_putts is not None:
            out[f"putts_{ft}ft"] = (putts, (putts - tour_putts) / PUTTS_TOLERANCE)
    checks = slope_checks(putter, n, ten_ft=holeouts[10])
    for key, (_, _, lo, hi) in SLOPE_TARGETS.items():
        centre, half = (lo + hi) / 2.0, (hi - lo) / 2.0
        out[key] = (checks[key], (checks[key] - centre) / half)
    return out


def refit(start, n=FIT_N, rounds=3, report=print):
    """The Tour putter refitted to every target at once, from ``start`` (a ``Putter``): a
    coordinate search, ``rounds`` times over the parameters of ``FIT_STEPS``, each moved a step
    up or down while the sum of the squared normalised errors (``fit_errors``) falls; on the
    calibration's seeded errors and greens, so the same start gives the same fit."""
    import dataclasses

    def loss(p):
        errors = fit_errors(p, n)
        return sum(e * e for _, e in errors.values()), errors

    best, (best_loss, errors) = start, loss(start)
    report(f"start {start}: loss {best_loss:.3f}")
    for _ in range(rounds):
        moved = False
        for name, step in FIT_STEPS.items():
            for sign in (1.0, -1.0):
                while True:
                    value = round(getattr(best, name) + sign * step, 4)
                    lo, hi, _ = PUTTER_RANGES[name]
                    if not lo <= value <= hi:  # (a share above 1, a negative sd: no putter's)
                        break
                    trial = dataclasses.replace(best, **{name: value})
                    trial_loss, trial_errors = loss(trial)
                    if trial_loss >= best_loss:
                        break
                    best, best_loss, errors, moved = trial, trial_loss, trial_errors, True
                    report(f"{name} = {value:g}: loss {best_loss:.3f}")
        if not moved:
            break
    return best, best_loss, errors
