"""The inputs of a shot, once: the error a user's input raises, and one table of the quantities a
user gives (``QUANTITIES``), read by the one-shot API (``mcrun.api``), the scenario reader
(``mcrun.run.scenario``), the sampler (``mcrun.run.sampling``) and the run's plan.

Each row names a quantity as the user sees it (``column``: the keyword argument of
``mcrun.api.simulate``, the range's name in ``RANGES``, the sampled column of a run, units in
the name), its kind (a ``mcrun.units`` kind, "number" for a dimensionless value, "choice" for a
name), its allowed range in the column's unit, its key paths in a scenario file
(``"turf.mu"``), its default (SI, or a function of the names chosen, e.g. the turf preset's
field) and the kernel column (``mcrun.engine.schema.INPUT_FIELDS``) it fills as it is, SI.
``kernel_columns`` turns the SI values of a shot (or of a block of shots, as arrays) into the
kernel's columns and the sampled columns: the single shot and the runs share it, so that a
scenario of constants gives exactly the kernel inputs of ``mcrun.api.simulate``.

Adding a quantity that the kernel reads as it is: one row here (a kernel column of that name in
``schema.INPUT_FIELDS``, and its physics); its name in ``SAMPLED_ORDER`` places its column in a
run's table.
"""

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from mcrun.engine.schema import INPUT_FIELDS
from mcrun.engine.shot import default_dt_s
from mcrun.errors import InputError
from mcrun.physics import aero, atmosphere
from mcrun.physics.constants import (
    DEG,
    STANDARD_HUMIDITY,
    STANDARD_PRESSURE_PA,
    STANDARD_TEMPERATURE_K,
    STANDARD_WIND_HEIGHT_M,
)
from mcrun.physics.flight import WIND_PROFILES, wind_factor
from mcrun.physics.launch import DEFAULT_CLUB_MASS_KG, launch_from_club
from mcrun.physics.turf import LIMITS as TURF_LIMITS
from mcrun.physics.turf import PRESETS, rho_g_from_stimp
from mcrun.units import KINDS, shown

__all__ = [
    "BOUNCE_MODELS",
    "DEFAULTS",
    "DRIVER_COLUMNS",
    "QUANTITIES",
    "RANGES",
    "SAMPLED_ORDER",
    "SECTIONS",
    "WIND_PROFILE_DEFAULTS",
    "InputError",
    "Quantity",
    "air",
    "by_column",
    "by_path",
    "check_range",
    "club_launch",
    "column_and_factor",
    "default_of",
    "finite_number",
    "from_si",
    "kernel_columns",
    "kernel_part",
    "to_si",
    "with_defaults",
]


# Default parameter of each wind profile: roughness length z0 (m) of the log law over short
# grass, and the 1/7 exponent of the power law.
WIND_PROFILE_DEFAULTS = {"uniform": 0.0, "log": 0.03, "power": 1.0 / 7.0}
# A wind profile may raise the wind at the height of a high drive's apex (WIND_CHECK_HEIGHT_M)
# to at most this many times the wind at its reference height. The atmosphere's profiles stay
# well within it: from a 10 m reference, 2.6 times for a power law's steepest exponent (0.6, a
# very stable night) and 2.0 for a log law over a forest's roughness (2 m); from a handheld 2 m
# reading, 1.6 for the 1/7 law and 2.7 for a log law over 0.3 m. A profile from a reference
# height within a roughness length's reach (a log law from 10 m over 9.9 m: 161 times), or a
# power law of exponent 1 from 0.1 m (500 times), flew a 5 m/s wind at hundreds of metres a
# second and reported the shots as ok.
MAX_WIND_FACTOR = 4.0
WIND_CHECK_HEIGHT_M = 50.0

BOUNCE_MODELS = ("penner2002",)


def _factor(kind):
    """(factor, offset) of the kind's bare unit: SI = value * factor + offset."""
    if kind in ("number", "choice"):
        return 1.0, 0.0
    return KINDS[kind][1][KINDS[kind][0]]


def wind_profile_problem(profile, reference_m, parameter):
    """Why a wind profile (its name, reference height in m and parameter) is refused, or None:
    the log law's roughness length must be > 0 and below the reference height, the power law's
    exponent within [0, 1], and neither may raise the wind at WIND_CHECK_HEIGHT_M above
    MAX_WIND_FACTOR times the reference wind."""
    if profile == "log" and not 0.0 < parameter < reference_m:
        return (f"the log profile's roughness length must be > 0 and below the reference height "
                f"({reference_m:g} m), got {parameter:g} m")  # fmt: skip
    if profile == "power" and not 0.0 <= parameter <= 1.0:
        return f"the power profile's exponent must be within [0, 1], got {parameter:g}"
    factor = wind_factor.py_func(WIND_CHECK_HEIGHT_M, WIND_PROFILES[profile], reference_m,
                                 parameter)  # fmt: skip
    if factor > MAX_WIND_FACTOR:
        what = (
            f"a roughness length of {parameter:g} m"
            if profile == "log"
            else (f"an exponent of {parameter:g}")
        )
        return (f"the {profile} profile with {what} from a reference height "
                f"of {reference_m:g} m makes the wind at {WIND_CHECK_HEIGHT_M:g} m "
                f"{factor:.3g} times the reference wind; allowed: at most {MAX_WIND_FACTOR:g} "
                "(a reference height of 2-10 m, a roughness length of 0.0002-2 m, an "
                "exponent of 0.06-0.6)")  # fmt: skip
    return None


def to_si(value, kind):
    """A value in the kind's bare unit (deg, C, ...) in SI."""
    factor, offset = _factor(kind)
    if factor != 1.0:
        value = value * factor
    if offset:
        value = value + offset
    return value


def from_si(value, kind):
    """An SI value (a float or an array) in the kind's bare unit."""
    factor, offset = _factor(kind)
    if offset:
        value = value - offset
    if factor != 1.0:
        value = value / factor
    return value


def _preset(field):
    """The default of a turf field: the chosen preset's (a name, or a Turf)."""

    def default(chosen):
        preset = chosen["turf.preset"]
        return getattr(PRESETS[preset] if isinstance(preset, str) else preset, field)

    return default


def _by_profile(table):
    """A default that depends on the chosen wind profile."""
    return lambda chosen: table(chosen["weather.wind_profile"])


@dataclass(frozen=True)
class Quantity:
    """One quantity a user gives: see the module's docstring."""

    column: str
    kind: str
    range: tuple[float, float] | None = None
    paths: tuple[str, ...] = ()
    default: object = None
    kernel: str | None = None
    choices: tuple[str, ...] = ()
    constant_only: bool = False
    # An alternative (the club delivery, the altitude, the Stimp reading): its column is in a
    # run's table only when a point gives it.
    optional: bool = False
    # Why a bare number is refused, where it would be read in SI and mean something else to a
    # user ("" where a bare number is read in the kind's bare unit).
    bare_refused: str = ""

    @property
    def limits(self):
        """The range in SI (deg -> rad, C -> K), as the scenario checks it."""
        if self.range is None:
            return None
        return tuple(to_si(float(v), self.kind) for v in self.range)

    def default_si(self, chosen=None):
        """The default, SI (or a name for a choice): None when the quantity has none."""
        if callable(self.default):
            return self.default(chosen or {})
        return self.default

    def default_shown(self):
        """The default in the column's unit (or a name): what the API's signature shows."""
        value = self.default_si()
        return value if self.kind == "choice" or value is None else from_si(value, self.kind)


# In a scenario's order (the sections, and their keys in each): the club's azimuth and spin
# axis come after its speed, mass and loft; the ball's after its spin.
QUANTITIES = (
    # The ball launch, as a launch monitor reports it (angles positive to the right).
    Quantity("ball_speed_mps", "speed", (0.5, 120.0), ("launch.ball_speed",)),
    Quantity("launch_angle_deg", "angle", (-20.0, 89.0), ("launch.launch_angle",)),
    Quantity("spin_radps", "spin", (0.0, 2000.0), ("launch.spin",)),
    # The club delivery (Penner 2001), instead of the ball launch.
    Quantity("club_speed_mps", "speed", (1.0, 90.0), ("club.speed",), optional=True),
    Quantity(
        "club_mass_kg", "mass", (0.05, 1.0), ("club.mass",), DEFAULT_CLUB_MASS_KG, optional=True
    ),
    Quantity("loft_deg", "angle", (0.0, 70.0), ("club.loft",), optional=True),
    Quantity("azimuth_deg", "angle", (-60.0, 60.0), ("launch.azimuth", "club.azimuth"), 0.0),
    Quantity(
        "spin_axis_deg",
        "angle",
        (-90.0, 90.0),
        ("launch.spin_axis", "club.spin_axis"),
        0.0,
    ),
    # The turf (mcrun.physics.turf: its limits, check_turf's) and the ground's plane.
    Quantity("turf", "choice", None, ("turf.preset",), "green", choices=tuple(PRESETS)),
    Quantity("mu", "number", TURF_LIMITS["mu"], ("turf.mu",), _preset("mu"), "mu"),
    Quantity(
        "softness",
        "number",
        TURF_LIMITS["softness"],
        ("turf.softness",),
        _preset("softness"),
        "softness",
    ),
    # Scales e0, e1, e2 and e_high; above 1.9 the paper's e0 = 0.510 would exceed 0.97.
    Quantity("restitution", "number", (0.0, 1.9), ("turf.restitution",), 1.0),
    Quantity("rho_g", "number", TURF_LIMITS["rho_g"], ("turf.rho_g",), _preset("rho_g")),
    Quantity(  # or rho_g
        "stimp_m",
        "length",
        (0.1, 6.0),
        ("turf.stimp",),
        optional=True,
        bare_refused='give its unit, e.g. "10 ft" (a Stimp reading is quoted in feet; a bare '
        "number would be read in metres)",
    ),
    Quantity(
        "critical_height_m",
        "length",
        TURF_LIMITS["critical_height_m"],
        ("turf.critical_height",),
        _preset("critical_height_m"),
        "critical_height_m",
    ),
    Quantity("slope_deg", "angle", (0.0, 45.0), ("turf.slope",), 0.0, "slope_rad"),
    Quantity("fall_line_deg", "angle", (-360.0, 360.0), ("turf.fall_line",), 0.0, "fall_line_rad"),
    # The weather: wind (the direction it blows towards: 0 tailwind, 90 deg left to right) and
    # air.
    Quantity("wind_speed_mps", "speed", (0.0, 50.0), ("weather.wind_speed",), 0.0),
    Quantity("wind_direction_deg", "angle", (-360.0, 360.0), ("weather.wind_direction",), 0.0),
    Quantity(
        "wind_profile",
        "choice",
        None,
        ("weather.wind_profile",),
        "uniform",
        choices=tuple(WIND_PROFILES),
    ),
    Quantity(
        "wind_reference_height_m",
        "length",
        (0.1, 100.0),
        ("weather.wind_reference_height",),
        STANDARD_WIND_HEIGHT_M,
        "wind_reference_height_m",
        constant_only=True,
    ),
    Quantity(
        "wind_profile_parameter",
        "number",
        (0.0, 100.0),
        ("weather.wind_profile_parameter",),
        _by_profile(WIND_PROFILE_DEFAULTS.get),
        "wind_profile_parameter",
        constant_only=True,
    ),
    Quantity(
        "temperature_c",
        "temperature",
        (-40.0, 55.0),
        ("weather.temperature",),
        STANDARD_TEMPERATURE_K,
    ),  # fmt: skip
    Quantity("altitude_m", "length", (-500.0, 5000.0), ("weather.altitude",), optional=True),
    Quantity(
        "pressure_pa",
        "pressure",
        (50000.0, 110000.0),
        ("weather.pressure",),
        STANDARD_PRESSURE_PA,
    ),  # fmt: skip
    Quantity("relative_humidity", "fraction", (0.0, 1.0), ("weather.humidity",), STANDARD_HUMIDITY),
    # The models and the step.
    Quantity(
        "aero_model",
        "choice",
        None,
        ("models.aero",),
        aero.DEFAULT_MODEL,
        choices=tuple(aero.MODELS),
    ),
    Quantity(
        "bounce_model", "choice", None, ("models.bounce",), "penner2002", choices=BOUNCE_MODELS
    ),
    Quantity("cd_scale", "number", (0.0, 3.0), ("models.cd_scale",), 1.0, "cd_scale"),
    Quantity("cl_scale", "number", (0.0, 3.0), ("models.cl_scale",), 1.0, "cl_scale"),
    Quantity(
        "dt_s",
        "time",
        (1e-4, 0.25),
        ("models.dt",),
        _by_profile(default_dt_s),
        "dt_s",
        constant_only=True,
    ),
    # Of the one-shot API only: an air density that overrides the weather's, and one impact
    # (``bounce_once``): angle from the vertical, backspin positive (topspin negative).
    Quantity("air_density_kgpm3", "number", (0.5, 1.5)),
    Quantity("impact_angle_deg", "angle", (0.0, 89.9)),
    Quantity("backspin_radps", "spin", (-2000.0, 2000.0)),
)

SECTIONS = ("launch", "club", "turf", "weather", "models")

# The sampled columns of a run, in their order in its table: the quantities' columns and those
# derived from them (the wind's components, the air's density and viscosity), and the row of a
# resampled launch file. ``mcrun.run.sampling.sampled_columns`` keeps those a run has.
SAMPLED_ORDER = (
    "ball_speed_mps",
    "launch_angle_deg",
    "azimuth_deg",
    "spin_radps",
    "spin_axis_deg",
    "club_speed_mps",
    "club_mass_kg",
    "loft_deg",
    "source_row",
    "wind_speed_mps",
    "wind_direction_deg",
    "wind_x_mps",
    "wind_right_mps",
    "wind_reference_height_m",
    "wind_profile_parameter",
    "temperature_c",
    "pressure_pa",
    "altitude_m",
    "relative_humidity",
    "air_density_kgpm3",
    "kinematic_viscosity_m2ps",
    "mu",
    "softness",
    "restitution",
    "rho_g",
    "stimp_m",
    "critical_height_m",
    "slope_deg",
    "fall_line_deg",
    "cd_scale",
    "cl_scale",
    "dt_s",
)

_BY_COLUMN = {q.column: q for q in QUANTITIES}
_BY_PATH = {path: q for q in QUANTITIES for path in q.paths}

# The defaults that do not depend on a choice, in the units of the argument names (the
# signatures of ``mcrun.api``).
DEFAULTS = {
    q.column: q.default_shown()
    for q in QUANTITIES
    if q.default is not None and not callable(q.default)
}

# Documented input ranges (inclusive), in the units of the argument names.
RANGES = {q.column: q.range for q in QUANTITIES if q.range is not None}

# The sampled column of each quantity a user can give a distribution (scenario key paths): the
# candidate drivers of the variance. Derived columns (the ball launch of a club delivery, the
# air density, the wind components) are not candidates: their quantities are.
DRIVER_COLUMNS = {
    path: q.column
    for section in SECTIONS
    for q in QUANTITIES
    if q.kind != "choice" and not q.constant_only
    for path in q.paths
    if path.partition(".")[0] == section
}


def by_column(column):
    """The Quantity of a column (``"mu"``, ``"temperature_c"``)."""
    return _BY_COLUMN[column]


def by_path(path):
    """The Quantity of a scenario key path (``"turf.mu"``)."""
    return _BY_PATH[path]


def column_and_factor(path):
    """(sampled column, factor from SI to its unit) of a scenario key path whose unit is a
    scale of SI (not a temperature): ``launch.launch_angle`` -> ``("launch_angle_deg", 1 / DEG)``.
    """
    q = _BY_PATH[path]
    factor, offset = _factor(q.kind)
    if offset:
        raise ValueError(f"{path}: its unit {KINDS[q.kind][0]} is not a scale of SI")
    return q.column, 1.0 / factor


def default_of(path, chosen=None):
    """The default of a scenario key path, SI (or a name), given the names ``chosen`` so far
    ({key path: name}: the turf preset, the wind profile); None when it has none."""
    return _BY_PATH[path].default_si(chosen)


def finite_number(name, value):
    """``value`` as a float, or raise InputError naming ``name`` unless it is a finite number
    (a bool is not: ``float(True)`` is 1; nor is text: ``float("70")`` reads 70 where "70
    m/s" is refused; a value in the unit its name carries is passed as a number)."""
    if isinstance(value, bool | np.bool_ | str | bytes | np.str_):
        raise InputError(f"{name} must be a number, got {shown(value)}")
    try:
        value = float(value)
    except OverflowError:  # (an int beyond a float: 10**400)
        raise InputError(f"{name} must be finite, got {shown(value, 40)}") from None
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {shown(value)}") from None
    if not math.isfinite(value):
        raise InputError(f"{name} must be finite, got {value}")
    return value


def check_range(name, value):
    """Return ``value`` as a float, or raise InputError naming ``name`` and its allowed range."""
    lo, hi = RANGES[name]
    value = finite_number(name, value)
    if not lo <= value <= hi:
        raise InputError(f"{name} = {value:g} is outside the allowed range [{lo:g}, {hi:g}]")
    return value


# --- the conversions, shared by the single shot and the runs ----------------------------------


@njit(cache=True)
def _launch_from_club_array(club_speed, club_mass, loft):
    n = club_speed.shape[0]
    speed = np.empty(n)
    angle = np.empty(n)
    spin = np.empty(n)
    for k in range(n):
        speed[k], angle[k], spin[k] = launch_from_club(club_speed[k], club_mass[k], loft[k])
    return speed, angle, spin


def _scalar(*values):
    return all(isinstance(v, float) for v in values)


def _rho_g_of_stimp(stimp_m):
    """rho_g of a Stimp reading (m), of a float or an array: a drawn reading of 0 or less (out
    of its limits, so that its shot is refused as invalid_input) gives NaN, not an error."""
    if _scalar(stimp_m):
        return rho_g_from_stimp(stimp_m)
    positive = stimp_m > 0.0
    return np.where(positive, rho_g_from_stimp(np.where(positive, stimp_m, 1.0)), np.nan)


def club_launch(club_speed, club_mass, loft):
    """(ball speed m/s, launch angle deg, spin rad/s) of a club delivery (SI, loft in rad;
    Penner 2001), of floats or arrays: the launch angle as the API reports it, in degrees."""
    if _scalar(club_speed, club_mass, loft):
        speed, angle, spin = launch_from_club(club_speed, club_mass, loft)
        return speed, angle / DEG, spin
    n = max(np.size(v) for v in (club_speed, club_mass, loft))
    arrays = [np.broadcast_to(np.asarray(v, dtype=float), (n,)).copy() for v in (
        club_speed, club_mass, loft)]  # fmt: skip
    speed, angle, spin = _launch_from_club_array(*arrays)
    return speed, angle / DEG, spin


def air(values, density=None):
    """(pressure Pa, density kg/m^3, kinematic viscosity m^2/s) of the weather's SI ``values``
    by key path (``mcrun.physics.atmosphere``): ``weather.altitude`` replaces
    ``weather.pressure``; an explicit ``density`` wins."""
    t_k, humidity = values["weather.temperature"], values["weather.humidity"]
    if "weather.altitude" in values:
        pressure = atmosphere.pressure_at_altitude_pa(values["weather.altitude"])
    else:
        pressure = values["weather.pressure"]
    if density is not None:
        rho = density
    elif _scalar(t_k, humidity) and np.ndim(pressure) == 0:
        rho = atmosphere.air_density_kgpm3(t_k, float(pressure), humidity)
    else:
        rho = atmosphere.air_density_kgpm3(t_k, pressure, humidity)
    return pressure, rho, atmosphere.kinematic_viscosity_m2ps(t_k, rho)


def with_defaults(values, sections=SECTIONS):
    """``values`` ({key path: SI value or name}) with the defaults of the quantities of
    ``sections`` that it lacks, in the table's order (a turf field's after the preset, the
    step's after the wind profile). A quantity without a default (an alternative) stays out."""
    for q in QUANTITIES:
        for path in q.paths:
            if path not in values and path.partition(".")[0] in sections:
                default = q.default_si(values)
                if default is not None:
                    values[path] = default
    return values


def kernel_columns(values, wind=None, air_density=None):
    """The kernel's columns and the sampled columns of a shot, or of a block of shots.

    Parameters
    ----------
    values : dict of str -> float, array or name
        SI values by scenario key path (``"turf.mu"``), defaults filled in, and the names chosen
        (``"turf.preset"`` a preset's name or a Turf, ``"weather.wind_profile"``,
        ``"models.aero"``). The launch: ``launch.*``, or ``club.*`` (a club delivery).
        ``weather.altitude`` replaces ``weather.pressure``, ``turf.stimp`` ``turf.rho_g``.
    wind : (float, float), optional
        The wind's components (along the line, to the right), m/s, instead of
        ``weather.wind_speed`` and ``weather.wind_direction``.
    air_density : float, optional
        kg/m^3, instead of the weather's.

    Returns
    -------
    dict of str -> float or array
        ``schema.INPUT_FIELDS`` (``kernel_part`` keeps these) and the sampled columns that the
        values give (``SAMPLED_ORDER``); the derived ones are computed once, for both.
    """
    v = values
    out = {}
    for q in QUANTITIES:  # the quantities' own columns, and those the kernel reads as they are
        for path in q.paths:
            if path in v and q.kind != "choice":
                out[q.column] = from_si(v[path], q.kind)
                if q.kernel is not None:
                    out[q.kernel] = v[path]
    # The launch: a club delivery's goes through degrees, as the API reports its angle.
    if "club.speed" in v:
        speed, angle_deg, spin = club_launch(v["club.speed"], v["club.mass"], v["club.loft"])
        launch = (speed, angle_deg * DEG, spin, v["club.azimuth"], v["club.spin_axis"])
    elif "launch.ball_speed" in v:
        launch = tuple(
            v[f"launch.{n}"] for n in ("ball_speed", "launch_angle", "spin", "azimuth", "spin_axis")
        )
    else:
        launch = None  # the conditions alone
    if launch is not None:
        speed, angle, spin, azimuth, spin_axis = launch
        out.update(
            ball_speed_mps=speed,
            launch_angle_rad=angle,
            azimuth_rad=azimuth,
            spin_radps=spin,
            spin_axis_rad=spin_axis,
            launch_angle_deg=angle / DEG,
            azimuth_deg=azimuth / DEG,
            spin_axis_deg=spin_axis / DEG,
        )

    # The air and the wind.
    pressure, rho, nu = air(v, air_density)
    out.update(pressure_pa=pressure, air_density_kgpm3=rho, kinematic_viscosity_m2ps=nu)

    if wind is not None:
        wind_x, wind_right = wind
    else:
        wind_speed, direction = v["weather.wind_speed"], v["weather.wind_direction"]
        if _scalar(wind_speed, direction):
            wind_x = wind_speed * math.cos(direction)
            wind_right = wind_speed * math.sin(direction)
        else:
            wind_x = wind_speed * np.cos(direction)
            wind_right = wind_speed * np.sin(direction)
    out.update(wind_x_mps=wind_x, wind_right_mps=wind_right)

    # The turf: the preset's restitution scaled; a Stimp reading gives rho_g.
    preset = v["turf.preset"]
    preset = PRESETS[preset] if isinstance(preset, str) else preset
    scale = v["turf.restitution"]
    rho_g = _rho_g_of_stimp(v["turf.stimp"]) if "turf.stimp" in v else v["turf.rho_g"]
    out.update(
        e0=preset.e0 * scale,
        e1=preset.e1 * scale,
        e2=preset.e2 * scale,
        e_break_speed_mps=preset.e_break_speed_mps,
        e_high=preset.e_high * scale,
        rho_g=rho_g,
        aero_model=float(aero.MODELS[v["models.aero"]]),
        wind_profile=float(WIND_PROFILES[v["weather.wind_profile"]]),
    )
    return out


def kernel_part(columns):
    """The kernel's columns of ``kernel_columns``' answer, in their order, for ``schema.pack``."""
    return {name: columns[name] for name in INPUT_FIELDS if name in columns}
