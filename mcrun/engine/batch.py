"""The shot loop: every shot, from launch to rest, in lockstep lanes.

``simulate_batch`` simulates the rows of ``inputs``, an (n, N_INPUT) float64 array in Fortran
order (each column contiguous, named by ``schema.INPUT_FIELDS``, SI, user frame), in ``prange``
over tasks of TASK_SHOTS shots, and writes ``out``, an (n, N_OUTCOME) float64 array in Fortran
order whose columns are ``schema.OUTCOME_FIELDS``. A single shot, with its trajectory or
without, is the same loop on one row (``simulate_traced``): there is no other.

A task's shots go through the phases of a shot in lanes, LANES shots at a time, each phase
written once: they fly (RK4 steps, ``physics.flight``), land (the root inside the last step,
``engine.shot``), bounce (``physics.bounce.impact`` and ``hop``, until its rule ends the
bouncing) and roll out (``physics.roll``), asking the ground (``mcrun.ground``) for its normal
and turf. Every shot is independent of the others, of its lane and of the thread that runs it,
so the results are the same bit for bit whatever the thread count or the order of the rows.

Frames as in ``engine.shot``: user frame in and out, the core's (y to the LEFT) inside.
"""

import math

import numba
import numpy as np
from numba import njit, prange

from mcrun import ground
from mcrun.engine.schema import COLUMN, INPUT_FIELDS, N_INPUT, N_OUTCOME
from mcrun.engine.shot import (
    TRAJECTORY_DT_S,
    apex_after_step,
    fail,
    landing_newton,
    landing_speed_angle,
    start_shot,
    write_landing,
    write_run,
)
from mcrun.physics.aero import (
    C_LYU,
    C_RAMP,
    QUADRATIC_COEFFICIENTS,
    SPIN_K,
    SPIN_RATE,
    flies_in_lanes,
)
from mcrun.physics.bounce import HOPS, TOO_MANY, hop, impact, impact_rebound, incidence
from mcrun.physics.constants import BALL_AREA_M2, BALL_MASS_KG, G_MPS2
from mcrun.physics.flight import (
    WIND_UNIFORM,
    FlightParams,
    derivatives,
    derivatives_quadratic,
    hermite_root,
    make_flight_params,
    rk4_combine,
    rk4_stage,
    rk4_stage_quadratic,
    rk4_step,
    rk4_step_quadratic,
)
from mcrun.physics.launch import initial_state
from mcrun.physics.roll import roll_out, roll_out_short
from mcrun.physics.turf import Turf
from mcrun.status import MAX_FLIGHT_TIME_S, NOT_LANDED, NOT_STOPPED, OK, TOO_MANY_BOUNCES
from mcrun.trajectory import BOUNCE, FLIGHT, record

# Input columns, by name.
(SPEED, LAUNCH_ANGLE, AZIMUTH, SPIN, SPIN_AXIS, AIR_DENSITY, VISCOSITY, AERO_MODEL, CD_SCALE,
 CL_SCALE, WIND_X_IN, WIND_RIGHT, WIND_PROFILE, WIND_HEIGHT, WIND_PARAMETER, SLOPE, FALL_LINE,
 DT_IN) = (COLUMN[name] for name in (
    "ball_speed_mps", "launch_angle_rad", "azimuth_rad", "spin_radps", "spin_axis_rad",
    "air_density_kgpm3", "kinematic_viscosity_m2ps", "aero_model", "cd_scale", "cl_scale",
    "wind_x_mps", "wind_right_mps", "wind_profile", "wind_reference_height_m",
    "wind_profile_parameter", "slope_rad", "fall_line_rad", "dt_s"))  # fmt: skip
# The turf's columns are Turf's fields, in its order, from TURF on.
TURF = COLUMN["mu"]
assert INPUT_FIELDS[TURF : TURF + len(Turf._fields)] == Turf._fields


@njit(cache=True, error_model="numpy")
def _turf(inputs, i):
    """Turf of shot i."""
    c = inputs[i]
    return Turf(
        c[TURF], c[TURF + 1], c[TURF + 2], c[TURF + 3], c[TURF + 4], c[TURF + 5], c[TURF + 6],
        c[TURF + 7], c[TURF + 8],
    )  # fmt: skip


@njit(cache=True, error_model="numpy")
def _params(inputs, i):
    """FlightParams of shot i."""
    c = inputs[i]
    return make_flight_params(
        c[AIR_DENSITY], c[VISCOSITY], int(c[AERO_MODEL]), c[CD_SCALE], c[CL_SCALE],
        c[WIND_X_IN], c[WIND_RIGHT], int(c[WIND_PROFILE]), c[WIND_HEIGHT], c[WIND_PARAMETER],
    )  # fmt: skip


# How a shot flies: a quadratic or Reynolds aerodynamic model in uniform wind (the usual case)
# in lanes
# whose steps the compiler turns into vector instructions (``flight.derivatives_quadratic``),
# any other model or wind profile in lanes of the general form (``flight.derivatives``).
# Both are the same loop (``_make_flight``) and give the same numbers for a shot both can fly.
INVALID = -1
QUADRATIC = 0
GENERAL = 1


@njit(cache=True, error_model="numpy")
def _kind(inputs, i, out):
    """Check shot i and write its launch fields (``shot.start_shot``); its flight kind, or
    INVALID (status written) when an input is non-finite or non-physical."""
    c = inputs[i]
    p = _params(inputs, i)
    turf = _turf(inputs, i)
    if not start_shot(
        c[SPEED], c[LAUNCH_ANGLE], c[AZIMUTH], c[SPIN], c[SPIN_AXIS], p, turf, c[SLOPE],
        c[FALL_LINE], c[DT_IN], out, i,
    ):  # fmt: skip
        return INVALID
    vectorised = flies_in_lanes(p.aero_model) and p.wind_profile == WIND_UNIFORM
    return QUADRATIC if vectorised else GENERAL


# Flight lanes: a block of LANES shots stepped together, one loop per RK4 stage over the lanes.
# A lane whose ball goes below the ground hands its last state to the landing table and takes
# the next shot; once LANES shots wait there, their landings are located together, and they
# wait for the bounce lanes.
LANES = 16
# Rows of the lane table, a flat array whose row r of lane k is at r * LANES + k (a layout
# whose offsets the compiler can see, so that it vectorises the loop over the lanes): the state,
# the height and vertical speed at the end of the last step, the spin axis, the flight's
# constants (C0.., below), the step, the time and the apex, ...
(X, Y, Z, VX, VY, VZ, W, Z1, VZ1, AXIS_X, AXIS_Y, AXIS_Z) = range(12)
C0 = 12
N_CONSTANTS = 16
(DT, T, APEX) = range(C0 + N_CONSTANTS, C0 + N_CONSTANTS + 3)
N_SHOT_ROWS = APEX + 1  # (the rows that go with a shot into the landing table)
# ... the derivatives (K) and velocities (V) of the RK4 stages of the step under way, the rest
# of the state at its end (with Z1 and VZ1), and, in the landing table only, the flight step,
# the ground's normal, the shot, the speed and angle at landing and the time of landing.
K1, K2, K3 = N_SHOT_ROWS, N_SHOT_ROWS + 4, N_SHOT_ROWS + 8  # four rows each: ax, ay, az, dw/dt
V2, V3 = K3 + 4, K3 + 7  # three rows each: vx, vy, vz
(X1, Y1, VX1, VY1, W1, H_MAX, NX, NY, NZ, SHOT, SPEED_LANDING, ANGLE, T_LANDING) = range(
    V3 + 3, V3 + 16
)
# On a ground that varies: the end of the last step whose ground track was in play (PLAY_X,
# PLAY_Y; the tee at first), and the end of the step after it (OUT_X, OUT_Y) once LEFT_PLAY
# (1.0) says there is one: a ball that lands where its shot ends crossed in between
# (``ground.crossing``).
(PLAY_X, PLAY_Y, OUT_X, OUT_Y, LEFT_PLAY) = range(T_LANDING + 1, T_LANDING + 6)
# Whether the last step ended below the ground (1.0), in the lane table.
LANDED = LEFT_PLAY + 1
N_LANE_ROWS = LANDED + 1


@njit(cache=True, error_model="numpy", inline="always")
def _quadratic_constants(lanes, k, p, table):
    """Rows C0.. of lane k for a quadratic or Reynolds model in uniform wind: the wind,
    k C_D-scale and k C_L-scale (k = rho A / 2m), the model's row of ``table`` and the
    kinematic viscosity."""
    k_air = 0.5 * p.air_density_kgpm3 * BALL_AREA_M2 / BALL_MASS_KG
    row = table[p.aero_model]
    for j, value in enumerate((p.wind_x_mps, p.wind_y_mps, k_air * p.cd_scale,
                               k_air * p.cl_scale, row[0], row[1], row[2], row[3], row[4],
                               row[5], row[6], p.kinematic_viscosity_m2ps, row[C_LYU],
                               row[C_RAMP], row[SPIN_K], row[SPIN_RATE])):  # fmt: skip
        lanes[(C0 + j) * LANES + k] = value


@njit(cache=True, error_model="numpy", inline="always")
def _quadratic_context(lanes, k, table):
    """The ``flight.derivatives_quadratic`` context of lane k."""
    return (
        lanes[AXIS_X * LANES + k], lanes[AXIS_Y * LANES + k], lanes[AXIS_Z * LANES + k],
        lanes[C0 * LANES + k], lanes[(C0 + 1) * LANES + k], lanes[(C0 + 2) * LANES + k],
        lanes[(C0 + 3) * LANES + k], lanes[(C0 + 4) * LANES + k],
        lanes[(C0 + 5) * LANES + k], lanes[(C0 + 6) * LANES + k],
        lanes[(C0 + 7) * LANES + k], lanes[(C0 + 8) * LANES + k],
        lanes[(C0 + 9) * LANES + k], lanes[(C0 + 10) * LANES + k],
        lanes[(C0 + 11) * LANES + k], lanes[(C0 + 12) * LANES + k],
        lanes[(C0 + 13) * LANES + k], lanes[(C0 + 14) * LANES + k],
        lanes[(C0 + 15) * LANES + k],
    )  # fmt: skip


@njit(cache=True, error_model="numpy", inline="always")
def _general_constants(lanes, k, p, table):
    """Rows C0.. of lane k for any model and wind: the FlightParams, field by field."""
    for j, value in enumerate((p.air_density_kgpm3, p.kinematic_viscosity_m2ps,
                               float(p.aero_model), p.cd_scale, p.cl_scale, p.wind_x_mps,
                               p.wind_y_mps, float(p.wind_profile), p.wind_reference_height_m,
                               p.wind_profile_parameter)):  # fmt: skip
        lanes[(C0 + j) * LANES + k] = value


@njit(cache=True, error_model="numpy", inline="always")
def _general_context(lanes, k, table):
    """The ``flight.derivatives`` context of lane k."""
    p = FlightParams(
        lanes[C0 * LANES + k], lanes[(C0 + 1) * LANES + k], int(lanes[(C0 + 2) * LANES + k]),
        lanes[(C0 + 3) * LANES + k], lanes[(C0 + 4) * LANES + k],
        lanes[(C0 + 5) * LANES + k], lanes[(C0 + 6) * LANES + k],
        int(lanes[(C0 + 7) * LANES + k]), lanes[(C0 + 8) * LANES + k],
        lanes[(C0 + 9) * LANES + k],
    )  # fmt: skip
    return (lanes[AXIS_X * LANES + k], lanes[AXIS_Y * LANES + k], lanes[AXIS_Z * LANES + k], p,
            table)  # fmt: skip


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
def _below_ground(lanes, k, terrain):
    """Whether the step of lane k ends below the ground (``ground.clearance``): it lands."""
    return _clearance_end(lanes, k, terrain) < 0.0


@njit(cache=True, error_model="numpy", inline="always")
def _clearance_end(lanes, k, terrain):
    """The height of lane k's ball above the ground at the end of its step."""
    return ground.clearance(
        terrain, lanes[X1 * LANES + k], lanes[Y1 * LANES + k], lanes[Z1 * LANES + k]
    )


@njit(cache=True, error_model="numpy", inline="always")
def _clearance_rate_end(lanes, k, terrain):
    """The rate of change of ``_clearance_end``."""
    return ground.clearance_rate(
        terrain, lanes[X1 * LANES + k], lanes[Y1 * LANES + k], lanes[VX1 * LANES + k],
        lanes[VY1 * LANES + k], lanes[VZ1 * LANES + k],
    )  # fmt: skip


@njit(cache=True, error_model="numpy", inline="always")
def _any_lane_busy(shot):
    """Whether some lane still holds a shot (shot[k] is -1 for an empty lane)."""
    for k in range(LANES):
        if shot[k] >= 0:
            return True
    return False


# The trajectory of one shot (the traced one) is recorded as the loop takes it, into ``traj``
# (rows t, x, y, z, phase; ``trajectory.record``). ``tracer`` holds the traced shot (or -1),
# the next row of ``traj``, and the time of the next point of the run (its bounces and roll)
# and the interval of those points; the flight's are every TRAJECTORY_DT_S.
TRACED, ROW, T_NEXT, DT_RECORD = range(4)


def _make_flight(derivative, stage, step, constants, context):
    """The flight of a task's shots of one kind, in lanes: ``derivative`` (ax, ay, az,
    dspin/dt), its RK4 ``stage`` and ``step`` (``flight._make_rk4``), and how a lane holds the
    flight's constants (``constants``) and gives them back as the derivative's ``context``."""

    @njit(cache=True, error_model="numpy", inline="always")
    def lane_stage(lanes, k, c, d, vz_k, table):
        """The RK4 stage of lane k at c times the derivative d."""
        return stage(
            lanes[VX * LANES + k], lanes[VY * LANES + k], lanes[VZ * LANES + k],
            lanes[W * LANES + k], lanes[Z * LANES + k], c, d, vz_k, context(lanes, k, table),
        )  # fmt: skip

    @njit(cache=True, error_model="numpy")
    def rk4_lanes(lanes, table):
        """An RK4 step of length DT of every lane, from its state to rows X1..W1, split into
        one loop per stage. The iterations of a loop are independent, so the processor
        overlaps their long chains of square roots and divisions, where a single loop through
        the whole step waits on them."""
        for k in range(LANES):
            _set_lane_derivative(
                lanes, K1, k,
                derivative(
                    lanes[VX * LANES + k], lanes[VY * LANES + k], lanes[VZ * LANES + k],
                    lanes[W * LANES + k], lanes[Z * LANES + k], context(lanes, k, table),
                ),
            )  # fmt: skip
        # (The rows are named in each loop: passed as arguments, they stop it vectorising.)
        for k in range(LANES):
            v, d = lane_stage(
                lanes, k, 0.5 * lanes[DT * LANES + k], _lane_derivative(lanes, K1, k),
                lanes[VZ * LANES + k], table,
            )  # fmt: skip
            _set_lane_velocity(lanes, V2, k, v)
            _set_lane_derivative(lanes, K2, k, d)
        for k in range(LANES):
            v, d = lane_stage(
                lanes, k, 0.5 * lanes[DT * LANES + k], _lane_derivative(lanes, K2, k),
                lanes[(V2 + 2) * LANES + k], table,
            )  # fmt: skip
            _set_lane_velocity(lanes, V3, k, v)
            _set_lane_derivative(lanes, K3, k, d)
        for k in range(LANES):
            dt = lanes[DT * LANES + k]
            v4, k4 = lane_stage(
                lanes, k, dt, _lane_derivative(lanes, K3, k), lanes[(V3 + 2) * LANES + k], table
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
    def record_step(lanes, k, h, table, traj, n):
        """Trajectory points of lane k inside a flight step of length h from its state, every
        TRAJECTORY_DT_S up to its end (exclusive), by RK4 from the step's start: the recorded
        path does not depend on the step."""
        ctx = context(lanes, k, table)
        t = lanes[T * LANES + k]
        j = 1
        while j * TRAJECTORY_DT_S < h - 1e-9:
            s = j * TRAJECTORY_DT_S
            px, py, pz, _, _, _, _ = step(
                lanes[X * LANES + k], lanes[Y * LANES + k], lanes[Z * LANES + k],
                lanes[VX * LANES + k], lanes[VY * LANES + k], lanes[VZ * LANES + k],
                lanes[W * LANES + k], s, ctx,
            )  # fmt: skip
            n = record(traj, n, t + s, px, py, pz, FLIGHT)
            j += 1
        return n

    @njit(cache=True, error_model="numpy")
    def step_lanes(lanes, shot, table, traj, tracer, terrain):
        """One flight step of every lane. A lane whose ball stays in the air takes the new
        state, its apex and time; one that went below the ground keeps the state before the
        step, for ``land_lanes``, and the step's z1 and vz1. Returns the number of lanes (empty
        ones included) that went below the ground or past MAX_FLIGHT_TIME_S."""
        rk4_lanes(lanes, table)
        traced = -1
        if tracer[TRACED] >= 0:
            for k in range(LANES):
                if shot[k] == tracer[TRACED] and _clearance_end(lanes, k, terrain) >= 0.0:
                    traced = k
                    tracer[ROW] = record_step(
                        lanes, k, lanes[DT * LANES + k], table, traj, int(tracer[ROW])
                    )
        # Where each step ends: below the ground (LANDED), and, on a ground that varies, over
        # ground in play or not (one look-up of the ground each).
        if ground.varies(terrain):
            for k in range(LANES):
                x1 = lanes[X1 * LANES + k]
                y1 = lanes[Y1 * LANES + k]
                clear, state = ground.flight_check(terrain, x1, y1, lanes[Z1 * LANES + k])
                lanes[LANDED * LANES + k] = 1.0 if clear < 0.0 else 0.0
                if clear < 0.0:
                    continue
                if state == OK:
                    lanes[PLAY_X * LANES + k] = x1
                    lanes[PLAY_Y * LANES + k] = y1
                    lanes[LEFT_PLAY * LANES + k] = 0.0
                elif lanes[LEFT_PLAY * LANES + k] == 0.0:
                    lanes[OUT_X * LANES + k] = x1
                    lanes[OUT_Y * LANES + k] = y1
                    lanes[LEFT_PLAY * LANES + k] = 1.0
        else:
            for k in range(LANES):
                lanes[LANDED * LANES + k] = 1.0 if _below_ground(lanes, k, terrain) else 0.0
        events = 0
        for k in range(LANES):
            z = lanes[Z * LANES + k]
            vz = lanes[VZ * LANES + k]
            z1 = lanes[Z1 * LANES + k]
            vz1 = lanes[VZ1 * LANES + k]
            dt = lanes[DT * LANES + k]
            landed = lanes[LANDED * LANES + k] != 0.0
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
        if traced >= 0:
            k = traced
            tracer[ROW] = record(
                traj, int(tracer[ROW]), lanes[T * LANES + k], lanes[X * LANES + k],
                lanes[Y * LANES + k], lanes[Z * LANES + k], FLIGHT,
            )  # fmt: skip
        return events

    @njit(cache=True, error_model="numpy")
    def land_lanes(g, table, terrain):
        """Locate the landing of the shots in the landing table ``g`` (lane table rows, the step
        that went below the ground in X1..VZ1): the root of the cubic Hermite interpolant of the
        ball's height above the ground (``ground.clearance``: z on a Plane), then an RK4 step
        of that length from the start of the step, refined by Newton steps on that height.
        Leaves the landing state in rows X1..W1, the step in DT, its time in T_LANDING,
        the apex in APEX and the speed and angle at landing in SPEED_LANDING and ANGLE."""
        for k in range(LANES):
            x = g[X * LANES + k]
            y = g[Y * LANES + k]
            g[DT * LANES + k] = hermite_root(
                ground.clearance(terrain, x, y, g[Z * LANES + k]),
                ground.clearance_rate(
                    terrain, x, y, g[VX * LANES + k], g[VY * LANES + k], g[VZ * LANES + k]
                ),
                _clearance_end(g, k, terrain), _clearance_rate_end(g, k, terrain),
                g[H_MAX * LANES + k],
            )  # fmt: skip
        for _ in range(2):
            rk4_lanes(g, table)
            for k in range(LANES):
                g[DT * LANES + k] = landing_newton(
                    g[DT * LANES + k], _clearance_end(g, k, terrain),
                    _clearance_rate_end(g, k, terrain), g[H_MAX * LANES + k],
                )  # fmt: skip
        rk4_lanes(g, table)
        for k in range(LANES):
            h = g[DT * LANES + k]
            vz1 = g[VZ1 * LANES + k]
            # The apex may lie in the landing step (a flight of one or two steps).
            g[APEX * LANES + k] = apex_after_step(
                g[APEX * LANES + k], g[Z * LANES + k], g[VZ * LANES + k],
                ground.height_at(terrain, g[X1 * LANES + k], g[Y1 * LANES + k]), vz1, h,
            )  # fmt: skip
            g[T_LANDING * LANES + k] = g[T * LANES + k] + h
            speed, angle_deg = landing_speed_angle(g[VX1 * LANES + k], g[VY1 * LANES + k], vz1)
            g[SPEED_LANDING * LANES + k] = speed
            g[ANGLE * LANES + k] = angle_deg

    @njit(cache=True, error_model="numpy")
    def file_landings(g, count, out, start, landings, pending, n_landed, table, traj, tracer,
                      terrain):  # fmt: skip
        """Land the first ``count`` shots of the landing table ``g``: write their flight fields
        and their landings, and queue them in ``pending`` after the n_landed there (a shot that
        lands where it ends, in a penalty area say, ends there). Returns n_landed."""
        land_lanes(g, table, terrain)
        for j in range(count):
            s = g[j::LANES]  # s[row] is row ``row`` of column j
            i = int(s[SHOT])
            w1 = s[W1]
            z1 = ground.height_at(terrain, s[X1], s[Y1])
            if i == tracer[TRACED]:
                n = record_step(g, j, s[DT], table, traj, int(tracer[ROW]))
                tracer[ROW] = record(traj, n, s[T_LANDING], s[X1], s[Y1], z1, FLIGHT)
                tracer[T_NEXT] = s[T_LANDING] + tracer[DT_RECORD]
            write_landing(
                out, i, s[X1], s[Y1], s[T_LANDING], s[APEX], s[SPEED_LANDING], s[ANGLE], w1
            )
            state = ground.state_at(terrain, s[X1], s[Y1])
            if state != OK:
                left = s[LEFT_PLAY] == 1.0
                ref_x, ref_y = ground.crossing(
                    terrain, s[PLAY_X], s[PLAY_Y], s[OUT_X] if left else s[X1],
                    s[OUT_Y] if left else s[Y1],
                )  # fmt: skip
                write_run(out, i, s[X1], s[X1], s[Y1], z1, s[T_LANDING], state, 0.0, np.nan,
                          np.nan, ref_x, ref_y)  # fmt: skip
                continue
            nx, ny, nz = ground.normal_or(terrain, s[NX], s[NY], s[NZ], s[X1], s[Y1])
            landings[i - start] = (
                s[X1], s[Y1], s[VX1], s[VY1], s[VZ1], w1 * s[AXIS_X], w1 * s[AXIS_Y],
                w1 * s[AXIS_Z], s[T_LANDING], nx, ny, nz,
            )  # fmt: skip
            pending[n_landed] = i
            n_landed += 1
        return n_landed

    @njit(cache=True, error_model="numpy")
    def load_lane(inputs, kinds, kind, next_i, stop, start, table, lanes, shot, k, traj, tracer):
        """Put the next shot of this ``kind`` into lane k. Returns the index of the shot after
        it; shot[k] = -1 when none was left."""
        while next_i < stop:
            i = next_i
            next_i += 1
            if kinds[i - start] != kind:
                continue
            c = inputs[i]
            p = _params(inputs, i)
            vx, vy, vz, ax, ay, az, w = initial_state(
                c[SPEED], c[LAUNCH_ANGLE], c[AZIMUTH], c[SPIN], c[SPIN_AXIS]
            )
            for row, value in ((X, 0.0), (Y, 0.0), (Z, 0.0), (VX, vx), (VY, vy), (VZ, vz),
                               (W, w), (AXIS_X, ax), (AXIS_Y, ay), (AXIS_Z, az),
                               (DT, c[DT_IN]), (T, 0.0), (APEX, 0.0), (PLAY_X, 0.0),
                               (PLAY_Y, 0.0), (LEFT_PLAY, 0.0)):  # fmt: skip
                lanes[row * LANES + k] = value
            constants(lanes, k, p, table)
            shot[k] = i
            if i == tracer[TRACED]:
                tracer[ROW] = record(traj, 0, 0.0, 0.0, 0.0, 0.0, FLIGHT)
            return next_i
        shot[k] = -1
        return next_i

    @njit(cache=True, error_model="numpy")
    def fly(inputs, kinds, kind, start, stop, table, out, landings, pending, n_landed, traj,
            tracer, terrain):  # fmt: skip
        """Fly shots start..stop-1 of ``inputs`` of this ``kind`` LANES at a time, land them
        LANES at a time and queue them in ``pending``; returns the number queued there."""
        lanes = np.zeros(N_LANE_ROWS * LANES)
        g = np.zeros(N_LANE_ROWS * LANES)  # the landing table
        waiting = 0  # shots in it
        shot = np.full(LANES, -1)
        next_i = start
        for k in range(LANES):
            next_i = load_lane(
                inputs, kinds, kind, next_i, stop, start, table, lanes, shot, k, traj, tracer
            )
        while _any_lane_busy(shot):
            if step_lanes(lanes, shot, table, traj, tracer, terrain) == 0:
                continue
            for k in range(LANES):
                i = shot[k]
                if i < 0:
                    continue
                if lanes[LANDED * LANES + k] != 0.0:
                    for row in range(N_SHOT_ROWS):
                        g[row * LANES + waiting] = lanes[row * LANES + k]
                    # (Where the step went below the ground, and where it was last in play.)
                    for row in (X1, Y1, VX1, VY1, PLAY_X, PLAY_Y, OUT_X, OUT_Y, LEFT_PLAY):
                        g[row * LANES + waiting] = lanes[row * LANES + k]
                    nx, ny, nz = _plane_normal(inputs, i)
                    for row, value in ((H_MAX, lanes[DT * LANES + k]), (NX, nx), (NY, ny),
                                       (NZ, nz), (SHOT, float(i))):  # fmt: skip
                        g[row * LANES + waiting] = value
                    waiting += 1
                    if waiting == LANES:
                        n_landed = file_landings(
                            g, waiting, out, start, landings, pending, n_landed, table, traj,
                            tracer, terrain,
                        )  # fmt: skip
                        waiting = 0
                    next_i = load_lane(
                        inputs, kinds, kind, next_i, stop, start, table, lanes, shot, k, traj,
                        tracer,
                    )  # fmt: skip
                elif lanes[T * LANES + k] > MAX_FLIGHT_TIME_S:
                    fail(out, i, NOT_LANDED)
                    next_i = load_lane(
                        inputs, kinds, kind, next_i, stop, start, table, lanes, shot, k, traj,
                        tracer,
                    )  # fmt: skip
        if waiting > 0:
            n_landed = file_landings(
                g, waiting, out, start, landings, pending, n_landed, table, traj, tracer, terrain
            )
        return n_landed

    return fly


_fly_quadratic = _make_flight(
    derivatives_quadratic, rk4_stage_quadratic, rk4_step_quadratic, _quadratic_constants,
    _quadratic_context,
)  # fmt: skip
_fly_general = _make_flight(derivatives, rk4_stage, rk4_step, _general_constants, _general_context)


@njit(cache=True, error_model="numpy")
def _plane_normal(inputs, i):
    """The normal of shot i's Plane (``ground.plane``: its slope), where there is no terrain."""
    p = ground.plane(inputs[i, SLOPE], inputs[i, FALL_LINE], _turf(inputs, i))
    return p.nx, p.ny, p.nz


# Bounce lanes: once a task's shots have landed, their bounces run LANES at a time too, one
# impact and hop of every lane per pass of vectorised loops (``bounce.impact`` and
# ``bounce.hop``); a lane whose ball stops bouncing hands it to the roll table, where LANES
# shots roll out together (``roll.roll_out_short``, or ``roll.roll_out`` on their own where
# that is not enough), and takes the next landed shot.
# Rows of the bounce lane table: the ball, the bouncing so far, and the ground under it (its
# normal, BNX.., and its turf, MU.., in Turf's order) ...
(BX, BY, BZ, BVX, BVY, BVZ, BWX, BWY, BWZ, BNX, BNY, BNZ, BT, BOUNCES, PREVIOUS, FIRST_HEIGHT,
 FIRST_LENGTH, THEN, MU) = range(19)  # fmt: skip
# ... where the ball last touched the ground in play (QX, QY) and the state where it touched it
# last (``ground.state_at``), and, in the roll table only, the shot and where and when
# ``roll.roll_out_short`` brings it to rest, if it does (SHORT); on a terrain, how far (m) the
# ground around the ball is one plane of one zone (REACH, ``ground.calm_reach``).
(QX, QY, STATE, BSHOT, REST_X, REST_Y, REST_T, SHORT, REACH) = range(
    MU + len(Turf._fields), MU + len(Turf._fields) + 9
)
N_BOUNCE_ROWS = REACH + 1
# What comes after an impact (``bounce.impact``'s HOPS, ROLLS, TOO_MANY), or: its hop came down
# where the shot ends (STATE).
ENDS = -1.0
# The equivalent surface of the impact under way (``bounce.incidence``), a table of its own:
# its normal and v.e. (Written into the bounce table, which the same loop reads, it kept the
# compiler from vectorising the loop: 12 % of the kernel's time.)
(EX, EY, EZ, VNE) = range(4)
N_SURFACE_ROWS = 4
# On a terrain, the rebounds of the impacts under way, a table of their own too
# (``_impact_lanes_on_grid``): their (vx, vy, vz, wx, wy, wz, height, hop_time, then), and the
# end (x1, y1, z1, vz1) of the hop on the plane under the ball and whether it ends there (CALM:
# within its REACH), so that the rebounds and the hops on calm ground stay one vectorised loop
# and the other hops (``ground.hop_landing`` on the grid, one lane at a time) another.
(RVX, RVY, RVZ, RWX, RWY, RWZ, RHEIGHT, RHOP_T, RTHEN, RX1, RY1, RZ1, RVZ1, CALM) = range(14)
N_REBOUND_ROWS = CALM + 1
# The landing of a shot, kept until its bounces run: (x, y, vx, vy, vz, wx, wy, wz, t, nx, ny,
# nz) in the core's frame.
N_LANDING = 12


@njit(cache=True, error_model="numpy", inline="always")
def _lane_ground(b, k):
    """The ground under bounce lane k."""
    return ground.Plane(
        b[BNX * LANES + k], b[BNY * LANES + k], b[BNZ * LANES + k],
        Turf(b[MU * LANES + k], b[(MU + 1) * LANES + k], b[(MU + 2) * LANES + k],
             b[(MU + 3) * LANES + k], b[(MU + 4) * LANES + k], b[(MU + 5) * LANES + k],
             b[(MU + 6) * LANES + k], b[(MU + 7) * LANES + k], b[(MU + 8) * LANES + k]),
    )  # fmt: skip


@njit(cache=True, error_model="numpy", inline="always")
def _set_lane_ground(b, k, nx, ny, nz, turf):
    """Rows BNX.. and MU.. of bounce lane k: the normal and turf of the ground under it."""
    b[BNX * LANES + k] = nx
    b[BNY * LANES + k] = ny
    b[BNZ * LANES + k] = nz
    for j, value in enumerate(turf):
        b[(MU + j) * LANES + k] = value


@njit(cache=True, error_model="numpy", inline="always")
def _incidences(b, e):
    """The equivalent surface of every bounce lane's impact (``bounce.incidence``) into e."""
    for k in range(LANES):
        under = _lane_ground(b, k)
        ex, ey, ez, vne, _ = incidence(
            b[BVX * LANES + k], b[BVY * LANES + k], b[BVZ * LANES + k], under.nx, under.ny,
            under.nz, under.turf,
        )  # fmt: skip
        e[EX * LANES + k] = ex
        e[EY * LANES + k] = ey
        e[EZ * LANES + k] = ez
        e[VNE * LANES + k] = vne


@njit(cache=True, error_model="numpy")
def _impact_lanes(b, e, terrain, rb):
    """One impact, and the hop it starts, for every bounce lane: ``bounce.impact`` in two
    vectorised loops (as ``step_lanes``, so that the lanes' long chains overlap), on the ground
    under the ball (on a terrain, ``_impact_lanes_on_grid``). Returns the number of lanes
    (empty ones included) whose ball no longer hops."""
    if ground.varies(terrain):
        return _impact_lanes_on_grid(b, e, terrain, rb)
    _incidences(b, e)
    ended = 0
    for k in range(LANES):
        under = _lane_ground(b, k)
        x = b[BX * LANES + k]
        y = b[BY * LANES + k]
        nx, ny, nz = under.nx, under.ny, under.nz
        bounces = b[BOUNCES * LANES + k]
        vx, vy, vz, wx, wy, wz, height, hop_time, then = impact_rebound(
            b[BVX * LANES + k], b[BVY * LANES + k], b[BVZ * LANES + k], b[BWX * LANES + k],
            b[BWY * LANES + k], b[BWZ * LANES + k], nx, ny, nz, e[EX * LANES + k],
            e[EY * LANES + k], e[EZ * LANES + k], e[VNE * LANES + k],
            under.turf, bounces, b[PREVIOUS * LANES + k],
        )  # fmt: skip
        # (On a plane, always in play: the hop's end is the exact return to it.)
        x1, y1, z1, vz1, hop_time = ground.hop_landing(
            terrain, x, y, b[BZ * LANES + k], vx, vy, vz, hop_time
        )
        hops = then == HOPS
        first = hops & (bounces == 0)
        b[FIRST_HEIGHT * LANES + k] = height if first else b[FIRST_HEIGHT * LANES + k]
        b[FIRST_LENGTH * LANES + k] = x1 - x if first else b[FIRST_LENGTH * LANES + k]
        b[BX * LANES + k] = x1 if hops else x
        b[BY * LANES + k] = y1 if hops else y
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
        ended += 0 if then == HOPS else 1
    return ended


@njit(cache=True, error_model="numpy")
def _impact_lanes_on_grid(b, e, terrain, rb):
    """``_impact_lanes`` on a terrain: the impacts' rebounds, and their hops where the ground
    is calm (one plane and zone as far as the hop goes: there the plane's exact hop, as on a
    Plane), in vectorised loops (into the rebound table ``rb``), then each other lane's hop on
    the grid (``ground.hop_landing``) and the ground where it comes down (``ground.contact``).
    """
    _incidences(b, e)
    for k in range(LANES):
        under = _lane_ground(b, k)
        vx, vy, vz, wx, wy, wz, height, hop_time, then = impact_rebound(
            b[BVX * LANES + k], b[BVY * LANES + k], b[BVZ * LANES + k], b[BWX * LANES + k],
            b[BWY * LANES + k], b[BWZ * LANES + k], under.nx, under.ny, under.nz,
            e[EX * LANES + k], e[EY * LANES + k], e[EZ * LANES + k], e[VNE * LANES + k],
            under.turf, b[BOUNCES * LANES + k], b[PREVIOUS * LANES + k],
        )  # fmt: skip
        x1, y1, z1, vz1 = hop(
            b[BX * LANES + k], b[BY * LANES + k], b[BZ * LANES + k], vx, vy, vz, hop_time
        )
        calm = (hop_time > 0.0) & (math.sqrt(vx * vx + vy * vy) * hop_time <= b[REACH * LANES + k])
        rb[RVX * LANES + k] = vx
        rb[RVY * LANES + k] = vy
        rb[RVZ * LANES + k] = vz
        rb[RWX * LANES + k] = wx
        rb[RWY * LANES + k] = wy
        rb[RWZ * LANES + k] = wz
        rb[RHEIGHT * LANES + k] = height
        rb[RHOP_T * LANES + k] = hop_time
        rb[RTHEN * LANES + k] = then
        rb[RX1 * LANES + k] = x1
        rb[RY1 * LANES + k] = y1
        rb[RZ1 * LANES + k] = z1
        rb[RVZ1 * LANES + k] = vz1
        rb[CALM * LANES + k] = 1.0 if calm else 0.0
    ended = 0
    for k in range(LANES):
        x = b[BX * LANES + k]
        y = b[BY * LANES + k]
        vx = rb[RVX * LANES + k]
        vy = rb[RVY * LANES + k]
        vz = rb[RVZ * LANES + k]
        height = rb[RHEIGHT * LANES + k]
        then = rb[RTHEN * LANES + k]
        bounces = b[BOUNCES * LANES + k]
        hops = then == HOPS
        vz1 = vz
        if hops:
            if rb[CALM * LANES + k] != 0.0:
                # On the plane and zone under the ball: its normal and turf stay.
                x1 = rb[RX1 * LANES + k]
                y1 = rb[RY1 * LANES + k]
                z1 = rb[RZ1 * LANES + k]
                vz1 = rb[RVZ1 * LANES + k]
                hop_time = rb[RHOP_T * LANES + k]
                state = OK
                b[REACH * LANES + k] = ground.calm_reach(terrain, x1, y1)
            else:
                x1, y1, z1, vz1, hop_time = ground.hop_landing(
                    terrain, x, y, b[BZ * LANES + k], vx, vy, vz, rb[RHOP_T * LANES + k]
                )
                # The ground where it comes down: what the next impact asks of it.
                state, nx, ny, nz, turf, reach = ground.contact(terrain, _lane_ground(b, k), x1, y1)
                _set_lane_ground(b, k, nx, ny, nz, turf)
                b[REACH * LANES + k] = reach
            b[QX * LANES + k] = x
            b[QY * LANES + k] = y
            b[STATE * LANES + k] = state
            if state != OK:
                then = ENDS
            if bounces == 0:
                b[FIRST_HEIGHT * LANES + k] = height
                b[FIRST_LENGTH * LANES + k] = x1 - x
            b[BX * LANES + k] = x1
            b[BY * LANES + k] = y1
            b[BZ * LANES + k] = z1
            b[BT * LANES + k] += hop_time
            b[PREVIOUS * LANES + k] = height
            b[BOUNCES * LANES + k] = bounces + 1.0
        b[BVX * LANES + k] = vx
        b[BVY * LANES + k] = vy
        b[BVZ * LANES + k] = vz1
        b[BWX * LANES + k] = rb[RWX * LANES + k]
        b[BWY * LANES + k] = rb[RWY * LANES + k]
        b[BWZ * LANES + k] = rb[RWZ * LANES + k]
        b[THEN * LANES + k] = then
        ended += 0 if then == HOPS else 1
    return ended


@njit(cache=True, error_model="numpy")
def _record_hop(b, k, before, traj, tracer, terrain):
    """The trajectory points of the hop bounce lane k has just made from the state ``before``
    (its rows before the impact): the impact taken again (``bounce.impact``, the same
    numbers), then the ballistic arc every DT_RECORD up to the hop's end."""
    s = before
    under = _lane_ground(b, k)  # (the ground where it hit: the impact does not change it)
    vx, vy, vz, _, _, _, _, _, _ = impact(
        s[BVX], s[BVY], s[BVZ], s[BWX], s[BWY], s[BWZ], under.nx, under.ny, under.nz,
        under.turf, s[BOUNCES], s[PREVIOUS],
    )  # fmt: skip
    n = int(tracer[ROW])
    t = s[BT]
    while tracer[T_NEXT] < b[BT * LANES + k]:
        h = tracer[T_NEXT] - t
        n = record(
            traj, n, tracer[T_NEXT], s[BX] + vx * h, s[BY] + vy * h,
            s[BZ] + vz * h - 0.5 * G_MPS2 * h * h, BOUNCE,
        )  # fmt: skip
        tracer[T_NEXT] += tracer[DT_RECORD]
    tracer[ROW] = n


@njit(cache=True, error_model="numpy")
def _load_bounce_lane(inputs, landings, start, pending, next_j, b, shot, k, terrain):
    """Put the next landed shot of ``pending`` into bounce lane k (shot[k] = -1 if none)."""
    if next_j == pending.shape[0]:
        shot[k] = -1
        return next_j
    i = pending[next_j]
    g = landings[i - start]
    for row, value in ((BX, g[0]), (BY, g[1]), (BZ, ground.height_at(terrain, g[0], g[1])),
                       (BVX, g[2]), (BVY, g[3]), (BVZ, g[4]), (BWX, g[5]), (BWY, g[6]),
                       (BWZ, g[7]), (BT, g[8]), (BOUNCES, 0.0), (PREVIOUS, 0.0),
                       (FIRST_HEIGHT, 0.0), (FIRST_LENGTH, 0.0), (QX, g[0]), (QY, g[1]),
                       (STATE, float(OK))):  # fmt: skip
        b[row * LANES + k] = value
    # The ground where it landed: the Plane of the landing (its normal, the shot's turf), or
    # the terrain's there.
    _, nx, ny, nz, turf, reach = ground.contact(
        terrain, ground.Plane(g[9], g[10], g[11], _turf(inputs, i)), g[0], g[1]
    )
    _set_lane_ground(b, k, nx, ny, nz, turf)
    b[REACH * LANES + k] = reach
    shot[k] = i
    return next_j + 1


@njit(cache=True, error_model="numpy")
def _roll_lanes(r, terrain):
    """``roll.roll_out_short`` of every lane of the roll table ``r`` (the vectorised loop), on
    a Plane; on a terrain every ball rolls out on its own (``roll.roll_out``)."""
    plane = not ground.varies(terrain)
    for k in range(LANES):
        under = _lane_ground(r, k)
        x = r[BX * LANES + k]
        y = r[BY * LANES + k]
        nx, ny, nz = ground.normal_at(terrain, under, x, y)
        turf = ground.turf_at(terrain, under, x, y)
        x, y, t, short = roll_out_short(
            x, y, r[BZ * LANES + k], r[BVX * LANES + k], r[BVY * LANES + k],
            r[BVZ * LANES + k], r[BWX * LANES + k], r[BWY * LANES + k], r[BWZ * LANES + k], nx,
            ny, nz, turf.mu, turf.rho_g, r[BT * LANES + k],
        )  # fmt: skip
        r[REST_X * LANES + k] = x
        r[REST_Y * LANES + k] = y
        r[REST_T * LANES + k] = t
        r[SHORT * LANES + k] = 1.0 if short & plane else 0.0


@njit(cache=True, error_model="numpy")
def _file_rolls(start, landings, r, count, out, traj, tracer, terrain):
    """Roll out the first ``count`` shots of the roll table ``r`` and write their run: LANES
    at a time by ``_roll_lanes``, and on their own (``roll.roll_out``) where that is not
    enough, the ground is a terrain or the shot is traced."""
    _roll_lanes(r, terrain)
    for j in range(count):
        s = r[j::LANES]  # s[row] is row ``row`` of column j
        i = int(s[BSHOT])
        x, y, t, status = s[REST_X], s[REST_Y], s[REST_T], OK
        # (On the Plane, the rest's height on it.)
        z = s[BZ] - (s[BNX] * (x - s[BX]) + s[BNY] * (y - s[BY])) / s[BNZ]
        ref_x = np.nan
        ref_y = np.nan
        traced = i == tracer[TRACED]
        if s[SHORT] == 0.0 or traced:
            x, y, z, t, status, n, qx, qy = roll_out(
                s[BX], s[BY], s[BZ], s[BVX], s[BVY], s[BVZ], s[BWX], s[BWY], s[BWZ],
                ground.surface, terrain, _lane_ground(r, j), s[BT],
                traj if traced else traj[:0], int(tracer[ROW]) if traced else 0,
                tracer[T_NEXT] if traced else s[BT], tracer[DT_RECORD],
            )  # fmt: skip
            if traced:
                tracer[ROW] = n
            if status > NOT_STOPPED:
                ref_x, ref_y = ground.crossing(terrain, qx, qy, x, y)
        landing_x = landings[i - start, 0]
        write_run(out, i, landing_x, x, y, z, t, status, s[BOUNCES], s[FIRST_HEIGHT],
                  s[FIRST_LENGTH], ref_x, ref_y)  # fmt: skip


@njit(cache=True, error_model="numpy")
def _bounce_all(inputs, start, landings, pending, out, traj, tracer, terrain):
    """The bounces and the roll of the landed shots ``pending``, LANES at a time; a shot that
    stops hopping waits in the roll table until LANES shots roll out together."""
    b = np.zeros(N_BOUNCE_ROWS * LANES)
    r = np.zeros(N_BOUNCE_ROWS * LANES)  # the roll table
    e = np.zeros(N_SURFACE_ROWS * LANES)  # the equivalent surfaces of the impacts
    rb = np.zeros(N_REBOUND_ROWS * LANES)  # their rebounds, on a terrain
    before = np.zeros(N_BOUNCE_ROWS)  # the traced lane before its impact
    waiting = 0  # shots in it
    shot = np.full(LANES, -1)
    next_j = 0
    for k in range(LANES):
        next_j = _load_bounce_lane(inputs, landings, start, pending, next_j, b, shot, k, terrain)
    while _any_lane_busy(shot):
        traced = -1
        if tracer[TRACED] >= 0:
            for k in range(LANES):
                if shot[k] == tracer[TRACED]:
                    traced = k
                    before[:] = b[k::LANES]
        ended = _impact_lanes(b, e, terrain, rb)
        if traced >= 0 and (b[THEN * LANES + traced] == HOPS) | (b[THEN * LANES + traced] == ENDS):
            _record_hop(b, traced, before, traj, tracer, terrain)
        if ended == 0:
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
                    out, i, landing_x, s[BX], s[BY], s[BZ], s[BT], TOO_MANY_BOUNCES, s[BOUNCES],
                    s[FIRST_HEIGHT], s[FIRST_LENGTH], np.nan, np.nan,
                )  # fmt: skip
            elif b[THEN * LANES + k] == ENDS:
                s = b[k::LANES]
                ref_x, ref_y = ground.crossing(terrain, s[QX], s[QY], s[BX], s[BY])
                write_run(
                    out, i, landings[i - start, 0], s[BX], s[BY], s[BZ], s[BT], int(s[STATE]),
                    s[BOUNCES], s[FIRST_HEIGHT], s[FIRST_LENGTH], ref_x, ref_y,
                )  # fmt: skip
            else:
                for row in range(N_BOUNCE_ROWS):
                    r[row * LANES + waiting] = b[row * LANES + k]
                r[BSHOT * LANES + waiting] = i
                waiting += 1
                if waiting == LANES:
                    _file_rolls(start, landings, r, waiting, out, traj, tracer, terrain)
                    waiting = 0
            next_j = _load_bounce_lane(
                inputs, landings, start, pending, next_j, b, shot, k, terrain
            )
    if waiting > 0:
        _file_rolls(start, landings, r, waiting, out, traj, tracer, terrain)


@njit(cache=True, error_model="numpy")
def _lockstep(inputs, start, stop, table, out, traj, tracer, terrain):
    """Simulate shots start..stop-1 of ``inputs`` into ``out``: check them, fly each kind
    LANES at a time and land them LANES at a time, then bounce and roll them out LANES at a
    time."""
    kinds = np.empty(stop - start, dtype=np.int8)
    general = False
    for i in range(start, stop):
        kinds[i - start] = _kind(inputs, i, out)
        general |= kinds[i - start] == GENERAL
    landings = np.empty((stop - start, N_LANDING))
    pending = np.empty(stop - start, dtype=np.int64)
    n_landed = _fly_quadratic(
        inputs, kinds, QUADRATIC, start, stop, table, out, landings, pending, 0, traj, tracer,
        terrain,
    )  # fmt: skip
    if general:
        n_landed = _fly_general(
            inputs, kinds, GENERAL, start, stop, table, out, landings, pending, n_landed, traj,
            tracer, terrain,
        )  # fmt: skip
    _bounce_all(inputs, start, landings, pending[:n_landed], out, traj, tracer, terrain)


# Shots per parallel task: enough to keep the lanes full, few enough to balance two threads.
TASK_SHOTS = 2048


@njit(parallel=True, cache=True, error_model="numpy", nogil=True)
def _simulate_batch(inputs, table, out, terrain):
    n = inputs.shape[0]
    tasks = (n + TASK_SHOTS - 1) // TASK_SHOTS
    no_trajectory = np.empty((0, 5))
    for task in prange(tasks):
        untraced = np.full(4, -1.0)
        _lockstep(
            inputs, task * TASK_SHOTS, min(n, (task + 1) * TASK_SHOTS), table, out,
            no_trajectory, untraced, terrain,
        )  # fmt: skip


def _as_kernel_layout(inputs):
    """``inputs`` as the one layout the kernel is compiled for: float64, Fortran order, at
    least two rows. Numba types an array of fewer than two rows as C-contiguous (it is both),
    which would compile the kernel again for that layout: such a batch runs as two rows,
    padded with zeros (a shot of speed 0, answered with invalid_input at once)."""
    if inputs.ndim != 2 or inputs.shape[1] != N_INPUT:
        raise ValueError(f"inputs must have shape (n, {N_INPUT}), got {inputs.shape}")
    if inputs.shape[0] < 2:
        padded = np.zeros((2, N_INPUT), order="F")
        padded[: inputs.shape[0]] = inputs
        return padded
    # A slice of the rows (not contiguous) is copied, not compiled again.
    return np.asfortranarray(inputs, dtype=np.float64)


def simulate_batch(inputs, out=None, table=QUADRATIC_COEFFICIENTS, terrain=None):
    """Simulate every row of ``inputs`` (n, N_INPUT) on ``terrain`` (a ``ground.Terrain``; None:
    each shot's own Plane); return ``out`` (n, N_OUTCOME), F-order."""
    rows = _as_kernel_layout(inputs)
    n = inputs.shape[0]
    if out is None:
        out = np.empty((n, N_OUTCOME), order="F")
    result = out if rows.shape[0] == n else np.empty((rows.shape[0], N_OUTCOME), order="F")
    _run(rows, table, result, terrain)
    if result is not out:
        out[:] = result[:n]
    return out


def _run(inputs, table, out, terrain):
    """``_simulate_batch``, on this thread alone when the batch is one task: waking the other
    threads gains nothing, and their barrier can wait a whole time slice when the cores are
    busy (a sweep's small chunks took 4 ms each, for 20 us of work)."""
    threads = numba.get_num_threads()
    if inputs.shape[0] <= TASK_SHOTS and threads > 1:
        numba.set_num_threads(1)
        try:
            _simulate_batch(inputs, table, out, terrain)
        finally:
            numba.set_num_threads(threads)
    else:
        _simulate_batch(inputs, table, out, terrain)


@njit(cache=True, error_model="numpy")
def _simulate_traced(inputs, shot, table, out, traj, terrain):
    tracer = np.array([float(shot), 0.0, 0.0, TRAJECTORY_DT_S])
    _lockstep(inputs, 0, inputs.shape[0], table, out, traj, tracer, terrain)
    return int(tracer[ROW])


def simulate_traced(inputs, shot, table=QUADRATIC_COEFFICIENTS, trajectory_rows=4096,
                    terrain=None):  # fmt: skip
    """Simulate the rows of ``inputs`` on this thread, recording the path of row ``shot``:
    returns (outcomes (n, N_OUTCOME), trajectory (m, 5): t, x, y, z, phase, user frame). The
    buffer grows until the whole path fits."""
    n = inputs.shape[0]
    rows = _as_kernel_layout(inputs)
    out = np.empty((rows.shape[0], N_OUTCOME), order="F")
    path = _recorded(
        lambda traj: _simulate_traced(rows, shot, table, out, traj, terrain), trajectory_rows
    )
    return out[:n], path


def _recorded(simulate, rows):
    """The path ``simulate(traj)`` records (it returns how many rows the path has), in a buffer
    of ``rows`` rows grown until the whole path fits."""
    while True:
        traj = np.empty((rows, 5))
        m = simulate(traj)
        if m <= rows:
            return traj[:m]
        rows = m


@njit(cache=True, error_model="numpy")
def _simulate_landed(inputs, landings, out, traj, tracer, terrain):
    _bounce_all(inputs, 0, landings, np.arange(landings.shape[0]), out, traj, tracer, terrain)
    return int(tracer[ROW])


def simulate_landed(inputs, landings, traced=-1, dt_record_s=TRAJECTORY_DT_S, trajectory_rows=4096,
                    terrain=None):  # fmt: skip
    """The run alone (bounces, slide and roll) of balls that have landed: the loop from its
    landing on, for studies of the bounce (Penner's figures start from a landing).

    ``landings`` (n, N_LANDING): x, y, vx, vy, vz, wx, wy, wz, t, nx, ny, nz of each ball as it
    touches the ground, in the core's frame (y to the LEFT), with the ground's normal;
    ``inputs`` (n, N_INPUT) gives each its turf (on a ``terrain``, its zones do, and the
    ball starts on its surface). Returns (outcomes, trajectory): the run's
    fields of ``schema.OUTCOME_FIELDS`` (from ``bounces`` on; total_m and final_x_m are the x
    where the ball rests, run_m its distance from the landing), and the path of row
    ``traced`` (rows t, x, y, z, phase every ``dt_record_s``, user frame; empty if none).
    """
    n = landings.shape[0]
    rows = _as_kernel_layout(inputs)
    landings = np.ascontiguousarray(landings, dtype=np.float64)
    out = np.full((rows.shape[0], N_OUTCOME), np.nan, order="F")
    t_next = landings[traced, 8] + dt_record_s if traced >= 0 else 0.0

    def simulate(traj):
        tracer = np.array([float(traced), 0.0, t_next, dt_record_s])
        return _simulate_landed(rows, landings, out, traj, tracer, terrain)

    return out[:n], _recorded(simulate, trajectory_rows if traced >= 0 else 0)
