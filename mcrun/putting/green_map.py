"""Expected putts from every point of a green: the map, with the read (start line and pace)
at every point, the share of one-putts and of three putts or more.

The value of a point is the expected number of strokes to hole out from there, every putt read
as ``read`` says, the later putts valued by the map itself:

    V(p) = min over reads of  E[ 1 + V(where the putt stopped) ],   V(in the hole) = 0,

where the reads are, with ``read="own"`` (the default), the putter's own alone: its pace
(``Putter.pace_m``) on the centre line it perceives, the putter its calibration holds to the
Tour's putts; with ``read="best"``, those of ``mcrun.putting.read.search`` (the paces
``read.PACES_M``, each on the centre line the putter perceives, then start lines
``read.AIM_STEPS_DEG`` either side of the best): the best a putter with the same errors could
choose. Over ``n`` putts whose errors (start line, speed, read, the green's drift: ``putter``,
``stroke``) are common to every read and every point (common random numbers: the map is smooth,
and its differences are the ground's). A putt that leaves the green is a chip from where it
left: 1 + the baseline's fairway strokes from there (the fringe's lie, ``hole.zones``).

The map's points: rings around the hole (``POLAR_RADII_M`` x ``POLAR_ANGLES``, where most
second putts stop, so that the short putts' values are resolved finely), then the nodes of a
grid of ``resolution_m`` on the green. A stop point is valued by bilinear interpolation: in the
rings within ``R_NEAR_M`` of the hole (a ball within ``TAP_IN_M`` is holed with the next putt),
on the grid beyond (among its nodes on the green). The points are solved outwards from the hole
in bands of distance (a Gauss-Seidel sweep: each band reads the values of the bands inside it,
and the baseline's putts for the points not yet solved); then sweeps of every point with its read,
each on the last one's values, until no value changes by more than ``SWEEP_TOLERANCE`` (at most
``MAX_SWEEPS``; ``GreenMap.sweep_change`` is the last sweep's largest change, ``sweeps`` their
number). Within a band the points are independent, so the map is the same whatever the number
of threads.
"""

import math
import time
from dataclasses import dataclass, field

import numba
import numpy as np
from numba import njit

from mcrun.executor import on_threads
from mcrun.hole.hole import PUTTING_READS as READS
from mcrun.putting.green import GreenError
from mcrun.putting.putter import PUTTERS, putter_errors
from mcrun.putting.read import AIM_STEPS_DEG, PACES_M, READ_NODES, search, value_read
from mcrun.putting.rest import (
    CHIP_MAX_M,
    CHIP_STEP_M,
    POLAR_ANGLES,
    POLAR_RADII_M,
    R_NEAR_M,
    TAP_IN_M,
    bilinear,
    map_value,
    map_values,
    polar,
)
from mcrun.putting.stroke import PuttGreen, stroke_of
from mcrun.strokes.baseline import tour_baseline

__all__ = [
    "DEFAULT_N",
    "DEFAULT_READ",
    "DEFAULT_RESOLUTION_M",
    "READS",
    "GreenMap",
    "expected_putts_map",
    "read_candidates",
]

DEFAULT_RESOLUTION_M = 0.5
DEFAULT_N = 200
# The roll's steps on a green: at most MAP_DT_S and half a cell of the green's grid (the
# plane's closed forms are met within 0.1 mm at these steps: tests/test_green_map.py).
MAP_DT_S = 0.05
BAND_M = 0.25
# A point's solution: offset, pace, mean, se, p1, p3, start line, then its read's lines.
_OUT = 7 + len(READ_NODES)
# The sweeps after the first: until no point's value changes by more than SWEEP_TOLERANCE.
SWEEP_TOLERANCE = 0.001
MAX_SWEEPS = 8
# How each putt is read (``READS``): "own", the putter's own read (its pace on the centre line it
# perceives: the read its calibration holds to the Tour's putts); "best", the best of
# ``read.search``'s paces and start lines (the least expected putts under the putter's errors).
DEFAULT_READ = "own"


@njit(cache=True, nogil=True)
def _solve_points(xs, ys, read, hx, hy, green, stroke, z, keys, rest, paces, aim_steps, out):
    """Solve each point (xs[k], ys[k]) for the hole at (hx, hy): with ``read``, search its read
    (``read.search``) and write out[k] = (offset, pace, mean, se, p1, p3, start line, its
    ``read.read_lines``...), the offset off the perceived centre line and the start line (the
    centre line without error plus the offset) in rad; without, value the read already in
    out[k]."""
    tried = np.zeros((paces.shape[0] + aim_steps.shape[0], 3))
    putts = np.zeros(z.shape[0])
    for k in range(xs.shape[0]):
        lines = out[k, 7:]
        if read:
            best = search(xs[k], ys[k], hx, hy, green, stroke, z, keys, rest, paces, aim_steps,
                          tried, putts, lines)  # fmt: skip
            for j in range(6):
                out[k, j] = best[j]
            out[k, 6] = best[0] + lines[0]
        else:
            m, se, p1, p3 = value_read(xs[k], ys[k], hx, hy, out[k, 1], out[k, 0], lines, green,
                                       stroke, z, keys, rest, putts)  # fmt: skip
            out[k, 2], out[k, 3], out[k, 4], out[k, 5] = m, se, p1, p3


@dataclass
class GreenMap:
    """Expected putts over a green: on the grid of ``resolution_m`` (node [iy, ix] at
    (x0_m + ix resolution_m, y0_m + iy resolution_m), hole frame), NaN off the green:
    ``expected_putts`` and its standard error, ``p_one_putt``, ``p_three_putt`` (three or more
    strokes), the read's start line ``read_aim_deg`` (+ left of the hole, as ``mcrun putt``: the
    centre line the putter perceives without error, plus the read's offset) and pace
    ``read_pace_m`` (past the hole); the rings around the hole (``polar_*``), the settings,
    ``sweeps`` (after the first) and ``sweep_change`` (the largest change of a point's value in
    the last)."""

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
    sweeps: int = 1

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
        rest = map_values(self.polar_expected, self.polar_p_one,
                          (self.x0_m, self.y0_m, self.resolution_m),
                          np.nan_to_num(self.expected_putts), np.nan_to_num(self.p_one_putt),
                          valid, _chip_table())  # fmt: skip
        return _values(x, y, hx, hy, rest, self.polar_p_three, np.nan_to_num(self.p_three_putt))

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
def _values(x, y, hx, hy, rest, polar_p3, grid_p3):
    """(expected putts, one-putt share, share of three or more) at each (x[k], y[k])."""
    n = x.shape[0]
    v = np.empty(n)
    p1 = np.empty(n)
    p3 = np.empty(n)
    x0, y0, cell = rest.grid
    for k in range(n):
        v[k], p1[k] = map_value(x[k], y[k], hx, hy, rest)
        dx, dy = x[k] - hx, y[k] - hy
        r = math.hypot(dx, dy)
        if r < TAP_IN_M:
            p3[k] = 0.0
        elif r < R_NEAR_M:
            p3[k] = polar(polar_p3, r, dx, dy)
        else:
            p, w = bilinear(grid_p3, rest.grid_valid, (x[k] - x0) / cell, (y[k] - y0) / cell)
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


def read_candidates(read, putter):
    """(paces m, start lines rad off the perceived centre line) that ``read.search`` tries at
    every point of a map under ``read`` (``READS``) for ``putter`` (a ``Putter``): the own
    read's pace alone, or the search's paces then start lines."""
    if read not in READS:
        raise ValueError(f"read {read!r}: choose {', '.join(READS)}")
    if read == "own":
        return np.array([putter.pace_m]), np.zeros(0)
    return np.array(PACES_M, dtype=float), np.radians(np.array(AIM_STEPS_DEG, dtype=float))


def map_grid(green, resolution_m):
    """The grid of a map of ``green`` at ``resolution_m``, over the green's grid: its first
    node (gx0, gy0), its nodes' x and y (m, hole frame) and which are on the green; GreenError
    where none is (a map of no point was NaN everywhere)."""
    xs_g, ys_g = green.nodes_xy()
    gx0 = math.floor(xs_g.min() / resolution_m) * resolution_m
    gy0 = math.floor(ys_g.min() / resolution_m) * resolution_m
    nx = int(math.floor((xs_g.max() - gx0) / resolution_m)) + 1
    ny = int(math.floor((ys_g.max() - gy0) / resolution_m)) + 1
    mx, my = np.meshgrid(gx0 + np.arange(nx) * resolution_m, gy0 + np.arange(ny) * resolution_m)
    on = _on_green(green, mx, my)
    if not on.any():
        raise GreenError(f"{green.source}: no point of the map's grid of {resolution_m:g} m is "
                         f"on the green ({green.area_m2():.2f} m^2): a finer resolution, or a "
                         "green mapped larger")  # fmt: skip
    return gx0, gy0, mx, my, on


def expected_putts_map(green, putter="tour", n=DEFAULT_N, seed=0,
                       resolution_m=DEFAULT_RESOLUTION_M, threads=None, progress=None,
                       read=DEFAULT_READ):  # fmt: skip
    """The GreenMap of ``green`` (a ``putting.green.Green``) for ``putter`` (a name of
    ``PUTTERS`` or a ``Putter``), ``n`` putts per read with errors seeded by ``seed``, on a grid
    of ``resolution_m``, every putt read as ``read`` says (``READS``). ``progress(done,
    total)``: called as the points are solved."""
    started = time.perf_counter()
    if isinstance(putter, str):
        putter = PUTTERS[putter]
    threads = numba.get_num_threads() if threads is None else int(threads)
    surface = green.surface
    hx, hy = green.pin_xy_m
    z, keys = putter_errors(n, seed)
    z = np.ascontiguousarray(z[:, :1, :])
    keys = np.ascontiguousarray(keys[:, :1])
    putt_green = PuttGreen(surface, 0.0, 1.0, 0.0, float(green.rho_g), float(green.drift_sd),
                           MAP_DT_S, surface.cell_m / 2.0)  # fmt: skip
    stroke = stroke_of(putter)
    paces, aim_steps = read_candidates(read, putter)
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
    polar_out = np.zeros(px.shape + (_OUT,))

    gx0, gy0, mx, my, on = map_grid(green, resolution_m)
    grid = (float(gx0), float(gy0), float(resolution_m))
    grid_v = np.ascontiguousarray(np.where(on, base.expected("green", np.hypot(mx - hx, my - hy)),
                                           0.0))  # fmt: skip
    grid_p1 = np.zeros(mx.shape)
    grid_valid = np.ascontiguousarray(on, dtype=np.uint8)
    grid_out = np.full(mx.shape + (_OUT,), np.nan)
    # The values the solves read: these arrays, updated in place as the points are solved.
    rest = map_values(polar_v, polar_p1, grid, grid_v, grid_p1, grid_valid, chip)

    total = px.size + int(on.sum())
    done = 0

    def solve(xs, ys, read, out):
        """``_solve_points`` of the points (xs, ys) into ``out``, in slices on threads."""
        cuts = np.linspace(0, xs.size, min(xs.size, 4 * threads) + 1).astype(np.int64)

        def work(k):
            a, b = cuts[k], cuts[k + 1]
            _solve_points(xs[a:b], ys[a:b], read, hx, hy, putt_green, stroke, z, keys, rest,
                          paces, aim_steps, out[a:b])  # fmt: skip

        on_threads(work, len(cuts) - 1, threads)

    # First sweep: the rings, inside out, then the grid in bands of distance.
    for j in range(len(radii)):
        out = np.zeros((POLAR_ANGLES, _OUT))
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
        out = np.zeros((chosen.size, _OUT))
        solve(mx[iy[chosen], ix[chosen]], my[iy[chosen], ix[chosen]], True, out)
        grid_out[iy[chosen], ix[chosen]] = out
        grid_v[iy[chosen], ix[chosen]] = out[:, 2]
        grid_p1[iy[chosen], ix[chosen]] = out[:, 4]
        done += chosen.size
        if progress is not None:
            progress(done, total)
    # Then sweeps of every point with its read, each on the last one's values (Jacobi: the
    # values read are the last sweep's, whatever the order and the threads), until they settle.
    polar_flat = polar_out.reshape(-1, _OUT)
    sweeps, change = 0, math.inf
    while change > SWEEP_TOLERANCE and sweeps < MAX_SWEEPS:
        again_polar = polar_flat.copy()
        solve(px.ravel(), py.ravel(), False, again_polar)
        again_grid = grid_out[iy, ix].copy()
        solve(mx[iy, ix], my[iy, ix], False, again_grid)
        change = max(
            float(np.abs(again_polar[:, 2] - polar_flat[:, 2]).max()),
            float(np.abs(again_grid[:, 2] - grid_out[iy, ix, 2]).max()) if iy.size else 0.0,
        )
        polar_flat[:] = again_polar
        grid_out[iy, ix] = again_grid
        polar_v[:] = polar_out[..., 2]
        polar_p1[:] = polar_out[..., 4]
        grid_v[iy, ix] = again_grid[:, 2]
        grid_p1[iy, ix] = again_grid[:, 4]
        sweeps += 1

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
        read_aim_deg=-np.degrees(grid_out[..., 6]) * nan,  # the frame's +y is right
        read_pace_m=grid_out[..., 1] * nan,
        polar_expected=polar_v.copy(),
        polar_p_one=polar_p1.copy(),
        polar_p_three=polar_out[..., 5].copy(),
        putter=putter,
        n=int(n),
        seed=int(seed),
        sweep_change=change,
        elapsed_s=time.perf_counter() - started,
        settings={
            "dt_s": MAP_DT_S,
            "ds_max_m": surface.cell_m / 2.0,
            "band_m": BAND_M,
            "r_near_m": R_NEAR_M,
            "sweep_tolerance": SWEEP_TOLERANCE,
            "read": read,
        },
        sweeps=sweeps,
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
