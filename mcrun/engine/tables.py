"""The shot loop's tables, each row declared once by name: the inputs' columns it reads, and the
lane tables it keeps its shots in (``engine.flight_lanes``, ``engine.bounce_lanes``).

A lane table is a flat float64 array whose row r of lane k is at r * LANES + k: a layout whose
offsets the compiler sees (r a constant), so that it vectorises a loop over the lanes. Each
table's rows are a namedtuple of ints (``rows``), built once at import: Numba takes a global
namedtuple as a constant, so ``LANE.X * LANES + k`` compiles as ``X * LANES + k`` with X a
number, and two tables cannot share a row by mistake (``LANE.X`` is not ``BOUNCE.X``).
"""

from collections import namedtuple

import numpy as np
from numba import njit

from mcrun.engine.schema import COLUMN, INPUT_FIELDS
from mcrun.ground import read_turf
from mcrun.physics.flight import FlightParams, QuadraticContext, make_flight_params
from mcrun.physics.turf import Turf

# Shots stepped together in one pass of a loop. A lane that holds no shot is computed with the
# others, on what its rows hold: the tables start as ones, not zeros, so that it divides by no
# zero, which the compiled loop would not mind (error_model="numpy") but Python does, where the
# loop runs as Python (NUMBA_DISABLE_JIT=1) for a developer to step through it.
LANES = 16


def rows(table, *names):
    """The rows of a table, in order: each of ``names`` is a row, or (name, count) for that
    many rows from that one on. Returns a namedtuple (of type ``table``) of each name's first
    row, and N, the number of rows."""
    fields = []
    first = []
    n = 0
    for name in names:
        name, count = (name, 1) if isinstance(name, str) else name
        fields.append(name)
        first.append(n)
        n += count
    return namedtuple(table, [*fields, "N"])(*first, n)


def rows_from(table, start, names):
    """A table's rows ``names`` laid out one after another from row ``start`` of another: a
    block of it, by name (a namedtuple, as ``rows``, N the row after the block)."""
    return namedtuple(table, [*names, "N"])(*range(start, start + len(names) + 1))


# The input columns the loop reads, by name (``schema.INPUT_FIELDS``).
IN = namedtuple("Inputs", INPUT_FIELDS)(*(COLUMN[name] for name in INPUT_FIELDS))
# The turf's columns are Turf's fields, in its order, from IN.mu on.
assert INPUT_FIELDS[IN.mu : IN.mu + len(Turf._fields)] == Turf._fields


@njit(cache=True, error_model="numpy")
def input_turf(inputs, i):
    """Turf of shot i."""
    return read_turf(inputs[i], IN.mu, 1)


@njit(cache=True, error_model="numpy")
def input_params(inputs, i):
    """FlightParams of shot i."""
    c = inputs[i]
    return make_flight_params(
        c[IN.air_density_kgpm3], c[IN.kinematic_viscosity_m2ps], int(c[IN.aero_model]),
        c[IN.cd_scale], c[IN.cl_scale], c[IN.wind_x_mps], c[IN.wind_right_mps],
        int(c[IN.wind_profile]), c[IN.wind_reference_height_m], c[IN.wind_profile_parameter],
    )  # fmt: skip


@njit(cache=True, error_model="numpy", inline="always")
def any_lane_busy(shot):
    """Whether some lane still holds a shot (shot[k] is -1 for an empty lane)."""
    for k in range(LANES):
        if shot[k] >= 0:
            return True
    return False


# The lane table of the flight (``engine.flight_lanes``): the state, the height and vertical
# speed at the end of the last step, the flight's context (the spin axis, then its constants:
# ``QUADRATIC_ROWS``, ``GENERAL_ROWS``), the step, the time and the apex (the rows before
# SHOT_ROWS go with a shot into the landing table, of the same layout), the derivatives (K, four
# rows each: ax, ay, az, dspin/dt) and velocities (V, three rows each) of the RK4 stages of the
# step under way, the rest of the state at its end (with Z1 and VZ1), and, in the landing table
# only, the flight step (H_MAX), the ground's normal, the shot, the speed and angle at landing
# and the time of landing. On a ground that varies: the end of the last step whose ground track
# was in play (PLAY_X, PLAY_Y; the tee at first), and the end of the step after it (OUT_X,
# OUT_Y) once LEFT_PLAY (1.0) says there is one: a ball that lands where its shot ends crossed
# in between (``ground.crossing``). Last, whether the last step ended below the ground (LANDED,
# 1.0), in the lane table.
LANE = rows(
    "Lane", "X", "Y", "Z", "VX", "VY", "VZ", "W", "Z1", "VZ1", "AXIS_X", "AXIS_Y", "AXIS_Z",
    ("CONSTANTS", len(QuadraticContext._fields) - 3), "DT", "T", "APEX", ("K1", 4), ("K2", 4),
    ("K3", 4), ("V2", 3), ("V3", 3), "X1", "Y1", "VX1", "VY1", "W1", "H_MAX", "NX", "NY", "NZ",
    "SHOT", "SPEED_LANDING", "ANGLE", "T_LANDING", "PLAY_X", "PLAY_Y", "OUT_X", "OUT_Y",
    "LEFT_PLAY", "LANDED",
)  # fmt: skip
SHOT_ROWS = LANE.APEX + 1
# The flight's context in its rows, by name: a QuadraticContext from AXIS_X on, or the spin axis
# and the FlightParams from CONSTANTS on (a shot of any other model or wind).
QUADRATIC_ROWS = rows_from("QuadraticRows", LANE.AXIS_X, QuadraticContext._fields)
GENERAL_ROWS = rows_from("GeneralRows", LANE.CONSTANTS, FlightParams._fields)
assert QUADRATIC_ROWS.N == LANE.DT
assert GENERAL_ROWS.N <= LANE.DT

# The bounce lane table (``engine.bounce_lanes``), and the roll table, of the same layout: the
# ball, the bouncing so far, and the ground under it (its normal, NX.., and its turf, Turf's
# fields in its order from TURF on), where the ball last touched the ground in play (QX, QY)
# and the state where it touched it last (``ground.state_at``), and, in the roll table only,
# the shot and where and when ``roll.roll_out_short`` brings it to rest, if it does (SHORT); on a
# terrain, how far (m) the ground around the ball is one plane of one zone (REACH,
# ``ground.calm_reach``).
BOUNCE = rows(
    "Bounce", "X", "Y", "Z", "VX", "VY", "VZ", "WX", "WY", "WZ", "NX", "NY", "NZ", "T",
    "BOUNCES", "PREVIOUS", "FIRST_HEIGHT", "FIRST_LENGTH", "THEN", ("TURF", len(Turf._fields)),
    "QX", "QY", "STATE", "SHOT", "REST_X", "REST_Y", "REST_T", "SHORT", "REACH",
)  # fmt: skip
# The equivalent surface of the impact under way (``bounce.incidence``), a table of its own: its
# normal and v.e. (Written into the bounce table, which the same loop reads, it kept the
# compiler from vectorising the loop: 12 % of the kernel's time.)
INCIDENCE = rows("Incidence", "EX", "EY", "EZ", "VNE")
# On a terrain, the rebounds of the impacts under way, a table of their own too: their (vx, vy,
# vz, wx, wy, wz, height, hop_time, then), and the end (x1, y1, z1, vz1) of the hop on the plane
# under the ball and whether it ends there (CALM: within its REACH), so that the rebounds and the
# hops on calm ground stay one vectorised loop and the other hops (``ground.hop_landing`` on the
# grid, one lane at a time) another.
REBOUND = rows(
    "Rebound", "VX", "VY", "VZ", "WX", "WY", "WZ", "HEIGHT", "HOP_T", "THEN", "X1", "Y1", "Z1",
    "VZ1", "CALM",
)  # fmt: skip
# The landing of a shot, kept until its bounces run (a row of an array), in the core's frame,
# with the ground's normal there.
LANDING = rows("Landing", "X", "Y", "VX", "VY", "VZ", "WX", "WY", "WZ", "T", "NX", "NY", "NZ")
N_LANDING = LANDING.N
# The trajectory of one shot (the traced one) is recorded as the loop takes it (rows t, x, y,
# z, phase; ``trajectory.record``). The tracer holds the traced shot (or -1), the next row of
# the trajectory, and the time of the next point of the run (its bounces and roll) and the
# interval of those points; the flight's are every TRAJECTORY_DT_S.
TRACER = rows("Tracer", "TRACED", "ROW", "T_NEXT", "DT_RECORD")
# No shots yet: the start of the loops' counts. Numba types a literal 0 as Literal[int](0) and
# compiles a callee given it a specialisation of its own, beside the int64 one the count
# takes later (three compiles of ``file_landings`` where one does); an int64 zero is int64.
NO_SHOTS = np.int64(0)
