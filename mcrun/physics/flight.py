"""Flight through the air: gravity, drag, Magnus lift, spin decay and wind, in 3D.

Frame of the core: right-handed, x along the target line, y to the LEFT, z up (the user-facing
frame, y to the right, is converted in ``shot.py``). The flight state is seven floats,
(x, y, z, vx, vy, vz, spin): the spin axis keeps its direction in flight (spin decay only
shrinks |w|), so it is a parameter, not a state.

This module holds the step only (forces, the RK4 update, and the interpolation used to locate
an event inside a step); the event handling lives in ``shot.py``. Keeping them apart lets a
later performance pass step a block of shots in lockstep.

    m dv/dt = -m g z - 1/2 rho A C_D |v_rel| v_rel + 1/2 rho A C_L |v_rel|^2 (w x v_rel)/|w x v_rel|
    dw/dt   = -k |v_rel| / r w                              (Smits and Smith 1994, k = 2e-5)

or, for the Reynolds models of ``aero``, the spin decay of their row (``aero.spin_decay_rate``).
"""

import math
from typing import NamedTuple

from numba import njit

from mcrun.physics.aero import (
    C_LYU,
    C_RAMP,
    SPIN_K,
    SPIN_RATE,
    coefficients,
    is_reynolds,
    lyu_rise,
    quadratic,
    ramp_rise,
    spin_decay_rate,
)
from mcrun.physics.constants import BALL_AREA_M2, BALL_MASS_KG, BALL_RADIUS_M, G_MPS2, SPIN_DECAY_K

WIND_UNIFORM = 0
WIND_LOG = 1
WIND_POWER = 2
WIND_PROFILES = {"uniform": WIND_UNIFORM, "log": WIND_LOG, "power": WIND_POWER}


class FlightParams(NamedTuple):
    """Everything the flight needs besides its state, in SI and in the core's frame."""

    air_density_kgpm3: float
    kinematic_viscosity_m2ps: float
    aero_model: int
    cd_scale: float
    cl_scale: float
    wind_x_mps: float
    wind_y_mps: float
    wind_profile: int
    # Height at which the wind has its given speed, and the profile's parameter: the roughness
    # length z0 (m) of the log law, or the exponent of the power law.
    wind_reference_height_m: float
    wind_profile_parameter: float


@njit(cache=True, error_model="numpy")
def wind_factor(z, profile, reference_height, parameter):
    """Wind speed at height z as a fraction of its speed at the reference height."""
    if profile == WIND_UNIFORM:
        return 1.0
    if z <= 0.0:
        return 0.0
    if profile == WIND_LOG:
        if z <= parameter:
            return 0.0
        return math.log(z / parameter) / math.log(reference_height / parameter)
    return (z / reference_height) ** parameter


@njit(cache=True, error_model="numpy", inline="always")
def air_speed(ux, uy, uz, axis_x, axis_y, axis_z):
    """What the forces need of the air-relative velocity u (|u| > 0): its speed |u|, 1 / |u|,
    and the lift's direction l = w_hat x u with the scale |u|^2 / |l| that gives the lift its
    |u|^2 (0 where l vanishes, u along the spin axis). Two square roots and one division."""
    lx = axis_y * uz - axis_z * uy
    ly = axis_z * ux - axis_x * uz
    lz = axis_x * uy - axis_y * ux
    speed = math.sqrt(ux * ux + uy * uy + uz * uz)
    norm = math.sqrt(lx * lx + ly * ly + lz * lz)
    lifts = norm > 1e-12 * speed
    inverse = 1.0 / (speed * norm if lifts else speed)
    inverse_speed = norm * inverse if lifts else inverse
    lift_scale = speed * speed * speed * inverse if lifts else 0.0
    return speed, inverse_speed, lx, ly, lz, lift_scale


@njit(cache=True, error_model="numpy", inline="always")
def forces(ux, uy, uz, speed, spin, lx, ly, lz, lift_scale, k_cd, k_cl, cd, cl):
    """Acceleration and spin decay from the air-relative velocity u and ``air_speed``'s terms.

    k_cd = k C_D-scale and k_cl = k C_L-scale, with k = rho A / (2 m).
    """
    drag = k_cd * cd * speed
    lift = k_cl * cl * lift_scale
    ax = -drag * ux + lift * lx
    ay = -drag * uy + lift * ly
    az = -drag * uz + lift * lz - G_MPS2
    return ax, ay, az, -SPIN_DECAY_K * speed / BALL_RADIUS_M * spin


class GeneralContext(NamedTuple):
    """What ``derivatives`` needs besides the state: the unit spin axis, the FlightParams and
    ``aero.QUADRATIC_COEFFICIENTS``."""

    axis_x: float
    axis_y: float
    axis_z: float
    params: FlightParams
    table: object  # (n_models, n_columns) float64


class QuadraticContext(NamedTuple):
    """What ``derivatives_quadratic`` needs besides the state, 19 floats: the unit spin axis,
    the wind, k C_D-scale and k C_L-scale (k = rho A / 2m), the columns of the model's row of
    ``aero.QUADRATIC_COEFFICIENTS`` and the kinematic viscosity nu (``quadratic_context``). The
    shot loop keeps it in a table's rows, in this order, by these names."""

    axis_x: float
    axis_y: float
    axis_z: float
    wind_x: float
    wind_y: float
    k_cd: float
    k_cl: float
    a0: float
    a1: float
    a2: float
    b0: float
    b1: float
    b2: float
    s_max: float
    nu: float
    c_lyu: float
    c_ramp: float
    spin_k: float
    spin_rate: float


@njit(cache=True, error_model="numpy", inline="always")
def quadratic_context(axis_x, axis_y, axis_z, p, table):
    """The QuadraticContext of a shot of spin axis ``axis`` and FlightParams p, a quadratic or
    Reynolds model in uniform wind: the same numbers ``derivatives`` takes from p."""
    k_air = 0.5 * p.air_density_kgpm3 * BALL_AREA_M2 / BALL_MASS_KG
    row = table[p.aero_model]
    return QuadraticContext(
        axis_x, axis_y, axis_z, p.wind_x_mps, p.wind_y_mps, k_air * p.cd_scale,
        k_air * p.cl_scale, row[0], row[1], row[2], row[3], row[4], row[5], row[6],
        p.kinematic_viscosity_m2ps, row[C_LYU], row[C_RAMP], row[SPIN_K], row[SPIN_RATE],
    )  # fmt: skip


@njit(cache=True, error_model="numpy")
def derivatives(vx, vy, vz, spin, z, ctx):
    """Time derivatives (ax, ay, az, dspin/dt) of the flight state, any model and wind.

    ``ctx``: a GeneralContext.
    """
    axis_x, axis_y, axis_z, p, table = ctx.axis_x, ctx.axis_y, ctx.axis_z, ctx.params, ctx.table
    f = wind_factor(z, p.wind_profile, p.wind_reference_height_m, p.wind_profile_parameter)
    ux = vx - f * p.wind_x_mps
    uy = vy - f * p.wind_y_mps
    uz = vz
    if ux == 0.0 and uy == 0.0 and uz == 0.0:
        return 0.0, 0.0, -G_MPS2, 0.0
    speed, inverse_speed, lx, ly, lz, lift_scale = air_speed(ux, uy, uz, axis_x, axis_y, axis_z)
    spin_ratio = BALL_RADIUS_M * spin * inverse_speed
    reynolds = speed * 2.0 * BALL_RADIUS_M / p.kinematic_viscosity_m2ps
    cd, cl = coefficients(p.aero_model, spin_ratio, reynolds, table)
    k = 0.5 * p.air_density_kgpm3 * BALL_AREA_M2 / BALL_MASS_KG
    ax, ay, az, dspin = forces(
        ux, uy, uz, speed, spin, lx, ly, lz, lift_scale, k * p.cd_scale, k * p.cl_scale, cd, cl
    )
    if is_reynolds(p.aero_model):  # a spin decay of its own (aero.spin_decay_rate)
        dspin = -spin_decay_rate(p.aero_model, speed, table) * spin
    return ax, ay, az, dspin


@njit(cache=True, error_model="numpy")
def derivatives_quadratic(vx, vy, vz, spin, z, ctx):
    """``derivatives`` for a quadratic or Reynolds aerodynamic model in uniform wind, without
    branches, so that a loop over a block of shots vectorises. Bit for bit the same numbers as
    ``derivatives`` gives for such a shot (ignoring the measure-zero case |v_rel| = 0): for a
    quadratic model the rises are scaled by 0 and the spin decay is k |v_rel| / r + 0 with
    k = constants.SPIN_DECAY_K.

    ``ctx``: a QuadraticContext.
    """
    c = ctx
    ux = vx - c.wind_x
    uy = vy - c.wind_y
    uz = vz
    speed, inverse_speed, lx, ly, lz, lift_scale = air_speed(
        ux, uy, uz, c.axis_x, c.axis_y, c.axis_z
    )
    cd, cl = quadratic(
        BALL_RADIUS_M * spin * inverse_speed, c.a0, c.a1, c.a2, c.b0, c.b1, c.b2, c.s_max
    )
    reynolds = speed * 2.0 * BALL_RADIUS_M / c.nu
    cd += c.c_lyu * lyu_rise(reynolds) + c.c_ramp * ramp_rise(reynolds)
    ax, ay, az, _ = forces(ux, uy, uz, speed, spin, lx, ly, lz, lift_scale, c.k_cd, c.k_cl, cd, cl)
    return ax, ay, az, -(c.spin_k * speed / BALL_RADIUS_M + c.spin_rate) * spin


@njit(cache=True, error_model="numpy", inline="always")
def rk4_combine(x, y, z, vx, vy, vz, spin, h, v2, v3, v4, k1, k2, k3, k4):
    """The end of an RK4 step of size h from (x, ..., spin): the new seven-float state from the
    velocities v2, v3, v4 of stages 2-4 and the derivatives k1-k4 (ax, ay, az, dspin/dt) of
    stages 1-4."""
    w = h / 6.0
    return (
        x + w * (vx + 2.0 * v2[0] + 2.0 * v3[0] + v4[0]),
        y + w * (vy + 2.0 * v2[1] + 2.0 * v3[1] + v4[1]),
        z + w * (vz + 2.0 * v2[2] + 2.0 * v3[2] + v4[2]),
        vx + w * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]),
        vy + w * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]),
        vz + w * (k1[2] + 2.0 * k2[2] + 2.0 * k3[2] + k4[2]),
        spin + w * (k1[3] + 2.0 * k2[3] + 2.0 * k3[3] + k4[3]),
    )


def _make_rk4(deriv):
    """The classical Runge-Kutta step for the derivative function ``deriv`` (called as
    deriv(vx, vy, vz, spin, z, ctx)), and its stage. One source for both derivative functions
    below; numba compiles each with its derivative inlined."""

    # Inlined where they are called, so that a loop over a block of shots vectorises.
    @njit(cache=True, error_model="numpy", inline="always")
    def rk4_stage(vx, vy, vz, spin, z, c, k, vz_k, ctx):
        """A stage of an RK4 step from (vx, vy, vz, spin, z): its velocity, at the state moved
        by c times the derivative k of the stage before (whose vertical velocity is vz_k), and
        its derivative."""
        v = (vx + c * k[0], vy + c * k[1], vz + c * k[2])
        return v, deriv(v[0], v[1], v[2], spin + c * k[3], z + c * vz_k, ctx)

    @njit(cache=True, error_model="numpy", inline="always")
    def rk4_step(x, y, z, vx, vy, vz, spin, h, ctx):
        """One RK4 step of size h; returns the new seven-float state."""
        k1 = deriv(vx, vy, vz, spin, z, ctx)
        hh = 0.5 * h
        v2, k2 = rk4_stage(vx, vy, vz, spin, z, hh, k1, vz, ctx)
        v3, k3 = rk4_stage(vx, vy, vz, spin, z, hh, k2, v2[2], ctx)
        v4, k4 = rk4_stage(vx, vy, vz, spin, z, h, k3, v3[2], ctx)
        return rk4_combine(x, y, z, vx, vy, vz, spin, h, v2, v3, v4, k1, k2, k3, k4)

    return rk4_stage, rk4_step


# rk4_step(x, y, z, vx, vy, vz, spin, h, ctx) and its stage for any shot (ctx a GeneralContext),
# and for a quadratic model in uniform wind (ctx a QuadraticContext), which a block of shots
# steps through one loop at a time: the same numbers.
rk4_stage, rk4_step = _make_rk4(derivatives)
rk4_stage_quadratic, rk4_step_quadratic = _make_rk4(derivatives_quadratic)


# Newton steps of ``hermite_root``: three reach the root to 1e-14 s on the pga-driver shots.
HERMITE_ITERATIONS = 5


@njit(cache=True, error_model="numpy", inline="always")
def hermite_root(z0, vz0, z1, vz1, h):
    """Time in [0, h] where the cubic Hermite interpolant of z(t) over a step of length h
    comes down through zero, z0 >= 0 > z1.

    Newton's method on the cubic in s = t / h, safeguarded by bisection, a fixed number of
    steps without branches (for loops over many shots): the root only starts the Newton steps
    on the RK4 step itself (``engine.batch``). It starts from the chord's root, or, on a step that
    starts on the ground (the launch: a flight shorter than one step), from the end of the step,
    so that a rising ball finds its landing and not its launch.
    """
    hv0 = h * vz0
    hv1 = h * vz1
    lo = 0.0
    hi = 1.0
    s = z0 / (z0 - z1) if z0 > 0.0 else (1.0 if vz0 >= 0.0 else 0.0)
    for _ in range(HERMITE_ITERATIONS):
        s2 = s * s
        s3 = s2 * s
        z = (
            (2.0 * s3 - 3.0 * s2 + 1.0) * z0
            + (s3 - 2.0 * s2 + s) * hv0
            + (-2.0 * s3 + 3.0 * s2) * z1
            + (s3 - s2) * hv1
        )
        dz = (
            (6.0 * s2 - 6.0 * s) * z0
            + (3.0 * s2 - 4.0 * s + 1.0) * hv0
            + (-6.0 * s2 + 6.0 * s) * z1
            + (3.0 * s2 - 2.0 * s) * hv1
        )
        above = z > 0.0
        lo = s if above else lo
        hi = hi if above else s
        newton = s - z / dz  # NaN or outside [lo, hi]: bisect
        s = newton if (lo <= newton) & (newton <= hi) else 0.5 * (lo + hi)
    return s * h


@njit(cache=True, error_model="numpy")
def make_flight_params(
    air_density_kgpm3,
    kinematic_viscosity_m2ps,
    aero_model,
    cd_scale,
    cl_scale,
    wind_x_mps,
    wind_right_mps,
    wind_profile,
    wind_reference_height_m,
    wind_profile_parameter,
):
    """FlightParams from the user's frame (wind positive to the right) to the core's (y left)."""
    return FlightParams(
        air_density_kgpm3,
        kinematic_viscosity_m2ps,
        aero_model,
        cd_scale,
        cl_scale,
        wind_x_mps,
        -wind_right_mps,
        wind_profile,
        wind_reference_height_m,
        wind_profile_parameter,
    )
