"""Holing out on plane greens: n putts of one length, each on its own plane green (the arrays of
``greens.tour_greens``), putted with the putter's own read
(``stroke.hole_out_from``) until the ball drops. The Tour putter's calibration and its slope
checks (``calibration``) are made of these.
"""

import numpy as np
from numba import njit, prange

from mcrun.putting.roll import DT_S
from mcrun.putting.stroke import MAX_PUTTS, hole_out_from, plane_putt_green, stroke_of

__all__ = ["MAX_PUTTS", "HoleOut", "hole_out_batch"]


@njit(cache=True, parallel=True)
def _hole_out(distance_m, slope_tan, fall_x, fall_y, rho_g, drift_sd, stroke, z, keys, putts,
              first):  # fmt: skip
    """Hole out n putts of ``distance_m``, putt i on the plane of slope_tan[i] falling towards
    (fall_x[i], fall_y[i]) in the putt's frame (x towards the hole), rolling resistance
    rho_g[i]; the putts each took into ``putts`` and its first putt's (status, x, y) into
    ``first``."""
    for i in prange(slope_tan.shape[0]):
        green = plane_putt_green(slope_tan[i], fall_x[i], fall_y[i], rho_g[i], drift_sd, DT_S)
        p, status, x, y = hole_out_from(0.0, 0.0, distance_m, 0.0, green, stroke, z[i], keys[i],
                                        0)  # fmt: skip
        putts[i] = p
        first[i, 0], first[i, 1], first[i, 2] = status, x, y


class HoleOut:
    """n putts of ``distance_m`` holed out: ``putts`` (int, MAX_PUTTS where not down by then),
    the first putt's roll status ``first_status`` and where it stopped (``first_x_m`` along the
    line to the hole from the ball, ``first_y_m`` to its left)."""

    def __init__(self, distance_m, putts, first):
        self.distance_m = distance_m
        self.putts = putts
        self.first_status = first[:, 0].astype(np.int64)
        self.first_x_m = first[:, 1]
        self.first_y_m = first[:, 2]

    def leave_m(self):
        """How far from the hole each first putt stopped (m)."""
        return np.hypot(self.first_x_m - self.distance_m, self.first_y_m)

    def short(self):
        """Whether each first putt stopped short of the hole (not past its front edge's
        perpendicular), not holed."""
        return (self.putts != 1) & (self.first_x_m < self.distance_m)


def hole_out_batch(distance_m, greens, putter, errors, drift_sd):
    """The ``HoleOut`` of ``putter`` (a ``putter.Putter``) from ``distance_m`` on ``greens``
    (slope_tan, fall_x, fall_y, rho_g arrays of n), with ``errors`` (z, keys) of
    ``putter.putter_errors`` and the greens' drift ``drift_sd`` (rad per sqrt(m))."""
    slope_tan, fall_x, fall_y, rho_g = (np.ascontiguousarray(a, dtype=float) for a in greens)
    z, keys = errors
    n = slope_tan.shape[0]
    putts = np.zeros(n, dtype=np.int64)
    first = np.zeros((n, 3))
    _hole_out(float(distance_m), slope_tan, fall_x, fall_y, rho_g, float(drift_sd),
              stroke_of(putter), np.ascontiguousarray(z, dtype=float),
              np.ascontiguousarray(keys, dtype=np.uint64), putts, first)  # fmt: skip
    return HoleOut(float(distance_m), putts, first)
