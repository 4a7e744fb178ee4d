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
terrain the ground is asked after every step (``roll``), and a step goes at most a quarter of
a cell of its grid.
"""

import math
from typing import NamedTuple

from numba import njit

from mcrun.physics.constants import BALL_RADIUS_M, G_MPS2
from mcrun.physics.turf import Turf
from mcrun.status import MAX_ROLL_DISTANCE_M, MAX_ROLL_TIME_S, NOT_STOPPED, OK
from mcrun.trajectory import ROLL, record

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


@njit(cache=True)
def _record_segment(traj, n, t_next, dt_record, t0, h, px, py, pz, vx, vy, vz, ax, ay, az):
    """Record the points of the trajectory grid that fall inside [t0, t0 + h)."""
    if traj.shape[0] == 0:
        return n, t_next
    while t_next < t0 + h:
        s = t_next - t0
        n = record(
            traj,
            n,
            t_next,
            px + vx * s + 0.5 * ax * s * s,
            py + vy * s + 0.5 * ay * s * s,
            pz + vz * s + 0.5 * az * s * s,
            ROLL,
        )
        t_next += dt_record
    return n, t_next


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
def _onto_plane(x, y, z, nx, ny, nz):
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
def _climbed(vx, vy, vz, dz):
    """The velocity of a rolling ball whose step along the tangent plane ended dz (m) below
    the ground, where it is put: its kinetic energy (7/10) v^2 pays for the height, so that
    the step conserves (7/10) v^2 + g z as the ground's curvature would (zero if it cannot)."""
    v2 = vx * vx + vy * vy + vz * vz
    left = v2 - (10.0 / 7.0) * G_MPS2 * dz
    k = math.sqrt(left / v2) if (left > 0.0) & (v2 > 0.0) else 0.0
    return vx * k, vy * k, vz * k


@njit(cache=True, error_model="numpy", inline="always")
def _turned(vx, vy, vz, dgx, dgy, dgz, h):
    """The velocity at the end of a roll step of h (s) that held the acceleration of its
    start, where gravity along the ground changed by dg over it: turned by the mean of that
    change, (5/7) dg h / 2 (the trapezoid rule, which makes the direction second order), its
    length kept (``_climbed`` gives it)."""
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
def _patch_acceleration(x, y, vx, vy, patch, rho_g):
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
def _exit_time(p, v, a, lo, hi):
    """The first time p + v t + a t^2 / 2 leaves [lo, hi] by PATCH_OVERSHOOT_M."""
    return min(
        _first_root(0.5 * a, v, p - hi - PATCH_OVERSHOOT_M),
        _first_root(0.5 * a, v, p - lo + PATCH_OVERSHOOT_M),
    )


@njit(cache=True, error_model="numpy", inline="always")
def _overshoot(p, v, lo, hi):
    """How long (s) a ball at p moving at v has been past [lo, hi] by more than
    PATCH_OVERSHOOT_M (0 if it has not)."""
    past = max(p - hi, lo - p) - PATCH_OVERSHOOT_M
    return past / abs(v) if (past > 0.0) & (v != 0.0) else 0.0


@njit(cache=True, error_model="numpy", inline="always")
def _patch_step(px, py, vx, vy, ax, ay, h, patch, rho_g):
    """A step of h of the classical Runge-Kutta method from (px, py) at (vx, vy), where the
    acceleration is (ax, ay): the position and velocity after it."""
    h2 = 0.5 * h
    x2 = px + h2 * vx
    y2 = py + h2 * vy
    u2 = vx + h2 * ax
    w2 = vy + h2 * ay
    a2x, a2y = _patch_acceleration(x2, y2, u2, w2, patch, rho_g)
    x3 = px + h2 * u2
    y3 = py + h2 * w2
    u3 = vx + h2 * a2x
    w3 = vy + h2 * a2y
    a3x, a3y = _patch_acceleration(x3, y3, u3, w3, patch, rho_g)
    x4 = px + h * u3
    y4 = py + h * w3
    u4 = vx + h * a3x
    w4 = vy + h * a3y
    a4x, a4y = _patch_acceleration(x4, y4, u4, w4, patch, rho_g)
    h6 = h / 6.0
    return (
        px + h6 * (vx + 2.0 * (u2 + u3) + u4),
        py + h6 * (vy + 2.0 * (w2 + w3) + w4),
        vx + h6 * (ax + 2.0 * (a2x + a3x) + a4x),
        vy + h6 * (ay + 2.0 * (a2y + a3y) + a4y),
    )


@njit(cache=True, error_model="numpy", inline="always")
def _patch_height(x, y, patch):
    u = x - patch.xc
    w = patch.yc - y
    return patch.hc + patch.bx * u + patch.by * w + patch.ec * u * w


@njit(cache=True)
def _record_patch_step(traj, n, t_next, dt_record, t0, h, px, py, vx, vy, x1, y1, vx1, vy1,
                       patch):  # fmt: skip
    """Record the points of the trajectory grid inside [t0, t0 + h) of a step on a patch: the
    cubic through its ends with their velocities, on the patch's surface."""
    if traj.shape[0] == 0:
        return n, t_next
    while t_next < t0 + h:
        s = (t_next - t0) / h
        a = (1.0 - s) * (1.0 - s) * (1.0 + 2.0 * s)
        b = s * (1.0 - s) * (1.0 - s) * h
        c = s * s * (3.0 - 2.0 * s)
        d = s * s * (s - 1.0) * h
        x = a * px + b * vx + c * x1 + d * vx1
        y = a * py + b * vy + c * y1 + d * vy1
        n = record(traj, n, t_next, x, y, _patch_height(x, y, patch), ROLL)
        t_next += dt_record
    return n, t_next


@njit(cache=True, error_model="numpy")
def roll(px, py, pz, vx, vy, vz, wx, wy, wz, surface, terrain, plane, t0, traj, n, t_next,
         dt_record):  # fmt: skip
    """Slide, then roll, from a point on the ground until the ball stops.

    The ground is asked at every step: ``surface(terrain, plane, x, y, z)`` gives the Surface
    there (``ground.surface``): its height, normal, turf, state (``mcrun.status``: OK in play,
    or where the shot ends), the longest step along it and the smooth patch around it. Where
    the normal changes, the velocity (and the slip) turn into the new plane, their length
    kept, and gravity along it is taken anew; where the turf changes, its friction and rolling
    resistance. On a plane neither changes, and the steps are those of the plane's exact
    phases.

    The velocity must lie in the ground's plane. Trajectory points are recorded at the times
    t_next, t_next + dt_record, ... Returns (px, py, pz, t_end, status, n, qx, qy): n the next
    row of the trajectory buffer, (qx, qy) the last point in play (where the status is not OK,
    the ball stopped at the first point of the step that left play).
    """
    here = surface(terrain, plane, px, py, pz)
    nx, ny, nz, turf, state = here.nx, here.ny, here.nz, here.turf, here.state
    ds, patch = here.step_m, here.patch
    qx = px
    qy = py
    if state != OK:
        return px, py, pz, t0, state, n, qx, qy
    g_n, gx, gy, gz, g_t, h_max, snap = plane_gravity(nx, ny, nz)
    x0 = px
    y0 = py
    t = t0
    ux, uy, uz = contact_slip(vx, vy, vz, wx, wy, wz, nx, ny, nz)
    k_slide = turf.mu * g_n
    while True:
        u = math.sqrt(ux * ux + uy * uy + uz * uz)
        if u <= 1e-12:
            break
        if t - t0 > MAX_ROLL_TIME_S:
            return px, py, pz, t, NOT_STOPPED, n, qx, qy
        speed = math.sqrt(vx * vx + vy * vy + vz * vz)
        (ax, ay, az), h, done, x1, y1, z1, vx1, vy1, vz1, ux, uy, uz = slide_step(
            px, py, pz, vx, vy, vz, ux, uy, uz, u, gx, gy, gz, k_slide,
            min(h_max, ds / speed), snap,
        )  # fmt: skip
        n, t_next = _record_segment(
            traj, n, t_next, dt_record, t, h, px, py, pz, vx, vy, vz, ax, ay, az
        )
        qx = px
        qy = py
        px, py, pz, vx, vy, vz = x1, y1, z1, vx1, vy1, vz1
        t += h
        here = surface(terrain, plane, px, py, pz)
        pz, mx, my, mz, under = here.height_m, here.nx, here.ny, here.nz, here.turf
        state, ds, patch = here.state, here.step_m, here.patch
        if state != OK:
            return px, py, pz, t, state, n, qx, qy
        if (
            (mx != nx)
            | (my != ny)
            | (mz != nz)
            | (under.mu != turf.mu)
            | (under.rho_g != turf.rho_g)
        ):
            nx, ny, nz = mx, my, mz
            vx, vy, vz = _onto_plane(vx, vy, vz, nx, ny, nz)
            ux, uy, uz = _onto_plane(ux, uy, uz, nx, ny, nz)
            g_n, gx, gy, gz, g_t, h_max, snap = plane_gravity(nx, ny, nz)
            turf = under
            k_slide = turf.mu * g_n
        if done:
            break
    k_roll = turf.rho_g * g_n
    snap = (5.0 / 7.0) * snap
    static = g_t <= k_roll  # tan(beta) <= rho_g: a ball at rest stays at rest
    while True:
        if t - t0 > MAX_ROLL_TIME_S or rolled_too_far(px, py, x0, y0):
            return px, py, pz, t, NOT_STOPPED, n, qx, qy
        v = math.sqrt(vx * vx + vy * vy + vz * vz)
        h_cap = ds / v if v > 0.0 else math.inf
        to_edge = False  # a step to the edge of a level patch, where the next one turns it
        if (patch.smooth != 0.0) & (v > 1e-12):
            # On smooth ground: a Runge-Kutta step to the patch's edge, unless the ball is
            # about to stop.
            decel = (5.0 / 7.0) * G_MPS2 * (vz / v + turf.rho_g * nz)
            t_stop = v / decel if decel > 0.0 else math.inf
            level = patch.smooth == LEVEL_PATCH
            if level:
                # On a level patch the roll's own step is exact: it goes to the patch's edge.
                to_edge = True
                k = (5.0 / 7.0) * turf.rho_g * G_MPS2 / v
                h_cap = min(
                    _exit_time(px - patch.xc, vx, -k * vx, patch.u_lo, patch.u_hi),
                    _exit_time(patch.yc - py, -vy, k * vy, patch.w_lo, patch.w_hi),
                )
            elif STOP_FRACTION * t_stop >= PATCH_DT_MIN_S:
                ax, ay = _patch_acceleration(px, py, vx, vy, patch, turf.rho_g)
                h_edge = min(
                    _exit_time(px - patch.xc, vx, ax, patch.u_lo, patch.u_hi),
                    _exit_time(patch.yc - py, -vy, -ay, patch.w_lo, patch.w_hi),
                )
                h = min(STOP_FRACTION * t_stop, PATCH_DT_MAX_S, h_edge)
                if h > 0.0:
                    x1, y1, vx1, vy1 = _patch_step(px, py, vx, vy, ax, ay, h, patch, turf.rho_g)
                    # Past the patch's edge by more than PATCH_OVERSHOOT_M (the step's length was
                    # foreseen at constant acceleration): the step again, ending there.
                    over = _overshoot(x1 - patch.xc, vx1, patch.u_lo, patch.u_hi)
                    over_w = _overshoot(patch.yc - y1, -vy1, patch.w_lo, patch.w_hi)
                    if over_w > over:
                        over = over_w
                    if (over > PATCH_REFINE_S) & (over < h):
                        h -= over
                        x1, y1, vx1, vy1 = _patch_step(px, py, vx, vy, ax, ay, h, patch, turf.rho_g)
                    if vx1 * vx + vy1 * vy > 0.0:
                        n, t_next = _record_patch_step(
                            traj, n, t_next, dt_record, t, h, px, py, vx, vy, x1, y1, vx1, vy1,
                            patch,
                        )  # fmt: skip
                        qx = px
                        qy = py
                        # The velocity in the patch's tangent plane at the step's end.
                        u = x1 - patch.xc
                        w = patch.yc - y1
                        hx = patch.bx + patch.ec * w
                        hy = -(patch.by + patch.ec * u)
                        vz = hx * vx1 + hy * vy1
                        px, py, vx, vy = x1, y1, vx1, vy1
                        t += h
                        if (
                            (u >= patch.u_lo)
                            & (u <= patch.u_hi)
                            & (w >= patch.w_lo)
                            & (w <= patch.w_hi)
                        ):
                            # Still on the patch: its height and normal there.
                            pz = patch.hc + patch.bx * u + patch.by * w + patch.ec * u * w
                            k = 1.0 / math.sqrt(1.0 + hx * hx + hy * hy)
                            nx = -hx * k
                            ny = -hy * k
                            nz = k
                        else:
                            here = surface(terrain, plane, px, py, pz)
                            pz, nx, ny, nz, under = (
                                here.height_m, here.nx, here.ny, here.nz, here.turf
                            )  # fmt: skip
                            state, ds, patch = here.state, here.step_m, here.patch
                            if state != OK:
                                return px, py, pz, t, state, n, qx, qy
                            # Into the tangent plane of the next patch.
                            vx, vy, vz = _onto_plane(vx, vy, vz, nx, ny, nz)
                            turf = under
                        g_n, gx, gy, gz, g_t, h_max, snap = plane_gravity(nx, ny, nz)
                        snap = (5.0 / 7.0) * snap
                        k_roll = turf.rho_g * g_n
                        static = g_t <= k_roll
                        continue
        if v <= 1e-12:
            if static:
                break
            # At rest on a slope too steep to hold it: it starts down the fall line.
            dx = gx / g_t
            dy = gy / g_t
            dz = gz / g_t
        else:
            dx = vx * (1.0 / v)
            dy = vy * (1.0 / v)
            dz = vz * (1.0 / v)
        (ax, ay, az), h, done, x1, y1, z1, vx1, vy1, vz1 = roll_step(
            px, py, pz, vx, vy, vz, dx, dy, dz, gx, gy, gz, k_roll, min(h_max, h_cap), snap
        )
        n, t_next = _record_segment(
            traj, n, t_next, dt_record, t, h, px, py, pz, vx, vy, vz, ax, ay, az
        )
        qx = px
        qy = py
        px, py, pz, vx, vy, vz = x1, y1, z1, vx1, vy1, vz1
        t += h
        here = surface(terrain, plane, px, py, pz)
        pz, mx, my, mz, under = here.height_m, here.nx, here.ny, here.nz, here.turf
        state, ds, patch = here.state, here.step_m, here.patch
        if state != OK:
            return px, py, pz, t, state, n, qx, qy
        if pz != z1:  # on a terrain: the ground is put under the ball again
            vx, vy, vz = _climbed(vx, vy, vz, pz - z1)
        if (mx != nx) | (my != ny) | (mz != nz) | (under.rho_g != turf.rho_g):
            nx, ny, nz = mx, my, mz
            g_n, gx1, gy1, gz1, g_t, h_max, snap = plane_gravity(nx, ny, nz)
            if not (done | to_edge):
                vx, vy, vz = _turned(vx, vy, vz, gx1 - gx, gy1 - gy, gz1 - gz, h)
            gx, gy, gz = gx1, gy1, gz1
            vx, vy, vz = _onto_plane(vx, vy, vz, nx, ny, nz)
            snap = (5.0 / 7.0) * snap
            turf = under
            k_roll = turf.rho_g * g_n
            static = g_t <= k_roll
        if done and static:
            break
    return px, py, pz, t, OK, n, qx, qy


@njit(cache=True)
def roll_out(x, y, z, vx, vy, vz, wx, wy, wz, surface, terrain, plane, t, traj, n, t_next, dt):
    """After the last impact: the ball stays on the ground with its velocity along it, slides
    and rolls to rest (``roll.roll``). Returns (x, y, z, t, status, n, qx, qy)."""
    here = surface(terrain, plane, x, y, z)
    nx, ny, nz = here.nx, here.ny, here.nz
    vn = vx * nx + vy * ny + vz * nz
    x, y, z, t, status, n, qx, qy = roll(
        x, y, z, vx - vn * nx, vy - vn * ny, vz - vn * nz, wx, wy, wz, surface, terrain, plane,
        t, traj, n, t_next, dt,
    )  # fmt: skip
    n = record(traj, n, t, x, y, z, ROLL)
    return x, y, z, t, status, n, qx, qy


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
    far = (t1 - t > MAX_ROLL_TIME_S) | rolled_too_far(px, py, x, y)
    v = math.sqrt(vx * vx + vy * vy + vz * vz)
    moving = v > 1e-12
    _, h, stopped, x2, y2, _, _, _, _ = roll_step(
        px, py, pz, vx, vy, vz, vx * (1.0 / v), vy * (1.0 / v), vz * (1.0 / v), gx, gy, gz,
        k_roll, h_max, (5.0 / 7.0) * snap,
    )  # fmt: skip
    short = (slid | ~slides) & ~far & (g_t <= k_roll) & (stopped | ~moving)
    return (x2 if moving else px), (y2 if moving else py), (t1 + h if moving else t1), short
