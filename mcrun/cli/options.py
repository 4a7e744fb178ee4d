"""What the command modules share: option values read into SI, and the options of several
commands.

Values take an optional unit (``mcrun.units``: ``167mph``, ``2686rpm``, ``10.9`` degrees); a value
that cannot be read is an ``InputError`` or a ``UnitError`` naming the option. The conditions
options (turf, wind, air, step) are those of ``mcrun shot`` and ``mcrun replay``; ``--dpi`` is
that of ``mcrun plot``, ``mcrun report`` and ``mcrun paper``.
"""

import argparse
import inspect
import math

from mcrun import api, units
from mcrun.physics import aero, atmosphere, turf
from mcrun.quantities import RANGES, InputError

DPI_RANGE = (30, 600)


def api_default(func, name):
    """The default of ``func``'s keyword argument ``name``: the API is its one source."""
    return inspect.signature(func).parameters[name].default


# --- reading option values ---------------------------------------------------------------------


def quantity(text, kind, option):
    """SI value of an option with an optional unit, or None when the option was not given."""
    return None if text is None else units.parse_quantity(text, kind, option)


def _humidity(text):
    """--humidity as a share; a bare number over 1 that reads as a percentage (50) is refused
    saying how to write it (the range error said only [0, 1])."""
    if text is None:
        return None
    value, unit_given = units.read_quantity(text, "fraction", "--humidity")
    if not unit_given and 1.0 < value <= 100.0:
        raise InputError(f"--humidity {text}: allowed: a share from 0 to 1 (for {value:g} %, "
                         f"give {value / 100:g} or {value:g}%)")  # fmt: skip
    return value


def with_unit(text, kind, option, example):
    """SI value of an option whose unit must be given, where a bare number would be read in a
    unit its users do not quote it in (a Stimp reading in metres, a drive in metres):
    InputError naming the option and an ``example``."""
    try:
        bare = float(text)
    except ValueError:
        return units.parse_quantity(text, kind, option)
    if not math.isfinite(bare):  # ("inf" wants no unit: it is no length)
        return units.parse_quantity(text, kind, option)
    raise InputError(f"{option} {text}: give its unit, e.g. {example}")


def aero_model(text, option):
    """``text``, a name of ``aero.MODELS``; InputError naming the option otherwise."""
    if text not in aero.MODELS:
        raise InputError(f"{option} {text}: allowed: {', '.join(aero.MODELS)} (mcrun models "
                         "lists them)")  # fmt: skip
    return text


def from_si(value, kind, unit):
    """``value`` (SI) in ``unit``, or None when the option was not given."""
    return None if value is None else units.to_unit(value, kind, unit)


def degrees(text, option):
    """An angle option (bare number in degrees, or with ``deg``/``rad``) in degrees."""
    return from_si(quantity(text, "angle", option), "angle", "deg")


def number(text, option):
    """A plain dimensionless number (friction, scale factors, ...), or None when not given."""
    if text is None:
        return None
    foreign = units.foreign_digits(text)
    if foreign is not None:
        raise InputError(f"{option}: cannot read {text!r} as a number: {foreign}")
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"{option}: cannot read {text!r} as a number") from None
    if not math.isfinite(value):
        raise InputError(f"{option}: cannot read {text!r}: not a finite number")
    return value


def named(call, options, typed=None):
    """``call()``, an InputError that names an API value re-raised naming its option too; where
    ``typed`` ({API name: (text, kind)}) holds it as a bare number out of its range, and in the
    unit users quote (``units.QUOTED_UNITS``) in range, saying how to give that unit (``--spin
    8000`` is 8000 rad/s, and meant 8000 rpm)."""
    try:
        return call()
    except InputError as err:
        text = str(err)
        name = text.split(" ", 1)[0].removesuffix(":")
        if name not in options:
            raise
        hint = _quoted_unit_hint(name, *(typed or {}).get(name, (None, None)))
        raise InputError(f"{options[name]} ({name}){text[len(name) :]}{hint}") from None


def _quoted_unit_hint(name, text, kind):
    """`` (a bare number is rad/s: for 8000 rpm, give 8000rpm)`` where ``text``, a bare number
    read in ``kind``'s SI unit, is out of ``name``'s range and in it in a unit users quote
    (``units.meant_quoted``); else ""."""
    if text is None or name not in RANGES:
        return ""
    value, unit_given = units.read_quantity(text, kind, name)
    quoted = () if unit_given else units.meant_quoted(value, kind, *RANGES[name])
    return units.quoted_hint(text.strip(), kind, quoted, lambda typed, unit: f"{typed}{unit}")


def whole(text, option, least, most=None):
    """A whole number of at least ``least`` (and at most ``most``: ``2000``, ``1e4``);
    InputError naming the option."""
    value, why = units.whole_number(str(text).strip())  # (a text: read exactly)
    said = units.shown(str(text))  # (quoted, cut: 5,000 digits were said whole)
    if why:
        raise InputError(f"{option} {said}: {why}")
    top = 2**63 - 1 if most is None else most  # (an int64: what the kernels take)
    if value is None or not least <= value <= top:
        allowed = units.whole_numbers_allowed(least, most)
        raise InputError(f"{option} {said}: allowed: {allowed}")
    return value


def local_workers(text, option="--workers"):
    """The workers of a local Dask cluster from ``option`` (None when not given: the cores):
    a whole number from 1 to ``distributed.most_local_workers()``; InputError naming the
    option."""
    if text is None:
        return None
    from mcrun.run.distributed import check_local_workers

    value, why = units.whole_number(str(text).strip())  # (read as every whole number is)
    said = f"{option} {units.shown(str(text))}"
    if why:
        raise InputError(f"{said}: {why}")
    return check_local_workers(math.nan if value is None else value, said)


def given(**kwargs):
    """The keyword arguments that were given, so that the API's defaults apply to the rest."""
    return {k: v for k, v in kwargs.items() if v is not None}


# --- options several commands share ------------------------------------------------------------


def turf_from_args(args):
    """The turf preset named by ``--turf`` with the overrides given on the command line."""
    # A bare number is refused (5, meaning feet as Stimp readings are quoted, was 5 m).
    stimp_m = None if args.stimp is None else with_unit(args.stimp, "length", "--stimp", "10ft")
    if stimp_m is not None:  # named as given (the API names stimp_m, in m)
        lo, hi = api.RANGES["stimp_m"]
        if not lo <= stimp_m <= hi:
            ft = units.to_unit(1.0, "length", "ft")
            raise InputError(f"--stimp {args.stimp}: allowed: {lo * ft:.2g} ft to "
                             f"{hi * ft:.3g} ft (a Stimpmeter reading)")  # fmt: skip
    return api.resolve_turf(
        args.turf,
        **given(
            mu=number(args.mu, "--mu"),
            softness=number(args.softness, "--softness"),
            rho_g=number(args.rho_g, "--rho-g"),
            stimp_m=stimp_m,
            critical_height_m=quantity(args.critical_height, "length", "--critical-height"),
        ),
    )


def conditions_kwargs(args):
    """Keyword arguments of ``mcrun.api.simulate`` from ``add_conditions_options``' options."""
    wind = None if args.wind is None else units.parse_vector(args.wind, "speed", "--wind")
    profile = args.wind_profile
    if args.wind_param is not None and profile == "uniform":
        raise InputError("--wind-param: is for --wind-profile log or power (uniform has none)")
    if args.wind_height is not None and profile == "uniform":  # (ignored: the same numbers)
        raise InputError("--wind-height: is for --wind-profile log or power (a uniform wind is "
                         "the same at every height)")  # fmt: skip
    if args.air_density is not None and (args.altitude or args.pressure) is not None:
        given_air = "--altitude" if args.altitude is not None else "--pressure"
        raise InputError(f"{given_air}: the air's density is given (--air-density), which is "
                         "all the pressure sets: give one or the other")  # fmt: skip
    if profile == "log":  # the log law's parameter is a roughness length, e.g. 3cm
        wind_param = quantity(args.wind_param, "length", "--wind-param")
    else:  # the power law's is an exponent
        wind_param = number(args.wind_param, "--wind-param")
    return given(
        turf=turf_from_args(args),
        slope_deg=degrees(args.slope, "--slope"),
        fall_line_deg=degrees(args.fall_line, "--fall-line"),
        dt_s=number(args.dt, "--dt"),
        aero_model=aero_model(args.aero, "--aero"),
        cd_scale=number(args.cd_scale, "--cd-scale"),
        cl_scale=number(args.cl_scale, "--cl-scale"),
        wind_mps=wind,
        wind_profile=profile,
        wind_reference_height_m=quantity(args.wind_height, "length", "--wind-height"),
        wind_profile_parameter=wind_param,
        temperature_c=from_si(
            quantity(args.temperature, "temperature", "--temperature"), "temperature", "C"
        ),
        pressure_pa=quantity(args.pressure, "pressure", "--pressure"),
        altitude_m=quantity(args.altitude, "length", "--altitude"),
        relative_humidity=_humidity(args.humidity),
        air_density_kgpm3=number(args.air_density, "--air-density"),
    )


def add_conditions_options(p):
    """The options of everything but the launch (turf and ground, aerodynamics and wind, air,
    step), shared by ``mcrun shot`` and ``mcrun replay``; ``conditions_kwargs`` reads them."""
    sim = api.conditions_inputs
    fp = api.flight_params
    air = api.air_properties
    ground = p.add_argument_group("turf and ground")
    ground.add_argument(
        "--turf",
        metavar="NAME",
        default=api_default(sim, "turf"),
        help=f"turf preset: {', '.join(turf.PRESETS)} (default %(default)s; "
        f"{' and '.join(turf.ESTIMATED_PRESETS)} are estimates; see 'mcrun turfs')",
    )
    ground.add_argument("--mu", metavar="MU", help="override: ball-turf kinetic friction")
    ground.add_argument(
        "--softness", metavar="S", help="override: scale on the equivalent-surface tilt theta_c"
    )
    ground.add_argument("--rho-g", metavar="RHO", help="override: rolling resistance rho_g")
    ground.add_argument(
        "--stimp",
        metavar="LENGTH",
        help="override rho_g by a Stimpmeter reading, with its unit: 10ft",
    )
    ground.add_argument(
        "--critical-height",
        metavar="LENGTH",
        help="override: hop height below which the ball rolls, e.g. 5mm (bare: m)",
    )
    ground.add_argument(
        "--slope",
        metavar="ANGLE",
        help=f"ground slope (bare: deg; default {api_default(sim, 'slope_deg'):g})",
    )
    ground.add_argument(
        "--fall-line",
        metavar="ANGLE",
        help="downhill direction from the target line, positive to the right: 0 = downhill "
        f"towards the target, 180 = uphill (bare: deg; default "
        f"{api_default(sim, 'fall_line_deg'):g})",
    )
    flight = p.add_argument_group("aerodynamics and wind")
    flight.add_argument(
        "--aero",
        metavar="NAME",
        default=api_default(fp, "aero_model"),
        help=f"aerodynamic model: {', '.join(aero.MODELS)} (default %(default)s; "
        "see 'mcrun models')",
    )
    flight.add_argument(
        "--cd-scale",
        metavar="X",
        help=f"scale on the drag coefficient (default {api_default(fp, 'cd_scale'):g})",
    )
    flight.add_argument(
        "--cl-scale",
        metavar="X",
        help=f"scale on the lift coefficient (default {api_default(fp, 'cl_scale'):g})",
    )
    flight.add_argument(
        "--wind",
        metavar="X,Y",
        help="wind vector: X along the target line (positive = tailwind), Y positive = "
        "blowing to the right; e.g. 10mph,-3mph (bare: m/s; default 0,0)",
    )
    flight.add_argument(
        "--wind-profile",
        metavar="PROFILE",
        default=api_default(fp, "wind_profile"),
        help=f"wind height profile: {' | '.join(api.WIND_PROFILE_DEFAULTS)} (default %(default)s)",
    )
    flight.add_argument(
        "--wind-height",
        metavar="LENGTH",
        help="height at which --wind is given (bare: m; default "
        f"{api.DEFAULTS['wind_reference_height_m']:g})",
    )
    flight.add_argument(
        "--wind-param",
        metavar="VALUE",
        help="profile parameter: log law roughness length z0 (bare: m; default "
        f"{api.WIND_PROFILE_DEFAULTS['log']:g}), power law exponent (default "
        f"{api.WIND_PROFILE_DEFAULTS['power']:.4g})",
    )
    weather = p.add_argument_group("air")
    weather.add_argument(
        "--temperature",
        metavar="T",
        help=f"air temperature (bare: Celsius; default {api_default(air, 'temperature_c'):g})",
    )
    weather.add_argument(
        "--pressure",
        metavar="P",
        help=f"air pressure (bare: Pa; default {atmosphere.STANDARD_PRESSURE_PA:g})",
    )
    weather.add_argument(
        "--altitude",
        metavar="LENGTH",
        help="altitude, sets the standard pressure there (bare: m; not with --pressure)",
    )
    weather.add_argument(
        "--humidity",
        metavar="RH",
        help=f"relative humidity, 0.5 or 50%% (default {api_default(air, 'relative_humidity'):g})",
    )
    weather.add_argument(
        "--air-density",
        metavar="RHO",
        help="air density in kg/m^3, overrides the one from temperature, pressure, humidity",
    )
    p.add_argument_group("numerics").add_argument(
        "--dt",
        metavar="SECONDS",
        help="flight step in s (default 0.2 in uniform wind, 0.02 with a wind profile)",
    )


def dpi_value(text):
    """argparse type of --dpi: a whole number within DPI_RANGE."""
    value, why = units.whole_number(text.strip())  # (int() read ٧٢ as 72)
    said = units.shown(text)  # (quoted, cut)
    if why:
        raise argparse.ArgumentTypeError(f"{said}: {why}")
    if value is None:
        raise argparse.ArgumentTypeError(f"cannot read {said} as a whole number")
    lo, hi = DPI_RANGE
    if not lo <= value <= hi:
        shown_value = value if abs(value) < 10**20 else said  # (1e400: its 401 digits)
        raise argparse.ArgumentTypeError(f"{shown_value} is outside [{lo}, {hi}]")
    return value
