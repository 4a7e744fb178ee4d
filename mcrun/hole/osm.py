"""A golf course as OpenStreetMap draws it, read from a GeoJSON FeatureCollection (as Overpass
tools and QGIS export it).

What is read: ``golf=hole`` LineStrings (tee to green; ``ref``, ``par``, ``name`` when
present), the zone polygons and multipolygons (``golf=tee|fairway|green|fringe|bunker|rough|
water_hazard|lateral_water_hazard``, ``natural=water``), ``golf=pin`` points and the
``leisure=golf_course`` boundary. Everything else (cart paths, buildings) is left out.
Coordinates stay WGS84 lon/lat here; ``hole.Hole`` puts them in the hole's frame.
"""

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from mcrun.hole.errors import HoleError
from mcrun.hole.zones import zone_of_tags

ATTRIBUTION = "(c) OpenStreetMap contributors, ODbL"


@dataclass(frozen=True)
class HoleLine:
    """One ``golf=hole`` line: its 1-based position among the file's holes, its tags and its
    points ((n, 2) lon, lat deg, tee first)."""

    index: int
    ref: str | None
    par: int | None
    name: str | None
    lonlat: np.ndarray
    feature: str  # the feature's id, or "feature N"


@dataclass(frozen=True)
class Course:
    """A course's holes, zones (kind, polygon: a list of (n, 2) lon/lat rings, outer first),
    pins ((n, 2) lon/lat) and boundary polygons (empty: no boundary mapped)."""

    source: str
    name: str | None
    holes: list = field(default_factory=list)
    zones: list = field(default_factory=list)
    pins: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    boundary: list = field(default_factory=list)

    def hole(self, key):
        """The hole whose ``ref`` is ``key`` (a string), else whose position is ``key``
        (1-based, in file order); HoleError saying how many there are."""
        for line in self.holes:
            if line.ref is not None and line.ref == str(key):
                return line
        try:
            index = int(key)
        except (TypeError, ValueError):
            index = None
        if index is not None and str(index) == str(key).strip() and 1 <= index <= len(self.holes):
            return self.holes[index - 1]
        refs = [h.ref for h in self.holes if h.ref is not None]
        refs_text = f" or a ref ({', '.join(refs)})" if refs else " (the file has no ref tags)"
        raise HoleError(
            f"{self.source}: hole {key!r} does not exist: the map has {len(self.holes)} "
            f"golf=hole lines; give a position 1-{len(self.holes)}{refs_text}"
        )


def _points(coords, where, depth):
    """``coords`` as float arrays nested ``depth`` deep (0: one (n, 2) array)."""
    try:
        if depth == 0:
            a = np.asarray(coords, dtype=float)
            if a.ndim != 2 or a.shape[0] < 2 or a.shape[1] < 2 or not np.isfinite(a).all():
                raise ValueError
            return a[:, :2]
        return [_points(c, where, depth - 1) for c in coords]
    except (TypeError, ValueError):
        raise HoleError(f"{where}: its coordinates are not lists of [lon, lat] points") from None


def _polygons(geometry, where):
    """The polygons (lists of rings) of a Polygon or MultiPolygon geometry."""
    kind = geometry.get("type")
    if kind == "Polygon":
        return [_points(geometry.get("coordinates"), where, 1)]
    if kind == "MultiPolygon":
        return _points(geometry.get("coordinates"), where, 2)
    return []


def _int_or_none(value):
    try:
        return int(str(value).strip())
    except (TypeError, ValueError):
        return None


def read_course(path):
    """The Course of the GeoJSON FeatureCollection at ``path``; HoleError (one line naming the
    file) when it is not one or a feature that is read is malformed."""
    path = Path(path)
    source = str(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise HoleError(f"{source}: cannot read the map: {err.strerror or err}") from None
    except UnicodeDecodeError:
        raise HoleError(f"{source}: is not a GeoJSON file (not UTF-8 text)") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as err:
        raise HoleError(
            f"{source}: is not a GeoJSON file (line {err.lineno}: {err.msg}); "
            "give a FeatureCollection as Overpass tools or QGIS export it"
        ) from None
    if not isinstance(data, dict) or data.get("type") != "FeatureCollection":
        got = data.get("type") if isinstance(data, dict) else type(data).__name__
        raise HoleError(f"{source}: is a GeoJSON {got!s}, not a FeatureCollection")
    features = data.get("features")
    if not isinstance(features, list):
        raise HoleError(f"{source}: its 'features' is not a list")
    holes, zones, pins, boundary, name = [], [], [], [], None
    for k, feature in enumerate(features, 1):
        if not isinstance(feature, dict) or not isinstance(feature.get("geometry"), dict):
            continue
        tags = feature.get("properties") or {}
        if not isinstance(tags, dict):
            continue
        geometry = feature["geometry"]
        where = f"{source}: feature {feature.get('id') or k}"
        golf = tags.get("golf")
        if golf == "hole" and geometry.get("type") == "LineString":
            lonlat = _points(geometry.get("coordinates"), where, 0)
            holes.append(
                HoleLine(
                    index=len(holes) + 1,
                    ref=None if tags.get("ref") is None else str(tags["ref"]),
                    par=_int_or_none(tags.get("par")),
                    name=tags.get("name"),
                    lonlat=lonlat,
                    feature=str(feature.get("id") or f"feature {k}"),
                )
            )
        elif golf == "pin" and geometry.get("type") == "Point":
            point = _points([geometry.get("coordinates"), geometry.get("coordinates")], where, 0)
            pins.append(point[0])
        elif tags.get("leisure") == "golf_course":
            polygons = _polygons(geometry, where)
            boundary.extend(polygons)
            if polygons and name is None:
                name = tags.get("name")
        else:
            kind = zone_of_tags(tags)
            if kind is not None:
                zones.extend((kind, polygon) for polygon in _polygons(geometry, where))
    if not holes:
        raise HoleError(f"{source}: has no golf=hole LineString: it is not a golf course map")
    return Course(
        source=source,
        name=name,
        holes=holes,
        zones=zones,
        pins=np.array(pins, dtype=float).reshape(-1, 2),
        boundary=boundary,
    )
