"""``mcrun replay``: each measured shot of a launch-monitor file, simulated as given
(``mcrun.run.replay``), on the turf and in the weather of the conditions options; then the
session per club (``mcrun.run.clubs``): the gapping table and the model against the device."""

import sys
from pathlib import Path

from mcrun import status
from mcrun.api import InputError, conditions_inputs
from mcrun.cli import Interrupted
from mcrun.cli.options import add_conditions_options, conditions_kwargs
from mcrun.run import clubs, replay
from mcrun.run.monitors import NAMES


def _cmd_replay(args):
    try:
        conditions = conditions_kwargs(args)
        conditions_inputs(**conditions)  # every option checked before reading the file
        destination = Path(args.output)
        if destination.suffix.lower() not in (".parquet", ".pq"):
            raise InputError(f"-o {args.output}: the output must be a .parquet file")
        frame = replay.replay_file(
            args.shots, destination, force=args.force, format=args.format, **conditions
        )
    except KeyboardInterrupt:
        raise Interrupted("nothing was written") from None
    bad = int((frame["status"] != status.OK).sum())
    how = "detected" if frame.attrs["format_detected"] else "as asked"
    print(f"read {args.shots}: {frame.attrs['format_title']} ({how})")
    print(f"replayed {len(frame)} shots from {args.shots}; wrote {args.output}")
    if not args.quiet:
        print()
        print(_gapping(clubs.club_summary(frame)))
        comparison = clubs.device_comparison(frame)
        if len(comparison):
            print()
            print(_comparison(comparison))
    if bad:
        print(
            f"mcrun: warning: {bad} shot(s) did not end ok (status_name says why; a missing or "
            "out-of-range launch value gives invalid_input)",
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
        [r.club, r.quantity, r.shots, f"{r.bias:+.2f}", f"{r.rmse:.2f}"]
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
        "MLM2PRO, SkyTrak, FlightScope, Foresight, Square Golf, Awesome Golf, GSPro JSON "
        "lines; detected from its header) or a CSV or Parquet with columns named with their "
        "unit (ball_speed_mph, launch_deg, spin_rpm, optional spin_axis_deg, azimuth_deg). "
        "Values take units as in 'mcrun shot'.",
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
    add_conditions_options(p)
    p.set_defaults(func=_cmd_replay)
