"""Holing out: putt, then putt again from where the ball stopped, until it drops (cap 10).

Every putt is struck by a putter (``mcrun.putting.putter``): it aims at a start line and a pace,
and misses both by its sampled errors. The first putt may be given its own aim and pace (the read
of ``mcrun.putting.read`` tries several); every later one is read as the putter reads any putt:
the start line on which the error-free putt at the putter's pace rolls over the hole's centre
(``line_through_centre``), and the speed that would finish ``pace_m`` past the hole on the
straight line to it (``pace_speed_mps``).
"""

import math

import numpy as np
from numba import njit

from mcrun.physics.constants import G_MPS2
from mcrun.putting.cup import HOLE_RADIUS_M
from mcrun.putting.roll import (
    DT_S,
    MAX_TIME_S,
    NO_SURFACE,
    ROLLING_FACTOR,
    STATUS_HOLED,
    STATUS_STOPPED,
    roll,
    roll_core,
)

__all__ = ["MAX_PUTTS", "centre_line", "hole_out", "line_through_centre", "pace_speed_mps"]

MAX_PUTTS = 10
# The start lines the read looks between (rad, either side of the line to the hole), and how
# close (m) the error-free putt must pass the hole's centre.
READ_SPAN_RAD = 0.6
READ_TOL_M = 0.0005


@njit(cache=True)
def pace_speed_mps(length_m, pace_m, along_fall, slope_tan, rho_g):
    """The start speed that rolls a putt ``pace_m`` past a hole ``length_m`` away on the straight
    line to it, ``along_fall`` the cosine between that line and the fall line: v^2 = 2 a (L + p),
    a = (5/7) g (rho_g cos(beta) - sin(beta) along_fall). Where the line runs downhill steeper
    than the stopping slope (a <= 0), a tenth of the rolling resistance stands in for a."""
    cos_b = 1.0 / math.sqrt(1.0 + slope_tan * slope_tan)
    sin_b = slope_tan * cos_b
    k = ROLLING_FACTOR * G_MPS2
    a = k * (rho_g * cos_b - sin_b * along_fall)
    a = max(a, 0.1 * k * rho_g * cos_b)
    return math.sqrt(2.0 * a * (length_m + pace_m))


@njit(cache=True)
def _miss_m(x, y, hx, hy, angle, speed, slope_tan, fall_x, fall_y, rho_g, ux, uy, surface, dt_s,
            ds_max_m):  # fmt: skip
    """How far left (+) of the hole's centre the error-free putt passes (the cup ignored)."""
    out = roll_core(x, y, speed * math.cos(angle), speed * math.sin(angle), slope_tan, fall_x,
                    fall_y, rho_g, hx, hy, False, dt_s, MAX_TIME_S, surface, ds_max_m)  # fmt: skip
    return (out[5] - hx) * (-uy) + (out[6] - hy) * ux


@njit(cache=True)
def centre_line(x, y, hx, hy, speed, slope_tan, fall_x, fall_y, rho_g, surface, dt_s, ds_max_m):
    """The start line (rad, from the line to the hole, + towards the frame's +y) on which a putt
    from (x, y) at ``speed`` rolls over the hole's centre: regula falsi (Illinois) within
    +-READ_SPAN_RAD, on either ground of ``roll.roll_core`` (a plane: ``NO_SURFACE``)."""
    length = math.hypot(hx - x, hy - y)
    ux, uy = (hx - x) / length, (hy - y) / length
    base = math.atan2(uy, ux)
    a, b = -READ_SPAN_RAD, READ_SPAN_RAD
    fa = _miss_m(x, y, hx, hy, base + a, speed, slope_tan, fall_x, fall_y, rho_g, ux, uy,
                 surface, dt_s, ds_max_m)  # fmt: skip
    fb = _miss_m(x, y, hx, hy, base + b, speed, slope_tan, fall_x, fall_y, rho_g, ux, uy,
                 surface, dt_s, ds_max_m)  # fmt: skip
    if fa * fb > 0.0:  # beyond reach: the side that misses least
        return a if abs(fa) < abs(fb) else b
    side = 0
    c = 0.0
    for _ in range(40):
        c = (a * fb - b * fa) / (fb - fa)
        fc = _miss_m(x, y, hx, hy, base + c, speed, slope_tan, fall_x, fall_y, rho_g, ux, uy,
                     surface, dt_s, ds_max_m)  # fmt: skip
        if abs(fc) < READ_TOL_M:
            return c
        if fc * fb > 0.0:
            b, fb = c, fc
            if side == -1:
                fa /= 2.0
            side = -1
        else:
            a, fa = c, fc
            if side == 1:
                fb /= 2.0
            side = 1
    return c


@njit(cache=True)
def line_through_centre(x, y, hx, hy, speed, slope_tan, fall_x, fall_y, rho_g):
    """``centre_line`` on a plane green, in the plane's steps (+ left: the putt's frame)."""
    return centre_line(x, y, hx, hy, speed, slope_tan, fall_x, fall_y, rho_g, NO_SURFACE, DT_S,
                       0.0)  # fmt: skip


@njit(cache=True)
def hole_out(distance_m, slope_tan, fall_x, fall_y, rho_g, first_aim_rad, first_pace_m,
             use_first, pace_m, sigma_line_rad, sigma_speed, z, putts, first_status):  # fmt: skip
    """Hole out n putts of ``distance_m`` (each on its own plane: the arrays ``slope_tan``,
    ``fall_x``, ``fall_y`` (the fall line's direction in the putt's frame, x towards the hole),
    ``rho_g``, of length n), writing the putts each took into ``putts`` (MAX_PUTTS where it was
    not holed by then) and the roll status of the first putt into ``first_status``.

    The first putt is struck on the start line ``first_aim_rad`` (from the line to the hole,
    + left) at the speed of ``first_pace_m`` when ``use_first``, else read as the later ones
    (pace ``pace_m``). ``z`` (n, MAX_PUTTS, 2): standard normal errors of each putt's start line
    (times ``sigma_line_rad``) and speed (times ``sigma_speed``, relative)."""
    n = slope_tan.shape[0]
    hx, hy = distance_m, 0.0
    for i in range(n):
        x, y = 0.0, 0.0
        putts[i] = MAX_PUTTS
        for k in range(MAX_PUTTS):
            length = math.hypot(hx - x, hy - y)
            ux, uy = (hx - x) / length, (hy - y) / length
            along = ux * fall_x[i] + uy * fall_y[i]
            if k == 0 and use_first:
                pace = first_pace_m
            else:
                pace = pace_m
            speed = pace_speed_mps(length, pace, along, slope_tan[i], rho_g[i])
            if k == 0 and use_first:
                aim = first_aim_rad
            else:
                aim = line_through_centre(x, y, hx, hy, speed, slope_tan[i], fall_x[i],
                                          fall_y[i], rho_g[i])  # fmt: skip
            angle = math.atan2(uy, ux) + aim + sigma_line_rad * z[i, k, 0]
            v = max(0.0, speed * (1.0 + sigma_speed * z[i, k, 1]))
            out = roll(x, y, v * math.cos(angle), v * math.sin(angle), slope_tan[i], fall_x[i],
                       fall_y[i], rho_g[i], hx, hy, True, DT_S, MAX_TIME_S)  # fmt: skip
            if k == 0:
                first_status[i] = out[0]
            if out[0] == STATUS_HOLED:
                putts[i] = k + 1
                break
            if out[0] != STATUS_STOPPED:
                break  # never rests: not holed (MAX_PUTTS)
            x, y = out[1], out[2]
            if math.hypot(hx - x, hy - y) <= HOLE_RADIUS_M:  # stopped over the hole: in
                putts[i] = k + 1
                break


def hole_out_batch(distance_m, greens, putter, z, first=None):
    """``hole_out`` from Python: ``greens`` (slope_tan, fall_x, fall_y, rho_g arrays), a
    ``Putter``, ``z`` errors; ``first`` (aim_rad, pace_m) or None. Returns (putts, first_status),
    int arrays of length n."""
    slope_tan, fall_x, fall_y, rho_g = (np.ascontiguousarray(a, dtype=float) for a in greens)
    n = slope_tan.shape[0]
    putts = np.zeros(n, dtype=np.int64)
    status = np.zeros(n, dtype=np.int64)
    aim, pace = (0.0, putter.pace_m) if first is None else first
    hole_out(float(distance_m), slope_tan, fall_x, fall_y, rho_g, float(aim), float(pace),
             first is not None, float(putter.pace_m), math.radians(putter.line_sd_deg),
             putter.speed_sd_pct / 100.0, np.ascontiguousarray(z, dtype=float), putts,
             status)  # fmt: skip
    return putts, status
