"""A hole's ground on a regular grid (``Terrain``), built from its arrays (``make_terrain``),
with each cell's calm reach (``calm_cells``), what a zone is for the Rules, and the kernel's
borrowed view of it (``borrowed``)."""

from typing import NamedTuple

import numpy as np
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic, overload

from mcrun.physics.turf import Turf

# What a zone of a Terrain is for the Rules (``Terrain.penalty``).
IN_PLAY = 0
PENALTY_AREA = 1  # water: the ball is not played from there
OUT_OF_BOUNDS = 2  # played on as any ground (its turf); a ball at rest there is out (Rule 18.2)


class Terrain(NamedTuple):
    """A hole's ground on a regular grid, in the hole's frame: x (m) from the tee towards the
    pin, y (m) to the RIGHT of that line, heights (m) relative to the ground at the tee.

    Node [iy, ix] lies at (x0_m + ix cell_m, y0_m + iy cell_m); the height between nodes is
    bilinear, the zone is that of the nearest node. Its arrays are shared by every thread.
    """

    x0_m: float
    y0_m: float
    cell_m: float
    height_m: np.ndarray  # (ny, nx) float64
    zone: np.ndarray  # (ny, nx) int8: a row of ``turf`` and ``penalty``
    turf: np.ndarray  # (n_zones, len(Turf._fields)) float64: each zone's Turf, in its order
    penalty: np.ndarray  # (n_zones,) int8: IN_PLAY, PENALTY_AREA or OUT_OF_BOUNDS
    calm: np.ndarray  # (ny - 1, nx - 1) uint8: ``calm_cells`` of each cell


# The longest calm reach ``calm_cells`` looks for, in cells.
MAX_CALM_CELLS = 32


def calm_cells(height_m, zone, max_cells=MAX_CALM_CELLS):
    """For each cell of the grid, how many cells around it (in every direction) are the same
    plane and the same zone: (ny - 1, nx - 1) uint8, up to ``max_cells``.

    A cell is "plain" when its four nodes lie in a plane (its bilinear surface is flat, of one
    gradient) and have one zone; a plain cell has calm reach r when every cell within r cells
    of it is plain with the same gradient and zone. A ball within a cell of reach r can go r
    cells in any direction on one plane of one turf, where a step of the roll or a hop is
    exact: the shot loop takes steps that long there (``surface``, ``_grid_hop``) and short
    ones (a quarter of a cell) where the ground bends or the zone changes. The numbers are the
    same either way, to rounding, as on the slope model's plane.
    """
    h = np.asarray(height_m, dtype=float)
    z = np.asarray(zone)
    h00, h10, h01, h11 = h[:-1, :-1], h[:-1, 1:], h[1:, :-1], h[1:, 1:]
    gx = h10 - h00
    gy = h01 - h00
    scale = np.maximum(np.abs(h).max(), 1.0)
    plain = (np.abs(h11 - h10 - h01 + h00) <= 1e-12 * scale) & (
        (z[:-1, :-1] == z[:-1, 1:]) & (z[:-1, :-1] == z[1:, :-1]) & (z[:-1, :-1] == z[1:, 1:])
    )
    key_z = z[:-1, :-1]
    reach = np.zeros(plain.shape, dtype=np.uint8)
    alive = plain.copy()
    for r in range(1, max_cells + 1):
        # Reach r: reach r - 1, and every neighbour has reach r - 1 with the same plane.
        ok = alive.copy()
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                if dx == 0 and dy == 0:
                    continue
                same = np.zeros(plain.shape, dtype=bool)
                ys = slice(max(dy, 0), plain.shape[0] + min(dy, 0))
                xs = slice(max(dx, 0), plain.shape[1] + min(dx, 0))
                yd = slice(max(-dy, 0), plain.shape[0] + min(-dy, 0))
                xd = slice(max(-dx, 0), plain.shape[1] + min(-dx, 0))
                same[yd, xd] = (
                    alive[ys, xs]
                    & (np.abs(gx[ys, xs] - gx[yd, xd]) <= 1e-12 * scale)
                    & (np.abs(gy[ys, xs] - gy[yd, xd]) <= 1e-12 * scale)
                    & (key_z[ys, xs] == key_z[yd, xd])
                )
                ok &= same
        if not ok.any():
            break
        reach[ok] = r
        alive = ok
    return reach


def make_terrain(x0_m, y0_m, cell_m, height_m, zone, turf, penalty):
    """The Terrain of these arrays (see ``Terrain``), with its ``calm_cells``."""
    height_m = np.ascontiguousarray(height_m, dtype=np.float64)
    zone = np.ascontiguousarray(zone, dtype=np.int8)
    if height_m.ndim != 2 or height_m.shape != zone.shape or min(height_m.shape) < 2:
        raise ValueError("a terrain needs heights and zones on one grid of at least 2 x 2 nodes")
    return Terrain(
        float(x0_m), float(y0_m), float(cell_m), height_m, zone,
        np.ascontiguousarray(turf, dtype=np.float64), np.ascontiguousarray(penalty, np.int8),
        calm_cells(height_m, zone),
    )  # fmt: skip


@njit(cache=True, error_model="numpy", inline="always")
def read_turf(a, first, step):
    """The Turf whose fields, in its order, are a[first], a[first + step], ...: a zone's row of
    ``Terrain.turf`` (step 1), or a shot's turf in a row or a column of the shot loop's tables."""
    return Turf(
        a[first], a[first + step], a[first + 2 * step], a[first + 3 * step],
        a[first + 4 * step], a[first + 5 * step], a[first + 6 * step], a[first + 7 * step],
        a[first + 8 * step],
    )  # fmt: skip


assert len(Turf._fields) == 9  # (read_turf's fields)


def borrowed(terrain):
    """The same Terrain (or None), its arrays borrowed: compiled, views of the same memory that
    Numba counts no references to. Each call that passes a Terrain counts a reference to each
    of its five arrays in and out, an atomic operation each: 9 % of a real-ground kernel's
    samples, which a task's borrowed Terrain spares (``engine.batch``). The caller must keep
    the Terrain alive while its borrowed view is in use, and nothing may keep the view beyond
    that (a kernel call's arguments live as long as the call). As Python, ``terrain`` itself."""
    return terrain


@overload(borrowed, inline="always")
def _borrowed(terrain):
    if terrain is None or isinstance(terrain, types.NoneType):
        return lambda terrain: terrain
    return lambda terrain: Terrain(
        terrain.x0_m, terrain.y0_m, terrain.cell_m, _borrowed_array(terrain.height_m),
        _borrowed_array(terrain.zone), _borrowed_array(terrain.turf),
        _borrowed_array(terrain.penalty), _borrowed_array(terrain.calm),
    )  # fmt: skip


@intrinsic
def _borrowed_array(typingctx, array):
    """The array, of the same type, without its meminfo (Numba's reference count, which it
    then skips) or parent (the Python object, which a kernel never returns)."""

    def codegen(context, builder, signature, args):
        owned = context.make_array(array)(context, builder, value=args[0])
        view = context.make_array(array)(context, builder)
        view.meminfo = cgutils.get_null_value(view.meminfo.type)
        view.parent = cgutils.get_null_value(view.parent.type)
        for field in ("nitems", "itemsize", "data", "shape", "strides"):
            setattr(view, field, getattr(owned, field))
        return view._getvalue()

    return array(array), codegen
