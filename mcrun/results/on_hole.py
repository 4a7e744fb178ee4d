"""What a run on a hole adds to its results: the columns of each shot (where it landed and
finished on the hole, as zones and lon/lat, how far from the pin) and, per point, the share of
shots in each zone with its 95 % interval.

The kernel gives the positions in the hole's frame (x from the tee towards the pin, y to the
right): the landing at (carry_m, carry_lateral_m) from where the shot was struck (the tee, or
its point's start: ``landing_xy``), the finish at (final_x_m, final_y_m) and,
for a ball that ended in a penalty area, where it crossed into it (penalty_x_m, penalty_y_m;
for a ball out of bounds, where it rests). The zone of a point is that of the terrain's
nearest node, as the kernel reads it (``Hole.zone_at``); ``off_map`` beyond the hole's grid.
A shot that its status ended (a penalty area, out of bounds, off the map) finishes in the zone
its status names: one source of truth for where a shot ended, which the zones' shares and the
scores both read.
"""

import math

import numpy as np
import pyarrow as pa

from mcrun import status as status_codes
from mcrun.engine.schema import OUTCOME_FIELDS
from mcrun.hole.zones import PENALTY_ZONES, ZONE_KINDS
from mcrun.results import stats
from mcrun.strokes import OUTCOMES, PUTTING_COLUMNS, score_shots, start_of

OFF_MAP = "off_map"
ZONE_NAMES = (*ZONE_KINDS, OFF_MAP)
_ZONE_DICTIONARY = pa.array(ZONE_NAMES, pa.string())
_COLUMN = {name: k for k, name in enumerate(OUTCOME_FIELDS)}
_PENALTY_CODES = [ZONE_NAMES.index(z) for z in PENALTY_ZONES]

# Where a hole's shots are struck unless a point says otherwise: the tee, the frame's origin.
TEE = (0.0, 0.0)

# The columns, after the kernel's outcomes, of a shot on a hole.
COLUMNS = {
    "landing_zone": pa.dictionary(pa.int32(), pa.string()),
    "finish_zone": pa.dictionary(pa.int32(), pa.string()),
    "pin_distance_m": pa.float64(),
    "final_lon_deg": pa.float64(),
    "final_lat_deg": pa.float64(),
    "penalty_lon_deg": pa.float64(),
    "penalty_lat_deg": pa.float64(),
    # Expected strokes (``mcrun.strokes``: the Tour baseline, penalties by the Rules).
    "penalty_strokes": pa.float64(),
    "expected_strokes_after": pa.float64(),
    "strokes_gained": pa.float64(),
}
# The columns a hole adds where its green is valued by its expected-putts map
# (``[hole] putting = "physics"``): each ball at rest on the green's chance to hole out in one
# putt, and to take three or more (NaN off the green).
PUTTING = {name: pa.float64() for name in PUTTING_COLUMNS}


def columns_of(hole):
    """The columns a shot on ``hole`` adds: COLUMNS, and PUTTING under physics putting."""
    if hole.putting["model"] == "physics":
        return {**COLUMNS, **PUTTING}
    return COLUMNS


# A share's interval: Wilson's score interval at 95 %.
Z95 = 1.959963984540054


# The zone a shot finishes in where its status ended it (the kernel's word, not the nearest
# node of where it stopped, which for a ball that left the grid or crossed into a penalty area
# can be the fairway it crossed from). A ball in a penalty area finishes in the kind of area
# it ended in (red or yellow, ``Hole.penalty_area_at``), ``water`` (red, Rule 17.1) where
# none is found there.
_ZONE_OF_STATUS = {
    status_codes.IN_PENALTY_AREA: ZONE_NAMES.index("water"),
    status_codes.OUT_OF_BOUNDS_STATUS: ZONE_NAMES.index("out_of_bounds"),
    status_codes.OFF_MAP: ZONE_NAMES.index(OFF_MAP),
}


def _zones(hole, x, y, status=None):
    """The zone of each point as a dictionary array of ZONE_NAMES; null where x is NaN. With
    the shots' ``status`` (the finish), the zone their status names where it ended them."""
    known = np.isfinite(x) & np.isfinite(y)
    codes = hole.zone_at(np.where(known, x, 0.0), np.where(known, y, 0.0)).astype(np.int32)
    codes[codes < 0] = len(ZONE_KINDS)  # off the grid
    if status is not None:
        for code, zone in _ZONE_OF_STATUS.items():
            ended = status == code
            codes[ended] = zone
            known = known | ended
        in_area = (status == status_codes.IN_PENALTY_AREA) & np.isfinite(x) & np.isfinite(y)
        if in_area.any():
            area = hole.penalty_area_at(x[in_area], y[in_area]).astype(np.int32)
            codes[in_area] = np.where(area >= 0, area, codes[in_area])
    return pa.DictionaryArray.from_arrays(pa.array(codes, mask=~known), _ZONE_DICTIONARY)


def scores(hole, outcomes, strokes=None, finish=None, start_xy_m=TEE):
    """``strokes.score_shots`` of the kernel's ``outcomes`` (n, N_OUTCOME) on ``hole``, struck
    from ``start_xy_m`` (hole frame, m: one (x, y), or an x and a y array with one start a
    shot; default the tee) (``strokes``: its keyword arguments, the baseline and lies, and
    ``putting``, the green's map where the hole's putting is physics: the run layer prepares
    it, ``putting.on_hole.map_of_hole``, and nothing here computes it; ``finish``: the finish
    zones, when already known)."""
    column = {name: outcomes[:, k] for name, k in _COLUMN.items()}
    fx, fy = column["final_x_m"], column["final_y_m"]
    if finish is None:
        finish = _zones(hole, fx, fy, column["status"])
    strokes = dict(strokes or {})
    if "putting" not in strokes and hole.putting["model"] == "physics":
        raise ValueError(
            f"{hole.source}: its green is valued by its expected-putts map: the run layer "
            "prepares it (putting.on_hole.map_of_hole) and passes it as strokes['putting']"
        )
    if not _at_tee(start_xy_m):
        strokes["start_lie"], strokes["start_distance_m"] = start_of(hole, start_xy_m, True)
    return score_shots(
        {
            "finish_zone": finish,
            "status": column["status"].astype(np.int64),
            "pin_distance_m": np.hypot(fx - hole.pin_xy[0], fy - hole.pin_xy[1]),
            "final_x_m": fx,
            "final_y_m": fy,
            "penalty_x_m": column["penalty_x_m"],
            "penalty_y_m": column["penalty_y_m"],
        },
        hole,
        **strokes,
    )


def shot_columns(hole, outcomes, strokes=None, start_xy_m=TEE):
    """{name: Arrow array} of ``columns_of(hole)`` for the kernel's ``outcomes`` (n, N_OUTCOME)
    of shots struck from ``start_xy_m`` (as ``scores``); ``strokes``: keyword arguments of
    ``strokes.score_shots`` (the baseline, lies)."""
    column = {name: outcomes[:, k] for name, k in _COLUMN.items()}
    fx, fy = column["final_x_m"], column["final_y_m"]
    px, py = hole.pin_xy
    lon, lat = hole.to_lonlat(fx, fy)
    plon, plat = _lonlat_where_finite(hole, column["penalty_x_m"], column["penalty_y_m"])
    finish = _zones(hole, fx, fy, column["status"])
    scored = scores(hole, outcomes, strokes, finish, start_xy_m)
    landing_x, landing_y = landing_xy(outcomes, start_xy_m)
    return {
        "landing_zone": _zones(hole, landing_x, landing_y),
        "finish_zone": finish,
        "pin_distance_m": pa.array(np.hypot(fx - px, fy - py)),
        "final_lon_deg": pa.array(np.asarray(lon, float)),
        "final_lat_deg": pa.array(np.asarray(lat, float)),
        "penalty_lon_deg": pa.array(np.asarray(plon, float)),
        "penalty_lat_deg": pa.array(np.asarray(plat, float)),
        **{
            name: pa.array(scored[name].to_numpy(dtype=float))
            for name in ("penalty_strokes", "expected_strokes_after", "strokes_gained")
        },
        **{name: pa.array(scored[name].to_numpy(float)) for name in PUTTING if name in scored},
    }


def _lonlat_where_finite(hole, x, y):
    """``hole.to_lonlat`` of the points where x and y are numbers (NaN elsewhere: a shot's
    penalty position, which most shots have none of), the conversion asked of those alone."""
    lon, lat = np.full(len(x), np.nan), np.full(len(x), np.nan)
    known = np.isfinite(x) & np.isfinite(y)
    if known.any():
        lon[known], lat[known] = hole.to_lonlat(x[known], y[known])
    return lon, lat


def _at_tee(start_xy_m):
    """Whether shots struck from ``start_xy_m`` are all struck from the tee."""
    x0, y0 = (np.asarray(v, dtype=float) for v in start_xy_m)
    return bool((x0 == 0.0).all() and (y0 == 0.0).all())


def landing_xy(outcomes, start_xy_m=TEE):
    """Where shots struck from ``start_xy_m`` landed, in the hole's frame: their carry and
    lateral carry (measured from the start) moved by it."""
    x0, y0 = start_xy_m
    return outcomes[:, _COLUMN["carry_m"]] + x0, outcomes[:, _COLUMN["carry_lateral_m"]] + y0


def wilson(k, n, z=Z95):
    """Wilson's score interval (lo, hi) of a share k / n; (nan, nan) for n = 0."""
    if n == 0:
        return math.nan, math.nan
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return max(centre - half, 0.0), min(centre + half, 1.0)


class HoleTally:
    """The summary's columns of one point on a hole, streamed chunk by chunk from its shots'
    hole columns as they are made (``shot_columns``), merged in chunk order (a Dask run's
    tasks return theirs): for the landing and the finish, the count of shots in each zone;
    the expected strokes after the shot and the strokes gained (exact means, ``ExactSum``, and
    their standard errors); each outcome's count and the exact sum of its expected strokes;
    under physics putting, the exact sums of the one-putt and three-putt chances of the balls
    on the green. ``row`` gives the summary's columns from them."""

    def __init__(self, putting=False):
        self.putting = bool(putting)
        self.n_shots = 0
        self.start = math.nan  # the expected strokes from its start, by its first scored shot
        self.zones = {"landing": np.zeros(len(ZONE_NAMES), np.int64),
                      "finish": np.zeros(len(ZONE_NAMES), np.int64)}  # fmt: skip
        self.after = stats.RunningMoments()
        self.gained = stats.RunningMoments()
        self.outcomes = np.zeros(len(OUTCOMES), np.int64)
        self.outcome_after = [stats.ExactSum() for _ in OUTCOMES]
        self.on_green = 0
        self.one_putt = stats.ExactSum()
        self.three_putt = stats.ExactSum()

    def update(self, columns, status):
        """Add a chunk: ``columns`` as ``shot_columns`` made them, ``status`` its shots'
        status codes (the kernel's)."""
        after = columns["expected_strokes_after"].to_numpy(zero_copy_only=False)
        gained = columns["strokes_gained"].to_numpy(zero_copy_only=False)
        if math.isnan(self.start):  # (the first shot failed: its values NaN, and the start's)
            scored = np.flatnonzero(np.isfinite(gained) & np.isfinite(after))
            if scored.size:
                k = scored[0]
                self.start = float(gained[k] + 1.0 + after[k])
        self.n_shots += len(after)
        finish = None
        for which, tally in self.zones.items():
            zone = columns[f"{which}_zone"]
            # (a null index was a NaN to numpy, cast with a RuntimeWarning: filled, masked)
            codes = zone.indices.fill_null(0).to_numpy(zero_copy_only=False).astype(np.int64)
            valid = zone.is_valid().to_numpy(zero_copy_only=False)
            tally += np.bincount(codes[valid], minlength=len(ZONE_NAMES))
            if which == "finish":
                finish = np.where(valid, codes, -1)
        # Each shot's outcome (an index of OUTCOMES, -1: failed), as ``score_shots`` names it.
        outcome = finish
        for code, name in (
            (status_codes.IN_PENALTY_AREA, "water"),
            (status_codes.OUT_OF_BOUNDS_STATUS, "out_of_bounds"),
            (status_codes.OFF_MAP, OFF_MAP),
        ):
            ended = status == code
            if code == status_codes.IN_PENALTY_AREA:
                ended &= ~np.isin(outcome, _PENALTY_CODES)  # the area's kind, when named
            outcome[ended] = OUTCOMES.index(name)
        scored = np.isfinite(after) & (outcome >= 0)  # (no zone: failed, as no score)
        outcome[~scored] = -1
        self.after.add(after[scored])
        self.gained.add(gained[scored])
        self.outcomes += np.bincount(outcome[scored], minlength=len(OUTCOMES))
        for k in np.unique(outcome[scored]):
            self.outcome_after[k].add(after[scored & (outcome == k)])
        if self.putting:
            one = columns["p_one_putt"].to_numpy(zero_copy_only=False)
            three = columns["p_three_putt"].to_numpy(zero_copy_only=False)
            on = np.isfinite(one)
            self.on_green += int(on.sum())
            self.one_putt.add(one[on])
            self.three_putt.add(three[on])

    def merge(self, other):
        """Add the tally of the chunks that follow this one's."""
        if math.isnan(self.start):
            self.start = other.start
        self.n_shots += other.n_shots
        for which in self.zones:
            self.zones[which] += other.zones[which]
        self.after.merge(other.after)
        self.gained.merge(other.gained)
        self.outcomes += other.outcomes
        for mine, theirs in zip(self.outcome_after, other.outcome_after, strict=True):
            mine.merge(theirs)
        self.on_green += other.on_green
        self.one_putt.merge(other.one_putt)
        self.three_putt.merge(other.three_putt)

    def row(self):
        """The summary's columns: ``n_landed`` and the zones' shares with their 95 % intervals
        (Wilson's), the expected strokes (``strokes.point_strokes``' columns: the mean after
        the shot and the strokes gained with their standard errors, each outcome's share and
        part), and under physics putting the balls on the green and their putting shares."""
        n = int(self.zones["landing"].sum())
        scored = self.after.n
        row = {"n_landed": n, "expected_strokes_start": self.start}
        (row["expected_strokes_after_mean"],
         row["expected_strokes_after_se"]) = self.after.mean_se()  # fmt: skip
        row["strokes_gained_mean"], row["strokes_gained_se"] = self.gained.mean_se()
        row["n_scored"] = scored
        for k, name in enumerate(OUTCOMES):
            count = int(self.outcomes[k])
            p = count / scored if scored else math.nan
            row[f"p_outcome_{name}"] = p
            row[f"expected_strokes_after_part_{name}"] = (
                p * (self.outcome_after[k].value() / count) if count else 0.0
            )
        if self.putting:
            m = self.on_green
            row["n_on_green"] = m
            row["p_one_putt_green"] = self.one_putt.value() / m if m else math.nan
            row["p_three_putt_green"] = self.three_putt.value() / m if m else math.nan
        for which, tally in self.zones.items():
            for name, k in zip(ZONE_NAMES, tally, strict=True):
                lo, hi = wilson(int(k), n)
                row[f"p_{which}_{name}"] = k / n if n else math.nan
                row[f"p_{which}_{name}_lo95"] = lo
                row[f"p_{which}_{name}_hi95"] = hi
        return row
