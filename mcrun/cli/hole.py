"""``mcrun hole``: describe a hole (its zones and their areas, its length, its ground, its par)
and draw its map; or list the holes of a course map."""

import sys
from pathlib import Path

import numpy as np

from mcrun.cli import CommandError
from mcrun.hole.errors import HoleError
from mcrun.hole.geo import Frame
from mcrun.hole.hole import (
    M_PER_YD,
    PAR_RANGE,
    check_reach,
    hole_from_table,
    load_hole,
    read_hole_file,
    tee_and_pin,
)
from mcrun.hole.osm import ATTRIBUTION, hole_title, read_course
from mcrun.putting.on_hole import check_putting

GEOJSON_SUFFIXES = (".geojson", ".json")


# The pictures ``--plot`` writes, by the suffix of its file.
PICTURE_SUFFIXES = (".png", ".pdf", ".svg")


def skipped_line(skipped):
    """What of a map was left out, unreadable (``osm.Course.skipped``, ``Hole.map_skipped``), in
    one line."""
    return (f"{len(skipped)} feature(s) of the map left out, their geometry unreadable (the "
            f"first: {skipped[0]})")  # fmt: skip


def say_skipped(hole):
    """Tell, on stderr, what of ``hole``'s map was left out (the commands that play a hole: the
    hole is played as the rest of its map draws it); nothing for a hole whose map read whole."""
    if hole is not None and hole.map_skipped:
        print(f"mcrun: note: {hole.map_source}: {skipped_line(hole.map_skipped)}",
              file=sys.stderr, flush=True)  # fmt: skip


def _list_holes(path):
    """Every hole of the map: its number, par, length and course; a hole that cannot be
    played as mapped is listed too, marked with why."""
    course = read_course(path)
    courses = [course.course_of(line) for line in course.holes]
    names = {name for name in courses if name}
    on = f" on {len(names)} courses" if len(names) > 1 else ""
    title = course.name if course.name and len(names) == 1 else path
    print(f"{title}: {len(course.holes)} holes{on} (choose one with --hole N)")
    print(f"{'hole':>4}  {'ref':>4}  {'par':>3}  {'length_m':>8}  {'length_yd':>9}  title")
    bad = 0
    for line, course_name in zip(course.holes, courses, strict=True):
        head = f"{line.index:>4}  {line.ref or '-':>4}  {line.par or '-':>3}"
        title = hole_title(course_name, line)
        try:
            if line.par is not None and line.par not in PAR_RANGE:  # (as load_hole checks it)
                raise HoleError(f"{path}: par {line.par!r}: allowed is a whole number 2-7 (mend "
                                "the map, or give 'par' in a hole file)")  # fmt: skip
            tee, pin = tee_and_pin(course, line, str(path))
            frame = Frame.from_tee_pin(tee, pin)
            x, y = frame.to_xy(*np.vstack([line.lonlat, [tee, pin]]).T)
            length_m = float(frame.to_xy(*pin)[0])
            check_reach(length_m, max(np.ptp(x), np.ptp(y)), f"hole {line.index}")
        except HoleError as err:
            bad += 1
            why = str(err).removeprefix(f"{path}: ")
            print(f"{head}  {'-':>8}  {'-':>9}  {title}  ! {why}")
            continue
        print(f"{head}  {length_m:>8.1f}  {length_m / M_PER_YD:>9.1f}  {title}")
    if bad:
        print(
            f"{bad} of {len(course.holes)} holes cannot be played as mapped (marked !): "
            "give them a 'pin' on a green in a hole file, or mend the map"
        )
    if course.skipped:
        print(skipped_line(course.skipped))
    print(f"map: {course.source}, {ATTRIBUTION}")


def _describe(hole):
    t = hole.terrain()
    print(hole.name or hole.source)
    if hole.map_source:
        ref = f", ref {hole.ref}" if hole.ref else ""
        print(f"map: {hole.map_source}, hole {hole.index}{ref}; {hole.attribution}")
        if hole.map_skipped:
            print(f"map: {skipped_line(hole.map_skipped)}")
    print(f"par: {hole.par if hole.par is not None else '-'}")
    if hole.frame is not None:
        for what, (lon, lat) in (("tee", hole.tee_lonlat), ("pin", hole.pin_lonlat)):
            print(f"{what}: lon {lon:.6f}, lat {lat:.6f}")
    print(f"length tee-pin: {hole.length_m:.1f} m ({hole.length_m / M_PER_YD:.1f} yd)")
    if hole.ground == "flat":
        print("ground: flat")
    else:
        lo, hi = float(t.height_m.min()), float(t.height_m.max())
        print(f"ground: {hole.ground}: {lo:+.2f} to {hi:+.2f} m relative to the tee")
    ny, nx = t.zone.shape
    x1, y1 = t.x0_m + (nx - 1) * t.cell_m, t.y0_m + (ny - 1) * t.cell_m
    print(
        f"grid: {nx} x {ny} nodes at {t.cell_m:g} m, x {t.x0_m:.1f} to {x1:.1f} m, "
        f"y {t.y0_m:.1f} to {y1:.1f} m ({(t.height_m.nbytes + t.zone.nbytes) / 1e6:.1f} MB)"
    )
    print("zone areas on the grid (m^2):")
    for kind, area in hole.zone_areas_m2().items():
        if area > 0:
            print(f"  {kind:<14}{area:>10.0f}")


def _cmd_hole(args):
    path = Path(args.file)
    suffix = Path(args.plot).suffix.lower() if args.plot else None
    if args.plot and suffix not in PICTURE_SUFFIXES:  # before the hole is described
        raise CommandError(f"--plot {args.plot}: a picture is {', '.join(PICTURE_SUFFIXES)}, "
                           f"got {suffix or 'no suffix'}")  # fmt: skip
    if args.plot:  # a folder there, a file for a folder, a name too long: said before, too
        from mcrun.run.aim import check_output

        check_output(args.plot, args.force, "--plot", PICTURE_SUFFIXES, "picture")
    if path.suffix.lower() in GEOJSON_SUFFIXES:
        if args.hole is None:
            if args.plot:
                raise CommandError("--plot draws one hole: choose it with --hole N")
            _list_holes(path)
            return 0
        hole = hole_from_table({"map": path.name, "hole": args.hole}, path.parent, str(path))
    else:
        hole = load_hole(path) if args.hole is None else _with_hole(path, args.hole)
    check_putting(hole)
    _describe(hole)
    if args.plot:
        from mcrun.report.hole_map import write_hole_map

        try:
            write_hole_map(hole, args.plot, force=args.force)
        except OSError as err:
            raise CommandError(f"cannot write {args.plot}: {err.strerror or err}") from None
        print(f"wrote {args.plot}")
    return 0


def _with_hole(path, key):
    """The hole file at ``path`` with its 'hole' replaced by ``key``."""
    table, source = read_hole_file(path)
    return hole_from_table({**table, "hole": key}, path.parent, source)


def register(subparsers):
    """Add ``hole`` to an argparse subparsers object."""
    p = subparsers.add_parser(
        "hole",
        help="describe and draw a hole, or list the holes of a course map",
        description="Describe a hole: its par, tee and pin, length tee to pin, ground "
        "(elevation range), its grid and the areas of its zones (rough, fairway, tee, fringe, "
        "green, bunker, water, out of bounds). FILE is a hole TOML file, or a GeoJSON course "
        "map (OpenStreetMap golf tags): without --hole, its holes are listed. --plot draws "
        "the hole's map (needs matplotlib, mcrun[plot]).",
        epilog="example: mcrun hole scenarios/holes/riverside-2.toml --plot hole2.png",
        allow_abbrev=False,
    )
    p.add_argument("file", metavar="FILE", help="a hole TOML file or a GeoJSON course map")
    p.add_argument(
        "--hole",
        metavar="N",
        help="the hole: its ref, or its 1-based position in the map ('#N': the position N)",
    )
    p.add_argument("--plot", metavar="PNG", help="draw the hole's map into this file")
    p.add_argument("--force", action="store_true", help="replace the --plot file if it exists")
    p.set_defaults(func=_cmd_hole)
