"""The look-ups of a Terrain's grid: the cell under a point, its height, slope, zone and state,
and the answers to the shot loop's questions on a grid (``ground.questions``), each in one
look-up of the cell where a loop asks at every step. Each reads the grid through its view
(``terrain.TerrainView``: flat arrays, row by row)."""

import math

from numba import njit
from numba.extending import overload

from mcrun.ground.terrain import OUT_OF_BOUNDS, PENALTY_AREA, TURF_FIELDS, read_turf
from mcrun.physics.roll import LEVEL_PATCH, Patch, Surface
from mcrun.status import IN_PENALTY_AREA, OFF_MAP, OK, OUT_OF_BOUNDS_STATUS


def cell_index(f, last):
    """The cell at the fraction f (of cells from the grid's origin) along an axis, in [0,
    last]: the edge cells are extended. Compiled, ``int(floor(f))`` clamped (its overload); as
    Python (``NUMBA_DISABLE_JIT=1``) the same, and 0 where f is not a number (the garbage of a
    lane that holds no shot, which the compiled code clamps as any number), where Python's
    ``int`` would raise."""
    if math.isnan(f):
        return 0
    return min(max(int(math.floor(f)), 0), last) if math.isfinite(f) else (last if f > 0 else 0)


@overload(cell_index, inline="always")
def _cell_index(f, last):
    return lambda f, last: min(max(int(math.floor(f)), 0), last)


@njit(cache=True, error_model="numpy", inline="always")
def _in_cells(terrain, d):
    """A length d (m) in cells of the grid: d times 1 / cell_m, which the compiler computes
    once, out of the loops (a division at every look-up was the longest wait in it); exactly
    d / cell_m where the cell is a power of two of a metre (0.25, 0.5, 1, 2 m: every library
    hole), and within a rounding of it otherwise."""
    return d * (1.0 / terrain.cell_m)


@njit(cache=True, error_model="numpy")
def _locate(terrain, x, y):
    """The cell of the grid under core-frame (x, y) (y to the LEFT, the grid's y to the right):
    its lower node (ix, iy), the fractions (tx, ty) across it, and whether (x, y) is on the
    grid at all (off it, the edge cells are extended): ``_cell_at`` without the heights."""
    ix, iy, tx, ty, inside, _, _, _, _ = _cell_at(terrain, x, y)
    return ix, iy, tx, ty, inside


@njit(cache=True, error_model="numpy", inline="always")
def _cell_at(terrain, x, y):
    """``_locate`` inlined where a loop asks at every step, with the heights of the cell's four
    nodes: (ix, iy, tx, ty, inside, h00, h10, h01, h11)."""
    ny_, nx_ = terrain.ny, terrain.nx
    fx = _in_cells(terrain, x - terrain.x0_m)
    fy = _in_cells(terrain, -y - terrain.y0_m)
    inside = (fx >= 0.0) & (fx <= nx_ - 1.0) & (fy >= 0.0) & (fy <= ny_ - 1.0)
    ix = cell_index(fx, nx_ - 2)
    iy = cell_index(fy, ny_ - 2)
    tx = min(max(fx - ix, 0.0), 1.0)
    ty = min(max(fy - iy, 0.0), 1.0)
    h00, h10, h01, h11 = _corners(terrain, ix, iy)
    return ix, iy, tx, ty, inside, h00, h10, h01, h11


@njit(cache=True, error_model="numpy", inline="always")
def _four_nodes(terrain, values, ix, iy):
    """The values (a per-node array of the view: ``height_m``, ``zone``) at the four nodes of
    cell (ix, iy): (v00, v10, v01, v11), v10 the next along x, v01 the next along y."""
    i = iy * terrain.nx + ix
    j = i + terrain.nx  # (the node above)
    return values[i], values[i + 1], values[j], values[j + 1]


@njit(cache=True, error_model="numpy", inline="always")
def _corners(terrain, ix, iy):
    """The heights of the four nodes of cell (ix, iy): (h00, h10, h01, h11)."""
    return _four_nodes(terrain, terrain.height_m, ix, iy)


@njit(cache=True, error_model="numpy", inline="always")
def _cell_height(tx, ty, h00, h10, h01, h11):
    """The bilinear height at fractions (tx, ty) across a cell of these node heights."""
    return (h00 * (1.0 - tx) + h10 * tx) * (1.0 - ty) + (h01 * (1.0 - tx) + h11 * tx) * ty


@njit(cache=True, error_model="numpy", inline="always")
def _cell_slope(terrain, tx, ty, h00, h10, h01, h11):
    """(dh/dx, dh/dy) at fractions (tx, ty) of a cell of these node heights, y to the LEFT
    (``_grid_gradient``'s numbers)."""
    hx = _in_cells(terrain, (h10 - h00) * (1.0 - ty) + (h11 - h01) * ty)
    hy = -_in_cells(terrain, (h01 - h00) * (1.0 - tx) + (h11 - h10) * tx)
    return hx, hy


@njit(cache=True, error_model="numpy", inline="always")
def _nearest_zone(terrain, ix, iy, tx, ty):
    """The zone of the node of cell (ix, iy) nearest the point at fractions (tx, ty) across it."""
    return terrain.zone[(iy + (1 if ty >= 0.5 else 0)) * terrain.nx + ix + (1 if tx >= 0.5 else 0)]


@njit(cache=True, error_model="numpy", inline="always")
def _zone_turf(terrain, zone):
    """The Turf of a zone."""
    return read_turf(terrain.turf, int(zone) * TURF_FIELDS, 1)


@njit(cache=True, error_model="numpy", inline="always")
def _calm(terrain, ix, iy):
    """``calm_cells`` of cell (ix, iy)."""
    return terrain.calm[iy * (terrain.nx - 1) + ix]


@njit(cache=True, error_model="numpy")
def _grid_height(terrain, x, y):
    """Bilinear height (m) of the grid at core-frame (x, y)."""
    ix, iy, tx, ty, _ = _locate(terrain, x, y)
    h00, h10, h01, h11 = _corners(terrain, ix, iy)
    return _cell_height(tx, ty, h00, h10, h01, h11)


@njit(cache=True, error_model="numpy")
def _grid_gradient(terrain, x, y):
    """(dh/dx, dh/dy) of the bilinear grid at core-frame (x, y), y to the LEFT."""
    ix, iy, tx, ty, _ = _locate(terrain, x, y)
    h00, h10, h01, h11 = _corners(terrain, ix, iy)
    return _cell_slope(terrain, tx, ty, h00, h10, h01, h11)


@njit(cache=True, error_model="numpy")
def _grid_zone(terrain, x, y):
    """The zone of the node nearest core-frame (x, y)."""
    ix, iy, tx, ty, _ = _locate(terrain, x, y)
    return _nearest_zone(terrain, ix, iy, tx, ty)


@njit(cache=True, error_model="numpy", inline="always")
def _state_of(inside, kind):
    """The state (``state_at``) of a moving ball over a point on the grid or not (``inside``)
    in a zone of this ``penalty`` kind: out of bounds is played on as any ground while the ball
    moves (Rule 18.2 decides it where the ball rests: ``_grid_rest_state``)."""
    if not inside:
        return OFF_MAP
    return IN_PENALTY_AREA if kind == PENALTY_AREA else OK


@njit(cache=True, error_model="numpy", inline="always")
def _grid_flight_check(terrain, x, y, z):
    ix, iy, tx, ty, inside, h00, h10, h01, h11 = _cell_at(terrain, x, y)
    height = _cell_height(tx, ty, h00, h10, h01, h11)
    kind = terrain.penalty[_nearest_zone(terrain, ix, iy, tx, ty)]
    state = _state_of(inside, kind)
    return z - height, state


@njit(cache=True, error_model="numpy")
def _grid_normal(terrain, x, y):
    hx, hy = _grid_gradient(terrain, x, y)
    k = 1.0 / math.sqrt(1.0 + hx * hx + hy * hy)
    return -hx * k, -hy * k, k


@njit(cache=True, error_model="numpy")
def _grid_turf(terrain, x, y):
    return _zone_turf(terrain, _grid_zone(terrain, x, y))


@njit(cache=True, error_model="numpy")
def _grid_state(terrain, x, y):
    _, _, _, _, inside = _locate(terrain, x, y)
    return _state_of(inside, terrain.penalty[_grid_zone(terrain, x, y)])


@njit(cache=True, error_model="numpy")
def _grid_rest_state(terrain, x, y):
    """``rest_state`` on the grid: OUT_OF_BOUNDS_STATUS where the zone of the node nearest
    (x, y) is out of bounds, OK elsewhere."""
    kind = terrain.penalty[_grid_zone(terrain, x, y)]
    return OUT_OF_BOUNDS_STATUS if kind == OUT_OF_BOUNDS else OK


@njit(cache=True, error_model="numpy", inline="always")
def _grid_contact(terrain, x, y):
    ix, iy, tx, ty, inside, h00, h10, h01, h11 = _cell_at(terrain, x, y)
    hx, hy = _cell_slope(terrain, tx, ty, h00, h10, h01, h11)
    k = 1.0 / math.sqrt(1.0 + hx * hx + hy * hy)
    zone = _nearest_zone(terrain, ix, iy, tx, ty)
    kind = terrain.penalty[zone]
    state = _state_of(inside, kind)
    turf = _zone_turf(terrain, zone)
    reach = float(_calm(terrain, ix, iy)) * terrain.cell_m
    return state, -hx * k, -hy * k, k, turf, reach


@njit(cache=True, error_model="numpy", inline="always")
def _grid_calm_reach(terrain, x, y):
    ix, iy, _, _, _, _, _, _, _ = _cell_at(terrain, x, y)
    return float(_calm(terrain, ix, iy)) * terrain.cell_m


@njit(cache=True, error_model="numpy", inline="always")
def _grid_surface(terrain, x, y):
    """``surface`` on the grid: one look-up of the cell for all of it."""
    ix, iy, tx, ty, inside, h00, h10, h01, h11 = _cell_at(terrain, x, y)
    height = _cell_height(tx, ty, h00, h10, h01, h11)
    hx, hy = _cell_slope(terrain, tx, ty, h00, h10, h01, h11)
    k = 1.0 / math.sqrt(1.0 + hx * hx + hy * hy)
    upper_x = tx >= 0.5
    upper_y = ty >= 0.5
    zone = _nearest_zone(terrain, ix, iy, tx, ty)
    z00, z10, z01, z11 = _four_nodes(terrain, terrain.zone, ix, iy)
    kind = terrain.penalty[zone]
    state = _state_of(inside, kind)
    calm = _calm(terrain, ix, iy)
    c = terrain.cell_m
    u_lo = 0.0
    u_hi = c
    w_lo = 0.0
    w_hi = c
    if (z00 != z10) | (z00 != z01) | (z00 != z11):
        # The quarter of the cell nearest the node whose zone is that of (x, y).
        u_lo = 0.5 * c if upper_x else 0.0
        u_hi = c if upper_x else 0.5 * c
        w_lo = 0.5 * c if upper_y else 0.0
        w_hi = c if upper_y else 0.5 * c
    inv = 1.0 / c
    smooth = 0.0
    if (calm == 0) & inside:
        smooth = LEVEL_PATCH if (h10 == h00) & (h01 == h00) & (h11 == h00) else 1.0
    patch = Patch(
        smooth, terrain.x0_m + ix * c, -(terrain.y0_m + iy * c),
        h00, (h10 - h00) * inv, (h01 - h00) * inv, (h11 - h10 - h01 + h00) * (inv * inv), u_lo,
        u_hi, w_lo, w_hi,
    )  # fmt: skip
    return Surface(
        height, -hx * k, -hy * k, k, _zone_turf(terrain, zone), state, max(0.25, float(calm)) * c,
        patch,
    )  # fmt: skip


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
