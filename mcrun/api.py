"""The Python API for one shot: SI keyword arguments with units in their names, results as
dicts and DataFrames. Every check of user input lives here (and nowhere in the kernels), so the
command line and a Python user get the same one-line errors.
"""

import math
from dataclasses import dataclass

from mcrun import status
from mcrun.engine.backend import simulate_batch, simulate_traced
from mcrun.engine.schema import outcome_record, pack
from mcrun.engine.shot import default_dt_s
from mcrun.physics import aero, atmosphere
from mcrun.physics.bounce import bounce_in_plane, critical_backspin_radps
from mcrun.physics.constants import DEG, STANDARD_HUMIDITY, STANDARD_WIND_HEIGHT_M
from mcrun.physics.flight import WIND_PROFILES, make_flight_params
from mcrun.physics.launch import DEFAULT_CLUB_MASS_KG, launch_from_club
from mcrun.physics.turf import Turf, check_turf, rho_g_from_stimp, turf_preset
from mcrun.trajectory import PHASE_NAMES
from mcrun.units import shown


class InputError(ValueError):
    """An input out of its documented range; the message is one line meant for the user."""


# Documented input ranges (inclusive), in the units of the argument names.
RANGES = {
    "ball_speed_mps": (0.5, 120.0),
    "launch_angle_deg": (-20.0, 89.0),
    "azimuth_deg": (-60.0, 60.0),
    "spin_radps": (0.0, 2000.0),
    "spin_axis_deg": (-90.0, 90.0),
    "club_speed_mps": (1.0, 90.0),
    "club_mass_kg": (0.05, 1.0),
    "loft_deg": (0.0, 70.0),
    "temperature_c": (-40.0, 55.0),
    "pressure_pa": (50000.0, 110000.0),
    "altitude_m": (-500.0, 5000.0),
    "relative_humidity": (0.0, 1.0),
    "air_density_kgpm3": (0.5, 1.5),
    "wind_speed_mps": (0.0, 50.0),
    "wind_reference_height_m": (0.1, 100.0),
    "cd_scale": (0.0, 3.0),
    "cl_scale": (0.0, 3.0),
    "slope_deg": (0.0, 45.0),
    "fall_line_deg": (-360.0, 360.0),
    "dt_s": (1e-4, 0.25),
    # One impact (bounce_once): angle from the vertical, backspin positive (topspin negative).
    "impact_angle_deg": (0.0, 89.9),
    "backspin_radps": (-2000.0, 2000.0),
}

# Default parameter of each wind profile: roughness length z0 (m) of the log law over short
# grass, and the 1/7 exponent of the power law.
WIND_PROFILE_DEFAULTS = {"uniform": 0.0, "log": 0.03, "power": 1.0 / 7.0}


def check_range(name, value):
    """Return ``value`` as a float, or raise InputError naming ``name`` and its allowed range."""
    lo, hi = RANGES[name]
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {shown(value)}") from None
    if not math.isfinite(value):
        raise InputError(f"{name} must be finite, got {value}")
    if not lo <= value <= hi:
        raise InputError(f"{name} = {value:g} is outside the allowed range [{lo:g}, {hi:g}]")
    return value


@dataclass(frozen=True)
class ShotResult:
    """Outcome of one shot (``outcome``, SI, field names with units; ``schema.outcome_record``:
    NaN, or None for the bounces, where the shot did not get that far) and, on request, its
    trajectory (DataFrame t_s, x_m, y_m, z_m, phase; y positive to the right)."""

    outcome: dict
    trajectory: object = None  # a pandas DataFrame, or None

    def __getattr__(self, name):
        try:
            return self.outcome[name]
        except KeyError:
            raise AttributeError(name) from None

    @property
    def status_name(self):
        return status.NAMES[int(self.outcome["status"])]


def resolve_turf(turf="green", **overrides):
    """A Turf from a preset name or a Turf, with fields overridden (``stimp_m`` sets rho_g)."""
    if isinstance(turf, str):
        try:
            turf = turf_preset(turf)
        except ValueError as err:
            raise InputError(str(err)) from None
    overrides = {k: v for k, v in overrides.items() if v is not None}
    stimp_m = overrides.pop("stimp_m", None)
    if stimp_m is not None and "rho_g" in overrides:
        raise InputError("give rho_g or a Stimp reading, not both")
    if stimp_m is not None:
        try:
            overrides["rho_g"] = rho_g_from_stimp(float(stimp_m))
        except ValueError as err:
            raise InputError(str(err)) from None
    unknown = set(overrides) - set(Turf._fields)
    if unknown:
        raise InputError(f"unknown turf field(s): {', '.join(sorted(unknown))}")
    turf = turf._replace(**{k: float(v) for k, v in overrides.items()})
    try:
        return check_turf(turf)
    except ValueError as err:
        raise InputError(str(err)) from None


def launch_conditions(
    ball_speed_mps=None,
    launch_angle_deg=None,
    spin_radps=None,
    club_speed_mps=None,
    club_mass_kg=None,
    loft_deg=None,
):
    """(ball speed m/s, launch angle deg, spin rad/s) from a launch monitor or a club delivery
    (club mass default DEFAULT_CLUB_MASS_KG, a driver head)."""
    club = club_speed_mps is not None or loft_deg is not None or club_mass_kg is not None
    ball = ball_speed_mps is not None or launch_angle_deg is not None or spin_radps is not None
    if club and ball:
        raise InputError(
            "give either the ball launch (speed, angle, spin) or the club delivery "
            "(club speed, loft), not both"
        )
    if club:
        if club_speed_mps is None or loft_deg is None:
            raise InputError("a club delivery needs both the club speed and the dynamic loft")
        speed, angle, spin = launch_from_club(
            check_range("club_speed_mps", club_speed_mps),
            check_range(
                "club_mass_kg", DEFAULT_CLUB_MASS_KG if club_mass_kg is None else club_mass_kg
            ),
            check_range("loft_deg", loft_deg) * DEG,
        )
        return speed, angle / DEG, spin
    missing = [
        n
        for n, v in (
            ("ball_speed_mps", ball_speed_mps),
            ("launch_angle_deg", launch_angle_deg),
            ("spin_radps", spin_radps),
        )
        if v is None
    ]
    if missing:
        raise InputError(f"a ball launch needs {', '.join(missing)} (or give a club delivery)")
    return (
        check_range("ball_speed_mps", ball_speed_mps),
        check_range("launch_angle_deg", launch_angle_deg),
        check_range("spin_radps", spin_radps),
    )


def air_properties(
    temperature_c=20.0,
    pressure_pa=None,
    altitude_m=None,
    relative_humidity=STANDARD_HUMIDITY,
    air_density_kgpm3=None,
):
    """(density kg/m^3, kinematic viscosity m^2/s) from the weather; an explicit density wins."""
    t_k = check_range("temperature_c", temperature_c) + 273.15
    if pressure_pa is not None and altitude_m is not None:
        raise InputError("give the pressure or the altitude, not both")
    if altitude_m is not None:
        pressure = atmosphere.pressure_at_altitude_pa(check_range("altitude_m", altitude_m))
    elif pressure_pa is not None:
        pressure = check_range("pressure_pa", pressure_pa)
    else:
        pressure = atmosphere.STANDARD_PRESSURE_PA
    rh = check_range("relative_humidity", relative_humidity)
    if air_density_kgpm3 is not None:
        rho = check_range("air_density_kgpm3", air_density_kgpm3)
    else:
        rho = atmosphere.air_density_kgpm3(t_k, float(pressure), rh)
    return rho, atmosphere.kinematic_viscosity_m2ps(t_k, rho)


def flight_params(
    aero_model=aero.DEFAULT_MODEL,
    cd_scale=1.0,
    cl_scale=1.0,
    wind_mps=(0.0, 0.0),
    wind_profile="uniform",
    wind_reference_height_m=STANDARD_WIND_HEIGHT_M,
    wind_profile_parameter=None,
    **air,
):
    """FlightParams (core frame) from user-frame arguments; ``air`` as for ``air_properties``."""
    try:
        model = aero.model_id(aero_model)
    except ValueError as err:
        raise InputError(str(err)) from None
    if wind_profile not in WIND_PROFILES:
        raise InputError(
            f"unknown wind profile '{wind_profile}': choose one of {', '.join(WIND_PROFILES)}"
        )
    wind_x, wind_right = (float(w) for w in wind_mps)
    check_range("wind_speed_mps", math.hypot(wind_x, wind_right))
    if wind_profile_parameter is None:
        wind_profile_parameter = WIND_PROFILE_DEFAULTS[wind_profile]
    ref_h = check_range("wind_reference_height_m", wind_reference_height_m)
    if wind_profile == "log" and not 0.0 < wind_profile_parameter < ref_h:
        raise InputError(
            "the log wind profile's roughness length must be positive and below "
            "the reference height"
        )
    if wind_profile == "power" and not 0.0 <= wind_profile_parameter <= 1.0:
        raise InputError("the power wind profile's exponent must be within [0, 1]")
    rho, nu = air_properties(**air)
    return make_flight_params(
        rho,
        nu,
        model,
        check_range("cd_scale", cd_scale),
        check_range("cl_scale", cl_scale),
        wind_x,
        wind_right,
        WIND_PROFILES[wind_profile],
        ref_h,
        float(wind_profile_parameter),
    )


def conditions_inputs(turf="green", slope_deg=0.0, fall_line_deg=0.0, dt_s=None, **conditions):
    """The kernel's input columns that do not depend on the launch (turf, ground, air, wind,
    models, step), checked: {name of ``schema.INPUT_FIELDS``: float}. ``turf`` is a preset name
    or a Turf; ``conditions`` are the keyword arguments of ``flight_params``."""
    slope = check_range("slope_deg", slope_deg) * DEG
    fall_line = check_range("fall_line_deg", fall_line_deg) * DEG
    if dt_s is None:
        dt_s = default_dt_s(conditions.get("wind_profile", "uniform"))
    dt = check_range("dt_s", dt_s)
    turf = resolve_turf(turf)
    params = flight_params(**conditions)
    return {
        "air_density_kgpm3": params.air_density_kgpm3,
        "kinematic_viscosity_m2ps": params.kinematic_viscosity_m2ps,
        "aero_model": float(params.aero_model),
        "cd_scale": params.cd_scale,
        "cl_scale": params.cl_scale,
        "wind_x_mps": params.wind_x_mps,
        "wind_right_mps": -params.wind_y_mps,  # FlightParams is in the core's frame, y left
        "wind_profile": float(params.wind_profile),
        "wind_reference_height_m": params.wind_reference_height_m,
        "wind_profile_parameter": params.wind_profile_parameter,
        **turf._asdict(),
        "slope_rad": slope,
        "fall_line_rad": fall_line,
        "dt_s": dt,
    }


def shot_inputs(
    *,
    ball_speed_mps=None,
    launch_angle_deg=None,
    spin_radps=None,
    azimuth_deg=0.0,
    spin_axis_deg=0.0,
    club_speed_mps=None,
    club_mass_kg=None,
    loft_deg=None,
    **conditions,
):
    """The kernel's inputs of one shot, checked: (inputs, launch angle).

    The arguments are those of ``simulate`` (``conditions``: ``conditions_inputs``'). Returns
    the (1, N_INPUT) array of ``schema.pack`` and the launch angle in degrees, as given or as
    the club delivery gives it (the kernel reports it back through radians, which may move its
    last bit).
    """
    speed, angle_deg, spin = launch_conditions(
        ball_speed_mps, launch_angle_deg, spin_radps, club_speed_mps, club_mass_kg, loft_deg
    )
    launch = {
        "ball_speed_mps": speed,
        "launch_angle_rad": angle_deg * DEG,
        "azimuth_rad": check_range("azimuth_deg", azimuth_deg) * DEG,
        "spin_radps": spin,
        "spin_axis_rad": check_range("spin_axis_deg", spin_axis_deg) * DEG,
    }
    return pack({**launch, **conditions_inputs(**conditions)}, 1), angle_deg


def simulate(*, trajectory=False, **shot):
    """Simulate one shot from launch to rest.

    Give the ball launch as a launch monitor reports it (``ball_speed_mps``,
    ``launch_angle_deg`` above the horizontal, ``spin_radps``, ``azimuth_deg`` and
    ``spin_axis_deg``, both positive to the right) or the club delivery (``club_speed_mps``,
    ``club_mass_kg``, ``loft_deg``; Penner 2001), and the conditions: ``turf`` (a preset name
    or a Turf), ``slope_deg``, ``fall_line_deg``, ``dt_s`` and the keyword arguments of
    ``flight_params`` (aero model, scales, wind, weather); the defaults are those of
    ``shot_inputs`` and ``conditions_inputs``. Returns a ShotResult; ``trajectory=True`` adds
    its path.
    """
    inputs, angle_deg = shot_inputs(**shot)
    if trajectory:
        out, traj = simulate_traced(inputs)
    else:
        out = simulate_batch(inputs)
    outcome = outcome_record(out)
    outcome["launch_angle_deg"] = angle_deg  # as given, not back from radians
    frame = None
    if trajectory:
        import pandas as pd  # only here: a shot without its path starts faster

        frame = pd.DataFrame(traj, columns=["t_s", "x_m", "y_m", "z_m", "phase"])
        frame["phase"] = pd.Categorical.from_codes(frame["phase"].astype(int), PHASE_NAMES)
    return ShotResult(outcome, frame)


def bounce_once(speed_mps, angle_deg, backspin_radps, turf="green", **turf_overrides):
    """One impact on level turf in the paper's terms (angles from the vertical, backspin
    positive): theta_c_deg, e, mu_c, mode, rebound speed, angle and spin, hop height."""
    speed = check_range("ball_speed_mps", speed_mps)
    angle = check_range("impact_angle_deg", angle_deg) * DEG
    backspin = check_range("backspin_radps", backspin_radps)
    turf = resolve_turf(turf, **turf_overrides)
    result = bounce_in_plane(speed, angle, backspin, turf)
    result["critical_backspin_radps"] = critical_backspin_radps(speed, angle, turf)
    return result
