"""``mcrun play PLAYER HOLE``: the hole solved for the player: the expected score from the tee,
the best club and aim, what the decisions save, the score distribution; every state and action
to Parquet, and a picture."""

import contextlib
import sys

from mcrun.cli import Interrupted, compile_if_needed, write_all_or_nothing
from mcrun.cli.options import whole
from mcrun.quantities import InputError
from mcrun.units import parse_quantity


def _hole_of(spec):
    """The Hole of a hole TOML file, or of a scenario (a file or a library name) with a [hole]."""
    from mcrun.hole.errors import HoleError
    from mcrun.hole.hole import load_hole, read_hole_file
    from mcrun.putting.on_hole import check_putting
    from mcrun.run import scenario as sc

    try:
        table, _ = read_hole_file(spec)
        if "scenario" not in table and "launch" not in table:
            return check_putting(load_hole(spec))
    except HoleError:
        pass
    scenario = sc.load(spec)
    if scenario.hole is None:
        raise InputError(f"HOLE {spec}: a scenario without a [hole]: give a hole file")
    return scenario.hole


def _cmd_play(args):
    from mcrun.play import load_player, play_hole
    from mcrun.run import aim

    if args.output is not None:
        destination = aim.check_output(args.output, args.force, "-o", (".parquet",), ".parquet")
    if args.plot is not None:
        from mcrun.report import style

        style.require_matplotlib("play --plot")
        aim.check_output(args.plot, args.force, "--plot", (".png",), ".png")
    player = load_player(args.player)
    hole = _hole_of(args.hole)
    n = whole(args.n, "-n", 2)
    plays = whole(args.plays, "--plays", 1)
    coarse = parse_quantity(args.coarse, "length", "--coarse")
    fine = parse_quantity(args.fine, "length", "--fine")
    for name, value in (("--coarse", coarse), ("--fine", fine)):
        if not 1.0 <= value <= 50.0:
            raise InputError(f"{name} {value:g} m: allowed: 1 m to 50 m")
    seed = None if args.seed is None else whole(args.seed, "--seed", 0)
    others = []
    if args.vs is not None:
        others.append(load_player(args.vs))
    if args.longer is not None:
        from mcrun.play.player import longer

        yards = parse_quantity(args.longer, "length", "--longer") / 0.9144
        if not -100.0 <= yards <= 100.0:
            raise InputError(f"--longer {args.longer}: allowed: -100 yd to 100 yd")
        others.append(longer(player, 0, yards))
    print(f"play: {hole.name or hole.source} (par {hole.par or '?'}, {hole.length_m:.0f} m) as "
          f"{player.name} ({len(player.clubs)} clubs); {n} shots an action",
          file=sys.stderr, flush=True)  # fmt: skip
    compile_if_needed("terrain")  # said apart from the solver's own time
    from tqdm import tqdm

    bar = tqdm(unit="action", file=sys.stderr, leave=False, dynamic_ncols=True)
    with contextlib.ExitStack() as stack:
        client = None
        if args.dask is not None:
            from distributed import Client

            from mcrun.run import distributed

            workers = None if args.workers is None else whole(args.workers, "--workers", 1)
            cluster = stack.enter_context(distributed.local_cluster(workers))
            client = stack.enter_context(Client(cluster))
        try:
            result = play_hole(player, hole, n=n, seed=seed, coarse_m=coarse, fine_m=fine,
                               plays=plays, progress=lambda k: bar.update(k - bar.n),
                               client=client)  # fmt: skip
            others = [play_hole(o, hole, n=n, seed=seed, coarse_m=coarse, fine_m=fine,
                                plays=plays, client=client) for o in others]  # fmt: skip
        except KeyboardInterrupt:
            raise Interrupted("nothing was written") from None
        finally:
            bar.close()
    tr, s = result.transitions, result.solution
    print(f"{result.lattice.size:,} states (every {coarse:g} m, every {fine:g} m near the pin), "
          f"{len(tr.actions)} actions, {tr.shots_flown:,} shots; solved in {s.sweeps} sweeps, "
          f"{result.seconds:.1f} s")  # fmt: skip
    best = result.tee_rows()[0]
    print(f"expected score from the tee: {result.tee_value:.3f} +- {result.tee_se:.3f} "
          f"(seed {result.seed}); best: {best[1]}")  # fmt: skip
    for name, (value, saved) in result.savings().items():
        print(f"against {name}: {value:.3f}, the best saves {saved:.3f}")
    shares = result.score_shares()
    listed = ", ".join(f"{k} {100 * v:.1f} %" for k, v in shares.items())
    print(f"{len(result.scores):,} plays: {listed}; mean {result.scores.mean():.3f}")
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
        None if args.output is None else lambda: write_play(result, destination, args.force),
        picture,
        args.force,
    )
    for path in (args.output, args.plot):
        if path is not None:
            print(f"wrote {path}")
    return 0


def write_play(result, path, force=False):
    """Every state and action of ``result`` to Parquet, with its provenance."""
    from mcrun.results import output

    frame = result.actions_frame()
    states = result.states_frame()
    frame.insert(3, "lie", states["lie"].to_numpy()[frame["state"].to_numpy()])
    frame["state_expected_strokes"] = states["expected_strokes"].to_numpy()[frame["state"]]
    provenance = {
        "player": result.player.name, "player_source": result.player.source,
        "spread": list(result.player.spread), "hole": result.hole.source,
        "n": result.n, "seed": result.seed, "states": result.lattice.size,
        "sweeps": result.solution.sweeps, "tee_expected_strokes": result.tee_value,
        "tee_expected_strokes_se": result.tee_se, "seconds": round(result.seconds, 3),
        "attribution": result.hole.attribution or "", "file": "play",
    }  # fmt: skip
    with output.AtomicFile(path, force=force) as target:
        output.write_table(target.tmp, frame, output.encode_provenance(provenance))
        target.commit()


def register(subparsers):
    p = subparsers.add_parser(
        "play",
        help="solve a hole for a player: expected strokes, club and aim from everywhere",
        description="Solve HOLE (a hole file, or a scenario with a [hole]) for PLAYER (a "
        "preset: tour, scratch, bogey; or a player file: a scenario of clubs without a hole): "
        "every club and aim flown N times from every state of the hole, value iteration to the "
        "player's expected strokes from everywhere and the best club and aim; the expected "
        "score from the tee, the strokes the decisions save against simple policies, and the "
        "score distribution of the policy played from the tee.",
        epilog="example: mcrun play pga-tour-bag scenarios/holes/riverside-9.toml",
        allow_abbrev=False,
    )
    p.add_argument("player", metavar="PLAYER")
    p.add_argument("hole", metavar="HOLE")
    p.add_argument("-n", default="100", metavar="N", help="shots of each action (100)")
    p.add_argument("--seed", metavar="S", help="random seed (the player's)")
    p.add_argument("--coarse", default="8m", help="states' spacing (8m)")
    p.add_argument("--fine", default="3m", help="near the pin (3m)")
    p.add_argument("--plays", default="4000", help="plays of the policy (4000)")
    p.add_argument("--vs", metavar="PLAYER2", help="a second player on the same hole")
    p.add_argument("--longer", metavar="YD", help="and the player with a driver YD longer: 10yd")
    p.add_argument("--dask", choices=["local"], help="fly the shots on a local Dask cluster")
    p.add_argument("--workers", metavar="W", help="its workers (default: the cores)")
    p.add_argument("-o", "--output", metavar="FILE", help="every state and action (.parquet)")
    p.add_argument("--plot", metavar="PNG", help="the picture")
    p.add_argument("--force", action="store_true", help="replace existing outputs")
    p.set_defaults(func=_cmd_play)
