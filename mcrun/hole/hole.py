"""A hole to play: its spec from a TOML table, its frame, zones, tee and pin, and its ground on
a grid (``Hole.terrain()``, a ``ground.Terrain``).

The ``[hole]`` table of a scenario and a standalone hole TOML file have the same keys:

- ``map``: a GeoJSON course (``osm``), relative to the TOML's folder; ``hole``: its ``ref``, or
  its 1-based position among the file's ``golf=hole`` lines ("#N": the position N);
- ``tee``, ``pin``: [lon, lat] overrides (default: the hole line's first point; the
  ``golf=pin`` in the hole's green, else the line's last point); the pin must be on a green,
  and a hole of a map without a green near its end is refused;
- ``elevation`` (a file, relative to the TOML's folder; ``elevation_crs`` when the file does
  not say), or ``shape`` (an analytic ground: its kind, or a table with ``kind`` and its
  parameters); neither: flat;
- without a map, the hole is a rectangle of one zone kind ``surface`` (default fairway),
  ``length_m`` from tee to pin (or ``tee`` and ``pin`` as [lon, lat]) and ``width_m`` wide;
- ``cell_m`` (grid spacing, default 0.5), ``margin_m`` (default 50: how far the grid reaches
  beyond the hole line, the tee and the pin; beyond the rectangle's ends without a map);
- ``par``, ``name`` (when the map has none);
- ``penalty_areas``: "red" or "yellow", the colour of every penalty area of the hole (its
  relief under Rule 17.1d: red lateral, yellow not); default as mapped (``golf=water_hazard``
  yellow, ``golf=lateral_water_hazard`` and ``natural=water`` red);
- ``[hole.turf.KIND]``: turf values of a zone kind (``preset`` = a turf preset, and any
  ``physics.turf.Turf`` field), checked against ``turf.LIMITS``;
- ``putting``: how a ball at rest on the green is valued: "table" (default: the baseline's
  putts from its distance) or "physics" (the expected-putts map of the green's contour,
  ``mcrun.putting.green_map``), or a table ``[hole.putting]`` with ``model`` and the map's
  settings (``PUTTING_KEYS``: ``putter``, ``n``, ``seed``, ``resolution_m``, ``cell_m`` the
  green's grid, finer than the hole's where its ground has the detail; ``elevation``, a survey
  of the green alone, relative to the TOML's folder, and its ``elevation_crs``;
  ``drift_mm_per_m`` the green's drift, ``putting.greens``: 4.9 pure bentgrass, 0 a perfect
  green, 13 a patch of Poa annua).
"""

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numba import njit

from mcrun.ground import IN_PLAY, PENALTY_AREA, Terrain, make_terrain
from mcrun.hole.errors import HoleError
from mcrun.hole.geo import Frame
from mcrun.hole.osm import (
    ACCEPTED,
    ATTRIBUTION,
    hole_title,
    playable,
    read_course,
    sniff,
    tag_text,
)
from mcrun.hole.zones import (
    PENALTY_COLOURS,
    PENALTY_ZONES,
    ZONE_INDEX,
    ZONE_KINDS,
    ZONE_PENALTY,
    ZONE_TURF,
    contains,
    rasterize,
)
from mcrun.physics.turf import (
    GREEN_DRIFT_MM_PER_M,
    GREEN_DRIFT_RANGE_MM_PER_M,
    PRESETS,
    Turf,
    check_turf,
)
from mcrun.units import path_of, shown

M_PER_YD = 0.9144
DEFAULT_CELL_M = 0.5
DEFAULT_MARGIN_M = 50.0
CELL_RANGE_M = (0.05, 10.0)
MARGIN_RANGE_M = (0.0, 1000.0)
SIZE_RANGE_M = (1.0, 2000.0)
# The most nodes a hole's grid may have: about 10 bytes each in its Terrain (a hole of 700 by
# 200 m at the default cell has 560,000; at 0.1 m, 14 million).
MAX_NODES = 50_000_000
# A golf=pin further than this from the hole's green is another green's.
PIN_SEARCH_M = 10.0
# A green further than this from the end of a hole line is another hole's (a map may hold a
# country's courses: only the greens near the line's end are looked at).
GREEN_SEARCH_M = 1000.0

KEYS = (
    "map",
    "hole",
    "tee",
    "pin",
    "elevation",
    "elevation_crs",
    "shape",
    "surface",
    "length_m",
    "width_m",
    "cell_m",
    "margin_m",
    "par",
    "name",
    "penalty_areas",
    "turf",
    "putting",
)
PUTTING_MODELS = ("table", "physics")
# How the map reads each putt (``putting.green_map``): the putter's own read, or the best of a
# search.
PUTTING_READS = ("own", "best")
# [hole.putting]: its keys, defaults and what is allowed.
PUTTING_DEFAULTS = {"model": "table", "putter": "tour", "read": "own", "n": 200, "seed": 0,
                    "resolution_m": 0.5, "cell_m": None, "elevation": None,
                    "elevation_crs": None,
                    "drift_mm_per_m": GREEN_DRIFT_MM_PER_M}  # fmt: skip
PUTTING_KEYS = tuple(PUTTING_DEFAULTS)
# Putts a read is valued on (``[hole.putting] n``, ``mcrun putt -n``): the most take minutes.
PUTTING_N_RANGE = (2, 100_000)
# A hole's par ('par' of a hole file, or its map's tag).
PAR_RANGE = range(2, 8)


@njit(cache=True, nogil=True)
def _zones_at(zone, x0_m, y0_m, cell_m, x_m, y_m, out):
    """``Hole.zone_at`` of the points (x_m, y_m) into ``out``: the zone of the nearest node of
    the grid ``zone`` (its node [0, 0] at (x0_m, y0_m)), -1 off the grid (or not a number)."""
    ny, nx = zone.shape
    for i in range(x_m.size):
        ix = np.rint((x_m[i] - x0_m) / cell_m)
        iy = np.rint((y_m[i] - y0_m) / cell_m)
        if ix >= 0 and ix < nx and iy >= 0 and iy < ny:
            out[i] = zone[int(iy), int(ix)]
        else:
            out[i] = -1


@dataclass
class Hole:
    """A hole in its frame (x from the tee towards the pin, y to the right, metres)."""

    source: str  # where it was read, for messages: "FILE" or "FILE [hole]"
    frame: Frame | None  # None: a hole without a map or lon/lat (to_lonlat gives NaN)
    pin_xy: tuple  # (x_m, y_m); the tee is (0, 0)
    zones: list  # (kind, polygon: a list of (n, 2) rings in the frame), in map order
    boundary: list  # the course boundary's polygons in the frame; empty: no boundary
    extent_m: tuple  # (x_min, x_max, y_min, y_max) the grid covers
    cell_m: float = DEFAULT_CELL_M
    turf: dict = field(default_factory=dict)  # zone kind -> Turf, overrides applied
    index: int | None = None  # the position of the hole in its map
    ref: str | None = None
    par: int | None = None
    name: str | None = None
    map_source: str | None = None
    attribution: str | None = None  # to show wherever the map's data or a figure of it appears
    map_skipped: tuple = ()  # what of its map was left out, unreadable (``osm.Course.skipped``)
    ground: str = "flat"  # "flat", "elevation FILE" or "shape KIND"
    line_xy: np.ndarray | None = None  # the hole line in the frame
    putting: dict = field(default_factory=lambda: dict(PUTTING_DEFAULTS))  # [hole.putting]
    _heights: object = None  # callable(x_m, y_m) -> heights relative to the tee, or None
    _terrain: Terrain | None = None

    @property
    def length_m(self):
        """Tee to pin, in the plane of the frame (m)."""
        return float(math.hypot(*self.pin_xy))

    @property
    def tee_lonlat(self):
        return None if self.frame is None else (self.frame.tee_lon_deg, self.frame.tee_lat_deg)

    @property
    def pin_lonlat(self):
        if self.frame is None:
            return None
        lon, lat = self.frame.to_lonlat(*self.pin_xy)
        return float(lon), float(lat)

    def to_lonlat(self, x_m, y_m):
        """(lon_deg, lat_deg) of points of the hole's frame; NaN when the hole has no lon/lat."""
        if self.frame is None:
            shape = np.broadcast(np.asarray(x_m), np.asarray(y_m)).shape
            return np.full(shape, np.nan), np.full(shape, np.nan)
        return self.frame.to_lonlat(x_m, y_m)

    def terrain(self):
        """The hole's ground.Terrain over ``extent_m`` (built once, then shared)."""
        if self._terrain is None:
            self._terrain = self.terrain_over(self.extent_m)
        return self._terrain

    def course_extent_m(self):
        """(x_min, x_max, y_min, y_max) of every zone and the boundary: the whole course."""
        points = [ring for _, polygon in self.zones for ring in polygon]
        points += [ring for polygon in self.boundary for ring in polygon]
        if not points:
            return self.extent_m
        xy = np.concatenate(points)
        return (xy[:, 0].min(), xy[:, 0].max(), xy[:, 1].min(), xy[:, 1].max())

    def terrain_over(self, extent_m, cell_m=None):
        """A ground.Terrain of this hole over ``extent_m`` = (x_min, x_max, y_min, y_max), on a
        grid of ``cell_m`` (default the hole's): its nodes on multiples of the cell, its zones
        rasterised and its heights sampled from the hole's ground at that spacing (a green to
        putt on is this ground at a finer one, ``putting.green``)."""
        cell = self.cell_m if cell_m is None else float(cell_m)
        x0, y0, nx, ny = _grid_of(extent_m, cell)
        zone = rasterize(self.zones, x0, y0, cell, nx, ny, self.boundary)
        if self._heights is None:
            height = np.zeros((ny, nx))
        else:
            height = self._heights(x0, y0, cell, nx, ny)
        turf = np.array([[getattr(self.turf[k], f) for f in Turf._fields] for k in ZONE_KINDS])
        penalty = np.array([ZONE_PENALTY[k] for k in ZONE_KINDS], dtype=np.int8)
        return make_terrain(x0, y0, cell, height, zone, turf, penalty)

    def zone_at(self, x_m, y_m):
        """Zone index (``zones.ZONE_KINDS``) at (x_m, y_m): that of the nearest node of the
        terrain, as the ground's; -1 off the grid. Vectorised."""
        t = self.terrain()
        x, y = np.broadcast_arrays(np.asarray(x_m, float), np.asarray(y_m, float))
        out = np.empty(x.shape, dtype=np.int8)
        _zones_at(t.zone, t.x0_m, t.y0_m, t.cell_m, np.ascontiguousarray(x).ravel(),
                  np.ascontiguousarray(y).ravel(), out.reshape(-1))  # fmt: skip
        return out

    def in_play_at(self, x_m, y_m):
        """Whether a ball at (x_m, y_m) is in play (on the map, not in a penalty area or out
        of bounds): where a shot can be struck as it lies. Vectorised."""
        state = np.array([ZONE_PENALTY[k] for k in ZONE_KINDS] + [-1])  # -1: off the grid
        return state[self.zone_at(x_m, y_m)] == IN_PLAY

    def why_not_playable(self, x_m, y_m):
        """Why a shot cannot be struck from (x_m, y_m) as the ball lies ("off the hole's map",
        "in a penalty area (water)", "out of bounds (out_of_bounds)"), None where it can."""
        code = int(self.zone_at(np.array([float(x_m)]), np.array([float(y_m)]))[0])
        if code < 0:
            return "off the hole's map"
        kind = ZONE_KINDS[code]
        if ZONE_PENALTY[kind] == PENALTY_AREA:
            return f"in a penalty area ({kind})"
        if ZONE_PENALTY[kind] != IN_PLAY:
            return f"out of bounds ({kind})"
        return None

    def penalty_area_at(self, x_m, y_m):
        """Zone index of the penalty area (``zones.PENALTY_ZONES``) a ball that ended at
        (x_m, y_m) is in: that of the nearest node when it is one, else of a node next to it
        (the later kind of ``ZONE_KINDS`` where two touch); -1 where none is. Vectorised."""
        penalty = np.array([ZONE_PENALTY[k] for k in ZONE_KINDS] + [0]) == PENALTY_AREA
        t = self.terrain()
        x, y = np.asarray(x_m, float), np.asarray(y_m, float)
        at = self.zone_at(x, y)
        found = np.where(penalty[at], at, -1)
        near = np.full(found.shape, -1, dtype=np.int8)
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                code = self.zone_at(x + dx * t.cell_m, y + dy * t.cell_m)
                near = np.maximum(near, np.where(penalty[code], code, -1))
        return np.where(found >= 0, found, near).astype(np.int8)

    def zone_areas_m2(self):
        """{zone kind: area (m^2) on the hole's grid} (node count x cell^2)."""
        counts = np.bincount(self.terrain().zone.ravel(), minlength=len(ZONE_KINDS))
        return {kind: float(counts[k]) * self.cell_m**2 for k, kind in enumerate(ZONE_KINDS)}


# --- reading a spec ----------------------------------------------------------------------------


def load_hole(path):
    """The Hole of a standalone hole TOML file (its top-level keys, or a ``[hole]`` table)."""
    path = path_of(path, "hole", "a hole file's path", HoleError)
    table, source = read_hole_file(path)
    return hole_from_table(table, path.parent, source)


# A hole TOML file holds a few kB of keys; its course map and elevation are files of their own.
MAX_HOLE_FILE_BYTES = 1_000_000


def read_hole_file(path):
    """(table, source) of a hole TOML file: its ``[hole]`` table (source "FILE [hole]"), else
    its top-level keys (source "FILE"); HoleError saying what the file is when it is no TOML
    (a KML, a GPX, a GeoJSON under another name ...)."""
    path = Path(path)
    if "\0" in str(path):
        raise HoleError(f"{shown(str(path))}: a path cannot hold a NUL character")
    if path.is_dir():
        raise HoleError(f"{path}: is a folder, not a hole file")
    if path.exists() and not path.is_file():  # (/dev/zero was read until memory ran out)
        raise HoleError(f"{path}: is not a regular file (a device or a pipe): allowed is a "
                        "hole TOML file")  # fmt: skip
    if path.is_file() and path.stat().st_size > MAX_HOLE_FILE_BYTES:
        raise HoleError(f"{path}: {path.stat().st_size:,} bytes: a hole TOML file is at most "
                        f"{MAX_HOLE_FILE_BYTES:,} (its map and elevation are files of their "
                        "own)")  # fmt: skip
    what = sniff(path)
    if what is not None:
        raise HoleError(
            f"{path}: is {what}, not a hole: allowed is a hole TOML file or {ACCEPTED}; "
            "convert it, e.g. ogr2ogr -f GeoJSON course.geojson FILE"
        )
    try:
        with path.open("rb") as f:
            data = tomllib.load(f)
    except OSError as err:
        raise HoleError(f"{path}: cannot read the hole file: {err.strerror or err}") from None
    except ValueError as err:  # (TOMLDecodeError, UnicodeDecodeError, 4,301 digits)
        with path.open("rb") as f:
            json_like = f.read(64).lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"{")
        if json_like:
            raise HoleError(
                f"{path}: is not a hole TOML file but looks like JSON: a GeoJSON course map "
                "is read when its name ends in .geojson or .json"
            ) from None
        message = " ".join(str(err).split())
        raise HoleError(
            f"{path}: is not valid TOML ({message}): allowed is a hole TOML file or {ACCEPTED}"
        ) from None
    if isinstance(data.get("hole"), dict):
        return data["hole"], f"{path} [hole]"
    return data, str(path)


def _number(table, key, where, lo, hi, default=None):
    value = table.get(key, default)
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, int | float) or not lo <= value <= hi:
        raise HoleError(f"{where}: '{key}' = {value!r} must be a number in [{lo:g}, {hi:g}]")
    return float(value)


def _lonlat(table, key, where):
    value = table.get(key)
    if value is None:
        return None
    ok = (
        isinstance(value, list)
        and len(value) == 2
        and all(isinstance(v, int | float) and not isinstance(v, bool) for v in value)
    )
    if not ok or not (-180 <= value[0] <= 180 and -90 <= value[1] <= 90):
        raise HoleError(f"{where}: '{key}' = {value!r} must be [lon, lat] in degrees (WGS84)")
    return float(value[0]), float(value[1])


def _turfs(table, where):
    """Each zone kind's Turf: its preset, then the table's overrides, checked."""
    turfs = {kind: PRESETS[ZONE_TURF[kind]] for kind in ZONE_KINDS}
    overrides = table.get("turf", {})
    if not isinstance(overrides, dict):
        raise HoleError(f"{where}: 'turf' must be a table of zone kinds ([hole.turf.green] ...)")
    for kind, values in overrides.items():
        key = f"turf.{kind}"
        if kind not in ZONE_INDEX:
            raise HoleError(f"{where}: '{key}': unknown zone kind; choose {', '.join(ZONE_KINDS)}")
        if not isinstance(values, dict):
            raise HoleError(f"{where}: '{key}' must be a table of turf values")
        if ZONE_PENALTY[kind] == PENALTY_AREA:  # (its values were accepted and never used)
            raise HoleError(
                f"{where}: '{key}': a ball ends where it touches a penalty area, so no turf of "
                "it is used: give the turf of another zone kind"
            )
        turf = turfs[kind]
        if "preset" in values:
            if not isinstance(values["preset"], str) or values["preset"] not in PRESETS:
                raise HoleError(
                    f"{where}: '{key}.preset' = {values['preset']!r}: choose {', '.join(PRESETS)}"
                )
            turf = PRESETS[values["preset"]]
        changes = {k: v for k, v in values.items() if k != "preset"}
        for name, value in changes.items():
            if name not in Turf._fields:
                raise HoleError(
                    f"{where}: '{key}.{name}': unknown turf value; choose preset, "
                    f"{', '.join(Turf._fields)}"
                )
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise HoleError(f"{where}: '{key}.{name}' = {value!r} must be a number")
        try:
            turfs[kind] = check_turf(turf._replace(**{k: float(v) for k, v in changes.items()}))
        except ValueError as err:
            raise HoleError(f"{where}: '{key}': {err}") from None
    return turfs


def _putting(table, where, folder):
    """The ``putting`` key: a model name or a table of ``PUTTING_KEYS``, checked (the putter's
    name against the presets by ``putting.on_hole.check_putting``, a layer above)."""
    value = table.get("putting", "table")
    spec = dict(PUTTING_DEFAULTS)
    if isinstance(value, str):
        value = {"model": value}
    if not isinstance(value, dict):
        raise HoleError(f"{where}: 'putting' must be {' or '.join(map(repr, PUTTING_MODELS))} "
                        "or a table [hole.putting]")  # fmt: skip
    for key, v in value.items():
        name = f"putting.{key}"
        if key not in PUTTING_DEFAULTS:
            raise HoleError(f"{where}: '{name}': unknown key; allowed: {', '.join(PUTTING_KEYS)}")
        if key == "model" and v not in PUTTING_MODELS:
            raise HoleError(f"{where}: '{name}' = {v!r}: choose {', '.join(PUTTING_MODELS)}")
        if key == "read" and v not in PUTTING_READS:
            raise HoleError(f"{where}: '{name}' = {v!r}: choose {', '.join(PUTTING_READS)}")
        if key == "putter" and (not isinstance(v, str) or not v):
            raise HoleError(f"{where}: '{name}' = {v!r} must be a putter's name")
        lo, hi = PUTTING_N_RANGE
        if key == "n" and (isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi):
            raise HoleError(f"{where}: '{name}' = {v!r} must be a whole number in [{lo}, {hi}]")
        if key == "seed" and (isinstance(v, bool) or not isinstance(v, int) or v < 0):
            raise HoleError(f"{where}: '{name}' = {v!r} must be a whole number 0 or more")
        if key in ("resolution_m", "cell_m"):
            v = _number({name: v}, name, where, 0.05, 5.0)
        if key == "drift_mm_per_m":
            v = _number({name: v}, name, where, *GREEN_DRIFT_RANGE_MM_PER_M)
        if key in ("elevation", "elevation_crs") and (not isinstance(v, str) or not v):
            raise HoleError(f"{where}: '{name}' = {v!r} must be a file name (a CRS for _crs)")
        if key == "elevation":
            v = str(Path(folder) / v)
        spec[key] = v
    return spec


def _ring_distance_m(polygon, x, y):
    """Distance (m) from (x, y) to the nearest edge of ``polygon``."""
    best = math.inf
    for ring in polygon:
        a, b = ring, np.roll(ring, -1, axis=0)
        d = b - a
        length2 = np.maximum((d * d).sum(1), 1e-12)  # a repeated point is an edge of length 0
        t = np.clip(((x - a[:, 0]) * d[:, 0] + (y - a[:, 1]) * d[:, 1]) / length2, 0, 1)
        px, py = a[:, 0] + t * d[:, 0], a[:, 1] + t * d[:, 1]
        best = min(best, float(np.hypot(px - x, py - y).min()))
    return best


def _in_frame(frame, polygon):
    return [np.column_stack(frame.to_xy(ring[:, 0], ring[:, 1])) for ring in polygon]


def contains_any(polygons, x, y):
    """Whether the point (x, y) is in any of ``polygons`` (each a list of rings)."""
    return any(bool(contains(p, x, y)) for p in polygons)


def tee_and_pin(course, line, where, table=None):
    """The tee and the pin ((lon, lat) deg) of ``line``, a hole of ``course`` (an
    ``osm.Course``): the table's 'tee' and 'pin' when given, else the line's first point and
    the ``golf=pin`` on the hole's green (the green holding the line's end, else the nearest
    within ``GREEN_SEARCH_M``), else the line's last point. HoleError (one line, from
    ``where``) when the hole has no green or its pin is not on one."""
    table = {} if table is None else table
    map_path = course.source
    playable(line)
    tee = _lonlat(table, "tee", where) or tuple(line.lonlat[0])
    # Find the green and the pin in a provisional frame at the tee (east-north, metres).
    local = Frame(*tee, 0.0)
    pin = _lonlat(table, "pin", where)
    ends = [line.lonlat[-1]] + ([] if pin is None else [pin])
    greens = [_in_frame(local, p) for p in course.greens_near(ends, GREEN_SEARCH_M)]
    end_xy = local.to_xy(*line.lonlat[-1])
    reach = math.hypot(*end_xy)  # from the tee, the line's first point without a 'tee'
    if "tee" not in table and pin is None and reach < 1.0:
        raise HoleError(
            f"{where}: hole {line.index}: its golf=hole line ends {reach:.1f} m from where it "
            "starts: allowed is a line from the tee to the green (or a 'tee' and a 'pin' in a "
            "hole file)"
        )
    if "tee" not in table and pin is None and not contains_any(greens, *end_xy):
        # A line drawn from the green back to the tee starts on its green, and its end finds
        # the nearest other green: the hole was played to another hole's pin, without a word.
        starts_on = [_in_frame(local, p) for p in course.greens_near(tee, 1.0)]
        if contains_any(starts_on, 0.0, 0.0):
            raise HoleError(
                f"{where}: hole {line.index}: its golf=hole line starts on a green and ends off "
                "one: drawn backwards? allowed is a line from the tee to the green (or a 'tee' "
                "and a 'pin' in a hole file)"
            )
    if pin is None:
        pin = tuple(line.lonlat[-1])
        if greens:
            green = min(
                greens, key=lambda g: 0 if contains(g, *end_xy) else _ring_distance_m(g, *end_xy)
            )
            pins_xy = np.column_stack(local.to_xy(course.pins[:, 0], course.pins[:, 1]))
            inside = np.flatnonzero(contains(green, pins_xy[:, 0], pins_xy[:, 1]))
            # Only pins within PIN_SEARCH_M of the green's box can count (a country's map has
            # thousands).
            lo = np.min([ring.min(axis=0) for ring in green], axis=0) - PIN_SEARCH_M
            hi = np.max([ring.max(axis=0) for ring in green], axis=0) + PIN_SEARCH_M
            close = np.flatnonzero(((pins_xy >= lo) & (pins_xy <= hi)).all(axis=1))
            near = sorted((_ring_distance_m(green, *pins_xy[k]), k) for k in close)
            if inside.size:
                pin = tuple(course.pins[inside[0]])
            elif near and near[0][0] <= PIN_SEARCH_M:
                pin = tuple(course.pins[near[0][1]])
    if not greens:
        anywhere = (
            " has no golf=green polygon"
            if not course.greens
            else (f" has no golf=green polygon within {GREEN_SEARCH_M:g} m of the hole's end")
        )
        if course.skipped:  # (a green whose geometry is broken is among them)
            anywhere += (f" it reads ({len(course.skipped)} feature(s) left out, their geometry "
                         f"unreadable; the first: {course.skipped[0]})")  # fmt: skip
        raise HoleError(
            f"{where}: hole {line.index} has no green: {map_path}{anywhere}, and a hole is "
            "played to a pin on its green; allowed is a map with its greens (or a hole without "
            "a 'map': 'length_m', 'width_m' and a 'surface')"
        )
    pin_xy = local.to_xy(*pin)
    if not any(contains(g, *pin_xy) for g in greens):
        nearest = min(_ring_distance_m(g, *pin_xy) for g in greens)
        raise HoleError(
            f"{where}: the pin [{pin[0]:.6f}, {pin[1]:.6f}] of hole {line.index} is outside "
            f"every green of {map_path} ({nearest:.1f} m from the nearest): give a 'pin' on a green"
        )
    if math.dist(local.to_xy(*pin), (0.0, 0.0)) < 1.0:
        raise HoleError(f"{where}: the tee and the pin of hole {line.index} are the same point")
    return tee, pin


def _map_hole(table, folder, where):
    """Frame, tee/pin, zones and boundary of a hole of a map."""
    map_path = folder / str(table["map"])
    try:
        course = read_course(map_path)
        if "hole" not in table:
            raise HoleError(
                f"{where}: 'hole' is missing: give the hole's ref or its position 1-"
                f"{len(course.holes)} in {map_path}"
            )
        line = course.hole(table["hole"])
    except HoleError as err:  # the map's own message, said of the TOML that names it
        if str(err).startswith(where):
            raise
        raise HoleError(f"{where}: 'map': {err}") from None
    tee, pin = tee_and_pin(course, line, where, table)
    frame = Frame.from_tee_pin(tee, pin)
    line_xy = np.column_stack(frame.to_xy(line.lonlat[:, 0], line.lonlat[:, 1]))
    zones = [(kind, _in_frame(frame, p)) for kind, p in course.zones]
    boundary = [_in_frame(frame, p) for p in course.boundary]
    return dict(
        frame=frame,
        pin_xy=(float(frame.to_xy(*pin)[0]), 0.0),
        zones=zones,
        boundary=boundary,
        line_xy=line_xy,
        index=line.index,
        ref=line.ref,
        par=line.par,
        name=hole_title(course.course_of(line), line),
        map_source=str(map_path),
        attribution=ATTRIBUTION,
        map_skipped=tuple(course.skipped),
    )


def _plain_hole(table, where, margin_m, cell_m):
    """A rectangle of one zone kind: frame (from tee and pin when given), pin and zones."""
    surface = table.get("surface", "fairway")
    if surface not in ZONE_INDEX or ZONE_PENALTY[surface]:
        playable = [k for k in ZONE_KINDS if not ZONE_PENALTY[k]]
        raise HoleError(f"{where}: 'surface' = {surface!r}: choose {', '.join(playable)}")
    tee, pin = _lonlat(table, "tee", where), _lonlat(table, "pin", where)
    if (tee is None) != (pin is None):
        raise HoleError(f"{where}: give both 'tee' and 'pin' as [lon, lat], or neither")
    frame = None
    if tee is not None:
        if "length_m" in table:
            raise HoleError(
                f"{where}: 'length_m' comes from 'tee' and 'pin': give one or the other"
            )
        frame = Frame.from_tee_pin(tee, pin)
        length = float(frame.to_xy(*pin)[0])
        if length < 1.0:
            raise HoleError(f"{where}: 'tee' and 'pin' are the same point")
    else:
        length = _number(table, "length_m", where, *SIZE_RANGE_M)
        if length is None:
            raise HoleError(
                f"{where}: a hole without a 'map' needs 'length_m' (or 'tee' and 'pin') "
                "and 'width_m'"
            )
    width = _number(table, "width_m", where, *SIZE_RANGE_M)
    if width is None:
        raise HoleError(f"{where}: a hole without a 'map' needs 'width_m'")
    x0, x1, y0, y1 = -margin_m, length + margin_m, -width / 2, width / 2
    # Half a cell wider than the grid, so that its edge nodes are inside (the crossing rule is
    # half-open).
    e = cell_m / 2
    rectangle = [np.array([[x0 - e, y0 - e], [x1 + e, y0 - e], [x1 + e, y1 + e], [x0 - e, y1 + e]])]
    return dict(
        frame=frame,
        pin_xy=(length, 0.0),
        zones=[(surface, rectangle)],
        boundary=[],
        extent_m=(x0, x1, y0, y1),
    )


def _grid_of(extent_m, cell_m):
    """(x0, y0, nx, ny) of the grid over ``extent_m`` = (x_min, x_max, y_min, y_max): its nodes
    on multiples of ``cell_m``, its first at or before each minimum, its last at or past each
    maximum."""
    x_min, x_max, y_min, y_max = extent_m
    x0 = math.floor(x_min / cell_m) * cell_m
    y0 = math.floor(y_min / cell_m) * cell_m
    return (
        x0,
        y0,
        int(math.ceil((x_max - x0) / cell_m)) + 1,
        int(math.ceil((y_max - y0) / cell_m)) + 1,
    )


def check_reach(length_m, reach_m, where):
    """HoleError where the pin is further than ``SIZE_RANGE_M``'s top from the tee, or the
    hole (its line from the tee, the tee and the pin) reaches further than that along or
    across: a point far off a hole's line made a grid of millions of nodes, built for half a
    minute before it was refused or played."""
    most = SIZE_RANGE_M[1]
    if length_m > most:
        raise HoleError(
            f"{where}: the pin is {length_m:,.1f} m from the tee: allowed: up to {most:,.0f} m "
            "(the longest holes are about 1,000 m)"
        )
    if reach_m > most:
        raise HoleError(
            f"{where}: its golf=hole line reaches {reach_m:,.0f} m from end to end, for a pin "
            f"{length_m:,.0f} m from the tee: allowed: up to {most:,.0f} m (a point of the "
            "line far off the hole: mend the map)"
        )


def _check_nodes(extent_m, cell_m, where):
    """HoleError, before anything is built, where the grid of ``extent_m`` at ``cell_m``
    (``_grid_of``, as ``Hole.terrain_over`` builds it) would have more than MAX_NODES nodes."""
    x_min, x_max, y_min, y_max = extent_m
    _, _, nx, ny = _grid_of(extent_m, cell_m)
    if nx * ny > MAX_NODES:
        least = math.sqrt((x_max - x_min) * (y_max - y_min) / MAX_NODES)
        raise HoleError(
            f"{where}: 'cell_m' = {cell_m:g} over {x_max - x_min:.0f} x {y_max - y_min:.0f} m "
            f"(the hole and its margin_m) is a grid of {nx:,} x {ny:,} nodes: allowed are at "
            f"most {MAX_NODES:,} (a cell_m of at least {math.ceil(least * 100) / 100:g} m, or a "
            "smaller margin_m)"
        )


def _elevation_heights(table, folder, where, frame):
    """The heights of an elevation file, relative to the tee, on a grid of the frame."""
    from mcrun.hole.elevation import load_elevation

    path = folder / str(table["elevation"])
    crs = table.get("elevation_crs")
    try:
        elevation = load_elevation(path, crs=crs)
    except (OSError, ValueError) as err:
        message = " ".join(str(err).split())
        raise HoleError(f"{where}: 'elevation': {message}") from None
    tee_h = float(np.asarray(elevation.height_m(frame.tee_lon_deg, frame.tee_lat_deg)))
    if not math.isfinite(tee_h):
        raise HoleError(f"{where}: the elevation {path} does not cover the tee")

    def heights(x0, y0, cell, nx, ny, rows=256):
        out = np.empty((ny, nx))
        x = x0 + np.arange(nx) * cell
        for start in range(0, ny, rows):
            y = y0 + np.arange(start, min(start + rows, ny)) * cell
            lon, lat = frame.to_lonlat(x[None, :], y[:, None])
            out[start : start + y.size] = np.asarray(elevation.height_m(lon, lat)) - tee_h
        bad = ~np.isfinite(out)
        if bad.any():
            edge = bad[0].any() or bad[-1].any() or bad[:, 0].any() or bad[:, -1].any()
            iy, ix = np.argwhere(bad)[0]
            at = f"x = {x0 + ix * cell:.1f} m, y = {y0 + iy * cell:.1f} m"
            if edge:
                raise HoleError(
                    f"{where}: the elevation {path} does not cover the hole's grid "
                    f"({bad.sum()} of {bad.size} nodes have no height, first at {at}): "
                    "give an elevation covering it, or a smaller 'margin_m'"
                )
            raise HoleError(
                f"{where}: the elevation {path} has holes (NaN) inside the hole's area: "
                f"{bad.sum()} nodes, first at {at}; fill them"
            )
        return out

    return heights, f"elevation {path}"


def _shape_heights(table, where):
    """The heights of an analytic shape, relative to its height at the tee."""
    from mcrun.hole.shapes import shape_height

    shape = table["shape"]
    if isinstance(shape, str):
        kind, params = shape, {}
    elif isinstance(shape, dict) and isinstance(shape.get("kind"), str):
        kind, params = shape["kind"], {k: v for k, v in shape.items() if k != "kind"}
    else:
        raise HoleError(f"{where}: 'shape' must be a kind or a table with 'kind' and parameters")
    try:
        tee_h = float(np.asarray(shape_height(kind, params, np.zeros(1), np.zeros(1)))[0])
    except ValueError as err:
        raise HoleError(f"{where}: 'shape': {' '.join(str(err).split())}") from None

    def heights(x0, y0, cell, nx, ny):
        x = x0 + np.arange(nx) * cell
        y = y0 + np.arange(ny) * cell
        xx, yy = np.meshgrid(x, y)
        return np.asarray(shape_height(kind, params, xx, yy), dtype=float) - tee_h

    return heights, f"shape {kind}"


def hole_from_table(table, folder, source):
    """The Hole of a ``[hole]`` table (or a hole file's keys): ``folder`` is the TOML's folder
    (relative paths start there), ``source`` names it in messages ("FILE [hole]")."""
    where = str(source)
    if not isinstance(table, dict):
        raise HoleError(f"{where}: the hole must be a table of keys ({', '.join(KEYS)})")
    unknown = sorted(set(table) - set(KEYS))
    if unknown:
        raise HoleError(f"{where}: unknown key '{unknown[0]}'; allowed: {', '.join(KEYS)}")
    if "elevation" in table and "shape" in table:
        raise HoleError(f"{where}: give 'elevation' or 'shape', not both")
    if "elevation_crs" in table and "elevation" not in table:
        raise HoleError(f"{where}: 'elevation_crs' without an 'elevation' file")
    folder = Path(folder)
    cell = _number(table, "cell_m", where, *CELL_RANGE_M, default=DEFAULT_CELL_M)
    margin = _number(table, "margin_m", where, *MARGIN_RANGE_M, default=DEFAULT_MARGIN_M)
    if "map" in table:
        for key in ("surface", "length_m", "width_m"):
            if key in table:
                raise HoleError(f"{where}: '{key}' is for a hole without a 'map'")
        parts = _map_hole(table, folder, where)
        # The hole line from the tee on (a tee moved up the hole leaves the line behind it).
        line = parts["line_xy"]
        xy = np.vstack([line[line[:, 0] > 0.0], [(0.0, 0.0), parts["pin_xy"]]])
        parts["extent_m"] = (
            xy[:, 0].min() - margin,
            xy[:, 0].max() + margin,
            xy[:, 1].min() - margin,
            xy[:, 1].max() + margin,
        )
    else:
        if "hole" in table:
            raise HoleError(f"{where}: 'hole' chooses a hole of a 'map', and there is none")
        parts = _plain_hole(table, where, margin, cell)
    x0, x1, y0, y1 = parts["extent_m"]
    check_reach(math.hypot(*parts["pin_xy"]), max(x1 - x0, y1 - y0) - 2 * margin, where)
    _check_nodes(parts["extent_m"], cell, where)
    heights, ground = None, "flat"
    if "elevation" in table:
        if parts["frame"] is None:
            raise HoleError(
                f"{where}: an 'elevation' needs the hole on the Earth: a 'map', or 'tee' and 'pin'"
            )
        heights, ground = _elevation_heights(table, folder, where, parts["frame"])
    elif "shape" in table:
        heights, ground = _shape_heights(table, where)
    par = table.get("par", parts.get("par"))
    if par is not None and (isinstance(par, bool) or par not in PAR_RANGE):
        if "par" not in table:  # the map's tag
            raise HoleError(
                f"{where}: the map's par of hole {parts['index']} is {par!r}: allowed is a whole "
                "number 2-7 (mend the map, or give 'par' in a hole file)"
            )
        raise HoleError(f"{where}: 'par' = {par!r} must be a whole number 2-7")
    par = None if par is None else int(par)  # (a TOML 3.0 was printed "par: 3.0")
    if "name" in table and not (isinstance(table["name"], str) and table["name"].strip()):
        # (5 was named "5"; "" fell back to the file's name)
        raise HoleError(f"{where}: 'name' = {table['name']!r}: allowed: a name (text), or no "
                        "'name' for the map's")  # fmt: skip
    name = tag_text(table.get("name", parts.get("name")))
    colour = table.get("penalty_areas")
    if colour is not None:
        if colour not in PENALTY_COLOURS:
            raise HoleError(
                f"{where}: 'penalty_areas' = {colour!r}: choose {', '.join(PENALTY_COLOURS)}"
            )
        kind = PENALTY_COLOURS[colour]
        parts["zones"] = [(kind if k in PENALTY_ZONES else k, p) for k, p in parts["zones"]]
    hole = Hole(
        source=where,
        frame=parts["frame"],
        pin_xy=parts["pin_xy"],
        zones=parts["zones"],
        boundary=parts["boundary"],
        extent_m=parts["extent_m"],
        cell_m=cell,
        turf=_turfs(table, where),
        index=parts.get("index"),
        ref=parts.get("ref"),
        par=par,
        name=None if name is None else str(name),
        map_source=parts.get("map_source"),
        attribution=parts.get("attribution"),
        map_skipped=parts.get("map_skipped", ()),
        ground=ground,
        line_xy=parts.get("line_xy"),
        putting=_putting(table, where, folder),
        _heights=heights,
    )
    return hole
