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
import pandas as pd
import pyarrow as pa

from mcrun import status as status_codes
from mcrun.engine.schema import OUTCOME_FIELDS
from mcrun.hole.zones import PENALTY_ZONES, ZONE_KINDS
from mcrun.strokes import OUTCOMES, PUTTING_COLUMNS, point_strokes, score_shots, start_of

OFF_MAP = "off_map"
ZONE_NAMES = (*ZONE_KINDS, OFF_MAP)
_ZONE_DICTIONARY = pa.array(ZONE_NAMES, pa.string())
_COLUMN = {name: k for k, name in enumerate(OUTCOME_FIELDS)}

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
    plon, plat = hole.to_lonlat(column["penalty_x_m"], column["penalty_y_m"])
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


def zone_shares(columns, putting=False):
    """The summary's zone columns of one point, whose shots ``columns`` (a
    ``stats.ShotsColumns``) reads: for the landing and the finish, the share of the shots that
    landed in each zone (``p_finish_green``) with its 95 % interval (``_lo95``, ``_hi95``)
    and the count they are out of (``n_landed``); with ``putting`` (a hole whose green is valued
    by its map), the putting shares of its balls on the green (``_putting_summary``)."""
    counts = {"landing": np.zeros(len(ZONE_NAMES), np.int64),
              "finish": np.zeros(len(ZONE_NAMES), np.int64)}  # fmt: skip
    for table in columns.tables(["landing_zone", "finish_zone"]):
        for which in counts:
            zone = table[f"{which}_zone"].combine_chunks()
            # (A file read back may hold a dictionary of only the zones it has.)
            to_zone = np.array([ZONE_NAMES.index(z) for z in zone.dictionary.to_pylist()], int)
            indices = zone.indices.to_numpy(zero_copy_only=False)
            valid = zone.is_valid().to_numpy(zero_copy_only=False)
            counts[which] += np.bincount(
                to_zone[indices[valid].astype(int)], minlength=len(ZONE_NAMES)
            )
    n = int(counts["landing"].sum())
    row = {"n_landed": n, **_strokes_summary(columns)}
    if putting:
        row.update(_putting_summary(columns))
    for which, tally in counts.items():
        for name, k in zip(ZONE_NAMES, tally, strict=True):
            lo, hi = wilson(int(k), n)
            row[f"p_{which}_{name}"] = k / n if n else math.nan
            row[f"p_{which}_{name}_lo95"] = lo
            row[f"p_{which}_{name}_hi95"] = hi
    return row


def _strokes_summary(columns):
    """The summary's expected strokes of one point (``strokes.point_strokes`` of its shots'
    columns): means with their standard errors, and each outcome's share and part."""
    names = ["status", "finish_zone", "expected_strokes_after", "strokes_gained",
             "penalty_strokes"]  # fmt: skip
    parts = [t.to_pandas() for t in columns.tables(names)]
    shots = pd.concat(parts, ignore_index=True) if parts else pd.DataFrame(columns=names)
    # The scores as written, with the outcome and lie cost they imply.
    outcome = _outcome_of(shots)
    scored = pd.DataFrame(
        {
            "outcome": outcome,
            "expected_strokes_after": shots["expected_strokes_after"].to_numpy(float),
            "strokes_gained": shots["strokes_gained"].to_numpy(float),
            "lie_cost_strokes": np.zeros(len(shots)),
            "expected_strokes_start": (
                shots["strokes_gained"] + 1.0 + shots["expected_strokes_after"]
            ).to_numpy(float),
        }
    )
    full = point_strokes(scored)
    row = {
        "expected_strokes_start": full["expected_strokes_start"],
        "expected_strokes_after_mean": full["expected_strokes_after_mean"],
        "expected_strokes_after_se": full["expected_strokes_after_se"],
        "strokes_gained_mean": full["strokes_gained_mean"],
        "strokes_gained_se": full["strokes_gained_se"],
        "n_scored": full["n_scored"],
    }
    for name in OUTCOMES:
        row[f"p_outcome_{name}"] = full[f"p_{name}"]
        row[f"expected_strokes_after_part_{name}"] = full[f"expected_strokes_after_part_{name}"]
    return row


def _putting_summary(columns):
    """Under physics putting: the mean one-putt and three-or-more shares of the point's balls
    at rest on the green (``p_one_putt_green``, ``p_three_putt_green``) and how many there
    were (``n_on_green``)."""
    ones, threes = [], []
    for table in columns.tables(list(PUTTING)):
        one = table["p_one_putt"].to_numpy(zero_copy_only=False)
        three = table["p_three_putt"].to_numpy(zero_copy_only=False)
        on = np.isfinite(one)
        ones.append(one[on])
        threes.append(three[on])
    n = int(sum(len(v) for v in ones))
    # math.fsum: exactly rounded, so the same whatever the row groups (local or Dask).
    return {
        "n_on_green": n,
        "p_one_putt_green": math.fsum(np.concatenate(ones)) / n if n else math.nan,
        "p_three_putt_green": math.fsum(np.concatenate(threes)) / n if n else math.nan,
    }


def _outcome_of(shots):
    """Each shot's outcome as ``strokes.score_shots`` names it: its finish zone, or its
    status where that ended it (water, out of bounds, off the map), or failed."""
    status = shots["status"].to_numpy()
    zone = shots["finish_zone"].astype(object).to_numpy()
    outcome = np.where(pd.isna(zone), "failed", zone).astype(object)
    for code, name in (
        (status_codes.IN_PENALTY_AREA, "water"),
        (status_codes.OUT_OF_BOUNDS_STATUS, "out_of_bounds"),
        (status_codes.OFF_MAP, "off_map"),
    ):
        ended = status == code
        if code == status_codes.IN_PENALTY_AREA:
            ended = ended & ~np.isin(outcome, PENALTY_ZONES)  # the area's kind, when named
        outcome[ended] = name
    scored = np.isfinite(shots["expected_strokes_after"].to_numpy(float))
    outcome[~scored] = "failed"
    return outcome
