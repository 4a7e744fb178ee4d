"""A hole's ground on a regular grid (``Terrain``), built from its arrays (``make_terrain``),
with each cell's calm reach (``calm_cells``), what a zone is for the Rules, and the view of it
a kernel borrows (``TerrainView``, ``borrowed``)."""

from typing import NamedTuple

import numpy as np
from numba import njit, types
from numba.core import errors
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
    turf = np.ascontiguousarray(turf, dtype=np.float64)
    penalty = np.ascontiguousarray(penalty, np.int8)
    # Compiled code reads a zone's turf and penalty kind without bounds checks: every zone of
    # the grid must have both.
    if turf.ndim != 2 or turf.shape[1] != TURF_FIELDS or penalty.shape != (turf.shape[0],):
        raise ValueError(
            f"a terrain needs a turf ({TURF_FIELDS} fields) and a penalty kind for each zone, "
            f"got turf {turf.shape} and penalty {penalty.shape}"
        )
    if zone.min() < 0 or zone.max() >= turf.shape[0]:
        raise ValueError(
            f"a terrain's zones must be 0 to {turf.shape[0] - 1} (one for each turf), got "
            f"{zone.min()} to {zone.max()}"
        )
    return Terrain(
        float(x0_m), float(y0_m), float(cell_m), height_m, zone, turf, penalty,
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


# Fields of a zone's turf in ``Terrain.turf`` and in a view's flat ``turf``.
TURF_FIELDS = len(Turf._fields)


class TerrainView(NamedTuple):
    """A Terrain as a kernel reads it (``borrowed``): its numbers, its nodes along x and y, and
    its arrays flat, row by row: node [iy, ix] of ``height_m`` and ``zone`` at iy * nx + ix,
    cell [iy, ix] of ``calm`` at iy * (nx - 1) + ix, zone z's turf field j at
    z * TURF_FIELDS + j. Compiled, each is a pointer to the Terrain's own memory, which Numba
    neither counts references to nor passes as the several fields of an array; as Python, the
    array's flat view."""

    x0_m: float
    y0_m: float
    cell_m: float
    nx: int  # nodes along x (the grid's columns)
    ny: int  # nodes along y (its rows)
    height_m: object
    zone: object
    turf: object
    penalty: object
    calm: object


def is_view(terrain):
    """Whether ``terrain`` (a value, or its Numba type) is a kernel's TerrainView."""
    return getattr(terrain, "instance_class", type(terrain)) is TerrainView


def borrowed(terrain):
    """The kernel's view of a Terrain (``TerrainView``; None stays None, a view stays itself).
    Compiled, its arrays are pointers to the Terrain's memory: a call that passes it passes ten
    numbers, where a Terrain is 46 (each array its data pointer, shape, strides and four more)
    and a call of Numba's reference count for each array, in and out. A batch's task borrows
    its Terrain once (``engine.batch``), and the ground's questions answer on the view. The
    caller must keep the Terrain alive while its view is in use, and nothing may keep the view
    beyond that (a kernel call's arguments live as long as the call). As Python, the arrays'
    flat views."""
    if terrain is None or is_view(terrain):
        return terrain
    ny, nx = terrain.height_m.shape
    return TerrainView(
        terrain.x0_m, terrain.y0_m, terrain.cell_m, nx, ny, terrain.height_m.ravel(),
        terrain.zone.ravel(), terrain.turf.ravel(), terrain.penalty, terrain.calm.ravel(),
    )  # fmt: skip


@overload(borrowed, inline="always")
def _borrowed(terrain):
    if terrain is None or isinstance(terrain, types.NoneType) or is_view(terrain):
        return lambda terrain: terrain
    return lambda terrain: TerrainView(
        terrain.x0_m, terrain.y0_m, terrain.cell_m, terrain.height_m.shape[1],
        terrain.height_m.shape[0], _data(terrain.height_m), _data(terrain.zone),
        _data(terrain.turf), _data(terrain.penalty), _data(terrain.calm),
    )  # fmt: skip


@intrinsic
def _data(typingctx, array):
    """A pointer to the data of a C-contiguous array (its element [i, j] at i * shape[1] + j)."""
    if not isinstance(array, types.Array) or array.layout != "C":
        raise errors.TypingError(f"a Terrain's arrays are C-contiguous, not {array}")

    def codegen(context, builder, signature, args):
        return context.make_array(array)(context, builder, value=args[0]).data

    return types.CPointer(array.dtype)(array), codegen
