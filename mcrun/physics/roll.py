"""Roll: from the last hop to rest, on the ground: a plane that may slope, or a hole's terrain.

Two phases (Penner 2002 section 2 and physics.md):
- slide: while the contact point slips (u = v + w x (-r n) != 0, e.g. backspin kept by a sliding
  bounce), kinetic friction mu g cos(beta) opposes the slip; the slip changes at
  g_t - (7/2) mu g cos(beta) u_hat and the velocity at g_t - mu g cos(beta) u_hat.
- roll: rolling without slipping, a = (5/7) (g_t - rho_g g cos(beta) v_hat), eq. (9) plus the
  pull of gravity g_t = g sin(beta) down the fall line.

Each step holds the direction of u (or v) fixed, which is exact on level ground: there a single
step runs each phase to its end. On a slope the steps are ROLL_DT_S long. A ball on a slope
steeper than atan(rho_g) never stops: the bounds in ``status`` end it with NOT_STOPPED. On a
terrain the ground is asked after every step, and a step goes at most a quarter of a cell of
its grid: that loop, which asks the ground, is the engine's (``engine.rolling``); here are the
steps it takes, and the Surface and Patch of ground it asks for.
"""

import math
from typing import NamedTuple

from numba import njit

from mcrun.physics.constants import BALL_RADIUS_M, G_MPS2
from mcrun.physics.turf import Turf
from mcrun.status import MAX_ROLL_DISTANCE_M, MAX_ROLL_TIME_S

ROLL_DT_S = 0.01


class Patch(NamedTuple):
    """Where the ground around the ball is one smooth piece, one bilinear patch of one zone (on
    a grid, a cell, or the quarter of it nearest one node where its nodes' zones differ), in the
    core's frame: at u = x - xc, w = yc - y (the grid's fractions times the cell), its height is
    hc + bx u + by w + ec u w, for u in [u_lo, u_hi] and w in [w_lo, w_hi]. ``smooth`` is 1.0
    where the roll may take the patch's own steps (on a grid, where the cell is not calm),
    LEVEL_PATCH where that patch is level (where the roll's steps are exact up to its edge and
    to the ball's stop), else 0.0 (NO_PATCH: the rest is not used)."""

    smooth: float
    xc: float
    yc: float
    hc: float
    bx: float
    by: float
    ec: float
    u_lo: float
    u_hi: float
    w_lo: float
    w_hi: float


LEVEL_PATCH = 2.0
NO_PATCH = Patch(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


class Surface(NamedTuple):
    """What the roll asks of the ground at each step (``ground.surface``): the height (m) of the
    ground under the ball, its unit normal (core frame) and turf, the state there
    (``mcrun.status``: OK in play, or where the shot ends), the longest distance (m) a step may
    go on it, and the smooth Patch around it, where the roll may step further."""

    height_m: float
    nx: float
    ny: float
    nz: float
    turf: Turf
    state: int
    step_m: float
    patch: Patch


@njit(cache=True, error_model="numpy", inline="always")
def plane_gravity(nx, ny, nz):
    """Gravity on the ground plane of normal n: g n_z (pressing the ball on it), the part along
    it (gx, gy, gz) and its magnitude g_t, the step of the roll (one step per phase on level
    ground, where each step is exact) and the distance within which a step's end counts as
    zero slip (or speed)."""
    g_n = G_MPS2 * nz
    gx = g_n * nx
    gy = g_n * ny
    gz = g_n * nz - G_MPS2
    g_t = math.sqrt(gx * gx + gy * gy + gz * gz)
    h_max = ROLL_DT_S if g_t > 0.0 else MAX_ROLL_TIME_S
    return g_n, gx, gy, gz, g_t, h_max, 2.0 * g_t * ROLL_DT_S + 1e-9


@njit(cache=True, error_model="numpy", inline="always")
def contact_slip(vx, vy, vz, wx, wy, wz, nx, ny, nz):
    """Slip u = v + w x (-r n) of the contact point at -r n."""
    return (
        vx + (wy * (-BALL_RADIUS_M * nz) - wz * (-BALL_RADIUS_M * ny)),
        vy + (wz * (-BALL_RADIUS_M * nx) - wx * (-BALL_RADIUS_M * nz)),
        vz + (wx * (-BALL_RADIUS_M * ny) - wy * (-BALL_RADIUS_M * nx)),
    )


@njit(cache=True, error_model="numpy", inline="always")
def _step_to_zero(ux, uy, uz, ax, ay, az, h, snap):
    """The length of a step of at most h of a vector u that changes at the constant rate a,
    and whether the step brings u to zero: it ends where |u| is least, if that comes within h
    and within ``snap`` of zero."""
    a2 = ax * ax + ay * ay + az * az
    t_min = -(ux * ax + uy * ay + uz * az) / a2 if a2 > 0.0 else -1.0
    rx = ux + ax * t_min
    ry = uy + ay * t_min
    rz = uz + az * t_min
    done = (0.0 < t_min) & (t_min <= h) & (rx * rx + ry * ry + rz * rz <= snap * snap)
    return (t_min if done else h), done


@njit(cache=True, error_model="numpy", inline="always")
def _advance(px, py, pz, vx, vy, vz, ax, ay, az, h):
    """The position after h at velocity v and constant acceleration a."""
    return (
        px + vx * h + 0.5 * ax * h * h,
        py + vy * h + 0.5 * ay * h * h,
        pz + vz * h + 0.5 * az * h * h,
    )


@njit(cache=True, error_model="numpy", inline="always")
def slide_step(px, py, pz, vx, vy, vz, ux, uy, uz, u, gx, gy, gz, k_slide, h, snap):
    """A step of the slide, of at most h, with the contact point slipping at u (|u| = u > 0):
    the ball's acceleration, the step's length, whether it ends the slide, and the position,
    velocity and slip after it. A step that passes within ``snap`` of zero slip ends there,
    and friction then removes what slip is left: dv = -(2/7) u brings it to zero."""
    # Friction along -u_hat: one division for the six components.
    fx = k_slide * ux * (1.0 / u)
    fy = k_slide * uy * (1.0 / u)
    fz = k_slide * uz * (1.0 / u)
    avx = gx - fx
    avy = gy - fy
    avz = gz - fz
    aux = gx - 3.5 * fx
    auy = gy - 3.5 * fy
    auz = gz - 3.5 * fz
    h, done = _step_to_zero(ux, uy, uz, aux, auy, auz, h, snap)
    ux += aux * h
    uy += auy * h
    uz += auz * h
    px, py, pz = _advance(px, py, pz, vx, vy, vz, avx, avy, avz, h)
    return (
        (avx, avy, avz),
        h,
        done,
        px,
        py,
        pz,
        vx + avx * h - (2.0 / 7.0) * ux if done else vx + avx * h,
        vy + avy * h - (2.0 / 7.0) * uy if done else vy + avy * h,
        vz + avz * h - (2.0 / 7.0) * uz if done else vz + avz * h,
        ux,
        uy,
        uz,
    )


@njit(cache=True, error_model="numpy", inline="always")
def roll_step(px, py, pz, vx, vy, vz, dx, dy, dz, gx, gy, gz, k_roll, h, snap):
    """A step of the roll, of at most h, with rolling resistance against the direction d (of
    the velocity, or of the fall line for a ball at rest): the acceleration, the step's
    length, whether the ball stops, and the position and velocity after it (zero if it
    stops: a step that passes within ``snap`` of zero speed ends there)."""
    ax = (5.0 / 7.0) * (gx - k_roll * dx)
    ay = (5.0 / 7.0) * (gy - k_roll * dy)
    az = (5.0 / 7.0) * (gz - k_roll * dz)
    h, done = _step_to_zero(vx, vy, vz, ax, ay, az, h, snap)
    px, py, pz = _advance(px, py, pz, vx, vy, vz, ax, ay, az, h)
    return (
        (ax, ay, az),
        h,
        done,
        px,
        py,
        pz,
        0.0 if done else vx + ax * h,
        0.0 if done else vy + ay * h,
        0.0 if done else vz + az * h,
    )


@njit(cache=True, error_model="numpy", inline="always")
def rolled_too_far(px, py, x0, y0):
    """Whether the ball has rolled more than MAX_ROLL_DISTANCE_M from (x0, y0)."""
    return (px - x0) * (px - x0) + (py - y0) * (py - y0) > MAX_ROLL_DISTANCE_M**2


@njit(cache=True, error_model="numpy", inline="always")
def onto_plane(x, y, z, nx, ny, nz):
    """The vector (x, y, z) turned into the plane of normal n, its length kept."""
    m2 = x * x + y * y + z * z
    d = x * nx + y * ny + z * nz
    x -= d * nx
    y -= d * ny
    z -= d * nz
    p2 = x * x + y * y + z * z
    k = math.sqrt(m2 / p2) if p2 > 0.0 else 0.0
    return x * k, y * k, z * k


@njit(cache=True, error_model="numpy", inline="always")
def climbed(vx, vy, vz, dz):
    """The velocity of a rolling ball whose step along the tangent plane ended dz (m) below
    the ground, where it is put: its kinetic energy (7/10) v^2 pays for the height, so that
    the step conserves (7/10) v^2 + g z as the ground's curvature would (zero if it cannot)."""
    v2 = vx * vx + vy * vy + vz * vz
    left = v2 - (10.0 / 7.0) * G_MPS2 * dz
    k = math.sqrt(left / v2) if (left > 0.0) & (v2 > 0.0) else 0.0
    return vx * k, vy * k, vz * k


@njit(cache=True, error_model="numpy", inline="always")
def turned(vx, vy, vz, dgx, dgy, dgz, h):
    """The velocity at the end of a roll step of h (s) that held the acceleration of its
    start, where gravity along the ground changed by dg over it: turned by the mean of that
    change, (5/7) dg h / 2 (the trapezoid rule, which makes the direction second order), its
    length kept (``climbed`` gives it)."""
    m0 = math.sqrt(vx * vx + vy * vy + vz * vz)
    c = (5.0 / 14.0) * h
    x = vx + c * dgx
    y = vy + c * dgy
    z = vz + c * dgz
    m1 = math.sqrt(x * x + y * y + z * z)
    k = m0 / m1 if m1 > 0.0 else 0.0
    return x * k, y * k, z * k


# On smooth ground of a terrain (``Surface.patch``: one bilinear patch of one zone) the roll
# takes steps of the classical Runge-Kutta method (fourth order) on the ball's horizontal
# position and velocity, with its height on the patch: each step ends where the ball leaves the
# patch (PATCH_OVERSHOOT_M past its edge, where the next patch turns the velocity), or after at
# most PATCH_DT_MAX_S, or STOP_FRACTION of the time the ball would take to stop at its present
# deceleration. Where that time is shorter than PATCH_DT_MIN_S, ROLL_DT_S steps bring it to
# rest, as on calm ground.
PATCH_DT_MAX_S = 0.25
PATCH_DT_MIN_S = 0.02
STOP_FRACTION = 0.4
PATCH_OVERSHOOT_M = 1e-6
# A step that ends further past the edge than this (s at its speed) is taken again, shortened.
PATCH_REFINE_S = 1e-6


@njit(cache=True, error_model="numpy", inline="always")
def patch_acceleration(x, y, vx, vy, patch, rho_g):
    """The horizontal acceleration of a ball rolling without slipping at (x, y) on the patch at
    horizontal velocity (vx, vy): (5/7) (g_t - rho_g g n_z v_hat), plus the normal force that
    keeps it on the patch's surface h (which bends it by the twist h_xy = -EC)."""
    hx = patch.bx + patch.ec * (patch.yc - y)
    hy = -(patch.by + patch.ec * (x - patch.xc))
    n2 = 1.0 + hx * hx + hy * hy
    vz = hx * vx + hy * vy
    inv = 1.0 / n2
    k = (5.0 / 7.0) * rho_g * G_MPS2 / math.sqrt(n2 * (vx * vx + vy * vy + vz * vz))
    c = ((5.0 / 7.0) * G_MPS2 - 2.0 * patch.ec * vx * vy) * inv
    return -c * hx - k * vx, -c * hy - k * vy


@njit(cache=True, error_model="numpy", inline="always")
def _first_root(a, b, c):
    """The first t > 0 where a t^2 + b t + c = 0 (inf if none)."""
    if a == 0.0:
        r = -c / b if b != 0.0 else -1.0
        return r if r > 0.0 else math.inf
    d = b * b - 4.0 * a * c
    if d < 0.0:
        return math.inf
    q = -0.5 * (b + math.copysign(math.sqrt(d), b))
    r1 = q / a
    r2 = c / q if q != 0.0 else -1.0
    r1 = r1 if r1 > 0.0 else math.inf
    r2 = r2 if r2 > 0.0 else math.inf
    return min(r1, r2)


@njit(cache=True, error_model="numpy", inline="always")
def exit_time(p, v, a, lo, hi):
    """The first time p + v t + a t^2 / 2 leaves [lo, hi] by PATCH_OVERSHOOT_M."""
    return min(
        _first_root(0.5 * a, v, p - hi - PATCH_OVERSHOOT_M),
        _first_root(0.5 * a, v, p - lo + PATCH_OVERSHOOT_M),
    )


@njit(cache=True, error_model="numpy", inline="always")
def overshoot(p, v, lo, hi):
    """How long (s) a ball at p moving at v has been past [lo, hi] by more than
    PATCH_OVERSHOOT_M (0 if it has not)."""
    past = max(p - hi, lo - p) - PATCH_OVERSHOOT_M
    return past / abs(v) if (past > 0.0) & (v != 0.0) else 0.0


@njit(cache=True, error_model="numpy", inline="always")
def patch_step(px, py, vx, vy, ax, ay, h, patch, rho_g):
    """A step of h of the classical Runge-Kutta method from (px, py) at (vx, vy), where the
    acceleration is (ax, ay): the position and velocity after it."""
    h2 = 0.5 * h
    x2 = px + h2 * vx
    y2 = py + h2 * vy
    u2 = vx + h2 * ax
    w2 = vy + h2 * ay
    a2x, a2y = patch_acceleration(x2, y2, u2, w2, patch, rho_g)
    x3 = px + h2 * u2
    y3 = py + h2 * w2
    u3 = vx + h2 * a2x
    w3 = vy + h2 * a2y
    a3x, a3y = patch_acceleration(x3, y3, u3, w3, patch, rho_g)
    x4 = px + h * u3
    y4 = py + h * w3
    u4 = vx + h * a3x
    w4 = vy + h * a3y
    a4x, a4y = patch_acceleration(x4, y4, u4, w4, patch, rho_g)
    h6 = h / 6.0
    return (
        px + h6 * (vx + 2.0 * (u2 + u3) + u4),
        py + h6 * (vy + 2.0 * (w2 + w3) + w4),
        vx + h6 * (ax + 2.0 * (a2x + a3x) + a4x),
        vy + h6 * (ay + 2.0 * (a2y + a3y) + a4y),
    )


@njit(cache=True, error_model="numpy", inline="always")
def patch_height(x, y, patch):
    u = x - patch.xc
    w = patch.yc - y
    return patch.hc + patch.bx * u + patch.by * w + patch.ec * u * w


@njit(cache=True, error_model="numpy", inline="always")
def roll_out_short(x, y, z, vx, vy, vz, wx, wy, wz, nx, ny, nz, mu, rho_g, t):
    """``roll_out`` without branches, for loops over many shots, when at most one step of
    slide and one of roll bring the ball to rest (level ground: each step ends its phase).
    Returns (x, y, t, short): where short is False (on a slope, say), the ball needs
    ``roll_out`` itself."""
    vn = vx * nx + vy * ny + vz * nz
    vx = vx - vn * nx
    vy = vy - vn * ny
    vz = vz - vn * nz
    g_n, gx, gy, gz, g_t, h_max, snap = plane_gravity(nx, ny, nz)
    ux, uy, uz = contact_slip(vx, vy, vz, wx, wy, wz, nx, ny, nz)
    u = math.sqrt(ux * ux + uy * uy + uz * uz)
    slides = u > 1e-12
    _, h, slid, x1, y1, z1, vx1, vy1, vz1, _, _, _ = slide_step(
        x, y, z, vx, vy, vz, ux, uy, uz, u, gx, gy, gz, mu * g_n, h_max, snap
    )
    px = x1 if slides else x
    py = y1 if slides else y
    pz = z1 if slides else z
    vx = vx1 if slides else vx
    vy = vy1 if slides else vy
    vz = vz1 if slides else vz
    t1 = t + h if slides else t
    k_roll = rho_g * g_n
    v = math.sqrt(vx * vx + vy * vy + vz * vz)
    moving = v > 1e-12
    _, h, stopped, x2, y2, _, _, _, _ = roll_step(
        px, py, pz, vx, vy, vz, vx * (1.0 / v), vy * (1.0 / v), vz * (1.0 / v), gx, gy, gz,
        k_roll, h_max, (5.0 / 7.0) * snap,
    )  # fmt: skip
    x_end = x2 if moving else px
    y_end = y2 if moving else py
    t_end = t1 + h if moving else t1
    # past the roll's bounds (a slide on ice): ``roll_out`` ends it there, NOT_STOPPED
    far = (t_end - t > MAX_ROLL_TIME_S) | rolled_too_far(x_end, y_end, x, y)
    short = (slid | ~slides) & ~far & (g_t <= k_roll) & (stopped | ~moving)
    return x_end, y_end, t_end, short
