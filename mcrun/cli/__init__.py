"""The command line: ``mcrun shot``, ``mcrun bounce``, ``mcrun models`` and ``mcrun turfs``.

A thin edge over ``mcrun.api``: options are read into SI with ``mcrun.units`` (so ``167mph``,
``2686rpm`` and ``10.9`` degrees all work), handed to the API, which checks every range, and the
result is printed as an aligned table or as one JSON object. A mistake the user can make ends with
one line, ``mcrun: error: <message>``, on stderr and exit code 2; anything else is a bug and raises.
"""

import argparse
import importlib
import inspect
import json
import math
import os
import re
import sys
import textwrap
import time

from mcrun import api, exits, status, units
from mcrun.api import InputError
from mcrun.physics import aero, atmosphere, turf
from mcrun.units import UnitError


class CommandError(ValueError):
    """A mistake on the command line that neither the API nor the unit reader catches (an
    unwritable output file, a command that cannot be loaded); one line meant for the user."""


def _api_default(func, name):
    """The default of ``func``'s keyword argument ``name``: the API is its one source."""
    return inspect.signature(func).parameters[name].default


# --- reading option values ---------------------------------------------------------------------


def _quantity(text, kind, option):
    """SI value of an option with an optional unit, or None when the option was not given."""
    return None if text is None else units.parse_quantity(text, kind, option)


def _from_si(value, kind, unit):
    """``value`` (SI) in ``unit``, or None when the option was not given."""
    return None if value is None else units.to_unit(value, kind, unit)


def _degrees(text, option):
    """An angle option (bare number in degrees, or with ``deg``/``rad``) in degrees."""
    return _from_si(_quantity(text, "angle", option), "angle", "deg")


def _number(text, option):
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


def _given(**kwargs):
    """The keyword arguments that were given, so that the API's defaults apply to the rest."""
    return {k: v for k, v in kwargs.items() if v is not None}


# A value with a leading minus and a unit or a comma (``-3mph,2mph``, ``-2.5deg``) looks like an
# option to argparse; plain negative numbers (``-5``, ``-2.5``) it already reads as values.
_NEGATIVE_VALUE = re.compile(r"-\.?\d")
_NEGATIVE_NUMBER = re.compile(r"-\d+|-\d*\.\d+")


def _attach_negative_values(argv):
    """Rewrite ``--opt -3mph,2mph`` as ``--opt=-3mph,2mph`` so that argparse reads the value."""
    out = []
    for token in argv:
        previous = out[-1] if out else ""
        if (
            previous.startswith("--")
            and "=" not in previous
            and _NEGATIVE_VALUE.match(token)
            and not _NEGATIVE_NUMBER.fullmatch(token)
        ):
            out[-1] = f"{previous}={token}"
        else:
            out.append(token)
    return out


# --- printing ----------------------------------------------------------------------------------

# Golf units shown beside SI values in tables, by kind of the field's unit suffix.
_TABLE_UNITS = {"length": "yd", "speed": "mph", "spin": "rpm"}


def _format(value, spec=".3f"):
    if isinstance(value, bool) or not isinstance(value, float):
        return str(value)
    return format(value + 0.0, spec)  # + 0.0: no "-0.000" for a lateral -0.0


def _golf_units(name, value):
    """``(281.7 yd)`` beside ``carry_m``; empty where there is no unit to convert."""
    parsed = units.from_column_name(name)
    if parsed is None or not isinstance(value, float) or not math.isfinite(value):
        return ""
    _, kind, unit = parsed
    shown = _TABLE_UNITS.get(kind)
    if shown is None or shown == unit:
        return ""
    factor, offset = units.KINDS[kind][1][unit]
    converted = units.to_unit(value * factor + offset, kind, shown)
    digits = 0 if kind == "spin" else 1
    return f"({converted:.{digits}f} {shown})"


def _print_table(rows):
    """Print ``(name, value)`` rows as an aligned table: name, value, value in golf units."""
    cells = [(name, _format(value), _golf_units(name, value)) for name, value in rows]
    w_name = max(len(c[0]) for c in cells)
    w_value = max(len(c[1]) for c in cells)
    for name, value, extra in cells:
        print(f"{name:<{w_name}}  {value:>{w_value}}  {extra}".rstrip())


def _json_value(value):
    """JSON has no NaN: a field the shot did not reach is null."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _print_json(mapping):
    print(json.dumps({k: _json_value(v) for k, v in mapping.items()}, allow_nan=False))


def _not_stopped_reason(slope_deg, rho_g):
    """Why a ball may still roll at the roll's bounds, for the ground it rolled on."""
    bounds = f"still rolling after {status.MAX_ROLL_TIME_S:g} s or {status.MAX_ROLL_DISTANCE_M:g} m"
    if slope_deg > 0.0 and math.tan(math.radians(slope_deg)) > rho_g:
        return (
            f"{bounds} (on a slope of {slope_deg:g} deg, steeper than atan(rho_g) = "
            f"{math.degrees(math.atan(rho_g)):.2g} deg, the ball never stops)"
        )
    if slope_deg == 0.0 and rho_g == 0.0:
        return (
            f"{bounds} (with no rolling resistance, rho_g 0, a ball on level ground never "
            "stops rolling)"
        )
    return bounds


def _status_note(code, slope_deg=0.0, rho_g=None):
    """Why a shot ended with a non-OK status, in one line (``slope_deg`` and ``rho_g``: the
    ground the ball rolled on)."""
    reasons = {
        status.INVALID_INPUT: "a non-finite or out-of-range input reached the kernel",
        status.NOT_LANDED: f"still in the air after {status.MAX_FLIGHT_TIME_S:g} s",
        status.TOO_MANY_BOUNCES: f"still bouncing after {status.MAX_BOUNCES} bounces",
        status.NOT_STOPPED: _not_stopped_reason(slope_deg, math.inf if rho_g is None else rho_g),
    }
    name = status.NAMES.get(code, str(code))
    reason = reasons.get(code)
    return f"the shot ended with status {name}" + (f": {reason}" if reason else "")


# --- commands ----------------------------------------------------------------------------------


def _turf_from_args(args):
    """The turf preset named by ``--turf`` with the overrides given on the command line."""
    return api.resolve_turf(
        args.turf,
        **_given(
            mu=_number(args.mu, "--mu"),
            softness=_number(args.softness, "--softness"),
            rho_g=_number(args.rho_g, "--rho-g"),
            stimp_m=_quantity(args.stimp, "length", "--stimp"),
            critical_height_m=_quantity(args.critical_height, "length", "--critical-height"),
        ),
    )


def conditions_kwargs(args):
    """Keyword arguments of ``mcrun.api.simulate`` from ``add_conditions_options``' options."""
    wind = None if args.wind is None else units.parse_vector(args.wind, "speed", "--wind")
    profile = args.wind_profile
    if profile == "log":  # the log law's parameter is a roughness length, e.g. 3cm
        wind_param = _quantity(args.wind_param, "length", "--wind-param")
    else:  # the power law's is an exponent
        wind_param = _number(args.wind_param, "--wind-param")
    return _given(
        turf=_turf_from_args(args),
        slope_deg=_degrees(args.slope, "--slope"),
        fall_line_deg=_degrees(args.fall_line, "--fall-line"),
        dt_s=_number(args.dt, "--dt"),
        aero_model=args.aero,
        cd_scale=_number(args.cd_scale, "--cd-scale"),
        cl_scale=_number(args.cl_scale, "--cl-scale"),
        wind_mps=wind,
        wind_profile=profile,
        wind_reference_height_m=_quantity(args.wind_height, "length", "--wind-height"),
        wind_profile_parameter=wind_param,
        temperature_c=_from_si(
            _quantity(args.temperature, "temperature", "--temperature"), "temperature", "C"
        ),
        pressure_pa=_quantity(args.pressure, "pressure", "--pressure"),
        altitude_m=_quantity(args.altitude, "length", "--altitude"),
        relative_humidity=_quantity(args.humidity, "fraction", "--humidity"),
        air_density_kgpm3=_number(args.air_density, "--air-density"),
    )


def _shot_kwargs(args):
    """Keyword arguments of ``mcrun.api.simulate`` from the ``shot`` options."""
    return _given(
        ball_speed_mps=_quantity(args.ball_speed, "speed", "--ball-speed"),
        launch_angle_deg=_degrees(args.launch, "--launch"),
        spin_radps=_quantity(args.spin, "spin", "--spin"),
        azimuth_deg=_degrees(args.azimuth, "--azimuth"),
        spin_axis_deg=_degrees(args.spin_axis, "--spin-axis"),
        club_speed_mps=_quantity(args.club_speed, "speed", "--club-speed"),
        club_mass_kg=_quantity(args.club_mass, "mass", "--club-mass"),
        loft_deg=_degrees(args.loft, "--loft"),
    ) | conditions_kwargs(args)


def _run_shot(args):
    kwargs = _shot_kwargs(args)
    result = api.simulate(trajectory=args.trajectory is not None, **kwargs)
    if args.trajectory is not None:
        try:
            result.trajectory.to_csv(args.trajectory, index=False)
        except OSError as err:
            reason = err.strerror or str(err)
            raise CommandError(f"--trajectory: cannot write {args.trajectory}: {reason}") from None
    outcome = dict(result.outcome)
    outcome["status_name"] = result.status_name
    if args.json:
        _print_json(outcome)
    else:
        rows = [(k, v) for k, v in outcome.items() if k not in ("status", "status_name")]
        _print_table([*rows, ("status", outcome["status_name"])])
    if outcome["status"] != status.OK:
        ground = {"slope_deg": kwargs.get("slope_deg", 0.0), "rho_g": kwargs["turf"].rho_g}
        print(f"mcrun: warning: {_status_note(outcome['status'], **ground)}", file=sys.stderr)
    return 0


def _run_bounce(args):
    speed = _quantity(args.speed, "speed", "--speed")
    angle = _degrees(args.angle, "--angle")
    spin = _quantity(args.spin, "spin", "--spin")
    overrides = _given(mu=_number(args.mu, "--mu"), softness=_number(args.softness, "--softness"))
    result = api.bounce_once(speed, angle, spin, turf=args.turf, **overrides)
    if args.json:
        _print_json(result)
    else:
        _print_table(list(result.items()))
    return 0


def _run_models(args):
    if args.json:
        print(
            json.dumps(
                [
                    {"name": n, "default": n == aero.DEFAULT_MODEL, "source": aero.SOURCES[n]}
                    for n in aero.MODELS
                ]
            )
        )
        return 0
    for name in aero.MODELS:
        print(name + ("  (default)" if name == aero.DEFAULT_MODEL else ""))
        print(
            textwrap.fill(
                aero.SOURCES[name], width=96, initial_indent="    ", subsequent_indent="    "
            )
        )
    return 0


def _run_turfs(args):
    presets = []
    for name, preset in turf.PRESETS.items():
        fields = preset._asdict()
        fields["stimp_m"] = turf.stimp_from_rho_g(preset.rho_g)
        source = "estimate" if name in turf.ESTIMATED_PRESETS else "Penner (2002)"
        presets.append({"name": name, "source": source, **fields})
    if args.json:
        print(json.dumps(presets))
        return 0
    columns = list(presets[0])
    table = [columns] + [[_format(p[c], ".4g") for c in columns] for p in presets]
    widths = [max(len(row[i]) for row in table) for i in range(len(columns))]
    for row in table:
        print("  ".join(cell.ljust(w) for cell, w in zip(row, widths, strict=True)).rstrip())
    return 0


# --- the parser --------------------------------------------------------------------------------


class _Parser(argparse.ArgumentParser):
    """argparse with its usage errors on one line, in the same form as every other error."""

    def error(self, message):
        self.exit(2, f"mcrun: error: {message} (see '{self.prog} --help')\n")


_SHOT_DESCRIPTION = """\
Simulate one shot from launch to rest: flight, bounces on compliant turf (Penner 2002), roll.

Frame: x along the target line, y positive to the RIGHT, z up. Give the ball launch as a launch
monitor reports it (--ball-speed, --launch, --spin, optionally --azimuth and --spin-axis), or the
club delivery (--club-speed, --loft, optionally --club-mass; Penner 2001 club model), not both.

Values take an optional unit: speeds 167mph, 74.3 (m/s), 120km/h; spins 2686rpm, 281 (rad/s);
angles 10.9 or 10.9deg (a bare angle is degrees), 0.19rad; lengths 10ft, 3cm, 5 (m);
temperatures 68F, 293K, 20 (Celsius); pressures 1013hPa, 29.92inHg, 101325 (Pa).
A value starting with a minus and carrying a unit or a comma may be written --opt -3mph,2mph or
--opt=-3mph,2mph.

Output: a table of the outcome (SI, names carry the unit; golf units beside), or with --json one
JSON object with every outcome field and status_name (null where the shot did not get that far).
Landing angles are from the vertical (as in the paper), launch angles above the horizontal.
A shot that ends with a status other than ok is still printed, with a warning on stderr."""

_SHOT_EPILOG = """\
examples:
  mcrun shot --ball-speed 167mph --launch 10.9 --spin 2686rpm
  mcrun shot --club-speed 55 --loft 13.3 --turf firm_green --json
  mcrun shot --ball-speed 50 --launch 20 --spin 6000rpm --wind 10mph,-3mph --temperature 68F"""


def add_conditions_options(p):
    """The options of everything but the launch (turf and ground, aerodynamics and wind, air,
    step), shared by ``mcrun shot`` and ``mcrun replay``; ``conditions_kwargs`` reads them."""
    conditions = api.conditions_inputs
    fp = api.flight_params
    air = api.air_properties
    ground = p.add_argument_group("turf and ground")
    ground.add_argument(
        "--turf",
        metavar="NAME",
        default=_api_default(conditions, "turf"),
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
        help="override rho_g by a Stimpmeter reading, e.g. 10ft (bare: m)",
    )
    ground.add_argument(
        "--critical-height",
        metavar="LENGTH",
        help="override: hop height below which the ball rolls, e.g. 5mm (bare: m)",
    )
    ground.add_argument(
        "--slope",
        metavar="ANGLE",
        help=f"ground slope (bare: deg; default {_api_default(conditions, 'slope_deg'):g})",
    )
    ground.add_argument(
        "--fall-line",
        metavar="ANGLE",
        help="downhill direction from the target line, positive to the right: 0 = downhill "
        f"towards the target, 180 = uphill (bare: deg; default "
        f"{_api_default(conditions, 'fall_line_deg'):g})",
    )
    flight = p.add_argument_group("aerodynamics and wind")
    flight.add_argument(
        "--aero",
        metavar="NAME",
        default=_api_default(fp, "aero_model"),
        help=f"aerodynamic model: {', '.join(aero.MODELS)} (default %(default)s; "
        "see 'mcrun models')",
    )
    flight.add_argument(
        "--cd-scale",
        metavar="X",
        help=f"scale on the drag coefficient (default {_api_default(fp, 'cd_scale'):g})",
    )
    flight.add_argument(
        "--cl-scale",
        metavar="X",
        help=f"scale on the lift coefficient (default {_api_default(fp, 'cl_scale'):g})",
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
        default=_api_default(fp, "wind_profile"),
        help=f"wind height profile: {' | '.join(api.WIND_PROFILE_DEFAULTS)} (default %(default)s)",
    )
    flight.add_argument(
        "--wind-height",
        metavar="LENGTH",
        help="height at which --wind is given (bare: m; default "
        f"{_api_default(fp, 'wind_reference_height_m'):g})",
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
        help=f"air temperature (bare: Celsius; default {_api_default(air, 'temperature_c'):g})",
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
        help=f"relative humidity, 0.5 or 50%% (default {_api_default(air, 'relative_humidity'):g})",
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


def _add_shot(subparsers):
    sim = api.shot_inputs
    p = subparsers.add_parser(
        "shot",
        help="simulate one shot from launch to rest",
        description=_SHOT_DESCRIPTION,
        epilog=_SHOT_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
        allow_abbrev=False,
    )
    ball = p.add_argument_group("ball launch (as a launch monitor reports it)")
    ball.add_argument("--ball-speed", metavar="SPEED", help="ball speed (bare: m/s)")
    ball.add_argument(
        "--launch", metavar="ANGLE", help="vertical launch angle above the horizontal (bare: deg)"
    )
    ball.add_argument("--spin", metavar="SPIN", help="total spin, >= 0 (bare: rad/s)")
    ball.add_argument(
        "--azimuth",
        metavar="ANGLE",
        help="horizontal launch direction from the target line, positive to the right "
        f"(bare: deg; default {_api_default(sim, 'azimuth_deg'):g})",
    )
    ball.add_argument(
        "--spin-axis",
        metavar="ANGLE",
        help="tilt of the spin axis, positive curves the ball to the right (a fade for a "
        f"right-hander) (bare: deg; default {_api_default(sim, 'spin_axis_deg'):g})",
    )
    club = p.add_argument_group("club delivery (instead of the ball launch; Penner 2001)")
    club.add_argument("--club-speed", metavar="SPEED", help="club-head speed (bare: m/s)")
    club.add_argument(
        "--club-mass",
        metavar="MASS",
        help=f"club-head mass (bare: kg; default {api.DEFAULT_CLUB_MASS_KG:.3f})",
    )
    club.add_argument(
        "--loft", metavar="ANGLE", help="dynamic loft, face to the vertical (bare: deg)"
    )
    add_conditions_options(p)
    out = p.add_argument_group("numerics and output")
    out.add_argument(
        "--trajectory",
        metavar="FILE.csv",
        help="write the path to a CSV: t_s, x_m, y_m (positive right), z_m, phase",
    )
    out.add_argument("--json", action="store_true", help="print one JSON object instead")
    p.set_defaults(func=_run_shot)


def _add_bounce(subparsers):
    p = subparsers.add_parser(
        "bounce",
        help="one impact on level turf (Penner 2002, section 2)",
        description="One impact of a ball on level turf, in the paper's terms: angles from the "
        "vertical, backspin positive. Prints the tilt theta_c of the equivalent surface (8), "
        "the restitution e (5), the critical friction mu_c (4), whether the ball leaves "
        "sliding or rolling, the rebound (speed, angle from the vertical, negative when the "
        "ball goes back, spin with backspin positive), the hop height, and the critical "
        "backspin for a backward bounce (10).",
        epilog="example: mcrun bounce --speed 26.8 --angle 68 --spin 224 --mu 0.4",
        allow_abbrev=False,
    )
    p.add_argument("--speed", metavar="SPEED", required=True, help="impact speed (bare: m/s)")
    p.add_argument(
        "--angle",
        metavar="ANGLE",
        required=True,
        help="impact angle from the vertical, [0, 90) (bare: deg)",
    )
    p.add_argument(
        "--spin",
        metavar="SPIN",
        required=True,
        help="spin at impact, backspin positive (bare: rad/s)",
    )
    p.add_argument(
        "--turf",
        metavar="NAME",
        default=_api_default(api.bounce_once, "turf"),
        help=f"turf preset: {', '.join(turf.PRESETS)} (default %(default)s)",
    )
    p.add_argument("--mu", metavar="MU", help="override: ball-turf kinetic friction")
    p.add_argument(
        "--softness", metavar="S", help="override: scale on the equivalent-surface tilt theta_c"
    )
    p.add_argument("--json", action="store_true", help="print one JSON object instead")
    p.set_defaults(func=_run_bounce)


def _add_lists(subparsers):
    p = subparsers.add_parser(
        "models", help="list the aerodynamic models and their sources", allow_abbrev=False
    )
    p.add_argument("--json", action="store_true", help="print JSON instead")
    p.set_defaults(func=_run_models)
    p = subparsers.add_parser(
        "turfs", help="list the turf presets and their fields", allow_abbrev=False
    )
    p.add_argument("--json", action="store_true", help="print JSON instead")
    p.set_defaults(func=_run_turfs)


# Commands of their own modules, which bring pandas, pyarrow or matplotlib: imported only
# when the command line may need them, so that `mcrun shot` starts quickly.
COMMAND_MODULES = {
    "run": "mcrun.run.local",
    "validate": "mcrun.run.local",
    "scenarios": "mcrun.run.local",
    "replay": "mcrun.run.local",
    "calibrate": "mcrun.calibrate",
    "paper": "mcrun.paper",
    "plot": "mcrun.report.plots",
    "report": "mcrun.report.html",
}
CORE_COMMANDS = ("shot", "bounce", "models", "turfs")


def build_parser(command=None):
    """The ``mcrun`` argument parser: every subcommand, or only the core ones when ``command``
    (the first word of the command line) is one of them."""
    parser = _Parser(
        prog="mcrun",
        description="Golf shots: flight, compliant-turf bounce (Penner 2002) and roll.",
        allow_abbrev=False,
    )
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)
    _add_shot(subparsers)
    _add_bounce(subparsers)
    _add_lists(subparsers)
    if command not in CORE_COMMANDS:
        for module in dict.fromkeys(COMMAND_MODULES.values()):
            importlib.import_module(module).register(subparsers)
    return parser


# The kernel each simulating command runs: the single shot or the batch.
SIMULATING_COMMANDS = {
    "shot": "single",
    "calibrate": "single",
    "paper": "single",
    "run": "batch",
    "replay": "batch",
}


def _kernel_cached(kind):
    """Whether the kernel is in numba's on-disk cache (None when it cannot be told): the shot
    loop, which a single shot runs too."""
    from mcrun.engine.batch import _simulate_batch

    try:
        return os.path.exists(_simulate_batch._cache._cache_file._index_path)
    except AttributeError:  # numba's cache internals moved
        return None


def _compile(kind):
    """Compile the command's kernel (or load it from numba's cache)."""
    if kind == "single":
        api.simulate(ball_speed_mps=70.0, launch_angle_deg=12.0, spin_radps=250.0)
    else:
        import numpy as np

        from mcrun.engine.backend import simulate_batch
        from mcrun.engine.schema import N_INPUT

        simulate_batch(np.zeros((0, N_INPUT)))


def _compile_if_needed(kind):
    """When the command's kernel is not in numba's on-disk cache yet (the first run after an
    install or an upgrade compiles it, which takes a while), compile it before the command
    starts, saying so on stderr with the time it took: a run's rate is then its own."""
    if _kernel_cached(kind) is not False:
        return
    print(
        "mcrun: compiling the kernels (first run after install; cached for the next runs)",
        file=sys.stderr,
        flush=True,
    )
    started = time.perf_counter()
    _compile(kind)
    print(f"mcrun: compiled the kernels in {time.perf_counter() - started:.0f} s", file=sys.stderr)


def main(argv=None):
    """Run ``mcrun`` with ``argv`` (default: the process's arguments); return the exit code."""
    argv = sys.argv[1:] if argv is None else list(argv)
    parser = build_parser(argv[0] if argv else None)
    try:
        args = parser.parse_args(_attach_negative_values(argv))
    except SystemExit as exit_:  # --help, or a usage error argparse has already reported
        return exit_.code if isinstance(exit_.code, int) else int(exit_.code is not None)
    # SIGTERM stops a command as Ctrl-C does (the commands clean up on KeyboardInterrupt).
    with exits.sigterm_interrupts() as terminated:
        code = _run_command(args)
    if terminated and code == exits.EXIT_INTERRUPTED:
        return exits.EXIT_TERMINATED
    return code


def _run_command(args):
    """``args.func(args)``, with every error a user can cause as one line and exit code 2."""
    try:
        if args.command in SIMULATING_COMMANDS:
            _compile_if_needed(SIMULATING_COMMANDS[args.command])
        return args.func(args)
    except (InputError, UnitError, CommandError) as err:
        print("mcrun: error: " + " ".join(str(err).split()), file=sys.stderr)
        return 2
    except BrokenPipeError:  # e.g. `mcrun shot ... | head -3`: the reader has gone, not a bug
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no error at exit
        return 1
    except OSError as err:
        if not exits.is_name_too_long(err):
            raise
        print(f"mcrun: error: {exits.name_too_long(err)}", file=sys.stderr)
        return 2
    except exits.Terminated:
        print("mcrun: terminated (SIGTERM)", file=sys.stderr)
        return exits.EXIT_TERMINATED
    except KeyboardInterrupt:
        print("mcrun: interrupted", file=sys.stderr)
        return exits.EXIT_INTERRUPTED
