"""The ground under the ball: what the shot loop asks of it, and the two kinds there are.

The shot loop (``engine.batch``) holds no slope or turf of its own: it asks the ground, where
the ball is, for the ball's height above it (``clearance``, ``clearance_rate``: the flight ends
where it goes below; ``flight_check`` with the state under it, at each flight step), its normal
and turf (``normal_at``, ``turf_at``; ``contact`` with the state and the ``calm_reach``, where a
ball comes down for its next impact), where a hop comes down on it (``hop_landing``), what the
roll needs at each step (``surface``: height, normal, turf, state, the longest step), the state
there under the Rules (``state_at``: in play, or a penalty area, out of bounds, off the map) and
where the ball crossed into such a place (``crossing``). The questions a loop asks at every
step are answered in one look-up of the grid each. Two kinds of ground answer:

- a shot's own ``Plane`` (``terrain`` None): the slope model. The flight comes down to z = 0 and
  the landing area is the plane of the shot's slope through the landing point, of one turf,
  built from the shot's input row;
- a hole's ``Terrain`` (``make_terrain``): heights on a grid, bilinear between nodes, and a zone
  per node with its turf and its status.

Each question is a Numba ``overload`` on the type of ``terrain``, so the loop is compiled once
for each kind, and the Plane's loop is the same code, with the same numbers, as before there
were terrains.
"""

import math
from typing import NamedTuple

import numpy as np
from numba import njit, types
from numba.extending import overload

from mcrun.physics.bounce import hop
from mcrun.physics.constants import G_MPS2
from mcrun.physics.turf import Turf
from mcrun.status import IN_PENALTY_AREA, OFF_MAP, OK, OUT_OF_BOUNDS_STATUS

# What a zone of a Terrain is for the Rules (``Terrain.penalty``).
IN_PLAY = 0
PENALTY_AREA = 1  # water: the ball is not played from there
OUT_OF_BOUNDS = 2


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


class Plane(NamedTuple):
    """A plane of one turf: the landing area of one shot."""

    nx: float  # unit normal, core frame
    ny: float
    nz: float
    turf: Turf


@njit(cache=True, error_model="numpy")
def plane(slope, fall_line, turf):
    """The Plane of the given slope (rad) falling towards ``fall_line`` (rad from the target
    line, positive to the RIGHT): its normal tilts towards the fall line, which is
    (cos a, -sin a, 0) in the core's frame."""
    if slope == 0.0:
        return Plane(0.0, 0.0, 1.0, turf)
    sb = math.sin(slope)
    return Plane(sb * math.cos(fall_line), -sb * math.sin(fall_line), math.cos(slope), turf)


# The ground as the shot loop asks it. Each question is one function of (terrain, ...): with
# ``terrain`` None the shot's own Plane (``plane``) answers and the flight comes down to z = 0,
# exactly as the slope model always has; with a Terrain its grid answers. Numba compiles the
# loop once for each (``overload`` picks the answer by the type of ``terrain``), so the plane's
# loop is the same code, and the same numbers, as before there were terrains.


def _flat(terrain):
    return isinstance(terrain, types.NoneType)


@njit(cache=True, error_model="numpy")
def _locate(terrain, x, y):
    """The cell of the grid under core-frame (x, y) (y to the LEFT, the grid's y to the right):
    its lower node (ix, iy), the fractions (tx, ty) across it, and whether (x, y) is on the
    grid at all (off it, the edge cells are extended)."""
    ny, nx = terrain.height_m.shape
    fx = (x - terrain.x0_m) / terrain.cell_m
    fy = (-y - terrain.y0_m) / terrain.cell_m
    inside = (fx >= 0.0) & (fx <= nx - 1.0) & (fy >= 0.0) & (fy <= ny - 1.0)
    ix = min(max(int(math.floor(fx)), 0), nx - 2)
    iy = min(max(int(math.floor(fy)), 0), ny - 2)
    return ix, iy, min(max(fx - ix, 0.0), 1.0), min(max(fy - iy, 0.0), 1.0), inside


@njit(cache=True, error_model="numpy", inline="always")
def _cell_at(terrain, x, y):
    """``_locate`` inlined where a loop asks at every step (a call counts the terrain's arrays
    in and out), with the heights of the cell's four nodes: (ix, iy, tx, ty, inside, h00,
    h10, h01, h11)."""
    ny_, nx_ = terrain.height_m.shape
    fx = (x - terrain.x0_m) / terrain.cell_m
    fy = (-y - terrain.y0_m) / terrain.cell_m
    inside = (fx >= 0.0) & (fx <= nx_ - 1.0) & (fy >= 0.0) & (fy <= ny_ - 1.0)
    ix = min(max(int(math.floor(fx)), 0), nx_ - 2)
    iy = min(max(int(math.floor(fy)), 0), ny_ - 2)
    tx = min(max(fx - ix, 0.0), 1.0)
    ty = min(max(fy - iy, 0.0), 1.0)
    h = terrain.height_m
    return ix, iy, tx, ty, inside, h[iy, ix], h[iy, ix + 1], h[iy + 1, ix], h[iy + 1, ix + 1]


@njit(cache=True, error_model="numpy", inline="always")
def _cell_slope(terrain, tx, ty, h00, h10, h01, h11):
    """(dh/dx, dh/dy) at fractions (tx, ty) of a cell of these node heights, y to the LEFT
    (``_grid_gradient``'s numbers)."""
    hx = ((h10 - h00) * (1.0 - ty) + (h11 - h01) * ty) / terrain.cell_m
    hy = -((h01 - h00) * (1.0 - tx) + (h11 - h10) * tx) / terrain.cell_m
    return hx, hy


@njit(cache=True, error_model="numpy")
def _grid_height(terrain, x, y):
    """Bilinear height (m) of the grid at core-frame (x, y)."""
    ix, iy, tx, ty, _ = _locate(terrain, x, y)
    h = terrain.height_m
    return (h[iy, ix] * (1.0 - tx) + h[iy, ix + 1] * tx) * (1.0 - ty) + (
        h[iy + 1, ix] * (1.0 - tx) + h[iy + 1, ix + 1] * tx
    ) * ty


@njit(cache=True, error_model="numpy")
def _grid_gradient(terrain, x, y):
    """(dh/dx, dh/dy) of the bilinear grid at core-frame (x, y), y to the LEFT."""
    ix, iy, tx, ty, _ = _locate(terrain, x, y)
    h = terrain.height_m
    dx = (h[iy, ix + 1] - h[iy, ix]) * (1.0 - ty) + (h[iy + 1, ix + 1] - h[iy + 1, ix]) * ty
    dy = (h[iy + 1, ix] - h[iy, ix]) * (1.0 - tx) + (h[iy + 1, ix + 1] - h[iy, ix + 1]) * tx
    return dx / terrain.cell_m, -dy / terrain.cell_m


@njit(cache=True, error_model="numpy")
def _grid_zone(terrain, x, y):
    """The zone of the node nearest core-frame (x, y)."""
    ix, iy, tx, ty, _ = _locate(terrain, x, y)
    return terrain.zone[iy + (1 if ty >= 0.5 else 0), ix + (1 if tx >= 0.5 else 0)]


@njit(cache=True, error_model="numpy", inline="always")
def _state_of(inside, kind):
    """The state (``state_at``) of a point on the grid or not (``inside``) in a zone of this
    ``penalty`` kind."""
    if not inside:
        return OFF_MAP
    if kind == PENALTY_AREA:
        return IN_PENALTY_AREA
    return OUT_OF_BOUNDS_STATUS if kind == OUT_OF_BOUNDS else OK


def height_at(terrain, x, y):
    """Height (m) of the ground's surface at (x, y): where the flight ends. On a Plane the flight
    comes down to z = 0 and the plane through the landing point is the landing area."""
    raise NotImplementedError("compiled code only")


@overload(height_at, inline="always")
def _height_at(terrain, x, y):
    if _flat(terrain):
        return lambda terrain, x, y: 0.0
    return lambda terrain, x, y: _grid_height(terrain, x, y)


def clearance(terrain, x, y, z):
    """Height (m) of a ball at (x, y, z) above the ground, and its rate of change at velocity
    (vx, vy, vz): z - h and vz - grad(h).v. On a Plane, z and vz themselves."""
    raise NotImplementedError("compiled code only")


@overload(clearance, inline="always")
def _clearance(terrain, x, y, z):
    if _flat(terrain):
        return lambda terrain, x, y, z: z
    return lambda terrain, x, y, z: z - _grid_height(terrain, x, y)


def clearance_rate(terrain, x, y, vx, vy, vz):
    """d/dt of ``clearance`` for a ball at (x, y) moving at (vx, vy, vz)."""
    raise NotImplementedError("compiled code only")


@overload(clearance_rate, inline="always")
def _clearance_rate(terrain, x, y, vx, vy, vz):
    if _flat(terrain):
        return lambda terrain, x, y, vx, vy, vz: vz

    def rate(terrain, x, y, vx, vy, vz):
        hx, hy = _grid_gradient(terrain, x, y)
        return vz - (hx * vx + hy * vy)

    return rate


def flight_check(terrain, x, y, z):
    """What a flight step asks of the ground where it ends, (x, y, z), in one look-up: the
    ball's height above it (``clearance``) and the state of the ground under it
    (``state_at``)."""
    raise NotImplementedError("compiled code only")


@njit(cache=True, error_model="numpy", inline="always")
def _grid_flight_check(terrain, x, y, z):
    ix, iy, tx, ty, inside, h00, h10, h01, h11 = _cell_at(terrain, x, y)
    height = (h00 * (1.0 - tx) + h10 * tx) * (1.0 - ty) + (h01 * (1.0 - tx) + h11 * tx) * ty
    kind = terrain.penalty[terrain.zone[iy + (1 if ty >= 0.5 else 0), ix + (1 if tx >= 0.5 else 0)]]
    state = _state_of(inside, kind)
    return z - height, state


@overload(flight_check, inline="always")
def _flight_check(terrain, x, y, z):
    if _flat(terrain):
        return lambda terrain, x, y, z: (z, OK)
    return lambda terrain, x, y, z: _grid_flight_check(terrain, x, y, z)


def normal_at(terrain, plane, x, y):
    """Unit normal (nx, ny, nz) of the ground at (x, y), core frame: the Plane's, or the grid's
    (-dh/dx, -dh/dy, 1) normalised."""
    raise NotImplementedError("compiled code only")


@njit(cache=True, error_model="numpy")
def _grid_normal(terrain, x, y):
    hx, hy = _grid_gradient(terrain, x, y)
    k = 1.0 / math.sqrt(1.0 + hx * hx + hy * hy)
    return -hx * k, -hy * k, k


@overload(normal_at, inline="always")
def _normal_at(terrain, plane, x, y):
    if _flat(terrain):
        return lambda terrain, plane, x, y: (plane.nx, plane.ny, plane.nz)
    return lambda terrain, plane, x, y: _grid_normal(terrain, x, y)


def normal_or(terrain, nx, ny, nz, x, y):
    """``normal_at`` where the Plane's normal is (nx, ny, nz)."""
    raise NotImplementedError("compiled code only")


@overload(normal_or, inline="always")
def _normal_or(terrain, nx, ny, nz, x, y):
    if _flat(terrain):
        return lambda terrain, nx, ny, nz, x, y: (nx, ny, nz)
    return lambda terrain, nx, ny, nz, x, y: _grid_normal(terrain, x, y)


def turf_at(terrain, plane, x, y):
    """The turf of the ground at (x, y): the Plane's, or that of the zone there."""
    raise NotImplementedError("compiled code only")


@njit(cache=True, error_model="numpy")
def _grid_turf(terrain, x, y):
    t = terrain.turf[_grid_zone(terrain, x, y)]
    return Turf(t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8])


@overload(turf_at, inline="always")
def _turf_at(terrain, plane, x, y):
    if _flat(terrain):
        return lambda terrain, plane, x, y: plane.turf
    return lambda terrain, plane, x, y: _grid_turf(terrain, x, y)


# Where the ball touches the ground, for the Rules (``state_at``): in play, or a place where the
# shot ends there (its status, ``mcrun.status``).
def state_at(terrain, x, y):
    """OK where the ball is in play at (x, y); IN_PENALTY_AREA, OUT_OF_BOUNDS_STATUS or OFF_MAP
    (``mcrun.status``) where its shot ends there. Always OK on a Plane."""
    raise NotImplementedError("compiled code only")


@njit(cache=True, error_model="numpy")
def _grid_state(terrain, x, y):
    _, _, _, _, inside = _locate(terrain, x, y)
    return _state_of(inside, terrain.penalty[_grid_zone(terrain, x, y)])


@overload(state_at, inline="always")
def _state_at(terrain, x, y):
    if _flat(terrain):
        return lambda terrain, x, y: OK
    return lambda terrain, x, y: _grid_state(terrain, x, y)


def contact(terrain, plane, x, y):
    """What an impact asks of the ground at (x, y), in one look-up: the state there
    (``state_at``), its unit normal (``normal_at``) and turf (``turf_at``), and its
    ``calm_reach``."""
    raise NotImplementedError("compiled code only")


@njit(cache=True, error_model="numpy", inline="always")
def _grid_contact(terrain, x, y):
    ix, iy, tx, ty, inside, h00, h10, h01, h11 = _cell_at(terrain, x, y)
    hx, hy = _cell_slope(terrain, tx, ty, h00, h10, h01, h11)
    k = 1.0 / math.sqrt(1.0 + hx * hx + hy * hy)
    zone = terrain.zone[iy + (1 if ty >= 0.5 else 0), ix + (1 if tx >= 0.5 else 0)]
    t = terrain.turf[zone]
    kind = terrain.penalty[zone]
    state = _state_of(inside, kind)
    turf = Turf(t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8])
    reach = float(terrain.calm[iy, ix]) * terrain.cell_m
    return state, -hx * k, -hy * k, k, turf, reach


@overload(contact, inline="always")
def _contact(terrain, plane, x, y):
    if _flat(terrain):
        return lambda terrain, plane, x, y: (
            OK, plane.nx, plane.ny, plane.nz, plane.turf, math.inf
        )  # fmt: skip
    return lambda terrain, plane, x, y: _grid_contact(terrain, x, y)


def calm_reach(terrain, x, y):
    """How far (m) a ball at (x, y) may go in any direction on one plane of one zone: the
    ``calm_cells`` of the cell under it, in metres (0 where the ground bends or the zone
    changes there; no limit on a Plane)."""
    raise NotImplementedError("compiled code only")


@njit(cache=True, error_model="numpy", inline="always")
def _grid_calm_reach(terrain, x, y):
    ix, iy, _, _, _ = _locate(terrain, x, y)
    return float(terrain.calm[iy, ix]) * terrain.cell_m


@overload(calm_reach, inline="always")
def _calm_reach(terrain, x, y):
    if _flat(terrain):
        return lambda terrain, x, y: math.inf
    return lambda terrain, x, y: _grid_calm_reach(terrain, x, y)


# ``surface``'s patch: where the ground around the ball is one smooth piece, one bilinear
# patch of one zone (a cell of the grid, or the quarter of it nearest one node where its nodes'
# zones differ), in the core's frame, the numbers (SMOOTH, XC, YC, HC, BX, BY, EC, U_LO, U_HI,
# W_LO, W_HI): SMOOTH 1.0 where the roll may take the patch's own steps (on a grid, where the
# cell is not calm), LEVEL_PATCH where that patch is level (where the roll's steps are exact up
# to its edge and to the ball's stop), else 0.0 (and the rest is not used); at U = x - XC,
# W = YC - y (the grid's fractions times the cell), its height is HC + BX U + BY W + EC U W,
# for U in [U_LO, U_HI] and W in [W_LO, W_HI].
LEVEL_PATCH = 2.0
NO_PATCH = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


@njit(cache=True, error_model="numpy")
def _plane_surface(terrain, plane, x, y, z):
    return z, plane.nx, plane.ny, plane.nz, plane.turf, OK, math.inf, NO_PATCH


@njit(cache=True, error_model="numpy", inline="always")
def _grid_surface(terrain, plane, x, y, z):
    """``surface`` on the grid: one look-up of the cell for all of it."""
    ix, iy, tx, ty, inside, h00, h10, h01, h11 = _cell_at(terrain, x, y)
    height = (h00 * (1.0 - tx) + h10 * tx) * (1.0 - ty) + (h01 * (1.0 - tx) + h11 * tx) * ty
    hx, hy = _cell_slope(terrain, tx, ty, h00, h10, h01, h11)
    k = 1.0 / math.sqrt(1.0 + hx * hx + hy * hy)
    upper_x = tx >= 0.5
    upper_y = ty >= 0.5
    zones = terrain.zone
    zone = zones[iy + (1 if upper_y else 0), ix + (1 if upper_x else 0)]
    t = terrain.turf[zone]
    kind = terrain.penalty[zone]
    state = _state_of(inside, kind)
    calm = terrain.calm[iy, ix]
    c = terrain.cell_m
    u_lo = 0.0
    u_hi = c
    w_lo = 0.0
    w_hi = c
    if (
        (zones[iy, ix] != zones[iy, ix + 1])
        | (zones[iy, ix] != zones[iy + 1, ix])
        | (zones[iy, ix] != zones[iy + 1, ix + 1])
    ):
        # The quarter of the cell nearest the node whose zone is that of (x, y).
        u_lo = 0.5 * c if upper_x else 0.0
        u_hi = c if upper_x else 0.5 * c
        w_lo = 0.5 * c if upper_y else 0.0
        w_hi = c if upper_y else 0.5 * c
    inv = 1.0 / c
    smooth = 0.0
    if (calm == 0) & inside:
        smooth = LEVEL_PATCH if (h10 == h00) & (h01 == h00) & (h11 == h00) else 1.0
    patch = (
        smooth, terrain.x0_m + ix * c, -(terrain.y0_m + iy * c),
        h00, (h10 - h00) * inv, (h01 - h00) * inv, (h11 - h10 - h01 + h00) * (inv * inv), u_lo,
        u_hi, w_lo, w_hi,
    )  # fmt: skip
    return (
        height, -hx * k, -hy * k, k, Turf(t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8]),
        state, max(0.25, float(calm)) * c, patch,
    )  # fmt: skip


def _surface(terrain, plane, x, y, z):
    raise NotImplementedError("compiled code only")


@overload(_surface, inline="always")
def _surface_overload(terrain, plane, x, y, z):
    if _flat(terrain):
        return lambda terrain, plane, x, y, z: _plane_surface(terrain, plane, x, y, z)
    return lambda terrain, plane, x, y, z: _grid_surface(terrain, plane, x, y, z)


@njit(cache=True, error_model="numpy", inline="always")
def surface(terrain, plane, x, y, z):
    """What the roll asks at each step (``roll.roll``, to which it is passed): the height of
    the ground at (x, y) (on a Plane, z itself: the ball stays on the plane), its normal and
    turf, the state there (``state_at``) and the longest distance (m) a step may go on it (a
    quarter of a cell of a grid; on a Plane, the same everywhere, no limit), and the smooth
    patch of ground around it (``NO_PATCH``'s numbers), where the roll may step further."""
    return _surface(terrain, plane, x, y, z)


def varies(terrain):
    """Whether the ground changes from place to place (a grid), so that the shot loop must ask
    it anew where the ball goes; a Plane does not."""
    raise NotImplementedError("compiled code only")


@overload(varies, inline="always")
def _varies(terrain):
    if _flat(terrain):
        return lambda terrain: False
    return lambda terrain: True


def step_length(terrain):
    """The longest step (m) of a ball along the ground anywhere: a quarter of a cell of the
    grid, within which its slope changes little (``surface`` gives longer ones on calm
    ground); no limit on a Plane."""
    raise NotImplementedError("compiled code only")


@overload(step_length, inline="always")
def _step_length(terrain):
    if _flat(terrain):
        return lambda terrain: math.inf
    return lambda terrain: 0.25 * terrain.cell_m


def hop_landing(terrain, x, y, z, vx, vy, vz, hop_time):
    """Where a hop from (x, y, z) at velocity (vx, vy, vz) meets the ground again: (x, y, z,
    vz, t) at its end. On a Plane, after ``hop_time`` (the exact return to the plane, from
    ``bounce.impact``); on a grid, the first time its parabola goes below the surface."""
    raise NotImplementedError("compiled code only")


@overload(hop_landing, inline="always")
def _hop_landing(terrain, x, y, z, vx, vy, vz, hop_time):
    if _flat(terrain):

        def on_plane(terrain, x, y, z, vx, vy, vz, hop_time):
            x1, y1, z1, vz1 = hop(x, y, z, vx, vy, vz, hop_time)
            return x1, y1, z1, vz1, hop_time

        return on_plane
    return lambda terrain, x, y, z, vx, vy, vz, hop_time: _grid_hop(
        terrain, x, y, z, vx, vy, vz, hop_time
    )


# Bounds of the search for the end of a hop on a grid: the ball leaves the ground at t = 0, so
# the search starts a little after it; at most MAX_HOP_STEPS steps of the march.
HOP_T_MIN_S = 1e-9
MAX_HOP_STEPS = 100_000
# The hop ends where the ball is within this of the surface (its height then is the surface's).
HOP_GAP_TOLERANCE_M = 1e-9


@njit(cache=True, error_model="numpy", inline="always")
def _grid_hop(terrain, x, y, z, vx, vy, vz, hop_time):
    """``hop_landing`` on the grid. A hop that stays on calm ground (``calm_cells``) ends after
    ``hop_time``, the plane's exact return, as on a Plane. Any other follows its ground track
    from cell to cell (across a calm cell's square of one plane at once): over a cell the gap
    between the parabola and the bilinear surface is a quadratic in time, and the hop ends at
    its first root (``_marched_hop`` where that finds none: a track that leaves the grid)."""
    vh = math.sqrt(vx * vx + vy * vy)
    ix, iy, _, _, _ = _locate(terrain, x, y)
    reach_m = float(terrain.calm[iy, ix]) * terrain.cell_m
    if (hop_time > 0.0) & (vh * hop_time <= reach_m):
        x1, y1, z1, vz1 = hop(x, y, z, vx, vy, vz, hop_time)
        return x1, y1, z1, vz1, hop_time
    t_min = HOP_T_MIN_S
    if (
        z
        + vz * t_min
        - 0.5 * G_MPS2 * t_min * t_min
        - _grid_height(terrain, x + vx * t_min, y + vy * t_min)
        <= 0.0
    ):
        return x, y, z, vz, 0.0
    ny, nx = terrain.height_m.shape
    c = terrain.cell_m
    h = terrain.height_m
    fx0 = (x - terrain.x0_m) / c
    fy0 = (-y - terrain.y0_m) / c
    dfx = vx / c
    dfy = -vy / c
    sx = 1 if dfx > 0.0 else -1
    sy = 1 if dfy > 0.0 else -1
    t_in = 0.0
    for _ in range(MAX_HOP_STEPS):
        # When the track leaves cell (ix, iy), unless at the grid's edge (extended beyond it),
        # or the square of r cells around it, all of its plane, where the cell is calm.
        r = int(terrain.calm[iy, ix])
        tx = math.inf
        if (dfx > 0.0) & (ix + r < nx - 2):
            tx = (ix + r + 1 - fx0) / dfx
        elif (dfx < 0.0) & (ix - r > 0):
            tx = (ix - r - fx0) / dfx
        ty = math.inf
        if (dfy > 0.0) & (iy + r < ny - 2):
            ty = (iy + r + 1 - fy0) / dfy
        elif (dfy < 0.0) & (iy - r > 0):
            ty = (iy - r - fy0) / dfy
        t_out = min(tx, ty)
        # The gap at t_in + s: c0 + c1 s + c2 s^2, the cell's height h00 + a u + b w + e u w.
        u = fx0 + dfx * t_in - ix
        w = fy0 + dfy * t_in - iy
        h00 = h[iy, ix]
        a = h[iy, ix + 1] - h00
        b = h[iy + 1, ix] - h00
        e = h[iy + 1, ix + 1] - h[iy, ix + 1] - h[iy + 1, ix] + h00
        c0 = z + (vz - 0.5 * G_MPS2 * t_in) * t_in - (h00 + a * u + b * w + e * u * w)
        c1 = vz - G_MPS2 * t_in - (a * dfx + b * dfy + e * (u * dfy + w * dfx))
        c2 = -0.5 * G_MPS2 - e * dfx * dfy
        if t_in == 0.0:
            s = _root_after(c2, c1, c0, t_min)
        elif c0 <= 0.0:
            s = 0.0  # (rounding, where the track grazes the ground at a cell's edge)
        else:
            s = _root_after(c2, c1, c0, 0.0)
        if t_in + s <= t_out:
            t = t_in + s
            x1 = x + vx * t
            y1 = y + vy * t
            return x1, y1, _grid_height(terrain, x1, y1), vz - G_MPS2 * t, t
        if t_out == math.inf:
            break
        t_in = t_out
        if tx <= ty:
            ix += sx * (r + 1)
            iy = min(max(int(math.floor(fy0 + dfy * t_in)), iy - r, 0), iy + r, ny - 2)
        else:
            iy += sy * (r + 1)
            ix = min(max(int(math.floor(fx0 + dfx * t_in)), ix - r, 0), ix + r, nx - 2)
    return _marched_hop(terrain, x, y, z, vx, vy, vz, hop_time)


@njit(cache=True, error_model="numpy", inline="always")
def _root_after(a, b, c, s_min):
    """The first root s > s_min of a s^2 + b s + c (inf if none)."""
    if a == 0.0:
        r = -c / b if b != 0.0 else -math.inf
        return r if r > s_min else math.inf
    d = b * b - 4.0 * a * c
    if d < 0.0:
        return math.inf
    q = -0.5 * (b + math.copysign(math.sqrt(d), b))
    r1 = q / a
    r2 = c / q if q != 0.0 else -math.inf
    r1 = r1 if r1 > s_min else math.inf
    r2 = r2 if r2 > s_min else math.inf
    return min(r1, r2)


@njit(cache=True, error_model="numpy")
def _marched_hop(terrain, x, y, z, vx, vy, vz, hop_time):
    """``hop_landing`` on the grid by a march along the parabola in steps of at most half
    ``hop_time`` and a quarter of a cell, to the first step that ends below the surface, then
    the crossing inside it (Illinois' false position, to a nanometre)."""
    vh = math.sqrt(vx * vx + vy * vy)
    ix, iy, _, _, _ = _locate(terrain, x, y)
    reach_m = float(terrain.calm[iy, ix]) * terrain.cell_m
    dt = 0.5 * hop_time if hop_time > 0.0 else 1e-3
    if vh > 0.0:
        dt = min(dt, max(0.25 * terrain.cell_m, reach_m) / vh)
    dt = max(dt, 1e-6)

    def gap(t):
        return z + vz * t - 0.5 * G_MPS2 * t * t - _grid_height(terrain, x + vx * t, y + vy * t)

    a = 0.0
    fa = 0.0
    b = dt
    fb = gap(b)
    steps = 0
    while fb > 0.0 and steps < MAX_HOP_STEPS:
        a = b
        fa = fb
        b += dt
        fb = gap(b)
        steps += 1
    if a == 0.0:
        # Leaving the ground, the ball is above it at once; take the bracket from there.
        a = HOP_T_MIN_S
        fa = gap(a)
        if fa <= 0.0:
            return x, y, z, vz, 0.0
    side = 0
    t = b
    for _ in range(100):
        t = (a * fb - b * fa) / (fb - fa)
        ft = gap(t)
        if ft > 0.0:
            a, fa = t, ft
            if side == 1:
                fb *= 0.5
            side = 1
        else:
            b, fb = t, ft
            if side == -1:
                fa *= 0.5
            side = -1
        if abs(ft) < HOP_GAP_TOLERANCE_M or b - a < 1e-12:
            break  # at t, the last estimate
    return x + vx * t, y + vy * t, _grid_height(terrain, x + vx * t, y + vy * t), vz - G_MPS2 * t, t


def crossing(terrain, xa, ya, xb, yb):
    """Where the ground track from (xa, ya), in play, to (xb, yb), not, crosses into what ends
    the shot there (``state_at``): the Rules' reference point, to a millimetre. On a Plane
    (always in play), (xb, yb)."""
    raise NotImplementedError("compiled code only")


@overload(crossing, inline="always")
def _crossing(terrain, xa, ya, xb, yb):
    if _flat(terrain):
        return lambda terrain, xa, ya, xb, yb: (xb, yb)
    return lambda terrain, xa, ya, xb, yb: _grid_crossing(terrain, xa, ya, xb, yb)


@njit(cache=True, error_model="numpy")
def _grid_crossing(terrain, xa, ya, xb, yb):
    """``crossing`` on the grid; (xa, ya) may lie in the area too: the search first goes back
    from b beyond a, a cell at a time, to a point in play (or to the grid's edge)."""
    dx = xa - xb
    dy = ya - yb
    d = math.sqrt(dx * dx + dy * dy)
    if d == 0.0:
        return xb, yb
    ux = dx / d
    uy = dy / d
    s = min(d, terrain.cell_m)
    while _grid_state(terrain, xb + ux * s, yb + uy * s) != OK:
        if _grid_state(terrain, xb + ux * s, yb + uy * s) == OFF_MAP:
            return xb + ux * s, yb + uy * s
        s += terrain.cell_m
    lo = 0.0  # not in play
    hi = s  # in play
    while hi - lo > 1e-3:
        mid = 0.5 * (lo + hi)
        if _grid_state(terrain, xb + ux * mid, yb + uy * mid) == OK:
            hi = mid
        else:
            lo = mid
    return xb + ux * lo, yb + uy * lo
