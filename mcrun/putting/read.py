"""The read: the pace and start line of a putt that minimise its expected putts, searched the same
way for a plane green's putt (``mcrun putt``) and for every point of a green's map.

A read is a pace (m past the hole, ``stroke.pace_speed_mps``) and a start line off the centre
line the putter perceives (``stroke.centre_line`` on the green read with each putt's own misread
tilt, ``stroke.tilt``): the putter chooses where to aim relative to the break it sees. A small
search with common random numbers: every candidate is struck with the same n putts' errors, so
that the differences between candidates are the candidates', not the samples'. First the paces
``PACES_M``, each on the perceived centre line; then, at the best pace, start lines
``AIM_STEPS_DEG`` either side of it. What a ball at rest is worth is ``rest.rest_values``.

The perceived centre line of each of the n putts is the quadratic in its misread tilt (tx, ty)
through the centre lines at the tilts (0, 0), (+-h, 0), (0, +-h) and (h, h), h the putter's
read_sd, computed once per pace (``read_lines``): n root searches become six (within 0.1 deg of
the searched line out to 2 h: tests/test_putting.py).

The strategy is that of Broadie's putting simulations: an aim line and a speed chosen for the
least expected putts under the golfer's errors (M. Broadie, "A simulation model of putting",
2007; M. Broadie and D. Shin, "Golf analytics: a random putting model and its applications to
optimal targeting strategy and attribution analysis", 2014).
"""

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from mcrun.putting.cup import HOLE_RADIUS_M
from mcrun.putting.rest import MAP, off_value, rest_values
from mcrun.putting.roll import STATUS_HOLED, STATUS_STOPPED
from mcrun.putting.stroke import centre_line, pace_speed_mps, strike_all, struck_velocity, tilt

__all__ = [
    "AIM_STEPS_DEG",
    "PACES_M",
    "READ_NODES",
    "Read",
    "read_lines",
    "score",
    "search",
    "value_read",
]

PACES_M = (0.15, 0.3, 0.43, 0.6, 0.8, 1.0)
AIM_STEPS_DEG = (-1.0, -0.5, -0.25, 0.25, 0.5, 1.0)
# The tilts of ``read_lines``, in units of the putter's read_sd: the first is the read without
# error.
READ_NODES = ((0.0, 0.0), (1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0), (1.0, 1.0))


@dataclass(frozen=True)
class Read:
    """The chosen start line (deg from the line to the hole, + left), pace (m past the hole),
    their mean putts, and every candidate tried: ((aim_deg, pace_m, mean_putts), ...). The start
    line is the perceived centre line's of the putter's read without error plus ``offset_deg``
    (+ left)."""

    aim_deg: float
    pace_m: float
    mean_putts: float
    tried: tuple
    offset_deg: float = 0.0


@njit(cache=True)
def read_lines(x, y, hx, hy, pace_m, green, stroke):
    """The perceived centre lines (rad) at the tilts ``READ_NODES`` for ``pace_m``: lines[0] is
    the read without error."""
    lines = np.zeros(len(READ_NODES))
    h = stroke.read_sd
    for j, (a, b) in enumerate(READ_NODES):
        if j > 0 and h == 0.0:
            lines[j] = lines[0]
            continue
        speed = pace_speed_mps(x, y, hx, hy, pace_m, stroke.pace_slope_share, green, a * h,
                               b * h)  # fmt: skip
        lines[j] = centre_line(x, y, hx, hy, speed, green, a * h, b * h)
    return lines


@njit(cache=True, inline="always")
def line_at(lines, h, tx, ty):
    """The quadratic through ``lines`` (at ``READ_NODES`` times h) at the tilt (tx, ty)."""
    if h == 0.0:
        return lines[0]
    u, w = tx / h, ty / h
    bu, cu = 0.5 * (lines[1] - lines[2]), 0.5 * (lines[1] + lines[2]) - lines[0]
    bw, cw = 0.5 * (lines[3] - lines[4]), 0.5 * (lines[3] + lines[4]) - lines[0]
    cuw = lines[5] - lines[0] - bu - cu - bw - cw
    return lines[0] + (bu + cu * u + cuw * w) * u + (bw + cw * w) * w


@njit(cache=True)
def score(x, y, hx, hy, pace_m, offset, lines, green, stroke, z, keys, rest, putts):
    """(mean, standard error, one-putt share, share of three or more) of the putts from (x, y)
    read at ``pace_m`` on the perceived centre line (``read_lines``) + ``offset`` (rad), each
    putt with its errors z[i, 0] and keys[i, 0]; each sample's putts into ``putts``."""
    n = z.shape[0]
    # Every putt's strike, then their rolls at once (``stroke.strike_all``: each as
    # ``stroke.strike`` rolls it; on every thread but in a map's solver, whose values at rest
    # are the map's), then their values in order.
    start_x, start_y = np.full(n, x), np.full(n, y)
    vx, vy = np.empty(n), np.empty(n)
    drift_keys = np.empty(n, dtype=keys.dtype)
    for i in range(n):
        tx, ty = tilt(stroke, z[i, 0])
        speed = pace_speed_mps(x, y, hx, hy, pace_m, stroke.pace_slope_share, green, tx, ty)
        aim = line_at(lines, stroke.read_sd, tx, ty) + offset
        vx[i], vy[i] = struck_velocity(x, y, hx, hy, aim, speed, stroke, z[i, 0, 0], z[i, 0, 1])
        drift_keys[i] = keys[i, 0]
    status = np.empty(n, dtype=np.int64)
    end_x, end_y = np.empty(n), np.empty(n)
    strike_all(start_x, start_y, vx, vy, drift_keys, hx, hy, green, status, end_x, end_y,
               rest.kind != MAP)  # fmt: skip
    later, p1_later = np.zeros(n), np.zeros(n)
    rest_values(end_x, end_y, status, hx, hy, green, stroke, rest, later, p1_later)
    total, total2, ones, threes = 0.0, 0.0, 0.0, 0.0
    for i in range(n):
        if status[i] == STATUS_HOLED:
            value, p1_next, holed = 1.0, 1.0, True
        elif status[i] == STATUS_STOPPED:
            p1_next = p1_later[i]
            holed = later[i] == 0.0
            value = 1.0 + later[i]
        else:  # off the green (or never at rest)
            value = 1.0 + off_value(end_x[i], end_y[i], hx, hy, rest)
            p1_next, holed = 0.0, False
        putts[i] = value
        total += value
        total2 += value * value
        if holed:
            ones += 1.0
        else:
            threes += 1.0 - p1_next
    mean = total / n
    var = max(total2 / n - mean * mean, 0.0) * n / max(n - 1, 1)
    return mean, math.sqrt(var / n), ones / n, threes / n


@njit(cache=True, nogil=True)  # ``mcrun putt`` waits for it interruptibly
def search(x, y, hx, hy, green, stroke, z, keys, rest, paces, aim_steps, tried, putts,
           best_lines):  # fmt: skip
    """The read of a putt from (x, y): the paces, each on its perceived centre line, then the
    start lines ``aim_steps`` (rad) off it at the best pace. Writes each candidate's (offset rad,
    pace, mean) into ``tried`` (len(paces) + len(aim_steps), 3), the best's samples into
    ``putts`` and its ``read_lines`` into ``best_lines``; returns (offset, pace, mean, se, p1,
    p3) of the best."""
    if math.hypot(hx - x, hy - y) <= HOLE_RADIUS_M:
        putts[:] = 0.0
        best_lines[:] = 0.0
        return 0.0, 0.0, 0.0, 0.0, 1.0, 0.0
    samples = np.empty(z.shape[0])
    best = (0.0, 0.0, 1e30, 0.0, 0.0, 0.0)
    row = 0
    for pace in paces:
        lines = read_lines(x, y, hx, hy, pace, green, stroke)
        m, se, p1, p3 = score(x, y, hx, hy, pace, 0.0, lines, green, stroke, z, keys, rest,
                              samples)  # fmt: skip
        tried[row, 0], tried[row, 1], tried[row, 2] = 0.0, pace, m
        row += 1
        if m < best[2]:
            best = (0.0, pace, m, se, p1, p3)
            best_lines[:] = lines
            putts[:] = samples
    pace = best[1]
    for step in aim_steps:
        m, se, p1, p3 = score(x, y, hx, hy, pace, step, best_lines, green, stroke, z, keys,
                              rest, samples)  # fmt: skip
        tried[row, 0], tried[row, 1], tried[row, 2] = step, pace, m
        row += 1
        if m < best[2]:
            best = (step, pace, m, se, p1, p3)
            putts[:] = samples
    return best


@njit(cache=True, nogil=True)  # ``mcrun putt`` waits for it interruptibly
def value_read(x, y, hx, hy, pace, offset, lines, green, stroke, z, keys, rest, putts):
    """(mean, se, p1, p3) of the read (``pace``, ``offset``; its ``read_lines``) from (x, y),
    as ``search`` values its candidates."""
    if math.hypot(hx - x, hy - y) <= HOLE_RADIUS_M:
        putts[:] = 0.0
        return 0.0, 0.0, 1.0, 0.0
    return score(x, y, hx, hy, pace, offset, lines, green, stroke, z, keys, rest, putts)
