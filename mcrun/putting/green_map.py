"""Expected putts from every point of a green: the map, with the read (start line and pace)
at every point, the share of one-putts and of three putts or more.

The value of a point is the expected number of strokes to hole out from there, every putt read
as well as the putter can (``mcrun.putting.read``: the paces ``read.PACES_M``, each on the line
that rolls the error-free putt over the hole's centre, then start lines ``read.AIM_STEPS_DEG``
either side of the best), the later putts valued by the map itself:

    V(p) = min over reads of  E[ 1 + V(where the putt stopped) ],   V(in the hole) = 0,

over ``n`` putts whose errors (start line, speed) are common to every read and every point
(common random numbers: the map is smooth, and its differences are the ground's). A putt that
leaves the green is a chip from where it left: 1 + the baseline's fairway strokes from there
(the fringe's lie, ``hole.zones``).

The map's points: rings around the hole (``POLAR_RADII_M`` x ``POLAR_ANGLES``, where most
second putts stop, so that the short putts' values are resolved finely), then the nodes of a
grid of ``resolution_m`` on the green. A stop point is valued by bilinear interpolation: in the
rings within ``R_NEAR_M`` of the hole (a ball within ``TAP_IN_M`` is holed with the next putt),
on the grid beyond (among its nodes on the green). The points are solved outwards from the hole
in bands of distance (a Gauss-Seidel sweep: each band reads the values of the bands inside it,
and the baseline's putts for the points not yet solved); a second sweep, every point with its
read, says how far the map is from its fixed point (``GreenMap.sweep_change``). Within a band
the points are independent, so the map is the same whatever the number of threads.
"""

import math
import time
from dataclasses import dataclass, field

import numba
import numpy as np
from numba import njit

from mcrun.engine.batch import on_threads
from mcrun.physics.constants import G_MPS2
from mcrun.putting.cup import HOLE_RADIUS_M
from mcrun.putting.holeout import centre_line
from mcrun.putting.putter import PUTTERS, putter_errors
from mcrun.putting.read import AIM_STEPS_DEG, PACES_M
from mcrun.putting.roll import (
    MAX_TIME_S,
    ROLLING_FACTOR,
    STATUS_HOLED,
    STATUS_STOPPED,
    grid_height,
    roll_on,
)
from mcrun.strokes.baseline import tour_baseline

__all__ = [
    "DEFAULT_N",
    "DEFAULT_RESOLUTION_M",
    "GreenMap",
    "expected_putts_map",
]

DEFAULT_RESOLUTION_M = 0.5
DEFAULT_N = 200
# The roll's steps on a green: at most MAP_DT_S and half a cell of the green's grid (the
# plane's closed forms are met within 0.1 mm at these steps: tests/test_green_map.py).
MAP_DT_S = 0.05
R_NEAR_M = 1.5
TAP_IN_M = 0.1
POLAR_DR_M = 0.1
POLAR_RADII_M = tuple(round(TAP_IN_M + POLAR_DR_M * k, 10) for k in range(16))  # to 1.6 m
POLAR_ANGLES = 24
BAND_M = 0.25
CHIP_STEP_M = 0.05
CHIP_MAX_M = 200.0


@njit(cache=True, inline="always")
def _bilinear(values, valid, fx, fy):
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
def _polar(values, r, dx, dy):
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


@njit(cache=True)
def _value_at(x, y, hx, hy, polar_v, polar_p1, grid, grid_v, grid_p1, grid_valid, chip):
    """(expected strokes, one-putt share) from a ball at rest at (x, y) on the green."""
    dx, dy = x - hx, y - hy
    r = math.sqrt(dx * dx + dy * dy)
    if r <= HOLE_RADIUS_M:
        return 0.0, 1.0
    if r < TAP_IN_M:
        return 1.0, 1.0
    if r < R_NEAR_M:
        return _polar(polar_v, r, dx, dy), _polar(polar_p1, r, dx, dy)
    x0, y0, cell = grid
    fx, fy = (x - x0) / cell, (y - y0) / cell
    v, w = _bilinear(grid_v, grid_valid, fx, fy)
    if w > 1e-9:
        p, _ = _bilinear(grid_p1, grid_valid, fx, fy)
        return v / w, p / w
    return _chip(r, chip), 0.0


@njit(cache=True, inline="always")
def _chip(r, chip):
    """The baseline's fairway strokes from ``r`` (m): linear in the table ``chip``."""
    f = min(r / CHIP_STEP_M, chip.shape[0] - 1.000001)
    k = int(f)
    return chip[k] + (f - k) * (chip[k + 1] - chip[k])


@njit(cache=True)
def _speed(x, y, hx, hy, pace_m, surface, rho_g):
    """The start speed that would roll a putt from (x, y) ``pace_m`` past the hole on the
    straight line, by energy: v^2 = 2 (5/7) g (rho_g (L + pace) + z(end) - z(start)), the
    ground's heights at the ends (a tenth of the resistance's where the line falls faster)."""
    length = math.hypot(hx - x, hy - y)
    ux, uy = (hx - x) / length, (hy - y) / length
    rise = grid_height(hx + pace_m * ux, hy + pace_m * uy, surface) - grid_height(x, y, surface)
    k = ROLLING_FACTOR * G_MPS2
    a = max(rho_g * (length + pace_m) + rise, 0.1 * rho_g * (length + pace_m))
    return math.sqrt(2.0 * k * a)


@njit(cache=True)
def _score(x, y, aim, speed, surface, rho_g, hx, hy, line_sd, speed_sd, z, dt, ds, polar_v,
           polar_p1, grid, grid_v, grid_p1, grid_valid, chip):  # fmt: skip
    """(mean, standard error, one-putt share, share of three or more) of the putts from (x, y)
    struck on ``aim`` at ``speed``, each putt with its errors ``z[i]``."""
    n = z.shape[0]
    base = math.atan2(hy - y, hx - x)
    total, total2, ones, threes = 0.0, 0.0, 0.0, 0.0
    for i in range(n):
        angle = base + aim + line_sd * z[i, 0]
        v = max(0.0, speed * (1.0 + speed_sd * z[i, 1]))
        out = roll_on(x, y, v * math.cos(angle), v * math.sin(angle), surface, rho_g, hx, hy,
                      True, dt, MAX_TIME_S, ds)  # fmt: skip
        status = out[0]
        if status == STATUS_HOLED:
            value, p1_next, holed = 1.0, 1.0, True
        elif status == STATUS_STOPPED:
            rest, p1_next = _value_at(out[1], out[2], hx, hy, polar_v, polar_p1, grid, grid_v,
                                      grid_p1, grid_valid, chip)  # fmt: skip
            holed = rest == 0.0
            value = 1.0 + rest
        else:  # off the green (or never at rest): a chip from where it is
            value = 1.0 + _chip(math.hypot(out[1] - hx, out[2] - hy), chip)
            p1_next, holed = 0.0, False
        total += value
        total2 += value * value
        if holed:
            ones += 1.0
        else:
            threes += 1.0 - p1_next
    mean = total / n
    var = max(total2 / n - mean * mean, 0.0) * n / max(n - 1, 1)
    return mean, math.sqrt(var / n), ones / n, threes / n


@njit(cache=True, nogil=True)
def _solve_points(xs, ys, read, surface, rho_g, hx, hy, line_sd, speed_sd, z, dt, ds, paces,
                  aim_steps, polar_v, polar_p1, grid, grid_v, grid_p1, grid_valid, chip,
                  out):  # fmt: skip
    """Solve each point (xs[k], ys[k]): with ``read``, search the read (the paces, each on its
    centre line, then the aim steps around the best); without, value the read already in
    out[k, 0:2] (aim rad, pace m). Writes out[k] = (aim, pace, mean, se, p1, p3)."""
    for k in range(xs.shape[0]):
        x, y = xs[k], ys[k]
        if math.hypot(hx - x, hy - y) <= HOLE_RADIUS_M:
            out[k, 0], out[k, 1], out[k, 2], out[k, 3], out[k, 4], out[k, 5] = (
                0.0, 0.0, 0.0, 0.0, 1.0, 0.0)  # fmt: skip
            continue
        if not read:
            aim, pace = out[k, 0], out[k, 1]
            speed = _speed(x, y, hx, hy, pace, surface, rho_g)
            m, se, p1, p3 = _score(x, y, aim, speed, surface, rho_g, hx, hy, line_sd, speed_sd,
                                   z, dt, ds, polar_v, polar_p1, grid, grid_v, grid_p1,
                                   grid_valid, chip)  # fmt: skip
            out[k, 2], out[k, 3], out[k, 4], out[k, 5] = m, se, p1, p3
            continue
        best = (0.0, 0.0, 1e30, 0.0, 0.0, 0.0)
        for pace in paces:
            speed = _speed(x, y, hx, hy, pace, surface, rho_g)
            aim = centre_line(x, y, hx, hy, speed, 0.0, 1.0, 0.0, rho_g, surface, dt, ds)
            m, se, p1, p3 = _score(x, y, aim, speed, surface, rho_g, hx, hy, line_sd, speed_sd,
                                   z, dt, ds, polar_v, polar_p1, grid, grid_v, grid_p1,
                                   grid_valid, chip)  # fmt: skip
            if m < best[2]:
                best = (aim, pace, m, se, p1, p3)
        aim0, pace = best[0], best[1]
        speed = _speed(x, y, hx, hy, pace, surface, rho_g)
        for step in aim_steps:
            aim = aim0 + step
            m, se, p1, p3 = _score(x, y, aim, speed, surface, rho_g, hx, hy, line_sd, speed_sd,
                                   z, dt, ds, polar_v, polar_p1, grid, grid_v, grid_p1,
                                   grid_valid, chip)  # fmt: skip
            if m < best[2]:
                best = (aim, pace, m, se, p1, p3)
        for j in range(6):
            out[k, j] = best[j]


@dataclass
class GreenMap:
    """Expected putts over a green: on the grid of ``resolution_m`` (node [iy, ix] at
    (x0_m + ix resolution_m, y0_m + iy resolution_m), hole frame), NaN off the green:
    ``expected_putts`` and its standard error, ``p_one_putt``, ``p_three_putt`` (three or more
    strokes), the read's start line ``read_aim_deg`` (+ left of the hole, as ``mcrun putt``) and
    pace ``read_pace_m`` (past the hole); the rings around the hole (``polar_*``), the settings
    and ``sweep_change`` (the largest change of a point's value in the second sweep)."""

    green: object
    x0_m: float
    y0_m: float
    resolution_m: float
    expected_putts: np.ndarray
    expected_putts_se: np.ndarray
    p_one_putt: np.ndarray
    p_three_putt: np.ndarray
    read_aim_deg: np.ndarray
    read_pace_m: np.ndarray
    polar_expected: np.ndarray
    polar_p_one: np.ndarray
    polar_p_three: np.ndarray
    putter: object
    n: int
    seed: int
    sweep_change: float
    elapsed_s: float
    settings: dict = field(default_factory=dict)

    @property
    def valid(self):
        return np.isfinite(self.expected_putts)

    def nodes_xy(self):
        ny, nx = self.expected_putts.shape
        return np.meshgrid(
            self.x0_m + np.arange(nx) * self.resolution_m,
            self.y0_m + np.arange(ny) * self.resolution_m,
        )

    def value_at(self, x_m, y_m):
        """(expected putts, one-putt share, share of three or more) of balls at rest at
        (x_m, y_m) on the green, interpolated as the map's own stop points are. Vectorised."""
        x = np.ascontiguousarray(np.atleast_1d(np.asarray(x_m, dtype=float)))
        y = np.ascontiguousarray(np.atleast_1d(np.asarray(y_m, dtype=float)))
        hx, hy = self.green.pin_xy_m
        valid = np.ascontiguousarray(self.valid, dtype=np.uint8)
        return _values(x, y, hx, hy, self.polar_expected, self.polar_p_one,
                       self.polar_p_three, (self.x0_m, self.y0_m, self.resolution_m),
                       np.nan_to_num(self.expected_putts), np.nan_to_num(self.p_one_putt),
                       np.nan_to_num(self.p_three_putt), valid, _chip_table())  # fmt: skip

    def frame(self):
        """The map as a DataFrame, one row per node on the green: x_m, y_m (hole frame),
        expected_putts, expected_putts_se, p_one_putt, p_three_putt, read_aim_deg,
        read_pace_m."""
        import pandas as pd

        xx, yy = self.nodes_xy()
        on = self.valid
        return pd.DataFrame(
            {
                "x_m": xx[on],
                "y_m": yy[on],
                "expected_putts": self.expected_putts[on],
                "expected_putts_se": self.expected_putts_se[on],
                "p_one_putt": self.p_one_putt[on],
                "p_three_putt": self.p_three_putt[on],
                "read_aim_deg": self.read_aim_deg[on],
                "read_pace_m": self.read_pace_m[on],
            }
        )


@njit(cache=True)
def _values(x, y, hx, hy, polar_v, polar_p1, polar_p3, grid, grid_v, grid_p1, grid_p3,
            grid_valid, chip):  # fmt: skip
    n = x.shape[0]
    v = np.empty(n)
    p1 = np.empty(n)
    p3 = np.empty(n)
    x0, y0, cell = grid
    for k in range(n):
        v[k], p1[k] = _value_at(x[k], y[k], hx, hy, polar_v, polar_p1, grid, grid_v, grid_p1,
                                grid_valid, chip)  # fmt: skip
        dx, dy = x[k] - hx, y[k] - hy
        r = math.hypot(dx, dy)
        if r < TAP_IN_M:
            p3[k] = 0.0
        elif r < R_NEAR_M:
            p3[k] = _polar(polar_p3, r, dx, dy)
        else:
            p, w = _bilinear(grid_p3, grid_valid, (x[k] - x0) / cell, (y[k] - y0) / cell)
            p3[k] = p / w if w > 1e-9 else 1.0
    return v, p1, p3


_CHIP = None


def _chip_table():
    """The baseline's fairway strokes every CHIP_STEP_M from 0 to CHIP_MAX_M (m)."""
    global _CHIP
    if _CHIP is None:
        d = np.arange(0.0, CHIP_MAX_M + CHIP_STEP_M / 2, CHIP_STEP_M)
        _CHIP = np.ascontiguousarray(tour_baseline().expected("fairway", d), dtype=float)
    return _CHIP


def expected_putts_map(green, putter="tour", n=DEFAULT_N, seed=0,
                       resolution_m=DEFAULT_RESOLUTION_M, threads=None,
                       progress=None):  # fmt: skip
    """The GreenMap of ``green`` (a ``putting.green.Green``) for ``putter`` (a name of
    ``PUTTERS`` or a ``Putter``), ``n`` putts per read with errors seeded by ``seed``, on a grid
    of ``resolution_m``. ``progress(done, total)``: called as the points are solved."""
    started = time.perf_counter()
    if isinstance(putter, str):
        putter = PUTTERS[putter]
    threads = numba.get_num_threads() if threads is None else int(threads)
    surface = green.surface
    hx, hy = green.pin_xy_m
    rho_g = green.rho_g
    z = np.ascontiguousarray(putter_errors(n, seed)[:, 0, :])
    line_sd = math.radians(putter.line_sd_deg)
    speed_sd = putter.speed_sd_pct / 100.0
    dt, ds = MAP_DT_S, surface.cell_m / 2.0
    paces = np.array(PACES_M, dtype=float)
    aim_steps = np.radians(np.array(AIM_STEPS_DEG, dtype=float))
    chip = _chip_table()
    base = tour_baseline()

    # The rings around the hole.
    radii = np.array(POLAR_RADII_M)
    angles = np.arange(POLAR_ANGLES) * 2.0 * math.pi / POLAR_ANGLES
    px = hx + radii[:, None] * np.cos(angles)[None, :]
    py = hy + radii[:, None] * np.sin(angles)[None, :]
    polar_v = np.ascontiguousarray(base.expected("green", np.broadcast_to(radii[:, None],
                                                                         px.shape)))  # fmt: skip
    polar_p1 = np.zeros(px.shape)
    polar_out = np.zeros(px.shape + (6,))

    # The grid of the map, over the green's grid.
    xs_g, ys_g = green.nodes_xy()
    gx0 = math.floor(xs_g.min() / resolution_m) * resolution_m
    gy0 = math.floor(ys_g.min() / resolution_m) * resolution_m
    nx = int(math.floor((xs_g.max() - gx0) / resolution_m)) + 1
    ny = int(math.floor((ys_g.max() - gy0) / resolution_m)) + 1
    mx, my = np.meshgrid(gx0 + np.arange(nx) * resolution_m, gy0 + np.arange(ny) * resolution_m)
    on = _on_green(green, mx, my)
    grid = (float(gx0), float(gy0), float(resolution_m))
    grid_v = np.ascontiguousarray(np.where(on, base.expected("green", np.hypot(mx - hx, my - hy)),
                                           0.0))  # fmt: skip
    grid_p1 = np.zeros(mx.shape)
    grid_valid = np.ascontiguousarray(on, dtype=np.uint8)
    grid_out = np.full(mx.shape + (6,), np.nan)

    total = px.size + int(on.sum())
    done = 0

    def solve(xs, ys, read, out):
        """``_solve_points`` of the points (xs, ys) into ``out``, in slices on threads."""
        args = (surface, rho_g, hx, hy, line_sd, speed_sd, z, dt, ds, paces, aim_steps, polar_v,
                polar_p1, grid, grid_v, grid_p1, grid_valid, chip)  # fmt: skip
        cuts = np.linspace(0, xs.size, min(xs.size, 4 * threads) + 1).astype(np.int64)

        def work(k):
            a, b = cuts[k], cuts[k + 1]
            _solve_points(xs[a:b], ys[a:b], read, *args, out[a:b])

        on_threads(work, len(cuts) - 1, threads)

    # First sweep: the rings, inside out, then the grid in bands of distance.
    for j in range(len(radii)):
        out = np.zeros((POLAR_ANGLES, 6))
        solve(px[j], py[j], True, out)
        polar_out[j] = out
        polar_v[j], polar_p1[j] = out[:, 2], out[:, 4]
        done += POLAR_ANGLES
        if progress is not None:
            progress(done, total)
    iy, ix = np.nonzero(on)
    r = np.hypot(mx[iy, ix] - hx, my[iy, ix] - hy)
    order = np.argsort(r, kind="stable")
    iy, ix, r = iy[order], ix[order], r[order]
    band = np.floor(r / BAND_M).astype(np.int64)
    edges = np.flatnonzero(np.diff(band)) + 1
    for chosen in np.split(np.arange(r.size), edges):
        out = np.zeros((chosen.size, 6))
        solve(mx[iy[chosen], ix[chosen]], my[iy[chosen], ix[chosen]], True, out)
        grid_out[iy[chosen], ix[chosen]] = out
        grid_v[iy[chosen], ix[chosen]] = out[:, 2]
        grid_p1[iy[chosen], ix[chosen]] = out[:, 4]
        done += chosen.size
        if progress is not None:
            progress(done, total)
    # Second sweep: every point with its read, on the first sweep's values.
    again_polar = polar_out.reshape(-1, 6).copy()
    solve(px.ravel(), py.ravel(), False, again_polar)
    again_grid = grid_out[iy, ix].copy()
    solve(mx[iy, ix], my[iy, ix], False, again_grid)
    change = max(
        float(np.abs(again_polar[:, 2] - polar_out.reshape(-1, 6)[:, 2]).max()),
        float(np.abs(again_grid[:, 2] - grid_out[iy, ix, 2]).max()) if iy.size else 0.0,
    )

    nan = np.where(on, 1.0, np.nan)
    return GreenMap(
        green=green,
        x0_m=grid[0],
        y0_m=grid[1],
        resolution_m=float(resolution_m),
        expected_putts=grid_out[..., 2] * nan,
        expected_putts_se=grid_out[..., 3] * nan,
        p_one_putt=grid_out[..., 4] * nan,
        p_three_putt=grid_out[..., 5] * nan,
        read_aim_deg=-np.degrees(grid_out[..., 0]) * nan,  # the frame's +y is right
        read_pace_m=grid_out[..., 1] * nan,
        polar_expected=polar_v.copy(),
        polar_p_one=polar_p1.copy(),
        polar_p_three=polar_out[..., 5].copy(),
        putter=putter,
        n=int(n),
        seed=int(seed),
        sweep_change=change,
        elapsed_s=time.perf_counter() - started,
        settings={"dt_s": dt, "ds_max_m": ds, "band_m": BAND_M, "r_near_m": R_NEAR_M},
    )


def _on_green(green, x, y):
    """Whether the green's nearest node to each (x, y) is the green's."""
    s = green.surface
    ny, nx = s.on_green.shape
    ix = np.floor((x - s.x0_m) / s.cell_m + 0.5).astype(np.int64)
    iy = np.floor((y - s.y0_m) / s.cell_m + 0.5).astype(np.int64)
    inside = (ix >= 0) & (ix < nx) & (iy >= 0) & (iy < ny)
    out = np.zeros(x.shape, dtype=bool)
    out[inside] = s.on_green[iy[inside], ix[inside]] != 0
    return out
