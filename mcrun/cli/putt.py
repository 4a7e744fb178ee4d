"""``mcrun putt``: a putt on a plane green, read and holed out n times: make rate, three-putt
rate and average putts with their standard errors, and the read (start line and pace)."""

import math

from mcrun.putting import PUTTERS, putt
from mcrun.quantities import InputError
from mcrun.units import parse_quantity


def _slope_tan(text):
    """A slope as rise over run: a percentage ("2%") or a fraction ("0.02"), or an angle with
    its unit ("1.1deg", "0.02rad")."""
    if any(unit in text.lower() for unit in ("deg", "rad", "°")):
        return math.tan(parse_quantity(text, "angle", "--slope"))
    return parse_quantity(text, "fraction", "--slope")


def _whole(text, name, least):
    """A whole number of at least ``least``: ``2000``, ``1e4``."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value) or value != int(value) or value < least:
        raise InputError(f"{name} {text!r}: allowed: a whole number of at least {least}")
    return int(value)


def _cmd_putt(args):
    result = putt(
        parse_quantity(args.distance, "length", "--distance"),
        parse_quantity(args.stimp, "length", "--stimp"),
        _slope_tan(args.slope),
        parse_quantity(args.direction, "angle", "--direction") * 180.0 / math.pi,
        putter=args.putter,
        n=_whole(args.n, "-n", 2),
        seed=_whole(args.seed, "--seed", 0),
    )
    r = result.read
    if abs(r.aim_deg) < 0.005:
        line = "at the hole"
    else:
        line = f"{abs(r.aim_deg):.2f} deg {'left' if r.aim_deg > 0 else 'right'} of the hole"
    print(
        f"putt: {args.distance} on a plane green, Stimp {args.stimp}, slope {args.slope} "
        f"falling at {args.direction} deg; putter {args.putter}; n {result.n}, seed {args.seed}"
    )
    print(f"read: start line {line}, pace {r.pace_m:.2f} m past")
    print(f"make rate:       {100 * result.make_rate:5.1f} % +- {100 * result.make_rate_se:.1f}")
    print(
        f"three-putt rate: {100 * result.three_putt_rate:5.1f} % "
        f"+- {100 * result.three_putt_rate_se:.1f}"
    )
    print(f"average putts:   {result.average_putts:.3f} +- {result.average_putts_se:.3f}")
    return 0


def register(subparsers):
    """Add ``putt`` to an argparse subparsers object."""
    p = subparsers.add_parser(
        "putt",
        help="a putt on a plane green: make rate, three-putts, average putts, the read",
        description="Hole out a putt on a plane green N times with a putter's errors in start "
        "line and speed: the make rate, three-putt rate and average putts (with standard "
        "errors), and the read (start line and pace past the hole) that minimises the average "
        "putts. DIRECTION is the direction the green falls, in degrees from the putt's line "
        "(ball to hole), counter-clockwise seen from above: 0 downhill, 90 falls to the left "
        "(the putt breaks left), 180 uphill, 270 falls to the right.",
        epilog="example: mcrun putt --distance 10ft --stimp 11ft --slope 2%% --direction 90",
        allow_abbrev=False,
    )
    p.add_argument("--distance", required=True, help="to the hole, e.g. 10ft, 3m")
    p.add_argument("--stimp", default="11ft", help="the green's Stimpmeter reading (11ft)")
    p.add_argument("--slope", default="0%", help="the green's slope: 2%%, 0.02 or 1.1deg (0%%)")
    p.add_argument(
        "--direction", default="0", help="the fall line, degrees from the putt's line (0)"
    )
    p.add_argument("--putter", default="tour", choices=list(PUTTERS), help="(tour)")
    p.add_argument("-n", default="2000", metavar="N", help="holings-out (2000); 1e4 works")
    p.add_argument("--seed", default="0", metavar="S", help="random seed (0)")
    p.set_defaults(func=_cmd_putt)
