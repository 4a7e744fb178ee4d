"""A putt struck: the putter's read of the green, its errors and the green's drift, on the one
roll (``roll.roll_core``, or ``roll.roll_lanes`` for many at once: the same steps). Each is
done here and nowhere else:

- the green a putt is struck on (``PuttGreen``): a plane (``roll.NO_SURFACE`` and its slope) or
  a grid (a ``roll.Surface``), its rolling resistance, its drift and the roll's steps;
- the putter in the kernels' units (``Stroke``, from a ``putter.Putter``);
- the read of the slope: the putter perceives the green tilted by a plane it misreads, of fall
  vector ``read_sd (z_x, z_y)`` (slope as tan; z standard normals per putt, in the green's
  frame: a misread as likely in any direction), and strikes for that green (``tilt``);
- the pace (``pace_speed_mps``): a pace of p metres is struck, by energy on the perceived green,
  to roll the ball to the hole and p metres on where the green beyond the hole is level except
  for ``pace_slope_share`` of its slope: 1 rolls it p past on the green as perceived, 0 gets to
  the hole at the speed of a level green's p (Pelz's 17 in is a level green's). The share is
  fitted with the putter (``putter``: the Tour's leaves uphill and downhill);
- the start line (``centre_line``): the one on which the error-free putt at that speed rolls over
  the hole's centre on the perceived green;
- the strike (``strike``; ``struck_velocity``, then ``strike_lanes`` for many putts at once,
  ``strike_all`` on every thread): the chosen line and speed missed by the putter's start-line
  and relative speed errors, rolled on the green as it is, with its drift;
- holing out with the putter's own read (``hole_out_from``): the pace ``Stroke.pace_m``, the
  centre line, putt after putt until the ball drops.

A putt's errors are the normals ``z[k] = (line, speed, read x, read y)`` of
``putter.putter_errors`` and the drift's ``keys[k]``: the same for every read a search tries
(common random numbers).
"""

import math
from typing import NamedTuple

from numba import njit, prange, uint64

from mcrun.physics.constants import G_MPS2
from mcrun.putting.cup import HOLE_RADIUS_M
from mcrun.putting.roll import (
    LANES,
    MAX_TIME_S,
    NO_SURFACE,
    ROLLING_FACTOR,
    STATUS_HOLED,
    STATUS_STOPPED,
    Surface,
    grid_height,
    roll_core,
    roll_lanes,
)

__all__ = [
    "MAX_PUTTS",
    "PuttGreen",
    "Stroke",
    "centre_line",
    "hole_out_from",
    "pace_speed_mps",
    "plane_putt_green",
    "strike",
    "strike_all",
    "strike_lanes",
    "struck_velocity",
    "tilt",
]

MAX_PUTTS = 10
# The start lines the read looks between (rad, either side of the line to the hole), and how
# close (m) the error-free putt must pass the hole's centre.
READ_SPAN_RAD = 0.6
READ_TOL_M = 0.0005
# Where a line falls faster than the green holds a ball, the energy of a tenth of the rolling
# resistance's stands in for the slope's (a putt is still struck towards the hole).
LEAST_WORK_SHARE = 0.1


class PuttGreen(NamedTuple):
    """The green a putt is struck on: a grid ``surface`` (a ``roll.Surface``; the hole's frame,
    horizontal distances) or, where it is ``roll.NO_SURFACE``, the plane of ``slope_tan``
    falling towards (``fall_x``, ``fall_y``) (the putt's frame, distances along the plane); its
    rolling resistance ``rho_g``, its drift ``drift_sd`` (rad per sqrt(m)) and the roll's steps:
    at most ``dt_s`` and, on a grid, ``ds_max_m``."""

    surface: Surface
    slope_tan: float
    fall_x: float
    fall_y: float
    rho_g: float
    drift_sd: float
    dt_s: float
    ds_max_m: float


class Stroke(NamedTuple):
    """A putter in the kernels' units: the standard deviations of the start line (rad), of the
    speed (relative) and of each component of the misread tilt (tan), and its pace (m past the
    hole)."""

    line_sd_rad: float
    speed_sd: float
    read_sd: float
    pace_m: float
    pace_slope_share: float


def stroke_of(putter):
    """The ``Stroke`` of a ``putter.Putter``."""
    return Stroke(math.radians(putter.line_sd_deg), putter.speed_sd_pct / 100.0,
                  putter.read_sd_pct / 100.0, float(putter.pace_m),
                  float(putter.pace_slope_share))  # fmt: skip


@njit(cache=True)
def plane_putt_green(slope_tan, fall_x, fall_y, rho_g, drift_sd, dt_s):
    """The ``PuttGreen`` of a plane."""
    return PuttGreen(NO_SURFACE, slope_tan, fall_x, fall_y, rho_g, drift_sd, dt_s, 0.0)


@njit(cache=True, inline="always")
def _is_grid(green):
    return green.surface.height_m.shape[0] > 0


@njit(cache=True)
def height_m(x, y, green):
    """The green's height (m) at (x, y): the grid's bilinear height, or the plane's."""
    if _is_grid(green):
        return grid_height(x, y, green.surface)
    sin_b = green.slope_tan / math.sqrt(1.0 + green.slope_tan * green.slope_tan)
    return -sin_b * (green.fall_x * x + green.fall_y * y)


@njit(cache=True, inline="always")
def tilt(stroke, z):
    """The misread tilt (fall vector x, y) of a putt with the errors ``z`` (line, speed, read x,
    read y)."""
    return stroke.read_sd * z[2], stroke.read_sd * z[3]


@njit(cache=True)
def pace_speed_mps(x, y, hx, hy, pace_m, share, green, tilt_x, tilt_y):
    """The start speed (m/s) of a putt from (x, y) struck for ``pace_m`` on the green read with
    the tilt (``tilt_x``, ``tilt_y``): by energy, v^2 = 2 k max(rho_g c (L + p) + dz + share dz',
    0.1 rho_g c (L + p)), k = (5/7) g, L the distance to the hole, dz the rise from the ball to
    the hole and dz' from the hole to p past it on the perceived green, c the cosine of the
    plane's slope (1 on a grid, whose distances are horizontal)."""
    length = math.hypot(hx - x, hy - y)
    ux, uy = (hx - x) / length, (hy - y) / length
    c = 1.0
    if not _is_grid(green):
        c = 1.0 / math.sqrt(1.0 + green.slope_tan * green.slope_tan)
    z_hole = height_m(hx, hy, green)
    rise = z_hole - height_m(x, y, green) - tilt_x * (hx - x) - tilt_y * (hy - y)
    px, py = hx + pace_m * ux, hy + pace_m * uy
    beyond = height_m(px, py, green) - z_hole - tilt_x * (px - hx) - tilt_y * (py - hy)
    work = green.rho_g * c * (length + pace_m)
    k = ROLLING_FACTOR * G_MPS2
    return math.sqrt(2.0 * k * max(work + rise + share * beyond, LEAST_WORK_SHARE * work))


@njit(cache=True)
def _roll(x, y, vx, vy, hx, hy, cup, green, tilt_x, tilt_y, drift_sd, key):
    return roll_core(x, y, vx, vy, green.slope_tan, green.fall_x, green.fall_y, green.rho_g,
                     hx, hy, cup, green.dt_s, MAX_TIME_S, green.surface, green.ds_max_m, tilt_x,
                     tilt_y, drift_sd, key)  # fmt: skip


@njit(cache=True)
def _miss_m(x, y, hx, hy, angle, speed, green, tilt_x, tilt_y, ux, uy):
    """How far left (+) of the hole's centre the error-free putt passes (the cup ignored)."""
    out = _roll(x, y, speed * math.cos(angle), speed * math.sin(angle), hx, hy, False, green,
                tilt_x, tilt_y, 0.0, uint64(0))  # fmt: skip
    return (out[5] - hx) * (-uy) + (out[6] - hy) * ux


@njit(cache=True)
def centre_line(x, y, hx, hy, speed, green, tilt_x, tilt_y):
    """The start line (rad, from the line to the hole, + towards the frame's +y) on which a putt
    from (x, y) at ``speed`` rolls over the hole's centre on ``green`` read with the tilt
    (``tilt_x``, ``tilt_y``): regula falsi (Illinois) within +-READ_SPAN_RAD; beyond reach, the
    side that misses least."""
    length = math.hypot(hx - x, hy - y)
    ux, uy = (hx - x) / length, (hy - y) / length
    base = math.atan2(uy, ux)
    if not _is_grid(green) and green.slope_tan == 0.0 and tilt_x == 0.0 and tilt_y == 0.0:
        return 0.0  # a level green read level: straight at the hole
    a, b = -READ_SPAN_RAD, READ_SPAN_RAD
    fa = _miss_m(x, y, hx, hy, base + a, speed, green, tilt_x, tilt_y, ux, uy)
    fb = _miss_m(x, y, hx, hy, base + b, speed, green, tilt_x, tilt_y, ux, uy)
    if fa * fb > 0.0:
        return a if abs(fa) < abs(fb) else b
    side = 0
    c = 0.0
    for _ in range(40):
        c = (a * fb - b * fa) / (fb - fa)
        fc = _miss_m(x, y, hx, hy, base + c, speed, green, tilt_x, tilt_y, ux, uy)
        if abs(fc) < READ_TOL_M:
            return c
        if fc * fb > 0.0:
            b, fb = c, fc
            if side == -1:
                fa /= 2.0
            side = -1
        else:
            a, fa = c, fc
            if side == 1:
                fb /= 2.0
            side = 1
    return c


@njit(cache=True, inline="always")
def struck_velocity(x, y, hx, hy, aim_rad, speed, stroke, z_line, z_speed):
    """The velocity (m/s, x and y) of the putt from (x, y) aimed ``aim_rad`` from the line to
    the hole at ``speed``, missed by the errors ``z_line`` and ``z_speed`` (standard normals)."""
    angle = math.atan2(hy - y, hx - x) + aim_rad + stroke.line_sd_rad * z_line
    v = max(0.0, speed * (1.0 + stroke.speed_sd * z_speed))
    return v * math.cos(angle), v * math.sin(angle)


@njit(cache=True)
def strike(x, y, hx, hy, aim_rad, speed, green, stroke, z_line, z_speed, key):
    """The putt from (x, y) aimed ``aim_rad`` from the line to the hole at ``speed``, missed by
    the errors ``z_line`` and ``z_speed`` (standard normals), rolled on the green as it is with
    its drift (from ``key``) and the cup: the roll's (status, x, y, time, closest, cx, cy)."""
    vx, vy = struck_velocity(x, y, hx, hy, aim_rad, speed, stroke, z_line, z_speed)
    return _roll(x, y, vx, vy, hx, hy, True, green, 0.0, 0.0, green.drift_sd, key)


@njit(cache=True)
def strike_lanes(x, y, vx, vy, keys, hx, hy, green, status, end_x, end_y):
    """``strike``'s roll of n putts at once (``roll.roll_lanes``), the i-th from (x[i], y[i]) at
    the velocity (vx[i], vy[i]) (``struck_velocity``) with the drift's key keys[i]: its status
    and where it ended into status[i], end_x[i], end_y[i], as ``strike`` gives them."""
    roll_lanes(x, y, vx, vy, keys, green.slope_tan, green.fall_x, green.fall_y, green.rho_g, hx,
               hy, green.dt_s, MAX_TIME_S, green.surface, green.ds_max_m, green.drift_sd,
               status, end_x, end_y)  # fmt: skip


# The putts of one task of ``strike_all`` on threads: a few lane groups (``roll.LANES``) each.
STRIKE_PART = 16 * LANES


@njit(cache=True)
def strike_all(x, y, vx, vy, keys, hx, hy, green, status, end_x, end_y, on_threads):
    """``strike_lanes``, on every thread where ``on_threads`` (a plane green's putt: thousands
    of first putts; a map's solver, on threads of its own, strikes one lane group after
    another), in parts of ``STRIKE_PART`` putts: each putt's roll is its own whatever part or
    lane it takes, so that the putts are the same bit for bit either way."""
    if on_threads and x.shape[0] > STRIKE_PART:
        s = green.surface
        _strike_parts(x, y, vx, vy, keys, hx, hy, s.height_m, s.on_green, s.x0_m, s.y0_m,
                      s.cell_m, green[1:], status, end_x, end_y)  # fmt: skip
    else:
        strike_lanes(x, y, vx, vy, keys, hx, hy, green, status, end_x, end_y)


@njit(cache=True, parallel=True)
def _strike_parts(x, y, vx, vy, keys, hx, hy, height_m, on_green, x0_m, y0_m, cell_m, plane,
                  status, end_x, end_y):  # fmt: skip
    """``strike_all`` on threads, a part of ``STRIKE_PART`` putts a task. The green comes in its
    parts (its surface's, then the rest of the ``PuttGreen``, ``plane``), put together in the
    loop: Numba's parallel loops take no tuple that holds arrays."""
    n = x.shape[0]
    for part in prange((n + STRIKE_PART - 1) // STRIKE_PART):
        a, b = part * STRIKE_PART, min(n, (part + 1) * STRIKE_PART)
        green = PuttGreen(Surface(height_m, on_green, x0_m, y0_m, cell_m), *plane)
        strike_lanes(x[a:b], y[a:b], vx[a:b], vy[a:b], keys[a:b], hx, hy, green, status[a:b],
                     end_x[a:b], end_y[a:b])  # fmt: skip


@njit(cache=True)
def own_read(x, y, hx, hy, pace_m, green, stroke, z):
    """The putter's own read of a putt from (x, y) at ``pace_m`` with the errors ``z``:
    (start line rad, speed m/s) on the green as it perceives it."""
    tx, ty = tilt(stroke, z)
    speed = pace_speed_mps(x, y, hx, hy, pace_m, stroke.pace_slope_share, green, tx, ty)
    return centre_line(x, y, hx, hy, speed, green, tx, ty), speed


@njit(cache=True)
def hole_out_from(x, y, hx, hy, green, stroke, z, keys, k0):
    """Putt from (x, y) with the putter's own read, the k-th putt with the errors z[k] and the
    drift's keys[k], from k = k0 until the ball drops: (putts, status of the first, its rest x,
    y). The putts are MAX_PUTTS - k0 where the ball is not down by then, never rests (it runs
    off a plane steeper than its stopping slope) or leaves a grid's green (a chip, which holing
    out does not play: the map values it, ``rest``)."""
    first_status, fx, fy = -1, x, y
    for k in range(k0, MAX_PUTTS):
        if math.hypot(hx - x, hy - y) <= HOLE_RADIUS_M:  # at rest over the hole: in
            return k - k0, first_status, fx, fy
        aim, speed = own_read(x, y, hx, hy, stroke.pace_m, green, stroke, z[k])
        out = strike(x, y, hx, hy, aim, speed, green, stroke, z[k, 0], z[k, 1], keys[k])
        if k == k0:
            first_status, fx, fy = out[0], out[1], out[2]
        if out[0] == STATUS_HOLED:
            return k + 1 - k0, first_status, fx, fy
        if out[0] != STATUS_STOPPED:
            break  # never rests: not holed
        x, y = out[1], out[2]
    return MAX_PUTTS - k0, first_status, fx, fy
