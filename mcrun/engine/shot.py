"""The phases of one shot as the shot loop (``engine.batch``) takes them, on plain floats: the
check of its inputs, the apex, the landing inside the last flight step, and the outcome fields
written when it lands and when it comes to rest (``schema.OUTCOME_FIELDS``).

Frames: the kernel's inputs and outputs are in the user's frame, x along the target line, y to
the RIGHT, z up (azimuth, spin axis, wind and slope direction positive to the right). Inside it
runs in the right-handed frame with y to the left; the conversion happens where the outcome
fields are written (here), in ``flight.make_flight_params`` and in ``ground.plane``.

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
    FINAL_Z,
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
    PENALTY_X,
    PENALTY_Y,
    RUN,
    STATUS,
    TOTAL,
    TOTAL_TIME,
)
from mcrun.physics.trig import atan2_first_quadrant
from mcrun.status import (
    INVALID_INPUT,
    TOO_MANY_BOUNCES,
)

# The default flight step, chosen from the accuracy study (tests/test_accuracy.py,
# docs/accuracy.md): in uniform wind RK4 at 0.2 s puts carry within 4.3 mm of a DOP853
# reference for every model (within 0.8 mm for the quadratic ones); a log or power wind
# profile, whose shear is singular at the ground, needs 0.02 s for 2 mm.
DEFAULT_DT_S = 0.2
DEFAULT_DT_WIND_PROFILE_S = 0.02
# Interval of the trajectory points recorded during the hops and the roll.
TRAJECTORY_DT_S = 0.01


def default_dt_s(wind_profile="uniform"):
    """The default flight step (s) for a wind profile given by name."""
    return DEFAULT_DT_S if wind_profile == "uniform" else DEFAULT_DT_WIND_PROFILE_S


@njit(cache=True, inline="always")
def fail(out, i, status, first=CARRY):
    """Record that shot i ended with ``status``: its fields from ``first`` on (the flight's and
    the run's, or the run's alone when the flight was complete) are NaN."""
    for k in range(first, N_OUTCOME):
        out[i, k] = math.nan
    out[i, STATUS] = status


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


@njit(cache=True)
def from_start(out, i, x0, y0, z0):
    """Measure the distances of shot i from where it was struck, (x0, y0, z0) in the user's
    frame: its carry, lateral carry and total along the frame's axes, its apex above the ground
    there (``schema.OUTCOME_FIELDS``). From the tee (0, 0, 0) every field stays as it was, to
    the bit."""
    out[i, CARRY] -= x0
    out[i, CARRY_LATERAL] -= y0
    out[i, TOTAL] -= x0
    out[i, APEX] -= z0


@njit(cache=True, inline="always")
def write_run(out, i, landing_x, x, y, z, t, status, bounces, first_height, first_length, ref_x,
              ref_y):  # fmt: skip
    """Write the run fields of shot i, which landed at x = landing_x and rests (or ended) at
    (x, y, z); (ref_x, ref_y) is where it crossed into a penalty area or off the map, or, out of
    bounds, where it rests (``mcrun.status``)."""
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
    out[i, FINAL_Z] = z
    out[i, PENALTY_X] = ref_x
    out[i, PENALTY_Y] = -ref_y
    out[i, STATUS] = status
