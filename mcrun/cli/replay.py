"""``mcrun replay``: each measured shot of a launch-monitor file, simulated as given
(``mcrun.run.replay``), on the turf and in the weather of the conditions options."""

import sys
from pathlib import Path

from mcrun import status
from mcrun.api import InputError, conditions_inputs
from mcrun.cli import Interrupted
from mcrun.cli.options import add_conditions_options, conditions_kwargs
from mcrun.run import replay


def _cmd_replay(args):
    try:
        conditions = conditions_kwargs(args)
        conditions_inputs(**conditions)  # every option checked before reading the file
        destination = Path(args.output)
        if destination.suffix.lower() not in (".parquet", ".pq"):
            raise InputError(f"-o {args.output}: the output must be a .parquet file")
        frame = replay.replay_file(args.shots, destination, force=args.force, **conditions)
    except KeyboardInterrupt:
        raise Interrupted("nothing was written") from None
    bad = int((frame["status"] != status.OK).sum())
    print(f"replayed {len(frame)} shots from {args.shots}; wrote {args.output}")
    if bad:
        print(
            f"mcrun: warning: {bad} shot(s) did not end ok (status_name says why; a missing or "
            "out-of-range launch value gives invalid_input)",
            file=sys.stderr,
        )
    return 0


def register(subparsers):
    """Add ``replay`` to an argparse subparsers object."""
    p = subparsers.add_parser(
        "replay",
        help="simulate each measured shot of a launch-monitor file as given",
        description="Fly every shot of a launch-monitor session (CSV or Parquet; columns named "
        "with their unit: ball_speed_mph, launch_deg, spin_rpm, optional spin_axis_deg, "
        "azimuth_deg) as measured, without sampling, on the turf and in the weather given "
        "here, and write a Parquet of the inputs and outcomes. Values take units as in "
        "'mcrun shot'.",
        allow_abbrev=False,
    )
    p.add_argument("shots", metavar="SHOTS", help="measured shots, .csv or .parquet")
    p.add_argument("-o", "--output", metavar="OUT.parquet", required=True, help="output file")
    p.add_argument("--force", action="store_true", help="replace an existing output file")
    add_conditions_options(p)
    p.set_defaults(func=_cmd_replay)
