"""A golf course as OpenStreetMap draws it, read from a GeoJSON FeatureCollection (as Overpass
tools and QGIS export it).

What is read: ``golf=hole`` LineStrings (tee to green; ``ref``, ``par``, ``name`` when
present), the zone polygons and multipolygons (``golf=tee|fairway|green|fringe|bunker|rough|
water_hazard|lateral_water_hazard``, ``natural=water``), ``golf=pin`` points and the
``leisure=golf_course`` boundary. A ``golf=water_hazard`` is a yellow penalty area, a
``golf=lateral_water_hazard`` or ``natural=water`` a red one (``zones.ZONES``). Everything
else (cart paths, buildings) is left out. Coordinates stay WGS84 lon/lat here (checked:
longitudes in [-180, 180], latitudes in [-90, 90]); ``hole.Hole`` puts them in the hole's
frame.

An extract may hold many courses (a country's, as Overpass or Geofabrik cut it): a hole belongs
to the ``leisure=golf_course`` polygon that holds most of its line (the smallest, when they are
nested), and is titled by that course's name and its own number (``hole_title``).

Other formats are told apart from their first bytes (``sniff``), so that a KML, a GPX or an
OpenStreetMap XML file given as a map is named as what it is, with the formats accepted.
"""

import json
import math
import re
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from mcrun.hole.errors import HoleError
from mcrun.hole.geo import MEAN_RADIUS_M
from mcrun.hole.zones import contains, shoelace_area_m2, zone_of_tags
from mcrun.units import control_free

ATTRIBUTION = "(c) OpenStreetMap contributors, ODbL"


@dataclass(frozen=True)
class HoleLine:
    """One ``golf=hole`` line: its 1-based position among the file's holes, its tags and its
    points ((n, 2) lon, lat deg, tee first); a line whose points cannot be read has none
    (``lonlat`` None) and says why in ``problem`` (it keeps its position: the others keep
    their numbers, and choosing it says the problem)."""

    index: int
    ref: str | None
    par: int | str | None  # the tag as written where it is not one whole number
    name: str | None
    lonlat: np.ndarray | None
    feature: str  # the feature's id, or "feature N"
    problem: str | None = None


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
    courses: list = field(default_factory=list)  # (name or None, polygon): each golf_course
    # Why each zone, pin or course boundary whose geometry cannot be read was left out (a map
    # cut at its edge leaves such pieces); one line each.
    skipped: list = field(default_factory=list)

    @cached_property
    def greens(self):
        """The green polygons, in map order."""
        return [polygon for kind, polygon in self.zones if kind == "green"]

    @cached_property
    def _green_boxes(self):
        """(n, 4) lon_min, lat_min, lon_max, lat_max of each green's outer ring."""
        boxes = [(*p[0].min(axis=0), *p[0].max(axis=0)) for p in self.greens]
        return np.array(boxes, dtype=float).reshape(-1, 4)

    @cached_property
    def _course_boxes(self):
        """(n, 4) lon_min, lat_min, lon_max, lat_max of each course polygon's outer ring."""
        boxes = [(*p[0].min(axis=0), *p[0].max(axis=0)) for _, p in self.courses]
        return np.array(boxes, dtype=float).reshape(-1, 4)

    def greens_near(self, lonlat, radius_m):
        """The greens whose bounding box comes within about ``radius_m`` of any of the points
        ``lonlat`` ((n, 2) or (2,) lon/lat deg), in map order: a country's map has thousands."""
        points = np.asarray(lonlat, dtype=float).reshape(-1, 2)
        boxes = self._green_boxes
        near = np.zeros(len(boxes), dtype=bool)
        for lon, lat in points:
            dlat = math.degrees(radius_m / MEAN_RADIUS_M)
            dlon = dlat / max(math.cos(math.radians(lat)), 1e-6)
            near |= (
                (boxes[:, 0] - dlon <= lon)
                & (lon <= boxes[:, 2] + dlon)
                & (boxes[:, 1] - dlat <= lat)
                & (lat <= boxes[:, 3] + dlat)
            )
        return [g for g, keep in zip(self.greens, near, strict=True) if keep]

    def course_of(self, line):
        """The name of the ``leisure=golf_course`` polygon ``line`` (a HoleLine) lies in: the one
        holding most of its points, the smallest of those when nested; None when it lies in
        none, or that course has no name."""
        best = None
        if line.lonlat is None:
            return None
        lon, lat = line.lonlat[:, 0], line.lonlat[:, 1]
        boxes = self._course_boxes
        near = (
            (boxes[:, 0] <= lon.max())
            & (lon.min() <= boxes[:, 2])
            & (boxes[:, 1] <= lat.max())
            & (lat.min() <= boxes[:, 3])
        )
        for k in np.flatnonzero(near):  # a country's map has hundreds of courses
            name, polygon = self.courses[k]
            inside = int(contains(polygon, lon, lat).sum())
            if inside:
                rank = (-inside, shoelace_area_m2(polygon))
                if best is None or rank < best[0]:
                    best = (rank, name)
        return None if best is None else best[1]

    def hole(self, key):
        """The hole whose ``ref`` is ``key`` (a string) or holds it among its values (``1;10``:
        a nine played twice), else whose position is ``key`` (1-based, in file order); "#N" is
        always the position N. HoleError saying how many there are, or, when several holes
        share the ref (a map of many courses), which."""
        text = str(key).strip()
        if not text.startswith("#"):
            matches = [line for line in self.holes if _has_ref(line, text)]
            if len(matches) == 1:
                return playable(matches[0])
            if matches:
                shown = ", ".join(
                    f"#{m.index} on {self.course_of(m) or 'no named course'}" for m in matches[:5]
                )
                more = f" and {len(matches) - 5} more" if len(matches) > 5 else ""
                raise HoleError(
                    f"{self.source}: hole {key!r}: {len(matches)} holes have ref {text} "
                    f"({shown}{more}): "
                    "give the one you mean by its position in the file, as '#N'"
                )
        position = text.removeprefix("#")
        if position.isascii() and position.isdigit() and 1 <= int(position) <= len(self.holes):
            return playable(self.holes[int(position) - 1])
        refs = list(dict.fromkeys(h.ref for h in self.holes if h.ref is not None))
        refs_text = " (the file has no ref tags)"
        if refs:
            refs_text = f" or a ref ({', '.join(refs[:20])}{', ...' if len(refs) > 20 else ''})"
        raise HoleError(
            f"{self.source}: hole {key!r} does not exist: the map has {len(self.holes)} "
            f"golf=hole lines; give a position 1-{len(self.holes)}{refs_text}"
        )


def _has_ref(line, text):
    """Whether the hole's ``ref`` is ``text`` or one of its ';'-separated values."""
    if line.ref is None:
        return False
    return line.ref == text or text in (part.strip() for part in line.ref.split(";"))


def playable(line):
    """``line``, or HoleError saying why its points cannot be read."""
    if line.problem is not None:
        raise HoleError(line.problem)
    return line


def _points(coords, where, depth):
    """``coords`` as float arrays nested ``depth`` deep (0: one (n, 2) array), each point a
    longitude in [-180, 180] and a latitude in [-90, 90]."""
    try:
        if depth > 0:
            coords = list(coords)
        else:
            a = np.asarray(coords, dtype=float)
            if a.size == 0:
                a = a.reshape(0, 2)
            if a.ndim != 2 or a.shape[1] < 2:
                raise ValueError
            a = a[:, :2]
    except (TypeError, ValueError):
        raise HoleError(f"{where}: its coordinates are not lists of [lon, lat] points") from None
    if depth > 0:
        return [_points(c, where, depth - 1) for c in coords]
    if a.shape[0] < 2:
        raise HoleError(
            f"{where}: {a.shape[0]} point{'s' * (a.shape[0] != 1)}: allowed is a line or a ring "
            "of at least 2 [lon, lat] points"
        )
    if not np.isfinite(a).all():
        k = int(np.flatnonzero(~np.isfinite(a).all(axis=1))[0])
        raise HoleError(
            f"{where}: point {k + 1} is [{a[k, 0]:g}, {a[k, 1]:g}]: allowed are finite "
            "[lon, lat] numbers"
        )
    bad = (np.abs(a[:, 0]) > 180.0) | (np.abs(a[:, 1]) > 90.0)
    if bad.any():
        lon, lat = a[np.flatnonzero(bad)[0]]
        raise HoleError(
            f"{where}: point [{lon:g}, {lat:g}] is off the Earth: allowed are [lon, lat] in "
            "degrees (WGS84), longitude in [-180, 180], latitude in [-90, 90]"
        )
    return a


def _polygons(geometry, where):
    """The polygons (lists of rings) of a Polygon or MultiPolygon geometry; HoleError for a
    polygon without a ring or a ring of fewer than 3 points, which encloses nothing."""
    kind = geometry.get("type")
    if kind == "Polygon":
        polygons = [_points(geometry.get("coordinates"), where, 1)]
    elif kind == "MultiPolygon":
        polygons = _points(geometry.get("coordinates"), where, 2)
    else:
        return []
    for polygon in polygons:
        if not polygon:
            raise HoleError(f"{where}: a polygon without a ring: allowed is an outer ring of at "
                            "least 3 [lon, lat] points")  # fmt: skip
        for ring in polygon:
            if len(np.unique(ring, axis=0)) < 3:
                raise HoleError(
                    f"{where}: a ring of {len(ring)} points enclosing nothing: "
                    "allowed is a ring of 3 distinct [lon, lat] points or more"
                )
    return polygons


def _par(value):
    """A ``par`` tag: its whole number, None where there is none, the tag as written where it
    is not one whole number (``4;5``, men's and women's: refused where the par is used, as a
    par out of range is, rather than taken for no par)."""
    if value is None or (isinstance(value, str) and not value.strip()):
        return None
    if isinstance(value, float) and value.is_integer():  # a real field's 4.0 (QGIS)
        return int(value)
    text = str(value).strip()
    whole = re.fullmatch(r"\+?(\d+)(?:\.0*)?", text)  # (int() read "4_0" as 40)
    return int(whole.group(1)) if whole else text


TAG_MOST = 200  # characters of a name or a ref kept (a longer one is cut, ending "...")


def tag_text(value):
    """A tag's (or a hole file's name's) text as printed: on one line (a name with a line
    break broke the listing's lines), without control characters (an escape sequence or a
    right-to-left override reached the terminal), at most ``TAG_MOST`` characters; None
    where empty. A list (as some converters write a multi-valued tag) is joined by ';', as
    OpenStreetMap writes one."""
    if value is None:
        return None
    if isinstance(value, list):
        value = ";".join(str(v) for v in value)
    text = " ".join(str(value).split())
    text = control_free(text)
    if len(text) > TAG_MOST:
        text = text[: TAG_MOST - 3] + "..."
    return text or None


def _is_number(text):
    return isinstance(text, str) and text.strip().isdigit()


def hole_title(course_name, line):
    """A hole's title: its course's name and its number (its ``ref``, else a ``name`` that is
    a bare number, else its position in the file), then its own name when it has a real one:
    "Riverside, hole 3", "Links, hole 12: Amen Corner", "hole 3" without a course."""
    name = None if line.name is None else str(line.name).strip() or None
    number = line.ref or (name if _is_number(name) else None) or str(line.index)
    title = f"hole {number}" if course_name is None else f"{course_name}, hole {number}"
    if name is not None and not _is_number(name) and name != line.ref:
        title += f": {name}"
    return title


# What a file that is not a GeoJSON course map is, by its first bytes: (prefix, what it is).
_FORMATS = (
    (b"PK\x03\x04", "a ZIP archive (a KMZ or a zipped shapefile?)"),
    (b"SQLite format 3\x00", "a GeoPackage or SQLite database"),
    (b"%PDF", "a PDF document"),
    (b"\x89PNG", "a PNG image"),
    (b"\xff\xd8\xff", "a JPEG image"),
    (b"\x00\x00\x27\x0a", "an ESRI shapefile (.shp)"),
    (b"\x1f\x8b", "a gzip archive"),
)
_XML_ROOTS = (
    ("<kml", "a KML file (Google Earth)"),
    ("<gpx", "a GPX file (GPS tracks)"),
    ("<osm", "an OpenStreetMap XML file (.osm)"),
    ("<gml", "a GML file"),
    ("<wfs:", "a GML file"),
    ("<svg", "an SVG image"),
    ("<html", "an HTML page"),
    ("<!doctype html", "an HTML page"),
)
ACCEPTED = "a GeoJSON FeatureCollection (.geojson, .json) with OpenStreetMap golf tags"
CONVERT = "convert it, e.g. ogr2ogr -f GeoJSON course.geojson FILE, or export GeoJSON from Overpass"


def sniff(path):
    """What the file at ``path`` is when its first bytes say it is a map format mcrun does not
    read (KML, GPX, OSM XML, a KMZ or shapefile ...): a phrase such as "a KML file (Google
    Earth)"; None when they do not (it may be GeoJSON, TOML or anything else)."""
    try:
        with open(path, "rb") as f:
            head = f.read(4096)
    except OSError:
        return None
    for prefix, what in _FORMATS:
        if head.startswith(prefix):
            return what
    text = head.lstrip(b"\xef\xbb\xbf \t\r\n").decode("utf-8", "replace").lower()
    if text.startswith("<"):
        for root, what in _XML_ROOTS:
            if root in text:
                return what
        return "an XML file"
    return None


def read_course(path):
    """The Course of the GeoJSON FeatureCollection at ``path``; HoleError (one line naming the
    file) when it is not one. A feature whose geometry cannot be read does not stop the map (a
    map cut at its edge leaves such pieces): a hole line is kept, unplayable, with its
    ``problem``; a zone, pin or course boundary is left out, said in ``Course.skipped``."""
    path = Path(path)
    source = str(path)
    what = sniff(path)
    if what is not None:
        raise HoleError(f"{source}: is {what}, not a course map: allowed is {ACCEPTED}; {CONVERT}")
    try:
        text = path.read_text(encoding="utf-8-sig")  # (a byte-order mark, as Notepad saves)
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
    holes, zones, pins, boundary, courses, name, skipped = [], [], [], [], [], None, []
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
            try:
                lonlat, problem = _points(geometry.get("coordinates"), where, 0), None
            except HoleError as err:
                lonlat, problem = None, str(err)
            holes.append(
                HoleLine(
                    index=len(holes) + 1,
                    ref=tag_text(tags.get("ref")),
                    par=_par(tags.get("par")),
                    name=tag_text(tags.get("name")),
                    lonlat=lonlat,
                    feature=str(feature.get("id") or f"feature {k}"),
                    problem=problem,
                )
            )
        else:  # (a geometry that cannot be read raises before anything is added)
            try:
                if golf == "pin" and geometry.get("type") == "Point":
                    coordinates = geometry.get("coordinates")
                    pins.append(_points([coordinates, coordinates], where, 0)[0])
                elif tags.get("leisure") == "golf_course":
                    polygons = _polygons(geometry, where)
                    boundary.extend(polygons)
                    course_name = tag_text(tags.get("name"))
                    courses.extend((course_name, polygon) for polygon in polygons)
                    if polygons and name is None:
                        name = course_name
                else:
                    kind = zone_of_tags(tags)
                    if kind is not None:
                        zones.extend((kind, polygon) for polygon in _polygons(geometry, where))
            except HoleError as err:
                skipped.append(str(err).removeprefix(f"{source}: "))
    if not holes:
        raise HoleError(f"{source}: has no golf=hole LineString: it is not a golf course map")
    return Course(
        source=source,
        name=name,
        holes=holes,
        zones=zones,
        pins=np.array(pins, dtype=float).reshape(-1, 2),
        boundary=boundary,
        courses=courses,
        skipped=skipped,
    )
