"""``mcrun plot`` and ``mcrun report``: the pictures of a finished run (``mcrun.report.plots``)
and its self-contained HTML page (``mcrun.report.html``)."""

import sys
from pathlib import Path

from mcrun.cli import Interrupted
from mcrun.cli.options import DPI_RANGE, dpi_value
from mcrun.report import hole_plots, html, plots, replay_plots, style
from mcrun.report.run_view import PlotError
from mcrun.results import reader


def _cmd_plot(args):
    if replay_plots.is_replay(args.run_dir):
        for path in replay_plots.plot_replay_file(args.run_dir, args.out, args.dpi):
            print(f"wrote {path}")
        return 0
    if Path(args.run_dir).is_file():
        raise PlotError(replay_plots.not_a_replay(args.run_dir))
    try:
        written = plots.write_plots(
            args.run_dir, args.out, args.dpi, point_figures=hole_plots.point_figures,
            progress=sys.stderr.isatty(),
        )  # fmt: skip
    except style.WrittenThenInterrupted as err:
        raise Interrupted(f"after writing the {len(err.paths)} pictures") from None
    except KeyboardInterrupt:
        raise Interrupted("nothing was written") from None
    _say_if_unknown(args.run_dir)
    for path, _ in written:
        print(f"wrote {path}")
    return 0


def _add_plot(subparsers):
    p = subparsers.add_parser(
        "plot",
        help="plot a finished run: positions, distances, trajectories, the sweep",
        description="Write one PNG per plot of a run folder written by 'mcrun run': per point, "
        "the landing and final positions with the 68 % and 95 % ellipses and the target "
        "(pointNN-positions.png), histograms of carry, run and total (pointNN-distances.png), "
        "side and top views of sampled trajectories when the run wrote them "
        "(pointNN-trajectories.png); for a run on a hole, the hole map with the landing and "
        "finish positions, the 50 % and 95 % ellipses of the finish, the pin, the aim line "
        "and each zone's share (pointNN-hole.png); for several points, the summary against "
        "the swept parameter or per group (summary.png) and every point's finish "
        "(finish.png). Reads "
        "only the columns it draws, one point at a time: histograms and densities are "
        "binned over every shot, trajectories are the first of each point. Given a file written "
        "by 'mcrun replay' instead, its clubs and its model minus the device (as 'mcrun "
        "replay --plot'; default: beside the file). Needs matplotlib (mcrun[plot]).",
        epilog="example: mcrun plot runs/pga-driver-2019 -o plots",
        allow_abbrev=False,
    )
    p.add_argument(
        "run_dir",
        metavar="RUN_DIR",
        help="a folder written by 'mcrun run', or a .parquet written by 'mcrun replay'",
    )
    p.add_argument(
        "-o",
        "--out",
        metavar="DIR",
        help=f"output folder (created if missing; default RUN_DIR/{plots.PLOTS_FOLDER})",
    )
    p.add_argument(
        "--dpi",
        type=dpi_value,
        default=plots.DEFAULT_PLOT_DPI,
        help=f"resolution, {DPI_RANGE[0]}-{DPI_RANGE[1]} (default %(default)s)",
    )
    p.set_defaults(func=_cmd_plot)


def _say_if_unknown(run_dir):
    """A note on stderr where the run's files hold no provenance (rewritten by a tool that
    keeps no key-value metadata): what is drawn is the files' values, of a run unknown."""
    if not reader.open_run(run_dir).provenance:
        print(f"mcrun: note: {run_dir}: its files hold no mcrun provenance (rewritten by another "
              "tool?): the scenario, seed and versions are unknown", file=sys.stderr)  # fmt: skip


def _cmd_report(args):
    if replay_plots.is_replay(args.run_dir):  # ("not a folder: give the folder ...")
        raise PlotError(f"{args.run_dir}: a file of 'mcrun replay', which has no report: draw "
                        f"its clubs with 'mcrun plot {args.run_dir}'")  # fmt: skip
    path = html.write_report(args.run_dir, args.out, args.dpi)
    _say_if_unknown(args.run_dir)
    print(f"wrote {path}")
    return 0


def _add_report(subparsers):
    p = subparsers.add_parser(
        "report",
        help="one self-contained HTML page of a finished run",
        description="Write one HTML page of a run folder written by 'mcrun run': the scenario, "
        "the summary tables (on a hole, each zone's share first, and the map's "
        "attribution), the plots of 'mcrun plot' embedded as images, and the "
        "provenance (seed, N, versions, times, threads, backend). Self-contained: inline CSS, "
        "no script, no external resource, for sharing a study with someone who will not run "
        "Python. Needs matplotlib (mcrun[plot]).",
        epilog="example: mcrun report runs/pga-driver-2019 -o pga-driver.html",
        allow_abbrev=False,
    )
    p.add_argument("run_dir", metavar="RUN_DIR", help="a folder written by 'mcrun run'")
    p.add_argument(
        "-o",
        "--out",
        metavar="FILE",
        help=f"the HTML file (replaced if it exists; default RUN_DIR/{html.REPORT_FILE})",
    )
    p.add_argument(
        "--dpi",
        type=dpi_value,
        default=html.DEFAULT_REPORT_DPI,
        help=f"resolution of the embedded plots, {DPI_RANGE[0]}-{DPI_RANGE[1]} "
        "(default %(default)s)",
    )
    p.set_defaults(func=_cmd_report)


def register(subparsers):
    """Add ``plot`` and ``report`` to an argparse subparsers object."""
    _add_plot(subparsers)
    _add_report(subparsers)
