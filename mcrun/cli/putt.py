"""``mcrun putt``: a putt on a plane green, read and holed out n times: make rate, three-putt
rate and average putts with their standard errors, and the read (start line and pace); or,
with ``--hole``, the expected-putts map of a hole's green to Parquet (and a picture)."""

import math
import sys

from mcrun import exits, units
from mcrun.cli import compile_if_needed
from mcrun.cli.options import whole, with_unit
from mcrun.hole.hole import PUTTING_N_RANGE, PUTTING_READS
from mcrun.putting import MAX_PUTTS, MAX_SLOPE_TAN, PUTTERS, check_putt, check_stimp, putt
from mcrun.putting.greens import (
    DRIFT_MM_PER_M_BENTGRASS,
    DRIFT_RANGE_MM_PER_M,
    STIMP_RANGE_FT,
    stopping_slope,
)
from mcrun.putting.roll import MAX_TIME_S
from mcrun.quantities import InputError
from mcrun.strokes.baseline import FOOT_M
from mcrun.units import parse_quantity

DEFAULT_STIMP = "11ft"


# The option that gives each field ``check_putt`` names, and the argument that holds its text.
PUTT_OPTIONS = {
    "distance_m": ("--distance", "distance"),
    "slope_tan": ("--slope", "slope"),
    "direction_deg": ("--direction", "direction"),
    "drift_mm_per_m": ("--drift", "drift"),
    "n": ("-n", "n"),
}


def _slope_tan(text):
    """A slope as rise over run: a percentage ("2%") or a fraction ("0.02"), or an angle with
    its unit ("1.1deg", "0.02rad"); an angle beyond the steepest slope allowed is refused as it
    is (its tangent would wrap round)."""
    if any(unit in text.lower() for unit in ("deg", "rad", "°")):
        angle = parse_quantity(text, "angle", "--slope")
        if not 0.0 <= angle <= math.atan(MAX_SLOPE_TAN):
            raise InputError(
                f"--slope {text}: allowed: 0 to {100 * MAX_SLOPE_TAN:g} % "
                f"({math.degrees(math.atan(MAX_SLOPE_TAN)):.1f} deg)"
            )
        return math.tan(angle)
    return parse_quantity(text, "fraction", "--slope")


def _stimp_m(text):
    """The --stimp reading (m), within the Stimp readings of a green."""
    return check_stimp(with_unit(text, "length", "--stimp", "11ft"), f"--stimp {text}")


def _drift(text):
    """The --drift (mm of sideways spread per metre rolled), within ``DRIFT_RANGE_MM_PER_M``."""
    lo, hi = DRIFT_RANGE_MM_PER_M
    bare = text.strip().removesuffix("mm/m")
    foreign = units.foreign_digits(bare)
    if foreign is not None:  # (float read "４.９" as 4.9 and "1_0" as 10)
        raise InputError(f"--drift {text}: cannot read it as a number: {foreign}")
    try:
        value = float(bare)
    except ValueError:
        value = math.nan
    if not lo <= value <= hi:
        raise InputError(
            f"--drift {text}: allowed: {lo:g} to {hi:g} (mm per metre rolled; "
            f"{DRIFT_MM_PER_M_BENTGRASS:g} pure bentgrass, 0 a perfect green)"
        )
    return value


def _cmd_putt(args):
    if args.hole is not None:
        return _cmd_green(args)
    if args.distance is None:
        raise InputError("--distance: required for a putt on a plane green (or give --hole)")
    for name in ("resolution", "read", "output", "plot"):
        if getattr(args, name) is not None:
            raise InputError(f"--{name}: is for a green's map (with --hole)")
    if args.force:
        raise InputError("--force: is for a green's map (with --hole and -o or --plot)")
    args.slope = "0%" if args.slope is None else args.slope
    args.direction = "0" if args.direction is None else args.direction
    args.putter = "tour" if args.putter is None else args.putter
    args.seed = "0" if args.seed is None else args.seed
    args.stimp = DEFAULT_STIMP if args.stimp is None else args.stimp
    args.n = "2000" if args.n is None else args.n
    drift = DRIFT_MM_PER_M_BENTGRASS if args.drift is None else _drift(args.drift)
    given = dict(
        distance_m=with_unit(args.distance, "length", "--distance", "10ft"),
        stimp_m=_stimp_m(args.stimp),
        slope_tan=_slope_tan(args.slope),
        direction_deg=parse_quantity(args.direction, "angle", "--direction") * 180.0 / math.pi,
        putter=args.putter,
        n=whole(args.n, "-n", *PUTTING_N_RANGE),
        seed=whole(args.seed, "--seed", 0),
        drift_mm_per_m=drift,
    )
    said = {
        field: f"{option} {getattr(args, arg)}" for field, (option, arg) in PUTT_OPTIONS.items()
    }
    check_putt(**{k: v for k, v in given.items() if k != "seed"}, said=said)
    compile_if_needed("green", ("putt",))
    result = exits.interruptible(putt, **given)
    r = result.read
    if abs(r.aim_deg) < 0.005:
        line = "at the hole"
    else:
        line = f"{abs(r.aim_deg):.2f} deg {'left' if r.aim_deg > 0 else 'right'} of the hole"
    typed = {k: units.control_free(getattr(args, k)) for k in ("distance", "stimp", "slope")}
    print(
        f"putt: {typed['distance']} on a plane green, Stimp {typed['stimp']}, slope "
        f"{typed['slope']} falling at {given['direction_deg']:g} deg, drift {drift + 0.0:g} mm/m; "
        f"putter {args.putter}; n {result.n}, seed {given['seed']}"  # (the integer: 1.5e3 is 1500)
    )
    print(f"read: start line {line}, pace {r.pace_m:.2f} m past")
    print(f"make rate:       {100 * result.make_rate:5.1f} % +- {100 * result.make_rate_se:.1f}")
    print(
        f"three-putt rate: {100 * result.three_putt_rate:5.1f} % "
        f"+- {100 * result.three_putt_rate_se:.1f}"
    )
    print(f"average putts:   {result.average_putts:.3f} +- {result.average_putts_se:.3f}")
    _say_if_too_few(result)
    if result.unfinished_share > 0.0:
        rest = stopping_slope(given["stimp_m"])
        print(f"mcrun: warning: {100 * result.unfinished_share:.1f} % of the holings-out were "
              f"counted as {MAX_PUTTS} putts: a ball still rolling after {MAX_TIME_S:g} s (on a "
              f"slope this near the green's stopping slope, {100 * rest:.2f} %, a miss rolls on "
              f"for tens of metres) or not down after {MAX_PUTTS}; the rates and the average are "
              "not a green's", file=sys.stderr)  # fmt: skip
    return 0


# Fewer putts than this, a rate of 0 or 100 % says with its standard error (0) more than it
# knows: warned, with the exact one-sided 95 % bound, 1 - 0.05^(1/n) (about 3 / n).
FEW_PUTTS = 100


def _say_if_too_few(result):
    """A warning where a rate is 0 or 100 % in fewer than FEW_PUTTS putts: its standard error,
    0, says nothing (``-n 2``: "100.0 % +- 0.0"); the exact bound (Clopper-Pearson, one-sided
    95 %) says how far the rate may be."""
    rates = {"make rate": result.make_rate, "three-putt rate": result.three_putt_rate}
    sure = [name for name, rate in rates.items() if rate in (0.0, 1.0)]
    if result.n < FEW_PUTTS and sure:
        bound = 100 * (1.0 - 0.05 ** (1.0 / result.n))
        print(f"mcrun: warning: the {' and the '.join(sure)} {'is' if len(sure) == 1 else 'are'} "
              f"0 or 100 % in all {result.n} putts: a standard error of 0 says nothing there; "
              f"at 95 % the rate may be {bound:.0f} points from it; more putts (-n) tell "
              "more", file=sys.stderr)  # fmt: skip


def _cmd_green(args):
    """The expected-putts map of a hole's green: a table, a picture, a few lines."""
    from mcrun.cli import Interrupted, write_all_or_nothing
    from mcrun.cli.hole import say_skipped
    from mcrun.hole.hole import load_hole
    from mcrun.physics.turf import stimp_from_rho_g
    from mcrun.putting.green import GreenError, green_of_hole
    from mcrun.putting.green_map import expected_putts_map, map_grid
    from mcrun.putting.on_hole import check_putting
    from mcrun.results import output
    from mcrun.run import aim

    for name in ("distance", "slope", "direction"):
        if getattr(args, name) is not None:
            raise InputError(f"--{name}: is for a plane green; with --hole the green is the hole's")
    if args.output is None:
        raise InputError("--hole: give -o FILE.parquet for the map (and --plot FILE.png)")
    hole = load_hole(args.hole)
    say_skipped(hole)
    hole = check_putting(hole, green=False)  # the green: below, at its speed
    stimp_m = None if args.stimp is None else _stimp_m(args.stimp)
    destination = aim.check_output(args.output, args.force, "-o", (".parquet",), ".parquet")
    if args.plot is not None:
        from mcrun.report import style

        style.require_matplotlib("putt --plot")
        aim.check_output(args.plot, args.force, "--plot", (".png",), ".png")
    spec = dict(hole.putting)
    resolution = (spec["resolution_m"] if args.resolution is None
                  else parse_quantity(args.resolution, "length", "--resolution"))  # fmt: skip
    if not 0.05 <= resolution <= 5.0:
        raise InputError(f"--resolution {args.resolution}: allowed: 0.05 m to 5 m")
    n = spec["n"] if args.n is None else whole(args.n, "-n", *PUTTING_N_RANGE)
    seed = spec["seed"] if args.seed is None else whole(args.seed, "--seed", 0)
    putter = spec["putter"] if args.putter is None else args.putter
    read = spec["read"] if args.read is None else args.read
    drift = spec["drift_mm_per_m"] if args.drift is None else _drift(args.drift)
    try:
        green = green_of_hole(hole, spec["cell_m"], spec["elevation"], spec["elevation_crs"],
                              stimp_m, drift)  # fmt: skip
        map_grid(green, resolution)  # (before anything is said of the map)
    except GreenError as err:
        raise InputError(str(err)) from None
    speed = f"Stimp {green.stimp_m / FOOT_M:.1f} ft"
    if stimp_m is not None:
        hole_ft = stimp_from_rho_g(hole.turf["green"].rho_g) / FOOT_M
        speed += f" (--stimp; the hole's green: {hole_ft:.1f} ft)"
    speed += f", drift {drift:g} mm/m"
    print(f"putt: the green of {hole.source}: {green.area_m2():.0f} m^2, {speed}; map "
          f"{resolution:g} m, putter {putter} ({read} read), {n} putts a read, seed {seed}",
          file=sys.stderr, flush=True)  # fmt: skip
    compile_if_needed("green", ("map",))
    bar = _bar()
    try:
        result = expected_putts_map(green, putter, n, seed, resolution, progress=bar, read=read)
    except KeyboardInterrupt:
        raise Interrupted("nothing was written") from None
    finally:
        bar.close()
    frame = result.frame()
    lon, lat = hole.to_lonlat(frame["x_m"].to_numpy(), frame["y_m"].to_numpy())
    frame.insert(2, "lon_deg", lon)
    frame.insert(3, "lat_deg", lat)
    provenance = {
        "hole": hole.source, "putter": putter, "read": read, "n": n, "seed": seed,
        "resolution_m": resolution, "green_cell_m": green.cell_m, "stimp_m": green.stimp_m,
        "stimp_from": "hole" if stimp_m is None else "--stimp",
        "drift_mm_per_m": drift, "pin_xy_m": list(green.pin_xy_m),
        "sweeps": result.sweeps, "sweep_change": result.sweep_change,
        "elapsed_s": round(result.elapsed_s, 3), "file": "putts",
        "attribution": hole.attribution or "",
    }  # fmt: skip

    def write():
        with output.AtomicFile(destination, force=args.force) as target:
            output.write_table(target.tmp, frame, output.encode_provenance(provenance))
            target.commit()

    picture = None
    if args.plot is not None:
        from mcrun.report import green_plot

        picture = (args.plot, lambda: green_plot.green_figure(result, hole.attribution),
                   green_plot.DPI)  # fmt: skip
    write_all_or_nothing(write, picture, args.force)
    v = frame["expected_putts"]
    away = v[v > 0.0]  # (a node at the pin is in the hole)
    print(
        f"expected putts over the green: {away.min():.3f} to {away.max():.3f}, mean "
        f"{away.mean():.3f} ({len(away)} points, {result.elapsed_s:.1f} s; settled in "
        f"{result.sweeps} {'sweep' if result.sweeps == 1 else 'sweeps'} after the first: the "
        f"last changed a value by {result.sweep_change:.4f} at most)"
    )
    print(f"wrote {destination}")
    if args.plot is not None:
        print(f"wrote {args.plot}")
    return 0


def _bar():
    from tqdm import tqdm

    bar = tqdm(total=1, unit="point", file=sys.stderr, leave=False, dynamic_ncols=True,
               disable=None)  # fmt: skip

    class Bar:
        def __call__(self, done, total):
            bar.total = total
            bar.update(done - bar.n)

        def close(self):
            bar.close()

    return Bar()


def register(subparsers):
    """Add ``putt`` to an argparse subparsers object."""
    p = subparsers.add_parser(
        "putt",
        help="a putt on a plane green: make rate, three-putts, average putts, the read",
        description="Hole out a putt on a plane green N times with a putter's errors in its "
        "read of the slope, start line and speed, on a green whose drift turns the rolling "
        "ball at random: the make rate, three-putt rate and average putts (with standard "
        "errors), and the read (start line and pace past the hole) that minimises the average "
        "putts. DIRECTION is the direction the green falls, in degrees from the putt's line "
        "(ball to hole), counter-clockwise seen from above: 0 downhill, 90 falls to the left "
        "(the putt breaks left), 180 uphill, 270 falls to the right. With --hole: the "
        "expected-putts map of the hole's green (every point read and valued by N putts; its "
        "settings default to the hole's [hole.putting]; --stimp, where given, in place of the "
        "hole's green's speed) to -o FILE.parquet, and --plot PNG.",
        epilog="examples: mcrun putt --distance 10ft --stimp 11ft --slope 2% --direction 90; "
        "mcrun putt --hole green.toml -o putts.parquet --plot putts.png",
        allow_abbrev=False,
    )
    p.add_argument("--distance", help="to the hole, with its unit: e.g. 10ft, 3m")
    lo, hi = STIMP_RANGE_FT
    p.add_argument("--stimp", help=f"the green's Stimpmeter reading, {lo:g}ft to {hi:g}ft "
                   f"({DEFAULT_STIMP}; with --hole: the hole's green's)")  # fmt: skip
    p.add_argument("--slope", help=f"the green's slope, 0 to {100 * MAX_SLOPE_TAN:g}%%: 2%%, "
                   "0.02 or 1.1deg (0%%)")  # fmt: skip
    p.add_argument("--direction", help="the fall line, degrees from the putt's line (0)")
    p.add_argument(
        "--drift",
        metavar="MM_PER_M",
        help="the green's drift: sideways spread in "
        f"mm per metre rolled, 0 to {DRIFT_RANGE_MM_PER_M[1]:g} "
        f"({DRIFT_MM_PER_M_BENTGRASS:g}, pure bentgrass; with --hole: the hole's)",
    )
    p.add_argument("--putter", choices=list(PUTTERS), help="(tour)")
    p.add_argument("-n", metavar="N", help="holings-out (2000; a map: the hole's, 200)")
    p.add_argument("--seed", metavar="S", help="random seed (0)")
    p.add_argument("--hole", metavar="HOLE", help="a hole TOML file: map its green")
    p.add_argument("--resolution", help="the map's spacing (the hole's, 0.5m)")
    p.add_argument("--read", choices=list(PUTTING_READS),
                   help="how the map reads each putt: the putter's own read, or the best of a "
                   "search of paces and start lines (the hole's, own)")  # fmt: skip
    p.add_argument("-o", "--output", metavar="FILE", help="the map's Parquet (with --hole)")
    p.add_argument("--plot", metavar="PNG", help="the map's picture (with --hole)")
    p.add_argument("--force", action="store_true", help="replace existing outputs")
    p.set_defaults(func=_cmd_putt)
