"""``mcrun aim``: where to aim each club of a scenario on its hole (``mcrun.run.aim``), by
expected strokes (``mcrun.strokes``), with common random numbers; a table of every aim flown
(Parquet, written by ``aim.write_table`` with its provenance and geometry) and a picture
(``mcrun.report.aim_plot``) on request. Here the arguments are read and the results said."""

import math
import sys

from mcrun import units
from mcrun.cli import Interrupted, compile_if_needed, write_all_or_nothing
from mcrun.cli.hole import say_skipped
from mcrun.quantities import InputError
from mcrun.run import aim
from mcrun.strokes import BaselineError, load_baseline

# The command line's names of ``aim.search``'s arguments, for its one-line errors.
OPTION_NAMES = {
    "n": "-n",
    "centre_m": "--centre",
    "half_width_m": "--half-width",
    "coarse_m": "--step",
    "resolution_m": "--resolution",
    "offsets_m": "--offsets",
}


def _metres(text, option, converted=None):
    """A length option's text with its unit (``5yd``, read as ``play --coarse`` reads one) in
    m; a bare number in ASCII digits as typed, for ``aim.check`` to read and check, naming it
    as typed. None where not given; UnitError naming ``option`` for text that is neither.
    A length given with its unit is added to ``converted`` ([(option, text, metres)]), which
    ``aim.check``'s messages, in metres, are told with."""
    if text is None:
        return None
    if units.foreign_digits(text) is None:  # ("1_0" and "１０" go to parse_quantity's refusal)
        try:
            float(text)
            return text
        except ValueError:
            pass
    metres = units.parse_quantity(text, "length", option)
    if converted is not None:
        converted.append((option, text, metres))
    return metres


def _offsets(text, converted=None):
    """The aims of ``--offsets``, each in m or with its unit (checked by ``aim.check``; an
    empty one as typed, which it refuses naming the option's text)."""
    if text is None:
        return None
    return [_metres(v.strip(), "--offsets", converted) if v.strip() else v for v in text.split(",")]


def _with_units_given(err, converted):
    """``aim.check``'s message (values in m) with what each option it names was given as:
    ``--centre 1828.8: ...`` typed as ``--centre 2000yd`` says so."""
    message = str(err)
    said = {}
    for option, text, metres in converted:
        each = said.setdefault(option, []) if f"{option} " in message else None
        if each is not None and f"{text} is {metres:g} m" not in each:
            each.append(f"{text} is {metres:g} m")
    if not said:
        return err
    given = "; ".join(f"{option} {', '.join(each)}" for option, each in said.items())
    return aim.AimError(f"{message} ({given})")


def _cmd_aim(args):
    if args.offsets is not None:  # (each was ignored silently; --centre is the reference)
        given = [o for o, v in (("--half-width", args.half_width), ("--step", args.step),
                                ("--resolution", args.resolution)) if v is not None]  # fmt: skip
        if given:
            raise InputError(f"{given[0]}: is for the search; --offsets gives the aims to fly "
                             "(give one or the other)")  # fmt: skip
    scenario = aim.load_scenario(args.scenario, args.seed, "--seed")
    say_skipped(scenario.hole)
    converted = []
    chosen = {  # (None: the default; beside --offsets, none is given)
        "half_width_m": (_metres(args.half_width, "--half-width", converted),
                         aim.DEFAULT_HALF_WIDTH_M),
        "coarse_m": (_metres(args.step, "--step", converted), aim.DEFAULT_COARSE_M),
        "resolution_m": (_metres(args.resolution, "--resolution", converted),
                         aim.DEFAULT_RESOLUTION_M),
    }  # fmt: skip
    search = {k: default if v is None else v for k, (v, default) in chosen.items()}
    try:
        checked = aim.check(
            scenario, n=args.n, centre_m=_metres(args.centre, "--centre", converted),
            offsets_m=_offsets(args.offsets, converted), names=OPTION_NAMES, **search,
        )  # fmt: skip
    except aim.AimError as err:
        raise _with_units_given(err, converted) from None
    destination = None
    if args.output is not None:
        destination = aim.check_output(
            args.output, args.force, "-o", aim.TABLE_SUFFIXES, ".parquet"
        )
    if args.plot is not None:
        from mcrun.report import aim_plot, style

        style.require_matplotlib("aim --plot")
        aim.check_output(args.plot, args.force, "--plot", (".png",), ".png")
    baseline = None
    if args.baseline is not None:
        try:
            baseline = load_baseline(args.baseline)
        except BaselineError as err:
            raise InputError(str(err)) from None
    try:
        compile_if_needed("terrain")  # said apart from the search's own time
        print(checked.line(), file=sys.stderr, flush=True)
        result = aim.search(
            scenario, n=checked.n, half_width_m=checked.half_width_m, centre_m=checked.centre_m,
            coarse_m=checked.coarse_m, resolution_m=checked.resolution_m,
            offsets_m=checked.offsets_m, baseline=baseline,
        )  # fmt: skip
    except KeyboardInterrupt:
        raise Interrupted("nothing was written") from None
    print(_report(result, args.centre is not None))
    for line in _off_map_warnings(result):
        print(line, file=sys.stderr)
    if destination is None and args.plot is None:
        return 0
    write_all_or_nothing(
        None if destination is None else lambda: aim.write_table(
            result, destination, baseline=args.baseline, force=args.force),
        None if args.plot is None else (
            args.plot, lambda: aim_plot.aim_figure(result, aim.patterns(result)), aim_plot.DPI),
        args.force,
    )  # fmt: skip
    if destination is not None:
        print(f"wrote {destination}")
    if args.plot is not None:
        print(f"wrote {args.plot}")
    return 0


def _off_map_warnings(result):
    """A warning line for each club whose best aim sent shots off the hole's map (scored as out
    of bounds: stroke and distance), where the ground, and so the best aim, is not known; and
    for each whose best aim is the last flown on its side (``ClubAims.at_edge``)."""
    lines = []
    for club in result.clubs:
        k = club.best
        share = club.off_map_share(k)
        if share > 0.0:
            lines.append(
                f"mcrun: warning: {club.club} aimed {club.offsets_m[k]:+.1f} m: "
                f"{100.0 * share:.1f} % of its shots left the hole's map, where the ground is "
                "not known (scored as out of bounds); a larger map (margin_m) or aims nearer "
                "the pin tell more"
            )
        if club.at_edge:
            lines.append(
                f"mcrun: warning: {club.club}: its best aim, {club.offsets_m[k]:+.1f} m, is the "
                "last flown on its side, where the search stopped: an aim beyond it may be "
                "better; a wider --half-width or another --centre tells more"
            )
    return lines


def _xy(xy):
    return f"({xy[0]:.1f}, {xy[1]:+.1f}) m"


def _reference(result, centre_given):
    """(what the differences are to, as the header says it, and as the best's line does)."""
    ref = result.clubs[0].reference_m
    if centre_given:
        return f"--centre ({ref:+.1f} m)", "--centre"
    if len({round(c.reference_m, 9) for c in result.clubs}) > 1:
        return "each club's own aim (the scenario's)", "its aim"
    if abs(ref) < 1e-9:
        return "the pin (+0.0 m)", "the pin"
    return f"the scenario's aim ({ref:+.1f} m)", "the scenario's aim"


def _report(result, centre_given=False):
    hole = result.scenario.hole
    said, reference = _reference(result, centre_given)
    aims = sum(len(c.offsets_m) for c in result.clubs)
    lines = [
        f"aim search on {hole.name or hole.source}: {len(result.clubs)} club(s), {aims} aims x "
        f"{result.n:,} shots each, the same shots at every aim ({result.shots_flown:,} shots in "
        f"{result.seconds:.1f} s); expected strokes from the "
        f"{'tee' if result.from_tee else 'start ' + _xy(result.start_xy_m)} "
        f"{result.expected_start:.3f}",
        f"aims are metres right (+) of the line to the pin at its distance, "
        f"{result.pin_distance_m:.1f} m; differences are to {said}, paired shot by shot",
    ]
    header = ["club", "aims", "best aim", "E after", "+/-", "gained", "vs ref", "+/-"]
    rows = []
    for c in result.clubs:
        k = c.best
        # (About the line to the pin, as the offset is.)
        bearing = math.degrees(math.atan2(c.offsets_m[k], result.pin_distance_m))
        rows.append([
            c.club, str(len(c.offsets_m)), f"{c.offsets_m[k]:+.1f} m ({bearing:+.1f} deg)",
            f"{c.expected[k]:.3f}", f"{c.expected_se[k]:.3f}",
            f"{result.expected_start - 1.0 - c.expected[k]:+.3f}",
            f"{c.difference[k]:+.3f}", f"{c.difference_se[k]:.3f}",
        ])  # fmt: skip
    widths = [max(len(r[i]) for r in [header, *rows]) for i in range(len(header))]
    for line in [header, *rows]:
        lines.append("  ".join(v.ljust(w) for v, w in zip(line, widths, strict=True)).rstrip())
    club, k = result.best()
    lines.append(
        f"best: {club.club} aimed {club.offsets_m[k]:+.1f} m: {club.expected[k]:.3f} expected "
        f"strokes left (+/- {club.expected_se[k]:.3f}), {club.difference[k]:+.3f} "
        f"(+/- {club.difference_se[k]:.3f}) against {reference}"
    )
    return "\n".join(lines)


def register(subparsers):
    """Add ``aim`` to an argparse subparsers object."""
    p = subparsers.add_parser(
        "aim",
        help="find where to aim (and which club) on a scenario's hole, by expected strokes",
        description="Fly the scenario's shots on its hole at a range of aims (start lines, "
        "given as metres right of the line to the pin at the pin's distance) and score each "
        "shot by the strokes it leaves (the PGA Tour baseline of Broadie 2012, or --baseline; "
        "penalties by the Rules). Every aim of a club is flown with the same sampled shots, so "
        "that the differences between aims are measured shot by shot. The search is coarse to "
        "fine: --step apart over the region, then finer around the best down to --resolution. "
        "Each group of the scenario is a club.",
        epilog="example: mcrun aim par3-over-water -n 10000 --plot aim.png",
        allow_abbrev=False,
    )
    p.add_argument("scenario", metavar="SCENARIO", help="a scenario file or a library name")
    p.add_argument("-n", metavar="N", default="10000", help="shots per aim (10000)")
    p.add_argument("--seed", metavar="S", help="random seed (default: the scenario's)")
    p.add_argument(
        "--centre",
        default=None,
        metavar="M",
        help="centre of the region, right of the pin (m, or with a unit: 5yd; default the "
        "scenario's aim)",
    )
    p.add_argument(
        "--half-width",
        default=None,
        metavar="M",
        help=f"the region reaches this far each side (m, {aim.DEFAULT_HALF_WIDTH_M:g})",
    )
    p.add_argument(
        "--step",
        default=None,
        metavar="M",
        help=f"the coarse aims' spacing (m, {aim.DEFAULT_COARSE_M:g})",
    )
    p.add_argument(
        "--resolution",
        default=None,
        metavar="M",
        help=f"the finest spacing (m, {aim.DEFAULT_RESOLUTION_M:g})",
    )
    p.add_argument(
        "--offsets",
        metavar="M,M,...",
        help="fly exactly these aims instead (right of the pin: m, or with units), no refinement",
    )
    p.add_argument("--baseline", metavar="CSV", help="your own expected-strokes table")
    p.add_argument("-o", "--output", metavar="PARQUET", help="write every aim flown here")
    p.add_argument("--plot", metavar="PNG", help="draw the search and the best aim's pattern")
    p.add_argument("--force", action="store_true", help="replace existing output files")
    p.set_defaults(func=_cmd_aim)
