"""Made-up course maps, for checks of what a course's layout does: an open course of straight,
flat holes (a tee, a fairway of a given width, a round green with its pin in the middle, rough
everywhere else, nothing else), written as the GeoJSON a course map is (``osm.read_course``
reads it). Optionally water across the fairway at a distance from the tee, and fairways of
another width. The holes lie side by side, ``HOLE_SPACING_M`` apart, each from west to east.
"""

import math

from mcrun.hole.geo import MEAN_RADIUS_M

__all__ = ["HOLE_SPACING_M", "open_course", "pars_for"]

YARD_M = 0.9144
HOLE_SPACING_M = 200.0
GREEN_RADIUS_M = 13.3  # about 6,000 sq ft (560 m^2), as the calibration's green
FAIRWAY_START_M = 30.0  # the fairway begins this far from the tee
ORIGIN = (15.0, 45.0)  # lon, lat deg of the first tee
# A realistic mix of pars for 18 holes (four par 3s, ten par 4s, four par 5s) and the share of a
# course's length each par's holes take on average (a par 3 0.60, a par 5 1.40 of a par 4).
PAR_MIX = (4, 4, 3, 5, 4, 4, 3, 4, 5, 4, 3, 4, 5, 4, 4, 3, 5, 4)
PAR_WEIGHT = {3: 0.60, 4: 1.0, 5: 1.40}


def pars_for(holes=18):
    """The pars of ``holes`` holes: ``PAR_MIX`` repeated."""
    return tuple(PAR_MIX[k % len(PAR_MIX)] for k in range(holes))


def _lonlat(x_m, y_m):
    lon0, lat0 = ORIGIN
    lat = lat0 + math.degrees(y_m / MEAN_RADIUS_M)
    lon = lon0 + math.degrees(x_m / (MEAN_RADIUS_M * math.cos(math.radians(lat0))))
    return [round(lon, 9), round(lat, 9)]


def _ring(points):
    ring = [_lonlat(x, y) for x, y in points]
    return [ring + [ring[0]]]


def _feature(tags, geometry):
    return {"type": "Feature", "properties": dict(tags), "geometry": geometry}


def open_course(total_yd, pars=None, fairway_width_m=40.0, water=None, name="open course"):
    """A GeoJSON course map (a dict) of ``pars`` (default ``pars_for(18)``) holes adding up to
    ``total_yd`` (each hole's tee-to-pin length its par's ``PAR_WEIGHT`` share of it, to the
    yard); ``water``: {hole number (1-based): (from_m, to_m)} a water band across the hole at
    those distances from its tee, 200 m wide (a red penalty area)."""
    pars = tuple(pars or pars_for(18))
    weights = [PAR_WEIGHT[p] for p in pars]
    lengths_m = [total_yd * w / sum(weights) * YARD_M for w in weights]
    water = water or {}
    features = []
    for k, (par, length) in enumerate(zip(pars, lengths_m, strict=True)):
        y = k * HOLE_SPACING_M
        number = k + 1
        features.append(
            _feature(
                {"golf": "hole", "ref": str(number), "par": str(par)},
                {"type": "LineString", "coordinates": [_lonlat(0.0, y), _lonlat(length, y)]},
            )
        )
        features.append(
            _feature(
                {"golf": "tee"},
                {
                    "type": "Polygon",
                    "coordinates": _ring([(-5, y - 5), (5, y - 5), (5, y + 5), (-5, y + 5)]),
                },
            )
        )
        half = fairway_width_m / 2.0
        end = length - GREEN_RADIUS_M
        if par > 3 and end > FAIRWAY_START_M:
            features.append(
                _feature(
                    {"golf": "fairway"},
                    {
                        "type": "Polygon",
                        "coordinates": _ring(
                            [
                                (FAIRWAY_START_M, y - half),
                                (end, y - half),
                                (end, y + half),
                                (FAIRWAY_START_M, y + half),
                            ]
                        ),
                    },
                )
            )
        circle = [
            (
                length + GREEN_RADIUS_M * math.cos(2 * math.pi * j / 48),
                y + GREEN_RADIUS_M * math.sin(2 * math.pi * j / 48),
            )
            for j in range(48)
        ]
        features.append(
            _feature({"golf": "green"}, {"type": "Polygon", "coordinates": _ring(circle)})
        )
        features.append(
            _feature({"golf": "pin"}, {"type": "Point", "coordinates": _lonlat(length, y)})
        )
        if number in water:
            lo, hi = water[number]
            features.append(
                _feature(
                    {"natural": "water"},
                    {
                        "type": "Polygon",
                        "coordinates": _ring(
                            [(lo, y - 100), (hi, y - 100), (hi, y + 100), (lo, y + 100)]
                        ),
                    },
                )
            )
    return {"type": "FeatureCollection", "name": name, "features": features}
