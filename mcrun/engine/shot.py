"""The whole shot, from launch to rest, as one njit kernel on plain floats.

``simulate_shot`` is what the Monte Carlo engine runs in ``prange``: no Python objects, no
allocation per step, a status code instead of an exception. It flies the ball with fixed RK4
steps (``flight.py``), locates the landing inside the last step, then hands over to the
event-driven part: bounces (``bounce.py``) as exact ballistic hops until the next hop would be
lower than the turf's critical height, then the slide and roll (``roll.py``).

Frames: the kernel's inputs and outputs are in the user's frame, x along the target line, y to
the RIGHT, z up (azimuth, spin axis, wind and slope direction positive to the right). Inside it
runs in the right-handed frame with y to the left; the conversion happens here and in
``flight.make_flight_params`` only.

Hops fly without air (the paper's bounce heights, e.g. 2.82 m, are the vacuum values
v_n^2 / 2g; drag over a hop of under 10 m/s changes it by a few per cent) and keep their spin.
"""

import math

from numba import njit

from mcrun.engine.schema import (
    APEX,
    BOUNCES,
    CARRY,
    CARRY_LATERAL,
    FINAL_X,
    FINAL_Y,
    FIRST_BOUNCE_HEIGHT,
    FIRST_BOUNCE_LENGTH,
    FLIGHT_TIME,
    LANDING_ANGLE,
    LANDING_SPEED,
    LANDING_SPIN,
    LAUNCH_ANGLE,
    LAUNCH_SPEED,
    LAUNCH_SPIN,
    N_OUTCOME,
    RUN,
    STATUS,
    TOTAL,
    TOTAL_TIME,
)
from mcrun.physics.bounce import hop_height, incidence, rebound
from mcrun.physics.constants import G_MPS2
from mcrun.physics.flight import hermite_root, rk4_step
from mcrun.physics.launch import initial_state
from mcrun.physics.roll import (
    contact_slip,
    plane_gravity,
    roll,
    roll_step,
    rolled_too_far,
    slide_step,
)
from mcrun.physics.trig import atan2_first_quadrant
from mcrun.status import (
    INVALID_INPUT,
    MAX_BOUNCES,
    MAX_FLIGHT_TIME_S,
    MAX_ROLL_TIME_S,
    NOT_LANDED,
    TOO_MANY_BOUNCES,
)
from mcrun.trajectory import BOUNCE, FLIGHT, ROLL, record

# A hop higher than this fraction of the one before ends the bouncing (see run_out). On level
# turf the hops shrink by 5 % or more each time; on a downhill, gravity along the slope during
# each hop feeds eq. (8)'s growth of theta_c with speed and the hops settle at a height of
# their own (5 mm at 3 deg, 33 mm at 5 deg) instead of dying out.
HOP_DECAY_LIMIT = 0.99

# The default flight step, chosen from the accuracy study (tests/test_accuracy.py, README
# "Numerical accuracy"): in uniform wind RK4 at 0.2 s puts carry within 4.3 mm of a DOP853
# reference for every model (within 0.8 mm for the quadratic ones); a log or power wind
# profile, whose shear is singular at the ground, needs 0.02 s for 2 mm.
DEFAULT_DT_S = 0.2
DEFAULT_DT_WIND_PROFILE_S = 0.02
# Interval of the trajectory points recorded during the hops and the roll.
TRAJECTORY_DT_S = 0.01


def default_dt_s(wind_profile="uniform"):
    """The default flight step (s) for a wind profile given by name."""
    return DEFAULT_DT_S if wind_profile == "uniform" else DEFAULT_DT_WIND_PROFILE_S


@njit(cache=True)
def fail(out, i, status, first=CARRY):
    """Record that shot i ended with ``status``: its fields from ``first`` on (the flight's and
    the run's, or the run's alone when the flight was complete) are NaN."""
    for k in range(first, N_OUTCOME):
        out[i, k] = math.nan
    out[i, STATUS] = status


# What follows an impact (``impact``).
HOPS = 0
ROLLS = 1
TOO_MANY = 2


@njit(cache=True, error_model="numpy", inline="always")
def impact(vx, vy, vz, wx, wy, wz, nx, ny, nz, turf, bounces, previous_height):
    """One impact (``bounce``) and what follows it: the velocity and spin after it, the height
    and duration of the hop it starts, and whether the ball HOPS, ROLLS (the hop would be lower
    than the critical height, Penner 2002, or no lower than HOP_DECAY_LIMIT times the one
    before) or has bounced TOO_MANY times. Branch-free, for loops over many shots."""
    ex, ey, ez, vne, _ = incidence(vx, vy, vz, nx, ny, nz, turf)
    return impact_rebound(
        vx, vy, vz, wx, wy, wz, nx, ny, nz, ex, ey, ez, vne, turf, bounces, previous_height
    )


@njit(cache=True, error_model="numpy", inline="always")
def impact_rebound(
    vx, vy, vz, wx, wy, wz, nx, ny, nz, ex, ey, ez, vne, turf, bounces, previous_height
):
    """The rest of ``impact`` once ``bounce.incidence`` has found the equivalent surface."""
    vx, vy, vz, wx, wy, wz, _, _, _ = rebound(vx, vy, vz, wx, wy, wz, ex, ey, ez, vne, turf)
    height = hop_height(vx, vy, vz, nx, ny, nz)
    rolls = (height < turf.critical_height_m) | (
        (bounces > 0) & (height > HOP_DECAY_LIMIT * previous_height)
    )
    then = ROLLS if rolls else (TOO_MANY if bounces == MAX_BOUNCES else HOPS)
    # Exact ballistic hop back to the plane: n.(v T - g z T^2 / 2) = 0.
    hop_time = 2.0 * (vx * nx + vy * ny + vz * nz) * (1.0 / (G_MPS2 * nz))
    return vx, vy, vz, wx, wy, wz, height, hop_time, then


@njit(cache=True, error_model="numpy", inline="always")
def hop(x, y, z, vx, vy, vz, hop_time):
    """Position (x, y, z) and vertical velocity at the end of a hop of ``hop_time`` in vacuum."""
    return (
        x + vx * hop_time,
        y + vy * hop_time,
        z + vz * hop_time - 0.5 * G_MPS2 * hop_time * hop_time,
        vz - G_MPS2 * hop_time,
    )


@njit(cache=True)
def roll_out(x, y, z, vx, vy, vz, wx, wy, wz, nx, ny, nz, turf, t, traj, n, t_next, dt):
    """After the last impact: the ball stays on the ground with its velocity along the plane,
    slides and rolls to rest (``roll.roll``). Returns (x, y, z, t, status, n)."""
    vn = vx * nx + vy * ny + vz * nz
    x, y, z, t, status, n = roll(
        x,
        y,
        z,
        vx - vn * nx,
        vy - vn * ny,
        vz - vn * nz,
        wx,
        wy,
        wz,
        nx,
        ny,
        nz,
        turf,
        t,
        traj,
        n,
        t_next,
        dt,
    )
    n = record(traj, n, t, x, y, z, ROLL)
    return x, y, z, t, status, n


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


@njit(cache=True)
def run_out(x, y, z, vx, vy, vz, wx, wy, wz, nx, ny, nz, turf, t, traj, n, dt):
    """The run (Penner 2002): bounces, then slide and roll, from a ball touching the ground.

    Everything in the core's frame (y to the LEFT): position (x, y, z) on the ground plane of
    unit normal (nx, ny, nz), velocity v into it and spin vector w (rad/s) at time t. Hops are
    exact ballistic arcs without air until the next hop would be lower than the turf's
    critical height (Penner 2002), or no lower than HOP_DECAY_LIMIT times the hop before
    (ours: hops that no longer die out are a rolling ball); then ``roll.roll``. Trajectory
    points go into ``traj`` from row n, every dt. Returns (x, y, z, t, status, bounces,
    first_bounce_height_m, first_bounce_length_m, n) at rest; first_bounce_length_m is
    measured along x. Status TOO_MANY_BOUNCES (a safety bound the rules above end every
    sequence well within) leaves the position where the bouncing stopped.
    """
    first_height = 0.0
    first_length = 0.0
    previous_height = 0.0
    bounces = 0
    t_next = t + dt
    while True:
        vx, vy, vz, wx, wy, wz, height, hop_time, then = impact(
            vx, vy, vz, wx, wy, wz, nx, ny, nz, turf, bounces, previous_height
        )
        if then == ROLLS:
            break
        if then == TOO_MANY:
            return x, y, z, t, TOO_MANY_BOUNCES, bounces, first_height, first_length, n
        while traj.shape[0] > 0 and t_next < t + hop_time:
            s = t_next - t
            n = record(
                traj, n, t_next, x + vx * s, y + vy * s, z + vz * s - 0.5 * G_MPS2 * s * s, BOUNCE
            )
            t_next += dt
        x1, y, z, vz = hop(x, y, z, vx, vy, vz, hop_time)
        if bounces == 0:
            first_height = height
            first_length = x1 - x
        x = x1
        t += hop_time
        previous_height = height
        bounces += 1
    x, y, z, t, status, n = roll_out(
        x, y, z, vx, vy, vz, wx, wy, wz, nx, ny, nz, turf, t, traj, n, t_next, dt
    )
    return x, y, z, t, status, bounces, first_height, first_length, n


@njit(cache=True)
def simulate_shot(
    speed,
    launch_angle,
    azimuth,
    spin,
    spin_axis,
    p,
    turf,
    slope,
    fall_line,
    dt,
    table,
    out,
    i,
    traj,
):
    """Simulate one shot and write its outcome into ``out[i, :]`` (fields ``OUTCOME_FIELDS``).

    Parameters
    ----------
    speed, launch_angle, azimuth, spin, spin_axis : float
        Ball speed (m/s), vertical launch angle above the horizontal (rad), horizontal launch
        angle (rad, positive right), total spin (rad/s) and spin axis tilt (rad, positive curves
        right), as a launch monitor reports them.
    p : FlightParams
        Air, wind and aerodynamic model (``flight.make_flight_params``).
    turf : Turf
        The ground the ball lands on.
    slope, fall_line : float
        Slope of the landing area (rad) and the direction it falls towards (rad from the target
        line, positive right). The ground is the plane of that slope through the landing point.
    dt : float
        Flight step (s).
    table : ndarray
        ``aero.QUADRATIC_COEFFICIENTS``.
    out : ndarray, shape (n, N_OUTCOME)
    i : int
        Row of ``out`` to write.
    traj : ndarray, shape (m, 5)
        Trajectory buffer (t, x, y, z, phase), filled every ``dt``; shape (0, 5) records nothing.

    Returns
    -------
    int
        Number of trajectory points the shot has (more than ``traj`` holds if it was too short).
    """
    if not start_shot(
        speed, launch_angle, azimuth, spin, spin_axis, p, turf, slope, fall_line, dt, out, i
    ):
        return 0
    vx, vy, vz, ax, ay, az, w = initial_state(speed, launch_angle, azimuth, spin, spin_axis)
    ctx = (ax, ay, az, p, table)
    x = 0.0
    y = 0.0
    z = 0.0
    t = 0.0
    apex = 0.0
    n = record(traj, 0, t, x, y, z, FLIGHT)
    while True:
        if t > MAX_FLIGHT_TIME_S:
            fail(out, i, NOT_LANDED)
            return n
        x1, y1, z1, vx1, vy1, vz1, w1 = rk4_step(x, y, z, vx, vy, vz, w, dt, ctx)
        if z1 < 0.0:
            break
        apex = apex_after_step(apex, z, vz, z1, vz1, dt)
        n = record_flight(traj, n, t, dt, x, y, z, vx, vy, vz, w, ctx)
        x, y, z, vx, vy, vz, w = x1, y1, z1, vx1, vy1, vz1, w1
        t += dt
        n = record(traj, n, t, x, y, z, FLIGHT)
    return finish_shot(
        x, y, z, vx, vy, vz, w, z1, vz1, t, apex, ctx, turf, slope, fall_line, dt, out, i, traj, n
    )


@njit(cache=True)
def start_shot(
    speed, launch_angle, azimuth, spin, spin_axis, p, turf, slope, fall_line, dt, out, i
):
    """Write the launch fields of shot i and check its inputs; False (and status
    INVALID_INPUT written) when one is non-finite or non-physical."""
    out[i, LAUNCH_SPEED] = speed
    out[i, LAUNCH_ANGLE] = math.degrees(launch_angle)
    out[i, LAUNCH_SPIN] = spin
    inputs = speed + launch_angle + azimuth + spin + spin_axis + slope + fall_line + dt
    inputs += p.cd_scale + p.cl_scale + p.wind_x_mps + p.wind_y_mps + p.wind_profile_parameter
    inputs += turf.e0 + turf.e1 + turf.e2 + turf.e_break_speed_mps + turf.e_high
    if not (
        math.isfinite(inputs)
        and speed > 0.0
        and spin >= 0.0
        and dt > 0.0
        and 0.0 <= slope < 0.5 * math.pi
        and p.air_density_kgpm3 > 0.0
        and p.kinematic_viscosity_m2ps > 0.0
        and turf.mu >= 0.0
        and turf.softness >= 0.0
        and turf.rho_g >= 0.0
        and turf.critical_height_m > 0.0
    ):
        fail(out, i, INVALID_INPUT)
        return False
    return True


@njit(cache=True, error_model="numpy", inline="always")
def apex_after_step(apex, z, vz, z1, vz1, dt):
    """Highest point so far after a step from (z, vz) to (z1, vz1)."""
    # Apex inside the step (vz changes sign), taking vz linear in time.
    inside = z + 0.5 * vz * dt * vz / (vz - vz1)
    crossed = (vz > 0.0) & (vz1 <= 0.0)
    return max(max(apex, inside) if crossed else apex, z1)


@njit(cache=True)
def record_flight(traj, n, t, h, x, y, z, vx, vy, vz, w, ctx):
    """Trajectory points inside a flight step from the state at t, every TRAJECTORY_DT_S
    up to t + h (exclusive), by RK4 from the step's start: the recorded path does not
    depend on the step."""
    k = 1
    while traj.shape[0] > 0 and k * TRAJECTORY_DT_S < h - 1e-9:
        s = k * TRAJECTORY_DT_S
        px, py, pz, _, _, _, _ = rk4_step(x, y, z, vx, vy, vz, w, s, ctx)
        n = record(traj, n, t + s, px, py, pz, FLIGHT)
        k += 1
    return n


@njit(cache=True, error_model="numpy", inline="always")
def landing_newton(h, z1, vz1, dt):
    """The next length of the landing step: a Newton step on the height z1 (vertical speed
    vz1) that a step of length h from the last state above the ground ends at, within [0, dt]."""
    return min(max(h - z1 / vz1, 0.0), dt) if vz1 < 0.0 else h


@njit(cache=True, error_model="numpy", inline="always")
def landing_speed_angle(vx, vy, vz):
    """Speed (m/s) and angle of descent from the vertical (deg) of a ball at velocity v."""
    angle = atan2_first_quadrant(math.sqrt(vx * vx + vy * vy), abs(vz))
    return (
        math.sqrt(vx * vx + vy * vy + vz * vz),
        math.degrees(math.pi - angle if vz > 0.0 else angle),
    )


@njit(cache=True, error_model="numpy")
def ground_normal(slope, fall_line):
    """Unit normal of the ground plane of the given slope, in the core's frame: the fall line
    (cos a, -sin a, 0), and the normal tilts towards it."""
    if slope == 0.0:
        return 0.0, 0.0, 1.0
    sb = math.sin(slope)
    return sb * math.cos(fall_line), -sb * math.sin(fall_line), math.cos(slope)


@njit(cache=True)
def write_landing(out, i, x, y, t, apex, speed, angle_deg, w):
    """Write the flight fields of shot i, which lands at (x, y) at time t."""
    out[i, CARRY] = x
    out[i, CARRY_LATERAL] = -y
    out[i, APEX] = apex
    out[i, FLIGHT_TIME] = t
    out[i, LANDING_SPEED] = speed
    out[i, LANDING_ANGLE] = angle_deg
    out[i, LANDING_SPIN] = w


@njit(cache=True, error_model="numpy")
def land(x, y, z, vx, vy, vz, w, z1, vz1, t, apex, ctx, slope, fall_line, dt, out, i, traj, n):
    """From the last step of the flight, (x, ..., w) at t above the ground and z1, vz1 below it:
    locate the landing and write the flight fields of shot i. Returns the ball at landing,
    (x, y, vx, vy, vz, wx, wy, wz, t), the normal (nx, ny, nz) of the ground there, and n.

    ``ctx`` as for ``rk4``'s derivative function; its first three items are the spin axis.
    """
    # Landing: root of the cubic Hermite interpolant of z, then an RK4 step of that length from
    # the start of the step, refined by Newton steps on z.
    h = hermite_root(z, vz, z1, vz1, dt)
    for _ in range(2):
        _, _, z1, _, _, vz1, _ = rk4_step(x, y, z, vx, vy, vz, w, h, ctx)
        h = landing_newton(h, z1, vz1, dt)
    n = record_flight(traj, n, t, h, x, y, z, vx, vy, vz, w, ctx)
    x1, y1, _, vx1, vy1, vz1, w1 = rk4_step(x, y, z, vx, vy, vz, w, h, ctx)
    # The apex may lie in the landing step (a flight of one or two steps).
    apex = apex_after_step(apex, z, vz, 0.0, vz1, h)
    t += h
    n = record(traj, n, t, x1, y1, 0.0, FLIGHT)
    speed, angle_deg = landing_speed_angle(vx1, vy1, vz1)
    write_landing(out, i, x1, y1, t, apex, speed, angle_deg, w1)
    nx, ny, nz = ground_normal(slope, fall_line)
    ax, ay, az = ctx[0], ctx[1], ctx[2]
    return x1, y1, vx1, vy1, vz1, w1 * ax, w1 * ay, w1 * az, t, nx, ny, nz, n


@njit(cache=True)
def write_run(out, i, landing_x, x, y, t, status, bounces, first_height, first_length):
    """Write the run fields of shot i, which landed at x = landing_x and rests at (x, y)."""
    if status == TOO_MANY_BOUNCES:
        fail(out, i, TOO_MANY_BOUNCES, BOUNCES)  # the flight's fields stand
        return
    out[i, BOUNCES] = bounces
    out[i, FIRST_BOUNCE_HEIGHT] = first_height
    out[i, FIRST_BOUNCE_LENGTH] = first_length
    out[i, RUN] = x - landing_x
    out[i, TOTAL] = x
    out[i, FINAL_X] = x
    out[i, FINAL_Y] = -y
    out[i, TOTAL_TIME] = t
    out[i, STATUS] = status


@njit(cache=True)
def finish_shot(
    x, y, z, vx, vy, vz, w, z1, vz1, t, apex, ctx, turf, slope, fall_line, dt, out, i, traj, n
):
    """From the last step of the flight: ``land``, ``run_out``, ``write_run``."""
    x, y, vx, vy, vz, wx, wy, wz, t, nx, ny, nz, n = land(
        x, y, z, vx, vy, vz, w, z1, vz1, t, apex, ctx, slope, fall_line, dt, out, i, traj, n
    )
    landing_x = x
    x, y, z, t, status, bounces, first_height, first_length, n = run_out(
        x, y, 0.0, vx, vy, vz, wx, wy, wz, nx, ny, nz, turf, t, traj, n, TRAJECTORY_DT_S
    )
    write_run(out, i, landing_x, x, y, t, status, bounces, first_height, first_length)
    return n
