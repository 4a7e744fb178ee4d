"""The Python API for one shot: SI keyword arguments with units in their names, results as
dicts and DataFrames. Every check of a shot's input lives here (and nowhere in the kernels), so
the command line and a Python user get the same one-line errors; the ranges, the defaults and the
conversion to the kernel's columns are those of the table of quantities (``mcrun.quantities``),
which the runs share.
"""

import inspect
import math
from dataclasses import dataclass

import numpy as np

from mcrun import status
from mcrun.engine.backend import simulate_batch, simulate_traced
from mcrun.engine.schema import outcome_record, pack
from mcrun.physics import aero
from mcrun.physics.bounce import bounce_in_plane, critical_backspin_radps
from mcrun.physics.constants import DEG
from mcrun.physics.flight import WIND_PROFILES, make_flight_params
from mcrun.physics.turf import Turf, check_turf, rho_g_from_stimp, turf_preset
from mcrun.quantities import (  # RANGES, InputError and check_range: re-exported, public here
    DEFAULTS,
    RANGES,
    WIND_PROFILE_DEFAULTS,
    InputError,
    air,
    by_column,
    check_range,
    club_launch,
    default_of,
    finite_number,
    kernel_columns,
    kernel_part,
    to_si,
    wind_profile_problem,
    with_defaults,
)
from mcrun.trajectory import PHASE_NAMES
from mcrun.units import shown

__all__ = [
    "RANGES",
    "WIND_PROFILE_DEFAULTS",
    "InputError",
    "ShotResult",
    "air_properties",
    "bounce_once",
    "check_range",
    "conditions_inputs",
    "flight_params",
    "launch_conditions",
    "resolve_turf",
    "shot_inputs",
    "simulate",
]


def _checked_si(column, value):
    """A keyword argument checked against its range, in SI."""
    return to_si(check_range(column, value), by_column(column).kind)


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


def resolve_turf(turf=DEFAULTS["turf"], **overrides):
    """A Turf from a preset name or a Turf, with fields overridden (``stimp_m`` sets rho_g)."""
    if isinstance(turf, str):
        try:
            turf = turf_preset(turf)
        except ValueError as err:
            raise InputError(str(err)) from None
    elif not isinstance(turf, Turf):
        raise InputError(f"turf {turf!r}: allowed: a preset's name (mcrun turfs) or a Turf")
    overrides = {k: v for k, v in overrides.items() if v is not None}
    stimp_m = overrides.pop("stimp_m", None)
    if stimp_m is not None and "rho_g" in overrides:
        raise InputError("give rho_g or a Stimp reading, not both")
    if stimp_m is not None:
        stimp_m = check_range("stimp_m", stimp_m)  # (a rho_g out of range named no Stimp)
        try:
            overrides["rho_g"] = rho_g_from_stimp(stimp_m)
        except ValueError as err:
            raise InputError(str(err)) from None
    unknown = set(overrides) - set(Turf._fields)
    if unknown:
        raise InputError(f"unknown turf field(s): {', '.join(sorted(unknown))}")
    turf = turf._replace(**{k: finite_number(f"turf {k}", v) for k, v in overrides.items()})
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
    (club mass default that of ``quantities``, a driver head's)."""
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
        launch = club_launch(
            check_range("club_speed_mps", club_speed_mps),
            check_range(
                "club_mass_kg", DEFAULTS["club_mass_kg"] if club_mass_kg is None else club_mass_kg
            ),
            _checked_si("loft_deg", loft_deg),
        )
        # The launch the delivery gives is held to the ranges of a launch given directly (a
        # loft of 0 with a club of 1 kg launched at 137.6 m/s, where 120 is the most).
        for name, value in zip(("ball_speed_mps", "launch_angle_deg", "spin_radps"), launch,
                               strict=True):  # fmt: skip
            lo, hi = RANGES[name]
            if not lo <= value <= hi:
                raise InputError(f"the club's delivery launches the ball with {name} = "
                                 f"{value:.4g}, outside the allowed range [{lo:g}, "
                                 f"{hi:g}]")  # fmt: skip
        return launch
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


def _air_values(
    temperature_c=DEFAULTS["temperature_c"],
    pressure_pa=None,
    altitude_m=None,
    relative_humidity=DEFAULTS["relative_humidity"],
    air_density_kgpm3=None,
):
    """The weather's SI values by key path, checked, and the density given (or None)."""
    values = {"weather.temperature": _checked_si("temperature_c", temperature_c)}
    if pressure_pa is not None and altitude_m is not None:
        raise InputError("give the pressure or the altitude, not both")
    if altitude_m is not None:
        values["weather.altitude"] = check_range("altitude_m", altitude_m)
    elif pressure_pa is not None:
        values["weather.pressure"] = check_range("pressure_pa", pressure_pa)
    else:
        values["weather.pressure"] = default_of("weather.pressure")
    values["weather.humidity"] = check_range("relative_humidity", relative_humidity)
    if air_density_kgpm3 is not None:
        return values, check_range("air_density_kgpm3", air_density_kgpm3)
    return values, None


def air_properties(
    temperature_c=DEFAULTS["temperature_c"],
    pressure_pa=None,
    altitude_m=None,
    relative_humidity=DEFAULTS["relative_humidity"],
    air_density_kgpm3=None,
):
    """(density kg/m^3, kinematic viscosity m^2/s) from the weather; an explicit density wins."""
    _, rho, nu = air(
        *_air_values(temperature_c, pressure_pa, altitude_m, relative_humidity, air_density_kgpm3)
    )
    return rho, nu


def _flight_values(
    aero_model=DEFAULTS["aero_model"],
    cd_scale=DEFAULTS["cd_scale"],
    cl_scale=DEFAULTS["cl_scale"],
    wind_mps=(0.0, 0.0),
    wind_profile=DEFAULTS["wind_profile"],
    wind_reference_height_m=None,
    wind_profile_parameter=None,
    **air_args,
):
    """The flight's SI values by key path, checked, the wind (along, right; m/s) and the
    density given (or None); the arguments are those of ``flight_params``."""
    try:
        aero.model_id(aero_model)
    except ValueError as err:
        raise InputError(str(err)) from None
    if wind_profile not in WIND_PROFILES:
        raise InputError(
            f"unknown wind profile '{wind_profile}': choose one of {', '.join(WIND_PROFILES)}"
        )
    if not (isinstance(wind_mps, list | tuple | np.ndarray) and np.shape(wind_mps) == (2,)):
        raise InputError(f"wind_mps {shown(wind_mps)}: allowed: two numbers (m/s), along the "
                         "target line (a tailwind > 0) and blowing to the right, such as (5.0, "
                         "0.0)")  # fmt: skip
    wind_x, wind_right = (finite_number("wind_mps", w) for w in wind_mps)
    check_range("wind_speed_mps", math.hypot(wind_x, wind_right))
    values = {"models.aero": aero_model, "weather.wind_profile": wind_profile}
    profile_args = {"wind_reference_height_m": wind_reference_height_m,
                    "wind_profile_parameter": wind_profile_parameter}  # fmt: skip
    given = [name for name, value in profile_args.items() if value is not None]
    if wind_profile == "uniform" and given:  # (ignored: the same numbers)
        raise InputError(f"{given[0]}: is for wind_profile 'log' or 'power' (a uniform wind is "
                         "the same at every height)")  # fmt: skip
    if wind_reference_height_m is None:
        wind_reference_height_m = DEFAULTS["wind_reference_height_m"]
    if wind_profile_parameter is None:
        wind_profile_parameter = default_of("weather.wind_profile_parameter", values)
    wind_profile_parameter = finite_number("wind_profile_parameter", wind_profile_parameter)
    ref_h = check_range("wind_reference_height_m", wind_reference_height_m)
    problem = wind_profile_problem(wind_profile, ref_h, wind_profile_parameter)
    if problem is not None:
        raise InputError(f"wind_profile_parameter: {problem}")
    weather, density = _air_values(**air_args)
    values.update(weather)
    values["weather.wind_reference_height"] = ref_h
    values["weather.wind_profile_parameter"] = float(wind_profile_parameter)
    values["models.cd_scale"] = check_range("cd_scale", cd_scale)
    values["models.cl_scale"] = check_range("cl_scale", cl_scale)
    return values, (wind_x, wind_right), density


def flight_params(
    aero_model=DEFAULTS["aero_model"],
    cd_scale=DEFAULTS["cd_scale"],
    cl_scale=DEFAULTS["cl_scale"],
    wind_mps=(0.0, 0.0),
    wind_profile=DEFAULTS["wind_profile"],
    wind_reference_height_m=None,
    wind_profile_parameter=None,
    **air_args,
):
    """FlightParams (core frame) from user-frame arguments; ``air_args`` as for
    ``air_properties``. ``wind_reference_height_m`` (default 10 m) and
    ``wind_profile_parameter`` (default the profile's, ``WIND_PROFILE_DEFAULTS``) are a log or
    power profile's: a uniform wind refuses them."""
    values, (wind_x, wind_right), density = _flight_values(
        aero_model,
        cd_scale,
        cl_scale,
        wind_mps,
        wind_profile,
        wind_reference_height_m,
        wind_profile_parameter,
        **air_args,
    )
    _, rho, nu = air(values, density)
    return make_flight_params(
        rho,
        nu,
        aero.model_id(aero_model),
        values["models.cd_scale"],
        values["models.cl_scale"],
        wind_x,
        wind_right,
        WIND_PROFILES[wind_profile],
        values["weather.wind_reference_height"],
        values["weather.wind_profile_parameter"],
    )


def _keywords(*functions):
    """The named parameters of ``functions``, in order (their ``**`` apart)."""
    return [name for f in functions for name, p in inspect.signature(f).parameters.items()
            if p.kind is not p.VAR_KEYWORD]  # fmt: skip


def _check_keywords(given, *functions):
    """InputError naming the first of the keyword arguments ``given`` that none of
    ``functions`` takes, and every one a shot takes (a TypeError naming a private function
    before)."""
    known = _keywords(*functions)
    unknown = [k for k in given if k not in known]
    if unknown:
        allowed = _keywords(shot_inputs, _conditions_values, _flight_values, _air_values)
        raise InputError(f"unknown argument {unknown[0]!r}; allowed: {', '.join(allowed)} (a "
                         "turf's fields: turf=resolve_turf(preset, mu=...))")  # fmt: skip


def _conditions_values(
    turf=DEFAULTS["turf"],
    slope_deg=DEFAULTS["slope_deg"],
    fall_line_deg=DEFAULTS["fall_line_deg"],
    dt_s=None,
    **conditions,
):
    """(SI values by key path, wind, density) of ``conditions_inputs``' arguments, checked."""
    values = {
        "turf.slope": _checked_si("slope_deg", slope_deg),
        "turf.fall_line": _checked_si("fall_line_deg", fall_line_deg),
    }
    if dt_s is None:
        profile = conditions.get("wind_profile", DEFAULTS["wind_profile"])
        dt_s = default_of("models.dt", {"weather.wind_profile": profile})
    values["models.dt"] = check_range("dt_s", dt_s)
    values["turf.preset"] = resolve_turf(turf)
    flight, wind, density = _flight_values(**conditions)
    values.update(flight)
    # The turf's fields are the Turf's (its restitution as it is).
    return with_defaults(values, ("turf",)), wind, density


def conditions_inputs(
    turf=DEFAULTS["turf"],
    slope_deg=DEFAULTS["slope_deg"],
    fall_line_deg=DEFAULTS["fall_line_deg"],
    dt_s=None,
    **conditions,
):
    """The kernel's input columns that do not depend on the launch (turf, ground, air, wind,
    models, step), checked: {name of ``schema.INPUT_FIELDS``: float}. ``turf`` is a preset name
    or a Turf; ``conditions`` are the keyword arguments of ``flight_params``."""
    _check_keywords(conditions, _flight_values, _air_values)
    values, wind, density = _conditions_values(turf, slope_deg, fall_line_deg, dt_s, **conditions)
    return kernel_part(kernel_columns(values, wind, density))


def shot_inputs(
    *,
    ball_speed_mps=None,
    launch_angle_deg=None,
    spin_radps=None,
    azimuth_deg=DEFAULTS["azimuth_deg"],
    spin_axis_deg=DEFAULTS["spin_axis_deg"],
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
    _check_keywords(conditions, _conditions_values, _flight_values, _air_values)
    speed, angle_deg, spin = launch_conditions(
        ball_speed_mps, launch_angle_deg, spin_radps, club_speed_mps, club_mass_kg, loft_deg
    )
    values, wind, density = _conditions_values(
        **conditions,
    )
    values.update(
        {
            "launch.ball_speed": speed,
            "launch.launch_angle": angle_deg * DEG,
            "launch.spin": spin,
            "launch.azimuth": _checked_si("azimuth_deg", azimuth_deg),
            "launch.spin_axis": _checked_si("spin_axis_deg", spin_axis_deg),
        }
    )
    return pack(kernel_part(kernel_columns(values, wind, density)), 1), angle_deg


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
    if not isinstance(trajectory, bool | np.bool_):  # ("no" was true: a path traced)
        raise InputError(f"trajectory {trajectory!r}: allowed: True or False")
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
    positive): theta_c_deg, e, mu_c, mode, rebound speed, angle and spin, hop height. The
    turf's fields but its rolling resistance (``rho_g``, ``stimp_m``) may be overridden."""
    speed = check_range("ball_speed_mps", speed_mps)
    angle = check_range("impact_angle_deg", angle_deg) * DEG
    backspin = check_range("backspin_radps", backspin_radps)
    rolling = [k for k in ("rho_g", "stimp_m") if turf_overrides.get(k) is not None]
    if rolling:  # (taken, and without effect)
        raise InputError(f"{rolling[0]}: the roll's resistance, which one impact does not use "
                         "(simulate() rolls the ball)")  # fmt: skip
    turf = resolve_turf(turf, **turf_overrides)
    result = bounce_in_plane(speed, angle, backspin, turf)
    result["critical_backspin_radps"] = critical_backspin_radps(speed, angle, turf)
    return result
