"""Where a hop comes down on a Terrain's grid (``grid_hop``): cell by cell along its ground
track, the gap between its parabola and the bilinear surface a quadratic in time over each."""

import math

from numba import njit

from mcrun.ground.grid import _calm, _cell_at, _corners, _grid_height, _in_cells, _locate
from mcrun.physics.bounce import hop
from mcrun.physics.constants import G_MPS2

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
    ix, iy, _, _, _, _, _, _, _ = _cell_at(terrain, x, y)
    reach_m = float(_calm(terrain, ix, iy)) * terrain.cell_m
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
    ny, nx = terrain.ny, terrain.nx
    fx0 = _in_cells(terrain, x - terrain.x0_m)
    fy0 = _in_cells(terrain, -y - terrain.y0_m)
    dfx = _in_cells(terrain, vx)
    dfy = -_in_cells(terrain, vy)
    sx = 1 if dfx > 0.0 else -1
    sy = 1 if dfy > 0.0 else -1
    t_in = 0.0
    for _ in range(MAX_HOP_STEPS):
        # When the track leaves cell (ix, iy), unless at the grid's edge (extended beyond it),
        # or the square of r cells around it, all of its plane, where the cell is calm.
        r = int(_calm(terrain, ix, iy))
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
        h00, h10, h01, h11 = _corners(terrain, ix, iy)
        a = h10 - h00
        b = h01 - h00
        e = h11 - h10 - h01 + h00
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
    reach_m = float(_calm(terrain, ix, iy)) * terrain.cell_m
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
