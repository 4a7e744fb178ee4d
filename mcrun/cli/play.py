"""``mcrun play PLAYER HOLE``: the hole solved for the player: the expected score from the tee,
the best club and aim, what the decisions save, the score distribution; every state and action
to Parquet, and a picture."""

import contextlib
import sys

from mcrun.cli import Interrupted, compile_if_needed, write_all_or_nothing
from mcrun.cli.options import local_workers, whole, with_unit
from mcrun.putting.putter import PUTTERS
from mcrun.quantities import InputError
from mcrun.units import parse_quantity

# Top-level tables or keys of a scenario file (a hole file has the hole's keys, or a [hole]).
_SCENARIO_KEYS = ("scenario", "launch", "club", "group", "sweep", "weather", "models")
# The names of ``plan_play``'s arguments on this command line.
OPTION_NAMES = {"n": "-n", "plays": "--plays", "coarse_m": "--coarse", "fine_m": "--fine"}


def _is_hole_file(spec):
    """Whether ``spec`` is a hole TOML file (not a scenario, nor a library name): a TOML file
    whose top level has none of a scenario's tables."""
    import tomllib
    from pathlib import Path

    try:
        with Path(spec).open("rb") as f:
            top = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError, UnicodeDecodeError):
        return False  # a library name, or a file the scenario reader explains
    return not any(key in top for key in _SCENARIO_KEYS)


def _hole_of(spec):
    """The Hole of a hole TOML file (its own errors said as they are: no green, a pin off the
    green), or of a scenario (a file or a library name) with a [hole]."""
    from mcrun.cli.hole import say_skipped
    from mcrun.hole.hole import load_hole
    from mcrun.putting.on_hole import check_putting
    from mcrun.run import scenario as sc

    if _is_hole_file(spec):
        hole = load_hole(spec)
    else:
        hole = sc.load(spec).hole
        if hole is None:
            raise InputError(f"HOLE {spec}: a scenario without a [hole]: give a hole file")
    say_skipped(hole)
    return check_putting(hole)


def _workers(args):
    """The workers of ``--dask local`` (given, else the cores); 0 without --dask (the shots are
    flown on this process's threads)."""
    if args.dask is None:
        if args.workers is not None:
            raise InputError(
                f"--workers {args.workers}: is for --dask local (without it the shots are "
                "flown on this process's threads): give --dask local --workers N"
            )
        return 0
    from mcrun.run import distributed

    distributed._dask()  # installed, else one line: pip install 'mcrun[dask]'
    workers = local_workers(args.workers)
    return distributed.local_cores() if workers is None else workers


def _score_line(result):
    """The plays' score distribution: against par, or by strokes where the par is not known."""
    if result.hole.par is None:
        shares = result.stroke_shares()
        listed = ", ".join(f"{k} strokes {100 * v:.1f} %" for k, v in shares.items())
        return (f"{len(result.scores):,} plays: {listed}; mean {result.scores.mean():.3f} "
                "(the hole's par is not known)")  # fmt: skip
    shares = result.score_shares()
    listed = ", ".join(f"{k} {100 * v:.1f} %" for k, v in shares.items())
    return f"{len(result.scores):,} plays: {listed}; mean {result.scores.mean():.3f}"


def checked_outputs(args, command):
    """The ``-o`` Parquet destination (None without one) and the ``--plot`` PNG of ``command``
    ("play", "rate") checked before any work (matplotlib there, nothing overwritten unasked)."""
    from mcrun.run import aim

    destination = None
    if args.output is not None:
        destination = aim.check_output(args.output, args.force, "-o", (".parquet",), ".parquet")
    if args.plot is not None:
        from mcrun.report import style

        style.require_matplotlib(f"{command} --plot")
        aim.check_output(args.plot, args.force, "--plot", (".png",), ".png")
    return destination


def solve_settings(args):
    """(workers, n, plays, coarse_m, fine_m, seed) of a solving command line (``play``,
    ``rate``), each checked: one line naming the option otherwise."""
    workers = _workers(args)
    n = whole(args.n, "-n", 2)
    plays = whole(args.plays, "--plays", 1)
    coarse = parse_quantity(args.coarse, "length", "--coarse")
    fine = parse_quantity(args.fine, "length", "--fine")
    for name, value in (("--coarse", coarse), ("--fine", fine)):
        if not 1.0 <= value <= 50.0:
            raise InputError(f"{name} {value:g} m: allowed: 1 m to 50 m")
    seed = None if args.seed is None else whole(args.seed, "--seed", 0)
    return workers, n, plays, coarse, fine, seed


def dask_client(stack, args, workers):
    """The client of ``--dask local`` (its cluster of ``workers`` closed with ``stack``, a
    contextlib.ExitStack); None without it."""
    if args.dask is None:
        return None
    from mcrun.run import distributed

    cluster = stack.enter_context(distributed.local_cluster(workers))
    return stack.enter_context(distributed._dask().Client(cluster))


def _cmd_play(args):
    from mcrun.play import load_player, plan_play, solve_planned

    destination = checked_outputs(args, "play")
    workers, n, plays, coarse, fine, seed = solve_settings(args)
    player = load_player(args.player, putter=args.putter)
    hole = _hole_of(args.hole)
    players = [player]
    if args.vs is not None:
        try:
            players.append(load_player(args.vs))
        except InputError as err:  # (the first player's is the positional argument)
            raise InputError(f"--vs: {err}") from None
    if args.longer is not None:
        from mcrun.play.calibration import longer

        yards = with_unit(args.longer, "length", "--longer", "10yd") / 0.9144
        if not -100.0 <= yards <= 100.0:
            raise InputError(f"--longer {args.longer}: allowed: -100 yd to 100 yd")
        players.append(longer(player, 0, yards))
    # Every player's solve planned and checked before any is flown: one that would not fit
    # beside those before it (whose results are kept) is refused before the first starts.
    compile_if_needed("plane")  # the plans fly each club on the level
    from mcrun.run.aim import available_memory

    memory = available_memory()
    plans = []
    for one in players:
        left = None if memory is None else memory - sum(p.bytes for p in plans)
        plans.append(plan_play(one, hole, n=n, seed=seed, coarse_m=coarse, fine_m=fine,
                               plays=plays, workers=workers, memory=left,
                               names=OPTION_NAMES))  # fmt: skip
    print(f"play: {hole.name or hole.source} (par {hole.par or '?'}, {hole.length_m:.0f} m) as "
          f"{player.name} ({len(player.clubs)} clubs, putter {player.putter}); {n:,} shots an "
          "action",
          file=sys.stderr, flush=True)  # fmt: skip
    for planned in plans:
        print(planned.line(), file=sys.stderr, flush=True)
    compile_if_needed("terrain")  # said apart from the solver's own time
    from tqdm import tqdm

    results = []
    with contextlib.ExitStack() as stack:
        client = dask_client(stack, args, workers)
        try:
            for planned in plans:
                bar = tqdm(total=len(planned.actions), unit="action", file=sys.stderr,
                           leave=False, dynamic_ncols=True, disable=None)  # fmt: skip
                try:
                    results.append(
                        solve_planned(
                            planned,
                            client=client,
                            progress=lambda k, bar=bar: bar.update(k - bar.n),
                        )
                    )
                finally:
                    bar.close()
        except KeyboardInterrupt:
            raise Interrupted("nothing was written") from None
    result, others = results[0], results[1:]
    tr, s = result.transitions, result.solution
    print(f"{result.lattice.size:,} states (every {coarse:g} m, every {fine:g} m near the pin), "
          f"{len(tr.actions)} actions, {tr.shots_flown:,} shots; solved in {s.sweeps} sweeps, "
          f"{result.seconds:.1f} s")  # fmt: skip
    best = result.tee_rows()[0]
    print(f"expected score from the tee: {result.tee_value:.3f} +- {result.tee_se:.3f} "
          f"(seed {result.seed}); best: {best[1]}")  # fmt: skip
    for name, (value, saved) in result.savings().items():
        print(f"against {name}: {value:.3f}, the best saves {saved:.3f}")
    print(_score_line(result))
    for o in results:
        note = o.gap_note()
        if note is not None:
            print(f"mcrun: warning: {o.player.name}: {note}", file=sys.stderr)
    for o in others:
        other = o.player
        print(f"{other.name}: {o.tee_value:.3f} +- {o.tee_se:.3f} from the tee (best: "
              f"{o.tee_rows()[0][1]}), {o.tee_value - result.tee_value:+.3f} against "
              f"{player.name}")  # fmt: skip
    if args.output is None and args.plot is None:
        return 0
    picture = None
    if args.plot is not None:
        from mcrun.report import play_plot

        picture = (args.plot, lambda: play_plot.play_figure(result), play_plot.DPI)
    write_all_or_nothing(
        None
        if args.output is None
        else lambda: write_play(
            result, destination, args.force, {"coarse_m": coarse, "fine_m": fine, "plays": plays}
        ),
        picture,
        args.force,
    )
    for path in (args.output, args.plot):
        if path is not None:
            print(f"wrote {path}")
    return 0


def write_play(result, path, force=False, settings=None):
    """Every state and action of ``result`` to Parquet, with its provenance (``settings``: the
    solve's lattice and plays, ``coarse_m``, ``fine_m`` and ``plays``, which it was run with)."""
    from mcrun.results import output

    frame = result.actions_frame()
    states = result.states_frame()
    frame.insert(3, "lie", states["lie"].to_numpy()[frame["state"].to_numpy()])
    frame["state_expected_strokes"] = states["expected_strokes"].to_numpy()[frame["state"]]
    provenance = {
        "player": result.player.name, "player_source": result.player.source,
        "putter": result.player.putter,
        "spread": list(result.player.spread), "hole": result.hole.source,
        "n": result.n, "seed": result.seed, "states": result.lattice.size,
        "sweeps": result.solution.sweeps, "tee_expected_strokes": result.tee_value,
        "tee_expected_strokes_se": result.tee_se, "seconds": round(result.seconds, 3),
        "attribution": result.hole.attribution or "", "file": "play",
        **(settings or {}), "versions": output.versions(),
    }  # fmt: skip
    with output.AtomicFile(path, force=force) as target:
        output.write_table(target.tmp, frame, output.encode_provenance(provenance))
        target.commit()


def register(subparsers):
    p = subparsers.add_parser(
        "play",
        help="solve a hole for a player: expected strokes, club and aim from everywhere",
        description="Solve HOLE (a hole file, or a scenario with a [hole]) for PLAYER (a "
        "preset: tour, scratch, bogey, scratch-woman, bogey-woman; or a player file: a "
        "scenario of clubs without a hole): "
        "every club and aim flown N times from every state of the hole, value iteration to the "
        "player's expected strokes from everywhere and the best club and aim; the expected "
        "score from the tee, the strokes the decisions save against simple policies, and the "
        "score distribution of the policy played from the tee.",
        epilog="example: mcrun play pga-tour-bag scenarios/holes/riverside-9.toml",
        allow_abbrev=False,
    )
    p.add_argument(
        "player",
        metavar="PLAYER",
        help="a preset (tour, scratch, bogey, "
        "scratch-woman, bogey-woman), a player file or a library scenario's name",
    )
    p.add_argument("hole", metavar="HOLE", help="a hole file, or a scenario with a [hole]")
    p.add_argument("-n", default="100", metavar="N", help="shots of each action (100)")
    p.add_argument("--seed", metavar="S", help="random seed (the player's)")
    p.add_argument("--coarse", default="8m", help="states' spacing (8m)")
    p.add_argument("--fine", default="3m", help="near the pin (3m)")
    p.add_argument("--plays", default="4000", help="plays of the policy (4000)")
    p.add_argument(
        "--putter",
        choices=list(PUTTERS),
        help="the player's putter on the green "
        "(a preset's own: tour, scratch, 15-handicap for bogey; a woman's her man's; a "
        "file's: tour)",
    )
    p.add_argument("--vs", metavar="PLAYER2", help="a second player on the same hole")
    p.add_argument("--longer", metavar="YD", help="and the player with a driver YD longer: 10yd")
    p.add_argument("--dask", choices=["local"], help="fly the shots on a local Dask cluster")
    p.add_argument(
        "--workers",
        metavar="W",
        help="its workers (default: the cores; at most 4 a core, as many as the memory holds)",
    )
    p.add_argument("-o", "--output", metavar="FILE", help="every state and action (.parquet)")
    p.add_argument("--plot", metavar="PNG", help="the picture")
    p.add_argument("--force", action="store_true", help="replace existing outputs")
    p.set_defaults(func=_cmd_play)
