"""The batch kernel: many shots in parallel, structure-of-arrays in, structure-of-arrays out.

``simulate_batch`` simulates the rows of ``inputs``, an (n, N_INPUT) float64 array in Fortran
order (each column contiguous, named by ``INPUT_FIELDS``, SI, user frame), in ``prange`` over
tasks of TASK_SHOTS shots, and writes ``out``, an (n, N_OUTCOME) float64 array in Fortran order
whose columns are ``schema.OUTCOME_FIELDS``. Within a task the shots fly, land, bounce and
roll out in lockstep lanes (below); each lane does exactly what ``shot.simulate_shot`` does
for one shot.
Every shot is independent of the others, of its lane and of the thread that runs it, so the
results are the same bit for bit whatever the thread count or the order of the rows.
"""

import numba
import numpy as np
from numba import njit, prange

from mcrun.engine.schema import N_INPUT, N_OUTCOME
from mcrun.engine.shot import (
    HOPS,
    TOO_MANY,
    TRAJECTORY_DT_S,
    apex_after_step,
    fail,
    ground_normal,
    hop,
    impact_rebound,
    landing_newton,
    landing_speed_angle,
    roll_out,
    roll_out_short,
    simulate_shot,
    start_shot,
    write_landing,
    write_run,
)
from mcrun.physics.aero import QUADRATIC_COEFFICIENTS, is_quadratic
from mcrun.physics.bounce import incidence
from mcrun.physics.constants import BALL_AREA_M2, BALL_MASS_KG
from mcrun.physics.flight import (
    WIND_UNIFORM,
    derivatives_quadratic,
    hermite_root,
    make_flight_params,
    rk4_combine,
    rk4_stage_quadratic,
)
from mcrun.physics.launch import initial_state
from mcrun.physics.turf import Turf
from mcrun.status import MAX_FLIGHT_TIME_S, NOT_LANDED, OK, TOO_MANY_BOUNCES


@njit(cache=True, error_model="numpy")
def _turf(inputs, i):
    """Turf of shot i."""
    c = inputs[i]
    return Turf(c[15], c[16], c[17], c[18], c[19], c[20], c[21], c[22], c[23])


@njit(cache=True, error_model="numpy")
def _params(inputs, i):
    """FlightParams and Turf of shot i."""
    c = inputs[i]
    p = make_flight_params(
        c[5], c[6], int(c[7]), c[8], c[9], c[10], c[11], int(c[12]), c[13], c[14]
    )
    return p, _turf(inputs, i)


@njit(cache=True, error_model="numpy")
def _shot(inputs, i, table, out, j, traj):
    """Shot i of ``inputs`` into row j of ``out``, one at a time (any model, any wind)."""
    c = inputs[i]
    p, turf = _params(inputs, i)
    return simulate_shot(
        c[0], c[1], c[2], c[3], c[4], p, turf, c[24], c[25], c[26], table, out, j, traj
    )


# Lockstep flight: shots with a quadratic aerodynamic model in uniform wind (the usual case)
# fly LANES at a time, a block of lanes stepped together by loops that the compiler turns into
# vector instructions. A lane whose ball goes below the ground hands its last state to the
# landing table and takes the next shot; once LANES shots wait there, their landings are
# located together (``shot.land``, in vectorised loops), and they wait for the bounce lanes.
# Every operation on a lane is the one ``shot.simulate_shot`` does, in the same order, so the
# results are the same bit for bit.
LANES = 16
# Rows of the lane table, a flat array whose row r of lane k is at r * LANES + k (a layout
# whose offsets the compiler can see, so that it vectorises the loop over the lanes): the state,
# the height and vertical speed at the end of the last step, the lane's constants, ...
(X, Y, Z, VX, VY, VZ, W, Z1, VZ1, AXIS_X, AXIS_Y, AXIS_Z, WIND_X, WIND_Y, K_CD, K_CL, A0, A1,
 A2, B0, B1, B2, S_MAX, DT, T, APEX) = range(26)  # fmt: skip
N_SHOT_ROWS = 26  # (the rows that go with a shot into the landing table)
# ... the derivatives (K) and velocities (V) of the RK4 stages of the step under way, the rest
# of the state at its end (with Z1 and VZ1), and, in the landing table only, the flight step,
# the ground's normal, the shot, and the speed and angle at landing.
K1, K2, K3 = 26, 30, 34  # four rows each: ax, ay, az, dspin/dt
V2, V3 = 38, 41  # three rows each: vx, vy, vz
(X1, Y1, VX1, VY1, W1, H_MAX, NX, NY, NZ, SHOT, SPEED, ANGLE) = range(44, 56)
N_LANE_ROWS = 56


@njit(cache=True, error_model="numpy", inline="always")
def _any_lane_busy(shot):
    """Whether some lane still holds a shot (shot[k] is -1 for an empty lane)."""
    for k in range(LANES):
        if shot[k] >= 0:
            return True
    return False


@njit(cache=True, error_model="numpy")
def _load_lane(inputs, next_i, stop, table, out, lanes, shot, k):
    """Put the next shot that can fly in lockstep into lane k; shots that cannot (another
    model or wind profile) are simulated on the spot, invalid ones recorded as such. Returns
    the index of the shot after the last one taken; shot[k] = -1 when none was left."""
    no_trajectory = np.empty((0, 5))
    while next_i < stop:
        i = next_i
        next_i += 1
        c = inputs[i]
        p, turf = _params(inputs, i)
        if not start_shot(c[0], c[1], c[2], c[3], c[4], p, turf, c[24], c[25], c[26], out, i):
            continue
        if not (is_quadratic(p.aero_model) and p.wind_profile == WIND_UNIFORM):
            _shot(inputs, i, table, out, i, no_trajectory)
            continue
        vx, vy, vz, ax, ay, az, w = initial_state(c[0], c[1], c[2], c[3], c[4])
        k_air = 0.5 * p.air_density_kgpm3 * BALL_AREA_M2 / BALL_MASS_KG
        row = table[p.aero_model]
        for field, value in (
            (X, 0.0),
            (Y, 0.0),
            (Z, 0.0),
            (VX, vx),
            (VY, vy),
            (VZ, vz),
            (W, w),
            (AXIS_X, ax),
            (AXIS_Y, ay),
            (AXIS_Z, az),
            (WIND_X, p.wind_x_mps),
            (WIND_Y, p.wind_y_mps),
            (K_CD, k_air * p.cd_scale),
            (K_CL, k_air * p.cl_scale),
            (A0, row[0]),
            (A1, row[1]),
            (A2, row[2]),
            (B0, row[3]),
            (B1, row[4]),
            (B2, row[5]),
            (S_MAX, row[6]),
            (DT, c[26]),
            (T, 0.0),
            (APEX, 0.0),
        ):
            lanes[field * LANES + k] = value
        shot[k] = i
        return next_i
    shot[k] = -1
    return next_i


@njit(cache=True, error_model="numpy", inline="always")
def _lane_context(lanes, k):
    """The ``flight.derivatives_quadratic`` context of lane k."""
    return (
        lanes[AXIS_X * LANES + k], lanes[AXIS_Y * LANES + k], lanes[AXIS_Z * LANES + k],
        lanes[WIND_X * LANES + k], lanes[WIND_Y * LANES + k], lanes[K_CD * LANES + k],
        lanes[K_CL * LANES + k], lanes[A0 * LANES + k], lanes[A1 * LANES + k],
        lanes[A2 * LANES + k], lanes[B0 * LANES + k], lanes[B1 * LANES + k],
        lanes[B2 * LANES + k], lanes[S_MAX * LANES + k],
    )  # fmt: skip


@njit(cache=True, error_model="numpy", inline="always")
def _lane_velocity(lanes, row, k):
    """The three rows row.. of lane k: a velocity (vx, vy, vz)."""
    return lanes[row * LANES + k], lanes[(row + 1) * LANES + k], lanes[(row + 2) * LANES + k]


@njit(cache=True, error_model="numpy", inline="always")
def _lane_derivative(lanes, row, k):
    """The four rows row.. of lane k: a derivative (ax, ay, az, dspin/dt)."""
    return (
        lanes[row * LANES + k], lanes[(row + 1) * LANES + k], lanes[(row + 2) * LANES + k],
        lanes[(row + 3) * LANES + k],
    )  # fmt: skip


@njit(cache=True, error_model="numpy", inline="always")
def _set_lane_velocity(lanes, row, k, v):
    """Rows row.. of lane k from the velocity v."""
    lanes[row * LANES + k] = v[0]
    lanes[(row + 1) * LANES + k] = v[1]
    lanes[(row + 2) * LANES + k] = v[2]


@njit(cache=True, error_model="numpy", inline="always")
def _set_lane_derivative(lanes, row, k, d):
    """Rows row.. of lane k from the derivative d."""
    lanes[row * LANES + k] = d[0]
    lanes[(row + 1) * LANES + k] = d[1]
    lanes[(row + 2) * LANES + k] = d[2]
    lanes[(row + 3) * LANES + k] = d[3]


@njit(cache=True, error_model="numpy", inline="always")
def _lane_stage(lanes, k, c, derivative, vz_k):
    """The RK4 stage of lane k at c times ``derivative`` (``flight.rk4_stage``)."""
    return rk4_stage_quadratic(
        lanes[VX * LANES + k], lanes[VY * LANES + k], lanes[VZ * LANES + k],
        lanes[W * LANES + k], lanes[Z * LANES + k], c, derivative, vz_k,
        _lane_context(lanes, k),
    )  # fmt: skip


@njit(cache=True, error_model="numpy")
def _rk4_lanes(lanes):
    """An RK4 step of length DT of every lane, from its state to rows X1..W1:
    ``flight.rk4_step`` with ``flight.derivatives_quadratic``, split into one vectorised loop
    per stage. The iterations of a loop are independent, so the processor overlaps their long
    chains of square roots and divisions, where a single loop through the whole step waits on
    them."""
    for k in range(LANES):
        _set_lane_derivative(
            lanes,
            K1,
            k,
            derivatives_quadratic(
                lanes[VX * LANES + k], lanes[VY * LANES + k], lanes[VZ * LANES + k],
                lanes[W * LANES + k], lanes[Z * LANES + k], _lane_context(lanes, k),
            ),
        )  # fmt: skip
    # (The rows are named in each loop: passed as arguments, they stop it vectorising.)
    for k in range(LANES):
        v, d = _lane_stage(
            lanes, k, 0.5 * lanes[DT * LANES + k], _lane_derivative(lanes, K1, k),
            lanes[VZ * LANES + k],
        )  # fmt: skip
        _set_lane_velocity(lanes, V2, k, v)
        _set_lane_derivative(lanes, K2, k, d)
    for k in range(LANES):
        v, d = _lane_stage(
            lanes, k, 0.5 * lanes[DT * LANES + k], _lane_derivative(lanes, K2, k),
            lanes[(V2 + 2) * LANES + k],
        )  # fmt: skip
        _set_lane_velocity(lanes, V3, k, v)
        _set_lane_derivative(lanes, K3, k, d)
    for k in range(LANES):
        dt = lanes[DT * LANES + k]
        v4, k4 = _lane_stage(
            lanes, k, dt, _lane_derivative(lanes, K3, k), lanes[(V3 + 2) * LANES + k]
        )
        x1, y1, z1, vx1, vy1, vz1, w1 = rk4_combine(
            lanes[X * LANES + k], lanes[Y * LANES + k], lanes[Z * LANES + k],
            lanes[VX * LANES + k], lanes[VY * LANES + k], lanes[VZ * LANES + k],
            lanes[W * LANES + k], dt, _lane_velocity(lanes, V2, k),
            _lane_velocity(lanes, V3, k), v4, _lane_derivative(lanes, K1, k),
            _lane_derivative(lanes, K2, k), _lane_derivative(lanes, K3, k), k4,
        )  # fmt: skip
        lanes[X1 * LANES + k] = x1
        lanes[Y1 * LANES + k] = y1
        lanes[Z1 * LANES + k] = z1
        lanes[VX1 * LANES + k] = vx1
        lanes[VY1 * LANES + k] = vy1
        lanes[VZ1 * LANES + k] = vz1
        lanes[W1 * LANES + k] = w1


@njit(cache=True, error_model="numpy")
def _step_lanes(lanes):
    """One flight step of every lane. A lane whose ball stays in the air takes the new state,
    its apex and time; one that went below the ground keeps the state before the step, for
    ``_land_lanes``, and the step's z1 and vz1. Returns the number of lanes (empty ones
    included) that went below the ground or past MAX_FLIGHT_TIME_S."""
    _rk4_lanes(lanes)
    events = 0
    for k in range(LANES):
        z = lanes[Z * LANES + k]
        vz = lanes[VZ * LANES + k]
        z1 = lanes[Z1 * LANES + k]
        vz1 = lanes[VZ1 * LANES + k]
        dt = lanes[DT * LANES + k]
        landed = z1 < 0.0
        apex = lanes[APEX * LANES + k]
        lanes[APEX * LANES + k] = apex if landed else apex_after_step(apex, z, vz, z1, vz1, dt)
        lanes[T * LANES + k] = lanes[T * LANES + k] if landed else lanes[T * LANES + k] + dt
        lanes[X * LANES + k] = lanes[X * LANES + k] if landed else lanes[X1 * LANES + k]
        lanes[Y * LANES + k] = lanes[Y * LANES + k] if landed else lanes[Y1 * LANES + k]
        lanes[Z * LANES + k] = z if landed else z1
        lanes[VX * LANES + k] = lanes[VX * LANES + k] if landed else lanes[VX1 * LANES + k]
        lanes[VY * LANES + k] = lanes[VY * LANES + k] if landed else lanes[VY1 * LANES + k]
        lanes[VZ * LANES + k] = vz if landed else vz1
        lanes[W * LANES + k] = lanes[W * LANES + k] if landed else lanes[W1 * LANES + k]
        events += 1 if landed | (lanes[T * LANES + k] > MAX_FLIGHT_TIME_S) else 0
    return events


@njit(cache=True, error_model="numpy")
def _land_lanes(g):
    """Locate the landing of the shots in the landing table ``g`` (lane table rows, the step
    that went below the ground in Z1 and VZ1): ``shot.land``, for LANES shots at a time. Leaves
    the landing state in rows X1..W1, its time in T, the apex in APEX and the speed and angle
    at landing in SPEED and ANGLE."""
    for k in range(LANES):
        g[DT * LANES + k] = hermite_root(
            g[Z * LANES + k], g[VZ * LANES + k], g[Z1 * LANES + k], g[VZ1 * LANES + k],
            g[H_MAX * LANES + k],
        )  # fmt: skip
    for _ in range(2):
        _rk4_lanes(g)
        for k in range(LANES):
            g[DT * LANES + k] = landing_newton(
                g[DT * LANES + k], g[Z1 * LANES + k], g[VZ1 * LANES + k], g[H_MAX * LANES + k]
            )
    _rk4_lanes(g)
    for k in range(LANES):
        h = g[DT * LANES + k]
        vz1 = g[VZ1 * LANES + k]
        g[APEX * LANES + k] = apex_after_step(
            g[APEX * LANES + k], g[Z * LANES + k], g[VZ * LANES + k], 0.0, vz1, h
        )
        g[T * LANES + k] = g[T * LANES + k] + h
        speed, angle_deg = landing_speed_angle(g[VX1 * LANES + k], g[VY1 * LANES + k], vz1)
        g[SPEED * LANES + k] = speed
        g[ANGLE * LANES + k] = angle_deg


@njit(cache=True, error_model="numpy")
def _file_landings(g, count, out, start, landings, pending, n_landed):
    """Land the first ``count`` shots of the landing table ``g``: write their flight fields and
    their landings, and queue them in ``pending`` after the n_landed there. Returns n_landed."""
    _land_lanes(g)
    for j in range(count):
        s = g[j::LANES]  # s[row] is row ``row`` of column j
        i = int(s[SHOT])
        w1 = s[W1]
        write_landing(out, i, s[X1], s[Y1], s[T], s[APEX], s[SPEED], s[ANGLE], w1)
        landings[i - start] = (
            s[X1], s[Y1], s[VX1], s[VY1], s[VZ1], w1 * s[AXIS_X], w1 * s[AXIS_Y],
            w1 * s[AXIS_Z], s[T], s[NX], s[NY], s[NZ],
        )  # fmt: skip
        pending[n_landed] = i
        n_landed += 1
    return n_landed


# Bounce lanes: once a task's shots have landed, their bounces run LANES at a time too, one
# impact and hop of every lane per pass of vectorised loops (``shot.impact`` and ``shot.hop``,
# the single-shot kernel's own functions); a lane whose ball stops bouncing hands it to the
# roll table, where LANES shots roll out together (``shot.roll_out_short``, or
# ``shot.roll_out`` on their own where that is not enough), and takes the next landed shot.
# Rows of the bounce lane table:
(BX, BY, BZ, BVX, BVY, BVZ, BWX, BWY, BWZ, BNX, BNY, BNZ, BT, BOUNCES, PREVIOUS, FIRST_HEIGHT,
 FIRST_LENGTH, THEN, MU, SOFTNESS, E0, E1, E2, E_BREAK, E_HIGH, CRITICAL) = range(26)  # fmt: skip
# The turf's rolling resistance, and, in the roll table only (below), the shot and where and
# when ``shot.roll_out_short`` brings it to rest, if it does (SHORT).
(RHO_G, BSHOT, REST_X, REST_Y, REST_T, SHORT) = range(26, 32)
N_BOUNCE_ROWS = 32
# The equivalent surface of the impact under way (``bounce.incidence``), a table of its own:
# its normal and v.e. (Written into the bounce table, which the same loop reads, it kept the
# compiler from vectorising the loop: 12 % of the kernel's time.)
(EX, EY, EZ, VNE) = range(4)
N_SURFACE_ROWS = 4
# The landing of a shot, kept until its bounces run: (x, y, vx, vy, vz, wx, wy, wz, t, nx, ny,
# nz) in the core's frame.
N_LANDING = 12


@njit(cache=True, error_model="numpy", inline="always")
def _bounce_turf(b, k):
    """The turf of bounce lane k, as far as the impact needs it (no rolling resistance)."""
    return Turf(
        b[MU * LANES + k],
        b[SOFTNESS * LANES + k],
        b[E0 * LANES + k],
        b[E1 * LANES + k],
        b[E2 * LANES + k],
        b[E_BREAK * LANES + k],
        b[E_HIGH * LANES + k],
        0.0,
        b[CRITICAL * LANES + k],
    )


@njit(cache=True, error_model="numpy")
def _impact_lanes(b, e):
    """One impact, and the hop it starts, for every bounce lane: ``shot.impact`` in two
    vectorised loops (as ``_step_lanes``, so that the lanes' long chains overlap). Returns the
    number of lanes (empty ones included) whose ball no longer hops."""
    for k in range(LANES):
        ex, ey, ez, vne, _ = incidence(
            b[BVX * LANES + k], b[BVY * LANES + k], b[BVZ * LANES + k], b[BNX * LANES + k],
            b[BNY * LANES + k], b[BNZ * LANES + k], _bounce_turf(b, k),
        )  # fmt: skip
        e[EX * LANES + k] = ex
        e[EY * LANES + k] = ey
        e[EZ * LANES + k] = ez
        e[VNE * LANES + k] = vne
    ended = 0
    for k in range(LANES):
        turf = _bounce_turf(b, k)
        bounces = b[BOUNCES * LANES + k]
        vx, vy, vz, wx, wy, wz, height, hop_time, then = impact_rebound(
            b[BVX * LANES + k], b[BVY * LANES + k], b[BVZ * LANES + k], b[BWX * LANES + k],
            b[BWY * LANES + k], b[BWZ * LANES + k], b[BNX * LANES + k], b[BNY * LANES + k],
            b[BNZ * LANES + k], e[EX * LANES + k], e[EY * LANES + k], e[EZ * LANES + k],
            e[VNE * LANES + k], turf, bounces, b[PREVIOUS * LANES + k],
        )  # fmt: skip
        x = b[BX * LANES + k]
        x1, y1, z1, vz1 = hop(x, b[BY * LANES + k], b[BZ * LANES + k], vx, vy, vz, hop_time)
        hops = then == HOPS
        first = hops & (bounces == 0)
        b[FIRST_HEIGHT * LANES + k] = height if first else b[FIRST_HEIGHT * LANES + k]
        b[FIRST_LENGTH * LANES + k] = x1 - x if first else b[FIRST_LENGTH * LANES + k]
        b[BX * LANES + k] = x1 if hops else x
        b[BY * LANES + k] = y1 if hops else b[BY * LANES + k]
        b[BZ * LANES + k] = z1 if hops else b[BZ * LANES + k]
        b[BVX * LANES + k] = vx
        b[BVY * LANES + k] = vy
        b[BVZ * LANES + k] = vz1 if hops else vz
        b[BWX * LANES + k] = wx
        b[BWY * LANES + k] = wy
        b[BWZ * LANES + k] = wz
        b[BT * LANES + k] = b[BT * LANES + k] + hop_time if hops else b[BT * LANES + k]
        b[PREVIOUS * LANES + k] = height if hops else b[PREVIOUS * LANES + k]
        b[BOUNCES * LANES + k] = bounces + 1.0 if hops else bounces
        b[THEN * LANES + k] = then
        ended += 0 if hops else 1
    return ended


@njit(cache=True, error_model="numpy")
def _load_bounce_lane(inputs, landings, start, pending, next_j, b, shot, k):
    """Put the next landed shot of ``pending`` into bounce lane k (shot[k] = -1 if none)."""
    if next_j == pending.shape[0]:
        shot[k] = -1
        return next_j
    i = pending[next_j]
    c = inputs[i]
    g = landings[i - start]
    for field, value in (
        (BX, g[0]),
        (BY, g[1]),
        (BZ, 0.0),
        (BVX, g[2]),
        (BVY, g[3]),
        (BVZ, g[4]),
        (BWX, g[5]),
        (BWY, g[6]),
        (BWZ, g[7]),
        (BT, g[8]),
        (BNX, g[9]),
        (BNY, g[10]),
        (BNZ, g[11]),
        (BOUNCES, 0.0),
        (PREVIOUS, 0.0),
        (FIRST_HEIGHT, 0.0),
        (FIRST_LENGTH, 0.0),
        (MU, c[15]),
        (SOFTNESS, c[16]),
        (E0, c[17]),
        (E1, c[18]),
        (E2, c[19]),
        (E_BREAK, c[20]),
        (E_HIGH, c[21]),
        (CRITICAL, c[23]),
        (RHO_G, c[22]),
    ):
        b[field * LANES + k] = value
    shot[k] = i
    return next_j + 1


@njit(cache=True, error_model="numpy")
def _roll_lanes(r):
    """``shot.roll_out_short`` of every lane of the roll table ``r`` (the vectorised loop)."""
    for k in range(LANES):
        x, y, t, short = roll_out_short(
            r[BX * LANES + k], r[BY * LANES + k], r[BZ * LANES + k], r[BVX * LANES + k],
            r[BVY * LANES + k], r[BVZ * LANES + k], r[BWX * LANES + k], r[BWY * LANES + k],
            r[BWZ * LANES + k], r[BNX * LANES + k], r[BNY * LANES + k], r[BNZ * LANES + k],
            r[MU * LANES + k], r[RHO_G * LANES + k], r[BT * LANES + k],
        )  # fmt: skip
        r[REST_X * LANES + k] = x
        r[REST_Y * LANES + k] = y
        r[REST_T * LANES + k] = t
        r[SHORT * LANES + k] = 1.0 if short else 0.0


@njit(cache=True, error_model="numpy")
def _file_rolls(inputs, start, landings, r, count, out):
    """Roll out the first ``count`` shots of the roll table ``r`` and write their run: LANES
    at a time by ``_roll_lanes``, and on their own (``shot.roll_out``) where that is not
    enough."""
    _roll_lanes(r)
    no_trajectory = np.empty((0, 5))
    for j in range(count):
        s = r[j::LANES]  # s[row] is row ``row`` of column j
        i = int(s[BSHOT])
        x, y, t, status = s[REST_X], s[REST_Y], s[REST_T], OK
        if s[SHORT] == 0.0:
            x, y, _, t, status, _ = roll_out(
                s[BX], s[BY], s[BZ], s[BVX], s[BVY], s[BVZ], s[BWX], s[BWY], s[BWZ], s[BNX],
                s[BNY], s[BNZ], _turf(inputs, i), s[BT], no_trajectory, 0, s[BT],
                TRAJECTORY_DT_S,
            )  # fmt: skip
        landing_x = landings[i - start, 0]
        write_run(out, i, landing_x, x, y, t, status, s[BOUNCES], s[FIRST_HEIGHT], s[FIRST_LENGTH])


@njit(cache=True, error_model="numpy")
def _bounce_all(inputs, start, landings, pending, out):
    """The bounces and the roll of the landed shots ``pending``, LANES at a time; a shot that
    stops hopping waits in the roll table until LANES shots roll out together."""
    b = np.zeros(N_BOUNCE_ROWS * LANES)
    r = np.zeros(N_BOUNCE_ROWS * LANES)  # the roll table
    e = np.zeros(N_SURFACE_ROWS * LANES)  # the equivalent surfaces of the impacts
    waiting = 0  # shots in it
    shot = np.full(LANES, -1)
    next_j = 0
    for k in range(LANES):
        next_j = _load_bounce_lane(inputs, landings, start, pending, next_j, b, shot, k)
    while _any_lane_busy(shot):
        if _impact_lanes(b, e) == 0:
            continue
        for k in range(LANES):
            i = shot[k]
            if i < 0:
                continue
            if b[THEN * LANES + k] == HOPS:
                continue
            if b[THEN * LANES + k] == TOO_MANY:
                s = b[k::LANES]  # s[row] is row ``row`` of lane k
                landing_x = landings[i - start, 0]
                write_run(
                    out, i, landing_x, s[BX], s[BY], s[BT], TOO_MANY_BOUNCES, s[BOUNCES],
                    s[FIRST_HEIGHT], s[FIRST_LENGTH],
                )  # fmt: skip
            else:
                for row in range(N_BOUNCE_ROWS):
                    r[row * LANES + waiting] = b[row * LANES + k]
                r[BSHOT * LANES + waiting] = i
                waiting += 1
                if waiting == LANES:
                    _file_rolls(inputs, start, landings, r, waiting, out)
                    waiting = 0
            next_j = _load_bounce_lane(inputs, landings, start, pending, next_j, b, shot, k)
    if waiting > 0:
        _file_rolls(inputs, start, landings, r, waiting, out)


@njit(cache=True, error_model="numpy")
def _lockstep(inputs, start, stop, table, out):
    """Simulate shots start..stop-1 of ``inputs`` into ``out``: their flights LANES at a time,
    their landings LANES at a time, then their bounces LANES at a time, then each roll."""
    lanes = np.zeros(N_LANE_ROWS * LANES)
    g = np.zeros(N_LANE_ROWS * LANES)  # the landing table
    waiting = 0  # shots in it
    shot = np.full(LANES, -1)
    landings = np.empty((stop - start, N_LANDING))
    pending = np.empty(stop - start, dtype=np.int64)
    n_landed = 0
    next_i = start
    for k in range(LANES):
        next_i = _load_lane(inputs, next_i, stop, table, out, lanes, shot, k)
    while _any_lane_busy(shot):
        if _step_lanes(lanes) == 0:
            continue
        for k in range(LANES):
            i = shot[k]
            if i < 0:
                continue
            if lanes[Z1 * LANES + k] < 0.0:
                for row in range(N_SHOT_ROWS):
                    g[row * LANES + waiting] = lanes[row * LANES + k]
                nx, ny, nz = ground_normal(inputs[i, 24], inputs[i, 25])
                for row, value in ((H_MAX, lanes[DT * LANES + k]), (NX, nx), (NY, ny), (NZ, nz)):
                    g[row * LANES + waiting] = value
                g[SHOT * LANES + waiting] = i
                waiting += 1
                if waiting == LANES:
                    n_landed = _file_landings(g, waiting, out, start, landings, pending, n_landed)
                    waiting = 0
                next_i = _load_lane(inputs, next_i, stop, table, out, lanes, shot, k)
            elif lanes[T * LANES + k] > MAX_FLIGHT_TIME_S:
                fail(out, i, NOT_LANDED)
                next_i = _load_lane(inputs, next_i, stop, table, out, lanes, shot, k)
    if waiting > 0:
        n_landed = _file_landings(g, waiting, out, start, landings, pending, n_landed)
    _bounce_all(inputs, start, landings, pending[:n_landed], out)


# Shots per parallel task: enough to keep the lanes full, few enough to balance two threads.
TASK_SHOTS = 2048


@njit(parallel=True, cache=True, error_model="numpy", nogil=True)
def _simulate_batch(inputs, table, out):
    n = inputs.shape[0]
    tasks = (n + TASK_SHOTS - 1) // TASK_SHOTS
    for task in prange(tasks):
        _lockstep(inputs, task * TASK_SHOTS, min(n, (task + 1) * TASK_SHOTS), table, out)


def simulate_batch(inputs, out=None, table=QUADRATIC_COEFFICIENTS):
    """Simulate every row of ``inputs`` (n, N_INPUT); return ``out`` (n, N_OUTCOME), F-order."""
    if inputs.ndim != 2 or inputs.shape[1] != N_INPUT:
        raise ValueError(f"inputs must have shape (n, {N_INPUT}), got {inputs.shape}")
    n = inputs.shape[0]
    if n < 2:
        # Numba types an array of fewer than two rows as C-contiguous (it is both), which would
        # compile the kernel again for that layout: such a batch runs as two rows, padded with
        # zeros (a shot of speed 0, answered with invalid_input at once).
        padded = np.zeros((2, N_INPUT), order="F")
        padded[:n] = inputs
        result = np.empty((2, N_OUTCOME), order="F")
        _run(padded, table, result)
        if out is None:
            out = np.empty((n, N_OUTCOME), order="F")
        out[:] = result[:n]
        return out
    # One compiled layout: a slice of the rows (not contiguous) is copied, not compiled again.
    inputs = np.asfortranarray(inputs, dtype=np.float64)
    if out is None:
        out = np.empty((n, N_OUTCOME), order="F")
    _run(inputs, table, out)
    return out


def _run(inputs, table, out):
    """``_simulate_batch``, on this thread alone when the batch is one task: waking the other
    threads gains nothing, and their barrier can wait a whole time slice when the cores are
    busy (a sweep's small chunks took 4 ms each, for 20 us of work)."""
    threads = numba.get_num_threads()
    if inputs.shape[0] <= TASK_SHOTS and threads > 1:
        numba.set_num_threads(1)
        try:
            _simulate_batch(inputs, table, out)
        finally:
            numba.set_num_threads(threads)
    else:
        _simulate_batch(inputs, table, out)


@njit(cache=True, error_model="numpy")
def trajectory_of(inputs, i, table, traj):
    """Trajectory of shot i of ``inputs`` into ``traj`` (m, 5); returns its number of points."""
    out = np.empty((1, N_OUTCOME))
    return _shot(inputs, i, table, out, 0, traj)
