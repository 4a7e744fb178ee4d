"""``mcrun rate COURSE``: a course rated by simulating the handicap system's model players: every
hole solved for the scratch and the bogey player, their Course and Bogey Ratings and the Slope
Rating (``mcrun.play.rating``); a table on screen, a row per hole and player to Parquet."""

import contextlib
import sys
from pathlib import Path

import numpy as np

from mcrun.cli import Interrupted, compile_if_needed, write_all_or_nothing
from mcrun.cli.options import whole
from mcrun.cli.play import OPTION_NAMES, checked_outputs, dask_client, solve_settings
from mcrun.quantities import InputError
from mcrun.units import parse_quantity

FULL_COURSE = 18  # holes: what a Slope Rating and the length rule are of
MARGIN_M = 60.0  # the ground kept around each hole's line (as the library's hole files)
CELL_M = 0.5


def holes_wanted(spec, count, where="--holes"):
    """The hole numbers (1-based) of ``spec`` ("1-9", "1,3,10-12"; None: all ``count``)."""
    if spec is None:
        return list(range(1, count + 1))
    numbers = []
    for part in str(spec).split(","):
        lo, _, hi = part.strip().partition("-")
        try:
            first, last = int(lo), int(hi or lo)
        except ValueError:
            raise InputError(f"{where} {spec!r}: allowed: hole numbers 1-{count} as 1-9 or "
                             "1,3,10-12") from None  # fmt: skip
        if not 1 <= first <= last <= count:
            raise InputError(f"{where} {spec!r}: allowed: hole numbers 1-{count} as 1-9 or "
                             f"1,3,10-12 (the map has {count} holes)")  # fmt: skip
        numbers.extend(range(first, last + 1))
    return sorted(set(numbers))


def read_scorecard(path, count):
    """{hole number: yards} of a scorecard CSV (``hole,yards``: a row per hole, its number the
    hole's position in the map, 1-``count``, its length in yards along its line of play);
    InputError naming the file, the row and the field."""
    import csv

    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8-sig") as f:
            rows = list(csv.DictReader(f))
            header = rows[0].keys() if rows else None
    except OSError as err:
        raise InputError(f"--scorecard {path}: {err.strerror}") from None
    except UnicodeDecodeError:
        raise InputError(f"--scorecard {path}: not a text file: a CSV of hole,yards") from None
    if not rows or set(header) != {"hole", "yards"}:
        raise InputError(f"{path}: a scorecard is a CSV with the columns hole,yards and a row "
                         "per hole")  # fmt: skip
    yards = {}
    for k, row in enumerate(rows, start=2):
        try:
            hole, length = int(row["hole"]), float(row["yards"])
        except (TypeError, ValueError):
            raise InputError(f"{path} row {k}: hole {row['hole']!r}, yards {row['yards']!r}: "
                             "allowed: a hole number and a length in yards") from None  # fmt: skip
        if not 1 <= hole <= count or hole in yards:
            raise InputError(f"{path} row {k}: hole {hole}: allowed: each hole of the map once, "
                             f"1-{count}")  # fmt: skip
        if not 50.0 <= length <= 800.0:
            raise InputError(f"{path} row {k}: yards {length:g}: allowed: 50 to 800")
        yards[hole] = length
    return yards


def _tee_at(line, yards, where):
    """The (lon, lat) of the point of a hole's ``line`` (a ``HoleLine``) ``yards`` before its
    end along it; InputError where the line is shorter."""
    from mcrun.hole.geo import Frame

    frame = Frame(*line.lonlat[0], 0.0)
    x, y = frame.to_xy(line.lonlat[:, 0], line.lonlat[:, 1])
    xy = np.column_stack([x, y])
    along = np.r_[0.0, np.cumsum(np.hypot(*np.diff(xy, axis=0).T))]
    back = along[-1] - yards * 0.9144
    if back < -1.0:
        raise InputError(f"{where}: {yards:g} yd is longer than the hole's line "
                         f"({along[-1] / 0.9144:.0f} yd along it from its first point): a tee "
                         "set on the scorecard must lie on the hole's line")  # fmt: skip
    back = max(back, 0.0)
    k = min(int(np.searchsorted(along, back, side="right")) - 1, len(along) - 2)
    t = (back - along[k]) / (along[k + 1] - along[k])
    point = xy[k] + t * (xy[k + 1] - xy[k])
    lon, lat = frame.to_lonlat(point[0], point[1])
    return [float(lon), float(lat)]


def course_holes(path, spec=None, putting=None, scorecard=None):
    """The Holes of the course map ``path`` (a GeoJSON course map, as ``mcrun hole`` reads),
    those of ``spec`` (``holes_wanted``), in order, each checked as ``mcrun play`` checks a
    hole; a hole without a par in the map gets one by its line's length
    (``rating.par_by_length``); ``putting``: the holes' ``[hole.putting]`` settings
    (``hole.PUTTING_KEYS``: the maps of their greens, for a putter other than the Tour's);
    ``scorecard``: a CSV of a tee set (``read_scorecard``): each hole's tee that far from the
    end of its line, along it (the holes on it, where ``spec`` is None).
    Returns (their numbers, the holes, the numbers whose par was taken from their length)."""
    from mcrun.hole.hole import hole_from_table
    from mcrun.hole.osm import read_course
    from mcrun.play.rating import par_by_length
    from mcrun.putting.on_hole import check_putting

    path = Path(path)
    course = read_course(path)
    if not course.holes:
        raise InputError(f"{path}: no golf=hole lines: a course map needs its holes' lines "
                         "(tee to green) to be rated")  # fmt: skip
    yards = None if scorecard is None else read_scorecard(scorecard, len(course.holes))
    numbers = holes_wanted(spec, len(course.holes))
    if yards is not None:
        if spec is None:
            numbers = sorted(yards)
        missing = [k for k in numbers if k not in yards]
        if missing:
            raise InputError(f"{scorecard}: no row for hole {missing[0]}: the scorecard must "
                             "give every hole rated")  # fmt: skip
    holes, by_length = [], []
    for number in numbers:
        where = f"{path} hole {number}"
        table = {"map": path.name, "hole": f"#{number}", "cell_m": CELL_M, "margin_m": MARGIN_M}
        if putting:
            table["putting"] = dict(putting)
        hole = hole_from_table(table, path.parent, where)
        if hole.par is None:
            table["par"] = par_by_length(hole.length_m)
            by_length.append(number)
        if yards is not None:
            table["tee"] = _tee_at(course.hole(f"#{number}"), yards[number],
                                   f"{scorecard} hole {number}")  # fmt: skip
        if "par" in table or "tee" in table:
            hole = hole_from_table(table, path.parent, where)
        holes.append(check_putting(hole))
    return numbers, holes, by_length


def _cmd_rate(args):
    from mcrun.play.rating import BETTER_HALF, EXPECTED, plan_rating, rate_planned

    destination = checked_outputs(args, "rate")
    workers, n, plays, coarse, fine, seed = solve_settings(args)
    putting = {}
    if args.putts is not None:
        putting["n"] = whole(args.putts, "--putts", 2)
    if args.green_resolution is not None:
        resolution = parse_quantity(args.green_resolution, "length", "--green-resolution")
        if not 0.05 <= resolution <= 5.0:
            raise InputError(f"--green-resolution {resolution:g} m: allowed: 0.05 m to 5 m")
        putting["resolution_m"] = resolution
    numbers, holes, by_length = course_holes(args.course, args.holes, putting, args.scorecard)
    compile_if_needed("plane")  # the plans fly each club on the level
    # Every solve planned before the first is flown: a bad hole or one too big is refused here.
    plans = plan_rating(holes, n=n, seed=seed, coarse_m=coarse, fine_m=fine, plays=plays,
                        numbers=numbers, obstacles=args.obstacles, workers=workers,
                        names=OPTION_NAMES)  # fmt: skip
    length_yd = sum(h.length_m for h in holes) / 0.9144
    tees = "the back tees" if args.scorecard is None else f"the tees of {args.scorecard}"
    print(f"rate: {args.course}: {len(holes)} holes, {length_yd:,.0f} yd from {tees} (tee to "
          f"pin); scratch and bogey, {n:,} shots an action", file=sys.stderr,
          flush=True)  # fmt: skip
    if by_length:
        print(f"rate: par by length (the map has none) for hole(s) "
              f"{', '.join(map(str, by_length))}", file=sys.stderr, flush=True)  # fmt: skip
    compile_if_needed("terrain")
    from tqdm import tqdm

    with contextlib.ExitStack() as stack:
        client = dask_client(stack, args, workers)
        solves = sum(len(planned) for planned in plans.values())
        bar = tqdm(total=solves, unit="solve", file=sys.stderr,
                   leave=False, dynamic_ncols=True)  # fmt: skip
        stack.callback(bar.close)
        try:
            rating = rate_planned(holes, plans, client=client,
                                  progress=lambda *_: bar.update(1))  # fmt: skip
        except KeyboardInterrupt:
            raise Interrupted("nothing was written") from None
    frame = rating.frame()
    costs = "  obstacles cost: scratch, bogey" if args.obstacles else ""
    print(f"{'hole':>4} {'par':>3} {'yd':>5}  {'scratch':>13}  {'bogey':>13}  bogey - scratch"
          f"{costs}")  # fmt: skip
    for k, hole in enumerate(holes):
        s, b = (rating.scores[p][k] for p in rating.players)
        cost = (f"  {s.obstacles_strokes:+.3f}, {b.obstacles_strokes:+.3f}" if args.obstacles
                else "")  # fmt: skip
        print(f"{s.hole:>4} {hole.par:>3} {hole.length_m / 0.9144:>5.0f}  "
              f"{s.expected_strokes:6.3f} +- {s.expected_strokes_se:.3f}  "
              f"{b.expected_strokes:6.3f} +- {b.expected_strokes_se:.3f}  "
              f"{b.expected_strokes - s.expected_strokes:+15.3f}{cost}")  # fmt: skip
    full = len(holes) == FULL_COURSE
    for reading in (EXPECTED, BETTER_HALF):
        cr, br = (rating.rating(p, reading) for p in rating.players)
        slope = f", Slope Rating {rating.slope(reading)}" if full else ""
        print(f"{reading}: Course Rating {cr:.1f}, Bogey Rating {br:.1f}{slope}")
    if full:
        print(f"(par {sum(h.par for h in holes)}; the system's length rating: scratch "
              f"{length_yd / 220 + 40.9:.1f}, bogey {length_yd / 160 + 50.7:.1f})")  # fmt: skip
    else:
        print(f"(par {sum(h.par for h in holes)}; the Slope Rating and the length rating are "
              f"of {FULL_COURSE} holes)")  # fmt: skip
    if args.output is None and args.plot is None:
        return 0
    picture = None
    if args.plot is not None:
        from mcrun.report import rating_plot

        title = f"{Path(args.course).name}: {len(holes)} holes, {length_yd:,.0f} yd"
        picture = (args.plot, lambda: rating_plot.rating_figure(rating, title), rating_plot.DPI)
    write_all_or_nothing(
        None if args.output is None else lambda: write_rating(rating, frame, destination, args, n),
        picture,
        args.force,
    )
    for path in (args.output, args.plot):
        if path is not None:
            print(f"wrote {path}")
    return 0


def write_rating(rating, frame, path, args, n):
    """A row per hole and player to Parquet, with the ratings and the provenance."""
    from mcrun.play.rating import BETTER_HALF, EXPECTED
    from mcrun.results import output

    provenance = {"course": str(args.course), "holes": len(rating.holes),
                  "scorecard": None if args.scorecard is None else str(args.scorecard),
                  "players": list(rating.players), "seed": rating.seed, "n": n,
                  "length_yd": rating.length_yd,
                  "attribution": rating.holes[0].attribution or "", "file": "rating"}  # fmt: skip
    for reading, key in ((EXPECTED, "expected"), (BETTER_HALF, "better_half")):
        for player in rating.players[:2]:
            provenance[f"{player}_rating_{key}"] = round(rating.rating(player, reading), 1)
        if len(rating.holes) == FULL_COURSE:
            provenance[f"slope_rating_{key}"] = rating.slope(reading)
    with output.AtomicFile(path, force=args.force) as target:
        output.write_table(target.tmp, frame, output.encode_provenance(provenance))
        target.commit()


def register(subparsers):
    p = subparsers.add_parser(
        "rate",
        help="rate a course from its map: Course Rating and Slope by simulating scratch and bogey",
        description="Rate COURSE (a GeoJSON course map with its holes' lines, as 'mcrun hole' "
        "reads) by solving every hole for the handicap system's model players, scratch and "
        "bogey (each hole's line from its first point, the back tee, to its pin): their "
        "expected strokes per hole, the Course and Bogey Ratings as the expected score and as "
        "the better half's mean of their rounds, and the Slope Rating.",
        epilog="example: mcrun rate scenarios/holes/riverside-zagreb.osm.geojson --holes 1-3",
        allow_abbrev=False,
    )
    p.add_argument("course", metavar="COURSE")
    p.add_argument("--holes", metavar="SPEC", help="the holes to rate: 1-9, 1,3,10-12 (all)")
    p.add_argument("--scorecard", metavar="CSV", help="a tee set: hole,yards (the back tees: "
                   "each hole line's first point)")  # fmt: skip
    p.add_argument("-n", default="100", metavar="N", help="shots of each action (100)")
    p.add_argument("--seed", metavar="S", help="random seed (the players')")
    p.add_argument("--coarse", default="8m", help="states' spacing (8m)")
    p.add_argument("--fine", default="3m", help="near the pin (3m)")
    p.add_argument("--plays", default="4000", help="plays of each hole's policy (4000)")
    p.add_argument("--putts", metavar="N", help="putts a read of the greens' maps (200)")
    p.add_argument("--green-resolution", metavar="M", help="the greens' maps' spacing (0.5m)")
    p.add_argument("--obstacles", action="store_true",
                   help="solve each hole again without its bunkers, penalty areas and out of "
                   "bounds: what they cost each player (twice the solves)")  # fmt: skip
    p.add_argument("--dask", choices=["local"], help="fly the shots on a local Dask cluster")
    p.add_argument("--workers", metavar="W", help="workers of --dask local (the cores)")
    p.add_argument("-o", "--output", metavar="OUT.parquet", help="a row per hole and player")
    p.add_argument("--plot", metavar="PNG", help="each hole's strokes over par for both players")
    p.add_argument("--force", action="store_true", help="replace an existing output")
    p.set_defaults(func=_cmd_rate)
