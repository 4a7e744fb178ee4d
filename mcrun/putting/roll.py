"""The roll of a putt on a plane green, until it stops, drops or runs past a cap.

A putt starts in pure rolling (no skid phase: the ball is taken to leave the putter face rolling
without slipping, which is what a putter's loft and the first few centimetres of turf bring about;
the skid is left out). A ball rolling without slipping on a plane of slope angle ``beta``
accelerates down the fall line at (5/7) g sin(beta) and is slowed along its motion by the turf's
rolling resistance (5/7) rho_g g cos(beta) (A. R. Penner, "The physics of putting", Can. J. Phys.
80, 83-96 (2002); "The run of a golf ball", Can. J. Phys. 80, 931-940 (2002), eq. 9):

    a = (5/7) g (sin(beta) f_hat - rho_g cos(beta) v_hat),

``f_hat`` the fall line's direction, ``v_hat`` the ball's. rho_g comes from the green's Stimp
reading (``mcrun.physics.turf.rho_g_from_stimp``). A ball at rest stays so only where
tan(beta) <= rho_g (the stopping slope); on a steeper plane it never rests.

Two grounds, one roll:

- ``roll``, a plane green: x, y (m) in the plane of the green (distances along its surface, so
  that the equations above hold exactly), x from the ball's start towards the hole, y to the
  left; the slope is the same everywhere.
- ``roll_on``, a green on a grid of heights (``Surface``): x, y (m) in the horizontal plane of
  the hole's frame. The slope at a point is the gradient of the bilinear surface there: tan(beta)
  = |grad z|, the fall line -grad z / |grad z|. Distances are taken in the horizontal plane, not
  along the surface: on a green's slopes (under 5 %) the two differ by under 0.13 %. Each step
  takes the slope at its predicted midpoint, so the roll follows the grid's bends to second
  order in the step, and no step is longer than ``ds_max_m``. A ball that reaches a node that
  is not the green's stops there with ``STATUS_OFF_GREEN``: it is a chip from there.

Integration: classical Runge-Kutta (RK4) in time steps ``dt_s``; the last step before the ball
stops is solved in closed form (deceleration taken constant over it). A step is ``_step``;
``roll_core`` takes them one after the other for one ball, and ``roll_lanes`` for many putts
side by side (``LANES`` at once, each part of a step for every lane in turn), the same steps
bit for bit: a ball's step waits on its step before, a chain of square roots and divisions, so
that many balls keep the processor busy where one keeps it waiting (the putts of a green's map
roll about twice as fast).

Two things a real green and a real reader add (``roll_core``'s last arguments):

- the green's drift: a rolling ball's heading takes a random walk, turned after each step of
  length ds by an angle of mean 0 and standard deviation ``drift_sd`` sqrt(ds) (rad;
  ``drift_sd`` in rad per sqrt(m)), uniform (a walk of many steps is normal whatever its
  steps' law, and a uniform costs one draw), drawn from ``key`` (a counter-based generator,
  SplitMix64: the same key, the same walk). The sideways spread of a walk after L metres is
  drift_sd L^1.5 / sqrt(3): ``putting.greens.DRIFT_SD_BENTGRASS`` makes it the 4.9 mm per metre
  measured at 3 m on pure bentgrass;
- a read: the slope as a putter perceives it, the green's with a misread tilt added
  (``tilt_x``, ``tilt_y``: the fall vector, slope times fall direction, of a plane added to the
  green; the roll of a read is an error-free roll on that green, without drift).
"""

import math
from typing import NamedTuple

import numpy as np
from numba import njit, uint64

from mcrun.physics.constants import G_MPS2
from mcrun.putting.cup import HOLE_RADIUS_M, capture_speed_mps
from mcrun.status import HOLED, NOT_STOPPED, OFF_GREEN, OK

__all__ = [
    "DT_S",
    "MAX_TIME_S",
    "ROLL_STATUS",
    "STATUS_HOLED",
    "STATUS_NOT_STOPPED",
    "STATUS_OFF_GREEN",
    "NO_SURFACE",
    "STATUS_STOPPED",
    "Surface",
    "drift_step",
    "roll",
    "roll_core",
    "roll_lanes",
    "roll_on",
    "slope_at",
]

ROLLING_FACTOR = 5.0 / 7.0  # a uniform sphere rolling without slipping, I = (2/5) m r^2
DT_S = 0.004
MAX_TIME_S = 60.0
# The putts ``roll_lanes`` rolls side by side.
LANES = 16

# The roll's statuses are the project's (``mcrun.status``).
STATUS_STOPPED = OK  # at rest on the green
STATUS_HOLED = HOLED  # dropped in the cup
STATUS_NOT_STOPPED = NOT_STOPPED  # still moving at the cap (a slope too steep to rest on, or not)
STATUS_OFF_GREEN = OFF_GREEN  # left the green (or its grid): a chip from where it left
# What ``_step`` returns for a ball that rolls on (otherwise the status its roll ends with).
ROLLING = -1
ROLL_STATUS = {
    OK: "stopped",
    HOLED: "holed",
    NOT_STOPPED: "not stopped",
    OFF_GREEN: "off the green",
}


class Surface(NamedTuple):
    """A green on a grid: node [iy, ix] at (x0_m + ix cell_m, y0_m + iy cell_m) of the hole's
    frame, its height (m) and whether it is the green's (1) or not (0: a ball that reaches it
    has left the green). The height between nodes is bilinear."""

    height_m: np.ndarray  # (ny, nx) float64
    on_green: np.ndarray  # (ny, nx) uint8
    x0_m: float
    y0_m: float
    cell_m: float


# A plane green asks no grid: the empty surface.
NO_SURFACE = Surface(np.zeros((0, 0)), np.zeros((0, 0), dtype=np.uint8), 0.0, 0.0, 1.0)


_GOLDEN = uint64(0x9E3779B97F4A7C15)
_MIX1 = uint64(0xBF58476D1CE4E5B9)
_MIX2 = uint64(0x94D049BB133111EB)


@njit(cache=True, inline="always")
def _uniform(key):
    """SplitMix64: the next state of ``key`` and a uniform number in (0, 1) from it."""
    key = key + _GOLDEN
    z = key
    z = (z ^ (z >> uint64(30))) * _MIX1
    z = (z ^ (z >> uint64(27))) * _MIX2
    z = z ^ (z >> uint64(31))
    return key, ((z >> uint64(11)) + 0.5) * (1.0 / 9007199254740992.0)


@njit(cache=True, inline="always")
def drift_step(key):
    """The next state of ``key`` and a number of mean 0 and variance 1 (uniform)."""
    key, u = _uniform(key)
    return key, (u - 0.5) * 3.4641016151377544  # sqrt(12)


@njit(cache=True, inline="always")
def _tilted(slope_tan, fall_x, fall_y, tilt_x, tilt_y):
    """The slope (tan, fall direction) with the fall vector (tilt_x, tilt_y) added."""
    if tilt_x == 0.0 and tilt_y == 0.0:
        return slope_tan, fall_x, fall_y
    gx = slope_tan * fall_x + tilt_x
    gy = slope_tan * fall_y + tilt_y
    s = math.sqrt(gx * gx + gy * gy)
    if s > 0.0:
        return s, gx / s, gy / s
    return 0.0, 1.0, 0.0


@njit(cache=True)
def slope_at(x_m, y_m, slope_tan, fall_x, fall_y):
    """The slope at (x_m, y_m): (tan(beta), fall direction x, y). A plane: the same everywhere."""
    return slope_tan, fall_x, fall_y


@njit(cache=True, inline="always")
def _cell(x_m, y_m, surface):
    """The cell of ``surface`` holding (x_m, y_m) (the nearest one off the grid) and where in it:
    (ix, iy, tx, ty), the fractions clamped to [0, 1]."""
    ny, nx = surface.height_m.shape
    fx = (x_m - surface.x0_m) / surface.cell_m
    fy = (y_m - surface.y0_m) / surface.cell_m
    ix = min(max(int(math.floor(fx)), 0), nx - 2)
    iy = min(max(int(math.floor(fy)), 0), ny - 2)
    return ix, iy, min(max(fx - ix, 0.0), 1.0), min(max(fy - iy, 0.0), 1.0)


@njit(cache=True)
def grid_slope(x_m, y_m, surface):
    """The slope of ``surface`` at (x_m, y_m): (tan(beta), fall direction x, y), from the
    gradient of its bilinear height (the nearest cell where the point is off the grid)."""
    h = surface.height_m
    ix, iy, tx, ty = _cell(x_m, y_m, surface)
    h00, h10 = h[iy, ix], h[iy, ix + 1]
    h01, h11 = h[iy + 1, ix], h[iy + 1, ix + 1]
    gx = ((1.0 - ty) * (h10 - h00) + ty * (h11 - h01)) / surface.cell_m
    gy = ((1.0 - tx) * (h01 - h00) + tx * (h11 - h10)) / surface.cell_m
    s = math.sqrt(gx * gx + gy * gy)
    if s > 0.0:
        return s, -gx / s, -gy / s
    return 0.0, 1.0, 0.0


@njit(cache=True)
def grid_height(x_m, y_m, surface):
    """The bilinear height (m) of ``surface`` at (x_m, y_m) (clamped to its grid)."""
    h = surface.height_m
    ix, iy, tx, ty = _cell(x_m, y_m, surface)
    return ((1.0 - ty) * ((1.0 - tx) * h[iy, ix] + tx * h[iy, ix + 1])
            + ty * ((1.0 - tx) * h[iy + 1, ix] + tx * h[iy + 1, ix + 1]))  # fmt: skip


@njit(cache=True)
def on_green(x_m, y_m, surface):
    """Whether (x_m, y_m) is on the green: its nearest node is the green's (False off the
    grid)."""
    ny, nx = surface.on_green.shape
    ix = int(math.floor((x_m - surface.x0_m) / surface.cell_m + 0.5))
    iy = int(math.floor((y_m - surface.y0_m) / surface.cell_m + 0.5))
    if ix < 0 or iy < 0 or ix >= nx or iy >= ny:
        return False
    return surface.on_green[iy, ix] != 0


@njit(cache=True, inline="always")
def _pull(slope_tan, fall_x, fall_y, rho_g):
    """What a slope does to a rolling ball (Penner 2002), taken once per step: gravity along
    the plane (5/7) g sin(beta) times the fall direction (x, y), and the rolling resistance's
    deceleration (5/7) g rho_g cos(beta) (m/s^2)."""
    cos_b = 1.0 / math.sqrt(1.0 + slope_tan * slope_tan)
    k = ROLLING_FACTOR * G_MPS2
    g = k * slope_tan * cos_b
    return g * fall_x, g * fall_y, k * rho_g * cos_b


@njit(cache=True, inline="always")
def _accel(vx, vy, gx, gy, resist, fall_x, fall_y):
    """The acceleration (m/s^2) of a ball rolling at (vx, vy) under ``_pull``'s (gx, gy,
    resist): the resistance against its motion (a ball at rest starts down the fall line)."""
    speed = math.sqrt(vx * vx + vy * vy)
    if speed > 1e-9:
        return gx - resist * vx / speed, gy - resist * vy / speed
    return gx - resist * fall_x, gy - resist * fall_y


@njit(cache=True)
def _entry(x0, y0, x1, y1, hx, hy):
    """Where the segment (x0, y0) -> (x1, y1), starting outside the cup's circle, enters it: the
    fraction along the segment (-1 if it does not) and the offset of its line from the centre."""
    dx, dy = x1 - x0, y1 - y0
    ex, ey = x0 - hx, y0 - hy
    a = dx * dx + dy * dy
    if a <= 0.0:
        return -1.0, 0.0
    b = ex * dx + ey * dy
    c = ex * ex + ey * ey - HOLE_RADIUS_M * HOLE_RADIUS_M
    disc = b * b - a * c
    if disc < 0.0:
        return -1.0, 0.0
    s = (-b - math.sqrt(disc)) / a
    if s < 0.0 or s > 1.0:
        return -1.0, 0.0
    offset = abs(ex * dy - ey * dx) / math.sqrt(a)
    return s, offset


@njit(cache=True)
def roll(x_m, y_m, vx_mps, vy_mps, slope_tan, fall_x, fall_y, rho_g, hole_x_m, hole_y_m,
         cup, dt_s, max_time_s):  # fmt: skip
    """Roll a ball on a plane green from (x_m, y_m) at (vx_mps, vy_mps) until it stops, drops
    (with ``cup``) or runs past ``max_time_s``.

    Returns (status, x_m, y_m, time_s, closest_m, closest_x_m, closest_y_m): the ``STATUS_*``,
    where it ended, when, and (without ``cup``) the point of its path closest to the hole's
    centre.
    """
    return roll_core(x_m, y_m, vx_mps, vy_mps, slope_tan, fall_x, fall_y, rho_g, hole_x_m,
                     hole_y_m, cup, dt_s, max_time_s, NO_SURFACE, 0.0, 0.0, 0.0, 0.0,
                     uint64(0))  # fmt: skip


@njit(cache=True)
def roll_on(x_m, y_m, vx_mps, vy_mps, surface, rho_g, hole_x_m, hole_y_m, cup, dt_s,
            max_time_s, ds_max_m):  # fmt: skip
    """``roll`` on the grid ``surface`` (a ``Surface``; positions in the hole's frame), in steps
    of at most ``dt_s`` and ``ds_max_m``; it also ends ``STATUS_OFF_GREEN``, where the ball
    reached a node that is not the green's (the position: that point)."""
    return roll_core(x_m, y_m, vx_mps, vy_mps, 0.0, 1.0, 0.0, rho_g, hole_x_m, hole_y_m, cup,
                     dt_s, max_time_s, surface, ds_max_m, 0.0, 0.0, 0.0, uint64(0))  # fmt: skip


@njit(cache=True, inline="always")
def roll_core(x_m, y_m, vx_mps, vy_mps, slope_tan, fall_x, fall_y, rho_g, hole_x_m, hole_y_m,
              cup, dt_s, max_time_s, surface, ds_max_m, tilt_x, tilt_y, drift_sd,
              key):  # fmt: skip
    """The one roll of ``roll`` (an empty ``surface``, ``NO_SURFACE``: the plane of slope_tan,
    fall_x, fall_y) and of ``roll_on`` (a grid), for what asks of either ground: the ground
    tilted by the fall vector (``tilt_x``, ``tilt_y``) (a read; 0, 0: the ground as it is), the
    heading's random walk ``drift_sd`` (rad per sqrt(m); 0: none) drawn from ``key``: ``_step``
    after ``_step`` until the ball stops, drops, leaves the green or runs past ``max_time_s``."""
    x, y, vx, vy, t = x_m, y_m, vx_mps, vy_mps, 0.0
    best = math.hypot(x - hole_x_m, y - hole_y_m)
    bx, by = x, y
    while t < max_time_s:
        end, x, y, vx, vy, t, key, best, bx, by = _step(
            x, y, vx, vy, t, key, best, bx, by, slope_tan, fall_x, fall_y, rho_g, hole_x_m,
            hole_y_m, cup, dt_s, surface, ds_max_m, tilt_x, tilt_y, drift_sd,
        )  # fmt: skip
        if end != ROLLING:
            return end, x, y, t, best, bx, by
    return STATUS_NOT_STOPPED, x, y, t, best, bx, by


@njit(cache=True)
def roll_lanes(x_m, y_m, vx_mps, vy_mps, keys, slope_tan, fall_x, fall_y, rho_g, hole_x_m,
               hole_y_m, dt_s, max_time_s, surface, ds_max_m, drift_sd, status, end_x_m,
               end_y_m):  # fmt: skip
    """``roll_core`` of n putts with the cup, the i-th from (x_m[i], y_m[i]) at (vx_mps[i],
    vy_mps[i]) with the drift's key keys[i], on the ground as it is (no tilt): its status and
    where it ended into status[i], end_x_m[i], end_y_m[i], the same bit for bit.

    A roll is a chain of square roots and divisions, each step's waiting on the step before, so
    that one ball keeps the processor waiting. Here ``LANES`` balls roll side by side, a ball
    taking a lane as one leaves it, and each part of a step is taken for every lane in turn, so
    that the processor works on several balls' steps at once. A lane's step is ``_step``'s in
    its common case: the same operations in the same order. Where a step may be other than
    that (the ball stops in it, nearly stands, enters the cup's circle or leaves the green),
    the lane's step is ``_step`` itself, from the same state."""
    n = x_m.shape[0]
    grid = surface.height_m.shape[0] > 0
    w = min(LANES, n)
    ball = np.full(w, -1, dtype=np.int64)
    x, y, vx, vy, t = np.zeros(w), np.zeros(w), np.zeros(w), np.zeros(w), np.zeros(w)
    key = np.zeros(w, dtype=np.uint64)
    h, speed = np.zeros(w), np.zeros(w)
    fx, fy, gx, gy, resist = np.zeros(w), np.zeros(w), np.zeros(w), np.zeros(w), np.zeros(w)
    x1, y1, v1x, v1y = np.zeros(w), np.zeros(w), np.zeros(w), np.zeros(w)
    key1 = np.zeros(w, dtype=np.uint64)
    other = np.zeros(w, dtype=np.bool_)
    following, live = 0, 0
    for lane in range(w):
        following, live = _take_lane(lane, following, live, ball, x, y, vx, vy, t, key, x_m,
                                     y_m, vx_mps, vy_mps, keys, max_time_s, status, end_x_m,
                                     end_y_m)  # fmt: skip
    while live > 0:
        # Each part of a step for every lane in turn: the slope ahead (``_slope_ahead`` without
        # a tilt, written out: called, it cost the lanes a tenth of their time), RK4, the drift.
        for lane in range(w):
            sp = math.sqrt(vx[lane] * vx[lane] + vy[lane] * vy[lane])
            hh = dt_s
            if grid:
                if ds_max_m > 0.0 and sp * hh > ds_max_m:
                    hh = ds_max_m / sp
                s_tan, f_x, f_y = grid_slope(x[lane] + vx[lane] * hh / 2.0,
                                             y[lane] + vy[lane] * hh / 2.0, surface)  # fmt: skip
            else:
                s_tan, f_x, f_y = slope_at(x[lane], y[lane], slope_tan, fall_x, fall_y)
            gx[lane], gy[lane], resist[lane] = _pull(s_tan, f_x, f_y, rho_g)
            speed[lane], h[lane], fx[lane], fy[lane] = sp, hh, f_x, f_y
        for lane in range(w):
            sp, u, v = speed[lane], vx[lane], vy[lane]
            ax, ay = _accel(u, v, gx[lane], gy[lane], resist[lane], fx[lane], fy[lane])
            if sp > 1e-9:  # ``_step``'s own where the ball stops in this step
                decel = _decel(sp, ax, ay, u, v)
                other[lane] = decel > 0.0 and sp <= decel * h[lane]
            else:  # or nearly stands
                other[lane] = True
            x1[lane], y1[lane], v1x[lane], v1y[lane] = _rk4(
                x[lane], y[lane], u, v, h[lane], ax, ay, gx[lane], gy[lane], resist[lane],
                fx[lane], fy[lane],
            )  # fmt: skip
        if drift_sd > 0.0:
            for lane in range(w):
                key1[lane], v1x[lane], v1y[lane] = _drifted(
                    v1x[lane], v1y[lane], speed[lane], h[lane], drift_sd, key[lane]
                )
        else:
            for lane in range(w):  # (a loop, not key1[:] = key, whose shape check compiles slowly)
                key1[lane] = key[lane]
        # The cup's circle entered, the green left, the ball at rest: ``_step``'s own.
        for lane in range(w):
            if (x[lane] - hole_x_m) ** 2 + (y[lane] - hole_y_m) ** 2 > HOLE_RADIUS_M**2:
                if _entry(x[lane], y[lane], x1[lane], y1[lane], hole_x_m, hole_y_m)[0] >= 0.0:
                    other[lane] = True
            if grid and not on_green(x1[lane], y1[lane], surface):
                other[lane] = True
            if v1x[lane] == 0.0 and v1y[lane] == 0.0:
                other[lane] = True
        for lane in range(w):
            i = ball[lane]
            if i < 0:
                continue
            if other[lane]:
                end, x[lane], y[lane], vx[lane], vy[lane], t[lane], key[lane], _, _, _ = _step(
                    x[lane], y[lane], vx[lane], vy[lane], t[lane], key[lane], 0.0, 0.0, 0.0,
                    slope_tan, fall_x, fall_y, rho_g, hole_x_m, hole_y_m, True, dt_s, surface,
                    ds_max_m, 0.0, 0.0, drift_sd,
                )  # fmt: skip
            else:
                end = ROLLING
                x[lane], y[lane], vx[lane], vy[lane] = x1[lane], y1[lane], v1x[lane], v1y[lane]
                t[lane], key[lane] = t[lane] + h[lane], key1[lane]
            if end == ROLLING and not t[lane] < max_time_s:
                end = STATUS_NOT_STOPPED
            if end != ROLLING:
                status[i], end_x_m[i], end_y_m[i] = end, x[lane], y[lane]
                ball[lane] = -1
                live -= 1
                following, live = _take_lane(lane, following, live, ball, x, y, vx, vy, t, key,
                                             x_m, y_m, vx_mps, vy_mps, keys, max_time_s, status,
                                             end_x_m, end_y_m)  # fmt: skip


@njit(cache=True, inline="always")
def _take_lane(lane, following, live, ball, x, y, vx, vy, t, key, x_m, y_m, vx_mps, vy_mps,
               keys, max_time_s, status, end_x_m, end_y_m):  # fmt: skip
    """Put the next ball (``following``) that rolls at all into ``lane`` (a ball given no time,
    ``max_time_s`` <= 0, ends where it is, not stopped); (the next ball after it, balls
    rolling)."""
    while following < x_m.shape[0]:
        i = following
        following += 1
        if not 0.0 < max_time_s:
            status[i], end_x_m[i], end_y_m[i] = STATUS_NOT_STOPPED, x_m[i], y_m[i]
            continue
        ball[lane] = i
        x[lane], y[lane], vx[lane], vy[lane] = x_m[i], y_m[i], vx_mps[i], vy_mps[i]
        t[lane], key[lane] = 0.0, keys[i]
        return following, live + 1
    return following, live


@njit(cache=True, inline="always")
def _slope_ahead(x, y, vx, vy, slope_tan, fall_x, fall_y, rho_g, dt_s, surface, ds_max_m,
                 tilt_x, tilt_y):  # fmt: skip
    """A step's start: the ball's speed, the step's length in time (at most ``dt_s``, and on a
    grid ``ds_max_m`` in distance), and the pull of the slope (``_pull``, with the fall
    direction) at the step's midpoint as the ball is heading (on a plane, anywhere), tilted."""
    speed = math.sqrt(vx * vx + vy * vy)
    h = dt_s
    if surface.height_m.shape[0] > 0:
        if ds_max_m > 0.0 and speed * h > ds_max_m:
            h = ds_max_m / speed
        s_tan, fx, fy = grid_slope(x + vx * h / 2.0, y + vy * h / 2.0, surface)
    else:
        s_tan, fx, fy = slope_at(x, y, slope_tan, fall_x, fall_y)
    s_tan, fx, fy = _tilted(s_tan, fx, fy, tilt_x, tilt_y)
    gx, gy, resist = _pull(s_tan, fx, fy, rho_g)
    return speed, h, gx, gy, resist, fx, fy


@njit(cache=True, inline="always")
def _decel(speed, ax, ay, vx, vy):
    """The deceleration along the motion of a ball at ``speed`` (vx, vy) under the acceleration
    (ax, ay): -a.v_hat (0 for a ball nearly at rest). The ball stops in a step of h where
    0 < decel and speed <= decel h."""
    return -(ax * vx + ay * vy) / speed if speed > 1e-9 else 0.0


@njit(cache=True, inline="always")
def _rk4(x, y, vx, vy, h, ax, ay, gx, gy, resist, fx, fy):
    """A step of ``h`` (s) by RK4 under the pull (gx, gy, resist, fx, fy), (ax, ay) the
    acceleration at its start: (x, y, vx, vy) after it."""
    k1x, k1y = ax, ay
    k2x, k2y = _accel(vx + h / 2 * k1x, vy + h / 2 * k1y, gx, gy, resist, fx, fy)
    k3x, k3y = _accel(vx + h / 2 * k2x, vy + h / 2 * k2y, gx, gy, resist, fx, fy)
    k4x, k4y = _accel(vx + h * k3x, vy + h * k3y, gx, gy, resist, fx, fy)
    v1x = vx + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x)
    v1y = vy + h / 6 * (k1y + 2 * k2y + 2 * k3y + k4y)
    # position: RK4 of dx/dt = v with the stages' velocities
    x1 = x + h / 6 * (vx + 2 * (vx + h / 2 * k1x) + 2 * (vx + h / 2 * k2x) + vx + h * k3x)
    y1 = y + h / 6 * (vy + 2 * (vy + h / 2 * k1y) + 2 * (vy + h / 2 * k2y) + vy + h * k3y)
    return x1, y1, v1x, v1y


@njit(cache=True, inline="always")
def _drifted(vx, vy, speed, h, drift_sd, key):
    """The heading's random walk over a step of ``h`` (s) begun at ``speed``: (key, the
    velocity turned)."""
    key, w = drift_step(key)
    turn = drift_sd * math.sqrt(speed * h) * w  # the step's length, to O(h^2)
    # cos and sin of a turn under a degree, to 1e-10
    cos_t, sin_t = 1.0 - 0.5 * turn * turn, turn * (1.0 - turn * turn / 6.0)
    return key, cos_t * vx - sin_t * vy, sin_t * vx + cos_t * vy


@njit(cache=True, inline="always")
def _step(x, y, vx, vy, t, key, best, bx, by, slope_tan, fall_x, fall_y, rho_g, hole_x_m,
          hole_y_m, cup, dt_s, surface, ds_max_m, tilt_x, tilt_y, drift_sd):  # fmt: skip
    """One step of a roll (``roll_core``'s) from the state (x, y, vx, vy, t, key) and the
    closest approach so far (best, bx, by): (end, the state after it, the closest approach),
    ``end`` ``ROLLING`` or the status the roll ends with (then x, y where it ended)."""
    grid = surface.height_m.shape[0] > 0
    speed, h, gx, gy, resist, fx, fy = _slope_ahead(x, y, vx, vy, slope_tan, fall_x, fall_y,
                                                    rho_g, dt_s, surface, ds_max_m, tilt_x,
                                                    tilt_y)  # fmt: skip
    ax, ay = _accel(vx, vy, gx, gy, resist, fx, fy)
    decel = _decel(speed, ax, ay, vx, vy)
    if speed > 1e-9 and decel > 0.0 and speed <= decel * h:
        t_stop = speed / decel
        x1 = x + vx * t_stop / 2.0
        y1 = y + vy * t_stop / 2.0
        v1x, v1y = 0.0, 0.0
        h = t_stop
    else:
        x1, y1, v1x, v1y = _rk4(x, y, vx, vy, h, ax, ay, gx, gy, resist, fx, fy)
        if drift_sd > 0.0:
            key, v1x, v1y = _drifted(v1x, v1y, speed, h, drift_sd, key)
    # The cup: the centre's path enters the rim's circle in this step.
    outside = (x - hole_x_m) ** 2 + (y - hole_y_m) ** 2 > HOLE_RADIUS_M**2
    if outside:
        s, offset = _entry(x, y, x1, y1, hole_x_m, hole_y_m)
        if s >= 0.0:
            speed1 = math.sqrt(v1x * v1x + v1y * v1y)
            at_rim = speed + s * (speed1 - speed)
            if cup and at_rim < capture_speed_mps(offset):
                return (STATUS_HOLED, hole_x_m, hole_y_m, 0.0, 0.0, t + s * h, key, 0.0,
                        hole_x_m, hole_y_m)  # fmt: skip
    # The closest approach to the hole's centre along this step (a read's roll, without
    # the cup, asks it; a putt's roll does not).
    if not cup:
        dx, dy = x1 - x, y1 - y
        seg2 = dx * dx + dy * dy
        f = 0.0
        if seg2 > 0.0:
            f = min(1.0, max(0.0, ((hole_x_m - x) * dx + (hole_y_m - y) * dy) / seg2))
        px, py = x + f * dx, y + f * dy
        dist = math.hypot(px - hole_x_m, py - hole_y_m)
        if dist < best:
            best, bx, by = dist, px, py
    x, y, vx, vy, t = x1, y1, v1x, v1y, t + h
    if grid and not on_green(x, y, surface):
        return STATUS_OFF_GREEN, x, y, vx, vy, t, key, best, bx, by
    if vx == 0.0 and vy == 0.0:
        if grid:
            s_tan, fx, fy = grid_slope(x, y, surface)
        else:
            s_tan, fx, fy = slope_at(x, y, slope_tan, fall_x, fall_y)
        if _tilted(s_tan, fx, fy, tilt_x, tilt_y)[0] <= rho_g:
            return STATUS_STOPPED, x, y, vx, vy, t, key, best, bx, by
    return ROLLING, x, y, vx, vy, t, key, best, bx, by
