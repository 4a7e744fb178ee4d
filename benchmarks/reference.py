"""The reference integration: a shot's flight by scipy's DOP853 at rtol = atol = 1e-12.

The equations of motion of physics.md ("Flight") are written out again here, without calling
``mcrun.physics.flight`` or ``mcrun.physics.launch``, so that the kernel is checked against
something it does not share code with:

    dv/dt = -g z - k C_D |u| u + k C_L |u|^2 (w x u) / |w x u|,   u = v - wind(z),
    dw/dt = -2e-5 |u| / r w,    k = rho A / (2 m),    S = r |w| / |u|,

with a terminal event at the ground (z = 0, falling). From that landing state the run (bounces,
slide and roll) is the kernel's own shot loop from the landing on
(``mcrun.engine.backend.simulate_landed``): what is checked is the flight and the hand-over to the
ground, and how a landing error carries into the total.

A shot is one row of the kernel's inputs (``mcrun.engine.schema.INPUT_FIELDS``: SI, the user's
frame, y to the right). The integration runs in the core's frame (x along the target line, y to
the LEFT, z up), as the landing the shot loop takes.
"""

import math

import numpy as np
from scipy.integrate import solve_ivp

from mcrun.engine.backend import simulate_landed
from mcrun.engine.schema import COLUMN, FINAL_X, FINAL_Y, STATUS
from mcrun.physics.aero import QUADRATIC_COEFFICIENTS
from mcrun.physics.flight import WIND_PROFILES

R = 0.021335  # ball radius (m), physics.md
M = 0.04593  # ball mass (kg)
G = 9.80665  # m/s^2
AREA = math.pi * R * R
SPIN_DECAY = 2.0e-5  # Smits and Smith (1994): dw/dt = -k |u| / r w
RTOL = 1e-12
ATOL = 1e-12
MAX_TIME_S = 60.0


def launch_state(speed, elevation, azimuth, spin_axis):
    """Velocity and unit spin axis at launch, core frame (y LEFT), from a launch monitor's
    numbers (azimuth and spin axis positive to the right; physics.md, "Flight")."""
    v_hat = np.array(
        [
            math.cos(elevation) * math.cos(azimuth),
            -math.cos(elevation) * math.sin(azimuth),
            math.sin(elevation),
        ]
    )
    # Pure backspin is about v x z (to the right of the flight), so that w x v points up; the
    # spin axis tilts it about v, a positive tilt turning the lift to the right.
    b = np.cross(v_hat, [0.0, 0.0, 1.0])
    b /= np.linalg.norm(b)
    up = np.cross(b, v_hat)
    axis = math.cos(spin_axis) * b - math.sin(spin_axis) * up
    return speed * v_hat, axis


def _wind_factor(z, profile, z_ref, parameter):
    if profile == WIND_PROFILES["uniform"]:
        return 1.0
    if z <= 0.0:
        return 0.0
    if profile == WIND_PROFILES["log"]:
        return math.log(z / parameter) / math.log(z_ref / parameter) if z > parameter else 0.0
    return (z / z_ref) ** parameter


def reference_landing(row):
    """Landing of the shot ``row`` by DOP853: (t, x, y, vx, vy, vz, spin, axis), core frame."""
    c = {name: row[k] for name, k in COLUMN.items()}
    model = int(c["aero_model"])
    a0, a1, a2, b0, b1, b2, s_max = QUADRATIC_COEFFICIENTS[model][:7]
    if not math.isfinite(a0):
        raise ValueError(f"the reference knows the quadratic aerodynamic models only, not {model}")
    k = 0.5 * c["air_density_kgpm3"] * AREA / M
    cd_scale = c["cd_scale"]
    cl_scale = c["cl_scale"]
    wind_x = c["wind_x_mps"]
    wind_y = -c["wind_right_mps"]
    profile = int(c["wind_profile"])
    z_ref = c["wind_reference_height_m"]
    parameter = c["wind_profile_parameter"]
    v0, axis = launch_state(
        c["ball_speed_mps"], c["launch_angle_rad"], c["azimuth_rad"], c["spin_axis_rad"]
    )
    ax, ay, az = axis

    def rhs(t, s):
        f = _wind_factor(s[2], profile, z_ref, parameter)
        ux = s[3] - f * wind_x
        uy = s[4] - f * wind_y
        uz = s[5]
        u = math.sqrt(ux * ux + uy * uy + uz * uz)
        ratio = min(R * s[6] / u, s_max)
        cd = cd_scale * (a0 + a1 * ratio + a2 * ratio * ratio)
        cl = cl_scale * (b0 + b1 * ratio + b2 * ratio * ratio)
        lx = ay * uz - az * uy
        ly = az * ux - ax * uz
        lz = ax * uy - ay * ux
        lift = k * cl * u * u / math.sqrt(lx * lx + ly * ly + lz * lz)
        drag = k * cd * u
        return [
            s[3],
            s[4],
            s[5],
            -drag * ux + lift * lx,
            -drag * uy + lift * ly,
            -drag * uz + lift * lz - G,
            -SPIN_DECAY * u / R * s[6],
        ]

    def ground(t, s):
        return s[2]

    ground.terminal = True
    ground.direction = -1.0
    y0 = [0.0, 0.0, 0.0, *v0, c["spin_radps"]]
    sol = solve_ivp(
        rhs, (0.0, MAX_TIME_S), y0, method="DOP853", rtol=RTOL, atol=ATOL, events=ground
    )
    if sol.status != 1 or len(sol.t_events[0]) != 1:
        raise RuntimeError(f"the reference flight did not land: {sol.message}")
    t = sol.t_events[0][0]
    x, y, _, vx, vy, vz, spin = sol.y_events[0][0]
    return t, x, y, vx, vy, vz, spin, axis


def reference_shot(row):
    """Carry and total (m, along the target line) of the shot ``row``: the DOP853 flight, then
    the kernel's run from its landing state (``simulate_landed``). Returns a dict with the
    landing too."""
    c = {name: row[k] for name, k in COLUMN.items()}
    t, x, y, vx, vy, vz, spin, axis = reference_landing(row)
    # The ground: the plane of the slope through the landing point, its normal tilted towards
    # the fall line (positive right in the user's frame, so -y in the core's).
    slope = c["slope_rad"]
    fall_line = c["fall_line_rad"]
    nx = math.sin(slope) * math.cos(fall_line)
    ny = -math.sin(slope) * math.sin(fall_line)
    nz = math.cos(slope)
    w = spin * axis
    landing = [[x, y, vx, vy, vz, w[0], w[1], w[2], t, nx, ny, nz]]
    out, _ = simulate_landed(row[None, :], np.array(landing))
    final_x, final_y, status = out[0, FINAL_X], out[0, FINAL_Y], out[0, STATUS]
    return {
        "carry_m": x,
        "carry_lateral_m": -y,
        "flight_time_s": t,
        "landing_speed_mps": math.sqrt(vx * vx + vy * vy + vz * vz),
        "total_m": final_x,
        "final_y_m": final_y,
        "status": int(status),
    }
