"""Accuracy of the flight integration against a high-accuracy reference.

The reference integrates the equations of motion of physics.md ("Flight"), written out again here
without calling ``mcrun.physics.flight``, with scipy's DOP853 at rtol = atol = 1e-12 and a terminal
event at the ground. The kernel (fixed-step RK4 at ``shot.default_dt_s``, with a Hermite landing
root) must agree within 1 cm on carry, lateral and apex, and within 1e-3 m/s on the landing speed,
for every aerodynamic model, with spin axis, crosswind and a log wind profile.

Frame of the reference: right-handed, x along the target line, y to the LEFT, z up; the user's
lateral (positive right) is -y.
"""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from mcrun.api import WIND_PROFILE_DEFAULTS, air_properties, simulate
from mcrun.engine.shot import default_dt_s
from mcrun.physics.aero import MODELS, QUADRATIC_COEFFICIENTS

REYNOLDS = ("trackman2019_lyu", "trackman2019_ramp", "trackman2019_exp", "trackman2019_lyu_exp")

R = 0.021335  # ball radius (m), physics.md
M = 0.04593  # ball mass (kg)
G = 9.80665
AREA = math.pi * R * R
SPIN_DECAY = 2.0e-5  # Smits and Smith: dw/dt = -k |v_rel| / r w


def quadratic(a0, a1, a2, b0, b1, b2, s_max):
    def coefficients(s, re):
        s = min(s, s_max)
        return a0 + a1 * s + a2 * s * s, b0 + b1 * s + b2 * s * s

    return coefficients


def smits_smith(s, re):
    re = min(max(re, 7.0e4), 2.1e5)  # held inside its range of validity
    return 0.24 + 0.18 * s + 0.06 * math.sin(math.pi * (re - 9.0e4) / 2.0e5), 0.54 * s**0.4


def lyu(s, re):
    if re < 1.053e5:  # where the low- and high-Re fits cross
        cd = 1.29e-10 * re * re - 2.59e-5 * re + 1.50
    else:
        cd = 1.91e-11 * re * re - 5.40e-6 * re + 0.56
    s = min(s, 0.32)
    return cd, 1.99 * s - 3.25 * s * s


def reynolds(a0, a1, a2, b0, b1, b2, s_max, c_lyu, c_ramp, *_decay):
    """The quadratic plus Lyu et al.'s low-Re drag above its minimum (Re 2.59e-5 / 2.58e-10)
    and libgolf's linear rise from Re 1e5 to 5e4, scaled (physics.md, aero.py)."""
    s_part = quadratic(a0, a1, a2, b0, b1, b2, s_max)

    def lyu_low(re):
        return 1.29e-10 * re * re - 2.59e-5 * re + 1.50

    re_min = 2.59e-5 / 2.58e-10

    def coefficients(s, re):
        cd, cl = s_part(s, re)
        lyu = lyu_low(min(re, re_min)) - lyu_low(re_min)
        ramp = min(max((1.0e5 - re) / 5.0e4, 0.0), 1.0)
        return cd + c_lyu * lyu + c_ramp * ramp, cl

    return coefficients


COEFFICIENTS = {
    "ferguson2022": quadratic(0.1304, 0.9287, -0.8259, 0.0504, 1.2031, -1.1490, 0.75),
    "smits_smith1994": smits_smith,
    "lyu2018": lyu,
    # Fitted models: their coefficients are data, read from the table.
    "penner2002": quadratic(*QUADRATIC_COEFFICIENTS[3][:7]),
    "trackman2019": quadratic(*QUADRATIC_COEFFICIENTS[4][:7]),
    **{name: reynolds(*QUADRATIC_COEFFICIENTS[MODELS[name]]) for name in REYNOLDS},
}
# Spin decay dw/dt = -(k |v_rel| / r + lambda) w: (k, lambda) of each model.
DECAY = {name: (SPIN_DECAY, 0.0) for name in COEFFICIENTS}
DECAY.update({name: tuple(QUADRATIC_COEFFICIENTS[MODELS[name]][9:11]) for name in REYNOLDS})


def wind_factor(z, profile, z_ref, parameter):
    if profile == "uniform":
        return 1.0
    if z <= 0.0:
        return 0.0
    if profile == "log":
        return math.log(z / parameter) / math.log(z_ref / parameter) if z > parameter else 0.0
    return (z / z_ref) ** parameter


def reference_flight(shot):
    """Carry, lateral (m, right positive), apex (m) and landing speed (m/s) by DOP853."""
    rho, nu = air_properties(**shot.get("air", {}))
    coefficients = COEFFICIENTS[shot["aero_model"]]
    decay_k, decay_rate = DECAY[shot["aero_model"]]
    profile = shot.get("wind_profile", "uniform")
    parameter = WIND_PROFILE_DEFAULTS[profile]
    z_ref = 10.0
    wind = np.array([shot["wind_mps"][0], -shot["wind_mps"][1], 0.0])
    k = 0.5 * rho * AREA / M

    speed = shot["ball_speed_mps"]
    elevation = math.radians(shot["launch_angle_deg"])
    azimuth = math.radians(shot["azimuth_deg"])
    v_hat = np.array(
        [
            math.cos(elevation) * math.cos(azimuth),
            -math.cos(elevation) * math.sin(azimuth),
            math.sin(elevation),
        ]
    )
    # Backspin is about v x z (to the right of the flight); the spin axis tilts it about v so
    # that a positive tilt turns the lift w x v to the right.
    b = np.cross(v_hat, [0.0, 0.0, 1.0])
    b /= np.linalg.norm(b)
    up = np.cross(b, v_hat)
    tilt = math.radians(shot["spin_axis_deg"])
    axis = math.cos(tilt) * b - math.sin(tilt) * up

    def rhs(t, s):
        v = s[3:6]
        u = v - wind_factor(s[2], profile, z_ref, parameter) * wind
        u_mag = math.sqrt(u @ u)
        cd, cl = coefficients(R * s[6] / u_mag, u_mag * 2.0 * R / nu)
        lift = np.cross(axis, u)
        a = -k * cd * u_mag * u + k * cl * u_mag * u_mag * lift / math.sqrt(lift @ lift)
        a[2] -= G
        return [*v, *a, -(decay_k * u_mag / R + decay_rate) * s[6]]

    def ground(t, s):
        return s[2]

    ground.terminal = True
    ground.direction = -1.0

    def apex(t, s):
        return s[5]

    apex.direction = -1.0
    y0 = [0.0, 0.0, 0.0, *(speed * v_hat), shot["spin_radps"]]
    sol = solve_ivp(
        rhs, (0.0, 60.0), y0, method="DOP853", rtol=1e-12, atol=1e-12, events=(ground, apex)
    )
    assert sol.status == 1, "the reference must end on the ground event"
    land = sol.y_events[0][0]
    return {
        "carry_m": land[0],
        "carry_lateral_m": -land[1],
        "apex_m": max(sol.y_events[1][:, 2], default=0.0),
        "landing_speed_mps": math.sqrt(land[3] ** 2 + land[4] ** 2 + land[5] ** 2),
    }


def kernel_flight(shot, dt_s):
    kwargs = {key: value for key, value in shot.items() if key != "air"}
    return simulate(**kwargs, **shot.get("air", {}), dt_s=dt_s).outcome


def shot(aero_model, speed, angle, spin, axis=0.0, azimuth=0.0, wind=(0.0, 0.0), **extra):
    return dict(
        ball_speed_mps=speed,
        launch_angle_deg=angle,
        spin_radps=spin,
        spin_axis_deg=axis,
        azimuth_deg=azimuth,
        wind_mps=wind,
        aero_model=aero_model,
        **extra,
    )


SHOTS = {
    "driver, spin axis and crosswind": shot(
        "trackman2019", 70.0, 11.0, 280.0, axis=8.0, azimuth=-2.0, wind=(-3.0, 6.0)
    ),
    "driver, log wind profile": shot(
        "ferguson2022", 72.0, 10.5, 290.0, axis=-5.0, wind=(4.0, -5.0), wind_profile="log"
    ),
    "driver, Penner's air": shot("penner2002", 74.3, 10.7, 397.0, air={"air_density_kgpm3": 1.204}),
    "driver, Smits and Smith": shot("smits_smith1994", 65.0, 12.0, 300.0, axis=3.0),
    "driver, Lyu": shot("lyu2018", 68.0, 11.0, 270.0, wind=(5.0, 0.0)),
    "9-iron": shot("trackman2019", 48.0, 30.0, 850.0, axis=-4.0, wind=(0.0, -4.0)),
    "9-iron, Lyu (high spin ratio)": shot("lyu2018", 42.5, 35.4, 915.0),
    "low punch": shot(
        "ferguson2022", 40.0, 4.0, 450.0, azimuth=3.0, wind=(-6.0, 3.0), wind_profile="log"
    ),
    "punch, 5000 ft": shot("smits_smith1994", 45.0, 6.0, 500.0, air={"altitude_m": 1524.0}),
    # Flights of one and two steps: the landing and the apex lie in the step from the ground.
    "chip, shorter than one step": shot("trackman2019", 10.0, 5.0, 100.0),
    "chip, two steps": shot("ferguson2022", 12.0, 8.0, 150.0, wind=(2.0, 3.0)),
    # The Reynolds models, in their vectorised lanes (uniform wind) and the general (log).
    "7-iron, Lyu rise": shot("trackman2019_lyu", 53.6, 16.3, 743.0, axis=4.0, wind=(-3.0, 2.0)),
    "7-iron, Lyu rise, log wind": shot(
        "trackman2019_lyu", 53.6, 16.3, 743.0, wind=(4.0, -3.0), wind_profile="log"
    ),
    "wedge, ramp": shot("trackman2019_ramp", 45.6, 24.2, 974.0, wind=(0.0, 3.0)),
    "driver, 4 %/s decay": shot("trackman2019_exp", 74.7, 10.9, 281.0, axis=-3.0),
    "5-iron, Lyu rise and 4 %/s": shot("trackman2019_lyu_exp", 59.0, 12.1, 561.0),
}


@pytest.fixture(scope="module")
def references():
    return {name: reference_flight(s) for name, s in SHOTS.items()}


@pytest.mark.parametrize("name", SHOTS)
def test_default_step_matches_reference(name, references):
    """Carry, lateral and apex within 1 cm, landing speed within 1e-3 m/s, at the default
    step."""
    ref = references[name]
    got = kernel_flight(SHOTS[name], default_dt_s(SHOTS[name].get("wind_profile", "uniform")))
    assert got["carry_m"] == pytest.approx(ref["carry_m"], abs=0.01)
    assert got["carry_lateral_m"] == pytest.approx(ref["carry_lateral_m"], abs=0.01)
    assert got["apex_m"] == pytest.approx(ref["apex_m"], abs=0.01)
    assert got["landing_speed_mps"] == pytest.approx(ref["landing_speed_mps"], abs=1e-3)


def test_reference_is_not_trivially_the_kernel(references):
    """The shots exercise what they claim: the crosswind and spin axis move the driver by
    metres, the log profile changes the low punch's carry (the ball stays under 2 m, where the
    wind is weak), and the models differ by metres."""
    drive = references["driver, spin axis and crosswind"]
    assert drive["carry_lateral_m"] > 5.0
    uniform = reference_flight({**SHOTS["low punch"], "wind_profile": "uniform"})
    assert abs(uniform["carry_m"] - references["low punch"]["carry_m"]) > 1.0
    carries = [references[n]["carry_m"] for n in SHOTS if n.startswith("driver")]
    assert max(carries) - min(carries) > 5.0
