"""WGS84 longitude and latitude to the hole's metric frame, and back.

The frame: origin at the tee, x (m) along the line from the tee towards the pin, y (m) to the
RIGHT of that line (looking from the tee to the pin); heights are kept apart, as elevation
differences (``hole.Hole``), not as the third axis of this frame.

The projection is exact geometry, not a map projection: a point (lon, lat) on the WGS84
ellipsoid is taken to Earth-centred Earth-fixed coordinates, then to the local east-north-up
frame whose plane is tangent to the ellipsoid at the tee, and east and north are rotated to x
and y. The inverse goes back the same way, placing the point on the ellipsoid.

Its error over a hole's size: the frame's x and y are the orthogonal projection of the ground
onto the tangent plane, so a point at the geodesic distance s from the tee lies at
R sin(s / R) ~= s - s^3 / (6 R^2) in the plane: 0.9 um short at s = 600 m (R = 6371 km). Measured
against the WGS84 geodesic (pyproj.Geod) from a tee at Zagreb in every direction: 0.88-0.89 um
short at 600 m, 33 um at 2 km; lon/lat -> frame -> lon/lat returns within 10 nm. The
ground falls below the tangent plane by s^2 / (2 R) = 2.8 cm at 600 m; heights are elevation
differences, so the hole is flat-Earth in height to that amount (the ball's flight is too).
"""

import math

import numpy as np

# WGS84
A_M = 6378137.0
F = 1.0 / 298.257223563
E2 = F * (2.0 - F)
B_M = A_M * (1.0 - F)
EP2 = E2 / (1.0 - E2)
MEAN_RADIUS_M = 6371008.8


def to_ecef(lon_deg, lat_deg, h_m=0.0):
    """Earth-centred Earth-fixed (X, Y, Z) in metres of geodetic lon, lat (deg), h (m)."""
    lon = np.radians(lon_deg)
    lat = np.radians(lat_deg)
    sin_lat = np.sin(lat)
    n = A_M / np.sqrt(1.0 - E2 * sin_lat * sin_lat)
    r = (n + h_m) * np.cos(lat)
    return r * np.cos(lon), r * np.sin(lon), (n * (1.0 - E2) + h_m) * sin_lat


def _lon_lat_rad(x, y, z):
    """Geodetic (lon, lat) in radians of ECEF metres (float arrays) and their distance p (m)
    from the polar axis: Bowring's start, then Newton steps (sub-micrometre near the ground)."""
    p = np.hypot(x, y)
    lon = np.arctan2(y, x)
    theta = np.arctan2(z * A_M, p * B_M)
    lat = np.arctan2(z + EP2 * B_M * np.sin(theta) ** 3, p - E2 * A_M * np.cos(theta) ** 3)
    for _ in range(2):
        sin_lat = np.sin(lat)
        n = A_M / np.sqrt(1.0 - E2 * sin_lat * sin_lat)
        h = p / np.cos(lat) - n
        lat = np.arctan2(z, p * (1.0 - E2 * n / (n + h)))
    return lon, lat, p


def from_ecef(x, y, z):
    """Geodetic (lon_deg, lat_deg, h_m) of ECEF metres (``_lon_lat_rad``, then the height)."""
    x, y, z = np.asarray(x, float), np.asarray(y, float), np.asarray(z, float)
    lon, lat, p = _lon_lat_rad(x, y, z)
    sin_lat = np.sin(lat)
    n = A_M / np.sqrt(1.0 - E2 * sin_lat * sin_lat)
    h = p * np.cos(lat) + z * sin_lat - A_M * A_M / n
    return np.degrees(lon), np.degrees(lat), h


class Frame:
    """The hole's frame: tee at (``tee_lon_deg``, ``tee_lat_deg``), x towards the bearing
    ``heading_rad`` (clockwise from north), y to its right."""

    def __init__(self, tee_lon_deg, tee_lat_deg, heading_rad):
        self.tee_lon_deg = float(tee_lon_deg)
        self.tee_lat_deg = float(tee_lat_deg)
        self.heading_rad = float(heading_rad)
        lon, lat = math.radians(tee_lon_deg), math.radians(tee_lat_deg)
        self._origin = np.array(to_ecef(tee_lon_deg, tee_lat_deg, 0.0))
        # Rows: the unit east, north and up vectors at the tee, in ECEF.
        self._enu = np.array(
            [
                [-math.sin(lon), math.cos(lon), 0.0],
                [-math.sin(lat) * math.cos(lon), -math.sin(lat) * math.sin(lon), math.cos(lat)],
                [math.cos(lat) * math.cos(lon), math.cos(lat) * math.sin(lon), math.sin(lat)],
            ]
        )
        self._sin, self._cos = math.sin(heading_rad), math.cos(heading_rad)

    @classmethod
    def from_tee_pin(cls, tee_lonlat, pin_lonlat):
        """The frame of a hole played from ``tee_lonlat`` to ``pin_lonlat`` ((lon, lat) deg)."""
        east, north, _ = cls(*tee_lonlat, 0.0).enu(*pin_lonlat)
        return cls(*tee_lonlat, math.atan2(float(east), float(north)))

    def enu(self, lon_deg, lat_deg, h_m=0.0):
        """East, north, up (m) in the plane tangent at the tee, of points on the ellipsoid
        (or ``h_m`` above it)."""
        x, y, z = to_ecef(lon_deg, lat_deg, h_m)
        d = np.stack(np.broadcast_arrays(x, y, z)) - self._origin.reshape((3,) + (1,) * np.ndim(x))
        e, n, u = np.tensordot(self._enu, d, axes=1)
        return e, n, u

    def to_xy(self, lon_deg, lat_deg):
        """(x_m, y_m) in the hole's frame of points on the ellipsoid at (lon, lat) deg."""
        e, n, _ = self.enu(lon_deg, lat_deg)
        return e * self._sin + n * self._cos, e * self._cos - n * self._sin

    def to_lonlat(self, x_m, y_m):
        """(lon_deg, lat_deg) of the points of the ellipsoid under (x_m, y_m) of the frame."""
        x_m, y_m = np.asarray(x_m, float), np.asarray(y_m, float)
        e = x_m * self._sin + y_m * self._cos
        n = x_m * self._cos - y_m * self._sin
        # The ellipsoid lies below the tangent plane by about (e^2 + n^2) / (2 R); a metre's
        # error in that drop moves the point by s / R m sideways, which is nothing here.
        u = -(e * e + n * n) / (2.0 * MEAN_RADIUS_M)
        d = np.tensordot(self._enu.T, np.stack(np.broadcast_arrays(e, n, u)), axes=1)
        x, y, z = d + self._origin.reshape((3,) + (1,) * np.ndim(e))
        lon, lat, _ = _lon_lat_rad(x, y, z)  # (not the height: a sixth of the work)
        return np.degrees(lon), np.degrees(lat)
