"""What a run on a hole adds to its results: the columns of each shot (where it landed and
finished on the hole, as zones and lon/lat, how far from the pin) and, per point, the share of
shots in each zone with its 95 % interval.

The kernel gives the positions in the hole's frame (x from the tee towards the pin, y to the
right): the landing at (carry_m, carry_lateral_m), the finish at (final_x_m, final_y_m) and,
for a ball that ended in a penalty area or out of bounds, where it crossed into it
(penalty_x_m, penalty_y_m). The zone of a point is that of the terrain's nearest node, as the
kernel reads it (``Hole.zone_at``); ``off_map`` beyond the hole's grid.
"""

import math

import numpy as np
import pyarrow as pa

from mcrun.engine.schema import OUTCOME_FIELDS
from mcrun.hole.zones import ZONE_KINDS

OFF_MAP = "off_map"
ZONE_NAMES = (*ZONE_KINDS, OFF_MAP)
_ZONE_DICTIONARY = pa.array(ZONE_NAMES, pa.string())
_COLUMN = {name: k for k, name in enumerate(OUTCOME_FIELDS)}

# The columns, after the kernel's outcomes, of a shot on a hole.
COLUMNS = {
    "landing_zone": pa.dictionary(pa.int32(), pa.string()),
    "finish_zone": pa.dictionary(pa.int32(), pa.string()),
    "pin_distance_m": pa.float64(),
    "final_lon_deg": pa.float64(),
    "final_lat_deg": pa.float64(),
    "penalty_lon_deg": pa.float64(),
    "penalty_lat_deg": pa.float64(),
}
# A share's interval: Wilson's score interval at 95 %.
Z95 = 1.959963984540054


def _zones(hole, x, y):
    """The zone of each point as a dictionary array of ZONE_NAMES; null where x is NaN."""
    known = np.isfinite(x) & np.isfinite(y)
    codes = hole.zone_at(np.where(known, x, 0.0), np.where(known, y, 0.0)).astype(np.int32)
    codes[codes < 0] = len(ZONE_KINDS)  # off the grid
    return pa.DictionaryArray.from_arrays(pa.array(codes, mask=~known), _ZONE_DICTIONARY)


def shot_columns(hole, outcomes):
    """{name: Arrow array} of COLUMNS for the kernel's ``outcomes`` (n, N_OUTCOME)."""
    column = {name: outcomes[:, k] for name, k in _COLUMN.items()}
    fx, fy = column["final_x_m"], column["final_y_m"]
    px, py = hole.pin_xy
    lon, lat = hole.to_lonlat(fx, fy)
    plon, plat = hole.to_lonlat(column["penalty_x_m"], column["penalty_y_m"])
    return {
        "landing_zone": _zones(hole, column["carry_m"], column["carry_lateral_m"]),
        "finish_zone": _zones(hole, fx, fy),
        "pin_distance_m": pa.array(np.hypot(fx - px, fy - py)),
        "final_lon_deg": pa.array(np.asarray(lon, float)),
        "final_lat_deg": pa.array(np.asarray(lat, float)),
        "penalty_lon_deg": pa.array(np.asarray(plon, float)),
        "penalty_lat_deg": pa.array(np.asarray(plat, float)),
    }


def wilson(k, n, z=Z95):
    """Wilson's score interval (lo, hi) of a share k / n; (nan, nan) for n = 0."""
    if n == 0:
        return math.nan, math.nan
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return max(centre - half, 0.0), min(centre + half, 1.0)


def zone_shares(columns):
    """The summary's zone columns of one point, whose shots ``columns`` (a
    ``stats.ShotsColumns``) reads: for the landing and the finish, the share of the shots that
    landed in each zone (``p_finish_green``) with its 95 % interval (``_lo95``, ``_hi95``)
    and the count they are out of (``n_landed``)."""
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
    row = {"n_landed": n}
    for which, tally in counts.items():
        for name, k in zip(ZONE_NAMES, tally, strict=True):
            lo, hi = wilson(int(k), n)
            row[f"p_{which}_{name}"] = k / n if n else math.nan
            row[f"p_{which}_{name}_lo95"] = lo
            row[f"p_{which}_{name}_hi95"] = hi
    return row
