"""What a run records of its geometry, and reading it back: the frame its positions are in, the
tee, the pin, the aim and each point's target, and on a hole the map its pictures draw.

A run records them in its provenance (``mcrun.run.plan.provenance``), so that it describes
itself: a reader needs neither the scenario nor the hole's map and elevation files, which may
have moved. Two keys:

- ``geometry`` (every file of the run; a few hundred bytes, plus a pair a point):

  - ``surface``: ``"hole"`` or ``"plane"``;
  - ``frame``: the frame of every position the run writes (x_m, y_m, carry_m, final_x_m, ...):
    its ``origin`` (the tee; on a plane, where the ball is struck), ``origin_lon_deg``,
    ``origin_lat_deg`` and ``origin_height_m`` (WGS84; null for a hole without lon/lat and on
    a plane), ``heading_deg`` (the bearing of +x, clockwise from true north; null likewise)
    and ``axes``, in words: x from the tee towards the pin (on a plane, along the target
    line), y to its right seen from the tee, metres in the plane tangent to the WGS84
    ellipsoid at the tee (``mcrun.hole.geo.Frame``), heights relative to the tee's ground;
  - ``tee_xy_m`` ([0, 0]) and ``pin_xy_m`` (null on a plane), in the frame;
  - ``starts_xy_m``: per point, where its shots were struck, in the frame (the tee, [0, 0],
    unless the point starts elsewhere on the hole; a run written before points could start
    elsewhere has no such key: the tee);
  - ``aim_deg``: per point, the bearing of its aim line from its start, degrees, + to the right
    of +x (clockwise seen from above); a shot's start line in the frame is its sampled
    ``azimuth_deg`` (the shots' column, about the aim line) plus its point's aim;
    ``aim_sense`` says so in words;
  - ``targets_xy_m``: per point, its target in the frame (the scenario's, on a hole the pin
    by default), null where the point has none (its statistics are about its mean finish);
  - ``hole`` (null on a plane): its name, source, par, ref and position in its map, the map
    file's name and the attribution its data asks for, the ground (``"flat"``, ``"elevation
    FILE"``, ``"shape KIND"``), the tee-to-pin length (m), the grid's cell (m), the hole line
    in the frame (null without a map) and the box of the green that holds the pin (x_min,
    x_max, y_min, y_max in the frame; null without a green).

- ``hole_map`` (on a hole; only in summary.parquet, and in a file that stands alone such as the
  aim table: the other files of a run, and a Dask run's many parts, do not repeat it): the
  grid the kernel played on, as its pictures draw it: ``x0_m``, ``y0_m``, ``cell_m``, ``nx``,
  ``ny`` (node [iy, ix] at (x0_m + ix cell_m, y0_m + iy cell_m)), ``zone_kinds`` (the zone
  codes' names), ``zone`` (the (ny, nx) int8 codes) and ``height_m`` (the (ny, nx) float64
  heights relative to the tee, exactly as played; null on flat ground), each array as
  base64 of zlib of its little-endian bytes. The library's holes take 1-6 kB of zones and, where
  the ground has a shape or an elevation, 3 kB (a two-tier shape) to 0.62 MB (drive-real-ground:
  99,000 nodes of a survey) of heights; summary.parquet holds its metadata twice (the Arrow
  schema repeats it), 1.6 MB in all for drive-real-ground.

A run written before its geometry was recorded has neither key: ``read_geometry`` and
``read_hole_map`` return None and its pictures are drawn without a map.
"""

import base64
import math
import zlib
from dataclasses import dataclass

import numpy as np

from mcrun.hole.geo import Frame as GeoFrame
from mcrun.hole.zones import ZONE_KINDS

GEOMETRY_KEY = "geometry"
MAP_KEY = "hole_map"
VERSION = 1
AXES = (
    "x from the tee towards the pin (on a plane, along the target line), y to its right seen "
    "from the tee; metres in the plane tangent to the WGS84 ellipsoid at the tee; heights "
    "relative to the tee's ground"
)
AIM_SENSE = (
    "bearing of the aim line from the point's start (the tee unless starts_xy_m says), degrees, "
    "+ right of +x (clockwise seen from above); "
    "a shot's start line in the frame is its azimuth_deg plus its point's aim"
)


# --- the record --------------------------------------------------------------------------------


def _pair(xy):
    return None if xy is None else [float(xy[0]), float(xy[1])]


def green_box(hole):
    """(x_min, x_max, y_min, y_max) of the green that holds the pin (the nearest green) of a
    ``mcrun.hole.hole.Hole``, in its frame; None when it has no green."""
    best = None
    px, py = hole.pin_xy
    for kind, polygon in hole.zones:
        if kind != "green" or not polygon:
            continue
        xy = np.concatenate(polygon)
        box = (xy[:, 0].min(), xy[:, 0].max(), xy[:, 1].min(), xy[:, 1].max())
        gap = math.hypot(
            max(box[0] - px, 0.0, px - box[1]),
            max(box[2] - py, 0.0, py - box[3]),
        )
        if best is None or gap < best[0]:
            best = (gap, box)
    return None if best is None else tuple(float(v) for v in best[1])


def record(hole, aims_rad, targets_m, starts_m=None):
    """The ``geometry`` record of a run on ``hole`` (a ``mcrun.hole.hole.Hole``, None on a
    plane) whose points are aimed ``aims_rad`` (rad, + right; None: along +x), have the
    targets ``targets_m`` ((x, y) m or None) and are struck from ``starts_m`` ((x, y) m;
    default the tee), one of each per point."""
    targets = [_pair(t) for t in targets_m]
    aims_deg = [0.0 if a is None else math.degrees(float(a)) for a in aims_rad]
    starts = [[0.0, 0.0]] * len(targets) if starts_m is None else [_pair(s) for s in starts_m]
    frame = {
        "origin": "tee" if hole is not None else "where the ball is struck",
        "origin_lon_deg": None,
        "origin_lat_deg": None,
        "origin_height_m": None,
        "heading_deg": None,
        "axes": AXES,
    }
    out = {
        "version": VERSION,
        "surface": "plane" if hole is None else "hole",
        "frame": frame,
        "tee_xy_m": [0.0, 0.0],
        "pin_xy_m": None,
        "starts_xy_m": starts,
        "aim_deg": aims_deg,
        "aim_sense": AIM_SENSE,
        "targets_xy_m": targets,
        "hole": None,
    }
    if hole is None:
        return out
    if hole.frame is not None:
        frame.update(
            origin_lon_deg=hole.frame.tee_lon_deg,
            origin_lat_deg=hole.frame.tee_lat_deg,
            origin_height_m=0.0,  # the frame's origin is on the ellipsoid under the tee
            heading_deg=math.degrees(hole.frame.heading_rad),
        )
    out["pin_xy_m"] = _pair(hole.pin_xy)
    box = green_box(hole)
    out["hole"] = {
        "name": hole.name,
        "source": hole.source,
        "par": hole.par,
        "ref": hole.ref,
        "index": hole.index,
        "map_source": hole.map_source,
        "attribution": hole.attribution,
        "ground": hole.ground,
        "length_m": hole.length_m,
        "cell_m": float(hole.cell_m),
        "line_xy_m": None if hole.line_xy is None else np.asarray(hole.line_xy, float).tolist(),
        "green_box_m": None if box is None else list(box),
    }
    return out


def _pack(array, dtype):
    data = np.ascontiguousarray(array, dtype=np.dtype(dtype).newbyteorder("<")).tobytes()
    return base64.b64encode(zlib.compress(data, 6)).decode("ascii")


def _unpack(text, dtype, shape):
    data = zlib.decompress(base64.b64decode(text))
    return np.frombuffer(data, dtype=np.dtype(dtype).newbyteorder("<")).reshape(shape).copy()


def record_map(hole):
    """The ``hole_map`` record of ``hole`` (its terrain's grid of zones and heights)."""
    t = hole.terrain()
    ny, nx = t.zone.shape
    flat = hole.ground == "flat"
    return {
        "version": VERSION,
        "x0_m": float(t.x0_m),
        "y0_m": float(t.y0_m),
        "cell_m": float(t.cell_m),
        "nx": int(nx),
        "ny": int(ny),
        "zone_kinds": list(ZONE_KINDS),
        "zone": _pack(t.zone, np.int8),
        "height_m": None if flat else _pack(t.height_m, np.float64),
    }


# --- reading it back ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Frame:
    """The frame of a run's positions (``AXES``): its origin on the Earth and the bearing of
    +x, None where the run is not placed on the Earth."""

    origin_lon_deg: float | None
    origin_lat_deg: float | None
    origin_height_m: float | None
    heading_deg: float | None

    @property
    def on_earth(self):
        return self.origin_lon_deg is not None and self.heading_deg is not None

    def to_lonlat(self, x_m, y_m):
        """(lon_deg, lat_deg) of points of the frame; NaN when it is not on the Earth."""
        if not self.on_earth:
            shape = np.broadcast(np.asarray(x_m), np.asarray(y_m)).shape
            return np.full(shape, np.nan), np.full(shape, np.nan)
        geo = GeoFrame(self.origin_lon_deg, self.origin_lat_deg, math.radians(self.heading_deg))
        return geo.to_lonlat(x_m, y_m)


@dataclass(frozen=True)
class HoleFacts:
    """What a run recorded of its hole (``record``'s ``hole``)."""

    name: str | None
    source: str
    par: int | None
    ref: str | None
    index: int | None
    map_source: str | None
    attribution: str | None
    ground: str
    length_m: float
    cell_m: float
    line_xy: tuple | None  # ((x, y), ...) m in the frame
    green_box_m: tuple | None


@dataclass(frozen=True)
class RunGeometry:
    """A run's geometry as it recorded it: ``surface`` ("hole" or "plane"), its ``frame``,
    the tee and the pin in it (m), each point's aim (deg, + right of +x) and target (m, or
    None), and on a hole its ``hole`` facts."""

    surface: str
    frame: Frame
    tee_xy_m: tuple
    pin_xy_m: tuple | None
    aim_deg: tuple
    targets_xy_m: tuple
    hole: HoleFacts | None
    starts_xy_m: tuple = ()

    def start_xy(self, point):
        """Where ``point``'s shots were struck (m, in the frame): the tee unless it says."""
        return self.starts_xy_m[point] if point < len(self.starts_xy_m) else self.tee_xy_m

    @property
    def on_hole(self):
        return self.surface == "hole"

    def aim_rad(self, point):
        """The aim of ``point`` (rad, + right of +x)."""
        return math.radians(self.aim_deg[point])


@dataclass(frozen=True)
class HoleMap:
    """The map of a hole as a run recorded it: the grid of zone codes (``zone``, (ny, nx) of
    ``zone_kinds``) and heights (m, relative to the tee) with its origin and cell, the pin,
    and the hole's ``facts`` (``HoleFacts``: its name, ground, line, green, ...)."""

    zone: np.ndarray
    height_m: np.ndarray
    x0_m: float
    y0_m: float
    cell_m: float
    zone_kinds: tuple
    pin_xy: tuple
    facts: HoleFacts


def _tuple(xy):
    return None if xy is None else tuple(float(v) for v in xy)


def read_geometry(provenance):
    """The ``RunGeometry`` a run's provenance records, None when it records none (a run
    written before runs recorded their geometry)."""
    given = (provenance or {}).get(GEOMETRY_KEY)
    if not isinstance(given, dict):
        return None
    f = given["frame"]
    hole = given.get("hole")
    facts = None
    if hole is not None:
        line = hole.get("line_xy_m")
        facts = HoleFacts(
            name=hole.get("name"),
            source=hole.get("source") or "",
            par=hole.get("par"),
            ref=hole.get("ref"),
            index=hole.get("index"),
            map_source=hole.get("map_source"),
            attribution=hole.get("attribution"),
            ground=hole.get("ground") or "flat",
            length_m=float(hole["length_m"]),
            cell_m=float(hole["cell_m"]),
            line_xy=None if line is None else tuple(_tuple(xy) for xy in line),
            green_box_m=_tuple(hole.get("green_box_m")),
        )
    return RunGeometry(
        surface=given["surface"],
        frame=Frame(
            f.get("origin_lon_deg"),
            f.get("origin_lat_deg"),
            f.get("origin_height_m"),
            f.get("heading_deg"),
        ),
        tee_xy_m=_tuple(given["tee_xy_m"]),
        pin_xy_m=_tuple(given.get("pin_xy_m")),
        aim_deg=tuple(float(a) for a in given["aim_deg"]),
        targets_xy_m=tuple(_tuple(t) for t in given["targets_xy_m"]),
        hole=facts,
        starts_xy_m=tuple(_tuple(xy) for xy in given.get("starts_xy_m") or ()),
    )


def read_hole_map(provenance):
    """The ``HoleMap`` a run's provenance records, None when it records none."""
    geometry = read_geometry(provenance)
    given = (provenance or {}).get(MAP_KEY)
    if geometry is None or geometry.hole is None or not isinstance(given, dict):
        return None
    shape = (int(given["ny"]), int(given["nx"]))
    zone = _unpack(given["zone"], np.int8, shape)
    heights = given.get("height_m")
    height = np.zeros(shape) if heights is None else _unpack(heights, np.float64, shape)
    return HoleMap(
        zone=zone,
        height_m=height,
        x0_m=float(given["x0_m"]),
        y0_m=float(given["y0_m"]),
        cell_m=float(given["cell_m"]),
        zone_kinds=tuple(given["zone_kinds"]),
        pin_xy=geometry.pin_xy_m,
        facts=geometry.hole,
    )


def hole_map_of(hole):
    """The ``HoleMap`` of a ``mcrun.hole.hole.Hole`` in memory, as a run on it records it
    (for a picture of a hole that no run folder holds, such as an aim search's)."""
    return read_hole_map({GEOMETRY_KEY: record(hole, [], []), MAP_KEY: record_map(hole)})
