"""A hole's turf zones: their kinds, the turf and the Rules' status of each, the order that
resolves overlaps, and their polygons put onto the ground's grid.

Zone kinds, in the order that resolves overlaps (a later kind wins where polygons overlap):
rough < fairway < tee < fringe < green < bunker < water < water_yellow; outside the course
boundary, out_of_bounds wins over all. Rough is everything inside the course that no polygon
covers, so a bunker drawn inside the rough (or a fairway) is a bunker, and a pond in a fairway
is water. The two penalty areas of the Rules (Rule 17) are two kinds: ``water``, red (lateral
relief; OpenStreetMap's ``golf=lateral_water_hazard``, and ``natural=water``, as a penalty area
the committee has not marked is red, Rule 17.1), and ``water_yellow`` (``golf=water_hazard``:
stroke and distance or back on the line, no lateral drop). To the kernel both are
``PENALTY_AREA``; their relief is scored in ``strokes.expected``.
A kind's position in ``ZONES`` (``ZONE_KINDS``) is its index in ``ground.Terrain.zone``.
"""

from dataclasses import dataclass

import numpy as np

from mcrun.ground import IN_PLAY, OUT_OF_BOUNDS, PENALTY_AREA


@dataclass(frozen=True)
class ZoneKind:
    """A kind of zone, everything a hole, its scores and its map need of it: its ``name``; its
    ``turf`` (a preset of ``physics.turf.PRESETS``; water and out of bounds hold the rough's,
    so that every row of a terrain is a valid Turf, though the ball is not played there); its
    ``state`` under the Rules (``ground.IN_PLAY``, ``PENALTY_AREA``, ``OUT_OF_BOUNDS``); the
    OpenStreetMap tags that draw it (``"golf=green"``); the ``lie`` of the next shot from it
    (``strokes.baseline.LIES``; None where the ball is not played as it lies); whether it is
    ``mown`` (a water ball whose reference point lies there is dropped on the fairway); and its
    ``colour`` on a map, one golfers read."""

    name: str
    turf: str
    state: int
    tags: tuple[str, ...]
    lie: str | None
    mown: bool
    colour: str


# Every kind, in the order that resolves overlaps (a later kind wins). A new kind of zone is a
# row here (and, if its turf is new, a preset in ``physics.turf``).
ZONES = (
    ZoneKind("rough", "rough", IN_PLAY, ("golf=rough",), "rough", False, "#4f7d3a"),
    ZoneKind("fairway", "fairway", IN_PLAY, ("golf=fairway",), "fairway", True, "#9ed36a"),
    # A ball at rest on a teeing area is played as it lies, off mown grass.
    ZoneKind("tee", "tee", IN_PLAY, ("golf=tee",), "fairway", True, "#7fbf50"),
    # The Tour counts the fringe off the green (around the green, not putting).
    ZoneKind("fringe", "fringe", IN_PLAY, ("golf=fringe",), "fairway", True, "#6fcf4f"),
    ZoneKind("green", "green", IN_PLAY, ("golf=green",), "green", True, "#3fd13a"),
    ZoneKind("bunker", "bunker", IN_PLAY, ("golf=bunker",), "sand", False, "#ecd9a0"),
    # A red penalty area (Rule 17.1: one the committee has not marked is red).
    ZoneKind("water", "rough", PENALTY_AREA, ("golf=lateral_water_hazard", "natural=water"),
             None, False, "#4a90d9"),
    # A yellow penalty area: no lateral relief (Rule 17.1d).
    ZoneKind("water_yellow", "rough", PENALTY_AREA, ("golf=water_hazard",), None, False,
             "#2f6fb8"),
    ZoneKind("out_of_bounds", "rough", OUT_OF_BOUNDS, (), None, False, "#b0b0b0"),
)  # fmt: skip

ZONE_KINDS = tuple(z.name for z in ZONES)
ZONE_INDEX = {kind: k for k, kind in enumerate(ZONE_KINDS)}
ROUGH, FAIRWAY, TEE, FRINGE, GREEN, BUNKER, WATER, WATER_YELLOW, OUT = range(len(ZONE_KINDS))
# The columns of the table, by kind.
ZONE_TURF = {z.name: z.turf for z in ZONES}
ZONE_PENALTY = {z.name: z.state for z in ZONES}
PENALTY_ZONES = tuple(z.name for z in ZONES if z.state == PENALTY_AREA)
# The colour of each penalty area kind, as a hole file names it ('penalty_areas').
PENALTY_COLOURS = {"red": "water", "yellow": "water_yellow"}
LIE_OF_ZONE = {z.name: z.lie for z in ZONES if z.lie is not None}
MOWN_ZONES = tuple(z.name for z in ZONES if z.mown)
ZONE_COLOURS = {z.name: z.colour for z in ZONES}
_TAGS = {tag: z.name for z in ZONES for tag in z.tags}


def zone_of_tags(tags):
    """The zone kind of an OpenStreetMap feature's tags (its golf=* first, then natural=*), or
    None when it is not a zone."""
    for key in ("golf", "natural"):
        kind = _TAGS.get(f"{key}={tags.get(key)}")
        if kind is not None:
            return kind
    return None


def _edges(polygon):
    """(x1, y1, x2, y2) of every edge of every ring of ``polygon`` (a list of (n, 2) rings;
    a ring need not repeat its first point)."""
    parts = []
    for ring in polygon:
        ring = np.asarray(ring, dtype=float)
        parts.append(np.concatenate([ring, np.roll(ring, -1, axis=0)], axis=1))
    e = np.concatenate(parts)
    return e[:, 0], e[:, 1], e[:, 2], e[:, 3]


def contains(polygon, x, y):
    """Whether the points (x, y) lie inside ``polygon`` (a list of rings, holes included), by
    the even-odd rule; vectorised over the points."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    inside = np.zeros(np.broadcast(x, y).shape, dtype=bool)
    for x1, y1, x2, y2 in zip(*_edges(polygon), strict=True):
        if y1 == y2:
            continue
        straddles = (y1 > y) != (y2 > y)
        x_cross = x1 + (y - y1) * (x2 - x1) / (y2 - y1)
        inside ^= straddles & (x < x_cross)
    return inside


def shoelace_area_m2(polygon):
    """Area of ``polygon`` (outer ring minus its holes), by the shoelace formula."""
    total = 0.0
    for k, ring in enumerate(polygon):
        ring = np.asarray(ring, dtype=float)
        x, y = ring[:, 0], ring[:, 1]
        area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
        total += area if k == 0 else -area
    return total


def polygon_mask(polygon, x0_m, y0_m, cell_m, nx, ny, rows_per_block=512):
    """(ny, nx) bool: the grid's nodes (x0 + ix cell, y0 + iy cell) inside ``polygon``, by the
    even-odd rule over all its rings (so its holes are out).

    A scanline fill: on each row of nodes every edge that crosses the row toggles the nodes to
    the right of where it crosses; a running XOR along the row leaves the inside. Work and
    memory go with the polygon's bounding box, a block of rows at a time."""
    mask = np.zeros((ny, nx), dtype=bool)
    x1, y1, x2, y2 = _edges(polygon)
    keep = y1 != y2
    x1, y1, x2, y2 = x1[keep], y1[keep], x2[keep], y2[keep]
    if x1.size == 0:
        return mask
    lo_x, hi_x = min(x1.min(), x2.min()), max(x1.max(), x2.max())
    lo_y, hi_y = min(y1.min(), y2.min()), max(y1.max(), y2.max())
    ix0 = max(int(np.floor((lo_x - x0_m) / cell_m)), 0)
    ix1 = min(int(np.ceil((hi_x - x0_m) / cell_m)) + 1, nx)
    iy0 = max(int(np.floor((lo_y - y0_m) / cell_m)), 0)
    iy1 = min(int(np.ceil((hi_y - y0_m) / cell_m)) + 1, ny)
    width = ix1 - ix0
    if width <= 0 or iy1 <= iy0:
        return mask
    for start in range(iy0, iy1, rows_per_block):
        stop = min(start + rows_per_block, iy1)
        y = (y0_m + np.arange(start, stop) * cell_m)[:, None]
        straddles = (y1 > y) != (y2 > y)
        rows, edges = np.nonzero(straddles)
        x_cross = x1[edges] + (y[rows, 0] - y1[edges]) * (x2[edges] - x1[edges]) / (
            y2[edges] - y1[edges]
        )
        # The first node of the row at or right of the crossing: nodes with x < x_cross have
        # it on their right, which is the crossing test of ``contains``.
        first = np.clip(np.ceil((x_cross - x0_m) / cell_m).astype(np.int64) - ix0, 0, width)
        toggles = np.bincount(
            rows * (width + 1) + first, minlength=(stop - start) * (width + 1)
        ).reshape(stop - start, width + 1)
        # The running XOR counts the crossings at or left of each node; those right of it are
        # the row's total minus these (the total is even on closed rings: kept for safety).
        left = np.bitwise_xor.accumulate((toggles[:, :width] & 1).astype(np.uint8), axis=1)
        total = (toggles.sum(axis=1) & 1).astype(np.uint8)
        mask[start:stop, ix0:ix1] = (left ^ total[:, None]).astype(bool)
    return mask


def rasterize(zones, x0_m, y0_m, cell_m, nx, ny, boundary=()):
    """(ny, nx) int8 zone index of every node: rough, then each kind's polygons in the order of
    ``ZONE_KINDS`` (later wins), then out_of_bounds outside the ``boundary`` polygons (when
    any are given). ``zones``: (kind, polygon) pairs in the grid's frame."""
    grid = np.full((ny, nx), ROUGH, dtype=np.int8)
    for index, kind in enumerate(ZONE_KINDS):
        for zone_kind, polygon in zones:
            if zone_kind == kind:
                grid[polygon_mask(polygon, x0_m, y0_m, cell_m, nx, ny)] = index
    if len(boundary):
        inside = np.zeros((ny, nx), dtype=bool)
        for polygon in boundary:
            inside |= polygon_mask(polygon, x0_m, y0_m, cell_m, nx, ny)
        grid[~inside] = OUT
    return grid


def pin_off_green(kind, x_m, y_m, cell_m):
    """What is wrong with a hole whose pin (x_m, y_m) is on the zone ``kind`` of its grid of
    ``cell_m``, not on a green: a zone mapped over the green there, or a green too small."""
    return (f"the pin ({x_m:.1f}, {y_m:.1f}) m is on {kind} on the hole's grid of {cell_m:g} m, "
            f"not on a green (a {kind} mapped over it there, or a green smaller than a cell): "
            "a hole is played to a pin on its green")  # fmt: skip
