"""A hole's ground heights from an elevation file: ``load_elevation(path, crs=None)``.

Three formats, told apart by the file's suffix:

- ``.tif``/``.tiff``: a GeoTIFF DEM (survey and national LiDAR data), read with ``tifffile``. Its
  place comes from its ModelPixelScale and ModelTiepoint tags (or ModelTransformation, without
  rotation) and its coordinate system from the GeoKey directory (GeographicTypeGeoKey or
  ProjectedCSTypeGeoKey, an EPSG code). With PixelIsArea (the default) a value is the pixel's
  mean and stands at its centre, half a pixel in from the tie point's corner; with PixelIsPoint
  it stands at the raster coordinate itself. GDAL_NODATA (tag 42113) marks missing heights;
  VerticalUnitsGeoKey in feet is converted to metres.
- ``.asc``: an ESRI ASCII grid (ncols, nrows, xllcorner/xllcenter, yllcorner/yllcenter, cellsize
  or dx and dy, NODATA_value). Its coordinate system is ``crs``, else the WKT of a ``.prj`` file
  beside it, else WGS84 lon/lat when its coordinates can be longitudes and latitudes.
- ``.csv``: survey points, columns lon,lat,elevation (or lon_deg,lat_deg,elevation_m,
  lon,lat,alt and the other names of ``CSV_COLUMNS``, or x,y,z in the coordinate system
  ``crs``), gridded once here. Copies of a point (rows with the same coordinates, or the same
  node of a lattice) are one point when their heights agree to ``DUPLICATE_TOLERANCE_M``, and
  refused, naming the point and its rows, when they do not. Points on a regular lattice are
  that grid, node for node (a missing node is filled linearly from its neighbours); scattered
  points are interpolated linearly over their Delaunay triangulation onto a square grid whose
  spacing is the points' mean spacing, sqrt(area of their convex hull / number of points), NaN
  outside the hull.

The grid keeps its own coordinates; ``height_m(lon, lat)`` projects WGS84 lon/lat into them
(``pyproj`` for any other system than WGS84 lon/lat) and interpolates bilinearly between the
four nodes around the point, so a plane in the grid's coordinates is reproduced exactly. Outside
the nodes' extent, or next to a missing node, the height is NaN.

A height outside ``HEIGHT_LIMITS_M`` (the ground anywhere on Earth), an infinity or a fill value
no nodata marks among them, is refused. Any file that cannot be read raises ``ElevationError``
with one line naming the file, what is wrong and what is allowed. ``tifffile``, ``pyproj`` and
``scipy`` are optional: the ``hole`` extra installs the first two (``pip install 'mcrun[hole]'``).
"""

import math
import re
from dataclasses import dataclass, field

import numpy as np

from mcrun.errors import InputError
from mcrun.units import path_of

EARTH_RADIUS_M = 6_371_008.8  # mean radius (IUGG): cell sizes in degrees shown in metres
MAX_NODES = 25_000_000  # a grid gridded from points: 200 MB of float64 at most

# Heights of the ground anywhere on Earth (m): the Dead Sea's shore is 430 m below sea level,
# Everest 8,849 m above it. A height outside them is a fill value or a damaged file, not ground.
HEIGHT_LIMITS_M = (-500.0, 9000.0)
EDGE_CELLS = 1e-9  # how far outside the nodes' extent, in cells, a point still counts as on it
HOLE_EXTRA = "pip install 'mcrun[hole]'"

# GeoTIFF tags and GeoKeys (GeoTIFF 1.1, OGC 19-008r4)
TAG_PIXEL_SCALE = 33550
TAG_TIEPOINT = 33922
TAG_TRANSFORMATION = 34264
TAG_GEOKEYS = 34735
TAG_GDAL_NODATA = 42113
KEY_MODEL_TYPE = 1024  # 1 projected, 2 geographic, 3 geocentric
KEY_RASTER_TYPE = 1025  # 1 PixelIsArea, 2 PixelIsPoint
KEY_GEOGRAPHIC = 2048
KEY_PROJECTED = 3072
KEY_VERTICAL_UNITS = 4099
USER_DEFINED = 32767
PIXEL_IS_AREA = 1
PIXEL_IS_POINT = 2
VERTICAL_UNITS_M = {9001: 1.0, 9002: 0.3048, 9003: 1200.0 / 3937.0}  # metre, foot, US survey foot

CSV_COLUMNS = (
    "lon_deg,lat_deg,elevation_m (or lon|longitude|lng|long, lat|latitude, and "
    "elevation|elev|ele|alt|altitude|height|z, any with _m), or x,y,z with a crs"
)
LON_NAMES = ("lon_deg", "lon", "longitude", "lng", "long", "longitude_deg")
LAT_NAMES = ("lat_deg", "lat", "latitude", "latitude_deg")
X_NAMES = ("x_m", "x", "easting", "easting_m")
Y_NAMES = ("y_m", "y", "northing", "northing_m")
# Heights in metres under the names GPS, GIS and survey exports give them ("alt" and
# "altitude": GPS loggers, Google Earth; "ele": GPX and OpenStreetMap). Feet are not read.
Z_NAMES = (
    "elevation_m",
    "elevation",
    "elev_m",
    "elev",
    "ele",
    "height_m",
    "height",
    "alt_m",
    "alt",
    "altitude_m",
    "altitude",
    "z_m",
    "z",
)
# Copies of a point whose heights differ by no more than this are one point (their mean);
# survey heights are given to the millimetre or the centimetre.
DUPLICATE_TOLERANCE_M = 0.01


class ElevationError(InputError):
    """An elevation file that cannot be used; its message is one line naming the file."""


@dataclass(frozen=True)
class _Crs:
    """A horizontal coordinate system and the way from WGS84 lon/lat into it."""

    label: str
    geographic: bool  # coordinates are lon/lat degrees
    metres_per_unit: float  # of a projected system's axes
    forward: object = None  # pyproj Transformer WGS84 -> this; None: this is WGS84 lon/lat
    inverse: object = None


_WGS84 = _Crs("EPSG:4326", True, 1.0)
_WGS84_NAMES = {"epsg:4326", "ogc:crs84", "wgs84", "wgs 84", "crs84", "4326"}


def _place(value, name, what):
    """The _Crs of ``value`` (an EPSG code, 'EPSG:n', WKT or anything pyproj reads), found in
    ``what`` of file ``name``; ElevationError when it cannot be placed."""
    text = str(value).strip()
    if text.lower() in _WGS84_NAMES:
        return _WGS84
    try:
        import pyproj
    except ImportError:
        raise ElevationError(
            f"{name}: {what} {_short(text)} needs pyproj to be placed: {HOLE_EXTRA}"
        ) from None
    try:
        crs = pyproj.CRS.from_user_input(int(text) if text.isdigit() else text)
    except pyproj.exceptions.CRSError:
        raise ElevationError(
            f"{name}: {what} {_short(text)} is not a coordinate system pyproj knows: allowed is "
            "an EPSG code such as 'EPSG:32633' or a WKT"
        ) from None
    horizontal = crs.sub_crs_list[0] if crs.is_compound else crs
    if not (horizontal.is_geographic or horizontal.is_projected):
        raise ElevationError(
            f"{name}: {what} {_short(text)} is neither geographic nor projected: allowed is a "
            "lon/lat or a map-projection coordinate system"
        )
    authority = horizontal.to_authority()
    label = f"{authority[0]}:{authority[1]}" if authority else horizontal.name
    if label == "EPSG:4326":
        return _WGS84
    factor = 1.0
    if horizontal.is_projected:
        factor = horizontal.axis_info[0].unit_conversion_factor
    return _Crs(
        label,
        horizontal.is_geographic,
        factor,
        pyproj.Transformer.from_crs("EPSG:4326", horizontal, always_xy=True),
        pyproj.Transformer.from_crs(horizontal, "EPSG:4326", always_xy=True),
    )


def _short(text):
    text = " ".join(str(text).split())
    return repr(text if len(text) <= 60 else text[:57] + "...")


@dataclass(frozen=True, eq=False)
class Elevation:
    """Ground heights (m) on a regular grid in the coordinate system ``crs``: node [iy, ix] at
    (x0 + ix dx, y0 + iy dy), dx, dy > 0, x east and y north (lon/lat degrees or projected
    units); NaN where there is no height."""

    source: str  # the file's name
    crs: str  # e.g. 'EPSG:4326', 'EPSG:32633'
    x0: float
    y0: float
    dx: float
    dy: float
    heights_m: np.ndarray  # (ny, nx) float64
    description: str  # one line: the file, its kind, grid, coordinate system and heights
    spacing_m: tuple  # (dx, dy) in metres (at the grid's centre for lon/lat)
    _crs: _Crs = field(repr=False)

    def __str__(self):
        return self.description

    def height_m(self, lon_deg, lat_deg):
        """The ground's height (m) at WGS84 lon/lat (arrays broadcast): bilinear between the four
        nodes around the point; NaN outside the nodes' extent or next to a missing height."""
        lon, lat = np.broadcast_arrays(
            np.asarray(lon_deg, dtype=np.float64), np.asarray(lat_deg, dtype=np.float64)
        )
        if self._crs.forward is None:
            x, y = lon, lat
        else:
            x, y = self._crs.forward.transform(lon, lat)
            x, y = np.asarray(x, dtype=np.float64), np.asarray(y, dtype=np.float64)
        return self.height_native(x, y)

    def height_native(self, x, y):
        """The height (m) at coordinates (x, y) of the grid's own system ``crs``."""
        x = np.asarray(x, dtype=np.float64)
        y = np.asarray(y, dtype=np.float64)
        h = self.heights_m
        ny, nx = h.shape
        fx = (x - self.x0) / self.dx
        fy = (y - self.y0) / self.dy
        # A point on the extent's edge, to the rounding of its coordinates, is inside.
        e = EDGE_CELLS
        inside = (fx >= -e) & (fx <= nx - 1 + e) & (fy >= -e) & (fy <= ny - 1 + e)
        fx = np.where(inside, np.clip(fx, 0.0, nx - 1), 0.0)
        fy = np.where(inside, np.clip(fy, 0.0, ny - 1), 0.0)
        ix = np.minimum(np.floor(fx).astype(np.intp), nx - 2)
        iy = np.minimum(np.floor(fy).astype(np.intp), ny - 2)
        tx = fx - ix
        ty = fy - iy
        out = np.zeros(fx.shape)
        for w, jy, jx in (
            ((1 - tx) * (1 - ty), iy, ix),
            (tx * (1 - ty), iy, ix + 1),
            ((1 - tx) * ty, iy + 1, ix),
            (tx * ty, iy + 1, ix + 1),
        ):
            # A node of weight 0 does not count, so a height at a node next to a missing one
            # is still that node's.
            out = out + np.where(w > 0.0, w * h[jy, jx], 0.0)
        return np.where(inside, out, np.nan)

    def bounds_lonlat(self):
        """(lon_min, lat_min, lon_max, lat_max) of the nodes' extent, in WGS84 degrees."""
        ny, nx = self.heights_m.shape
        x1 = self.x0 + (nx - 1) * self.dx
        y1 = self.y0 + (ny - 1) * self.dy
        if self._crs.inverse is None:
            return (self.x0, self.y0, x1, y1)
        b = self._crs.inverse.transform_bounds(self.x0, self.y0, x1, y1, densify_pts=101)
        return tuple(float(v) for v in b)


def load_elevation(path, crs=None):
    """The Elevation of a GeoTIFF DEM (.tif, .tiff), an ESRI ASCII grid (.asc) or a CSV of
    survey points (.csv). ``crs`` (an EPSG code such as 'EPSG:32633', or a WKT) gives or
    overrides the file's coordinate system."""
    path = path_of(path, "elevation", "a .tif/.tiff, .asc or .csv path", ElevationError)
    name = path.name
    if path.is_dir():
        raise ElevationError(
            f"{name or path}: is a folder: allowed is a .tif/.tiff, .asc or .csv file of heights"
        )
    if not path.is_file():
        raise ElevationError(f"{name}: no such file ({path})")
    suffix = path.suffix.lower()
    if suffix in (".tif", ".tiff"):
        return _load_geotiff(path, crs)
    if suffix == ".asc":
        return _load_ascii_grid(path, crs)
    if suffix == ".csv":
        return _load_points(path, crs)
    raise ElevationError(
        f"{name}: unknown elevation format {path.suffix!r}: allowed are .tif/.tiff (GeoTIFF DEM), "
        ".asc (ESRI ASCII grid) and .csv (survey points)"
    )


_ALLOWED_HEIGHTS = f"{HEIGHT_LIMITS_M[0]:g} to {HEIGHT_LIMITS_M[1]:g} m"


def _off_earth(heights):
    """The indices of ``heights`` (1-d) that are given (not NaN) but outside HEIGHT_LIMITS_M:
    infinities among them."""
    lo, hi = HEIGHT_LIMITS_M
    return np.flatnonzero(~np.isnan(heights) & ~((heights >= lo) & (heights <= hi)))


def _grid(name, kind, place, x0, y0, dx, dy, heights, extra=""):
    """The Elevation of a north-up grid (row 0 at y0), checked."""
    heights = np.asarray(heights, dtype=np.float64)
    ny, nx = heights.shape
    if nx < 2 or ny < 2:
        raise ElevationError(
            f"{name}: the grid has {nx} x {ny} nodes: allowed is at least 2 x 2 heights"
        )
    bad = _off_earth(heights.ravel())
    if bad.size:
        iy, ix = divmod(int(bad[0]), nx)
        raise ElevationError(
            f"{name}: the node at x {x0 + ix * dx:.10g}, y {y0 + iy * dy:.10g} has a height of "
            f"{heights[iy, ix]:g} m: allowed are heights {_ALLOWED_HEIGHTS} (a missing height "
            "is nodata)"
        )
    valid = np.isfinite(heights)
    if not valid.any():
        raise ElevationError(f"{name}: every height is nodata: allowed is a grid with heights")
    heights = np.where(valid, heights, np.nan)
    heights.setflags(write=False)  # shared by whatever samples it
    if place.geographic:
        lat_c = math.radians(y0 + 0.5 * (ny - 1) * dy)
        dy_m = math.radians(dy) * EARTH_RADIUS_M
        spacing = (dy_m * dx / dy * math.cos(lat_c), dy_m)
    else:
        spacing = (dx * place.metres_per_unit, dy * place.metres_per_unit)
    missing = int((~valid).sum())
    description = (
        f"{name}: {kind}, {nx} x {ny} nodes {spacing[0]:.3g} m x {spacing[1]:.3g} m apart, "
        f"{place.label}, heights {np.nanmin(heights):.1f} to {np.nanmax(heights):.1f} m"
        + (f", {missing} nodes without a height" if missing else "")
        + extra
    )
    return Elevation(name, place.label, x0, y0, dx, dy, heights, description, spacing, _crs=place)


# --- GeoTIFF ---------------------------------------------------------------------------------


def _load_geotiff(path, crs):
    name = path.name
    try:
        import tifffile
    except ImportError:
        raise ElevationError(f"{name}: reading a GeoTIFF needs tifffile: {HOLE_EXTRA}") from None
    try:
        with tifffile.TiffFile(path) as tif:
            page = tif.pages[0]
            tags = {tag.code: tag.value for tag in page.tags.values()}
            data = page.asarray()
    except Exception as err:  # a corrupt file raises whatever its first bad byte leads to
        if "imagecodecs" in str(err):  # LZW, or a floating-point predictor, as GDAL writes them
            raise ElevationError(
                f"{name}: its compression needs the imagecodecs package: pip install imagecodecs"
            ) from None
        raise ElevationError(
            f"{name}: not a readable TIFF ({type(err).__name__}): allowed is a GeoTIFF DEM"
        ) from None
    data = np.squeeze(data)
    if data.ndim != 2 or not (
        np.issubdtype(data.dtype, np.floating) or np.issubdtype(data.dtype, np.integer)
    ):
        raise ElevationError(
            f"{name}: the image is {data.dtype} of shape {data.shape}: allowed is one band of "
            "heights (a 2-D array of numbers)"
        )
    keys = _geokeys(name, tags)
    place = _geotiff_crs(name, keys, crs)
    raster_type = keys.get(KEY_RASTER_TYPE, PIXEL_IS_AREA)
    if raster_type not in (PIXEL_IS_AREA, PIXEL_IS_POINT):
        raise ElevationError(
            f"{name}: GTRasterTypeGeoKey = {raster_type}: allowed are 1 (PixelIsArea) and "
            "2 (PixelIsPoint)"
        )
    units = keys.get(KEY_VERTICAL_UNITS, 9001)
    if units not in VERTICAL_UNITS_M:
        raise ElevationError(
            f"{name}: VerticalUnitsGeoKey = {units}: allowed are 9001 (metre), 9002 (foot) and "
            "9003 (US survey foot)"
        )
    a, f, d, h = _geotransform(name, tags)
    heights = data.astype(np.float64)
    nodata = tags.get(TAG_GDAL_NODATA)
    if nodata is not None:
        heights[_nodata_mask(name, data, nodata)] = np.nan
    heights *= VERTICAL_UNITS_M[units]
    # A value stands at its pixel's centre (PixelIsArea) or at the raster point (PixelIsPoint).
    shift = 0.5 if raster_type == PIXEL_IS_AREA else 0.0
    ny, nx = heights.shape
    x0, dx = d + a * shift, a
    y0, dy = h + f * shift, f
    if dx < 0:
        heights, x0, dx = heights[:, ::-1], x0 + dx * (nx - 1), -dx
    if dy < 0:  # the usual north-up image: its first row is the northmost
        heights, y0, dy = heights[::-1], y0 + dy * (ny - 1), -dy
    kind = "GeoTIFF DEM (PixelIs" + ("Area" if raster_type == PIXEL_IS_AREA else "Point") + ")"
    return _grid(name, kind, place, x0, y0, dx, dy, np.ascontiguousarray(heights))


def _geokeys(name, tags):
    """The GeoKey directory's short values, {key: value}."""
    raw = tags.get(TAG_GEOKEYS)
    if raw is None:
        raise ElevationError(
            f"{name}: no GeoKeyDirectory tag (34735), so not georeferenced: allowed is a GeoTIFF "
            "DEM with its coordinate system"
        )
    raw = [int(v) for v in raw]
    if len(raw) < 4 or len(raw) < 4 + 4 * raw[3]:
        raise ElevationError(
            f"{name}: GeoKeyDirectory tag (34735) is {len(raw)} values long, shorter than its "
            "header says: allowed is a GeoKey directory per GeoTIFF 1.1"
        )
    keys = {}
    for k in range(raw[3]):
        key, location, _count, value = raw[4 + 4 * k : 8 + 4 * k]
        if location == 0:  # a short stored in the directory itself: every key read here
            keys[key] = value
    return keys


def _geotiff_crs(name, keys, crs):
    if crs is not None:
        return _place(crs, name, "crs")
    model = keys.get(KEY_MODEL_TYPE)
    if model == 3:
        raise ElevationError(
            f"{name}: GTModelTypeGeoKey = 3 (geocentric): allowed are 1 (projected) and "
            "2 (geographic), or give crs"
        )
    if model == 2 or (model is None and KEY_PROJECTED not in keys):
        key, key_name = KEY_GEOGRAPHIC, "GeographicTypeGeoKey"
    else:
        key, key_name = KEY_PROJECTED, "ProjectedCSTypeGeoKey"
    code = keys.get(key)
    if code is None or code == USER_DEFINED or code == 0:
        shown = "missing" if code is None else f"{code} (user-defined)"
        raise ElevationError(
            f"{name}: {key_name} is {shown}: allowed is an EPSG code in it, or give crs such as "
            "'EPSG:32633'"
        )
    return _place(f"EPSG:{code}", name, key_name)


def _geotransform(name, tags):
    """(a, f, d, h): X = d + a i, Y = h + f j at raster coordinates (i, j)."""
    matrix = tags.get(TAG_TRANSFORMATION)
    if matrix is not None:
        m = [float(v) for v in matrix]
        if len(m) != 16 or m[1] != 0.0 or m[4] != 0.0:
            raise ElevationError(
                f"{name}: ModelTransformation is rotated or malformed: allowed is a north-up "
                "grid (no rotation terms)"
            )
        a, d, f, h = m[0], m[3], m[5], m[7]
    else:
        scale = tags.get(TAG_PIXEL_SCALE)
        tie = tags.get(TAG_TIEPOINT)
        if scale is None or tie is None or len(scale) < 2 or len(tie) < 6:
            raise ElevationError(
                f"{name}: no ModelPixelScale and ModelTiepoint (nor ModelTransformation) tags: "
                "allowed is a GeoTIFF DEM placed by them"
            )
        if len(tie) > 6:
            raise ElevationError(
                f"{name}: ModelTiepoint holds {len(tie) // 6} tie points: allowed is one tie "
                "point and a pixel scale"
            )
        sx, sy = float(scale[0]), float(scale[1])
        i, j, x, y = (float(v) for v in (tie[0], tie[1], tie[3], tie[4]))
        a, f = sx, -sy
        d, h = x - i * sx, y + j * sy
    if not all(math.isfinite(v) for v in (a, f, d, h)) or a == 0.0 or f == 0.0:
        raise ElevationError(
            f"{name}: pixel size {a:g} x {f:g} at ({d:g}, {h:g}): allowed are finite, non-zero "
            "pixel sizes"
        )
    return a, f, d, h


def _nodata_mask(name, data, nodata):
    text = str(nodata).strip().strip("\x00")
    try:
        value = float(text)
    except ValueError:
        raise ElevationError(
            f"{name}: GDAL_NODATA tag (42113) is {text!r}: allowed is a number"
        ) from None
    if math.isnan(value):
        return np.isnan(data) if np.issubdtype(data.dtype, np.floating) else np.zeros(data.shape)
    if np.issubdtype(data.dtype, np.floating):
        return data == data.dtype.type(value)  # as stored: -3.4e38 in float32
    return data == value


# --- ESRI ASCII grid -------------------------------------------------------------------------

ASC_KEYS = "ncols, nrows, xllcorner|xllcenter, yllcorner|yllcenter, cellsize|dx+dy, nodata_value"


def _load_ascii_grid(path, crs):
    name = path.name
    try:
        lines = path.read_text(encoding="ascii").splitlines()
    except (UnicodeDecodeError, OSError) as err:
        raise ElevationError(
            f"{name}: not a text file ({type(err).__name__}): allowed is an ESRI ASCII grid"
        ) from None
    header = {}
    k = 0
    while k < len(lines) and lines[k].strip() and re.match(r"[A-Za-z_]", lines[k].strip()):
        parts = lines[k].split()
        if len(parts) != 2:
            raise ElevationError(
                f"{name}: header line {k + 1} {_short(lines[k])} is not 'key value': allowed "
                f"keys are {ASC_KEYS}"
            )
        key = parts[0].lower()
        if key not in ("ncols", "nrows", "xllcorner", "xllcenter", "yllcorner", "yllcenter",
                       "cellsize", "dx", "dy", "nodata_value"):  # fmt: skip
            raise ElevationError(
                f"{name}: unknown header key {parts[0]!r} on line {k + 1}: allowed keys are "
                f"{ASC_KEYS}"
            )
        header[key] = parts[1]
        k += 1

    def number(key, kind=float, positive=False):
        if key not in header:
            raise ElevationError(
                f"{name}: header field {key!r} is missing: allowed keys are {ASC_KEYS}"
            )
        try:
            value = kind(header[key])
        except ValueError:
            value = None
        if value is None or not math.isfinite(value) or (positive and value <= 0):
            allowed = "a positive " if positive else "a "
            allowed += "integer" if kind is int else "number"
            raise ElevationError(
                f"{name}: header field {key} = {header[key]!r}: allowed is {allowed}"
            )
        return value

    ncols = number("ncols", int, positive=True)
    nrows = number("nrows", int, positive=True)
    if "cellsize" not in header and ("dx" in header or "dy" in header):
        dx, dy = number("dx", positive=True), number("dy", positive=True)
    else:
        dx = dy = number("cellsize", positive=True)
    x_key = "xllcenter" if "xllcenter" in header else "xllcorner"
    y_key = "yllcenter" if "yllcenter" in header else "yllcorner"
    x0 = number(x_key) + (0.0 if x_key == "xllcenter" else 0.5 * dx)
    y0 = number(y_key) + (0.0 if y_key == "yllcenter" else 0.5 * dy)
    nodata = number("nodata_value") if "nodata_value" in header else None

    tokens = " ".join(lines[k:]).split()
    if len(tokens) != ncols * nrows:
        raise ElevationError(
            f"{name}: {len(tokens)} heights where ncols x nrows = {ncols} x {nrows} = "
            f"{ncols * nrows}: allowed is one height per node"
        )
    try:
        values = np.array(tokens, dtype=np.float64)
    except ValueError:
        bad = next(t for t in tokens if not _is_number(t))
        raise ElevationError(
            f"{name}: height {bad!r} is not a number: allowed are numbers and NODATA_value"
        ) from None
    heights = values.reshape(nrows, ncols)[::-1]  # the first row is the northmost
    if nodata is not None:
        heights = np.where(heights == nodata, np.nan, heights)

    x1, y1 = x0 + (ncols - 1) * dx, y0 + (nrows - 1) * dy
    prj = path.with_suffix(".prj")
    if crs is not None:
        place = _place(crs, name, "crs")
    elif prj.is_file():
        place = _place(prj.read_text(encoding="utf-8", errors="replace"), prj.name, "WKT")
    elif -180.0 <= x0 and x1 <= 180.0 and -90.0 <= y0 and y1 <= 90.0:
        place = _WGS84
    else:
        raise ElevationError(
            f"{name}: coordinates x {x0:g} to {x1:g}, y {y0:g} to {y1:g} are not lon/lat and "
            f"there is no {prj.name}: allowed is a .prj beside it or a crs such as 'EPSG:32633'"
        )
    return _grid(name, "ESRI ASCII grid", place, x0, y0, dx, dy, np.ascontiguousarray(heights))


def _is_number(text):
    try:
        float(text)
    except ValueError:
        return False
    return True


# --- survey points ---------------------------------------------------------------------------


def _load_points(path, crs):
    import pandas as pd

    name = path.name
    try:
        table = pd.read_csv(path, skipinitialspace=True)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as err:
        raise ElevationError(
            f"{name}: not a readable CSV ({type(err).__name__}): allowed columns are {CSV_COLUMNS}"
        ) from None
    # The names as written (pandas renames a second 'alt' 'alt.1'), each once.
    written = pd.read_csv(path, header=None, nrows=1, dtype=str, skipinitialspace=True)
    seen = {}
    for raw in written.iloc[0].fillna(""):
        key = raw.strip().lower()
        if key in seen:
            spelt = f" (as {seen[key]!r} and {raw!r})" if seen[key] != raw else ""
            raise ElevationError(
                f"{name}: column {raw.strip()!r} twice{spelt}: allowed is each column once"
            )
        seen[key] = raw
    columns = {str(c).strip().lower(): c for c in table.columns}

    def find(names, tolerance):
        """The first of ``names`` in the table, its empty cells filled from another of them;
        ElevationError where another is there too with numbers further than ``tolerance``
        from its own (which to read would be a guess)."""
        given = [columns[n] for n in names if n in columns]
        for other in given[1:]:
            a = pd.to_numeric(table[given[0]], errors="coerce").to_numpy(dtype=np.float64)
            b = pd.to_numeric(table[other], errors="coerce").to_numpy(dtype=np.float64)
            differ = np.flatnonzero(np.abs(a - b) > tolerance)  # (NaN on either side: no)
            if differ.size:
                k = differ[0]
                raise ElevationError(
                    f"{name}: columns {given[0]} and {other} give the same thing and differ "
                    f"by more than {tolerance:g} (row {k + 2}: {table[given[0]].iloc[k]}, "
                    f"{table[other].iloc[k]}): allowed is one of them: remove or rename the other"
                )
            table[given[0]] = table[given[0]].where(table[given[0]].notna(), table[other])
        return given[0] if given else None

    # Two columns of one coordinate agree to about a centimetre (1e-7 degrees of lon/lat).
    cx, cy = find(LON_NAMES, 1e-7), find(LAT_NAMES, 1e-7)
    cz = find(Z_NAMES, DUPLICATE_TOLERANCE_M)
    lonlat = cx is not None and cy is not None
    if not lonlat:
        cx, cy = find(X_NAMES, DUPLICATE_TOLERANCE_M), find(Y_NAMES, DUPLICATE_TOLERANCE_M)
    if cx is None or cy is None or cz is None:
        shown = ",".join(str(c) for c in table.columns)
        raise ElevationError(f"{name}: columns {_short(shown)}: allowed are {CSV_COLUMNS}")
    if not lonlat and crs is None:
        raise ElevationError(
            f"{name}: columns {cx},{cy} are not lon/lat and no crs is given: allowed is a crs "
            "such as 'EPSG:32633' for x,y"
        )
    place = _WGS84 if crs is None else _place(crs, name, "crs")

    values = []
    for column in (cx, cy, cz):
        v = pd.to_numeric(table[column], errors="coerce").to_numpy(dtype=np.float64)
        bad = np.flatnonzero(np.isnan(v) & table[column].notna().to_numpy())
        if bad.size:
            raise ElevationError(
                f"{name}: row {bad[0] + 2} column {column} = {table[column].iloc[bad[0]]!r}: "
                "allowed is a number"
            )
        values.append(v)
    x, y, z = values
    if np.isnan(x).any() or np.isnan(y).any():
        row = int(np.flatnonzero(np.isnan(x) | np.isnan(y))[0]) + 2
        raise ElevationError(f"{name}: row {row} has no coordinates: allowed is a point per row")
    bad = _off_earth(z)
    if bad.size:
        raise ElevationError(
            f"{name}: row {bad[0] + 2} column {cz} = {z[bad[0]]:g} m: allowed are heights "
            f"{_ALLOWED_HEIGHTS} (a point without a height is an empty cell)"
        )
    keep = ~np.isnan(z)  # a point without a height is no point
    x, y, z = x[keep], y[keep], z[keep]
    rows = np.flatnonzero(keep) + 2  # the header is row 1
    if place.geographic and len(x) and (np.abs(x).max() > 180 or np.abs(y).max() > 90):
        raise ElevationError(
            f"{name}: {cx}/{cy} reach {np.abs(x).max():g}/{np.abs(y).max():g}: allowed are "
            "longitudes in [-180, 180] and latitudes in [-90, 90], or x,y with a crs"
        )
    if len(x) < 3:
        raise ElevationError(f"{name}: {len(x)} points with a height: allowed is at least 3 points")
    # One height per place: copies of a point that agree are averaged, others refused.
    xy, first, inverse = np.unique(
        np.stack([x, y], axis=1), axis=0, return_index=True, return_inverse=True
    )
    inverse = inverse.ravel()
    _refuse_conflicts(name, inverse, z, rows, x, y, (cx, cy), "")
    z = np.bincount(inverse, weights=z) / np.bincount(inverse)
    x, y, rows = xy[:, 0], xy[:, 1], rows[first]

    lattice_x, lattice_y = _lattice_axis(x), _lattice_axis(y)
    if lattice_x and lattice_y:
        (x0, dx, kx, nx), (y0, dy, ky, ny) = lattice_x, lattice_y
        if len(x) >= 0.5 * nx * ny and nx >= 2 and ny >= 2:
            # Points within 1e-6 of a step of each other are one node: copies too.
            where = " (points within 1e-6 of a lattice step are one node)"
            _refuse_conflicts(name, ky * nx + kx, z, rows, x, y, (cx, cy), where)
            return _lattice(name, place, x0, dx, kx, nx, y0, dy, ky, ny, z)
    return _scattered(name, place, x, y, z)


def _refuse_conflicts(name, group, z, rows, x, y, columns, where):
    """ElevationError naming the first point given more than once (``group``: one label per
    point, the same for copies) with heights further apart than ``DUPLICATE_TOLERANCE_M``,
    its rows and its heights; nothing when every copy agrees."""
    group = np.unique(group, return_inverse=True)[1].ravel()
    lo = np.full(group.max() + 1, np.inf)
    hi = np.full(group.max() + 1, -np.inf)
    np.minimum.at(lo, group, z)
    np.maximum.at(hi, group, z)
    bad = np.flatnonzero(hi - lo > DUPLICATE_TOLERANCE_M)
    if not bad.size:
        return
    copies = np.flatnonzero(group == bad[0])
    shown = copies[:5]
    heights = ", ".join(f"{v:g}" for v in z[shown]) + (", ..." if len(copies) > 5 else "")
    at = ", ".join(str(int(r)) for r in rows[shown]) + (", ..." if len(copies) > 5 else "")
    more = f"; {bad.size - 1} more points like it" if bad.size > 1 else ""
    point = f"{columns[0]} {float(x[copies[0]])!r}, {columns[1]} {float(y[copies[0]])!r}"
    raise ElevationError(
        f"{name}: the point {point} is given "
        f"{len(copies)} times{where} with different heights ({heights} m, rows {at}){more}: "
        f"allowed is one height per point (copies within {DUPLICATE_TOLERANCE_M:g} m are "
        "merged): remove the wrong copies"
    )


def _lattice_axis(v):
    """(v0, step, k, n) when every v is v0 + k step to 1e-6 of a step, k = 0 .. n - 1 (some k
    may be missing); None otherwise."""
    u = np.unique(v)
    if len(u) < 2:
        return None
    span = u[-1] - u[0]
    levels = u[np.concatenate([[True], np.diff(u) > 1e-9 * span])]
    if len(levels) < 2:
        return None
    step = np.diff(levels).min()
    k = np.rint((v - u[0]) / step).astype(np.int64)
    n = int(k.max()) + 1
    if n > 100 * len(levels):
        return None
    step = span / (n - 1)
    if np.abs(v - (u[0] + k * step)).max() > 1e-6 * step:
        return None
    return float(u[0]), float(step), k, n


def _lattice(name, place, x0, dx, kx, nx, y0, dy, ky, ny, z):
    # Points within 1e-6 of a step of each other are one node: their mean height (they agree:
    # ``_refuse_conflicts``).
    node = ky * nx + kx
    count = np.bincount(node, minlength=nx * ny)
    total = np.bincount(node, weights=z, minlength=nx * ny)
    with np.errstate(invalid="ignore", divide="ignore"):
        heights = (total / count).reshape(ny, nx)
    missing = (count == 0).reshape(ny, nx)
    extra = ""
    if missing.any():
        interpolator = _scipy_interpolator(name)
        jy, jx = np.nonzero(~missing)
        fill = interpolator(np.stack([jx, jy], axis=1), heights[~missing])
        my, mx = np.nonzero(missing)
        heights[missing] = fill(np.stack([mx, my], axis=1))
        filled = int(np.isfinite(heights[missing]).sum())
        extra = f", {filled} of {int(missing.sum())} missing nodes filled linearly"
    return _grid(name, f"{len(z)} survey points on a lattice", place, x0, y0, dx, dy, heights,
                 extra)  # fmt: skip


def _scipy_interpolator(name):
    try:
        from scipy.interpolate import LinearNDInterpolator
    except ImportError:
        raise ElevationError(
            f"{name}: gridding survey points needs scipy: pip install scipy"
        ) from None
    return LinearNDInterpolator


def _scattered(name, place, x, y, z):
    interpolator = _scipy_interpolator(name)
    from scipy.spatial import ConvexHull, QhullError

    # Triangulate in metres, so that the triangles are those of the ground, not of degrees.
    if place.geographic:
        lat0 = math.radians(0.5 * (y.min() + y.max()))
        sx = math.radians(1.0) * EARTH_RADIUS_M * math.cos(lat0)
        sy = math.radians(1.0) * EARTH_RADIUS_M
    else:
        sx = sy = place.metres_per_unit
    xm, ym = (x - x.min()) * sx, (y - y.min()) * sy
    points = np.stack([xm, ym], axis=1)
    try:
        area_m2 = ConvexHull(points).volume
        fill = interpolator(points, z)
    except QhullError:
        raise ElevationError(
            f"{name}: the points lie on one line: allowed are points spread over an area"
        ) from None
    spacing_m = math.sqrt(area_m2 / len(z))
    span_x, span_y = xm.max(), ym.max()
    nodes = (span_x / spacing_m + 1) * (span_y / spacing_m + 1)
    if nodes > MAX_NODES:  # points along a thin diagonal: a coarser grid
        spacing_m *= math.sqrt(nodes / MAX_NODES)
    nx = math.ceil(span_x / spacing_m) + 1
    ny = math.ceil(span_y / spacing_m) + 1
    gx = np.linspace(0.0, span_x, nx)
    gy = np.linspace(0.0, span_y, ny)
    heights = fill(*np.meshgrid(gx, gy))
    dx, dy = span_x / (nx - 1) / sx, span_y / (ny - 1) / sy
    kind = f"{len(z)} scattered survey points gridded linearly"
    return _grid(name, kind, place, float(x.min()), float(y.min()), dx, dy, heights)
