"""Flight lanes: a task's shots fly LANES at a time, one loop per RK4 stage over the lanes.

A lane whose ball goes below the ground hands its last state to the landing table and takes the
next shot; once LANES shots wait there, their landings are located together (``land_lanes``),
their flight fields written, and they wait in ``pending`` for the bounce lanes
(``engine.bounce_lanes``). The tables' rows are ``engine.tables``'s LANE.

How a shot flies: a quadratic or Reynolds aerodynamic model in uniform wind (the usual case) in
lanes whose steps the compiler turns into vector instructions (``flight.derivatives_quadratic``),
any other model or wind profile in lanes of the general form (``flight.derivatives``). Both are
the same loop (``_make_flight``) and give the same numbers for a shot both can fly.
"""

import numpy as np
from numba import njit

from mcrun import ground
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
from mcrun.engine.tables import (
    GENERAL_ROWS,
    IN,
    LANDING,
    LANE,
    LANES,
    NO_SHOTS,
    QUADRATIC_ROWS,
    SHOT_ROWS,
    TRACER,
    any_lane_busy,
    input_params,
    input_turf,
)
from mcrun.physics.aero import flies_in_lanes
from mcrun.physics.flight import (
    WIND_UNIFORM,
    FlightParams,
    GeneralContext,
    QuadraticContext,
    derivatives,
    derivatives_quadratic,
    hermite_root,
    quadratic_context,
    rk4_combine,
    rk4_stage,
    rk4_stage_quadratic,
    rk4_step,
    rk4_step_quadratic,
)
from mcrun.physics.launch import initial_state
from mcrun.status import MAX_FLIGHT_TIME_S, NOT_LANDED, OK
from mcrun.trajectory import FLIGHT, record

# The flight kind of a shot (``flight_kind``).
INVALID = -1
QUADRATIC = 0
GENERAL = 1


@njit(cache=True, error_model="numpy")
def flight_kind(inputs, i, out):
    """Check shot i and write its launch fields (``shot.start_shot``); its flight kind, or
    INVALID (status written) when an input is non-finite or non-physical."""
    c = inputs[i]
    p = input_params(inputs, i)
    turf = input_turf(inputs, i)
    if not start_shot(
        c[IN.ball_speed_mps],
        c[IN.launch_angle_rad],
        c[IN.azimuth_rad],
        c[IN.spin_radps],
        c[IN.spin_axis_rad],
        p,
        turf,
        c[IN.slope_rad],
        c[IN.fall_line_rad],
        c[IN.dt_s],
        out,
        i,
    ):
        return INVALID
    vectorised = flies_in_lanes(p.aero_model) and p.wind_profile == WIND_UNIFORM
    return QUADRATIC if vectorised else GENERAL


@njit(cache=True, error_model="numpy", inline="always")
def _quadratic_constants(lanes, k, p, table):
    """Rows QUADRATIC_ROWS of lane k, whose spin axis is in them, for a quadratic or Reynolds
    model in uniform wind: its ``flight.quadratic_context``."""
    ctx = quadratic_context(
        lanes[LANE.AXIS_X * LANES + k], lanes[LANE.AXIS_Y * LANES + k],
        lanes[LANE.AXIS_Z * LANES + k], p, table,
    )  # fmt: skip
    for j, value in enumerate(ctx):
        lanes[(QUADRATIC_ROWS.axis_x + j) * LANES + k] = value


@njit(cache=True, error_model="numpy", inline="always")
def _quadratic_context(lanes, k, table):
    """The ``flight.derivatives_quadratic`` context of lane k: its QuadraticContext, by name."""
    return QuadraticContext(
        lanes[QUADRATIC_ROWS.axis_x * LANES + k],
        lanes[QUADRATIC_ROWS.axis_y * LANES + k],
        lanes[QUADRATIC_ROWS.axis_z * LANES + k],
        lanes[QUADRATIC_ROWS.wind_x * LANES + k],
        lanes[QUADRATIC_ROWS.wind_y * LANES + k],
        lanes[QUADRATIC_ROWS.k_cd * LANES + k],
        lanes[QUADRATIC_ROWS.k_cl * LANES + k],
        lanes[QUADRATIC_ROWS.a0 * LANES + k],
        lanes[QUADRATIC_ROWS.a1 * LANES + k],
        lanes[QUADRATIC_ROWS.a2 * LANES + k],
        lanes[QUADRATIC_ROWS.b0 * LANES + k],
        lanes[QUADRATIC_ROWS.b1 * LANES + k],
        lanes[QUADRATIC_ROWS.b2 * LANES + k],
        lanes[QUADRATIC_ROWS.s_max * LANES + k],
        lanes[QUADRATIC_ROWS.nu * LANES + k],
        lanes[QUADRATIC_ROWS.c_lyu * LANES + k],
        lanes[QUADRATIC_ROWS.c_ramp * LANES + k],
        lanes[QUADRATIC_ROWS.spin_k * LANES + k],
        lanes[QUADRATIC_ROWS.spin_rate * LANES + k],
    )


@njit(cache=True, error_model="numpy", inline="always")
def _general_constants(lanes, k, p, table):
    """Rows GENERAL_ROWS of lane k for any model and wind: the FlightParams, field by field."""
    lanes[GENERAL_ROWS.air_density_kgpm3 * LANES + k] = p.air_density_kgpm3
    lanes[GENERAL_ROWS.kinematic_viscosity_m2ps * LANES + k] = p.kinematic_viscosity_m2ps
    lanes[GENERAL_ROWS.aero_model * LANES + k] = float(p.aero_model)
    lanes[GENERAL_ROWS.cd_scale * LANES + k] = p.cd_scale
    lanes[GENERAL_ROWS.cl_scale * LANES + k] = p.cl_scale
    lanes[GENERAL_ROWS.wind_x_mps * LANES + k] = p.wind_x_mps
    lanes[GENERAL_ROWS.wind_y_mps * LANES + k] = p.wind_y_mps
    lanes[GENERAL_ROWS.wind_profile * LANES + k] = float(p.wind_profile)
    lanes[GENERAL_ROWS.wind_reference_height_m * LANES + k] = p.wind_reference_height_m
    lanes[GENERAL_ROWS.wind_profile_parameter * LANES + k] = p.wind_profile_parameter


@njit(cache=True, error_model="numpy", inline="always")
def _general_context(lanes, k, table):
    """The ``flight.derivatives`` context of lane k: its GeneralContext."""
    p = FlightParams(
        lanes[GENERAL_ROWS.air_density_kgpm3 * LANES + k],
        lanes[GENERAL_ROWS.kinematic_viscosity_m2ps * LANES + k],
        int(lanes[GENERAL_ROWS.aero_model * LANES + k]),
        lanes[GENERAL_ROWS.cd_scale * LANES + k],
        lanes[GENERAL_ROWS.cl_scale * LANES + k],
        lanes[GENERAL_ROWS.wind_x_mps * LANES + k],
        lanes[GENERAL_ROWS.wind_y_mps * LANES + k],
        int(lanes[GENERAL_ROWS.wind_profile * LANES + k]),
        lanes[GENERAL_ROWS.wind_reference_height_m * LANES + k],
        lanes[GENERAL_ROWS.wind_profile_parameter * LANES + k],
    )
    return GeneralContext(
        lanes[LANE.AXIS_X * LANES + k], lanes[LANE.AXIS_Y * LANES + k],
        lanes[LANE.AXIS_Z * LANES + k], p, table,
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
def _below_ground(lanes, k, terrain):
    """Whether the step of lane k ends below the ground (``ground.clearance``): it lands."""
    return _clearance_end(lanes, k, terrain) < 0.0


@njit(cache=True, error_model="numpy", inline="always")
def _clearance_end(lanes, k, terrain):
    """The height of lane k's ball above the ground at the end of its step."""
    return ground.clearance(
        terrain, lanes[LANE.X1 * LANES + k], lanes[LANE.Y1 * LANES + k], lanes[LANE.Z1 * LANES + k]
    )


@njit(cache=True, error_model="numpy", inline="always")
def _clearance_rate_end(lanes, k, terrain):
    """The rate of change of ``_clearance_end``."""
    return ground.clearance_rate(
        terrain,
        lanes[LANE.X1 * LANES + k],
        lanes[LANE.Y1 * LANES + k],
        lanes[LANE.VX1 * LANES + k],
        lanes[LANE.VY1 * LANES + k],
        lanes[LANE.VZ1 * LANES + k],
    )


def _make_flight(derivative, stage, step, constants, context):
    """The flight of a task's shots of one kind, in lanes: ``derivative`` (ax, ay, az,
    dspin/dt), its RK4 ``stage`` and ``step`` (``flight._make_rk4``), and how a lane holds the
    flight's constants (``constants``) and gives them back as the derivative's ``context``."""

    @njit(cache=True, error_model="numpy", inline="always")
    def lane_stage(lanes, k, c, d, vz_k, table):
        """The RK4 stage of lane k at c times the derivative d."""
        return stage(
            lanes[LANE.VX * LANES + k],
            lanes[LANE.VY * LANES + k],
            lanes[LANE.VZ * LANES + k],
            lanes[LANE.W * LANES + k],
            lanes[LANE.Z * LANES + k],
            c,
            d,
            vz_k,
            context(lanes, k, table),
        )

    @njit(cache=True, error_model="numpy")
    def rk4_lanes(lanes, table):
        """An RK4 step of length DT of every lane, from its state to rows X1..W1, split into
        one loop per stage. The iterations of a loop are independent, so the processor
        overlaps their long chains of square roots and divisions, where a single loop through
        the whole step waits on them."""
        for k in range(LANES):
            _set_lane_derivative(
                lanes,
                LANE.K1,
                k,
                derivative(
                    lanes[LANE.VX * LANES + k],
                    lanes[LANE.VY * LANES + k],
                    lanes[LANE.VZ * LANES + k],
                    lanes[LANE.W * LANES + k],
                    lanes[LANE.Z * LANES + k],
                    context(lanes, k, table),
                ),
            )
        # (The rows are named in each loop: passed as arguments, they stop it vectorising.)
        for k in range(LANES):
            v, d = lane_stage(
                lanes,
                k,
                0.5 * lanes[LANE.DT * LANES + k],
                _lane_derivative(lanes, LANE.K1, k),
                lanes[LANE.VZ * LANES + k],
                table,
            )
            _set_lane_velocity(lanes, LANE.V2, k, v)
            _set_lane_derivative(lanes, LANE.K2, k, d)
        for k in range(LANES):
            v, d = lane_stage(
                lanes, k, 0.5 * lanes[LANE.DT * LANES + k], _lane_derivative(lanes, LANE.K2, k),
                lanes[(LANE.V2 + 2) * LANES + k], table,
            )  # fmt: skip
            _set_lane_velocity(lanes, LANE.V3, k, v)
            _set_lane_derivative(lanes, LANE.K3, k, d)
        for k in range(LANES):
            dt = lanes[LANE.DT * LANES + k]
            v4, k4 = lane_stage(
                lanes,
                k,
                dt,
                _lane_derivative(lanes, LANE.K3, k),
                lanes[(LANE.V3 + 2) * LANES + k],
                table,
            )
            x1, y1, z1, vx1, vy1, vz1, w1 = rk4_combine(
                lanes[LANE.X * LANES + k], lanes[LANE.Y * LANES + k], lanes[LANE.Z * LANES + k],
                lanes[LANE.VX * LANES + k], lanes[LANE.VY * LANES + k], lanes[LANE.VZ * LANES + k],
                lanes[LANE.W * LANES + k], dt, _lane_velocity(lanes, LANE.V2, k),
                _lane_velocity(lanes, LANE.V3, k), v4, _lane_derivative(lanes, LANE.K1, k),
                _lane_derivative(lanes, LANE.K2, k), _lane_derivative(lanes, LANE.K3, k), k4,
            )  # fmt: skip
            lanes[LANE.X1 * LANES + k] = x1
            lanes[LANE.Y1 * LANES + k] = y1
            lanes[LANE.Z1 * LANES + k] = z1
            lanes[LANE.VX1 * LANES + k] = vx1
            lanes[LANE.VY1 * LANES + k] = vy1
            lanes[LANE.VZ1 * LANES + k] = vz1
            lanes[LANE.W1 * LANES + k] = w1

    @njit(cache=True, error_model="numpy")
    def record_step(lanes, k, h, table, traj, n):
        """Trajectory points of lane k inside a flight step of length h from its state, every
        TRAJECTORY_DT_S up to its end (exclusive), by RK4 from the step's start: the recorded
        path does not depend on the step."""
        ctx = context(lanes, k, table)
        t = lanes[LANE.T * LANES + k]
        j = 1
        while j * TRAJECTORY_DT_S < h - 1e-9:
            s = j * TRAJECTORY_DT_S
            px, py, pz, _, _, _, _ = step(
                lanes[LANE.X * LANES + k], lanes[LANE.Y * LANES + k], lanes[LANE.Z * LANES + k],
                lanes[LANE.VX * LANES + k], lanes[LANE.VY * LANES + k], lanes[LANE.VZ * LANES + k],
                lanes[LANE.W * LANES + k], s, ctx,
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
        if tracer is not None:  # (a batch has none: pruned from its kernel)
            for k in range(LANES):
                if shot[k] == tracer[TRACER.TRACED] and _clearance_end(lanes, k, terrain) >= 0.0:
                    traced = k
                    tracer[TRACER.ROW] = record_step(
                        lanes, k, lanes[LANE.DT * LANES + k], table, traj, int(tracer[TRACER.ROW])
                    )
        # Where each step ends: below the ground (LANDED), and, on a ground that varies, over
        # ground in play or not (one look-up of the ground each).
        if terrain is not None:  # (a grid; pruned from the Plane's kernel, which never varies)
            for k in range(LANES):
                x1 = lanes[LANE.X1 * LANES + k]
                y1 = lanes[LANE.Y1 * LANES + k]
                clear, state = ground.flight_check(terrain, x1, y1, lanes[LANE.Z1 * LANES + k])
                lanes[LANE.LANDED * LANES + k] = 1.0 if clear < 0.0 else 0.0
                if clear < 0.0:
                    continue
                if state == OK:
                    lanes[LANE.PLAY_X * LANES + k] = x1
                    lanes[LANE.PLAY_Y * LANES + k] = y1
                    lanes[LANE.LEFT_PLAY * LANES + k] = 0.0
                elif lanes[LANE.LEFT_PLAY * LANES + k] == 0.0:
                    lanes[LANE.OUT_X * LANES + k] = x1
                    lanes[LANE.OUT_Y * LANES + k] = y1
                    lanes[LANE.LEFT_PLAY * LANES + k] = 1.0
        else:
            for k in range(LANES):
                lanes[LANE.LANDED * LANES + k] = 1.0 if _below_ground(lanes, k, terrain) else 0.0
        events = 0
        for k in range(LANES):
            z = lanes[LANE.Z * LANES + k]
            vz = lanes[LANE.VZ * LANES + k]
            z1 = lanes[LANE.Z1 * LANES + k]
            vz1 = lanes[LANE.VZ1 * LANES + k]
            dt = lanes[LANE.DT * LANES + k]
            landed = lanes[LANE.LANDED * LANES + k] != 0.0
            apex = lanes[LANE.APEX * LANES + k]
            lanes[LANE.APEX * LANES + k] = (
                apex if landed else apex_after_step(apex, z, vz, z1, vz1, dt)
            )
            lanes[LANE.T * LANES + k] = (
                lanes[LANE.T * LANES + k] if landed else lanes[LANE.T * LANES + k] + dt
            )
            lanes[LANE.X * LANES + k] = (
                lanes[LANE.X * LANES + k] if landed else lanes[LANE.X1 * LANES + k]
            )
            lanes[LANE.Y * LANES + k] = (
                lanes[LANE.Y * LANES + k] if landed else lanes[LANE.Y1 * LANES + k]
            )
            lanes[LANE.Z * LANES + k] = z if landed else z1
            lanes[LANE.VX * LANES + k] = (
                lanes[LANE.VX * LANES + k] if landed else lanes[LANE.VX1 * LANES + k]
            )
            lanes[LANE.VY * LANES + k] = (
                lanes[LANE.VY * LANES + k] if landed else lanes[LANE.VY1 * LANES + k]
            )
            lanes[LANE.VZ * LANES + k] = vz if landed else vz1
            lanes[LANE.W * LANES + k] = (
                lanes[LANE.W * LANES + k] if landed else lanes[LANE.W1 * LANES + k]
            )
            events += 1 if landed | (lanes[LANE.T * LANES + k] > MAX_FLIGHT_TIME_S) else 0
        if tracer is not None:
            if traced >= 0:
                k = traced
                tracer[TRACER.ROW] = record(
                    traj, int(tracer[TRACER.ROW]), lanes[LANE.T * LANES + k],
                    lanes[LANE.X * LANES + k], lanes[LANE.Y * LANES + k],
                    lanes[LANE.Z * LANES + k], FLIGHT,
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
            x = g[LANE.X * LANES + k]
            y = g[LANE.Y * LANES + k]
            g[LANE.DT * LANES + k] = hermite_root(
                ground.clearance(terrain, x, y, g[LANE.Z * LANES + k]),
                ground.clearance_rate(
                    terrain,
                    x,
                    y,
                    g[LANE.VX * LANES + k],
                    g[LANE.VY * LANES + k],
                    g[LANE.VZ * LANES + k],
                ),
                _clearance_end(g, k, terrain),
                _clearance_rate_end(g, k, terrain),
                g[LANE.H_MAX * LANES + k],
            )
        for _ in range(2):
            rk4_lanes(g, table)
            for k in range(LANES):
                g[LANE.DT * LANES + k] = landing_newton(
                    g[LANE.DT * LANES + k],
                    _clearance_end(g, k, terrain),
                    _clearance_rate_end(g, k, terrain),
                    g[LANE.H_MAX * LANES + k],
                )
        rk4_lanes(g, table)
        for k in range(LANES):
            h = g[LANE.DT * LANES + k]
            vz1 = g[LANE.VZ1 * LANES + k]
            # The apex may lie in the landing step (a flight of one or two steps).
            g[LANE.APEX * LANES + k] = apex_after_step(
                g[LANE.APEX * LANES + k], g[LANE.Z * LANES + k], g[LANE.VZ * LANES + k],
                ground.height_at(terrain, g[LANE.X1 * LANES + k], g[LANE.Y1 * LANES + k]), vz1, h,
            )  # fmt: skip
            g[LANE.T_LANDING * LANES + k] = g[LANE.T * LANES + k] + h
            speed, angle_deg = landing_speed_angle(
                g[LANE.VX1 * LANES + k], g[LANE.VY1 * LANES + k], vz1
            )
            g[LANE.SPEED_LANDING * LANES + k] = speed
            g[LANE.ANGLE * LANES + k] = angle_deg

    @njit(cache=True, error_model="numpy")
    def file_landings(g, count, out, start, landings, pending, n_landed, table, traj, tracer,
                      terrain):  # fmt: skip
        """Land the first ``count`` shots of the landing table ``g``: write their flight fields
        and their landings, and queue them in ``pending`` after the n_landed there (a shot that
        lands where it ends, in a penalty area say, ends there). Returns n_landed."""
        land_lanes(g, table, terrain)
        for j in range(count):
            s = g[j::LANES]  # s[row] is row ``row`` of column j
            i = int(s[LANE.SHOT])
            w1 = s[LANE.W1]
            z1 = ground.height_at(terrain, s[LANE.X1], s[LANE.Y1])
            if tracer is not None:
                if i == tracer[TRACER.TRACED]:
                    n = record_step(g, j, s[LANE.DT], table, traj, int(tracer[TRACER.ROW]))
                    tracer[TRACER.ROW] = record(
                        traj, n, s[LANE.T_LANDING], s[LANE.X1], s[LANE.Y1], z1, FLIGHT
                    )
                    tracer[TRACER.T_NEXT] = s[LANE.T_LANDING] + tracer[TRACER.DT_RECORD]
            write_landing(
                out,
                i,
                s[LANE.X1],
                s[LANE.Y1],
                s[LANE.T_LANDING],
                s[LANE.APEX],
                s[LANE.SPEED_LANDING],
                s[LANE.ANGLE],
                w1,
            )
            state = ground.state_at(terrain, s[LANE.X1], s[LANE.Y1])
            if state != OK:
                left = s[LANE.LEFT_PLAY] == 1.0
                ref_x, ref_y = ground.crossing(
                    terrain, s[LANE.PLAY_X], s[LANE.PLAY_Y], s[LANE.OUT_X] if left else s[LANE.X1],
                    s[LANE.OUT_Y] if left else s[LANE.Y1],
                )  # fmt: skip
                write_run(
                    out,
                    i,
                    s[LANE.X1],
                    s[LANE.X1],
                    s[LANE.Y1],
                    z1,
                    s[LANE.T_LANDING],
                    state,
                    0.0,
                    np.nan,
                    np.nan,
                    ref_x,
                    ref_y,
                )
                continue
            nx, ny, nz = ground.normal_or(
                terrain, s[LANE.NX], s[LANE.NY], s[LANE.NZ], s[LANE.X1], s[LANE.Y1]
            )
            # (Field by field: a row assigned a tuple compiles a shape check and its message.)
            row = landings[i - start]
            row[LANDING.X] = s[LANE.X1]
            row[LANDING.Y] = s[LANE.Y1]
            row[LANDING.VX] = s[LANE.VX1]
            row[LANDING.VY] = s[LANE.VY1]
            row[LANDING.VZ] = s[LANE.VZ1]
            row[LANDING.WX] = w1 * s[LANE.AXIS_X]
            row[LANDING.WY] = w1 * s[LANE.AXIS_Y]
            row[LANDING.WZ] = w1 * s[LANE.AXIS_Z]
            row[LANDING.T] = s[LANE.T_LANDING]
            row[LANDING.NX] = nx
            row[LANDING.NY] = ny
            row[LANDING.NZ] = nz
            pending[n_landed] = i
            n_landed += 1
        return n_landed

    @njit(cache=True, error_model="numpy")
    def load_lane(inputs, kinds, kind, next_i, stop, start, table, lanes, shot, k, traj, tracer,
                  terrain):  # fmt: skip
        """Put the next shot of this ``kind`` into lane k, on the ground at its start. Returns
        the index of the shot after it; shot[k] = -1 when none was left."""
        while next_i < stop:
            i = next_i
            next_i += 1
            if kinds[i - start] != kind:
                continue
            c = inputs[i]
            p = input_params(inputs, i)
            vx, vy, vz, ax, ay, az, w = initial_state(
                c[IN.ball_speed_mps],
                c[IN.launch_angle_rad],
                c[IN.azimuth_rad],
                c[IN.spin_radps],
                c[IN.spin_axis_rad],
            )
            x0 = c[IN.start_x_m]
            y0 = -c[IN.start_y_m]  # the core's frame: y to the left
            z0 = ground.height_at(terrain, x0, y0)
            for row, value in (
                (LANE.X, x0),
                (LANE.Y, y0),
                (LANE.Z, z0),
                (LANE.VX, vx),
                (LANE.VY, vy),
                (LANE.VZ, vz),
                (LANE.W, w),
                (LANE.AXIS_X, ax),
                (LANE.AXIS_Y, ay),
                (LANE.AXIS_Z, az),
                (LANE.DT, c[IN.dt_s]),
                (LANE.T, 0.0),
                (LANE.APEX, z0),
                (LANE.PLAY_X, x0),
                (LANE.PLAY_Y, y0),
                (LANE.LEFT_PLAY, 0.0),
            ):
                lanes[row * LANES + k] = value
            constants(lanes, k, p, table)
            shot[k] = i
            if tracer is not None:
                if i == tracer[TRACER.TRACED]:
                    tracer[TRACER.ROW] = record(traj, 0, 0.0, x0, y0, z0, FLIGHT)
            return next_i
        shot[k] = -1
        return next_i

    @njit(cache=True, error_model="numpy")
    def fly(inputs, kinds, kind, start, stop, table, out, landings, pending, n_landed, traj,
            tracer, terrain):  # fmt: skip
        """Fly shots start..stop-1 of ``inputs`` of this ``kind`` LANES at a time, land them
        LANES at a time and queue them in ``pending``; returns the number queued there."""
        # (Of ones: see ``tables.LANES``.)
        lanes = np.ones(LANE.N * LANES)
        g = np.ones(LANE.N * LANES)  # the landing table
        waiting = NO_SHOTS  # shots in it
        shot = np.full(LANES, -1)
        next_i = start
        for k in range(LANES):
            next_i = load_lane(
                inputs, kinds, kind, next_i, stop, start, table, lanes, shot, k, traj, tracer,
                terrain,
            )  # fmt: skip
        while any_lane_busy(shot):
            if step_lanes(lanes, shot, table, traj, tracer, terrain) == 0:
                continue
            for k in range(LANES):
                i = shot[k]
                if i < 0:
                    continue
                if lanes[LANE.LANDED * LANES + k] != 0.0:
                    for row in range(SHOT_ROWS):
                        g[row * LANES + waiting] = lanes[row * LANES + k]
                    # (Where the step went below the ground, and where it was last in play.)
                    for row in (
                        LANE.X1,
                        LANE.Y1,
                        LANE.VX1,
                        LANE.VY1,
                        LANE.PLAY_X,
                        LANE.PLAY_Y,
                        LANE.OUT_X,
                        LANE.OUT_Y,
                        LANE.LEFT_PLAY,
                    ):
                        g[row * LANES + waiting] = lanes[row * LANES + k]
                    nx, ny, nz = _plane_normal(inputs, i)
                    for row, value in (
                        (LANE.H_MAX, lanes[LANE.DT * LANES + k]),
                        (LANE.NX, nx),
                        (LANE.NY, ny),
                        (LANE.NZ, nz),
                        (LANE.SHOT, float(i)),
                    ):
                        g[row * LANES + waiting] = value
                    waiting += 1
                    if waiting == LANES:
                        n_landed = file_landings(
                            g, waiting, out, start, landings, pending, n_landed, table, traj,
                            tracer, terrain,
                        )  # fmt: skip
                        waiting = NO_SHOTS
                    next_i = load_lane(
                        inputs, kinds, kind, next_i, stop, start, table, lanes, shot, k, traj,
                        tracer, terrain,
                    )  # fmt: skip
                elif lanes[LANE.T * LANES + k] > MAX_FLIGHT_TIME_S:
                    fail(out, i, NOT_LANDED)
                    next_i = load_lane(
                        inputs, kinds, kind, next_i, stop, start, table, lanes, shot, k, traj,
                        tracer, terrain,
                    )  # fmt: skip
        if waiting > 0:
            n_landed = file_landings(
                g, waiting, out, start, landings, pending, n_landed, table, traj, tracer, terrain
            )
        return n_landed

    return fly


fly_quadratic = _make_flight(
    derivatives_quadratic, rk4_stage_quadratic, rk4_step_quadratic, _quadratic_constants,
    _quadratic_context,
)  # fmt: skip
fly_general = _make_flight(derivatives, rk4_stage, rk4_step, _general_constants, _general_context)


@njit(cache=True, error_model="numpy")
def _plane_normal(inputs, i):
    """The normal of shot i's Plane (``ground.plane``: its slope), where there is no terrain."""
    p = ground.plane(inputs[i, IN.slope_rad], inputs[i, IN.fall_line_rad], input_turf(inputs, i))
    return p.nx, p.ny, p.nz
