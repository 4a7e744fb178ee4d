"""``mcrun rate COURSE``: a course rated by simulating the handicap system's model players: every
hole solved for the scratch and the bogey player (men's, or women's with ``--women``), their
Course and Bogey Ratings, the Slope Rating and the plays-as yardage (``mcrun.play.rating``); a
table on screen, a row per hole and player to Parquet."""

import contextlib
import dataclasses
import re
import sys
from pathlib import Path

import numpy as np

from mcrun import exits
from mcrun.cli import Interrupted, compile_if_needed, write_all_or_nothing
from mcrun.cli.options import whole
from mcrun.cli.play import OPTION_NAMES, checked_outputs, dask_client, solve_settings
from mcrun.hole.hole import PUTTING_N_RANGE
from mcrun.quantities import InputError
from mcrun.units import parse_quantity, shown

FULL_COURSE = 18  # holes: what a Slope Rating is of
FAR_WALK_M = 300.0  # a green this far from the next hole's tee: the map's order is doubted
RATED_HOLES = (9, 18)  # what the system rates: a length rating and a plays-as yardage are of these
MARGIN_M = 60.0  # the ground kept around each hole's line (as the library's hole files)
CELL_M = 0.5
# A scorecard's hole number and yards as written (Python's int and float read "3_80" as 380).
_WHOLE = re.compile(r"^[0-9]+$")
_DECIMAL = re.compile(r"^[0-9]+(\.[0-9]*)?$|^\.[0-9]+$")


def holes_wanted(spec, count, where="--holes"):
    """The hole numbers (1-based) of ``spec`` ("1-9", "1,3,10-12"; None: all ``count``)."""
    if spec is None:
        return list(range(1, count + 1))
    numbers = []
    for part in str(spec).split(","):
        lo, dash, hi = part.strip().partition("-")
        # (in ASCII digits, as every whole number: int() read "١٢" as 12 and "1_2" as 12)
        ends = (lo.strip(), (hi if dash else lo).strip())  # ("1-" is no range: refused)
        if not all(end.isascii() and end.isdigit() for end in ends):
            raise InputError(f"{where} {shown(str(spec))}: allowed: hole numbers 1-{count} as "
                             "1-9 or 1,3,10-12")  # fmt: skip
        first, last = int(ends[0]), int(ends[1])
        if not 1 <= first <= last <= count:
            raise InputError(f"{where} {shown(str(spec))}: allowed: hole numbers 1-{count} as "
                             f"1-9 or 1,3,10-12 (the map has {count} holes)")  # fmt: skip
        numbers.extend(range(first, last + 1))
    return sorted(set(numbers))


def read_scorecard(path, count):
    """{hole number: yards} of a scorecard CSV (``hole,yards``: a row per hole, its number
    1-``count`` as ``play_order`` numbers it, its length in yards along its line of play);
    InputError naming the file, the row and the field."""
    import csv

    from mcrun.run.monitors.read import separator_of

    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8-sig") as f:
            lines = [line for line in f.read().splitlines() if line.strip()]
    except OSError as err:
        raise InputError(f"--scorecard {path}: {err.strerror}") from None
    except UnicodeDecodeError:
        raise InputError(f"--scorecard {path}: not a text file: a CSV of hole,yards") from None
    # Commas, or a spreadsheet's semicolons or tabs (as replay tells them); names in any case.
    sep = separator_of(lines[0]) if lines else ","
    table = list(csv.reader(lines, delimiter=sep, skipinitialspace=True))
    header = [name.strip().lower() for name in table[0]] if table else []
    twice = sorted({name for name in header if header.count(name) > 1})
    if twice:
        raise InputError(f"{path}: column {twice[0]!r} twice: a scorecard is a CSV with the "
                         "columns hole,yards")  # fmt: skip
    if len(table) < 2 or set(header) != {"hole", "yards"}:
        found = ",".join(table[0]) if table else "nothing"
        raise InputError(f"{path}: a scorecard is a CSV with the columns hole,yards and a row "
                         f"per hole; found {exits.shorten(found)}")  # fmt: skip
    yards = {}
    for k, fields in enumerate(table[1:], start=2):
        if len(fields) != 2:
            raise InputError(f"{path} row {k}: {len(fields)} fields: allowed: hole,yards")
        row = dict(zip(header, (field.strip() for field in fields), strict=True))
        try:
            if not (_WHOLE.match(row["hole"]) and _DECIMAL.match(row["yards"])):
                raise ValueError
            hole, length = int(row["hole"]), float(row["yards"])
        except ValueError:
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


def tee_set(spec):
    """The tee set of ``--tees``: None (the back tees: each hole line's first point), a
    number K (the K-th tee box of each hole in the map, from the back) or "forward" (each
    hole's front tee box); InputError otherwise."""
    text = "back" if spec is None else str(spec).strip().lower()
    if text in ("back", "forward"):
        return None if text == "back" else text
    if text.isascii() and text.isdigit() and 1 <= int(text) <= 9:
        return int(text)
    raise InputError(f"--tees {spec!r}: allowed: back (each hole line's first point), forward "
                     "(each hole's front tee box in the map) or K, 1-9 (the K-th tee box from "
                     "the back)")  # fmt: skip


def _map_tee(tees, number, wanted, notes):
    """The (lon, lat) of hole ``number``'s tee of set ``wanted`` (``tee_set``) among its tee
    boxes ``tees`` (``hole.tees.hole_tees``: back first), None for its line's first point;
    what was taken instead is added to ``notes``."""
    if not tees:
        notes.append(f"hole {number} has no tee box in the map: its line's first point")
        return None
    if wanted == "forward":
        return list(tees[-1])
    if wanted > len(tees):
        notes.append(f"hole {number} has {len(tees)} tee box(es): its front one")
    return list(tees[min(wanted, len(tees)) - 1])


def play_order(course):
    """{hole number: its position in the map (1-based)} of ``course`` (an ``osm.Course``), and
    a note where the map does not number its holes: by their ``ref`` where the refs are 1-N,
    else in the map's order (said in the note, with how far each green is from the next
    tee). Chaining each green to the nearest next tee is no better: on the library's course it
    gives an order whose walk is shorter than the map's and whose holes are 8-13, 18, 1-7,
    14-17."""
    from mcrun.hole.geo import Frame

    lines = course.holes
    refs = [(line.ref or "").strip() for line in lines]
    if all(r.isascii() and r.isdigit() for r in refs) and sorted(map(int, refs)) == list(
        range(1, len(lines) + 1)
    ):
        return {int(r): k + 1 for k, r in enumerate(refs)}, None
    read = [line for line in lines if line.lonlat is not None]
    frame = Frame(*read[0].lonlat[0], 0.0) if read else None
    walks = [np.nan if a.lonlat is None or b.lonlat is None else
             float(np.hypot(*np.subtract(frame.to_xy(*b.lonlat[0]), frame.to_xy(*a.lonlat[-1]))))
             for a, b in zip(lines, lines[1:], strict=False)]  # fmt: skip
    note = "the map does not number its holes 1-N (ref): they are taken in its order"
    if walks and not np.isnan(walks).all():
        far = int(np.nanargmax(walks))
        longest = walks[far]
        note += (f" (each green {np.nanmin(walks):.0f}-{longest:.0f} m from the next tee"
                 + (f": hole {far + 2}'s tee is {longest:.0f} m from hole {far + 1}'s green, "
                    "the map's order may not be the course's" if longest > FAR_WALK_M
                    else "") + ")")  # fmt: skip
    return {k: k for k in range(1, len(lines) + 1)}, note


def _ranges(numbers):
    """Hole numbers as "1-3, 7"."""
    runs = []
    for k in numbers:
        if runs and k == runs[-1][1] + 1:
            runs[-1][1] = k
        else:
            runs.append([k, k])
    return ", ".join(f"{a}" if a == b else f"{a}-{b}" for a, b in runs)


def check_one_course(course, path, numbers, position, spec, notes):
    """InputError for a golf=hole line drawn twice (its copy was rated as a hole of its own),
    and for holes on more than one of the map's named courses (``leisure=golf_course``: a map
    of two courses was rated as one) unless chosen (``spec``: then a note in ``notes``)."""
    lines = {k: course.hole(f"#{position[k]}") for k in numbers}
    seen, courses = {}, {}
    for k, line in lines.items():
        key = None if line.lonlat is None else np.asarray(line.lonlat).tobytes()
        if key is not None and key in seen:
            raise InputError(f"{path}: holes {seen[key]} and {k} are one golf=hole line drawn "
                             "twice (the same points): allowed is each hole once; mend the map, "
                             "or leave one out with --holes")  # fmt: skip
        seen[key] = k
        courses.setdefault(course.course_of(line), []).append(k)
    named = {name: ks for name, ks in courses.items() if name is not None}
    if len(named) < 2:
        return
    listed = "; ".join(f"{name}: hole{'s' * (len(ks) > 1)} {_ranges(ks)}"
                       for name, ks in named.items())  # fmt: skip
    if spec is None:
        raise InputError(f"{path}: its holes lie on {len(named)} courses ({listed}): a rating is "
                         "of one course; allowed: its holes, chosen with --holes")  # fmt: skip
    notes.append(f"the holes rated lie on {len(named)} courses of the map ({listed})")


def course_holes(path, spec=None, putting=None, scorecard=None, women=False, tees=None,
                 elevation=None, elevation_crs=None):  # fmt: skip
    """The Holes of the course map ``path`` (a GeoJSON course map, as ``mcrun hole`` reads),
    those of ``spec`` (``holes_wanted``, numbered as ``play_order`` numbers them), in order,
    each checked as ``mcrun play`` checks a hole; a hole without a par in the map gets one by
    its length from the tee it is played from (``rating.par_by_length``, a woman's with
    ``women``). ``putting``: the holes' ``[hole.putting]`` settings (``hole.PUTTING_KEYS``:
    the maps of their greens, for a putter other than the Tour's); ``scorecard``: a CSV of a
    tee set (``read_scorecard``): each hole's tee that far from the end of its line, along it
    (the holes on it, where ``spec`` is None); ``tees``: a tee set of the map's tee boxes
    (``tee_set``; not with a scorecard); ``elevation``: a file of the course's ground heights
    (``hole.elevation``; its ``elevation_crs``), each hole's relative to its tee (default
    flat). Returns (their numbers, the holes, the numbers whose par was taken from their
    length, notes on the order and the tees taken)."""
    from mcrun.cli.hole import skipped_line
    from mcrun.hole.hole import hole_from_table
    from mcrun.hole.osm import read_course
    from mcrun.hole.tees import hole_tees
    from mcrun.play.rating import par_by_length
    from mcrun.putting.on_hole import check_putting

    if tees is not None and scorecard is not None:
        raise InputError("--tees and --scorecard: give one tee set, from the map or from a "
                         "scorecard")  # fmt: skip
    path = Path(path)
    if elevation is not None and not Path(elevation).is_file():  # (named a hole file's key)
        why = "a folder" if Path(elevation).is_dir() else "no such file"
        raise InputError(f"--elevation {elevation}: {why}: allowed: a GeoTIFF, an ESRI ASCII "
                         "grid or a CSV of survey points")  # fmt: skip
    course = read_course(path)
    if not course.holes:
        raise InputError(f"{path}: no golf=hole lines: a course map needs its holes' lines "
                         "(tee to green) to be rated")  # fmt: skip
    yards = None if scorecard is None else read_scorecard(scorecard, len(course.holes))
    numbers = holes_wanted(spec, len(course.holes))
    position, order_note = play_order(course)
    boxes = {} if tees is None else hole_tees(course)
    notes = [] if order_note is None else [order_note]
    if course.skipped:
        notes.append(skipped_line(course.skipped))
    if yards is not None:
        if spec is None:
            numbers = sorted(yards)
        missing = [k for k in numbers if k not in yards]
        if missing:
            raise InputError(f"{scorecard}: no row for hole {missing[0]}: the scorecard must "
                             "give every hole rated")  # fmt: skip
    check_one_course(course, path, numbers, position, spec, notes)
    holes, by_length = [], []
    for number in numbers:
        where = f"{path} hole {number}"
        table = {"map": path.name, "hole": f"#{position[number]}", "cell_m": CELL_M,
                 "margin_m": MARGIN_M}  # fmt: skip
        if putting:
            table["putting"] = dict(putting)
        if elevation is not None:
            table["elevation"] = str(Path(elevation).resolve())
            if elevation_crs is not None:
                table["elevation_crs"] = str(elevation_crs)
        if yards is not None:
            table["tee"] = _tee_at(course.hole(f"#{position[number]}"), yards[number],
                                   f"{scorecard} hole {number}")  # fmt: skip
        elif tees is not None:
            tee = _map_tee(boxes.get(position[number], []), number, tees, notes)
            if tee is not None:
                table["tee"] = tee
        hole = hole_from_table(table, path.parent, where)
        if hole.par is None:  # by its length from the tee it is played from
            hole = dataclasses.replace(hole, par=par_by_length(hole.length_m, women))
            by_length.append(number)
        holes.append(check_putting(hole))
    return numbers, holes, by_length, notes


def _cmd_rate(args):
    from mcrun.play.rating import (
        BETTER_HALF,
        EXPECTED,
        MODEL_PLAYERS,
        length_rating,
        plan_rating,
        rate_planned,
    )

    destination = checked_outputs(args, "rate")
    workers, n, plays, coarse, fine, seed = solve_settings(args)
    putting = {}
    if args.putts is not None:
        putting["n"] = whole(args.putts, "--putts", *PUTTING_N_RANGE)
    if args.green_resolution is not None:
        resolution = parse_quantity(args.green_resolution, "length", "--green-resolution")
        if not 0.05 <= resolution <= 5.0:
            raise InputError(f"--green-resolution {resolution:g} m: allowed: 0.05 m to 5 m")
        putting["resolution_m"] = resolution
    if args.elevation_crs is not None and args.elevation is None:
        raise InputError("--elevation-crs: is for --elevation (the file whose coordinates it says)")
    tees = tee_set(args.tees)
    numbers, holes, by_length, notes = course_holes(args.course, args.holes, putting,
                                                    args.scorecard, args.women, tees,
                                                    args.elevation, args.elevation_crs)  # fmt: skip
    players = MODEL_PLAYERS["women" if args.women else "men"]
    compile_if_needed("plane")  # the plans fly each club on the level
    # Every solve planned before the first is flown: a bad hole or one too big is refused here.
    plans = plan_rating(holes, players, n=n, seed=seed, coarse_m=coarse, fine_m=fine, plays=plays,
                        numbers=numbers, obstacles=args.obstacles, workers=workers,
                        names=OPTION_NAMES)  # fmt: skip
    length_yd = sum(h.length_m for h in holes) / 0.9144
    if args.scorecard is not None:
        played_from = f"the tees of {args.scorecard}"
    else:
        played_from = {None: "the back tees", "forward": "the front tee boxes"}.get(
            tees, f"tee box {tees} from the back"
        )
    print(f"rate: {args.course}: {len(holes)} hole{'s' * (len(holes) > 1)}, {length_yd:,.0f} "
          f"yd from {played_from} (tee to pin); {' and '.join(players)}, {n:,} shots an action",
          file=sys.stderr, flush=True)  # fmt: skip
    for note in notes:
        print(f"rate: {note}", file=sys.stderr, flush=True)
    if by_length:
        print(f"rate: par by length (the map has none) for hole(s) "
              f"{', '.join(map(str, by_length))}", file=sys.stderr, flush=True)  # fmt: skip
    compile_if_needed("terrain")
    from tqdm import tqdm

    with contextlib.ExitStack() as stack:
        client = dask_client(stack, args, workers)
        bar = tqdm(total=len(plans), unit="hole", file=sys.stderr,
                   leave=False, dynamic_ncols=True, disable=None)  # fmt: skip
        stack.callback(bar.close)
        try:
            rating = rate_planned(holes, plans, args.women, client=client,
                                  progress=lambda *_: bar.update(1))  # fmt: skip
        except KeyboardInterrupt:
            raise Interrupted("nothing was written") from None
    frame = rating.frame()
    scratch, bogey = players
    costs = f"  obstacles cost: {scratch}, {bogey}" if args.obstacles else ""
    print(f"{'hole':>4} {'par':>3} {'yd':>5}  {scratch:>13}  {bogey:>13}  {bogey} - {scratch}"
          f"{costs}")  # fmt: skip
    for k, hole in enumerate(holes):
        s, b = (rating.scores[p][k] for p in rating.players)
        cost = (f"  {s.obstacles_strokes:+.3f}, {b.obstacles_strokes:+.3f}" if args.obstacles
                else "")  # fmt: skip
        print(f"{s.hole:>4} {hole.par:>3} {hole.length_m / 0.9144:>5.0f}  "
              f"{s.expected_strokes:6.3f} +- {s.expected_strokes_se:.3f}  "
              f"{b.expected_strokes:6.3f} +- {b.expected_strokes_se:.3f}  "
              f"{b.expected_strokes - s.expected_strokes:+{len(bogey) + len(scratch) + 3}.3f}"
              f"{cost}")  # fmt: skip
    full, rated = len(holes) == FULL_COURSE, len(holes) in RATED_HOLES
    for reading in (EXPECTED, BETTER_HALF):
        cr, br = (rating.rating(p, reading) for p in players)
        slope = f", Slope Rating {rating.slope(reading)}" if full else ""
        plays_as = ", ".join(f"{p} {rating.plays_as_yd(p, reading):,.0f}" for p in players)
        plays_as = f"; plays as (yd): {plays_as}" if rated else ""
        print(f"{reading}: Course Rating {cr:.1f}, Bogey Rating {br:.1f}{slope}{plays_as}")
    if rated:
        rule = ", ".join(f"{p} {length_rating(p, length_yd, len(holes)):.1f}" for p in players)
        rule = f"the system's length rating: {rule}"
    else:
        rule = "the length rating and the plays-as yardage are of 9 or 18 holes"
    slope = "" if full else f", the Slope Rating of {FULL_COURSE}"
    print(f"(par {sum(h.par for h in holes)}; {rule}{slope})")
    if args.output is None and args.plot is None:
        return 0
    picture = None
    if args.plot is not None:
        from mcrun.report import rating_plot

        title = f"{Path(args.course).name}: {len(holes)} holes, {length_yd:,.0f} yd"
        picture = (args.plot, lambda: rating_plot.rating_figure(rating, title), rating_plot.DPI)
    settings = {"n": n, "plays": plays, "coarse_m": coarse, "fine_m": fine,
                "holes_rated": list(numbers)}  # fmt: skip
    write_all_or_nothing(
        None
        if args.output is None
        else lambda: write_rating(rating, frame, destination, args, settings),
        picture,
        args.force,
    )
    for path in (args.output, args.plot):
        if path is not None:
            print(f"wrote {path}")
    return 0


def write_rating(rating, frame, path, args, settings):
    """A row per hole and player to Parquet, with the ratings and the provenance (``settings``:
    the solves' n, plays and lattice, and the numbers of the holes rated)."""
    from mcrun.play.rating import BETTER_HALF, EXPECTED
    from mcrun.results import output

    provenance = {"course": str(args.course), "holes": len(rating.holes), "women": rating.women,
                  "scorecard": None if args.scorecard is None else str(args.scorecard),
                  "tees": str(tee_set(args.tees) or "back"),
                  "elevation": None if args.elevation is None else str(args.elevation),
                  "players": list(rating.players), "seed": rating.seed, **settings,
                  "versions": output.versions(),
                  # the better half's rounds: each player's day form (``rating.DAY_FORM``)
                  "day_form": dict(rating.day_form),
                  "length_yd": rating.length_yd,
                  # the greens' maps the model players putt on (the holes share these settings)
                  "greens": {key: rating.holes[0].putting[key]
                             for key in ("read", "n", "seed", "resolution_m", "drift_mm_per_m")},
                  "attribution": rating.holes[0].attribution or "", "file": "rating"}  # fmt: skip
    for reading, key in ((EXPECTED, "expected"), (BETTER_HALF, "better_half")):
        for player in rating.players[:2]:
            name = player.replace("-", "_")
            provenance[f"{name}_rating_{key}"] = round(rating.rating(player, reading), 1)
            if len(rating.holes) in RATED_HOLES:
                provenance[f"{name}_plays_as_yd_{key}"] = round(rating.plays_as_yd(player, reading))
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
        "bogey, men's or women's (each hole's line from its first point, the back tee, to its "
        "pin): their expected strokes per hole, the Course and Bogey Ratings as the expected "
        "score and as the better half's mean of their rounds, the Slope Rating and the "
        "course's plays-as yardage for each.",
        epilog="example: mcrun rate scenarios/holes/riverside-zagreb.osm.geojson --holes 1-3",
        allow_abbrev=False,
    )
    p.add_argument("course", metavar="COURSE")
    p.add_argument("--holes", metavar="SPEC", help="the holes to rate: 1-9, 1,3,10-12 (all)")
    p.add_argument("--scorecard", metavar="CSV", help="a tee set: hole,yards (the back tees: "
                   "each hole line's first point)")  # fmt: skip
    p.add_argument("--elevation", metavar="FILE", help="the course's ground heights: a GeoTIFF, "
                   "an ESRI ASCII grid or a CSV of survey points (flat)")  # fmt: skip
    p.add_argument("--elevation-crs", metavar="CRS",
                   help="the elevation file's coordinate system where it does not say")  # fmt: skip
    p.add_argument("--tees", metavar="SET", help="a tee set of the map's tee boxes: forward "
                   "(each hole's front one) or K (the K-th from the back); back: each hole "
                   "line's first point (back)")  # fmt: skip
    p.add_argument("--women", action="store_true",
                   help="the women's model players (scratch-woman, bogey-woman), the women's "
                   "Slope and par by length")  # fmt: skip
    p.add_argument("-n", default="100", metavar="N", help="shots of each action (100)")
    p.add_argument("--seed", metavar="S", help="random seed (the players')")
    p.add_argument("--coarse", default="8m", help="states' spacing (8m)")
    p.add_argument("--fine", default="3m", help="near the pin (3m)")
    p.add_argument(
        "--plays", default="4000", help="plays of each hole's policy (4000; at least 100)"
    )
    p.add_argument("--putts", metavar="N", help="putts a read of the greens' maps (200)")
    p.add_argument("--green-resolution", metavar="M", help="the greens' maps' spacing (0.5m)")
    p.add_argument("--obstacles", action="store_true",
                   help="solve each hole again without its bunkers, penalty areas and out of "
                   "bounds: what they cost each player (twice the solves)")  # fmt: skip
    p.add_argument(
        "--dask",
        choices=["local"],
        help="solve on a local Dask cluster, each player's hole a worker's task",
    )
    p.add_argument("--workers", metavar="W", help="workers of --dask local (the cores)")
    p.add_argument("-o", "--output", metavar="OUT.parquet", help="a row per hole and player")
    p.add_argument("--plot", metavar="PNG", help="each hole's strokes over par for both players")
    p.add_argument("--force", action="store_true", help="replace an existing output")
    p.set_defaults(func=_cmd_rate)
