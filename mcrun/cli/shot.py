"""``mcrun shot``, ``mcrun bounce``, ``mcrun models`` and ``mcrun turfs``: one shot, one impact,
and the lists of the aerodynamic models and the turf presets.

A thin edge over ``mcrun.api``: options are read into SI (``mcrun.cli.options``), handed to the
API, which checks every range, and the result is printed as an aligned table or as one JSON
object. These are the core commands: their module imports neither pandas, pyarrow nor
matplotlib, so that ``mcrun shot`` starts quickly.
"""

import argparse
import json
import math
import os
import re
import sys
import textwrap
from pathlib import Path

from mcrun import api, status, units
from mcrun.cli import CommandError
from mcrun.cli.options import (
    add_conditions_options,
    api_default,
    conditions_kwargs,
    degrees,
    given,
    named,
    number,
    quantity,
)
from mcrun.physics import aero, turf
from mcrun.quantities import DEFAULTS

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
    """JSON has no NaN: a field the shot did not reach is null; -0.0 (a straight shot's side)
    is 0.0, as the table prints it."""
    if isinstance(value, float):
        return value + 0.0 if math.isfinite(value) else None
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


# The options of ``mcrun shot`` and ``mcrun bounce`` by the API's names of their values, which
# its range errors name ("ball_speed_mps = 0 is outside the allowed range [0.5, 120]").
SHOT_OPTIONS = {
    "ball_speed_mps": "--ball-speed",
    "launch_angle_deg": "--launch",
    "spin_radps": "--spin",
    "azimuth_deg": "--azimuth",
    "spin_axis_deg": "--spin-axis",
    "club_speed_mps": "--club-speed",
    "club_mass_kg": "--club-mass",
    "loft_deg": "--loft",
    # The conditions' (their errors named the API's field alone)
    "slope_deg": "--slope",
    "fall_line_deg": "--fall-line",
    "temperature_c": "--temperature",
    "relative_humidity": "--humidity",
    "wind_speed_mps": "--wind",
    "wind_mps": "--wind",
    "wind_profile_parameter": "--wind-param",
    "wind_reference_height_m": "--wind-height",
    "altitude_m": "--altitude",
    "pressure_pa": "--pressure",
    "air_density_kgpm3": "--air-density",
    "dt_s": "--dt",
    "cd_scale": "--cd-scale",
    "cl_scale": "--cl-scale",
}
BOUNCE_OPTIONS = {
    "ball_speed_mps": "--speed",
    "impact_angle_deg": "--angle",
    "backspin_radps": "--spin",
}


def _shot_kwargs(args):
    """Keyword arguments of ``mcrun.api.simulate`` from the ``shot`` options."""
    return given(
        ball_speed_mps=quantity(args.ball_speed, "speed", "--ball-speed"),
        launch_angle_deg=degrees(args.launch, "--launch"),
        spin_radps=quantity(args.spin, "spin", "--spin"),
        azimuth_deg=degrees(args.azimuth, "--azimuth"),
        spin_axis_deg=degrees(args.spin_axis, "--spin-axis"),
        club_speed_mps=quantity(args.club_speed, "speed", "--club-speed"),
        club_mass_kg=quantity(args.club_mass, "mass", "--club-mass"),
        loft_deg=degrees(args.loft, "--loft"),
    ) | conditions_kwargs(args)


# A trajectory's file: a CSV (compressed as its name says, by pandas) or Parquet.
TRAJECTORY_NAME = re.compile(r"\.(csv(\.(gz|bz2|xz|zst|zip))?|parquet)$", re.IGNORECASE)


def _check_trajectory_path(text):
    """CommandError, before the shot is flown, where ``--trajectory`` cannot be written (a
    folder that is missing is made, as every command's output makes it)."""
    path = Path(text)
    where = path.parent if str(path.parent) else Path(".")
    while not where.exists() and where.parent != where:
        where = where.parent
    reason = None
    if text == "-":  # (a file named "-" was written; stdout holds the shot's table)
        reason = "a file's path (the shot's table goes to stdout)"
    elif path.is_dir():
        reason = "is a folder; give a file name"
    elif not TRAJECTORY_NAME.search(path.name):  # (t.parquet was written as CSV)
        reason = "allowed: a file named .csv (or .csv.gz, .csv.bz2...) or .parquet"
    elif not where.is_dir():
        reason = f"{where} is not a folder"
    elif not os.access(where, os.W_OK | os.X_OK):
        reason = f"cannot write in {where}"
    if reason is not None:
        raise CommandError(f"--trajectory {text}: {reason}")


def _check_launch_given(args):
    """A ball launch needs --ball-speed, --launch and --spin, unless a club delivery is given
    (the API's message named its fields: launch_angle_deg, spin_radps)."""
    if args.club_speed is not None or args.loft is not None:
        return
    missing = [option for option, value in (("--ball-speed", args.ball_speed),
               ("--launch", args.launch), ("--spin", args.spin)) if value is None]  # fmt: skip
    if missing:
        raise CommandError(f"a ball launch needs {', '.join(missing)} (or a club delivery: "
                           "--club-speed and --loft)")  # fmt: skip


def _cmd_shot(args):
    _check_launch_given(args)
    kwargs = _shot_kwargs(args)
    if args.trajectory is not None:
        _check_trajectory_path(args.trajectory)
    result = named(
        lambda: api.simulate(trajectory=args.trajectory is not None, **kwargs), SHOT_OPTIONS,
        {"ball_speed_mps": (args.ball_speed, "speed"), "spin_radps": (args.spin, "spin"),
         "club_speed_mps": (args.club_speed, "speed")},
    )  # fmt: skip
    if args.trajectory is not None:
        try:
            path = Path(args.trajectory)
            path.parent.mkdir(parents=True, exist_ok=True)
            path_m = result.trajectory.copy()
            floats = path_m.select_dtypes("float").columns
            path_m[floats] += 0.0  # (-0.0, a straight shot's side, as 0.0)
            if path.suffix.lower() == ".parquet":
                path_m.to_parquet(path, index=False)
            else:
                path_m.to_csv(path, index=False)
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


def _cmd_bounce(args):
    speed = quantity(args.speed, "speed", "--speed")
    angle = degrees(args.angle, "--angle")
    spin = quantity(args.spin, "spin", "--spin")
    overrides = given(mu=number(args.mu, "--mu"), softness=number(args.softness, "--softness"))
    result = named(
        lambda: api.bounce_once(speed, angle, spin, turf=args.turf, **overrides),
        BOUNCE_OPTIONS,
        {"ball_speed_mps": (args.speed, "speed"), "backspin_radps": (args.spin, "spin")},
    )
    if args.json:
        _print_json(result)
    else:
        _print_table(list(result.items()))
    return 0


def _cmd_models(args):
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


def _cmd_turfs(args):
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


# --- the parsers -------------------------------------------------------------------------------

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
        f"(bare: deg; default {api_default(sim, 'azimuth_deg'):g})",
    )
    ball.add_argument(
        "--spin-axis",
        metavar="ANGLE",
        help="tilt of the spin axis, positive curves the ball to the right (a fade for a "
        f"right-hander) (bare: deg; default {api_default(sim, 'spin_axis_deg'):g})",
    )
    club = p.add_argument_group("club delivery (instead of the ball launch; Penner 2001)")
    club.add_argument("--club-speed", metavar="SPEED", help="club-head speed (bare: m/s)")
    club.add_argument(
        "--club-mass",
        metavar="MASS",
        help=f"club-head mass (bare: kg; default {DEFAULTS['club_mass_kg']:.3f})",
    )
    club.add_argument(
        "--loft", metavar="ANGLE", help="dynamic loft, face to the vertical (bare: deg)"
    )
    add_conditions_options(p)
    out = p.add_argument_group("output")
    out.add_argument(
        "--trajectory",
        metavar="FILE.csv",
        help="write the path to a CSV, or Parquet for a .parquet name (replaced if it exists; "
        "its folder made if missing): t_s, x_m, y_m (positive right), z_m, phase",
    )
    out.add_argument("--json", action="store_true", help="print one JSON object instead")
    p.set_defaults(func=_cmd_shot)


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
        help="impact angle from the vertical, {:g} to {:g} (bare: deg)".format(
            *api.RANGES["impact_angle_deg"]
        ),
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
        default=api_default(api.bounce_once, "turf"),
        help=f"turf preset: {', '.join(turf.PRESETS)} (default %(default)s)",
    )
    p.add_argument("--mu", metavar="MU", help="override: ball-turf kinetic friction")
    p.add_argument(
        "--softness", metavar="S", help="override: scale on the equivalent-surface tilt theta_c"
    )
    p.add_argument("--json", action="store_true", help="print one JSON object instead")
    p.set_defaults(func=_cmd_bounce)


def _add_lists(subparsers):
    p = subparsers.add_parser(
        "models", help="list the aerodynamic models and their sources", allow_abbrev=False
    )
    p.add_argument("--json", action="store_true", help="print JSON instead")
    p.set_defaults(func=_cmd_models)
    p = subparsers.add_parser(
        "turfs", help="list the turf presets and their fields", allow_abbrev=False
    )
    p.add_argument("--json", action="store_true", help="print JSON instead")
    p.set_defaults(func=_cmd_turfs)


def register(subparsers):
    """Add ``shot``, ``bounce``, ``models`` and ``turfs`` to an argparse subparsers object."""
    _add_shot(subparsers)
    _add_bounce(subparsers)
    _add_lists(subparsers)
