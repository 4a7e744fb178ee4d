"""``mcrun warm-up``: compile the kernels into Numba's on-disk cache ahead of the first run (after
an install, an upgrade, or on a new machine), in parallel processes where there are cores, and
say what was compiled or found cached and how long each took."""

from mcrun.cli import CommandError
from mcrun.cli.options import whole
from mcrun.engine import warmup
from mcrun.putting import warmup as green

ALL = "all"


def _which(value, allowed):
    return allowed if value == ALL else (value,)


def _cmd_warm_up(args):
    if args.processes is not None:
        args.processes = whole(args.processes, "--processes", 1)
    grounds = _which(args.ground, green.GROUNDS)
    kernels = None if args.kernel == ALL else (args.kernel,)
    try:
        report = green.warm_up_all(grounds, kernels, args.processes)
    except (ValueError, warmup.WarmUpError) as err:
        what = f"--kernel {args.kernel}: " if isinstance(err, ValueError) else ""
        raise CommandError(f"{what}{err}") from None
    width = max(7, *(len(done.kernel) for done in report.kernels))
    print(f"{'ground':<8}  {'kernel':<{width}}  {'state':<8}  {'time':>8}")
    for done in report.kernels:
        state = {True: "cached", False: "compiled"}.get(done.was_cached, "ready")
        print(f"{done.ground:<8}  {done.kernel:<{width}}  {state:<8}  {done.seconds:>6.1f} s")
    n = len(report.kernels)
    compiled = sum(done.was_cached is False for done in report.kernels)
    where = "1 process" if report.processes == 1 else f"{report.processes} processes"
    print(
        f"{n} kernel{'s' if n != 1 else ''} ({compiled} compiled, {n - compiled} cached) in "
        f"{report.wall_s:.1f} s wall time on {where}"
    )
    return 0


def register(subparsers):
    """Add ``warm-up`` to an argparse subparsers object."""
    p = subparsers.add_parser(
        "warm-up",
        help="compile the kernels into the on-disk cache ahead of the first run",
        description="Compile the kernels (the engine's batch and traced batch, each for the "
        "usual flight and for the general lanes, and its run from a landing, on the plane and "
        "on a hole's terrain; the green's putt on a plane green and expected-putts map) into "
        "Numba's on-disk cache, or find them there, so that no later command compiles: one "
        "process per kind of ground, at most the cores. Says what it compiled or found cached "
        "and how long each took. The cache is __pycache__ beside mcrun's sources, or "
        "NUMBA_CACHE_DIR.",
        epilog="example: mcrun warm-up --ground plane",
        allow_abbrev=False,
    )
    p.add_argument(
        "--ground",
        choices=(*green.GROUNDS, ALL),
        default=ALL,
        help="the kind of ground: plane (no hole), terrain (a hole), green (putting) or all "
        "(default)",
    )
    p.add_argument(
        "--kernel",
        choices=(*warmup.KERNELS, *green.KERNELS, ALL),
        default=ALL,
        help="the kernel: batch (every run), traced (recorded paths), landed (the paper's "
        "bounce studies), batch_general and traced_general (those of the aerodynamic models "
        "and wind profiles that fly in the general lanes), on the plane or a terrain; putt (a "
        "putt on a plane green) and map (a green's expected-putts map), on the green; or all "
        "(default)",
    )
    p.add_argument(
        "--processes",
        metavar="N",
        help="processes at once (default: one per kind of ground, at most the cores; 1: one "
        "after the other in this process)",
    )
    p.set_defaults(func=_cmd_warm_up)
