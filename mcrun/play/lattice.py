"""The states of a hole: the places a ball can be played from, on two square grids (fine near
the green, coarse elsewhere), with their lie, and the value of any point from the states'.

States are the nodes in play (not the green, a penalty area or out of bounds) of a grid of
``coarse_m`` over the hole's map, and of a grid of ``fine_m`` within ``fine_within_m`` of the
pin, where the short game is decided; the tee is a state of its own (index 0). A ball at rest
at a point off the green is worth the value of the states around it that share its lie
(bilinear over the four nodes of the finest grid that reaches it, weights renormalised over
those of the same lie); where none does, the nearest state of its lie within two cells, else
the baseline's strokes for that lie and distance (a point the lattice does not resolve).
"""

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from mcrun.hole.zones import LIE_OF_ZONE, ZONE_KINDS
from mcrun.strokes.baseline import LIES

__all__ = ["DEFAULT_COARSE_M", "DEFAULT_FINE_M", "DEFAULT_FINE_WITHIN_M", "Lattice", "lattice"]

DEFAULT_COARSE_M = 8.0
DEFAULT_FINE_M = 3.0
DEFAULT_FINE_WITHIN_M = 36.0
# The lie code (index in LIES) of a ball at rest in each zone (-1: not played as it lies).
LIE_CODE_OF_ZONE = np.array(
    [LIES.index(LIE_OF_ZONE[z]) if z in LIE_OF_ZONE else -1 for z in ZONE_KINDS], dtype=np.int64
)
GREEN_LIE = LIES.index("green")
TEE_LIE = LIES.index("tee")
# Baseline strokes by lie every TABLE_STEP_M up to TABLE_MAX_M (the fallback of a point).
TABLE_STEP_M = 0.5
TABLE_MAX_M = 800.0


@dataclass
class Lattice:
    """The states: ``xy`` (S, 2) m in the hole's frame, ``lie`` (S,) codes of ``LIES``, and the
    grids that index them (``grids``: (x0_m, y0_m, cell_m, index (ny, nx) of state or -1) fine
    first; a point uses the first grid whose ``reach_m`` from the pin holds it)."""

    xy: np.ndarray
    lie: np.ndarray
    grids: list
    reach_m: tuple
    pin_xy: tuple
    table: np.ndarray  # (len(LIES), k) baseline strokes by lie and distance

    @property
    def size(self):
        return len(self.xy)


def _grid(hole, cell_m, keep):
    t = hole.terrain()
    x_lo, x_hi = t.x0_m, t.x0_m + (t.zone.shape[1] - 1) * t.cell_m
    y_lo, y_hi = t.y0_m, t.y0_m + (t.zone.shape[0] - 1) * t.cell_m
    x0 = math.ceil(x_lo / cell_m) * cell_m
    y0 = math.ceil(y_lo / cell_m) * cell_m
    xs = np.arange(x0, x_hi + 1e-9, cell_m)
    ys = np.arange(y0, y_hi + 1e-9, cell_m)
    X, Y = np.meshgrid(xs, ys)
    zone = hole.zone_at(X, Y)
    lie = np.where(zone >= 0, LIE_CODE_OF_ZONE[np.maximum(zone, 0)], -1)
    ok = (lie >= 0) & (lie != GREEN_LIE) & keep(X, Y)
    return float(x0), float(y0), X, Y, lie, ok


def lattice(hole, baseline, coarse_m=DEFAULT_COARSE_M, fine_m=DEFAULT_FINE_M,
            fine_within_m=DEFAULT_FINE_WITHIN_M):  # fmt: skip
    """The Lattice of ``hole``; ``baseline``: the strokes of a point it does not resolve."""
    px, py = hole.pin_xy
    xy, lies, grids = [np.zeros((1, 2))], [np.array([TEE_LIE])], []
    count = 1
    for cell, reach in ((fine_m, fine_within_m), (coarse_m, math.inf)):

        def keep(X, Y, reach=reach, first=not grids):
            d = np.hypot(X - px, Y - py)
            # The coarse grid leaves out the fine grid's disc but for its outer ring of cells,
            # so that a point near the edge of the fine grid finds coarse neighbours too.
            return d <= reach if first else d > fine_within_m - 2.5 * coarse_m

        x0, y0, X, Y, lie, ok = _grid(hole, cell, keep)
        index = np.full(X.shape, -1, dtype=np.int64)
        index[ok] = count + np.arange(int(ok.sum()))
        count += int(ok.sum())
        xy.append(np.column_stack([X[ok], Y[ok]]))
        lies.append(lie[ok])
        grids.append((x0, y0, float(cell), index))
    d = np.arange(0.0, TABLE_MAX_M + TABLE_STEP_M / 2, TABLE_STEP_M)
    table = np.array([baseline.expected(lie, d) for lie in LIES])
    return Lattice(np.concatenate(xy), np.concatenate(lies).astype(np.int64), grids,
                   (fine_within_m - 1.5 * fine_m, math.inf), (float(px), float(py)),
                   np.ascontiguousarray(table))  # fmt: skip


@njit(cache=True, inline="always")
def _beyond(dx, dy, d2, reach):
    """hypot(dx, dy) > reach, decided on d2 = dx^2 + dy^2 where that is clear by far more than
    the rounding of either (a few ulp), and by hypot only where it is not: the same answer at
    a fraction of hypot's cost."""
    r2 = reach * reach
    if d2 < r2 * (1.0 - 1e-9):
        return False
    if d2 > r2 * (1.0 + 1e-9):
        return True
    return math.hypot(dx, dy) > reach


@njit(cache=True, inline="always")
def value_at(x, y, lie, values, g_x0, g_y0, g_cell, g_index, g_lie, reach, px, py, table):
    """The value of a ball at rest at (x, y) in ``lie`` (a code of LIES, not the green), from
    the states' ``values``: the grids ``g_*`` (stacked: g_index[k] the k-th grid's index of
    states, g_lie[k] their lies, both padded with -1), the first whose ``reach[k]`` from the pin
    holds the point. Inlined where it is called (a solve's sweeps call it for every shot: twice
    as fast as a call), and written for their speed: the grid chosen without a square root
    where it is clear (``_beyond``), and the cell's four nodes weighed without branches, a
    node off the grid or of another lie (or none) by 0.0, which adds nothing to the sums: the
    same value, bit for bit, as weighing only the nodes of the ball's lie."""
    dx, dy = x - px, y - py
    d2 = dx * dx + dy * dy
    k = 0
    while k < reach.shape[0] - 1 and _beyond(dx, dy, d2, reach[k]):
        k += 1
    cell = g_cell[k]
    fx = (x - g_x0[k]) / cell
    fy = (y - g_y0[k]) / cell
    ix = int(math.floor(fx))
    iy = int(math.floor(fy))
    tx, ty = fx - ix, fy - iy
    ny, nx = g_index.shape[1], g_index.shape[2]
    total, acc = 0.0, 0.0
    for oy in range(2):
        jy = min(max(iy + oy, 0), ny - 1)
        wy = ty if oy else 1.0 - ty
        for ox in range(2):
            jx = min(max(ix + ox, 0), nx - 1)
            # A node off the grid, of another lie or without a state (which reads the tee's
            # value, always finite) weighs 0.0: it adds nothing to the sums.
            here = (jx == ix + ox) and (jy == iy + oy) and g_lie[k, jy, jx] == lie
            w = (tx if ox else 1.0 - tx) * wy * (1.0 if here else 0.0)
            total += w
            acc += w * values[max(g_index[k, jy, jx], 0)]
    if total > 1e-12:
        return acc / total
    # The nearest state of its lie within two cells.
    best, found = 1e300, -1
    for jy in range(iy - 1, iy + 3):
        for jx in range(ix - 1, ix + 3):
            if jx < 0 or jy < 0 or jx >= nx or jy >= ny or g_lie[k, jy, jx] != lie:
                continue
            r = (jx - fx) ** 2 + (jy - fy) ** 2
            if r < best:
                best, found = r, g_index[k, jy, jx]
    if found >= 0:
        return values[found]
    f = min(math.hypot(dx, dy) / TABLE_STEP_M, table.shape[1] - 1.000001)
    j = int(f)
    return table[lie, j] + (f - j) * (table[lie, j + 1] - table[lie, j])


def stacked(lat):
    """The grids of ``lat`` as the arrays ``value_at`` takes: each grid's origin and cell, its
    index of states and their lies (-1 where none), padded to one shape, and the reaches."""
    ny = max(g[3].shape[0] for g in lat.grids)
    nx = max(g[3].shape[1] for g in lat.grids)
    index = np.full((len(lat.grids), ny, nx), -1, dtype=np.int64)
    for k, g in enumerate(lat.grids):
        index[k, : g[3].shape[0], : g[3].shape[1]] = g[3]
    lie = np.where(index >= 0, lat.lie[np.maximum(index, 0)], -1).astype(np.int8)
    x0, y0, cell = (np.array([g[k] for g in lat.grids]) for k in range(3))
    return x0, y0, cell, index, lie, np.array(lat.reach_m, dtype=float)
