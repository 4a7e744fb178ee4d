"""``mcrun paper -o DIR``: Penner (2002) Figs. 3-8 redrawn from our model, and targets.md
beside the paper (``mcrun.paper``)."""

from pathlib import Path

from mcrun import paper
from mcrun.cli import CommandError
from mcrun.cli.options import DPI_RANGE, dpi_value
from mcrun.results import output


def _cmd_paper(args):
    """``mcrun paper``: write the figures and targets.md."""
    try:
        import matplotlib
    except ImportError:
        raise CommandError(paper.MISSING_MATPLOTLIB) from None
    matplotlib.use("Agg")  # headless, whatever the user's default backend
    out_dir = Path(args.out)
    # What the command writes, checked before any is drawn: each replaced only with --force
    # (a user's targets.md was written over), none a folder (a traceback, half written).
    written = [out_dir / f"{name}.png" for name in paper.FIGURES] + [out_dir / "targets.md"]
    there = [path for path in written if path.exists() or path.is_symlink()]
    folder = next((path for path in there if path.is_dir()), None)
    if folder is not None:
        raise CommandError(f"-o {out_dir}: {folder.name} is a folder: allowed: a folder where "
                           f"{folder.name} can be written")  # fmt: skip
    if there and not args.force:
        raise CommandError(f"-o {out_dir}: {there[0].name} already exists: use --force to "
                           "replace the figures and targets.md")  # fmt: skip
    output.writable_folder(out_dir, "-o")
    for path in paper.write_paper(out_dir, args.dpi):
        print(f"wrote {path}")
    return 0


def register(subparsers):
    """Add the ``paper`` subcommand to an argparse subparsers object."""
    parser = subparsers.add_parser(
        "paper",
        help="redraw Penner (2002) Figs. 3-8 and compare every number of the paper",
        description=(
            "Redraw Penner (2002), 'The run of a golf ball', Figs. 3-8 from our model "
            "(fig3.png ... fig8.png) and write targets.md: every number the paper states, the "
            "paper's value beside ours and the difference. Needs matplotlib (mcrun[plot])."
        ),
        epilog="example: mcrun paper -o paper-figures --dpi 200",
        allow_abbrev=False,
    )
    parser.add_argument(
        "-o", "--out", metavar="DIR", required=True, help="output folder (created if missing)"
    )
    parser.add_argument(
        "--force", action="store_true", help="replace the figures and targets.md if they exist"
    )
    parser.add_argument(
        "--dpi",
        type=dpi_value,
        default=paper.DEFAULT_DPI,
        help=f"resolution of the PNGs, {DPI_RANGE[0]}-{DPI_RANGE[1]} (default %(default)s)",
    )
    parser.set_defaults(func=_cmd_paper)
