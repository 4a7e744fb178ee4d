"""The roll's loop: from the last impact to rest, a step of ``physics.roll`` at a time, asking
the ground (``ground.surface``) where each step ends.

The step formulas (the slide's and the roll's steps on a plane, the Runge-Kutta step on a
smooth patch, the turn of the velocity into a new plane) are the physics' (``physics.roll``);
this loop strings them together where the ground changes under the ball: its normal, its turf,
its state under the Rules. On a Plane neither changes, and the steps are those of the plane's
exact phases. The lanes of many shots (``engine.bounce_lanes``) roll out on a Plane with
``roll.roll_out_short`` where one step of each phase brings the ball to rest, and here
otherwise.
"""

import math

from numba import njit

from mcrun import ground
from mcrun.physics.constants import G_MPS2
from mcrun.physics.roll import (
    LEVEL_PATCH,
    PATCH_DT_MAX_S,
    PATCH_DT_MIN_S,
    PATCH_REFINE_S,
    STOP_FRACTION,
    climbed,
    contact_slip,
    exit_time,
    onto_plane,
    overshoot,
    patch_acceleration,
    patch_height,
    patch_step,
    plane_gravity,
    roll_step,
    rolled_too_far,
    slide_step,
    turned,
)
from mcrun.status import MAX_ROLL_DISTANCE_M, MAX_ROLL_TIME_S, NOT_STOPPED, OK
from mcrun.trajectory import ROLL, record


@njit(cache=True)
def _record_segment(traj, n, t_next, dt_record, t0, h, px, py, pz, vx, vy, vz, ax, ay, az):
    """Record the points of the trajectory grid that fall inside [t0, t0 + h)."""
    if traj is None:  # (a batch: pruned)
        return n, t_next
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


@njit(cache=True)
def _record_patch_step(traj, n, t_next, dt_record, t0, h, px, py, vx, vy, x1, y1, vx1, vy1,
                       patch):  # fmt: skip
    """Record the points of the trajectory grid inside [t0, t0 + h) of a step on a patch: the
    cubic through its ends with their velocities, on the patch's surface."""
    if traj is None:  # (a batch: pruned)
        return n, t_next
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
        n = record(traj, n, t_next, x, y, patch_height(x, y, patch), ROLL)
        t_next += dt_record
    return n, t_next


@njit(cache=True, error_model="numpy")
def roll(px, py, pz, vx, vy, vz, wx, wy, wz, terrain, plane, t0, traj, n, t_next, dt_record):
    """Slide, then roll, from a point on the ground until the ball stops.

    The ground is asked at every step: ``ground.surface(terrain, plane, x, y, z)`` gives the
    Surface there: its height, normal, turf, state (``mcrun.status``: OK in play,
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
    here = ground.surface(terrain, plane, px, py, pz)
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
        speed = math.sqrt(vx * vx + vy * vy + vz * vz)
        left = _bounds_left(t - t0, px - x0, py - y0, speed)
        if left <= 0.0:  # (the distance too: a ball sliding on mu 0 went 36 km)
            return px, py, pz, t, NOT_STOPPED, n, qx, qy
        (ax, ay, az), h, done, x1, y1, z1, vx1, vy1, vz1, ux, uy, uz = slide_step(
            px, py, pz, vx, vy, vz, ux, uy, uz, u, gx, gy, gz, k_slide,
            min(h_max, ds / speed, left), snap,
        )  # fmt: skip
        n, t_next = _record_segment(
            traj, n, t_next, dt_record, t, h, px, py, pz, vx, vy, vz, ax, ay, az
        )
        qx = px
        qy = py
        px, py, pz, vx, vy, vz = x1, y1, z1, vx1, vy1, vz1
        t += h
        here = ground.surface(terrain, plane, px, py, pz)
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
            vx, vy, vz = onto_plane(vx, vy, vz, nx, ny, nz)
            ux, uy, uz = onto_plane(ux, uy, uz, nx, ny, nz)
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
        # (A Plane has no patches: Numba prunes the branch on ``terrain is not None`` from a
        # Plane's kernel, which then compiles none of this.)
        if (terrain is not None) and ((patch.smooth != 0.0) & (v > 1e-12)):
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
                    exit_time(px - patch.xc, vx, -k * vx, patch.u_lo, patch.u_hi),
                    exit_time(patch.yc - py, -vy, k * vy, patch.w_lo, patch.w_hi),
                )
            elif STOP_FRACTION * t_stop >= PATCH_DT_MIN_S:
                ax, ay = patch_acceleration(px, py, vx, vy, patch, turf.rho_g)
                h_edge = min(
                    exit_time(px - patch.xc, vx, ax, patch.u_lo, patch.u_hi),
                    exit_time(patch.yc - py, -vy, -ay, patch.w_lo, patch.w_hi),
                )
                h = min(STOP_FRACTION * t_stop, PATCH_DT_MAX_S, h_edge)
                if h > 0.0:
                    x1, y1, vx1, vy1 = patch_step(px, py, vx, vy, ax, ay, h, patch, turf.rho_g)
                    # Past the patch's edge by more than PATCH_OVERSHOOT_M (the step's length was
                    # foreseen at constant acceleration): the step again, ending there.
                    over = overshoot(x1 - patch.xc, vx1, patch.u_lo, patch.u_hi)
                    over_w = overshoot(patch.yc - y1, -vy1, patch.w_lo, patch.w_hi)
                    if over_w > over:
                        over = over_w
                    if (over > PATCH_REFINE_S) & (over < h):
                        h -= over
                        x1, y1, vx1, vy1 = patch_step(px, py, vx, vy, ax, ay, h, patch, turf.rho_g)
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
                            here = ground.surface(terrain, plane, px, py, pz)
                            pz, nx, ny, nz, under = (
                                here.height_m, here.nx, here.ny, here.nz, here.turf
                            )  # fmt: skip
                            state, ds, patch = here.state, here.step_m, here.patch
                            if state != OK:
                                return px, py, pz, t, state, n, qx, qy
                            # Into the tangent plane of the next patch.
                            vx, vy, vz = onto_plane(vx, vy, vz, nx, ny, nz)
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
        left = _bounds_left(t - t0, px - x0, py - y0, v)
        if left <= 0.0:
            return px, py, pz, t, NOT_STOPPED, n, qx, qy
        (ax, ay, az), h, done, x1, y1, z1, vx1, vy1, vz1 = roll_step(
            px, py, pz, vx, vy, vz, dx, dy, dz, gx, gy, gz, k_roll, min(h_max, h_cap, left), snap
        )
        n, t_next = _record_segment(
            traj, n, t_next, dt_record, t, h, px, py, pz, vx, vy, vz, ax, ay, az
        )
        qx = px
        qy = py
        px, py, pz, vx, vy, vz = x1, y1, z1, vx1, vy1, vz1
        t += h
        here = ground.surface(terrain, plane, px, py, pz)
        pz, mx, my, mz, under = here.height_m, here.nx, here.ny, here.nz, here.turf
        state, ds, patch = here.state, here.step_m, here.patch
        if state != OK:
            return px, py, pz, t, state, n, qx, qy
        if pz != z1:  # on a terrain: the ground is put under the ball again
            vx, vy, vz = climbed(vx, vy, vz, pz - z1)
        if (mx != nx) | (my != ny) | (mz != nz) | (under.rho_g != turf.rho_g):
            nx, ny, nz = mx, my, mz
            g_n, gx1, gy1, gz1, g_t, h_max, snap = plane_gravity(nx, ny, nz)
            if not (done | to_edge):
                vx, vy, vz = turned(vx, vy, vz, gx1 - gx, gy1 - gy, gz1 - gz, h)
            gx, gy, gz = gx1, gy1, gz1
            vx, vy, vz = onto_plane(vx, vy, vz, nx, ny, nz)
            snap = (5.0 / 7.0) * snap
            turf = under
            k_roll = turf.rho_g * g_n
            static = g_t <= k_roll
        if done and static:
            break
    return px, py, pz, t, OK, n, qx, qy


@njit(cache=True, error_model="numpy", inline="always")
def _bounds_left(elapsed_s, dx_m, dy_m, speed_mps):
    """The longest step (s) a ball at ``speed_mps``, ``elapsed_s`` into its roll and (dx_m,
    dy_m) from where it began, may take within the roll's bounds (MAX_ROLL_TIME_S,
    MAX_ROLL_DISTANCE_M); 0 where it has reached one of them (to the nanosecond or
    nanometre). A step that stops the ball within them is shorter, and so unchanged."""
    time_left = MAX_ROLL_TIME_S - elapsed_s
    distance_left = MAX_ROLL_DISTANCE_M - math.sqrt(dx_m * dx_m + dy_m * dy_m)
    if time_left <= 1e-9 or distance_left <= 1e-9:
        return 0.0
    if speed_mps > 0.0:
        return min(time_left, distance_left / speed_mps)
    return time_left


@njit(cache=True)
def roll_out(x, y, z, vx, vy, vz, wx, wy, wz, terrain, plane, t, traj, n, t_next, dt):
    """After the last impact: the ball stays on the ground with its velocity along it, slides
    and rolls to rest (``roll``). Returns (x, y, z, t, status, n, qx, qy)."""
    here = ground.surface(terrain, plane, x, y, z)
    nx, ny, nz = here.nx, here.ny, here.nz
    vn = vx * nx + vy * ny + vz * nz
    x, y, z, t, status, n, qx, qy = roll(
        x, y, z, vx - vn * nx, vy - vn * ny, vz - vn * nz, wx, wy, wz, terrain, plane,
        t, traj, n, t_next, dt,
    )  # fmt: skip
    n = record(traj, n, t, x, y, z, ROLL)
    return x, y, z, t, status, n, qx, qy
