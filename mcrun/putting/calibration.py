"""The Tour putter's calibration: make rates and average putts on Tour-like greens against the
PGA Tour's (Broadie; the strokes-gained reference, "Putting", and the green row of its table).

``calibration_table`` holes out n putts from each distance, each on its own Tour-like green
(``mcrun.putting.greens.tour_greens``), with the putter's own read, and returns the simulated
make rate and average putts beside the Tour's, with their standard errors.
"""

import numpy as np

from mcrun.putting.greens import TOUR_GREENS_SEED, tour_greens
from mcrun.putting.holeout import hole_out_batch
from mcrun.putting.putter import putter_errors
from mcrun.strokes.baseline import FOOT_M

__all__ = ["TOUR_AVERAGE_PUTTS", "TOUR_MAKE_PCT", "calibration_table"]

# PGA Tour make rate (%) and average putts to hole out, by distance (ft).
TOUR_MAKE_PCT = {3: 96.0, 5: 77.0, 10: 40.0, 20: 15.0}
TOUR_AVERAGE_PUTTS = {5: 1.23, 10: 1.61, 20: 1.87, 30: 1.98, 40: 2.06}
# The tolerances the Tour putter is held to.
MAKE_TOLERANCE_PCT = 3.0
PUTTS_TOLERANCE = 0.03
ERRORS_SEED = 7


def calibration_table(putter, n, seed=ERRORS_SEED, greens_seed=TOUR_GREENS_SEED):
    """Rows (distance_ft, make_pct, make_se_pct, tour_make_pct, putts, putts_se, tour_putts)
    for every distance of the Tour's two lists (None where the Tour's list has no value)."""
    greens = tour_greens(n, greens_seed)
    z = putter_errors(n, seed)
    rows = []
    for ft in sorted(set(TOUR_MAKE_PCT) | set(TOUR_AVERAGE_PUTTS)):
        putts, _ = hole_out_batch(ft * FOOT_M, greens, putter, z)
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
