"""What a ball at rest on the green is worth, as the read's search asks (``read.score``): the
expected putts still to come and the chance that the next one drops.

Two kinds of answer, one table (``RestValues``), told apart by ``kind``:

- ``HOLE_OUT``: holed out from there with the putter's own read (``stroke.hole_out_from``), the
  later putts of each sample with its own errors: a plane green's putt (``mcrun putt``);
- ``MAP``: the expected-putts map's values, interpolated (``green_map``): bilinear in the rings
  around the hole within ``R_NEAR_M`` (a ball within ``TAP_IN_M`` is holed with the next putt),
  among the grid's nodes on the green beyond. A ball off the green is a chip: the baseline's
  fairway strokes from its distance (``chip``).
"""

import math
from typing import NamedTuple

import numpy as np
from numba import njit, prange

from mcrun.putting.cup import HOLE_RADIUS_M
from mcrun.putting.roll import STATUS_STOPPED, Surface
from mcrun.putting.stroke import MAX_PUTTS, PuttGreen, hole_out_from

__all__ = ["HOLE_OUT", "MAP", "RestValues", "hole_out_values", "rest_values"]

HOLE_OUT = 0
MAP = 1
R_NEAR_M = 1.5
TAP_IN_M = 0.1
POLAR_DR_M = 0.1
POLAR_RADII_M = tuple(round(TAP_IN_M + POLAR_DR_M * k, 10) for k in range(16))  # to 1.6 m
POLAR_ANGLES = 24
CHIP_STEP_M = 0.05
CHIP_MAX_M = 200.0


class RestValues(NamedTuple):
    """The value of a ball at rest: ``kind`` HOLE_OUT (the later putts' errors ``z`` (n,
    MAX_PUTTS, 4) and drift keys (n, MAX_PUTTS)) or MAP (the rings' values and one-putt shares
    (len(POLAR_RADII_M), POLAR_ANGLES), the grid (x0_m, y0_m, cell_m) with its values, one-putt
    shares and nodes on the green, the chip table); the other kind's arrays empty."""

    kind: int
    z: np.ndarray
    keys: np.ndarray
    polar_v: np.ndarray
    polar_p1: np.ndarray
    grid: tuple
    grid_v: np.ndarray
    grid_p1: np.ndarray
    grid_valid: np.ndarray
    chip: np.ndarray


_NONE2 = np.zeros((0, 0))


def hole_out_values(z, keys):
    """The RestValues of holing out with the errors ``z`` and drift ``keys``."""
    return RestValues(HOLE_OUT, np.ascontiguousarray(z, dtype=float),
                      np.ascontiguousarray(keys, dtype=np.uint64), _NONE2, _NONE2,
                      (0.0, 0.0, 1.0), _NONE2, _NONE2, np.zeros((0, 0), dtype=np.uint8),
                      np.zeros(2))  # fmt: skip


def map_values(polar_v, polar_p1, grid, grid_v, grid_p1, grid_valid, chip):
    """The RestValues of a map's values."""
    return RestValues(MAP, np.zeros((0, MAX_PUTTS, 4)), np.zeros((0, MAX_PUTTS), dtype=np.uint64),
                      polar_v, polar_p1, tuple(float(g) for g in grid), grid_v, grid_p1,
                      grid_valid, chip)  # fmt: skip


@njit(cache=True, inline="always")
def bilinear(values, valid, fx, fy):
    """Bilinear interpolation of ``values`` at fractional node (fx, fy), among the ``valid``
    nodes (weights renormalised); (value, total weight)."""
    ny, nx = values.shape
    ix = int(math.floor(fx))
    iy = int(math.floor(fy))
    tx, ty = fx - ix, fy - iy
    total, acc = 0.0, 0.0
    for dy in range(2):
        for dx in range(2):
            jx, jy = ix + dx, iy + dy
            if jx < 0 or jy < 0 or jx >= nx or jy >= ny or valid[jy, jx] == 0:
                continue
            w = (tx if dx else 1.0 - tx) * (ty if dy else 1.0 - ty)
            total += w
            acc += w * values[jy, jx]
    return acc, total


@njit(cache=True, inline="always")
def polar(values, r, dx, dy):
    """Bilinear interpolation in the rings around the hole (radius and angle) at a point
    ``r`` (m) from the hole, (dx, dy) from it."""
    n_rings, n_angles = values.shape
    fr = (r - TAP_IN_M) / POLAR_DR_M
    fa = (math.atan2(dy, dx) / (2.0 * math.pi)) * n_angles
    if fa < 0.0:
        fa += n_angles
    j = min(max(int(fr), 0), n_rings - 2)
    tr = fr - j
    a0 = int(fa) % n_angles
    ta = fa - math.floor(fa)
    a1 = (a0 + 1) % n_angles
    return ((1 - tr) * ((1 - ta) * values[j, a0] + ta * values[j, a1])
            + tr * ((1 - ta) * values[j + 1, a0] + ta * values[j + 1, a1]))  # fmt: skip


@njit(cache=True, inline="always")
def chip_strokes(r, chip):
    """The baseline's fairway strokes from ``r`` (m): linear in the table ``chip``."""
    f = min(r / CHIP_STEP_M, chip.shape[0] - 1.000001)
    k = int(f)
    return chip[k] + (f - k) * (chip[k + 1] - chip[k])


@njit(cache=True)
def map_value(x, y, hx, hy, rest):
    """(expected strokes, one-putt share) from a ball at rest at (x, y), by the map."""
    dx, dy = x - hx, y - hy
    r = math.sqrt(dx * dx + dy * dy)
    if r <= HOLE_RADIUS_M:
        return 0.0, 1.0
    if r < TAP_IN_M:
        return 1.0, 1.0
    if r < R_NEAR_M:
        return polar(rest.polar_v, r, dx, dy), polar(rest.polar_p1, r, dx, dy)
    x0, y0, cell = rest.grid
    fx, fy = (x - x0) / cell, (y - y0) / cell
    v, w = bilinear(rest.grid_v, rest.grid_valid, fx, fy)
    if w > 1e-9:
        p, _ = bilinear(rest.grid_p1, rest.grid_valid, fx, fy)
        return v / w, p / w
    return chip_strokes(r, rest.chip), 0.0


@njit(cache=True)
def rest_values(end_x, end_y, status, hx, hy, green, stroke, rest, later, p1):
    """(expected strokes still to come, one-putt share) of each sample's ball at rest after its
    first putt (status[i] STATUS_STOPPED) at (end_x[i], end_y[i]), into later[i] and p1[i]
    (the others' left as they are): a map's values interpolated, one sample after the other;
    holing out, each sample's later putts with its own errors, on every thread
    (``_hole_outs``)."""
    if rest.kind == MAP:
        for i in range(status.shape[0]):
            if status[i] == STATUS_STOPPED:
                later[i], p1[i] = map_value(end_x[i], end_y[i], hx, hy, rest)
    else:
        s = green.surface
        _hole_outs(end_x, end_y, status, hx, hy, s.height_m, s.on_green, s.x0_m, s.y0_m,
                   s.cell_m, green[1:], stroke, rest.z, rest.keys, later, p1)  # fmt: skip


@njit(cache=True, parallel=True)
def _hole_outs(end_x, end_y, status, hx, hy, height_m, on_green, x0_m, y0_m, cell_m, plane,
               stroke, z, keys, later, p1):  # fmt: skip
    """``rest_values`` holing out: sample i's later putts with its errors z[i] and drift keys
    keys[i], whatever thread takes it (a plane green's putt: thousands of hole-outs; a map's
    solver, on threads of its own, reads its values instead). The green comes in its parts
    (its surface's, then the rest of the ``PuttGreen``, ``plane``), put together in the loop:
    Numba's parallel loops take no tuple that holds arrays."""
    for i in prange(status.shape[0]):
        if status[i] == STATUS_STOPPED:
            green = PuttGreen(Surface(height_m, on_green, x0_m, y0_m, cell_m), *plane)
            putts = hole_out_from(end_x[i], end_y[i], hx, hy, green, stroke, z[i], keys[i], 1)[0]
            later[i] = float(putts)
            p1[i] = 1.0 if putts == 1 else 0.0


@njit(cache=True)
def off_value(x, y, hx, hy, rest):
    """The strokes still to come of a ball that left the green (a chip) or never rests (not
    holed: the rest of MAX_PUTTS)."""
    if rest.kind == MAP:
        return chip_strokes(math.hypot(x - hx, y - hy), rest.chip)
    return float(MAX_PUTTS - 1)
