"""A hole's green to putt on: its grid of heights (``roll.Surface``), which nodes are the
green's, the pin, the green's speed and its drift.

The green is the hole's own ground (``Hole.terrain_over``: the hole's grid, zones and heights)
over the box of the green that holds the pin plus a margin of ``MARGIN_CELLS`` nodes, at the
green's spacing, which may be finer than the hole's (``cell_m``, default
``DEFAULT_GREEN_CELL_M``): its heights sampled from the hole's ground (the elevation file's
interpolation, or the analytic shape) at that spacing, a node the green's where the hole's zones
put the green. The green's speed is the rolling resistance
of the hole's green turf (``[hole.turf.green] rho_g``; its Stimp reading is
``physics.turf.stimp_from_rho_g``): the approach's roll and the putts roll on one green.

A green to putt on is refused (``GreenError``, one line) where its speed is outside the Stimp
readings of ``greens.STIMP_RANGE_FT`` (rho_g 0, no rolling resistance, an infinite Stimp, among
them), and where a ball can rest nowhere on it: every point of every cell of its grid that touches
a node of the green is steeper than its stopping slope (tan(beta) > rho_g, the roll's own test of
a ball at rest, ``roll.roll_core``), so that every putt and every ball played onto it would run
off it.
"""

import math
from dataclasses import dataclass

import numpy as np

from mcrun.hole.errors import HoleError
from mcrun.hole.zones import ZONE_INDEX, ZONE_KINDS, contains, pin_off_green
from mcrun.physics.turf import rho_g_from_stimp, stimp_from_rho_g
from mcrun.putting.greens import (
    DRIFT_MM_PER_M_BENTGRASS,
    STIMP_RANGE_FT,
    STIMP_RANGE_M,
    drift_sd,
)
from mcrun.putting.roll import Surface
from mcrun.strokes.baseline import FOOT_M

__all__ = [
    "DEFAULT_GREEN_CELL_M",
    "Green",
    "GreenError",
    "check_green_speed",
    "green_of_hole",
    "least_slope",
]

DEFAULT_GREEN_CELL_M = 0.25
MARGIN_CELLS = 2
GREEN = ZONE_INDEX["green"]


class GreenError(HoleError):
    """A hole whose green cannot be putted on; its message is one line."""


@dataclass(frozen=True)
class Green:
    """A green on a grid (``surface``, the hole's frame: x from the tee towards the pin, y to the
    right), its pin (m), rolling resistance ``rho_g`` and drift (``greens``); ``source`` names
    it in messages."""

    surface: Surface
    pin_xy_m: tuple
    rho_g: float
    source: str
    drift_mm_per_m: float = DRIFT_MM_PER_M_BENTGRASS

    @property
    def drift_sd(self):
        """The rolling ball's heading's random walk (rad per sqrt(m), ``greens.drift_sd``)."""
        return drift_sd(self.drift_mm_per_m)

    @property
    def stimp_m(self):
        return float(stimp_from_rho_g(self.rho_g))

    @property
    def cell_m(self):
        return self.surface.cell_m

    def nodes_xy(self):
        """(x, y) of every node of the grid: two (ny, nx) arrays."""
        s = self.surface
        ny, nx = s.height_m.shape
        return np.meshgrid(s.x0_m + np.arange(nx) * s.cell_m, s.y0_m + np.arange(ny) * s.cell_m)

    def area_m2(self):
        return float(self.surface.on_green.sum()) * self.cell_m**2

    def key(self):
        """What the green's maps depend on: its heights, nodes, pin, speed and drift (bytes)."""
        s = self.surface
        head = np.array([s.x0_m, s.y0_m, s.cell_m, *self.pin_xy_m, self.rho_g,
                         self.drift_mm_per_m], dtype=float)  # fmt: skip
        return head.tobytes() + s.height_m.tobytes() + s.on_green.tobytes()


# The rolling resistance of a green to putt on: that of the Stimp readings allowed.
RHO_G_RANGE = (float(rho_g_from_stimp(STIMP_RANGE_M[1])), float(rho_g_from_stimp(STIMP_RANGE_M[0])))


def check_green_speed(hole):
    """``hole``, whose green turf's rho_g is that of a green to putt on (``RHO_G_RANGE``, a
    Stimp of ``greens.STIMP_RANGE_FT``); GreenError naming the hole's file and the field
    otherwise."""
    rho_g = float(hole.turf["green"].rho_g)
    lo, hi = RHO_G_RANGE
    if not lo <= rho_g <= hi:
        stimp_ft = stimp_from_rho_g(rho_g) / FOOT_M
        raise GreenError(
            f"{hole.source}: 'turf.green.rho_g' = {rho_g:g} (a Stimp of {stimp_ft:.3g} ft): "
            f"allowed for a green to putt on: {lo:.4f} to {hi:.4f}, a Stimp of "
            f"{STIMP_RANGE_FT[0]:g} ft to {STIMP_RANGE_FT[1]:g} ft"
        )
    return hole


def least_slope(surface):
    """The least slope (tan) anywhere on the green's grid ``surface``: over every cell with a node
    of the green, the least gradient of its bilinear height (exact: the gradient's x part
    varies along y only, its y part along x only, each linearly). inf without such a cell."""
    h = surface.height_m
    on = surface.on_green != 0
    if h.shape[0] < 2 or h.shape[1] < 2:
        return math.inf
    gx = np.diff(h, axis=1) / surface.cell_m  # (ny, nx - 1): along the cell's lower/upper edges
    gy = np.diff(h, axis=0) / surface.cell_m  # (ny - 1, nx): along its left/right edges

    def least(a, b):  # the least |a + t (b - a)| over t in [0, 1]
        return np.where(a * b <= 0.0, 0.0, np.minimum(np.abs(a), np.abs(b)))

    sx = least(gx[:-1, :], gx[1:, :])  # (ny - 1, nx - 1)
    sy = least(gy[:, :-1], gy[:, 1:])
    touches = on[:-1, :-1] | on[:-1, 1:] | on[1:, :-1] | on[1:, 1:]
    if not touches.any():
        return math.inf
    return float(np.hypot(sx, sy)[touches].min())


def green_of_hole(hole, cell_m=None, elevation=None, elevation_crs=None, stimp_m=None,
                  drift_mm_per_m=DRIFT_MM_PER_M_BENTGRASS):  # fmt: skip
    """The Green of ``hole`` (a ``mcrun.hole.Hole``): the green that holds its pin, on a grid of
    ``cell_m`` (default ``DEFAULT_GREEN_CELL_M``, or the hole's own cell where that is finer),
    its heights from the hole's ground or from ``elevation``, a survey of the green alone (any
    file ``mcrun.hole.elevation`` reads; ``elevation_crs`` where it does not say); its speed the
    hole's green turf's, or the Stimp reading ``stimp_m`` (m) where given; its drift
    ``drift_mm_per_m``. GreenError (one
    line) when the pin is on no green of the hole's zones, the survey does not cover the green,
    the green's speed is not a green's (``check_green_speed``) or a ball can rest nowhere on it
    (``least_slope`` above its stopping slope, rho_g)."""
    if stimp_m is None:
        check_green_speed(hole)
    cell = min(DEFAULT_GREEN_CELL_M, hole.cell_m) if cell_m is None else float(cell_m)
    px, py = hole.pin_xy
    polygons = [p for kind, p in hole.zones if kind == "green" and contains(p, px, py)]
    if not polygons:
        raise GreenError(
            f"{hole.source}: the pin is on no green of the hole's zones: putting on the green "
            "needs a golf=green polygon around the pin (a hole without a map: 'surface' = "
            "'green')"
        )
    rings = np.concatenate([ring for polygon in polygons for ring in polygon])
    margin = MARGIN_CELLS * cell
    x_min, y_min = rings.min(axis=0) - margin
    x_max, y_max = rings.max(axis=0) + margin
    # Within the hole's grid: the green's heights come from the hole's ground there.
    ex = hole.extent_m
    box = (max(x_min, ex[0]), min(x_max, ex[1]), max(y_min, ex[2]), min(y_max, ex[3]))
    ground = hole.terrain_over(box, cell)  # the hole's ground, at the green's spacing
    x0, y0 = ground.x0_m, ground.y0_m
    ny, nx = ground.height_m.shape
    on = np.ascontiguousarray(ground.zone == GREEN, dtype=np.uint8)
    if not on.any():  # (a sliver of a green: it was said to be too steep to rest on)
        raise GreenError(f"{hole.source}: the green around the pin covers no node of its grid "
                         f"of {cell:g} m: a green mapped smaller than its cell")  # fmt: skip
    ix, iy = round((px - x0) / cell), round((py - y0) / cell)
    if 0 <= iy < ny and 0 <= ix < nx and not on[iy, ix]:
        kind = ZONE_KINDS[ground.zone[iy, ix]]  # (a bunker over the pin: every putt 3 putts)
        raise GreenError(f"{hole.source}: {pin_off_green(kind, px, py, cell)}")
    if elevation is not None:
        height = _surveyed(hole, elevation, elevation_crs, x0, y0, cell, nx, ny, on)
    else:
        height = ground.height_m
    surface = Surface(np.ascontiguousarray(height, dtype=float), on, float(x0), float(y0), cell)
    if stimp_m is None:
        rho_g = float(hole.turf["green"].rho_g)
        speed = (f"'turf.green.rho_g' = {rho_g:g}, a Stimp of "
                 f"{stimp_from_rho_g(rho_g) / FOOT_M:.1f} ft")  # fmt: skip
    else:
        rho_g, speed = float(rho_g_from_stimp(stimp_m)), f"--stimp {stimp_m / FOOT_M:g} ft"
    least = least_slope(surface)
    if least > rho_g:
        raise GreenError(
            f"{hole.source}: the green is steeper than its stopping slope everywhere (at least "
            f"{100 * least:.1f} %, against {100 * rho_g:.1f} % for {speed}): a ball can rest "
            "nowhere on it, so no putt on it can be valued"
        )
    return Green(surface, (float(px), float(py)), rho_g, hole.source, float(drift_mm_per_m))


def _surveyed(hole, path, crs, x0, y0, cell, nx, ny, on):
    """Heights (m) of the green's nodes from the survey ``path``: the nodes off the green that it
    does not cover take the heights of the covered ones around them (they only bound the
    green)."""
    from mcrun.hole.elevation import load_elevation

    if hole.frame is None:
        raise GreenError(f"{hole.source}: 'putting.elevation' needs the hole on the Earth: a "
                         "'map', or 'tee' and 'pin'")  # fmt: skip
    try:
        survey = load_elevation(path, crs=crs)
    except (OSError, ValueError) as err:
        raise GreenError(f"{hole.source}: 'putting.elevation': {' '.join(str(err).split())}"
                         ) from None  # fmt: skip
    x, y = np.meshgrid(x0 + np.arange(nx) * cell, y0 + np.arange(ny) * cell)
    lon, lat = hole.frame.to_lonlat(x, y)
    height = np.asarray(survey.height_m(lon, lat), dtype=float)
    missing = ~np.isfinite(height)
    if (missing & (on != 0)).any():
        iy, ix = np.argwhere(missing & (on != 0))[0]
        raise GreenError(
            f"{hole.source}: 'putting.elevation' {path} does not cover the green: "
            f"{int((missing & (on != 0)).sum())} of its {int(on.sum())} nodes have no height, "
            f"first at x = {x[iy, ix]:.1f} m, y = {y[iy, ix]:.1f} m"
        )
    # Grown outwards from the covered nodes: each uncovered node next to covered ones takes
    # their mean, ring after ring.
    while missing.any():
        known = np.where(missing, 0.0, height)
        count = np.zeros(height.shape)
        total = np.zeros(height.shape)
        for dy, dx in ((-1, 0), (1, 0), (0, -1), (0, 1)):
            shifted_known = np.roll(~missing, (dy, dx), axis=(0, 1))
            shifted = np.roll(known, (dy, dx), axis=(0, 1))
            edge = np.zeros(height.shape, dtype=bool)  # np.roll wraps: not across the edges
            if dy:
                edge[0 if dy > 0 else -1, :] = True
            if dx:
                edge[:, 0 if dx > 0 else -1] = True
            ok = shifted_known & ~edge
            count += ok
            total += np.where(ok, shifted, 0.0)
        grow = missing & (count > 0)
        if not grow.any():
            break
        height[grow] = total[grow] / count[grow]
        missing &= ~grow
    return height
