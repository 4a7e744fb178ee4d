"""``mcrun replay``: each measured shot of a launch-monitor file, simulated as given
(``mcrun.run.replay``), on the turf and in the weather of the conditions options; then the
session per club (``mcrun.run.clubs``): the gapping table and the model against the device,
printed and written beside the output as CSV, and with ``--plot`` drawn
(``mcrun.report.replay_plots``)."""

import sys
from pathlib import Path

import numpy as np

from mcrun import status
from mcrun.api import conditions_inputs
from mcrun.cli import Interrupted
from mcrun.cli.options import DPI_RANGE, add_conditions_options, conditions_kwargs, dpi_value
from mcrun.quantities import InputError
from mcrun.report import plots, replay_plots
from mcrun.results.output import OutputError
from mcrun.run import clubs, replay
from mcrun.run.monitors import NAMES


def _cmd_replay(args):
    frame = None
    try:
        conditions = conditions_kwargs(args)
        conditions_inputs(**conditions)  # every option checked before reading the file
        destination = Path(args.output)
        if destination.suffix.lower() not in (".parquet", ".pq"):
            raise InputError(f"-o {args.output}: the output must be a .parquet file")
        if args.plot:  # before anything is written
            plots.require_matplotlib("replay --plot")
            for path in replay_plots.plot_paths(destination).values():
                if path.exists() and not args.force:
                    raise OutputError(f"the plot {path} already exists: use --force to replace it")
        frame = replay.replay_file(
            args.shots, destination, force=args.force, format=args.format, **conditions
        )
        written = frame.attrs["written"][1:]
        if args.plot:
            written += replay_plots.write_replay_plots(frame, destination, dpi=args.dpi)
    except KeyboardInterrupt as err:
        if frame is None:
            raise Interrupted("nothing was written") from None
        # The replay's files are in place; the pictures are all there or none is.
        pictures = getattr(err, "paths", None)  # style.WrittenThenInterrupted: all written
        kept = ", ".join(str(p) for p in [*frame.attrs["written"], *(pictures or [])])
        rest = "" if pictures else "; the pictures were not written"
        raise Interrupted(f"wrote {kept}{rest}") from None
    bad = int((frame["status"] != status.OK).sum())
    for note in frame.attrs.get("notes", ()):
        print(f"mcrun: note: {note}", file=sys.stderr)
    how = "detected" if frame.attrs["format_detected"] else "as asked"
    print(f"read {args.shots}: {frame.attrs['format_title']} ({how})")
    shots = "shot" if len(frame) == 1 else "shots"
    print(f"replayed {len(frame)} {shots} from {args.shots}; wrote {args.output}")
    for path in written:
        print(f"wrote {path}")
    if not args.quiet:
        print()
        print(_gapping(clubs.club_summary(frame)))
        comparison = clubs.device_comparison(frame)
        if len(comparison):
            print()
            print(_comparison(comparison))
    if bad:
        first = ""
        if "invalid_reason" in frame:
            reasons = frame["invalid_reason"].to_numpy(dtype=object)
            k = int(np.flatnonzero(reasons != "")[0])
            first = f"; row {k + 1}: {reasons[k]}"
        print(
            f"mcrun: warning: {bad} shot(s) did not end ok (status_name says why; a missing, "
            f"unreadable or out-of-range launch value gives invalid_input, invalid_reason "
            f"says which){first}",
            file=sys.stderr,
        )
    return 0


def _table(header, rows):
    widths = [max(len(str(r[k])) for r in [header, *rows]) for k in range(len(header))]
    lines = [header, *rows]
    return "\n".join(
        "  ".join(
            str(v).ljust(w) if k == 0 else str(v).rjust(w)
            for k, (v, w) in enumerate(zip(line, widths, strict=True))
        )
        for line in lines
    )


def _m(value):
    return "-" if value != value else f"{value:.1f}"


def _signed(value):
    return "-" if value != value else f"{value:+.2f}"


def _gapping(summary):
    header = ["club", "shots", "ok", "carry_m", "sd", "p10", "p90", "total_m", "sd", "side_m"]
    header += ["sd", "gap_m"]
    rows = [
        [
            r.club,
            r.shots,
            r.shots_ok,
            _m(r.carry_m_mean),
            _m(r.carry_m_sd),
            _m(r.carry_m_p10),
            _m(r.carry_m_p90),
            _m(r.total_m_mean),
            _m(r.total_m_sd),
            _m(r.side_m_mean),
            _m(r.side_m_sd),
            _m(r.gap_m),
        ]
        for r in summary.itertuples()
    ]
    return "per club (shots ok; mean, sd, percentiles):\n" + _table(header, rows)


def _comparison(comparison):
    header = ["club", "quantity", "shots", "bias", "rmse"]
    rows = [
        [r.club, r.quantity, r.shots, _signed(r.bias), "-" if r.rmse != r.rmse else f"{r.rmse:.2f}"]
        for r in comparison.itertuples()
    ]
    return "model minus device (bias, rmse; in the quantity's unit):\n" + _table(header, rows)


def register(subparsers):
    """Add ``replay`` to an argparse subparsers object."""
    p = subparsers.add_parser(
        "replay",
        help="simulate each measured shot of a launch-monitor file as given",
        description="Fly every shot of a launch-monitor session as measured, without sampling, "
        "on the turf and in the weather given here, and write a Parquet of the inputs, the "
        "device's own results and the outcomes; print the session per club and the model "
        "minus the device. The file is a device's export (TrackMan, Garmin R10, Rapsodo "
        "MLM2PRO, SkyTrak, FlightScope, Foresight, Square Golf, Awesome Golf, GSPro Open "
        "Connect messages or a log of them; detected from its header) or a CSV or Parquet with "
        "columns named with their "
        "unit (ball_speed_mph, launch_deg, spin_rpm, optional spin_axis_deg, azimuth_deg). "
        "The options' values take units as in 'mcrun shot'; the file's cells are numbers in "
        "their columns' units. Beside OUT.parquet: OUT-clubs.csv (the "
        "session per club) and, where the file has the device's results, OUT-device.csv (the "
        "model minus the device); with --plot, OUT-clubs.png and OUT-device.png.",
        allow_abbrev=False,
    )
    p.add_argument("shots", metavar="SHOTS", help="measured shots: an export, .csv or .parquet")
    p.add_argument("-o", "--output", metavar="OUT.parquet", required=True, help="output file")
    p.add_argument("--force", action="store_true", help="replace an existing output file")
    p.add_argument(
        "--format",
        choices=NAMES,
        metavar="FORMAT",
        help=f"read the file as this format instead of detecting it: {', '.join(NAMES)}",
    )
    p.add_argument("--quiet", action="store_true", help="no per-club tables, only what was written")
    p.add_argument(
        "--plot",
        action="store_true",
        help="also draw the clubs (carry and total per club, the gapping chart) and the model "
        "minus the device per club, as PNGs beside the output (needs mcrun[plot])",
    )
    p.add_argument(
        "--dpi",
        type=dpi_value,
        default=plots.DEFAULT_PLOT_DPI,
        help=f"resolution of --plot, {DPI_RANGE[0]}-{DPI_RANGE[1]} (default %(default)s)",
    )
    add_conditions_options(p)
    p.set_defaults(func=_cmd_replay)
