"""A course map's tee boxes, hole by hole: the ``golf=tee`` areas that belong to each hole
line, from the back of the hole to its front (``mcrun rate --tees``).

A map draws a hole's tee sets as several ``golf=tee`` areas along the first part of its line
(the back tee where the line starts, the others nearer the green), rarely tagged with which set
each is. An area belongs to the hole whose line passes nearest its centre: within
``TEE_LATERAL_M`` of the line (its first segment carried on behind its start, for a back tee
drawn behind it), no farther along the line than ``TEE_ALONG_SHARE`` of its length, and no more
than ``TEE_BEHIND_M`` behind its start. A hole's tees are ordered by how far along its line
they lie, the back tee first; a tee's place is its area's centroid.
"""

import numpy as np

from mcrun.hole.geo import MEAN_RADIUS_M, Frame

__all__ = ["TEE_ALONG_SHARE", "TEE_BEHIND_M", "TEE_LATERAL_M", "hole_tees"]

TEE_LATERAL_M = 30.0
TEE_ALONG_SHARE = 0.4
TEE_BEHIND_M = 150.0


def _centroid(ring):
    """The area centroid (lon, lat) of a small ring (lon/lat deg, closed or not), in a local
    plane about its first point; its vertices' mean where it has no area."""
    ring = np.asarray(ring, dtype=float)
    if len(ring) > 1 and np.array_equal(ring[0], ring[-1]):
        ring = ring[:-1]
    frame = Frame(*ring[0], 0.0)
    x, y = frame.to_xy(ring[:, 0], ring[:, 1])
    cross = x * np.roll(y, -1) - np.roll(x, -1) * y
    area = cross.sum() / 2.0
    if abs(area) < 1e-9:
        return tuple(ring.mean(axis=0))
    cx = ((x + np.roll(x, -1)) * cross).sum() / (6.0 * area)
    cy = ((y + np.roll(y, -1)) * cross).sum() / (6.0 * area)
    lon, lat = frame.to_lonlat(cx, cy)
    return float(lon), float(lat)


def _placed(line, points):
    """(distance from the line m, distance along it m, its length m) of ``points`` ((n, 2)
    lon/lat) against ``line`` (a HoleLine): the nearest point of its segments, the first
    carried on behind the line's start."""
    frame = Frame(*line.lonlat[0], 0.0)
    xy = np.column_stack(frame.to_xy(line.lonlat[:, 0], line.lonlat[:, 1]))
    p = np.column_stack(frame.to_xy(points[:, 0], points[:, 1]))
    seg = np.diff(xy, axis=0)
    seg_m = np.hypot(seg[:, 0], seg[:, 1])
    start_m = np.r_[0.0, np.cumsum(seg_m)]
    best_d = np.full(len(p), np.inf)
    best_s = np.zeros(len(p))
    for k in range(len(seg)):
        if seg_m[k] == 0.0:
            continue
        t = ((p - xy[k]) @ seg[k]) / seg_m[k] ** 2
        t = np.minimum(t, 1.0) if k == 0 else np.clip(t, 0.0, 1.0)
        d = np.hypot(*(p - (xy[k] + t[:, None] * seg[k])).T)
        closer = d < best_d
        best_d[closer] = d[closer]
        best_s[closer] = start_m[k] + t[closer] * seg_m[k]
    return best_d, best_s, start_m[-1]


def hole_tees(course):
    """{hole position (1-based, as ``Course.hole('#N')``): [(lon, lat) of each of its tees,
    the back tee first]} of ``course`` (an ``osm.Course``); a hole without a tee in the map is
    left out. Each tee area counts for one hole, the one whose line passes nearest it."""
    rings = [polygon[0] for kind, polygon in course.zones if kind == "tee"]
    if not rings or not course.holes:
        return {}
    centres = np.array([_centroid(r) for r in rings])
    owner = np.full(len(centres), -1)
    owner_d = np.full(len(centres), np.inf)
    along = np.zeros(len(centres))
    reach_deg = np.degrees((TEE_BEHIND_M + TEE_LATERAL_M) / MEAN_RADIUS_M)
    for line in course.holes:
        if line.lonlat is None:  # (a line that cannot be read: no tee is its)
            continue
        # Only tees within the line's box and reach can be its (a country's map has thousands).
        reach = reach_deg * np.array([1.0 / max(np.cos(np.radians(line.lonlat[0, 1])), 1e-6), 1.0])
        lo, hi = line.lonlat.min(axis=0) - reach, line.lonlat.max(axis=0) + reach
        near = np.flatnonzero(((centres >= lo) & (centres <= hi)).all(axis=1))
        if not near.size:
            continue
        d, s, length = _placed(line, centres[near])
        fits = (d <= TEE_LATERAL_M) & (s >= -TEE_BEHIND_M) & (s <= TEE_ALONG_SHARE * length)
        better = fits & (d < owner_d[near])
        owner[near[better]] = line.index
        owner_d[near[better]] = d[better]
        along[near[better]] = s[better]
    tees = {}
    for k in np.argsort(along, kind="stable"):
        if owner[k] >= 1:
            tees.setdefault(int(owner[k]), []).append(tuple(float(v) for v in centres[k]))
    return tees
